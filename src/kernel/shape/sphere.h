/* SPDX-License-Identifier: MIT */
/* kernel/shape/sphere.h - a sphere's own stages: no axis and no tube, its quadratic,
 * its far root and its normal (called through kernel/shape.h). */

/* The end of the rejection: the sphere test is the sphere itself, with a margin, and no
 * tube follows. The quadratic's A is d.d. */
CYLRAY_INLINE int KFN(sphere_reject)(KFN(lanes) *st, vm act)
{
    st->ex = st->ey = st->ez = vzero();
    st->A = st->dd, st->act = act;
    return many(act);
}

/* Stage 4 of a sphere: d.d t^2 - 2 nB t + C with nB = -p.d and C = p.p - R^2 from
 * the shifted origin p, and the discriminant in Lagrange's form, d.d R^2 - |p x d|^2:
 * |p x d| is the line's distance from the center times |d|, which no shift changes,
 * so near a tangency D is as accurate as d.d R^2 and the cross product, not the
 * difference of two squares of the shifted origin's terms. Returns whether any lane
 * can still hit. */
CYLRAY_INLINE int KFN(sphere_side)(KFN(lanes) *st, const cylray_kat_ *k, const cylray_kflags_ F)
{
    const vf zero = vzero(), dx = st->dx, dy = st->dy, dz = st->dz;
    const vf px = st->px, py = st->py, pz = st->pz;
    st->fx = st->fy = st->fz = st->g = zero;
    st->nB = vneg(KDOT(dx, dy, dz, px, py, pz));
    st->C = vsumsq_x(px, py, pz, st->rr_vv);
    vf hx = vfms(py, dz, vmul(pz, dy)), hy = vfms(pz, dx, vmul(px, dz)),
       hz = vfms(px, dy, vmul(py, dx));
    vf rr = st->rr;
    if (F.scaled || F.leaf) { /* 2^-2j, as the cylinder's (R 2^-j exact) */
        const vf gs = KFN(both_in)(k, F, offsetof(cylray_prepared, g_s), CYLRAY_LF_GS);
        const vf rs = vmul(st->rad, gs);
        rr = KFN(cyl_in)(k, F, offsetof(cylray_prepared, rr_d), vmul(rs, rs));
        hx = vmul(hx, gs), hy = vmul(hy, gs), hz = vmul(hz, gs);
    }
    st->AR2 = vmul(st->A, rr);
    st->D = vfms(st->A, rr, KDOT(hx, hy, hz, hx, hy, hz));
    const vm act = mand(st->act, veq(vfma(st->C, zero, vmul(st->D, zero)), zero));
    st->side = mand(act, vge(st->D, zero));
    st->inpar = vlt(vset1(1.0f), zero);
    return many(st->side);
}

/* A sphere's A is d.d, whose reciprocal the shift has formed. */
CYLRAY_INLINE vf KFN(sphere_near_root)(const KFN(lanes) *st, vf q)
{
    return vmul(q, st->rdd);
}

/* A shifted lane's nB = -p.d is nearly 0 (p is the closest approach, to the rounding of
 * s), so nB - sign(nB) sq cancels nothing that s + t' does not round away: the far root
 * by the reciprocal as well, and no division. A lane the shift left (s = 0) takes C / q
 * as the other shapes do, by the same branch. */
CYLRAY_INLINE vf KFN(sphere_far_root)(const KFN(lanes) *st, const cylray_kflags_ F, vm side,
                                      vf q, vf sq, vf r1)
{
    const vf nB = st->nB, C = st->C, A = st->A, tiny = vset1(KM_TINY);
    vf r2 = vmul(vsub(nB, vxorsign(sq, nB)), st->rdd);
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
    return r2;
}

/* The normal: (p + t d) / R, the hit point relative to the center. */
CYLRAY_INLINE void KFN(sphere_normal)(const KFN(lanes) *st, const cylray_kat_ *k,
                                      const cylray_kflags_ F, vf *nx, vf *ny, vf *nz)
{
    const vf tr = st->tr;
    const vf kn = KFN(both_in)(k, F, offsetof(cylray_prepared, nscale), CYLRAY_LF_NSCALE);
    *nx = vmul(vfma(tr, st->dx, st->px), kn);
    *ny = vmul(vfma(tr, st->dy, st->py), kn);
    *nz = vmul(vfma(tr, st->dz, st->pz), kn);
}
