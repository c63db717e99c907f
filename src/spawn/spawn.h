/* SPDX-License-Identifier: MIT */
/* spawn/spawn.h - secondary rays, written once against the double-vector vocabulary
 * (simd/f64_*.h) and compiled per ISA and width: the hit point with its bound, and the
 * spawned origin. spawn.c holds the derivation of every step; this is its one
 * implementation, the scalar entry points being its one-lane instance.
 *
 * Every operation is an IEEE double operation in a fixed order, with no fused
 * multiply-add (the vocabulary has none, and the build turns contraction off), so the
 * answers are the same bit for bit on every ISA and width. Where a branch of the
 * derivation depends on a lane, both sides are computed and a select keeps one; a
 * surface that does not take part contributes through a select, never through a
 * product with zero (its margin may be infinite). The roundings to float the analysis
 * relies on are explicit conversions (dround_f), which no optimiser may drop.
 *
 * Parameters: the vocabulary (DW lanes) and DFN(name), the instance's name. */

#ifndef CYLRAY_SPAWN_TMPL_ONCE_
#define CYLRAY_SPAWN_TMPL_ONCE_
#define CYLRAY_SPAWN_SAFETY 2.0 /* spawn.c says why */
#define CYLRAY_SQRT3 1.7320508075688774
#endif

/* One cylinder per lane, and what the derivation reads of it. */
typedef struct DFN(geo) {
    vd c[3], v[3];
    vd sv, inv_vv, inv_sv; /* |v|, 1/(v.v), 1/|v| */
    vd R, inv_R, Hf, hs;   /* Hf: H, 0 when infinite; hs = H/|v| (INFINITY: infinite) */
    vd H;                  /* INFINITY: infinite */
    vd tilt, uR2, uH2;     /* 2 sqrt(3) ulp(max|v_k|)/|v|, 2 ulp(R), 2 ulp(H) */
    vd praw[3], Lp;        /* a vector perpendicular to v, and its length */
    vd pu[3];              /* the same, of unit length */
    vdm lo, hi;            /* the discs that are part of the surface */
} DFN(geo);

/* The spacing of floats at |x| or above it (never less): the exponent of x rounded to
 * float, which can only round up into the next binade; 2^-149 below FLT_MIN. */
static inline vd DFN(ulp_f)(vd x)
{
    return dmax(dmul(dexpo(dround_f(dabs(x))), dset1(0x1p-23)), dset1(0x1p-149));
}

/* The float next to the float f, above it where up is set, below it elsewhere: one
 * spacing away from zero, half of one toward zero from a power of two above FLT_MIN. */
static inline vd DFN(next_f)(vd f, vdm up)
{
    const vd u = DFN(ulp_f)(f), af = dabs(f);
    const vdm toward0 = dmor(dmand(up, dlt(f, dset1(0.0))),
                             dmandn(dgt(f, dset1(0.0)), up));
    const vdm half = dmand(toward0, dmand(deq(af, dmul(u, dset1(0x1p23))),
                                          dgt(af, dset1(0x1p-126))));
    const vd step = dsel(half, dmul(u, dset1(0.5)), u);
    return dsel(up, dadd(f, step), dsub(f, step));
}

static inline vd DFN(max3)(vd a, vd b, vd c)
{
    return dmax(a, dmax(b, c));
}

static inline vd DFN(dot3)(const vd a[3], const vd b[3])
{
    return dadd(dadd(dmul(a[0], b[0]), dmul(a[1], b[1])), dmul(a[2], b[2]));
}

static inline vd DFN(l1)(const vd a[3])
{
    return dadd(dadd(dabs(a[0]), dabs(a[1])), dabs(a[2]));
}

/* The cylinders' derived values, from their floats (c, v, R, H and the discs). */
CYLRAY_INLINE void DFN(geo_make)(DFN(geo) *g, const vd c[3], const vd v[3], vd R, vd H,
                                 vdm lo, vdm hi)
{
    const vd one = dset1(1.0), zero = dset1(0.0);
    for (int k = 0; k < 3; k++) {
        g->c[k] = c[k];
        g->v[k] = v[k];
    }
    const vd vv = DFN(dot3)(v, v);
    g->sv = dsqrt(vv);
    g->inv_vv = ddiv(one, vv);
    g->inv_sv = ddiv(one, g->sv);
    g->R = R;
    g->inv_R = ddiv(one, R);
    g->H = H;
    const vdm finite = dlt(H, dset1(INFINITY));
    g->Hf = dsel(finite, H, zero);
    g->hs = dmul(H, g->inv_sv);
    g->lo = dmand(lo, finite);
    g->hi = dmand(hi, finite);
    const vd a0 = dabs(v[0]), a1 = dabs(v[1]), a2 = dabs(v[2]);
    g->tilt = dmul(dmul(dset1(2 * CYLRAY_SQRT3), DFN(ulp_f)(DFN(max3)(a0, a1, a2))),
                   g->inv_sv);
    g->uR2 = dmul(dset1(2.0), DFN(ulp_f)(R));
    g->uH2 = dmul(dset1(2.0), DFN(ulp_f)(H));
    /* v x e_k, with e_k the coordinate axis along which v is shortest (ties: the first
     * of the shortest), for points on the axis itself */
    const vdm k0 = dmand(dle(a0, a1), dle(a0, a2));
    const vdm k1 = dmand(dmnot(dle(a0, a1)), dle(a1, a2));
    const vdm k2 = dmnot(dmor(k0, k1));
    const vd e0 = dsel(k0, one, zero), e1 = dsel(k1, one, zero), e2 = dsel(k2, one, zero);
    g->praw[0] = dsub(dmul(v[1], e2), dmul(v[2], e1));
    g->praw[1] = dsub(dmul(v[2], e0), dmul(v[0], e2));
    g->praw[2] = dsub(dmul(v[0], e1), dmul(v[1], e0));
    g->Lp = dsqrt(DFN(dot3)(g->praw, g->praw));
    const vd il = ddiv(one, g->Lp);
    for (int k = 0; k < 3; k++)
        g->pu[k] = dmul(g->praw[k], il);
}

/* A prepared cylinder in every lane. */
static inline void DFN(geo_prepared)(DFN(geo) *g, const cylray_prepared *P)
{
    vd c[3], v[3];
    for (int k = 0; k < 3; k++) {
        c[k] = dset1((double)P->c[k]);
        v[k] = dset1((double)P->v[k]);
    }
    const vd yes = dset1(1.0), zero = dset1(0.0);
    DFN(geo_make)(g, c, v, dset1((double)P->radius), dset1((double)P->half_height),
                  dgt(dset1((P->caps & CYLRAY_CAPPED_LO) ? 1.0 : 0.0), zero),
                  dgt(dset1((P->caps & CYLRAY_CAPPED_HI) ? 1.0 : 0.0), zero));
    (void)yes;
}

/* THE HIT POINT of the rays o + t d at t on `part` (as doubles of its low bits): the
 * point p (doubles of floats) and the bound err (likewise). */
CYLRAY_INLINE void DFN(hit_point)(const DFN(geo) *g, const vd o[3], const vd d[3], vd t,
                                  vd part, const vd *nk, vd back, vd p[3], vd *err)
{
    const vd zero = dset1(0.0), one = dset1(1.0);
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
        const vdm valid = dmand(dmand(side, dgt(rl, dmul(dset1(0x1p-10), nl))),
                                dlt(rl, dset1(INFINITY)));
        const vdm clear = dgt(dabs(dn), dmul(dmul(dset1(0x1p-7), dsqrt(DFN(dot3)(d, d))), nl));
        const vdm dpos = dgt(dn, zero), bk = dgt(back, zero);
        const vdm flip = dmor(dmand(clear, dmor(dmandn(dpos, bk), dmandn(bk, dpos))),
                              dmandn(dlt(DFN(dot3)(rn, qr), zero), clear));
        const vd gn = ddiv(dsel(flip, dsub(zero, g->R), g->R), rl);
        for (int k = 0; k < 3; k++)
            q[k] = dsel(valid, dadd(dmul(s0, g->v[k]), dmul(gn, rn[k])), q[k]);
    }
    vd s = dmul(DFN(dot3)(q, g->v), g->inv_vv);
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
    s = dsel(on_cap, s_cap, s_side);
    const vd gain = dsel(on_cap, gain_cap, dmul(g->R, inv_L));
    const vd rad = dsel(on_cap, dmul(L, gain_cap), g->R);
    vd Pd[3];
    for (int k = 0; k < 3; k++) {
        Pd[k] = dadd(g->c[k], dadd(dmul(s, g->v[k]), dmul(gain, r[k])));
        p[k] = dround_f(Pd[k]);
    }
    const vd Pn = DFN(l1)(Pd);
    const vd side_gain = dsel(side, gain, zero);
    const vd a = dmul(dmul(dset1(0x1p-49), qn), inv_L);
    const vd env = dadd(dmul(dmul(dset1(0x1p-47), dadd(dadd(dadd(g->R, g->Hf), qn), Pn)),
                             dadd(one, side_gain)),
                        dsel(side, dmul(dmul(g->R, a), a), zero));

    /* e = P - P' exactly (Sterbenz); n, the normal at P' */
    vd e[3], n[3];
    for (int k = 0; k < 3; k++) {
        e[k] = dsub(p[k], Pd[k]);
        n[k] = dsel(side, dmul(r[k], inv_L),
                    dmul(dsel(chi, g->v[k], dsub(zero, g->v[k])), g->inv_sv));
    }
    const vd en = dabs(DFN(dot3)(e, n)), ee = DFN(dot3)(e, e), el = dsqrt(ee);
    const vd z = dmul(dabs(s), g->sv);
    const vdm c_side = dmand(side, dmand(dle(el, dmul(dset1(0.5), g->R)),
                                         dle(dadd(z, el), g->H)));
    const vdm c_cap = dmandn(dle(dadd(rad, el), g->R), side);
    const vd dist = dsel(c_side, dadd(en, dmul(ee, g->inv_R)), dsel(c_cap, en, el));
    /* (1 + 2^-40) covers the few roundings of dist itself */
    const vd bound = dmul(dadd(dist, dmul(dset1(3.0), env)), dset1(1 + 0x1p-40));
    const vd f = dround_f(bound);
    const vdm push = dlt(f, bound);
    *err = dmbits(push) ? dsel(push, DFN(next_f)(f, dgt(one, zero)), f) : f;
}

/* One surface to clear: its outward normal n, p's signed distance sigma, l1 = |n|_1,
 * the sign of the move along n, how far p lies on its wrong side (base), and the lanes
 * that clear it. A surface no lane clears is skipped: it would add zeros only. */
typedef struct DFN(surf) {
    vd n[3], sigma, l1, sgn, base;
    vdm in, pos;
    int any; /* some lane clears it */
} DFN(surf);

/* THE SPAWNED ORIGIN leaving p (doubles of floats, bound err) on `part` in direction
 * w: out, doubles of floats. side: +1 or -1 puts the origin on that side of the part's
 * own surface (+1: where its outward normal points), 0 on w's side; any other surface
 * it must clear is cleared to w's side. */
CYLRAY_INLINE void DFN(spawn)(const DFN(geo) *g, const vd p[3], vd err, vd part,
                              vd side, const vd w[3], vd out[3])
{
    const vd zero = dset1(0.0), one = dset1(1.0);
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
    const vd e_d = dmul(dset1(0x1p-47), dadd(dadd(DFN(l1)(q), g->R), g->Hf));
    const vd qmax = DFN(max3)(dabs(q[0]), dabs(q[1]), dabs(q[2]));
    const vd pmax = DFN(max3)(dabs(p[0]), dabs(p[1]), dabs(p[2]));
    const vd az = dabs(z);

    /* the side, then the discs at -H and +H */
    DFN(surf) S[3];
    for (int k = 0; k < 3; k++) {
        S[0].n[k] = r[k];
        S[2].n[k] = dmul(g->v[k], g->inv_sv);
        S[1].n[k] = dsub(zero, S[2].n[k]);
    }
    S[0].sigma = dsub(rho, g->R);
    S[1].sigma = dsub(dsub(zero, z), g->H);
    S[2].sigma = dsub(z, g->H);
    const vdm here[3] = {deq(part, dset1(CYLRAY_SIDE)), deq(part, dset1(CYLRAY_CAP_LO)),
                         deq(part, dset1(CYLRAY_CAP_HI))};
    const vdm exists[3] = {deq(zero, zero), dmor(here[1], g->lo), dmor(here[2], g->hi)};
    /* the margin at p, for the test of reach; refined below at the origin */
    const vd u2 = dmul(dset1(2.0), DFN(ulp_f)(dmax(qmax, pmax)));
    vd move = zero, count = zero;
    for (int i = 0; i < 3; i++) {
        DFN(surf) *x = &S[i];
        x->l1 = DFN(l1)(x->n);
        const vd m = dmul(dset1(CYLRAY_SPAWN_SAFETY),
                          dadd(dadd(dmul(u2, x->l1), dmul(i == 0 ? az : rho, g->tilt)),
                               i == 0 ? g->uR2 : g->uH2));
        x->in = dmand(exists[i],
                      dmor(here[i], dle(dabs(x->sigma), dadd(dadd(err, m), e_d))));
        x->any = dmbits(x->in) != 0;
        x->pos = x->in;
        x->sgn = one;
        x->base = zero;
        if (!x->any) /* no lane clears it: it adds nothing below */
            continue;
        /* to w's side; the part's own surface to the side asked for, where one is */
        const vdm chosen = dmand(here[i], dmnot(deq(side, zero)));
        x->pos = dmor(dmand(chosen, dgt(side, zero)),
                      dmandn(dgt(DFN(dot3)(x->n, w), zero), chosen));
        x->sgn = dsel(x->pos, one, dset1(-1.0));
        /* max(0, -sign sigma): how far p lies on the wrong side */
        x->base = dmax(zero, dsel(x->pos, dsub(zero, x->sigma), x->sigma));
        move = dadd(move, dsel(x->in, dadd(dadd(x->base, e_d), m), zero));
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
    vd delta[3] = {zero, zero, zero};
    for (int i = 0; i < 3; i++) {
        const DFN(surf) *x = &S[i];
        if (!x->any)
            continue;
        const vd m = dmul(dset1(CYLRAY_SPAWN_SAFETY),
                          dadd(dadd(dmul(v2, x->l1), dmul(i == 0 ? zmax : rmax, g->tilt)),
                               i == 0 ? g->uR2 : g->uH2));
        vd a = dadd(dadd(dadd(x->base, e_d), m), rim);
        if (i == 0) /* inward from the side: the rounding's tangential part */
            a = dadd(a, dsel(x->pos, zero, dmul(dmul(dmul(dset1(2.0), rnd), rnd), g->inv_R)));
        a = dmul(dmul(a, dset1(1 + 0x1p-20)), x->sgn);
        for (int k = 0; k < 3; k++)
            delta[k] = dadd(delta[k], dsel(x->in, dmul(a, x->n[k]), zero));
    }
    for (int k = 0; k < 3; k++) {
        const vd f = dround_f(dadd(p[k], delta[k])), moved = dsub(f, p[k]);
        /* never short of the move: the next float beyond, when rounding fell back */
        const vdm up = dmand(dgt(delta[k], zero), dlt(moved, delta[k]));
        const vdm down = dmand(dlt(delta[k], zero), dgt(moved, delta[k]));
        const vdm push = dmor(up, down);
        out[k] = dmbits(push) ? dsel(push, DFN(next_f)(f, up), f) : f;
    }
}

/* ---- lanes in memory ---------------------------------------------------------- */

/* Lane i of x to p[i] where bit i of bits is set. */
static inline void DFN(store)(float *p, vd x, uint32_t bits)
{
    if (bits == DFULL) {
        dstoreu_f(p, x);
        return;
    }
    float tmp[DW];
    dstoreu_f(tmp, x);
    for (int i = 0; i < DW; i++)
        if (bits >> i & 1u)
            p[i] = tmp[i];
}

/* Hit points of DW rays whose fields start at the given pointers (o, d: 3 each, t, then
 * the kernel's normal or NULLs); out: x, y, z, err (err may be NULL). */
CYLRAY_INLINE void DFN(hp_lanes)(const DFN(geo) *g, const float *const in[10],
                                 const int32_t *part, float *const out[4], uint32_t bits)
{
    vd o[3], d[3], p[3], err, n[3];
    for (int k = 0; k < 3; k++) {
        o[k] = dloadu_f(in[k]);
        d[k] = dloadu_f(in[3 + k]);
        n[k] = in[7] ? dloadu_f(in[7 + k]) : dset1(0.0);
    }
    DFN(hit_point)(g, o, d, dloadu_f(in[6]), dload_bits(part, CYLRAY_PART_MASK),
                   in[7] ? n : NULL, dload_bits(part, CYLRAY_BACKFACE), p, &err);
    for (int k = 0; k < 3; k++)
        DFN(store)(out[k], p[k], bits);
    if (out[3])
        DFN(store)(out[3], err, bits);
}

/* Origins of DW points (x, y, z, err: err may be NULL for 0) with directions w, and the
 * side asked for (+1, -1; NULL: w's side). */
CYLRAY_INLINE void DFN(sp_lanes)(const DFN(geo) *g, const float *const in[10],
                                 const int32_t *part, float *const out[3], uint32_t bits)
{
    vd p[3], w[3], x[3];
    for (int k = 0; k < 3; k++) {
        p[k] = dloadu_f(in[k]);
        w[k] = dloadu_f(in[4 + k]);
    }
    const vd err = in[3] ? dloadu_f(in[3]) : dset1(0.0);
    DFN(spawn)(g, p, err, dload_bits(part, CYLRAY_PART_MASK),
               in[7] ? dloadu_f(in[7]) : dset1(0.0), w, x);
    for (int k = 0; k < 3; k++)
        DFN(store)(out[k], x[k], bits);
}

/* Fewer than DW lanes (a stream's tail): through buffers padded with the first lane. */
CYLRAY_MAYBE_UNUSED static void DFN(tail)(void (*fn)(const DFN(geo) *, const float *const[10], const int32_t *,
                                 float *const[], uint32_t),
                      const DFN(geo) *g, const float *const in[10], const int32_t *part,
                      float *const *out, size_t nout, size_t cnt, uint32_t bits)
{
    float ib[10][DW], ob[4][DW];
    int32_t pb[DW];
    const float *ip[10];
    float *op[4];
    for (int f = 0; f < 10; f++) {
        ip[f] = in[f] ? ib[f] : NULL;
        for (size_t i = 0; i < DW && in[f]; i++)
            ib[f][i] = in[f][i < cnt ? i : 0];
    }
    for (size_t i = 0; i < DW; i++)
        pb[i] = part[i < cnt ? i : 0];
    for (size_t f = 0; f < 4; f++)
        op[f] = f < nout && out[f] ? ob[f] : NULL;
    fn(g, ip, pb, op, bits);
    for (size_t f = 0; f < nout; f++)
        for (size_t i = 0; i < cnt && out[f]; i++)
            if (bits >> i & 1u)
                out[f][i] = ob[f][i];
}

CYLRAY_MAYBE_UNUSED static void DFN(hp_fn)(const DFN(geo) *g, const float *const in[10], const int32_t *part,
                       float *const out[], uint32_t bits)
{
    DFN(hp_lanes)(g, in, part, out, bits);
}

CYLRAY_MAYBE_UNUSED static void DFN(sp_fn)(const DFN(geo) *g, const float *const in[10], const int32_t *part,
                       float *const out[], uint32_t bits)
{
    DFN(sp_lanes)(g, in, part, out, bits);
}

/* ---- the batched forms ---------------------------------------------------------- */

/* Packets of n lanes (a multiple of DW): ray and hit as n-lane field arrays; normals:
 * the hit's nx, ny, nz are the kernel's normals (the normal forms). */
CYLRAY_MAYBE_UNUSED static void DFN(hit_points_packet)(const cylray_prepared *P,
                                                       const float *ray, const float *hit,
                                                       size_t n, uint32_t mask, int normals,
                                                       float *pts)
{
    DFN(geo) g;
    DFN(geo_prepared)(&g, P);
    const int32_t *part = (const int32_t *)(const void *)(hit + 4 * n);
    for (size_t b = 0; b < n; b += DW) {
        const uint32_t bits = (mask >> b) & DFULL;
        if (!bits)
            continue;
        const float *const in[10] = {
            ray + b,         ray + n + b,     ray + 2 * n + b,
            ray + 3 * n + b, ray + 4 * n + b, ray + 5 * n + b,
            hit + b,         normals ? hit + n + b : NULL,
            hit + 2 * n + b, hit + 3 * n + b};
        float *const out[4] = {pts + b, pts + n + b, pts + 2 * n + b, pts + 3 * n + b};
        DFN(hp_lanes)(&g, in, part + b, out, bits);
    }
}

/* The sides asked for, as +1 or -1 a lane (bits of a mask, or bytes), for sp_lanes. */
static inline void DFN(sides_bits)(float side[DW], uint32_t outward)
{
    for (int i = 0; i < DW; i++)
        side[i] = outward >> i & 1u ? 1.0f : -1.0f;
}

CYLRAY_MAYBE_UNUSED static void DFN(spawn_rays_packet)(const cylray_prepared *P,
                                                       const float *pts, const float *hit,
                                                       size_t n, uint32_t mask,
                                                       const uint32_t *outward, float *ray)
{
    DFN(geo) g;
    DFN(geo_prepared)(&g, P);
    const int32_t *part = (const int32_t *)(const void *)(hit + 4 * n);
    float side[DW];
    for (size_t b = 0; b < n; b += DW) {
        const uint32_t bits = (mask >> b) & DFULL;
        if (!bits)
            continue;
        if (outward)
            DFN(sides_bits)(side, *outward >> b);
        const float *const in[10] = {pts + b,         pts + n + b,     pts + 2 * n + b,
                                     pts + 3 * n + b, ray + 3 * n + b, ray + 4 * n + b,
                                     ray + 5 * n + b, outward ? side : NULL};
        float *const out[3] = {ray + b, ray + n + b, ray + 2 * n + b};
        DFN(sp_lanes)(&g, in, part + b, out, bits);
        DFN(store)(ray + 6 * n + b, dset1(0.0), bits);
    }
}

/* The lanes of DW parts that are not CYLRAY_MISS. */
static inline uint32_t DFN(hit_bits)(const int32_t *part)
{
    return dmbits(dgt(dload_bits(part, CYLRAY_PART_MASK), dset1(0.0)));
}

CYLRAY_MAYBE_UNUSED static size_t DFN(hit_points_stream)(const cylray_prepared *P,
                                                         const cylray_rays *rays,
                                                         const cylray_hits *hits,
                                                         const cylray_points *pts, size_t n,
                                                         int normals)
{
    DFN(geo) g;
    DFN(geo_prepared)(&g, P);
    size_t count = 0;
    for (size_t b = 0; b < n; b += DW) {
        const float *const in[10] = {rays->ox + b, rays->oy + b, rays->oz + b,
                                     rays->dx + b, rays->dy + b, rays->dz + b,
                                     hits->t + b,  normals ? hits->nx + b : NULL,
                                     normals ? hits->ny + b : NULL,
                                     normals ? hits->nz + b : NULL};
        float *const out[4] = {pts->x + b, pts->y + b, pts->z + b,
                               pts->err ? pts->err + b : NULL};
        if (b + DW > n) {
            uint32_t bits = 0;
            for (size_t i = 0; b + i < n; i++)
                bits |= (uint32_t)((hits->part[b + i] & CYLRAY_PART_MASK) != CYLRAY_MISS) << i;
            if (bits) {
                count += CYLRAY_POPCOUNT(bits);
                DFN(tail)(DFN(hp_fn), &g, in, hits->part + b, out, 4, n - b, bits);
            }
            break;
        }
        const uint32_t bits = DFN(hit_bits)(hits->part + b);
        if (!bits)
            continue;
        count += CYLRAY_POPCOUNT(bits);
        DFN(hp_lanes)(&g, in, hits->part + b, out, bits);
    }
    return count;
}

/* outward: NULL (w's side), or a byte a ray (nonzero: the part's outward side). */
CYLRAY_MAYBE_UNUSED static void DFN(spawn_stream)(const cylray_prepared *P,
                                                  const cylray_points *pts,
                                                  const int32_t *part,
                                                  const uint8_t *outward,
                                                  const cylray_points *dirs,
                                                  const cylray_points *origins, size_t n)
{
    DFN(geo) g;
    DFN(geo_prepared)(&g, P);
    float side[DW];
    for (size_t b = 0; b < n; b += DW) {
        const size_t cnt = n - b < DW ? n - b : DW;
        if (outward)
            for (size_t i = 0; i < DW; i++)
                side[i] = outward[b + (i < cnt ? i : 0)] ? 1.0f : -1.0f;
        const float *const in[10] = {pts->x + b,  pts->y + b,  pts->z + b,
                                     pts->err ? pts->err + b : NULL,
                                     dirs->x + b, dirs->y + b, dirs->z + b,
                                     outward ? side : NULL};
        float *const out[3] = {origins->x + b, origins->y + b, origins->z + b};
        if (cnt < DW) {
            uint32_t bits = 0;
            for (size_t i = 0; i < cnt; i++)
                bits |= (uint32_t)((part[b + i] & CYLRAY_PART_MASK) != CYLRAY_MISS) << i;
            if (bits)
                DFN(tail)(DFN(sp_fn), &g, in, part + b, out, 3, cnt, bits);
            break;
        }
        const uint32_t bits = DFN(hit_bits)(part + b);
        if (bits)
            DFN(sp_lanes)(&g, in, part + b, out, bits);
    }
}

/* Leaves in bulk: hit i of a query of leaf[i] (its geom_ array, m lanes a field). The
 * lanes' cylinders are gathered into vectors; so are the AoS rays and hits. */
CYLRAY_MAYBE_UNUSED static void DFN(leaf_geo)(DFN(geo) *g, const float *const *leaf, const cylray_hit1 *hit,
                          size_t m, size_t cnt)
{
    float f[8][DW], lo[DW], hi[DW];
    static const int fields[8] = {CYLRAY_LF_CX, CYLRAY_LF_CY, CYLRAY_LF_CZ, CYLRAY_LF_VX,
                                  CYLRAY_LF_VY, CYLRAY_LF_VZ, CYLRAY_LF_R,  CYLRAY_LF_H};
    for (size_t i = 0; i < DW; i++) {
        const size_t j = i < cnt ? i : 0;
        const float *geom = leaf[j];
        const size_t lane = hit[j].lane % m;
        for (int k = 0; k < 8; k++)
            f[k][i] = geom[(size_t)fields[k] * m + lane];
        const unsigned caps = cylray_leaf_caps_((const uint32_t *)(const void *)(
                                                    geom + CYLRAY_LF_COUNT * m),
                                                (unsigned)lane);
        lo[i] = caps & CYLRAY_CAPPED_LO ? 1.0f : 0.0f;
        hi[i] = caps & CYLRAY_CAPPED_HI ? 1.0f : 0.0f;
    }
    vd c[3], v[3];
    for (int k = 0; k < 3; k++) {
        c[k] = dloadu_f(f[k]);
        v[k] = dloadu_f(f[3 + k]);
    }
    const vd zero = dset1(0.0);
    DFN(geo_make)(g, c, v, dloadu_f(f[6]), dloadu_f(f[7]), dgt(dloadu_f(lo), zero),
                  dgt(dloadu_f(hi), zero));
}

CYLRAY_MAYBE_UNUSED static void DFN(leaf_hit_points)(const float *const *leaf, size_t m,
                                                     const cylray_ray1 *ray,
                                                     const cylray_hit1 *hit,
                                                     const cylray_points *pts, size_t n,
                                                     int normals)
{
    for (size_t b = 0; b < n; b += DW) {
        const size_t cnt = n - b < DW ? n - b : DW;
        DFN(geo) g;
        DFN(leaf_geo)(&g, leaf + b, hit + b, m, cnt);
        float ib[10][DW], ob[4][DW];
        int32_t pb[DW];
        for (size_t i = 0; i < DW; i++) {
            const size_t j = b + (i < cnt ? i : 0);
            for (int k = 0; k < 3; k++) {
                ib[k][i] = ray[j].o[k];
                ib[3 + k][i] = ray[j].d[k];
                ib[7 + k][i] = hit[j].n[k];
            }
            ib[6][i] = hit[j].t;
            pb[i] = hit[j].part;
        }
        const float *const in[10] = {ib[0], ib[1], ib[2], ib[3], ib[4], ib[5], ib[6],
                                     normals ? ib[7] : NULL, ib[8], ib[9]};
        float *const out[4] = {ob[0], ob[1], ob[2], ob[3]};
        DFN(hp_lanes)(&g, in, pb, out, DFULL);
        for (size_t i = 0; i < cnt; i++) {
            pts->x[b + i] = ob[0][i];
            pts->y[b + i] = ob[1][i];
            pts->z[b + i] = ob[2][i];
            if (pts->err)
                pts->err[b + i] = ob[3][i];
        }
    }
}

CYLRAY_MAYBE_UNUSED static void DFN(leaf_spawn_origins)(const float *const *leaf, size_t m,
                                                        const cylray_hit1 *hit,
                                                        const cylray_points *pts,
                                                        const uint8_t *outward,
                                                        const cylray_points *dirs,
                                                        const cylray_points *origins,
                                                        size_t n)
{
    float side[DW];
    for (size_t b = 0; b < n; b += DW) {
        const size_t cnt = n - b < DW ? n - b : DW;
        DFN(geo) g;
        DFN(leaf_geo)(&g, leaf + b, hit + b, m, cnt);
        if (outward)
            for (size_t i = 0; i < DW; i++)
                side[i] = outward[b + (i < cnt ? i : 0)] ? 1.0f : -1.0f;
        const float *const in[10] = {pts->x + b,  pts->y + b,  pts->z + b,
                                     pts->err ? pts->err + b : NULL,
                                     dirs->x + b, dirs->y + b, dirs->z + b,
                                     outward ? side : NULL};
        float *const out[3] = {origins->x + b, origins->y + b, origins->z + b};
        int32_t pb[DW];
        for (size_t i = 0; i < DW; i++)
            pb[i] = hit[b + (i < cnt ? i : 0)].part;
        if (cnt == DW)
            DFN(sp_lanes)(&g, in, pb, out, DFULL);
        else
            DFN(tail)(DFN(sp_fn), &g, in, pb, out, 3, cnt, (1u << cnt) - 1u);
    }
}

#if DW == 1
/* The scalar entry points: one lane; n, the kernel's normal or NULL; side as in spawn. */
CYLRAY_MAYBE_UNUSED static void DFN(hit_point1)(const DFN(geo) *g, const float o[3],
                                                const float d[3], float t, int32_t part,
                                                const float *n, float p[3], float *err)
{
    const float *const in[10] = {&o[0], &o[1], &o[2], &d[0], &d[1], &d[2], &t,
                                 n ? &n[0] : NULL, n ? &n[1] : NULL, n ? &n[2] : NULL};
    float *const out[4] = {&p[0], &p[1], &p[2], err};
    DFN(hp_lanes)(g, in, &part, out, 1u);
}

CYLRAY_MAYBE_UNUSED static void DFN(spawn1)(const DFN(geo) *g, const float p[3], float err,
                                            int32_t part, int side, const float w[3],
                                            float out[3])
{
    const float sd = (float)side;
    const float *const in[10] = {&p[0], &p[1], &p[2], &err, &w[0], &w[1], &w[2],
                                 side ? &sd : NULL};
    float *const o[3] = {&out[0], &out[1], &out[2]};
    DFN(sp_lanes)(g, in, &part, o, 1u);
}
#endif
