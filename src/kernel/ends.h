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
        const uint32_t *meta = (const uint32_t *)(const void *)(k->L + CYLRAY_LF_COUNT * k->lm);
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

/* v x (p + t d) = f - t e: the point at t (relative to p) crossed with the axis. */
CYLRAY_INLINE void KFN(disc_point)(const KFN(lanes) *st, vf t, vf *fx, vf *fy, vf *fz)
{
    *fx = vfnma_x(t, st->ex, st->fx), *fy = vfnma_x(t, st->ey, st->fy);
    *fz = vfnma_x(t, st->ez, st->fz);
}

/* Whether the point at t (relative to p) of an end's plane lies on the end's disc,
 * whose radius is rc: |v x x|^2 = v.v |x_perp|^2 against v.v rc^2, with f - t e =
 * v x (p + t d). At the rim of a cone whose side meets the plane at a shallow angle
 * (a flat frustum), the side's root and the plane's t lie a fraction of an ulp apart
 * while the point lies many ulps of rc inside or outside the rim: the disc decides
 * what the comparison of the two t cannot. A rounding of t moves the point along d,
 * which moves it off the axis by no more than |t| eps |d|. */
CYLRAY_INLINE vm KFN(on_disc)(const KFN(lanes) *st, vf t, vf rc, vf vv)
{
    vf fx, fy, fz;
    KFN(disc_point)(st, t, &fx, &fy, &fz);
    return vle(vsumsq_x(fx, fy, fz, vmul(vmul(vv, rc), rc)), vzero());
}

/* Where the disc's verdict (KFN(on_disc)) is sure: the point's distance from the axis
 * |f - t e| / |v| and rc differ by more than 2^-18 of the terms that round (|v| |p|,
 * to which f is rounded, |t e| and the radius), some 64 ulps of them. Beside a tiny
 * disc at the end of a wide cone the terms are the cone's size and no verdict is. */
CYLRAY_INLINE vm KFN(disc_sure)(const KFN(lanes) *st, vf t, vf rc, vf vv)
{
    vf fx, fy, fz;
    KFN(disc_point)(st, t, &fx, &fy, &fz);
    const vf dist = vsqrt(KDOT(fx, fy, fz, fx, fy, fz)), rr = vmul(vsqrt(vv), rc);
    const vf v1 = vadd(vadd(vabs(st->vx), vabs(st->vy)), vabs(st->vz)),
             p1 = vadd(vadd(vabs(st->px), vabs(st->py)), vabs(st->pz)),
             e1 = vadd(vadd(vabs(st->ex), vabs(st->ey)), vabs(st->ez));
    const vf terms = vfma(v1, p1, vfma(vabs(t), e1, rr));
    return vgt(vabs(vsub(dist, rr)), vmul(vset1(0x1p-18f), terms));
}

/* A cone whose side is flatter than 45 degrees (slope^2 = kap^2 v.v > 1) at its ends.
 * A ray that passes an end's rim enters by the disc and leaves by the side (or the
 * reverse) at two t a fraction of an ulp apart, while the point lies many ulps of the
 * radius inside or outside the rim: where the two lie within a few ulps, the disc
 * decides whether the solid has that stretch of the ray (KFN(on_disc)). And a flat side
 * runs close along the plane far from the rim too: there the plane's t and the side's
 * entry (or exit) are a hair apart, and their order is rounding's. Exactly, the ray
 * enters by the plane if and only if the plane's point lies inside the cone there, on
 * the disc: where the two lie within KM_RIM the disc names the entry's part (and the
 * exit's), and the other bound is moved to it (the side's to the later entry, or out
 * of the way) so that the part and an open end's test follow. The slab's t agrees with
 * the side's to rounding because both take one axial coordinate (KFN(cone_z0)). An end
 * of radius 0 is the apex, which the roots decide: it has no disc, and a bound there a
 * hair from the side's is the side's. */
CYLRAY_INLINE void KFN(cone_rims)(KFN(lanes) *st, const cylray_kat_ *k, const cylray_kflags_ F,
                                  vf slab_in, vf slab_out)
{
    const vf zero = vzero(), inf = vset1(INFINITY);
    const vm live = mor(st->side, st->inpar);
    const vf kap = KFN(both_in)(k, F, offsetof(cylray_prepared, kap), CYLRAY_LF_RRVV);
    const vf vv = KDOT(st->vx, st->vy, st->vz, st->vx, st->vy, st->vz);
    const vm flat = mand(live, vgt(vmul(vmul(kap, kap), vv), vset1(1.0f)));
    if (!many(flat))
        return;
    /* the ends' radii: r0 at z = -H|v|, r1 at +H|v| (a leaf's as its side forms them) */
    vf ra, za;
    KFN(cone_anchor)(k, F, kap, &ra, &za);
    const vf hv = KFN(leaf_in)(k, F, CYLRAY_LF_HV);
    const vf r_lo =
        KFN(cyl_in)(k, F, offsetof(cylray_prepared, r0), vfma(kap, vsub(vneg(hv), za), ra));
    const vf r_hi =
        KFN(cyl_in)(k, F, offsetof(cylray_prepared, r1), vfma(kap, vsub(hv, za), ra));
    const vm up = vgt(st->dv, zero); /* in by the low end, out by the high one */
    const vf rc_in = vsel(up, r_lo, r_hi), rc_out = vsel(up, r_hi, r_lo);
    const vm has_in = mand(flat, vgt(rc_in, zero)), has_out = mand(flat, vgt(rc_out, zero));
    /* (strict: an infinite bound, as a ray inside the tube has, is no rim) */
#define KNEAR_(a, b, margin) vlt(vabs(vsub(a, b)), vmul(vset1(margin), vmax(vabs(a), vabs(b))))
    const vm rim_in = mand(has_in, KNEAR_(slab_in, st->side_hi, KM_RIM));
    const vm rim_out = mand(has_out, KNEAR_(slab_out, st->side_lo, KM_RIM));
    const vm rim = mor(rim_in, rim_out);
    if (many(rim)) {
        /* the other bounds of [max(side_lo, slab_in), min(side_hi, slab_out)] as before */
        vm ok = mand(live, mand(vle(st->side_lo, st->side_hi), vle(slab_in, slab_out)));
        ok = mand(ok, mor(mand(rim_in, KFN(on_disc)(st, slab_in, rc_in, vv)),
                          mandn(vle(slab_in, st->side_hi), rim_in)));
        ok = mand(ok, mor(mand(rim_out, KFN(on_disc)(st, slab_out, rc_out, vv)),
                          mandn(vle(st->side_lo, slab_out), rim_out)));
        st->ok_in = mor(mand(rim, ok), mandn(st->ok_in, rim));
    }
    /* The parts, on lanes with roots (a line inside the double cone throughout has no
     * side bound to weigh): the entry is the plane's exactly when the plane's point
     * lies on the disc. Where the two t lie within KM_RIM the disc names the part.
     * Further apart their order is surer than a disc test that rounding can turn, but
     * a side root that cancellation has moved by more than KM_RIM can fall on the
     * wrong side of the plane's t: within KM_ROOT, where the disc's verdict is sure
     * (KFN(disc_sure)) and the order says otherwise, the disc names it. */
    const vm sd = mandn(flat, st->inpar);
    vm in = mand(sd, KNEAR_(slab_in, st->side_lo, KM_RIM));
    vm out = mand(sd, KNEAR_(slab_out, st->side_hi, KM_RIM));
    /* further apart (within KM_ROOT), the lanes that may hit */
    const vm may = mand(sd, st->ok_in);
    const vm wide_in =
        mandn(mand(mand(may, has_in), KNEAR_(slab_in, st->side_lo, KM_ROOT)), in);
    const vm wide_out =
        mandn(mand(mand(may, has_out), KNEAR_(slab_out, st->side_hi, KM_ROOT)), out);
#undef KNEAR_
    if (!many(mor(mor(in, out), mor(wide_in, wide_out))))
        return;
    const vm on_in = mand(has_in, KFN(on_disc)(st, slab_in, rc_in, vv));
    const vm on_out = mand(has_out, KFN(on_disc)(st, slab_out, rc_out, vv));
    /* there, where the disc and the order of the two t disagree, a sure disc decides */
    const vm odd_in = mand(wide_in, mxor(on_in, vle(st->side_lo, slab_in)));
    const vm odd_out = mand(wide_out, mxor(on_out, vle(slab_out, st->side_hi)));
    if (many(mor(odd_in, odd_out))) {
        in = mor(in, mand(odd_in, KFN(disc_sure)(st, slab_in, rc_in, vv)));
        out = mor(out, mand(odd_out, KFN(disc_sure)(st, slab_out, rc_out, vv)));
    }
    if (many(in)) {
        const vm disc = mand(in, on_in);
        const vm side = mandn(in, disc);
        st->side_lo =
            vsel(disc, vneg(inf), vsel(side, vmax(st->side_lo, slab_in), st->side_lo));
        st->t_in = vsel(disc, slab_in, vsel(side, st->side_lo, st->t_in));
    }
    if (many(out)) {
        const vm disc = mand(out, on_out);
        const vm side = mandn(out, disc);
        st->side_hi = vsel(disc, inf, vsel(side, vmin(st->side_hi, slab_out), st->side_hi));
        st->t_out = vsel(disc, slab_out, vsel(side, st->side_hi, st->t_out));
    }
}

/* A cone's end of radius 0 is its apex: no disc to meet and no hole to pass. The side's
 * own nappe lies wholly beyond the apex's plane, so exactly the side's entry there is
 * never before the plane's t, nor its exit after it; where rounding (a line through the
 * apex's neighbourhood, its roots a double root there) puts it a hair beyond, the
 * plane's bound is the side's: the entry is a side hit at the apex, never an open end
 * that lets the ray through to leave by the far disc. */
CYLRAY_INLINE void KFN(cone_tips)(KFN(lanes) *st, const cylray_kat_ *k, const cylray_kflags_ F,
                                  vf slab_in, vf slab_out)
{
    if (!F.tiny) /* (a tip is a tiny end: cylray_cone_tiny_) */
        return;
    const vf zero = vzero();
    const vf kap = KFN(both_in)(k, F, offsetof(cylray_prepared, kap), CYLRAY_LF_RRVV);
    vf ra, za;
    KFN(cone_anchor)(k, F, kap, &ra, &za);
    const vm tip = mand(mor(st->side, st->inpar), mand(veq(ra, zero), vlt(zero, vabs(kap))));
    if (!many(tip))
        return;
    const vm up = vgt(st->dv, zero), lo = vgt(kap, zero); /* the tip is the low end */
    const vm tip_in = mandn(tip, mxor(up, lo)), tip_out = mand(tip, mxor(up, lo));
    st->side_lo = vsel(tip_in, vmax(st->side_lo, slab_in), st->side_lo);
    st->side_hi = vsel(tip_out, vmin(st->side_hi, slab_out), st->side_hi);
}

/* The axial coordinates of the ends' planes, -H|v| and +H|v| from the center, or from
 * a slender shape's anchor on its lanes that took one (kernel/anchor.h). */
CYLRAY_INLINE void KFN(planes)(const KFN(lanes) *st, const cylray_kat_ *k,
                               const cylray_kflags_ F, vf *zlo, vf *zhi)
{
    const vf hv = KFN(both_in)(k, F, offsetof(cylray_prepared, h_v), CYLRAY_LF_HV);
    *zlo = vneg(hv), *zhi = hv;
    if (F.slender) /* (-+H|v| on the lanes that kept the center) */
        *zlo = KFN(axial)(st, F, *zlo), *zhi = KFN(axial)(st, F, *zhi);
}

/* Stage 6, the ends: entry and exit relative to p, and whether each is on the
 * surface (the slab and the caps of a finite cylinder). */
CYLRAY_INLINE void KFN(ends)(KFN(lanes) *st, const cylray_kat_ *k, const cylray_kflags_ F)
{
    const vf zero = vzero(), inf = vset1(INFINITY), tn = st->tn, tf = st->tf;
    st->side_lo = tn, st->side_hi = tf;
    /* The axial coordinate z0 + t dv, over |v|. An aligned axis is measured along the
     * third coordinate itself, whatever its sign: the slab is symmetric, and the sign
     * only names the caps. */
    vf z0 = zero, dv = zero;
    if (F.finite && !F.sphere) {
        z0 = F.aligned ? st->pz
             : F.cone  ? KFN(cone_z0)(st)
                       : KDOT(st->px, st->py, st->pz, st->vx, st->vy, st->vz);
        dv = F.aligned ? st->dz
             : F.cone  ? KFN(cone_dv)(st)
                       : KDOT(st->dx, st->dy, st->dz, st->vx, st->vy, st->vz);
    }
    st->z0 = z0, st->dv = dv;
    if (F.capped) {
        /* The solid is the infinite one cut by the slab |z| <= H: inside on [max of the
         * entries, min of the exits]. The rim is then shared, not tested twice. A ray
         * parallel to the axis inside the tube is inside the side everywhere. */
        vf lo = tn, hi = tf;
        if (F.cone) {
            /* The double cone's inside on the ray: [tn, tf] where A > 0, on one nappe
             * (the cone's where its radius there is not negative); where A < 0 the two
             * half-lines beyond the roots, one on each side of the apex's plane, of
             * which the cone's runs the way the radius grows (the sign of a, exact,
             * rather than that of the radius at a root, which is 0 at a root near the
             * apex). The slab keeps the other nappe out; these choices keep rounding
             * near a tip from passing a sliver of it. */
            const vm neg = vlt(st->A, zero);
            const vm far = vgt(st->ca, zero);
            lo = vsel(neg, vsel(far, tf, vneg(inf)), tn);
            hi = vsel(neg, vsel(far, inf, tn), tf);
            const vf mid = vmul(vset1(0.5f), vadd(tn, tf));
            st->side = mandn(st->side, mandn(vlt(vfma_x(st->ca, mid, st->cr), zero), neg));
        }
        st->side_lo = vsel(st->inpar, vneg(inf), lo), st->side_hi = vsel(st->inpar, inf, hi);
        vf zlo, zhi;
        KFN(planes)(st, k, F, &zlo, &zhi);
        if (F.cone) /* a cone's lanes measured from its narrower end */
            KFN(cone_planes)(st, k, F, &zlo, &zhi);
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
        if (F.cone)
            KFN(cone_tips)(st, k, F, slab_in, slab_out);
        st->t_in = vmax(st->side_lo, slab_in);
        st->t_out = vmin(st->side_hi, slab_out);
        st->ok_in = mand(mor(st->side, st->inpar), vle(st->t_in, st->t_out));
        if (F.cone)
            KFN(cone_rims)(st, k, F, slab_in, slab_out);
        st->ok_out = st->ok_in;
        if (F.one_end)
            KFN(open_ends)(st, k, F, slab_in, slab_out);
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
