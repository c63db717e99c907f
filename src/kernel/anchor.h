/* SPDX-License-Identifier: MIT */
/* kernel/anchor.h - stage 3b: where a slender shape's lanes take their frame. */

/* The lanes of a slender shape (cylray_slender_): a prepared one's all, a leaf's as its
 * meta marks. */
CYLRAY_INLINE vm KFN(slender)(const cylray_kat_ *k, const cylray_kflags_ F)
{
    if (!F.finite || F.sphere)
        return mfrom_bits(0u);
    if (F.leaf) {
        const uint32_t *meta = (const uint32_t *)(const void *)(k->L + CYLRAY_LF_COUNT * k->lm);
        return mfrom_bits(cylray_leaf_slender_(meta) >> k->i);
    }
    return mfrom_bits(cylray_slender_(k->P) ? VFULL : 0u);
}

/* The center of a shape 16 radii long or more can lie thousands of radii from where a
 * ray meets it: p, f = v x p and C rounded at |p| there lose the local radius (a tip
 * cone 1e4 radii long kept 10 bits of t). Its lanes take their frame at a point
 * a = c + m v of the axis segment instead, the origin moved to its closest approach to
 * a. Two candidates: the segment's point nearest the line (the clamped common
 * perpendicular: |p| is then the line's distance from the segment, the least any point
 * of it gives), and the origin's own level (clamped), which serves an origin next to
 * the surface whose hit lies far along a shallow ray. The origin's level is taken where
 * the origin lies at least twice as near it as the other. The center stays where the
 * line passes it within twice the larger of that distance and R (a cone's narrower
 * end's): there its frame, with o - c exact, is as local, and a far origin keeps it.
 * A leaf's lane chooses from the same bits as a packet, and answers as it does.
 *
 * Any m is exact as long as everything measures from that same a: h = w - m v is
 * rounded once (the product exact), an error of eps |h| that moves the origin within
 * its own perturbation (|h| is at most its distance from the point); p = s d + h + wl as
 * the center's shift forms it. Axial coordinates are then measured from a: the slab's
 * planes lie at -+H|v| - m v.v, with v.v as an exact two-term sum (vdot3_x), so that a
 * plane near a is placed to the ulps of its own distance from it (KFN(ends), the cone's
 * narrower end in KFN(cone_side)). */
CYLRAY_INLINE void KFN(anchor)(KFN(lanes) *st, const cylray_kat_ *k, const cylray_kflags_ F)
{
    st->anc = mfrom_bits(0u);
    st->alo = st->ahi = vzero();
    const vm sl = mand(KFN(slender)(k, F), st->act);
    if (!many(sl))
        return;
    const vf zero = vzero(), four = vset1(4.0f);
    const vf vx = st->vx, vy = st->vy, vz = st->vz, dx = st->dx, dy = st->dy, dz = st->dz;
    const vf whx = st->whx, why = st->why, whz = st->whz;
    const vf vv = KDOT(vx, vy, vz, vx, vy, vz);
    const vf wv = KDOT(whx, why, whz, vx, vy, vz), dv = KDOT(dx, dy, dz, vx, vy, vz);
    const vf wd = KDOT(whx, why, whz, dx, dy, dz);
    const vf ivv = KRCP(F, vv); /* (a leaf's and a packet's the same bits) */
    const vf hv = KFN(both_in)(k, F, offsetof(cylray_prepared, h_v), CYLRAY_LF_HV);
    const vf lim = vmul(hv, ivv);
    /* the common perpendicular, (d.d w.v - d.v w.d) / |d x v|^2 (st->A is e.e here), and
     * the origin's level; a NaN (d along v) takes the center */
    vf ml = vdiv(vfms(st->dd, wv, vmul(dv, wd)), st->A);
    vf mo = vmul(wv, ivv);
    ml = vsel(veq(ml, ml), ml, zero);
    ml = vmax(vneg(lim), vmin(lim, ml)), mo = vmax(vneg(lim), vmin(lim, mo));
    const vf lx = vfma_x(vneg(ml), vx, whx), ly = vfma_x(vneg(ml), vy, why),
             lz = vfma_x(vneg(ml), vz, whz);
    const vf ox = vfma_x(vneg(mo), vx, whx), oy = vfma_x(vneg(mo), vy, why),
             oz = vfma_x(vneg(mo), vz, whz);
    const vm at_o = vle(vmul(four, KDOT(ox, oy, oz, ox, oy, oz)), KDOT(lx, ly, lz, lx, ly, lz));
    const vf m = vsel(at_o, mo, ml);
    const vf hx = vsel(at_o, ox, lx), hy = vsel(at_o, oy, ly), hz = vsel(at_o, oz, lz);
    /* the shift to the closest approach to a, skipped as the center's is */
    const vf hd = KDOT(hx, hy, hz, dx, dy, dz), hh = KDOT(hx, hy, hz, hx, hy, hz);
    const vf hd2 = vmul(vmul(hd, hd), st->rdd);
    const vf s = vkeep(vgt(vadd(hd2, hd2), hh), vmul(vneg(hd), st->rdd));
    const vf px = vfma_x2(s, dx, hx, st->wlx), py = vfma_x2(s, dy, hy, st->wly),
             pz = vfma_x2(s, dz, hz, st->wlz);
    const vf pp = KDOT(px, py, pz, px, py, pz);
    const vf pc = KDOT(st->px, st->py, st->pz, st->px, st->py, st->pz);
    /* R: a cone's narrower end's, which a leaf holds as a packet does */
    vf rr = st->rr;
    if (F.cone) {
        const vf kap = KFN(both_in)(k, F, offsetof(cylray_prepared, kap), CYLRAY_LF_RRVV);
        vf ra, za;
        KFN(cone_anchor)(k, F, kap, &ra, &za);
        rr = vmul(ra, ra);
    }
    const vm anc = mandn(sl, vle(pc, vmul(four, vmax(pp, rr))));
    st->anc = anc;
    if (!many(anc))
        return;
    st->s = vsel(anc, s, st->s);
    st->px = vsel(anc, px, st->px), st->py = vsel(anc, py, st->py);
    st->pz = vsel(anc, pz, st->pz);
    /* the planes -+H|v| - m v.v; an aligned axis measures along its third coordinate,
     * whose m v is m vz, exact */
    if (F.aligned) {
        const vf mz = vmul(m, vz);
        st->alo = vsub(vneg(hv), mz), st->ahi = vsub(hv, mz);
    } else {
        const vf vvl = vdot3_x(vx, vy, vz, vx, vy, vz, vneg(vv)), nm = vneg(m);
        st->alo = vdot3_x(nm, nm, zero, vv, vvl, zero, vneg(hv));
        st->ahi = vdot3_x(nm, nm, zero, vv, vvl, zero, hv);
    }
}
