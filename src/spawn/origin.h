/* SPDX-License-Identifier: MIT */
/* spawn/origin.h - the spawned origin */

/* One surface to clear: p's signed distance sigma, its margin m at p, the sign of the
 * move along its outward normal, how far p lies on its wrong side (base), and the lanes
 * that clear it. A surface no lane clears is skipped: it would add zeros only. */
typedef struct DFN(surf) {
    vd sigma, m, sgn, base;
    vdm in, pos;
    int any; /* some lane clears it */
} DFN(surf);

/* How far outside the side to start a ray along w that dips back into it, given the
 * clearance c the plain rule gives and the margin m (twice the kernels' tolerance box
 * b). The side is convex from outside: the ray meets it only when its origin lies
 * nearer than dt = R (1 / cos - 1), the offset at which its line is tangent (cos: of
 * the dip below the tangent plane, in the cross-section), and the distance at which it
 * meets it grows like 1 - sqrt(1 - c / dt), which is convex in c. A kernel may take the
 * origin for one up to b nearer; so near a tangency a clearance of 2b can turn a miss
 * into a hit, and a hit at half the distance into one much nearer. Clear of the tangency
 * (c <= 0.85 dt) a clearance of 3b keeps the nearer hit beyond half the exact one
 * (1 - sqrt(1 - 2u/3) >= (1 - sqrt(1 - u)) / 2 for u <= 0.9); nearer to it, the origin
 * goes out to dt + 2b, where the exact ray and every ray the box admits miss. A cone's
 * side reads as the cylinder with its ruling nv, its normal r and, for R, the radius of
 * curvature of its section across the ruling, r(z) / cos (Meusnier's theorem; cos =
 * cn, the tilt of the normal from the radial direction). */
CYLRAY_INLINE vd DFN(dip_clearance)(const vd R, const vd nv[3], const vd r[3], const vd w[3],
                                    vd c, vd m)
{
    const vd zero = dset1(0.0), one = dset1(1.0);
    const vd wr = DFN(dot3)(r, w), wv = DFN(dot3)(nv, w);
    const vd wp2 = dsub(DFN(dot3)(w, w), dmul(wv, wv));
    /* sin^2 of the dip; a w along the axis (wp2 = 0) runs along the side: no dip */
    const vd s2 = dsel(dgt(wp2, zero), dmin(one, ddiv(dmul(wr, wr), wp2)), zero);
    const vd co = dsqrt(dsub(one, s2));
    const vd dt = ddiv(dmul(R, s2), dmul(dadd(one, co), co)); /* INFINITY at co = 0 */
    const vd ch = dadd(c, dmul(dset1(0.5), m));
    return dsel(dle(ch, dmul(dset1(0.85), dt)), ch, dmax(ch, dadd(dt, m)));
}

/* THE SPAWNED ORIGIN leaving p (doubles of floats, bound err) on `part` in direction
 * w: out, doubles of floats. side: +1 or -1 puts the origin on that side of the part's
 * own surface (+1: where its outward normal points), 0 on w's side; any other surface
 * it must clear is cleared to w's side. */
CYLRAY_INLINE void DFN(spawn)(const DFN(geo) *g, const vd p[3], vd err, vd part, vd side,
                              const vd w[3], vd out[3])
{
    const vd zero = dset1(0.0), one = dset1(1.0);
    part = dsel(g->sph, dset1(CYLRAY_SIDE), part); /* a sphere has its side only */
    vd q[3], r[3];
    for (int k = 0; k < 3; k++)
        q[k] = dsub(p[k], g->c[k]);
    const vd s = dmul(DFN(dot3)(q, g->v), g->inv_vv), z = dmul(s, g->sv);
    for (int k = 0; k < 3; k++)
        r[k] = dsub(q[k], dmul(s, g->v[k]));
    vd rho = dsqrt(DFN(dot3)(r, r));
    const vdm off_axis = dgt(rho, zero);
    const vd ir = ddiv(one, rho);
    for (int k = 0; k < 3; k++)
        r[k] = dsel(off_axis, dmul(r[k], ir), g->pu[k]);
    rho = dsel(off_axis, rho, zero);
    /* A cone's side: radius rz at p's axial coordinate, outward normal nc = (r - kk nv)
     * cn (the gradient of rho - r(z)), its ruling gc = (nv + kk r) cn; a cylinder's lanes
     * keep r and nv. */
    vd nc[3], gc[3], rz = g->R;
    for (int k = 0; k < 3; k++) {
        nc[k] = r[k];
        gc[k] = g->nv[k];
    }
    if (g->any_cone) {
        rz = dsel(g->cone, DFN(cone_r)(g, s), g->R);
        for (int k = 0; k < 3; k++) {
            nc[k] = dsel(g->cone, dmul(dsub(r[k], dmul(g->kk, g->nv[k])), g->cn), r[k]);
            gc[k] = dsel(g->cone, dmul(dadd(g->nv[k], dmul(g->kk, r[k])), g->cn), g->nv[k]);
        }
    }
    const vd e_d = dmul(dset1(0x1p-47), dadd(dadd(DFN(l1)(q), g->R), g->Hf));
    const vd qmax = DFN(max3)(dabs(q[0]), dabs(q[1]), dabs(q[2]));
    const vd pmax = DFN(max3)(dabs(p[0]), dabs(p[1]), dabs(p[2]));
    const vd az = dabs(z);
    /* The kernels' t is a float, held to 4 ulps of the exact one: below 2^-126 that is
     * 4 * 2^-149 whatever the scale, so a surface within 2^-147 |w| of the origin along
     * w may be met at t = 0. That distance (|w|_1 >= |w|) joins each surface's box; for
     * a direction of length 1 it is 1e-44, for one of length FLT_MAX 2^-19. A w that is
     * not finite adds nothing (its ray is nothing to trace). */
    const vd wl = DFN(l1)(w);
    const vd tau = dsel(dlt(wl, dset1(INFINITY)), dmul(dset1(0x1p-147), wl), zero);
    const vd uRt = dadd(g->uR2, tau), uHt = dadd(g->uH2, tau);

    /* the side (outward normal r), then the discs at -H and +H (-nv and nv). The discs'
     * normals being opposite, their 1-norm, their margins and n.w up to its sign are
     * one computation for both (a negation is exact; a zero's sign changes no test and
     * no sum below, whose partial sums start at +0 and so are never -0). */
    DFN(surf) S[3];
    /* a cone's: the distance from its (infinite) side along nc */
    S[0].sigma = g->any_cone ? dsel(g->cone, dmul(dsub(rho, rz), g->cn), dsub(rho, g->R))
                             : dsub(rho, g->R);
    S[1].sigma = dsub(dsub(zero, z), g->H);
    S[2].sigma = dsub(z, g->H);
    const vdm here[3] = {deq(part, dset1(CYLRAY_SIDE)), deq(part, dset1(CYLRAY_CAP_LO)),
                         deq(part, dset1(CYLRAY_CAP_HI))};
    const vdm exists[3] = {deq(zero, zero), dmor(here[1], g->lo), dmor(here[2], g->hi)};
    const vd wv = DFN(dot3)(g->nv, w);
    const vdm wpos[3] = {dgt(DFN(dot3)(nc, w), zero), dlt(wv, zero), dgt(wv, zero)};
    /* the margin at p, for the test of reach; refined below at the origin */
    const vd u2 = dmul(dset1(2.0), DFN(ulp_f)(dmax(qmax, pmax)));
    const vd l1r = DFN(l1)(nc);
    /* a cone's side moves with its half height (the slope) and its tilt moves z too:
     * kk cn (2 ulp(H) + rho tilt) more along nc */
    const vd uRc =
        g->any_cone
            ? dadd(uRt, dmul(dmul(dabs(g->kk), g->cn), dadd(g->uH2, dmul(rho, g->tilt))))
            : uRt;
    S[0].m =
        dmul(dset1(CYLRAY_SPAWN_SAFETY), dadd(dadd(dmul(u2, l1r), dmul(az, g->tilt)), uRc));
    S[1].m = S[2].m =
        dmul(dset1(CYLRAY_SPAWN_SAFETY), dadd(dadd(dmul(u2, g->l1v), dmul(rho, g->tilt)), uHt));
    vd move = zero, count = zero;
    for (int i = 0; i < 3; i++) {
        DFN(surf) *x = &S[i];
        x->in =
            dmand(exists[i], dmor(here[i], dle(dabs(x->sigma), dadd(dadd(err, x->m), e_d))));
        x->any = dmbits(x->in) != 0;
        x->pos = x->in;
        x->sgn = one;
        x->base = zero;
        if (!x->any) /* no lane clears it: it adds nothing below */
            continue;
        /* to w's side; the part's own surface to the side asked for, where one is */
        const vdm chosen = dmand(here[i], dmnot(deq(side, zero)));
        x->pos = dmor(dmand(chosen, dgt(side, zero)), dmandn(wpos[i], chosen));
        x->sgn = dsel(x->pos, one, dset1(-1.0));
        /* max(0, -sign sigma): how far p lies on the wrong side */
        x->base = dmax(zero, dsel(x->pos, dsub(zero, x->sigma), x->sigma));
        move = dadd(move, dsel(x->in, dadd(dadd(x->base, e_d), x->m), zero));
        count = dadd(count, dsel(x->in, one, zero));
    }

    /* Second pass: the margins at the origin, whose coordinates are bounded by those of
     * p plus the first pass's moves, enlarged by 2^-19 to cover the second's growth. */
    const vd grow = dset1(1 + 0x1p-19);
    const vd wmax = dmul(dadd(qmax, move), grow), zmax = dmul(dadd(az, move), grow);
    const vd rmax = dmul(dadd(rho, move), grow), xmax = dmul(dadd(pmax, move), grow);
    const vd rnd = dmul(dset1(CYLRAY_SQRT3), DFN(ulp_f)(xmax));
    const vd v2 = dmul(dset1(2.0), DFN(ulp_f)(dmax(wmax, xmax)));
    const vd rim = dsel(dgt(count, one), rnd, zero);
    vd delta[3] = {zero, zero, zero}, a_side = zero, a_cap = zero;
    /* Outward from the side along a w that dips back into it (the side form only) */
    const vdm dip = dmandn(dmand(S[0].in, S[0].pos), wpos[0]);
    const int ndip = S[0].any && dmbits(dip) != 0;
    const vd m2c = S[1].any | S[2].any
                       ? dmul(dset1(CYLRAY_SPAWN_SAFETY),
                              dadd(dadd(dmul(v2, g->l1v), dmul(rmax, g->tilt)), uHt))
                       : zero;
    for (int i = 0; i < 3; i++) {
        const DFN(surf) *x = &S[i];
        if (!x->any)
            continue;
        const vd uRm =
            g->any_cone
                ? dadd(uRt, dmul(dmul(dabs(g->kk), g->cn), dadd(g->uH2, dmul(rmax, g->tilt))))
                : uRt;
        const vd m = i == 0 ? dmul(dset1(CYLRAY_SPAWN_SAFETY),
                                   dadd(dadd(dmul(v2, l1r), dmul(zmax, g->tilt)), uRm))
                            : m2c;
        vd a = dadd(dadd(dadd(x->base, e_d), m), rim);
        if (i == 0) { /* inward from the side: the rounding's tangential part */
            vd tang = dmul(dmul(dmul(dset1(2.0), rnd), rnd), g->inv_R);
            /* a cone's radius shrinks to 0 at a tip; the tangential part moves the
             * point by rnd at most, whatever the radius */
            if (g->any_cone)
                tang = dsel(g->cone, dmin(dmul(dset1(2.0), rnd), ddiv(dmul(tang, g->R), rz)),
                            tang);
            a = dadd(a, dsel(x->pos, zero, tang));
        }
        if (i == 0 && ndip) {
            const vd Rc = g->any_cone ? dsel(g->cone, ddiv(rz, g->cn), g->R) : g->R;
            a = dsel(
                dip,
                dadd(x->base, DFN(dip_clearance)(Rc, gc, nc, w, dadd(dadd(e_d, m), rim), m)),
                a);
        }
        a = dmul(dmul(a, dset1(1 + 0x1p-20)), x->sgn);
        if (i == 0) {
            /* r may be NaN where p is not finite: the lanes left out add +0 */
            for (int k = 0; k < 3; k++)
                delta[k] = dadd(delta[k], dsel(x->in, dmul(a, nc[k]), zero));
            a_side = dsel(x->in, a, zero);
        } else {
            /* along nv, finite: the lanes left out add a zero */
            a = dsel(x->in, i == 1 ? dsub(zero, a) : a, zero);
            for (int k = 0; k < 3; k++)
                delta[k] = dadd(delta[k], dmul(a, g->nv[k]));
            a_cap = dadd(a_cap, a);
        }
    }
    /* A cone's rim: its side's normal is not perpendicular to the disc's (nc.nv = -kk
     * cn), so the sum of the moves would shorten each along the other's normal (at a
     * sharp rim cancel them). The move alpha nc + beta nv meets both exactly: alpha +
     * beta c = a_side, alpha c + beta = a_cap, with 1 - c^2 = cn^2. */
    if (g->any_cone && S[0].any && (S[1].any | S[2].any)) {
        const vdm both = dmand(g->cone, dmand(S[0].in, dmor(S[1].in, S[2].in)));
        const vd c = dsub(zero, dmul(g->kk, g->cn)), den = dmul(g->cn, g->cn);
        const vd al = ddiv(dsub(a_side, dmul(c, a_cap)), den);
        const vd be = ddiv(dsub(a_cap, dmul(c, a_side)), den);
        for (int k = 0; k < 3; k++)
            delta[k] = dsel(both, dadd(dmul(al, nc[k]), dmul(be, g->nv[k])), delta[k]);
    }
    for (int k = 0; k < 3; k++) {
        const vd f = dround_f(dadd(p[k], delta[k])), moved = dsub(f, p[k]);
        /* never short of the move: the next float beyond, when rounding fell back */
        const vdm up = dmand(dgt(delta[k], zero), dlt(moved, delta[k]));
        const vdm down = dmand(dlt(delta[k], zero), dgt(moved, delta[k]));
        const vdm push = dmor(up, down);
        out[k] = dsel(push, DFN(next_f)(f, up), f);
    }
}
