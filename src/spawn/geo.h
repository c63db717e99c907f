/* SPDX-License-Identifier: MIT */
/* spawn/geo.h - one cylinder or sphere per lane (what the derivation reads of it), and
 * the ulp helpers */

/* One cylinder or sphere per lane, and what the derivation reads of it. A sphere is
 * the side of a cylinder with no axis (v = 0, H = 0, no discs): with 1/(v.v), 1/|v|,
 * tilt and nv zero there, its axial coordinate s is 0, r = q, and the side's rules read
 * as the sphere's (docs/secondary-rays.md, "Spheres"). */
typedef struct DFN(geo) {
    vd c[3], v[3];
    vd sv, inv_vv, inv_sv; /* |v|, 1/(v.v), 1/|v| */
    vd R, inv_R, Hf, hs;   /* Hf: H, 0 when infinite; hs = H/|v| (INFINITY: infinite) */
    vd H;                  /* INFINITY: infinite */
    vd tilt, uR2, uH2;     /* 2 sqrt(3) ulp(max|v_k|)/|v|, 2 ulp(R), 2 ulp(H) */
    vd praw[3], Lp;        /* a vector perpendicular to v, and its length */
    vd pu[3];              /* the same, of unit length */
    vd nv[3], l1v;         /* v/|v| (the outward normal of the disc at +H), |v/|v||_1 */
    vdm lo, hi;            /* the discs that are part of the surface */
    vdm sph;               /* the lanes that are spheres */
    int any_sph;           /* some lane is */
    /* A cone's lane: radius ra + kz (s - sa) at the axial parameter s (kz = kap v.v; ra
     * and sa its narrower end's radius and parameter, internal/leaf.h), rlo and rhi at
     * s = -+hs (never below 0), kk = dr/dz per unit length along the axis and cn =
     * 1/sqrt(1 + kk^2); R is then max(rlo, rhi). A cylinder's lane: ra = rlo = rhi = R,
     * sa = kz = kk = 0, cn = 1. */
    vdm cone;
    int any_cone;
    vd ra, sa, kz, rlo, rhi, kk, cn;
} DFN(geo);

/* The spacing of floats at the float f (as a double): its exponent (dexpo drops the
 * sign), 2^-149 below FLT_MIN. */
static inline vd DFN(ulp_float)(vd f)
{
    return dmax(dmul(dexpo(f), dset1(0x1p-23)), dset1(0x1p-149));
}

/* The spacing of floats at |x| or above it (never less): that of x rounded to float,
 * which can only round up into the next binade. */
static inline vd DFN(ulp_f)(vd x)
{
    return DFN(ulp_float)(dround_f(x));
}

/* The float next to the float f, above it where up is set, below it elsewhere: one
 * spacing away from zero, half of one toward zero from a power of two above FLT_MIN
 * (where f equals its exponent: 2^e = 2^23 ulp_f(f) from FLT_MIN up). */
static inline vd DFN(next_f)(vd f, vdm up)
{
    const vd af = dabs(f), ex = dexpo(f), u = DFN(ulp_float)(f);
    const vdm toward0 = dmor(dmand(up, dlt(f, dset1(0.0))), dmandn(dgt(f, dset1(0.0)), up));
    const vdm half = dmand(toward0, dmand(deq(af, ex), dgt(af, dset1(0x1p-126))));
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

/* A cone's radius at the axial parameter s (its lanes'; never below 0). */
static inline vd DFN(cone_r)(const DFN(geo) *g, vd s)
{
    return dmax(dset1(0.0), dadd(g->ra, dmul(g->kz, dsub(s, g->sa))));
}

/* The cylinders' derived values, from their floats (c, v, R, H and the discs); sph: the
 * lanes that are spheres (v = 0, H = 0, no discs); cone: the lanes that are cones, whose
 * R is read as ra (the narrower end's radius) and kap as their slope (as a leaf's rows
 * hold them, cylray_cone_ra_), so that a prepared cone and its leaf lane derive the
 * same values. */
CYLRAY_INLINE void DFN(geo_make)(DFN(geo) *g, const vd c[3], const vd v[3], vd R, vd H, vdm lo,
                                 vdm hi, vdm sph, vdm cone, vd kap)
{
    const vd one = dset1(1.0), zero = dset1(0.0);
    for (int k = 0; k < 3; k++) {
        g->c[k] = c[k];
        g->v[k] = v[k];
    }
    const vd vv = DFN(dot3)(v, v);
    g->sv = dsqrt(vv);
    /* a cone of slope 0 (a leaf's lane with r0 == r1) is the cylinder it prepares as */
    cone = dmandn(cone, deq(kap, zero));
    g->cone = cone;
    g->any_cone = dmbits(cone) != 0;
    g->ra = R;
    g->sa = g->kz = g->kk = dset1(0.0);
    g->cn = one;
    g->rlo = g->rhi = R;
    if (g->any_cone) {
        const vd hs = dmul(H, ddiv(one, g->sv));
        g->kz = dsel(cone, dmul(kap, vv), zero);
        g->kk = dmul(g->kz, ddiv(one, g->sv));
        g->cn = ddiv(one, dsqrt(dadd(one, dmul(g->kk, g->kk))));
        g->sa = dsel(dgt(g->kz, zero), dsub(zero, hs), dsel(dlt(g->kz, zero), hs, zero));
        g->rlo = dsel(cone, DFN(cone_r)(g, dsub(zero, hs)), R);
        g->rhi = dsel(cone, DFN(cone_r)(g, hs), R);
        R = dsel(cone, dmax(g->rlo, g->rhi), R);
    }
    g->sph = sph;
    g->any_sph = dmbits(sph) != 0;
    /* zero for a sphere, whose v is 0: then s = 0, nv = 0, hs = 0 and tilt = 0 */
    g->inv_vv = dsel(sph, zero, ddiv(one, vv));
    g->inv_sv = dsel(sph, zero, ddiv(one, g->sv));
    g->R = R;
    g->inv_R = ddiv(one, R);
    g->H = H;
    const vdm finite = dlt(H, dset1(INFINITY));
    g->Hf = dsel(finite, H, zero);
    g->hs = dmul(H, g->inv_sv);
    g->lo = dmand(lo, finite);
    g->hi = dmand(hi, finite);
    const vd a0 = dabs(v[0]), a1 = dabs(v[1]), a2 = dabs(v[2]);
    for (int k = 0; k < 3; k++)
        g->nv[k] = dmul(v[k], g->inv_sv);
    g->l1v = DFN(l1)(g->nv);
    g->tilt = dmul(dmul(dset1(2 * CYLRAY_SQRT3), DFN(ulp_f)(DFN(max3)(a0, a1, a2))), g->inv_sv);
    g->uR2 = dmul(dset1(2.0), DFN(ulp_f)(R));
    g->uH2 = dmul(dset1(2.0), DFN(ulp_f)(H));
    /* v x e_k, with e_k the coordinate axis along which v is shortest (ties: the first
     * of the shortest), for points on the axis itself; a sphere's center: e_x */
    const vdm k0 = dmand(dle(a0, a1), dle(a0, a2));
    const vdm k1 = dmand(dmnot(dle(a0, a1)), dle(a1, a2));
    const vdm k2 = dmnot(dmor(k0, k1));
    const vd e0 = dsel(k0, one, zero), e1 = dsel(k1, one, zero), e2 = dsel(k2, one, zero);
    g->praw[0] = dsub(dmul(v[1], e2), dmul(v[2], e1));
    g->praw[1] = dsub(dmul(v[2], e0), dmul(v[0], e2));
    g->praw[2] = dsub(dmul(v[0], e1), dmul(v[1], e0));
    g->praw[0] = dsel(sph, one, g->praw[0]);
    g->praw[1] = dsel(sph, zero, g->praw[1]);
    g->praw[2] = dsel(sph, zero, g->praw[2]);
    g->Lp = dsqrt(DFN(dot3)(g->praw, g->praw));
    const vd il = ddiv(one, g->Lp);
    for (int k = 0; k < 3; k++)
        g->pu[k] = dmul(g->praw[k], il);
}

/* A prepared shape in every lane. */
static inline void DFN(geo_prepared)(DFN(geo) *g, const cylray_prepared *P)
{
    const cylray_shape_ s = cylray_shape_of_(P);
    vd c[3], v[3];
    for (int k = 0; k < 3; k++) {
        c[k] = dset1((double)s.c[k]);
        v[k] = dset1((double)s.v[k]);
    }
    const vd zero = dset1(0.0);
    DFN(geo_make)
    (g, c, v, dset1((double)s.r), dset1((double)s.h),
     dgt(dset1((s.caps & CYLRAY_CAPPED_LO) ? 1.0 : 0.0), zero),
     dgt(dset1((s.caps & CYLRAY_CAPPED_HI) ? 1.0 : 0.0), zero),
     dgt(dset1(s.shape == CYLRAY_SHAPE_SPHERE ? 1.0 : 0.0), zero),
     dgt(dset1(s.shape == CYLRAY_SHAPE_CONE ? 1.0 : 0.0), zero), dset1((double)s.kap));
}
