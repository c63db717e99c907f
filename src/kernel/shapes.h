/* SPDX-License-Identifier: MIT */
/* kernel/shapes.h - stage 4 of the sphere and of the cone, whose quadratics are not the
 * cylinder's, and the polish of a cone's roots (called from kernel/solve.h). */

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

/* Stage 4 of a cone, whose radius at the axial coordinate z = p.v is r = ra + kap (z - za)
 * (cone_anchor): with f = v x p and e = d x v as the cylinder's, r0 the radius at the
 * shifted origin's level and a = kap (d.v) its rate along the ray, the side of the
 * double cone is |f - t e|^2 = v.v (r0 + a t)^2, so
 *   A = e.e - v.v a^2,  nB = e.f + v.v a r0,  C = f.f - v.v r0^2,
 * and Lagrange's identity turns B^2 - A C into v.v (|r0 e + a f|^2 - g^2), g = e.p as
 * the cylinder's (whose r0 e is R e and a 0). The roots of either sign of A are the
 * cylinder's; the slab of the ends (kernel/ends.h) then keeps the nappe the cone is on.
 * The terms that cancel (r0 near an apex, A near a generator line, nB, g and D near a
 * tangency) are each rounded once (vfma_x, KDOTX): the FMA ISAs' forms, which SSE4.1
 * forms in double; with their products rounded apart, SSE4.1 put t near an apex or a
 * tangency tens to hundreds of ulps outside the band. Returns whether any lane can
 * still hit. */
/* A cone's axial coordinate z0 = p.v, one rounding (KDOTX): its radius at z0 and the
 * ends' slab (kernel/ends.h) both take this one, so that an error in it moves
 * the planes and the side together along the axis and keeps their order where a flat
 * side runs along a plane (rounded product by product, SSE4.1 once put the slab past
 * the side there). The compiler forms it once. */
CYLRAY_INLINE vf KFN(cone_z0)(const KFN(lanes) *st)
{
    return KDOTX(st->px, st->py, st->pz, st->vx, st->vy, st->vz);
}
/* Its rate along the ray dv = d.v, one rounding too: the radius's rate a = kap dv and
 * the slab both take it. A = e.e - v.v a^2 cancels where the ray runs near a generator
 * line, and there an error in d.v that e = d x v does not share moves the root: rounded
 * product by product (SSE4.1), it put t 0.6 % outside the band on a flat tip cone
 * 1.4e-10 long and 0.47 wide. */
CYLRAY_INLINE vf KFN(cone_dv)(const KFN(lanes) *st)
{
    return KDOTX(st->dx, st->dy, st->dz, st->vx, st->vy, st->vz);
}

/* A cone's narrower end, from which its radius is formed: r = ra + kap (z - za), with ra
 * that end's radius as given and za its axial coordinate (-H|v| where kap > 0, +H|v|
 * where kap < 0). At the narrow end's plane z - za is exact (z0 is computed from the
 * same p.v as the slab's), so the disc meets the side at the radius given, however
 * small beside the other; rm + kap z would cancel there to an ulp of the wide end (a
 * 1e-10 tip beside a radius of 0.5 came out 7e-9 wide). Away from it kap (z - za) is
 * the radius's growth from ra, rounded relative to itself: the radius is good to a few
 * ulps of its own value at every level. A leaf holds ra as its radius row; a cylinder's
 * lane in a leaf of cones (kap = 0) takes za = 0, whose half height may be infinite. */
CYLRAY_INLINE void KFN(cone_anchor)(const cylray_kat_ *k, const cylray_kflags_ F, vf kap,
                                    vf *ra, vf *za)
{
    if (F.leaf) {
        const vf hv = KFN(leaf_in)(k, F, CYLRAY_LF_HV);
        *ra = KFN(leaf_in)(k, F, CYLRAY_LF_RA);
        *za = vsel(veq(kap, vzero()), vzero(), vneg(vxorsign(hv, kap)));
    } else {
        const cylray_prepared *P = k->P;
        *ra = vset1(cylray_cone_ra_(P));
        *za = vset1(P->kap > 0 ? -P->h_v : P->h_v);
    }
}

/* A cone is far smaller near its narrower end than its distance from the center, which
 * sets the rounding of p (and of s + t', and of f = v x p where p runs along the axis):
 * a ray from next to a tip 1e-9 wide and 10 from the center would see it to 1e-6. A
 * lane whose origin lies at least twice as near that end as the center therefore takes
 * its origin there: p = o - a unshifted (s = 0), with a = c + m v, m the power of two
 * nearest za / v.v, so that m v is exact and p = (wh - m v) + wl is o - a rounded at
 * its own size. Axial coordinates are then measured from a: the narrower end's plane
 * lies at zn = za - m v.v (vdot3_x: a residue of the rounding of H|v|, formed to far
 * below it), the other 2 H|v| beyond (KFN(cone_planes), for the slab). Everything after
 * is the same quadratic in that frame, whose C = f.f - v.v r0^2, which cancels to the
 * tiny radius, is formed to the last bits.
 *
 * Only where the cone comes to a point or nearly (its narrower end under 1/64 of the
 * other, cylray_cone_tiny_) is that end's size below what the center's frame resolves:
 * those cones, and leaves that hold one, run kernels of their own (CYLRAY_KF_TINY), and
 * every other cone's kernel has none of this work. */

/* The lanes of a tiny-ended cone: a prepared one's all, a leaf's as its meta marks. */
CYLRAY_INLINE vm KFN(cone_tiny)(const cylray_kat_ *k, const cylray_kflags_ F)
{
    if (!F.tiny)
        return mfrom_bits(0u);
    if (F.leaf) {
        const uint32_t *meta = KFN(leaf_meta)(k);
        return mfrom_bits(cylray_leaf_tiny_(meta) >> k->i);
    }
    /* (a slender cone's kernel serves tiny-ended ones and others) */
    return mfrom_bits(cylray_cone_tiny_(k->P) ? VFULL : 0u);
}

/* The lanes of `tiny` whose origin is near the narrower end, from w = o - c rounded:
 * |o - a|^2 v.v = w.w v.v - 2 (w.v) za + za^2, against w.w v.v / 4. */
CYLRAY_INLINE vm KFN(cone_near)(vm tiny, vf wx, vf wy, vf wz, vf vx, vf vy, vf vz, vf vv, vf za)
{
    const vf ww = KDOT(wx, wy, wz, wx, wy, wz), zw = KDOT(wx, wy, wz, vx, vy, vz);
    const vf oa = vfma(za, za, vfms(ww, vv, vmul(vadd(zw, zw), za)));
    return mand(tiny, vlt(vmul(oa, vset1(4.0f)), vmul(ww, vv)));
}

/* Takes the narrower end's frame on the lanes near it (st->near): p, s, and za, the
 * narrower end's axial coordinate, which becomes zn (kept in st->zn for the slab). */
CYLRAY_INLINE void KFN(cone_frame)(KFN(lanes) *st, vm tiny, vf vv, vf *za)
{
    const vf vx = st->vx, vy = st->vy, vz = st->vz;
    const vm near = KFN(cone_near)(tiny, st->whx, st->why, st->whz, vx, vy, vz, vv, *za);
    st->near = near;
    if (!many(near))
        return;
    const vf m = vexpsign(vmul(vdiv(*za, vv), vset1(1.25f)));
    const vf mx = vmul(m, vx), my = vmul(m, vy), mz = vmul(m, vz);
    st->px = vsel(near, vadd(vsub(st->whx, mx), st->wlx), st->px);
    st->py = vsel(near, vadd(vsub(st->why, my), st->wly), st->py);
    st->pz = vsel(near, vadd(vsub(st->whz, mz), st->wlz), st->pz);
    st->s = vsel(near, vzero(), st->s);
    st->zn = vdot3_x(vneg(mx), vneg(my), vneg(mz), vx, vy, vz, *za);
    *za = vsel(near, st->zn, *za);
}

/* The slab's planes, the axial coordinates of -H and +H (kernel/ends.h), on the lanes
 * that took the narrower end's frame: that end's at zn, the other 2 H|v| beyond. */
CYLRAY_INLINE void KFN(cone_planes)(const KFN(lanes) *st, const cylray_kat_ *k,
                                    const cylray_kflags_ F, vf *zlo, vf *zhi)
{
    if (!F.tiny || !many(st->near))
        return;
    const vf kap = KFN(both_in)(k, F, offsetof(cylray_prepared, kap), CYLRAY_LF_KAP);
    vf ra, za;
    KFN(cone_anchor)(k, F, kap, &ra, &za);
    const vf zn = st->zn, zf = vsub(zn, vadd(za, za));
    const vm lo = vlt(za, vzero()); /* the narrower end is the low one */
    *zlo = vsel(st->near, vsel(lo, zn, zf), *zlo);
    *zhi = vsel(st->near, vsel(lo, zf, zn), *zhi);
}

CYLRAY_INLINE int KFN(cone_side)(KFN(lanes) *st, const cylray_kat_ *k, const cylray_kflags_ F)
{
    const vf zero = vzero();
    const vf vx = st->vx, vy = st->vy, vz = st->vz;
    const vf kap = KFN(both_in)(k, F, offsetof(cylray_prepared, kap), CYLRAY_LF_KAP);
    vf ra, za;
    KFN(cone_anchor)(k, F, kap, &ra, &za);
    const vf vv = KDOT(vx, vy, vz, vx, vy, vz);
    const vm tiny = KFN(cone_tiny)(k, F);
    if (F.tiny)
        KFN(cone_frame)(st, tiny, vv, &za);
    if (F.slender) { /* the narrower end's plane from a slender cone's anchor */
        st->am = vsel(st->near, zero, st->am); /* (the tiny end's frame there) */
        za = vsel(st->near, za, KFN(axial)(st, F, za));
    }
    const vf px = st->px, py = st->py, pz = st->pz;
    const vf ex = st->ex, ey = st->ey, ez = st->ez;
    const vf fx = vfms(vy, pz, vmul(vz, py)), fy = vfms(vz, px, vmul(vx, pz)),
             fz = vfms(vx, py, vmul(vy, px));
    st->fx = fx, st->fy = fy, st->fz = fz;
    const vf r0 = vfma_x(kap, vsub(KFN(cone_z0)(st), za), ra);
    const vf a = vmul(kap, KFN(cone_dv)(st));
    const vf va = vmul(vv, a);
    st->cr = r0, st->ca = a;
    const vf ee = st->A;
    /* e.e - v.v a^2, and + 0: where both terms lie below the smallest float (a
     * direction within 1e-16 of the angle of a long, thin cone) A rounds to a zero,
     * whose sign the far root q / A takes. Exactly, A -> 0 from either side leaves the
     * same half-line inside, the one A >= 0 reads from [C / q, +-inf]; -0 would give
     * [-inf, C / q], the line's outside. */
    st->A = vadd(vfnma_x(va, a, ee), zero);
    st->pol = vlt(vabs(st->A), vmul(ee, vset1(KM_CANCEL))); /* see the roots */
    st->nB = vfma_x(va, r0, KDOTX(ex, ey, ez, fx, fy, fz));

    const vf vrr = vmul(vmul(vv, r0), r0);
    st->C = vsumsq_x(fx, fy, fz, vrr);
    if (KSUMSQ_CHAINED && F.tiny && many(tiny)) /* (in double, vsumsq_x is that already) */
        st->C = vsel(tiny, vdot3_x(fx, fy, fz, fx, fy, fz, vneg(vrr)), st->C);
    vf g = KDOTX(ex, ey, ez, px, py, pz);
    vf ux = vfma_x(r0, ex, vmul(a, fx)), uy = vfma_x(r0, ey, vmul(a, fy)),
       uz = vfma_x(r0, ez, vmul(a, fz));
    if (F.scaled || F.leaf) { /* 2^-2j, as the cylinder's */
        const vf gs = KFN(both_in)(k, F, offsetof(cylray_prepared, g_s), CYLRAY_LF_GS);
        ux = vmul(ux, gs), uy = vmul(uy, gs), uz = vmul(uz, gs), g = vmul(g, gs);
    }
    st->g = g;
    st->AR2 = KDOT(ux, uy, uz, ux, uy, uz);
    st->D = vfnma_x(g, g, st->AR2);
    const vm act = mand(st->act, veq(vfma(st->C, zero, vmul(st->D, zero)), zero));
    /* A < 0, a line steeper than the side's lines, crosses the apex's plane, where the
     * double cone is one point: it has a root on each side of that plane, or a double
     * root at the apex. D < 0 there is rounding (near the apex u = r0 e + a f cancels),
     * and the answer is that double root, nB / A, whose nappe the slab keeps (KFN(ends)):
     * never the whole line inside, which would let the slab's open end at a tip take
     * the entry. Only a line whose A may be 0 exactly (KM_ROOTLESS: along the side's
     * lines) can have no roots: A = 0 and nB = 0, and the line is inside everywhere
     * where C <= 0 and outside everywhere where C > 0. */
    st->side = mand(act, vge(st->D, zero));
    st->inpar = mfrom_bits(0u);
    const vm nod = mandn(mand(act, vlt(st->A, zero)), st->side);
    if (many(nod)) {
        const vm gen = vlt(vabs(st->A), vmul(ee, vset1(KM_ROOTLESS)));
        st->D = vsel(mandn(nod, gen), zero, st->D);
        st->side = mor(st->side, mandn(nod, gen));
        st->inpar = mand(mand(nod, gen), vle(st->C, zero)); /* no roots, inside everywhere */
    }
    if (F.leaf) {
        /* A cylinder's lane in a leaf of cones (a = 0) leaves A = e.e: a ray within
         * about an ulp of the axis direction is parallel, as the cylinder's, meets no
         * side, and is inside everywhere where C <= 0. (A prepared cone's radius
         * changes along any ray near its axis.) */
        const vf par_eps = vmul(vv, vset1(CYLRAY_PAR_EPS));
        const vm par = mand(veq(a, zero), vle(st->A, vmul(st->dd, par_eps)));
        st->side = mandn(st->side, par);
        st->inpar = mor(mandn(st->inpar, par), mand(mand(act, par), vle(st->C, zero)));
    }
    return many(mor(st->side, st->inpar));
}

/* A ray that runs within a few degrees of the side's lines (A = e.e - v.v a^2 cancels:
 * along a generator line, or leaving the side near the apex at a shallow angle) has
 * nB = e.f + v.v a r0 and C cancelled too: differences of terms many times larger,
 * whose rounding errors, uncorrelated, move a root by far more than the inputs' own 2
 * ulps do (with A small, q is about 2 nB, and C / q carries nB's relative error whole;
 * elsewhere a cancelled nB matters only near a tangency, where sqrt(D) no longer
 * outweighs it, and the band is as wide). At the root's point p + t d the quadratic's
 * terms are the size of the radius there, small near an apex, so its C and nB formed
 * there (f - t e and r0 + a t, each rounded once) are accurate, and one step of its
 * small root corrects t. A step that is not small (beyond 2^-4 |t|: a root there
 * ill-posed, as at the apex itself, a root running to infinity, or NaN) is not taken,
 * nor one that is not small beside the quadratic's other root there, q / A: on a ray
 * through the apex's neighbourhood the two roots close in on each other, C and nB at
 * the point are roundings of terms that vanish, and C / q is noise (0.3 % of t,
 * thousands of ulps). A root off by 0.7 % (a ray 0.2 degrees off a tip cone's
 * generator line, where A is small and the other root far) is not ill-posed, and
 * takes its step. */
CYLRAY_INLINE vf KFN(cone_polish)(const KFN(lanes) *st, vf t)
{
    const vf fx = vfnma(t, st->ex, st->fx), fy = vfnma(t, st->ey, st->fy),
             fz = vfnma(t, st->ez, st->fz);
    const vf r = vfma(st->ca, t, st->cr);
    const vf vv = KDOT(st->vx, st->vy, st->vz, st->vx, st->vy, st->vz);
    const vf vr = vmul(vv, r);
    const vf C = vsumsq_x(fx, fy, fz, vmul(vr, r));
    const vf nB = vfma(vmul(vv, st->ca), r, KDOT(st->ex, st->ey, st->ez, fx, fy, fz));
    const vf disc = vmax(vfnma(st->A, C, vmul(nB, nB)), vzero());
    const vf q = vadd(nB, vxorsign(vsqrt(disc), nB));
    const vf dt = vdiv(C, q);
    const vm small = mand(vle(vabs(dt), vmul(vabs(t), vset1(0x1p-4f))),
                          vle(vmul(vabs(dt), vmul(vabs(st->A), vset1(4.0f))), vabs(q)));
    return vsel(small, vadd(t, dt), t);
}
