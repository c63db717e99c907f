/* SPDX-License-Identifier: MIT */
/* kernel/shape/round_cone.h - a round cone's own stages (called through kernel/shape.h):
 * its spheres joined to its frustum's solid, the cut of an open end, and the spheres'
 * parts and normals. The side is the frustum's, a cone's or (a capsule's) a
 * cylinder's, run as a capped one's with both discs open: each disc lies within its
 * end's sphere, or at a point end is the tip. */

/* The origin relative to sphere i after the shift: p less the sphere's center from the
 * lane's frame point (the center c, or a slender lane's anchor c + am v), s_i - am along
 * v. The side reads the same p: the seams see one origin. */
CYLRAY_INLINE void KFN(round_w)(const KFN(lanes) *st, const cylray_kat_ *k,
                                const cylray_kflags_ F, int i, vf *wx, vf *wy, vf *wz)
{
    vf si = vset1(i ? k->P->rc_s : -k->P->rc_s);
    if (F.slender)
        si = vsub(si, st->am);
    *wx = vfnma(si, st->vx, st->px);
    *wy = vfnma(si, st->vy, st->py);
    *wz = vfnma(si, st->vz, st->pz);
}

/* One end's half-space z >= zlo (hi = 0) or z <= zhi (hi = 1) on the ray, [*lo, *up],
 * from that plane's crossing t and its offset n = zplane - z0: a ray along the plane
 * (dv = 0) lies wholly in it or wholly out, and one in the plane itself is in. */
CYLRAY_INLINE void KFN(round_half)(const KFN(lanes) *st, int hi, vf n, vf t, vf *lo, vf *up)
{
    const vf zero = vzero(), inf = vset1(INFINITY), ninf = vneg(inf);
    const vm rise = vgt(st->dv, zero), fall = vlt(st->dv, zero);
    const vm enter = hi ? fall : rise, leave = hi ? rise : fall;
    const vm flat = mandn(vle(zero, zero), mor(rise, fall));
    const vm out = mandn(flat, hi ? vge(n, zero) : vle(n, zero));
    *lo = vsel(enter, t, vsel(out, inf, ninf));
    *up = vsel(leave, t, vsel(out, ninf, inf));
}

/* After KFN(ends): the hull's solid is the frustum's joined to the two balls, convex,
 * so on a ray it is one interval, from the first entry to the last exit of the three.
 * A frustum's bound at a disc that a ball covers lies within that ball, whose own
 * entry comes before it and exit after, but at the rim, the seam, where the two meet:
 * there it is a point of the side, and it stays a candidate, so that a ball that
 * rounding misses near its seam leaves no hole. An open end then cuts the hull at its
 * plane, and a bound made by that plane is no hit: the ray passes through the hole. A
 * ball's part is recorded with its bound, for the store. The balls' discriminant is
 * scaled as the frustum's (g_s = 2^-j), so that d.d r^2 stays finite for radii far
 * from 1. */
CYLRAY_INLINE void KFN(round_hull)(KFN(lanes) *st, const cylray_kat_ *k, const cylray_kflags_ F,
                                   vf na, vf nb, vf ta, vf tb, vf slab_in, vf slab_out)
{
    const cylray_prepared *P = k->P;
    const vf zero = vzero(), inf = vset1(INFINITY), ninf = vneg(inf);
    const vm all = vle(zero, zero), none = vlt(zero, zero);
    const vm up = vgt(st->dv, zero);
    const vm ball0 = P->rc_rr[0] > 0 ? all : none, ball1 = P->rc_rr[1] > 0 ? all : none;
    const vm solid = mand(mor(st->side, st->inpar), vle(st->t_in, st->t_out));
    const vm in_disc = vgt(slab_in, st->side_lo), out_disc = vlt(slab_out, st->side_hi);
    const vm in_cov = mand(in_disc, mor(mand(up, ball0), mandn(ball1, up)));
    const vm out_cov = mand(out_disc, mor(mand(up, ball1), mandn(ball0, up)));
    vf tin = vsel(solid, st->t_in, inf), tout = vsel(solid, st->t_out, ninf);
    vm okin = mor(st->ok_in, mand(solid, in_cov)),
       okout = mor(st->ok_out, mand(solid, out_cov));
    vf pin = vset1(CYLRAY_SIDE), pout = pin;
    const vf A = st->dd, dx = st->dx, dy = st->dy, dz = st->dz, gs = vset1(P->g_s);
    for (int i = 0; i < 2; i++) {
        if (!(P->rc_rr[i] > 0))
            continue;
        vf wx, wy, wz;
        KFN(round_w)(st, k, F, i, &wx, &wy, &wz);
        const vf rr = vset1(P->rc_rr[i]), rrs = vmul(vmul(rr, gs), gs);
        const vf hx = vmul(vfms(wy, dz, vmul(wz, dy)), gs),
                 hy = vmul(vfms(wz, dx, vmul(wx, dz)), gs),
                 hz = vmul(vfms(wx, dy, vmul(wy, dx)), gs);
        const vf D = vfms(A, rrs, KDOT(hx, hy, hz, hx, hy, hz));
        const vm has = mand(st->act, vge(D, zero));
        if (!many(has))
            continue;
        const vf nB = vneg(KDOT(wx, wy, wz, dx, dy, dz)), C = vsumsq_x(wx, wy, wz, rr);
        const vf q = vadd(nB, vxorsign(vdiv(vsqrt(D), gs), nB));
        const vf r1 = vdiv(q, A);
        vf r2 = vdiv(C, q);
        r2 = vsel(mor(veq(q, zero), vlt(vmul(q, q), vmul(C, A))), r1, r2);
        const vf a = vmin(r1, r2), b = vmax(r1, r2);
        const vf part = vset1(i ? CYLRAY_CAP_HI : CYLRAY_CAP_LO);
        const vm ein = mand(has, vlt(a, tin)), eout = mand(has, vgt(b, tout));
        tin = vsel(ein, a, tin), okin = mor(okin, ein), pin = vsel(ein, part, pin);
        tout = vsel(eout, b, tout), okout = mor(okout, eout), pout = vsel(eout, part, pout);
    }
    for (int i = 0; i < 2; i++) { /* an open end with a ball: the hull cut at its plane */
        if (!(P->rc_rr[i] > 0) || (P->rc_caps & (i ? CYLRAY_CAPPED_HI : CYLRAY_CAPPED_LO)))
            continue;
        vf lo, hi;
        KFN(round_half)(st, i, i ? nb : na, i ? tb : ta, &lo, &hi);
        const vm cut_in = vgt(lo, tin), cut_out = vlt(hi, tout);
        tin = vmax(tin, lo), okin = mandn(okin, cut_in);
        tout = vmin(tout, hi), okout = mandn(okout, cut_out);
        /* The ball's bound that the cut leaves lies on the frustum's side of the plane,
         * within the frustum but for rounding: a point of the side, as near as the
         * rounding (an open end has no cap). */
        const vf cap = vset1(i ? CYLRAY_CAP_HI : CYLRAY_CAP_LO), side = vset1(CYLRAY_SIDE);
        pin = vsel(veq(pin, cap), side, pin), pout = vsel(veq(pout, cap), side, pout);
    }
    const vm there = mand(vle(tin, tout), mand(vlt(tin, inf), vgt(tout, ninf)));
    st->t_in = tin, st->t_out = tout;
    st->ok_in = mand(okin, there), st->ok_out = mand(okout, there);
    st->round.pin = pin, st->round.pout = pout;
}

/* The planes of the tangent circles, where the frustum ends, in place of -+H|v|. */
CYLRAY_INLINE void KFN(round_planes)(const cylray_kat_ *k, vf *zlo, vf *zhi)
{
    *zlo = vset1(k->P->rc_z[0]), *zhi = vset1(k->P->rc_z[1]);
}

/* The radii of the tangent circles, the frustum's rims. */
CYLRAY_INLINE void KFN(round_rims)(const cylray_kat_ *k, vf *r_lo, vf *r_hi)
{
    *r_lo = vset1(k->P->rc_rim[0]), *r_hi = vset1(k->P->rc_rim[1]);
}

/* The part of a hit lane: the side, or the ball whose bound it is. */
CYLRAY_INLINE vf KFN(round_part)(const KFN(lanes) *st)
{
    return vsel(st->front, st->round.pin, st->round.pout);
}

/* A ball's normal at its hit lanes, (w + t d) / r, over the side's. */
CYLRAY_INLINE void KFN(round_normal)(const KFN(lanes) *st, const cylray_kat_ *k,
                                     const cylray_kflags_ F, vf *nx, vf *ny, vf *nz)
{
    const vf part = KFN(round_part)(st), tr = st->tr;
    for (int i = 0; i < 2; i++) {
        const vm on = mand(st->hit, veq(part, vset1(i ? CYLRAY_CAP_HI : CYLRAY_CAP_LO)));
        if (!many(on))
            continue;
        vf wx, wy, wz;
        KFN(round_w)(st, k, F, i, &wx, &wy, &wz);
        const vf r = vsqrt(vset1(k->P->rc_rr[i]));
        *nx = vsel(on, vdiv(vfma(tr, st->dx, wx), r), *nx);
        *ny = vsel(on, vdiv(vfma(tr, st->dy, wy), r), *ny);
        *nz = vsel(on, vdiv(vfma(tr, st->dz, wz), r), *nz);
    }
}
