/* SPDX-License-Identifier: MIT */
/* kernel/front.h - stages 1 and 2: the ray, and the cheap rejections that end most
 * vectors that miss. */

/* Stage 1, the ray: A (aligned), d.d and the lanes in play. An Inf or NaN anywhere but
 * in d turns C or D into NaN later, which takes the lane out there. Returns
 * nonzero for a vector that the rare instance must take, else 0. */
CYLRAY_INLINE int KFN(load_ray)(KFN(lanes) *st, const cylray_kat_ *k, const cylray_kflags_ F)
{
    const vf zero = vzero(), one = vset1(1.0f), inf = vset1(INFINITY);
    KFN(load_o)(st, k, F);
    st->dx = KFN(ray_in)(k, F, k->R->dx), st->dy = KFN(ray_in)(k, F, k->R->dy);
    st->dz = KFN(ray_in)(k, F, k->R->dz);
    if (KFN(partial)(k, F)) {
        st->dx = KFN(sane)(k, st->dx, zero), st->dy = KFN(sane)(k, st->dy, one);
        st->dz = KFN(sane)(k, st->dz, zero);
    }
    vf dx = st->dx, dy = st->dy, dz = st->dz;
    vf A = F.aligned ? vfma(dx, dx, vmul(dy, dy)) : zero; /* the side's |d_perp|^2 */
    vf dd = F.aligned ? vfma(dz, dz, A) : KDOT(dx, dy, dz, dx, dy, dz);
    vm act = mand(vge(dd, vset1(KM_DD_LO)), vle(dd, vset1(KM_DD_HI)));
    /* A direction far from unit length makes A, D and their products under- or
     * overflow (|d| = 2^-56 loses a tiny radius, 2^64 overflows d.d). A vector with
     * such an active lane (or a bad one) goes to the rare instance, where every lane
     * takes d times an exact power of two m, so that its largest component lies in
     * [2^-29, 2^20]: the line is the same, and t = m t'. Everything after works in t'
     * but the range test and T itself. A zero, infinite or NaN direction never hits. */
    vf tscale = one;
    if (F.scaled) {
        vf M = vmax(vabs(dx), vmax(vabs(dy), vabs(dz)));
        tscale = vsel(vlt(M, vset1(0x1p-20f)), vset1(0x1p40f), tscale);
        tscale = vsel(vlt(M, vset1(0x1p-60f)), vset1(0x1p80f), tscale);
        tscale = vsel(vlt(M, vset1(0x1p-100f)), vset1(0x1p120f), tscale);
        tscale = vsel(vgt(M, vset1(0x1p20f)), vset1(0x1p-40f), tscale);
        tscale = vsel(vgt(M, vset1(0x1p60f)), vset1(0x1p-80f), tscale);
        tscale = vsel(vgt(M, vset1(0x1p100f)), vset1(0x1p-120f), tscale);
        dx = vmul(dx, tscale), dy = vmul(dy, tscale), dz = vmul(dz, tscale);
        st->dx = dx, st->dy = dy, st->dz = dz;
        A = F.aligned ? vfma(dx, dx, vmul(dy, dy)) : zero;
        dd = F.aligned ? vfma(dz, dz, A) : KDOT(dx, dy, dz, dx, dy, dz);
        act = mand(mand(vgt(dd, zero), vlt(dd, inf)), vlt(M, inf));
    }
    st->A = A, st->dd = dd, st->act = act, st->tscale = tscale;
    if (!F.scaled && (mbits(act) & k->bits) != k->bits)
        return 1; /* KFN(vector) calls the rare instance */
    return 0;
}

/* Stage 2, the cheap rejections: the sphere around a finite cylinder and the tube
 * around the axis (KFN(shape_reject)), from w = o - c rounded (a sphere: itself, with a
 * margin). Returns whether any lane is left. */
CYLRAY_INLINE int KFN(reject)(KFN(lanes) *st, const cylray_kat_ *k, const cylray_kflags_ F)
{
    const vf zero = vzero(), inf = vset1(INFINITY);
    const vf dx = st->dx, dy = st->dy, dz = st->dz, dd = st->dd;
    KFN(shape_axis)(st, k, F);
    /* A leaf derives what it does not store from what it does (64 bytes a lane). */
    st->rad = KFN(leaf_in)(k, F, CYLRAY_LF_R); /* zero elsewhere */
    st->rr = KFN(cyl_in)(k, F, offsetof(cylray_prepared, rr), vmul(st->rad, st->rad));
    st->rr_vv = KFN(both_in)(k, F, offsetof(cylray_prepared, rr_vv), CYLRAY_LF_RRVV);
    st->fin = F.leaf ? vlt(KFN(leaf_in)(k, F, CYLRAY_LF_HV), inf) : vle(zero, zero);
    st->infl = F.leaf ? vge(KFN(leaf_in)(k, F, CYLRAY_LF_HV), inf) : vlt(vset1(1.0f), zero);

    /* w = o - c, rounded here; its rounding error wl is recovered by the shift stage
     * (two-sum), once the cheap whole-vector rejections are behind. */
    vf whx = vsub(st->ox, st->cx), why = vsub(st->oy, st->cy), whz = vsub(st->oz, st->cz);
    st->whx = whx, st->why = why, st->whz = whz;
    vf ww = KDOT(whx, why, whz, whx, why, whz), wd = KDOT(whx, why, whz, dx, dy, dz);
    vm act = st->act;

    /* Shift to the closest approach to the center. s need not be accurate: any s is
     * exact as long as w' is formed from the same s, and t = s + t'. But the answers
     * (and a spawned ray's fate near a tangency) follow s bit for bit, so s comes from
     * the divider rather than the vendor's estimate (KRCP). */
    const vf rdd = KRCP(F, dd);
    vf s = vmul(vneg(wd), rdd);
    if (F.finite) {
        /* ww + s wd = ww - wd^2 / dd is the squared distance of the closest approach
         * to the center; a finite cylinder lies in a sphere, and a ray that passes
         * outside it misses. The slack (KM_SPHERE) covers the cancellation of a far
         * origin. */
        vf wd2 = vmul(vmul(wd, wd), rdd); /* wd^2 / dd; wd^2 is formed beside rdd */
        act = mand(
            act, vle(vfnma(ww, vset1(KM_SPHERE), vsub(ww, wd2)),
                     KFN(both_in)(k, F, offsetof(cylray_prepared, bound2), CYLRAY_LF_BOUND2)));
        /* A shift that brings the origin less than a factor sqrt(2) closer gains less
         * than it costs: a small t would lose its low bits in s + t'. (ww > 2 pp.) */
        s = F.leaf ? vsel(st->fin, vkeep(vgt(vadd(wd2, wd2), ww), s), s)
                   : vkeep(vgt(vadd(wd2, wd2), ww), s);
    }
    st->rdd = rdd, st->s = s;
    return KFN(shape_reject)(st, k, F, act, ww);
}
