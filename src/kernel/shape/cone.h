/* SPDX-License-Identifier: MIT */
/* kernel/shape/cone.h - a cone's own stages: its quadratic and the polish of its roots,
 * the nappe its slab keeps and its normal (called through kernel/shape.h; its frames in
 * shape/cone_frame.h, its rims and tips in shape/cone_rims.h). */

/* The end of the rejection: no tube, the cone's side is no cylinder's. */
CYLRAY_INLINE int KFN(cone_reject)(KFN(lanes) *st, vm act)
{
    st->act = act;
    return many(act);
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
        st->am = vsel(st->cone.near, zero, st->am); /* (the tiny end's frame there) */
        za = vsel(st->cone.near, za, KFN(axial)(st, F, za));
    }
    const vf px = st->px, py = st->py, pz = st->pz;
    const vf ex = st->ex, ey = st->ey, ez = st->ez;
    const vf fx = vfms(vy, pz, vmul(vz, py)), fy = vfms(vz, px, vmul(vx, pz)),
             fz = vfms(vx, py, vmul(vy, px));
    st->fx = fx, st->fy = fy, st->fz = fz;
    const vf r0 = vfma_x(kap, vsub(KFN(cone_z0)(st), za), ra);
    const vf a = vmul(kap, KFN(cone_dv)(st));
    const vf va = vmul(vv, a);
    st->cone.cr = r0, st->cone.ca = a;
    const vf ee = st->A;
    /* e.e - v.v a^2, and + 0: where both terms lie below the smallest float (a
     * direction within 1e-16 of the angle of a long, thin cone) A rounds to a zero,
     * whose sign the far root q / A takes. Exactly, A -> 0 from either side leaves the
     * same half-line inside, the one A >= 0 reads from [C / q, +-inf]; -0 would give
     * [-inf, C / q], the line's outside. */
    st->A = vadd(vfnma_x(va, a, ee), zero);
    st->cone.pol = vlt(vabs(st->A), vmul(ee, vset1(KM_CANCEL))); /* see the roots */
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

/* A of a ray along a generator line can be 0 or tiny: there the estimate of its
 * reciprocal gives way to the division. */
CYLRAY_INLINE vf KFN(cone_near_root)(const cylray_kflags_ F, vm side, vf q, vf A, vf r1)
{
    if (F.fast) {
        vm small = mand(side, vlt(vabs(A), vset1(KM_TINY)));
        if (many(small))
            r1 = vsel(small, vdiv(q, A), r1);
    }
    return r1;
}

/* A cone's A also vanishes off a tangency, for a ray along a generator line (e.e = v.v
 * a^2): the tangent's direct form would divide by the rounding of A, and C / q (q about
 * 2 nB there) is the accurate root. */
CYLRAY_INLINE vm KFN(cone_tangent)(const KFN(lanes) *st, vm tangent, vf A)
{
    return mand(tangent, vgt(vabs(A), vmul(KDOT(st->ex, st->ey, st->ez, st->ex, st->ey, st->ez),
                                           vset1(KM_GENERATOR))));
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
    const vf r = vfma(st->cone.ca, t, st->cone.cr);
    const vf vv = KDOT(st->vx, st->vy, st->vz, st->vx, st->vy, st->vz);
    const vf vr = vmul(vv, r);
    const vf C = vsumsq_x(fx, fy, fz, vmul(vr, r));
    const vf nB = vfma(vmul(vv, st->cone.ca), r, KDOT(st->ex, st->ey, st->ez, fx, fy, fz));
    const vf disc = vmax(vfnma(st->A, C, vmul(nB, nB)), vzero());
    const vf q = vadd(nB, vxorsign(vsqrt(disc), nB));
    const vf dt = vdiv(C, q);
    const vm small = mand(vle(vabs(dt), vmul(vabs(t), vset1(0x1p-4f))),
                          vle(vmul(vabs(dt), vmul(vabs(st->A), vset1(4.0f))), vabs(q)));
    return vsel(small, vadd(t, dt), t);
}

/* The roots of a cancelled nB, polished (CYLRAY_REFINE: all). */
CYLRAY_INLINE void KFN(cone_polish_roots)(const KFN(lanes) *st, const cylray_kflags_ F, vm side,
                                          vf *r1, vf *r2)
{
    const vm pol = F.refine ? side : mand(side, st->cone.pol);
    if (many(pol)) {
        *r1 = vsel(pol, KFN(cone_polish)(st, *r1), *r1);
        *r2 = vsel(pol, KFN(cone_polish)(st, *r2), *r2);
    }
}

/* The double cone's inside on the ray: [tn, tf] where A > 0, on one nappe (the cone's
 * where its radius there is not negative); where A < 0 the two half-lines beyond the
 * roots, one on each side of the apex's plane, of which the cone's runs the way the
 * radius grows (the sign of a, exact, rather than that of the radius at a root, which
 * is 0 at a root near the apex). The slab keeps the other nappe out; these choices keep
 * rounding near a tip from passing a sliver of it. */
CYLRAY_INLINE void KFN(cone_interval)(KFN(lanes) *st, vf *lo, vf *hi)
{
    const vf zero = vzero(), inf = vset1(INFINITY), tn = st->tn, tf = st->tf;
    const vm neg = vlt(st->A, zero);
    const vm far = vgt(st->cone.ca, zero);
    *lo = vsel(neg, vsel(far, tf, vneg(inf)), tn);
    *hi = vsel(neg, vsel(far, inf, tn), tf);
    const vf mid = vmul(vset1(0.5f), vadd(tn, tf));
    st->side = mandn(st->side, mandn(vlt(vfma_x(st->cone.ca, mid, st->cone.cr), zero), neg));
}

/* The normal: the gradient of |x_perp|^2 - r^2, p_perp - r slope n_axis, of length
 * r / cnrm on the side; p_perp = v x (p x v) / v.v as the cylinder's, and slope n_axis =
 * kap v. */
CYLRAY_INLINE void KFN(cone_normal)(const KFN(lanes) *st, const cylray_kat_ *k,
                                    const cylray_kflags_ F, vf *onx, vf *ony, vf *onz)
{
    const vf zero = vzero(), one = vset1(1.0f), tr = st->tr;
    const vf rvv = KRCP(F, KDOT(st->vx, st->vy, st->vz, st->vx, st->vy, st->vz));
    const vf kx = KFN(cyl_in)(k, F, offsetof(cylray_prepared, vk[0]), vmul(st->vx, rvv)),
             ky = KFN(cyl_in)(k, F, offsetof(cylray_prepared, vk[1]), vmul(st->vy, rvv)),
             kz = KFN(cyl_in)(k, F, offsetof(cylray_prepared, vk[2]), vmul(st->vz, rvv));
    const vf kap = KFN(both_in)(k, F, offsetof(cylray_prepared, kap), CYLRAY_LF_KAP);
    const vf cn = KFN(both_in)(k, F, offsetof(cylray_prepared, cnrm), CYLRAY_LF_CNRM);
    /* |r|: rounding near an apex may give a hit point a radius just below 0, which must
     * not turn the normal inwards. */
    const vf ar = vabs(vfma_x(st->cone.ca, tr, st->cone.cr)), rk = vmul(ar, kap),
             sc = vdiv(cn, ar);
    vf ux = vfms_x(tr, st->ex, st->fx), uy = vfms_x(tr, st->ey, st->fy),
       uz = vfms_x(tr, st->ez, st->fz);
    vf nx = vmul(vfnma_x(rk, st->vx, vfms_x(ky, uz, vmul(kz, uy))), sc);
    vf ny = vmul(vfnma_x(rk, st->vy, vfms_x(kz, ux, vmul(kx, uz))), sc);
    vf nz = vmul(vfnma_x(rk, st->vz, vfms_x(kx, uy, vmul(ky, ux))), sc);
    /* At the apex itself the gradient vanishes: the normal there is the axis, pointing
     * away from the cone (v's length is renormalised later). */
    const vm apex = mand(st->hit, veq(ar, zero));
    if (many(apex)) {
        const vf sg = vsel(vlt(kap, zero), one, vset1(-1.0f));
        nx = vsel(apex, vmul(sg, st->vx), nx), ny = vsel(apex, vmul(sg, st->vy), ny);
        nz = vsel(apex, vmul(sg, st->vz), nz);
    }
    *onx = nx, *ony = ny, *onz = nz;
}

/* A cap's normal is +-v / |v|: a leaf's cone lane forms 1 / |v| from its rows as
 * 1 / ((|v| / g_s) g_s). */
CYLRAY_INLINE vf KFN(cone_cap_scale)(const cylray_kat_ *k, const cylray_kflags_ F, vf sgn)
{
    return vdiv(sgn, vmul(KFN(leaf_in)(k, F, CYLRAY_LF_SQS), KFN(leaf_in)(k, F, CYLRAY_LF_GS)));
}
