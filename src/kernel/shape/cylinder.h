/* SPDX-License-Identifier: MIT */
/* kernel/shape/cylinder.h - a cylinder's own stages: the axis and the tube around it,
 * the side's quadratic and discriminant, the slide of an infinite cylinder's center and
 * the normal (called through kernel/shape.h). A cone reads its axis as a cylinder does
 * (KFN(axis_in), KFN(axis_cross)). */

/* The axis v (with an aligned axis, renamed: (0, 0, +-1)). */
CYLRAY_INLINE void KFN(axis_in)(KFN(lanes) *st, const cylray_kat_ *k, const cylray_kflags_ F)
{
    const vf zero = vzero();
    vf vx = zero, vy = zero, vz;
    if (!F.aligned)
        vx = KFN(both_in)(k, F, offsetof(cylray_prepared, v[0]), CYLRAY_LF_VX),
        vy = KFN(both_in)(k, F, offsetof(cylray_prepared, v[1]), CYLRAY_LF_VY);
    vz = F.leaf ? KFN(leaf_in)(k, F, CYLRAY_LF_VZ) : vset1(F.aligned ? k->P->vr : k->P->v[2]);
    st->vx = vx, st->vy = vy, st->vz = vz;
}

/* e = d x v to a relative accuracy that survives a ray almost along the axis, and A =
 * e.e; returns g0 = e.w from w rounded. With an aligned axis v = (0, 0, +-1) and e =
 * (dy, -dx, 0) up to the sign of v, which no product below sees. */
CYLRAY_INLINE vf KFN(axis_cross)(KFN(lanes) *st, const cylray_kflags_ F)
{
    const vf dx = st->dx, dy = st->dy, dz = st->dz, vx = st->vx, vy = st->vy, vz = st->vz;
    const vf whx = st->whx, why = st->why, whz = st->whz;
    vf g0, A = st->A;
    st->ex = st->ey = st->ez = vzero();
    if (F.aligned) {
        g0 = vfms(whx, dy, vmul(why, dx)); /* plain: within the tube's margin */
    } else {
        st->ex = vdop_x(dy, vz, dz, vy), st->ey = vdop_x(dz, vx, dx, vz);
        st->ez = vdop_x(dx, vy, dy, vx);
        A = KDOT(st->ex, st->ey, st->ez, st->ex, st->ey, st->ez);
        g0 = KDOT(st->ex, st->ey, st->ez, whx, why, whz);
    }
    st->A = A;
    return g0;
}

/* The end of the rejection: the tube. The ray's line passes at |g| / sqrt(A) from the
 * axis (g = e.w moves neither with the shift nor along the axis). g0 is off from the
 * exact g by less than 2^-21 sqrt(A ww); beyond that margin the line misses the tube. A
 * vector whose rays all miss the sphere or the tube ends here, before the exact work,
 * at one branch (two would mispredict on a mix of the two kinds of miss). */
CYLRAY_INLINE int KFN(cyl_reject)(KFN(lanes) *st, vm act, vf g0, vf ww)
{
    const vf A = st->A;
    act = mandn(act, vgt(vmul(g0, g0),
                         vmul(vmul(A, vset1(KM_TUBE_A)), vfma(ww, vset1(KM_TUBE_WW), st->rr))));
    st->act = act;
    return many(act);
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

/* Stage 4 of a cylinder: the side's quadratic A t^2 - 2 nB t + C and its discriminant
 * in Lagrange's form. Returns whether any lane can still hit. */
CYLRAY_INLINE int KFN(cyl_side)(KFN(lanes) *st, const cylray_kat_ *k, const cylray_kflags_ F)
{
    const vf zero = vzero(), dx = st->dx, dy = st->dy;
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

/* The normal: v x (p x v) = v.v p_perp, with p x v = f + t e already perpendicular, so
 * no axial magnitude leaks in; vk = v / (R v.v) makes it unit length. Along a
 * coordinate axis, p_perp / R in the plane. */
CYLRAY_INLINE void KFN(cyl_normal)(const KFN(lanes) *st, const cylray_kat_ *k,
                                   const cylray_kflags_ F, vf *nx, vf *ny, vf *nz)
{
    const vf tr = st->tr;
    if (F.aligned) {
        const vf kn = vset1(k->P->nscale);
        *nx = vmul(vfma(tr, st->dx, st->px), kn);
        *ny = vmul(vfma(tr, st->dy, st->py), kn);
        *nz = vzero();
        return;
    }
    const vf ns = KFN(leaf_in)(k, F, CYLRAY_LF_NSCALE);
    const vf kx = KFN(cyl_in)(k, F, offsetof(cylray_prepared, vk[0]), vmul(st->vx, ns)),
             ky = KFN(cyl_in)(k, F, offsetof(cylray_prepared, vk[1]), vmul(st->vy, ns)),
             kz = KFN(cyl_in)(k, F, offsetof(cylray_prepared, vk[2]), vmul(st->vz, ns));
    vf ux = vfms(tr, st->ex, st->fx), uy = vfms(tr, st->ey, st->fy),
       uz = vfms(tr, st->ez, st->fz);
    *nx = vfms(ky, uz, vmul(kz, uy));
    *ny = vfms(kz, ux, vmul(kx, uz));
    *nz = vfms(kx, uy, vmul(ky, ux));
}

/* The side's direction facing the ray where a hit point has none of its own (on the
 * axis): -d_perp, as v x e = v.v d_perp (aligned: d in the plane). A cone's is its
 * cylinder's. */
CYLRAY_INLINE void KFN(cyl_facing)(const KFN(lanes) *st, const cylray_kflags_ F, vf *ux, vf *uy,
                                   vf *uz)
{
    if (F.aligned) {
        *ux = st->dx, *uy = st->dy, *uz = vzero();
        return;
    }
    *ux = vfms(st->vy, st->ez, vmul(st->vz, st->ey));
    *uy = vfms(st->vz, st->ex, vmul(st->vx, st->ez));
    *uz = vfms(st->vx, st->ey, vmul(st->vy, st->ex));
}

/* A cap's normal is +-v / |v|: a leaf's lane forms 1 / |v| from its rows as
 * R |v| / (R v.v). */
CYLRAY_INLINE vf KFN(cyl_cap_scale)(const KFN(lanes) *st, const cylray_kat_ *k,
                                    const cylray_kflags_ F, vf sgn)
{
    return vmul(
        sgn, vmul(vmul(KFN(leaf_in)(k, F, CYLRAY_LF_NSCALE), st->rad),
                  vmul(KFN(leaf_in)(k, F, CYLRAY_LF_SQS), KFN(leaf_in)(k, F, CYLRAY_LF_GS))));
}
