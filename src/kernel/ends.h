/* SPDX-License-Identifier: MIT */
/* kernel/ends.h - stages 6 and 7: the ends of a finite cylinder, and the decision. */

/* Where a disc is not part of the surface, the solid is still what decides entry and
 * exit (so the other rim stays watertight), but a bound made by that disc is no hit:
 * the ray passes through the open end. Going up the axis (dv > 0) it enters by the low
 * disc and leaves by the high one. */
CYLRAY_INLINE void KFN(open_ends)(KFN(lanes) *st, const cylray_kat_ *k, const cylray_kflags_ F,
                                  vf slab_in, vf slab_out)
{
    vm lo_on, hi_on;
    if (F.leaf) {
        const uint32_t *meta = KFN(leaf_meta)(k);
        lo_on = mfrom_bits(meta[CYLRAY_LM_LO] >> k->i);
        hi_on = mfrom_bits(meta[CYLRAY_LM_HI] >> k->i);
    } else {
        lo_on = mfrom_bits(k->P->caps & CYLRAY_CAPPED_LO ? VFULL : 0u);
        hi_on = mfrom_bits(k->P->caps & CYLRAY_CAPPED_HI ? VFULL : 0u);
    }
    vm up = vgt(st->dv, vzero());
    vm in_disc = vgt(slab_in, st->side_lo), out_disc = vlt(slab_out, st->side_hi);
    vm in_open = mandn(in_disc, mor(mand(up, lo_on), mandn(hi_on, up)));
    vm out_open = mandn(out_disc, mor(mand(up, hi_on), mandn(lo_on, up)));
    st->ok_in = mandn(st->ok_in, in_open);
    st->ok_out = mandn(st->ok_out, out_open);
}

/* The axial coordinates of the ends' planes, -H|v| and +H|v| from the center, or from
 * a slender shape's anchor on its lanes that took one (kernel/anchor.h). */
CYLRAY_INLINE void KFN(planes)(const KFN(lanes) *st, const cylray_kat_ *k,
                               const cylray_kflags_ F, vf *zlo, vf *zhi)
{
    const vf hv = KFN(both_in)(k, F, offsetof(cylray_prepared, h_v), CYLRAY_LF_HV);
    *zlo = vneg(hv), *zhi = hv;
    KFN(shape_end_planes)(k, F, zlo, zhi);
    if (F.slender) /* (-+H|v| on the lanes that kept the center) */
        *zlo = KFN(axial)(st, F, *zlo), *zhi = KFN(axial)(st, F, *zhi);
}

/* Stage 6, the ends: entry and exit relative to p, and whether each is on the
 * surface (the slab and the caps of a finite cylinder). */
CYLRAY_INLINE void KFN(ends)(KFN(lanes) *st, const cylray_kat_ *k, const cylray_kflags_ F)
{
    const vf inf = vset1(INFINITY), tn = st->tn, tf = st->tf;
    st->side_lo = tn, st->side_hi = tf;
    vf z0, dv; /* the axial coordinate z0 + t dv, over |v| */
    KFN(shape_axial)(st, F, &z0, &dv);
    st->z0 = z0, st->dv = dv;
    if (F.capped) {
        /* The solid is the infinite one cut by the slab |z| <= H: inside on [max of the
         * entries, min of the exits]. The rim is then shared, not tested twice. A ray
         * parallel to the axis inside the tube is inside the side everywhere. */
        vf lo = tn, hi = tf;
        KFN(shape_interval)(st, F, &lo, &hi);
        st->side_lo = vsel(st->inpar, vneg(inf), lo), st->side_hi = vsel(st->inpar, inf, hi);
        vf zlo, zhi;
        KFN(planes)(st, k, F, &zlo, &zhi);
        KFN(shape_planes)(st, k, F, &zlo, &zhi);
        /* Two divisions rather than one reciprocal: a cap hit is then as exact as
         * the plane's offset, and dv = 0 gives the infinities the slab wants. */
        vf na = vsub(zlo, z0), nb = vsub(zhi, z0);
        vf ta, tb;
        if (F.fast) {
            vf rdv = vdiv(vset1(1.0f), dv);
            ta = vmul(na, rdv), tb = vmul(nb, rdv);
        } else {
            ta = vdiv(na, dv), tb = vdiv(nb, dv);
        }
        /* A ray in an end's plane (dv = 0, z0 = -+H exactly) gives 0/0 for that end: it
         * lies in the closed solid's boundary, which the slab then leaves unbounded, as
         * for any dv = 0 within it (the other end's infinity, negated), so that the ray
         * meets the rim as the solid's entry and no ray slips through a rim. */
        ta = vsel(veq(ta, ta), ta, vneg(tb));
        tb = vsel(veq(tb, tb), tb, vneg(ta));
        vf slab_in = vmin(ta, tb), slab_out = vmax(ta, tb);
        KFN(shape_slab)(st, k, F, slab_in, slab_out);
        st->t_in = vmax(st->side_lo, slab_in);
        st->t_out = vmin(st->side_hi, slab_out);
        st->ok_in = mand(mor(st->side, st->inpar), vle(st->t_in, st->t_out));
        KFN(shape_rims)(st, k, F, slab_in, slab_out);
        st->ok_out = st->ok_in;
        if (F.one_end)
            KFN(open_ends)(st, k, F, slab_in, slab_out);
        KFN(shape_ends)(st, k, F, na, nb, ta, tb, slab_in, slab_out);
    } else {
        st->t_in = tn, st->t_out = tf;
        st->ok_in = st->ok_out = st->side;
        if (F.kind == CYLRAY_KIND_OPEN) {
            const vf hv = vset1(k->P->h_v);
            if (F.slender) {
                vf zlo, zhi;
                KFN(planes)(st, k, F, &zlo, &zhi);
                const vf zn = vfma(tn, dv, z0), zf = vfma(tf, dv, z0);
                st->ok_in = mand(st->ok_in, mand(vle(zlo, zn), vle(zn, zhi)));
                st->ok_out = mand(st->ok_out, mand(vle(zlo, zf), vle(zf, zhi)));
            } else {
                st->ok_in = mand(st->ok_in, vle(vabs(vfma(tn, dv, z0)), hv));
                st->ok_out = mand(st->ok_out, vle(vabs(vfma(tf, dv, z0)), hv));
            }
        }
    }
}

/* Stage 7, the decision: the entry if it is not before tmin, else the exit (a hit from
 * inside); then one range test for whichever it is. Rounding s + t is monotonic, so the
 * entry test decides correctly which of the two can be the first in [tmin, tmax]. The
 * bounds are clamped to finite values, so that no infinite t ever hits. Returns the
 * hit lanes. */
CYLRAY_INLINE uint32_t KFN(decide)(KFN(lanes) *st, const cylray_kat_ *k, const cylray_kflags_ F)
{
    const vf one = vset1(1.0f);
    vf tmin = vmax(vset1(-FLT_MAX), KFN(ray_in)(k, F, k->R->tmin)); /* a NaN bound stays */
    vf tmax = vmin(vset1(FLT_MAX), KFN(ray_in)(k, F, k->R->tmax));
    /* (min, max and comparisons take subnormals without an assist) */
    vf T_in = vadd(st->s, st->t_in), t_to_test = one;
    /* With a scaled direction the range test is made where no scaling rounds: a
     * shrunk d (m < 1) moves the bounds to t' (exact, or overflowing as it should), a
     * grown one moves T to t (the same): t_to_test takes t' there, t_to_user takes
     * that to t. */
    st->t_to_user = one;
    if (F.scaled) {
        vm shrunk = vlt(st->tscale, one);
        vf rs = vdiv(one, st->tscale);
        tmin = vsel(shrunk, vmul(tmin, rs), tmin);
        tmax = vsel(shrunk, vmul(tmax, rs), tmax);
        t_to_test = vsel(shrunk, one, st->tscale);
        st->t_to_user = vsel(shrunk, st->tscale, one);
        T_in = vmul(T_in, t_to_test);
    }
    vm front = mand(st->ok_in, vge(T_in, tmin));
    vm cand = F.cull ? front : mor(front, st->ok_out);
    st->tr = vsel(front, st->t_in, st->t_out); /* relative to the shifted origin */
    /* s + tr rounds as the selected one of s + t_in and s + t_out would: one sum
     * rather than a second one and a select. */
    st->T = vadd(st->s, st->tr);
    if (F.scaled)
        st->T = vmul(st->T, t_to_test);
    vm hit = mand(cand, mand(vge(st->T, tmin), vle(st->T, tmax)));
    /* A shrunk direction's bounds were moved to t', where FLT_MAX became infinite: the
     * exit of a leaf's infinite lane, parallel inside it, is no hit there either. */
    if (F.scaled)
        hit = mand(hit, vlt(vabs(vmul(st->T, st->t_to_user)), vset1(INFINITY)));
    if (k->bits != VFULL) /* a whole vector is the common case, and needs no mask */
        hit = mand(hit, mfrom_bits(k->bits));
    st->back = mandn(hit, front);
    st->front = mand(hit, front);
    st->hit = hit;
    return mbits(hit);
}
