/* SPDX-License-Identifier: MIT */
/* kernel/solve.h - stages 3 to 5: the shifted origin, the side's quadratic and its
 * roots (the sphere's and the cone's stage 4 in kernel/shapes.h). */

/* Stage 3, the shift: w's rounding error, and the origin moved by s along the ray
 * with the product s d exact. The inputs are read again rather than kept across the
 * rejection (the caller's CYLRAY_REREAD): a rejected vector then spills nothing, and
 * the rest loses nothing (it would reload them from the stack instead). p = s d + (wh +
 * wl) is o - c + s d: without an FMA (simd/x86.h) it is formed from o and c in double,
 * the same bits, and wl is then left to the stages that read it (the slide, an aligned
 * g). */
CYLRAY_INLINE void KFN(shift)(KFN(lanes) *st, const cylray_kat_ *k, const cylray_kflags_ F)
{
    KFN(load_o)(st, k, F);
    vf bx = vsub(st->whx, st->ox), by = vsub(st->why, st->oy), bz = vsub(st->whz, st->oz);
    st->wlx = vsub(vsub(st->ox, vsub(st->whx, bx)), vadd(st->cx, bx));
    st->wly = vsub(vsub(st->oy, vsub(st->why, by)), vadd(st->cy, by));
    st->wlz = vsub(vsub(st->oz, vsub(st->whz, bz)), vadd(st->cz, bz));
    st->am = vzero(); /* (read only where F.slender) */
    if (F.slender) {  /* a slender shape's lanes framed where the ray passes */
        vf hx, hy, hz;
        KFN(anchor)(st, k, F, &hx, &hy, &hz);
        st->px = vfma_x2(st->s, st->dx, hx, st->wlx);
        st->py = vfma_x2(st->s, st->dy, hy, st->wly);
        st->pz = vfma_x2(st->s, st->dz, hz, st->wlz);
        return;
    }
    st->px = vfma_xw(st->s, st->dx, st->ox, st->cx, st->whx, st->wlx);
    st->py = vfma_xw(st->s, st->dy, st->oy, st->cy, st->why, st->wly);
    st->pz = vfma_xw(st->s, st->dz, st->oz, st->cz, st->whz, st->wlz);
}

/* An infinite cylinder has no center: c may slide along the axis (any slide u is
 * exact when the product u v is, as in the FMA). The error of a root t' grows with
 * its distance from the shifted point: a far origin aimed near c wants the point near
 * c, an origin near the surface far along the axis wants c slid to the origin's
 * level. |C / B| estimates the near root's distance; each lane keeps the shift that
 * makes it smaller. */
CYLRAY_INLINE void KFN(slide)(KFN(lanes) *st, const cylray_kat_ *k, const cylray_kflags_ F)
{
    const vf vx = st->vx, vy = st->vy, vz = st->vz, dx = st->dx, dy = st->dy, dz = st->dz;
    /* u need not be accurate (the slide is exact for any u); a leaf, which stores no
     * 1 / v.v, forms it as the shift does (KRCP). */
    vf u = vmul(KDOT(st->whx, st->why, st->whz, vx, vy, vz),
                KFN(cyl_in)(k, F, offsetof(cylray_prepared, inv_vv),
                            KRCP(F, KDOT(vx, vy, vz, vx, vy, vz))));
    vf hx = vfma_x(vneg(u), vx, st->whx), hy = vfma_x(vneg(u), vy, st->why),
       hz = vfma_x(vneg(u), vz, st->whz);
    vf s2 = vfnma(KDOT(hx, hy, hz, dx, dy, dz), st->rdd, vzero());
    vf qx = vfma_x2(s2, dx, hx, st->wlx);
    vf qy = vfma_x2(s2, dy, hy, st->wly);
    vf qz = vfma_x2(s2, dz, hz, st->wlz);
    vf nB2, C2, g2 = st->g, fx2, fy2, fz2;
    KFN(side_coefs)
    (st->rr_vv, F.aligned, dx, dy, st->ex, st->ey, st->ez, vx, vy, vz, qx, qy, qz, &fx2, &fy2,
     &fz2, &nB2, &C2, &g2);
    vm slide = vlt(vabs(vmul(C2, st->nB)), vabs(vmul(st->C, nB2)));
    if (F.leaf)
        slide = mand(slide, st->infl);
    st->s = vsel(slide, s2, st->s);
    st->px = vsel(slide, qx, st->px), st->py = vsel(slide, qy, st->py);
    st->pz = vsel(slide, qz, st->pz);
    st->fx = vsel(slide, fx2, st->fx), st->fy = vsel(slide, fy2, st->fy);
    st->fz = vsel(slide, fz2, st->fz);
    st->nB = vsel(slide, nB2, st->nB), st->C = vsel(slide, C2, st->C);
    st->g = vsel(slide, g2, st->g);
}

/* Stage 4, the side's quadratic and its discriminant, in Lagrange's form. Returns
 * whether any lane can still hit. */
CYLRAY_INLINE int KFN(side)(KFN(lanes) *st, const cylray_kat_ *k, const cylray_kflags_ F)
{
    const vf zero = vzero(), dx = st->dx, dy = st->dy;
    st->cr = st->ca = st->zn = zero; /* a cone's */
    st->near = mfrom_bits(0u);
    st->pol = vlt(vset1(1.0f), zero);
    if (F.sphere)
        return KFN(sphere_side)(st, k, F);
    if (F.cone)
        return KFN(cone_side)(st, k, F);
    st->g = zero;
    if (F.aligned) {
        /* g = w x d, in the plane: it does not change along the ray, and Kahan's
         * difference of products is accurate relative to g itself (2 eps), so g is
         * taken from the unshifted w = wh + wl, and the discriminant need not wait
         * for the shift. */
        st->g = vadd(vdop_x(st->whx, dy, st->why, dx), vfms(st->wlx, dy, vmul(st->wly, dx)));
    }
    KFN(side_coefs)
    (st->rr_vv, F.aligned, dx, dy, st->ex, st->ey, st->ez, st->vx, st->vy, st->vz, st->px,
     st->py, st->pz, &st->fx, &st->fy, &st->fz, &st->nB, &st->C, &st->g);
    if (!F.finite || (F.leaf && many(st->infl)))
        KFN(slide)(st, k, F);

    /* Lagrange's form of B^2 - A C, over v.v, with both products exact. AR2, the
     * larger term of D, sets its rounding. */
    const vf A = st->A, g = st->g;
    if (!F.scaled && !F.leaf) { /* a radius in [2^-20, 2^21): j = 0 */
        st->D = vdop_x(A, st->rr, g, g);
        st->AR2 = vmul(A, st->rr);
    } else { /* scaled by 2^-2j (cylray_prepared.rr_d), and sqrt_vv has 2^j */
        const vf gs = KFN(both_in)(k, F, offsetof(cylray_prepared, g_s), CYLRAY_LF_GS);
        const vf rs = vmul(st->rad, gs); /* a leaf's R 2^-j, exact */
        const vf rr_d = KFN(cyl_in)(k, F, offsetof(cylray_prepared, rr_d), vmul(rs, rs));
        vf gd = vmul(g, gs);
        st->D = vdop_x(A, rr_d, gd, gd);
        st->AR2 = vmul(A, rr_d);
    }
    vm act = mand(st->act, veq(vfma(st->C, zero, vmul(st->D, zero)), zero));

    /* A ray within about one ulp of the axis direction is parallel: it meets the side
     * nowhere, and no division by its tiny A may make a hit. */
    const vf par_eps = KFN(cyl_in)(
        k, F, offsetof(cylray_prepared, par_eps),
        vmul(KDOT(st->vx, st->vy, st->vz, st->vx, st->vy, st->vz), vset1(CYLRAY_PAR_EPS)));
    vm par = vle(A, vmul(st->dd, par_eps));
    st->side = mand(act, mandn(vge(st->D, zero), par));
    st->inpar = mand(act, mand(par, vle(st->C, zero))); /* parallel and inside the tube */
    return F.capped ? many(mor(st->side, st->inpar)) : many(st->side);
}

/* Stage 5, the side's roots tn <= tf (relative to p), polished with CYLRAY_REFINE. */
CYLRAY_INLINE void KFN(roots)(KFN(lanes) *st, const cylray_kat_ *k, const cylray_kflags_ F)
{
    const vm side = st->side;
    const vf A = st->A, C = st->C, D = st->D, nB = st->nB;
    /* The estimates see subnormal inputs as zero: below 2^-100 (rare where the
     * coordinates are near 1, and D = 0 at a tangency) the exact operation serves. */
    const vf tiny = vset1(KM_TINY);
    vf sq;
    if (F.fast) {
        sq = vmul(D, vrsqrt_fast(vmax(D, tiny)));
        vm small = mand(side, vlt(D, tiny));
        if (many(small))
            sq = vsel(small, vsqrt(D), sq);
    } else {
        sq = vsqrt(D);
    }
    /* |v| = 1 along a coordinate axis and on a sphere, and there j = 0 */
    if (!F.aligned && !(F.sphere && !F.scaled && !F.leaf))
        sq = vmul(sq, F.leaf ? KFN(leaf_in)(k, F, CYLRAY_LF_SQS)
                             : vset1(F.scaled ? k->P->sqrt_vv / k->P->g_s : k->P->sqrt_vv));
    vf q = vadd(nB, vxorsign(sq, nB)); /* -(B + sign(B) sqrt(disc)); sq >= 0 */
    /* A sphere's A is d.d, whose reciprocal the shift has formed. */
    vf r1 = F.sphere ? vmul(q, st->rdd) : F.fast ? vmul(q, vrcp_fast(A)) : vdiv(q, A);
    if (F.cone && F.fast) { /* A of a ray along a generator line can be 0 or tiny */
        vm small = mand(side, vlt(vabs(A), tiny));
        if (many(small))
            r1 = vsel(small, vdiv(q, A), r1);
    }
    vf r2;
    if (F.sphere) {
        /* A shifted lane's nB = -p.d is nearly 0 (p is the closest approach, to the
         * rounding of s), so nB - sign(nB) sq cancels nothing that s + t' does not
         * round away: the far root by the reciprocal as well, and no division. A lane
         * the shift left (s = 0) takes C / q as below, by the same branch. */
        r2 = vmul(vsub(nB, vxorsign(sq, nB)), st->rdd);
        const vm unshifted = mand(side, veq(st->s, vzero()));
        if (many(unshifted)) {
            vf r2q = F.fast ? vmul(C, vrcp_fast(q)) : vdiv(C, q);
            if (F.fast) {
                vm small = mand(side, vlt(vabs(q), tiny));
                if (many(small))
                    r2q = vsel(small, vdiv(C, q), r2q);
            }
            r2q = vsel(mor(veq(q, vzero()), vlt(vmul(q, q), vmul(C, A))), r1, r2q);
            r2 = vsel(unshifted, r2q, r2);
        }
    } else if (F.fast) {
        r2 = vmul(C, vrcp_fast(q));
        vm small = mand(side, vlt(vabs(q), tiny));
        if (many(small))
            r2 = vsel(small, vdiv(C, q), r2);
    } else {
        r2 = vdiv(C, q);
    }
    /* By construction q^2 >= A C. Where rounding of C (a point on the surface, or a
     * tangent ray) breaks that, C / q is no root: the two coincide at q / A. */
    if (!F.sphere)
        r2 = vsel(mor(veq(q, vzero()), vlt(vmul(q, q), vmul(C, A))), r1, r2);
    /* Near a tangency D is known only to a few ulps of A R^2 (the rounding of A, R^2
     * and g), and C, at a point near the surface, only to a few ulps of R^2: C / q then
     * divides one rounding error by another and can put the root anywhere, even past
     * the origin (a ray leaving the surface reported as hitting it from inside). The
     * direct form (nB - sign sq) / A errs by the error of sq alone. */
    vm tangent = mand(side, vlt(D, vmul(st->AR2, vset1(KM_TANGENT))));
    if (many(tangent)) {
        /* A cone's A also vanishes off a tangency, for a ray along a generator line
         * (e.e = v.v a^2): the direct form would divide by the rounding of A, and C / q
         * (q about 2 nB there) is the accurate root. */
        if (F.cone)
            tangent = mand(
                tangent, vgt(vabs(A), vmul(KDOT(st->ex, st->ey, st->ez, st->ex, st->ey, st->ez),
                                           vset1(KM_GENERATOR))));
        r2 = vsel(tangent, vdiv(vsub(nB, vxorsign(sq, nB)), A), r2);
    }
    if (F.cone) { /* the roots of a cancelled nB, polished (CYLRAY_REFINE: all) */
        const vm pol = F.refine ? side : mand(side, st->pol);
        if (many(pol)) {
            r1 = vsel(pol, KFN(cone_polish)(st, r1), r1);
            r2 = vsel(pol, KFN(cone_polish)(st, r2), r2);
        }
    }
    st->tn = vmin(r1, r2), st->tf = vmax(r1, r2);
    if (F.refine && !F.cone && many(side)) {
        /* Both roots are polished before anything is decided from them, so that the
         * entry test, the clip and the range test all see the t that is reported: a
         * call with tmax set to a reported t then reports it again. */
        st->tn = KFN(polish)(st->rr_vv, st->rr, F.aligned, F.sphere, side, st->tn, A, st->dx,
                             st->dy, st->dz, st->ex, st->ey, st->ez, st->vx, st->vy, st->vz,
                             st->px, st->py, st->pz);
        st->tf = KFN(polish)(st->rr_vv, st->rr, F.aligned, F.sphere, side, st->tf, A, st->dx,
                             st->dy, st->dz, st->ex, st->ey, st->ez, st->vx, st->vy, st->vz,
                             st->px, st->py, st->pz);
    }
}
