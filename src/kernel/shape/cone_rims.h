/* SPDX-License-Identifier: MIT */
/* kernel/shape/cone_rims.h - a cone's ends (called from stage 6, kernel/ends.h): where a flat
 * side meets an end's disc at its rim, and an end of radius 0, its apex. */

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
    const vf kap = KFN(both_in)(k, F, offsetof(cylray_prepared, kap), CYLRAY_LF_KAP);
    const vf vv = KDOT(st->vx, st->vy, st->vz, st->vx, st->vy, st->vz);
    const vm flat = mand(live, vgt(vmul(vmul(kap, kap), vv), vset1(1.0f)));
    if (!many(flat))
        return;
    /* the ends' radii: r0 at z = -H|v|, r1 at +H|v| (a leaf's as its side forms them) */
    vf ra, za;
    KFN(cone_anchor)(k, F, kap, &ra, &za);
    const vf hv = KFN(leaf_in)(k, F, CYLRAY_LF_HV);
    vf r_lo =
        KFN(cyl_in)(k, F, offsetof(cylray_prepared, r0), vfma(kap, vsub(vneg(hv), za), ra));
    vf r_hi = KFN(cyl_in)(k, F, offsetof(cylray_prepared, r1), vfma(kap, vsub(hv, za), ra));
    if (F.round) /* (its ends at the tangent circles) */
        KFN(round_rims)(k, &r_lo, &r_hi);
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
    if (!F.tiny && !F.round) /* (a tip is a tiny end: cylray_cone_tiny_; or a round
                                * cone's point end) */
        return;
    const vf zero = vzero();
    const vf kap = KFN(both_in)(k, F, offsetof(cylray_prepared, kap), CYLRAY_LF_KAP);
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
