/* SPDX-License-Identifier: MIT */
/* spawn/point.h - the hit point and its error bound */

/* A sphere's bound: the distance of the float point p from it, evaluated. With a_k =
 * p_k - c_k rounded once and D2 = a.a rounded three times more, D2 is within (1 + u)^5 - 1
 * <= 5.01u of |p - c|^2 (u = 2^-53; all terms positive), so |p - c| - R = (|p - c|^2 -
 * R^2) / (|p - c| + R) is at most (|D2 - R^2| + 5.02u D2) / ((1 - 3.6u) sqrt(D2) + R) in
 * magnitude (R^2 is exact in double). 5.5u and 8u are taken; (1 + 2^-40) covers the
 * roundings of the quotient itself; the result is rounded up to float. */
static inline vd DFN(sphere_err)(const DFN(geo) *g, const vd p[3])
{
    vd a[3];
    for (int k = 0; k < 3; k++)
        a[k] = dsub(p[k], g->c[k]);
    const vd D2 = DFN(dot3)(a, a);
    const vd num = dadd(dabs(dsub(D2, dmul(g->R, g->R))), dmul(dset1(0x1.6p-51), D2));
    const vd den = dadd(dmul(dsqrt(D2), dset1(1 - 0x1p-50)), g->R);
    return dmul(ddiv(num, den), dset1(1 + 0x1p-40));
}

/* The nearest point of a cone's part to the point at axial coordinate z and distance
 * rho from the axis, in the half plane through the axis that holds it (the nearest point
 * of a surface of revolution lies in that half plane): the side is the segment from
 * (rlo, -H) to (rhi, H), a disc the segment from its center to its rim. Out: the
 * nearest point's (rho, z). A parameter off by rounding still names a point of the
 * segment (it is clamped), so a distance measured to it is never short. */
static inline void DFN(cone_foot)(const DFN(geo) *g, vd rho, vd z, vdm side, vdm chi, vd *frho,
                                  vd *fz)
{
    const vd zero = dset1(0.0), one = dset1(1.0), two_h = dmul(dset1(2.0), g->H);
    const vd dR = dsub(g->rhi, g->rlo);
    const vd num = dadd(dmul(dsub(rho, g->rlo), dR), dmul(dadd(z, g->H), two_h));
    const vd t = dmin(one, dmax(zero, ddiv(num, dadd(dmul(dR, dR), dmul(two_h, two_h)))));
    const vd Rd = dsel(chi, g->rhi, g->rlo);
    *frho = dsel(side, dadd(g->rlo, dmul(t, dR)), dmin(rho, Rd));
    *fz = dsel(side, dadd(dsub(zero, g->H), dmul(t, two_h)), dsel(chi, g->H, dsub(zero, g->H)));
}

/* A cone's bound: the distance of the float point p from its part, evaluated as in
 * cone_foot. a = p - c, z, rho and the segment's ends are each within about 30u (|a| +
 * R + H) of their exact values (u = 2^-53), far inside env = 2^-44 (|a|_1 + R + H); the
 * distance is 1-Lipschitz in them and measured to a point of the part (cone_foot), so
 * the evaluated distance plus env, with (1 + 2^-40) for its own roundings, bounds it. */
static inline vd DFN(cone_err)(const DFN(geo) *g, const vd p[3], vdm side, vdm chi)
{
    vd a[3], r[3];
    for (int k = 0; k < 3; k++)
        a[k] = dsub(p[k], g->c[k]);
    const vd s = dmul(DFN(dot3)(a, g->v), g->inv_vv);
    for (int k = 0; k < 3; k++)
        r[k] = dsub(a[k], dmul(s, g->v[k]));
    const vd rho = dsqrt(DFN(dot3)(r, r)), z = dmul(s, g->sv);
    vd fr, fz;
    DFN(cone_foot)(g, rho, z, side, chi, &fr, &fz);
    const vd x = dsub(rho, fr), y = dsub(z, fz);
    const vd d = dsqrt(dadd(dmul(x, x), dmul(y, y)));
    const vd env = dmul(dset1(0x1p-44), dadd(dadd(DFN(l1)(a), g->R), g->H));
    return dmul(dadd(d, env), dset1(1 + 0x1p-40));
}

/* THE HIT POINT of the rays o + t d at t on `part` (as doubles of its low bits): the
 * point p (doubles of floats) and the bound err (likewise). */
CYLRAY_INLINE void DFN(hit_point)(const DFN(geo) *g, const vd o[3], const vd d[3], vd t,
                                  vd part, const vd *nk, vd back, vd p[3], vd *err)
{
    const vd zero = dset1(0.0), one = dset1(1.0);
    part = dsel(g->sph, dset1(CYLRAY_SIDE), part); /* a sphere has its side only */
    const vdm side = deq(part, dset1(CYLRAY_SIDE)), chi = deq(part, dset1(CYLRAY_CAP_HI));
    const vdm on_cap = dmor(deq(part, dset1(CYLRAY_CAP_LO)), chi);
    vd q[3], r[3];
    for (int k = 0; k < 3; k++) /* t d_k is exact */
        q[k] = dsub(dadd(o[k], dmul(t, d[k])), g->c[k]);
    if (nk) {
        /* The kernel's normal nk of a side hit (or NULL). Where float t or the
         * coordinates cannot place the hit (ulp(t)|d| not small against R), o + t d may
         * lie far around the tube from the hit the kernel found, whose normal is
         * accurate: the point is then taken at the kernel's azimuth, q = (q.v / v.v) v +
         * R n. The analysis holds for any q, and the normal at the point agrees with the
         * kernel's. The sign of n: the outward one (the BACKFACE bit against d where d.n
         * is clear of zero, else the side of q), so a face-forwarded normal serves too. */
        const vd s0 = dmul(DFN(dot3)(q, g->v), g->inv_vv);
        const vd sn = dmul(DFN(dot3)(nk, g->v), g->inv_vv);
        vd rn[3], qr[3];
        for (int k = 0; k < 3; k++) {
            rn[k] = dsub(nk[k], dmul(sn, g->v[k]));
            qr[k] = dsub(q[k], dmul(s0, g->v[k]));
        }
        const vd rl = dsqrt(DFN(dot3)(rn, rn)), nl = dsqrt(DFN(dot3)(nk, nk));
        const vd dn = DFN(dot3)(d, nk);
        /* not a side normal (or not finite): q stays */
        const vdm valid =
            dmand(dmand(side, dgt(rl, dmul(dset1(0x1p-10), nl))), dlt(rl, dset1(INFINITY)));
        const vdm clear = dgt(dabs(dn), dmul(dmul(dset1(0x1p-7), dsqrt(DFN(dot3)(d, d))), nl));
        const vdm dpos = dgt(dn, zero), bk = dgt(back, zero);
        const vdm flip = dmor(dmand(clear, dmor(dmandn(dpos, bk), dmandn(bk, dpos))),
                              dmandn(dlt(DFN(dot3)(rn, qr), zero), clear));
        /* a cone's radius at the kernel's axial coordinate */
        const vd Rn = g->any_cone ? dsel(g->cone, DFN(cone_r)(g, s0), g->R) : g->R;
        const vd gn = ddiv(dsel(flip, dsub(zero, Rn), Rn), rl);
        for (int k = 0; k < 3; k++)
            q[k] = dsel(valid, dadd(dmul(s0, g->v[k]), dmul(gn, rn[k])), q[k]);
    }
    vd s = dmul(DFN(dot3)(q, g->v), g->inv_vv);
    const vd s0q = s;
    for (int k = 0; k < 3; k++)
        r[k] = dsub(q[k], dmul(s, g->v[k]));
    const vd qn = DFN(l1)(q); /* |q|_1 >= |q|: the bound's terms in |q| stay bounds */
    vd L = dsqrt(DFN(dot3)(r, r));
    /* a side point on the axis: any radial direction serves; a cap point there stays
     * there (r = 0), the disc's center */
    const vdm on_axis = dmandn(dmnot(dgt(L, zero)), on_cap);
    for (int k = 0; k < 3; k++)
        r[k] = dsel(on_axis, g->praw[k], r[k]);
    L = dsel(on_axis, g->Lp, L);
    const vd inv_L = dsel(dgt(L, zero), ddiv(one, L), zero);
    /* cap: onto the plane, and into the disc; side: onto the radius, within the ends */
    const vd s_cap = dsel(chi, g->hs, dsub(zero, g->hs));
    const vd gain_cap = dsel(dgt(L, g->R), dmul(g->R, inv_L), one);
    const vd nhs = dsub(zero, g->hs);
    const vd s_side = dsel(dlt(s, nhs), nhs, dsel(dgt(s, g->hs), g->hs, s));
    const vd rho = dsel(on_axis, zero, L);
    s = dsel(on_cap, s_cap, s_side);
    vd gain = dsel(on_cap, gain_cap, dmul(g->R, inv_L));
    if (g->any_cone) {
        /* a cone: to the nearest point of its part in p's half plane (the side's foot
         * of the perpendicular, which pays where the side is steep and where it is flat
         * alike) */
        vd fr, fz;
        DFN(cone_foot)(g, rho, dmul(s0q, g->sv), side, chi, &fr, &fz);
        s = dsel(g->cone, dmul(fz, g->inv_sv), s);
        gain = dsel(g->cone, dmul(fr, inv_L), gain);
    }
    const vd rad = dsel(on_cap, dmul(L, gain_cap), g->R);
    vd Pd[3];
    for (int k = 0; k < 3; k++) {
        Pd[k] = dadd(g->c[k], dadd(dmul(s, g->v[k]), dmul(gain, r[k])));
        p[k] = dround_f(Pd[k]);
    }
    const vd Pn = DFN(l1)(Pd);
    const vd side_gain = dsel(side, gain, zero);
    const vd a = dmul(dmul(dset1(0x1p-49), qn), inv_L);
    const vd env = dadd(
        dmul(dmul(dset1(0x1p-47), dadd(dadd(dadd(g->R, g->Hf), qn), Pn)), dadd(one, side_gain)),
        dsel(side, dmul(dmul(g->R, a), a), zero));

    /* e = P - P' exactly (Sterbenz); n, the normal at P' up to its sign (|e.n| alone
     * is read): a disc's is +-nv */
    vd e[3], n[3];
    for (int k = 0; k < 3; k++) {
        e[k] = dsub(p[k], Pd[k]);
        n[k] = dsel(side, dmul(r[k], inv_L), g->nv[k]);
    }
    const vd en = dabs(DFN(dot3)(e, n)), ee = DFN(dot3)(e, e), el = dsqrt(ee);
    const vd z = dmul(dabs(s), g->sv);
    const vdm c_side =
        dmand(side, dmand(dle(el, dmul(dset1(0.5), g->R)), dle(dadd(z, el), g->H)));
    const vdm c_cap = dmandn(dle(dadd(rad, el), g->R), side);
    const vd dist = dsel(c_side, dadd(en, dmul(ee, g->inv_R)), dsel(c_cap, en, el));
    /* (1 + 2^-40) covers the few roundings of dist itself */
    vd bound = dmul(dadd(dist, dmul(dset1(3.0), env)), dset1(1 + 0x1p-40));
    if (g->any_sph) /* a sphere's point is measured against it directly */
        bound = dsel(g->sph, DFN(sphere_err)(g, p), bound);
    if (g->any_cone) /* so is a cone's, against its part */
        bound = dsel(g->cone, DFN(cone_err)(g, p, side, chi), bound);
    /* rounded up: bound >= 0, so the float above f is one spacing up */
    const vd f = dround_f(bound);
    const vdm push = dlt(f, bound);
    *err = dsel(push, dadd(f, DFN(ulp_float)(f)), f);
}
