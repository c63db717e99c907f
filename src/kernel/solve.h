/* SPDX-License-Identifier: MIT */
/* kernel/solve.h - stages 3 to 5: the shifted origin, the side's quadratic and its
 * roots (each shape's own part through kernel/shape.h). */

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
        KFN(anchor)(st, k, F, KFN(shape_anchor_rr)(st, k, F), &hx, &hy, &hz);
        st->px = vfma_x2(st->s, st->dx, hx, st->wlx);
        st->py = vfma_x2(st->s, st->dy, hy, st->wly);
        st->pz = vfma_x2(st->s, st->dz, hz, st->wlz);
        return;
    }
    st->px = vfma_xw(st->s, st->dx, st->ox, st->cx, st->whx, st->wlx);
    st->py = vfma_xw(st->s, st->dy, st->oy, st->cy, st->why, st->wly);
    st->pz = vfma_xw(st->s, st->dz, st->oz, st->cz, st->whz, st->wlz);
}

/* Stage 4, the side's quadratic and its discriminant, in Lagrange's form. Returns
 * whether any lane can still hit. */
CYLRAY_INLINE int KFN(side)(KFN(lanes) *st, const cylray_kat_ *k, const cylray_kflags_ F)
{
    KFN(shape_start)(st);
    return KFN(shape_side)(st, k, F);
}

/* Stage 5, the side's roots tn <= tf (relative to p), polished with CYLRAY_REFINE. */
CYLRAY_INLINE void KFN(roots)(KFN(lanes) *st, const cylray_kat_ *k, const cylray_kflags_ F)
{
    const vm side = st->side;
    const vf A = st->A, D = st->D, nB = st->nB;
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
    if (!KFN(shape_unit_v)(F)) /* (j = 0 where |v| = 1) */
        sq = vmul(sq, F.leaf ? KFN(leaf_in)(k, F, CYLRAY_LF_SQS)
                             : vset1(F.scaled ? k->P->sqrt_vv / k->P->g_s : k->P->sqrt_vv));
    vf q = vadd(nB, vxorsign(sq, nB)); /* -(B + sign(B) sqrt(disc)); sq >= 0 */
    vf r1 = KFN(shape_near_root)(st, F, side, q, A);
    vf r2 = KFN(shape_far_root)(st, F, side, q, sq, r1);
    /* Near a tangency D is known only to a few ulps of A R^2 (the rounding of A, R^2
     * and g), and C, at a point near the surface, only to a few ulps of R^2: C / q then
     * divides one rounding error by another and can put the root anywhere, even past
     * the origin (a ray leaving the surface reported as hitting it from inside). The
     * direct form (nB - sign sq) / A errs by the error of sq alone. */
    vm tangent = mand(side, vlt(D, vmul(st->AR2, vset1(KM_TANGENT))));
    if (many(tangent)) {
        tangent = KFN(shape_tangent)(st, F, tangent, A);
        r2 = vsel(tangent, vdiv(vsub(nB, vxorsign(sq, nB)), A), r2);
    }
    KFN(shape_polish_roots)(st, F, side, &r1, &r2);
    st->tn = vmin(r1, r2), st->tf = vmax(r1, r2);
    KFN(shape_polish_bounds)(st, F, side, A);
}
