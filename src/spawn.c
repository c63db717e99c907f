/* SPDX-License-Identifier: MIT */
/* spawn.c - secondary rays: the hit point moved onto the surface with a bound on its
 * distance to it, and the origin from which a new ray leaves that surface.
 *
 * Everything is evaluated in double from float inputs; docs/secondary-rays.md holds
 * the derivations in full, the comments below their steps.
 *
 * THE HIT POINT. Write u = 2^-53 (double) and q = (o + t d) - c, rounded; the rounding
 * of q only changes which point is projected, never how far the result is from the
 * surface, so the analysis starts at q.
 *   Side. s = (q.v)(1/(v.v)) is off by at most 8u|q|/|v| (a 3-term dot product, the
 *   rounded v.v, its reciprocal, the product), so r = q - s v keeps an axial part
 *   |alpha| <= 12.1u|q| (4.1u|q| more from the subtraction and the product). L = |r|
 *   and g = R (1/L) carry relative errors 2.6u and 4.7u. P' = c + (s v + g r), rounded
 *   three times. The distance of P' from the axis is |g perp(r) + perp(e)| with
 *   |g perp(r)| = g sqrt(L^2 - alpha^2), hence within 4.7u R + R (alpha/L)^2 +
 *   2u(|s v| + R) + u|P'| of R. Clamping s to [-H, H]/|v| (a finite side) adds at most
 *   4.6u H to the axial position.
 *   Cap. P' = c + (+-H/|v|) v + r, with r scaled down to length R when longer: the axial
 *   position is off by at most 4.6u H + 12.1u|q| + 2u(H + R) + u|P'|, the radius by 4.7u R.
 *   Every term is below env = 2^-47 (R + H + |q| + |P'|)(1 + R/L) + R (2^-49 |q|/L)^2
 *   (2^-47 = 64u; the factor R/L from g alpha; H counts only when finite).
 * Then P = fl(P'), and e = P - P' is exact in double (Sterbenz). fl is
 * cylray_round_float_, whose rounding no optimiser can drop (cylray_internal.h). Against the surface
 * point next to P', with the normal n there, the distance from P is at most
 *   |e.n| + |e|^2 / R   (side, |e| <= R/2: the tangential part of e moves the radius
 *                        by |e_t|^2 / (2(R - |e|)) at most),
 *   |e.n|               (cap, the disc's edge more than |e| away),
 *   |e|                 (otherwise, the triangle inequality),
 * plus 3 env (P' itself, and the normal's direction error times |e| <= R). err is that
 * sum rounded up to float.
 *
 * THE SPAWNED ORIGIN. The kernels are held (tests/check) to answer as the exact
 * geometry does for some inputs within 2 ulps of the given ones: the origin relative to
 * the center w = o - c by 2 ulps of its largest component in each component, the axis
 * likewise, the radius and the half height by 2 ulps. A decision the kernel can get
 * wrong is therefore one whose exact answer those perturbations can flip: an origin
 * closer to a surface than
 *   m_side = 2 ulp(X) |n|_1 + |z| tilt + 2 ulp(R),
 *   m_cap  = 2 ulp(X) |n|_1 + rho tilt + 2 ulp(H),   tilt = 2 sqrt(3) ulp(max|v_k|)/|v|,
 * with X = max|w_k| (z, rho: the origin's axial and radial coordinates) may be taken for
 * lying on its other side. The margins m_i used are twice these, with X the larger of
 * max|w_k| and the origin's own max|x_k| (CYLRAY_SPAWN_SAFETY below says why). So the
 * origin is moved along each surface's outward normal n_i, to w's side (sign of
 * dot(w, n_i), inward when 0), by
 *   a_i = max(0, -sign_i sigma_i) + e_d + m_i,
 * sigma_i being p's signed distance from surface i computed in double (off by at most
 * e_d = 2^-47 (|q|_1 + R + H)), for the part hit and for any other surface whose
 * distance from p is within err + m_i (a rim). Each float coordinate of the result is
 * then rounded away from p in the direction of the move (the next-float push of
 * pbrt-v4), so that its move along a single normal is never shortened; with two normals
 * (a rim) the rounding may cost sqrt(3) ulp(max|x_k|) against either, which is added to
 * both. Moving inward from the side, the rounding's tangential part shrinks the radius
 * by |e|^2 / rho at most, which is added as well. The margins grow with the origin's
 * own coordinates, so they are evaluated twice, the second time at the first pass's
 * origin enlarged by 2^-19 of itself, which bounds the second pass's. */
#include "cylray_internal.h"

#include <string.h>

/* The kernels' tolerance box is what the tests hold them to, not a proven bound: one
 * spawned ray in 10^7 (a reflection 0.0015 rad off the tangent plane, its line within
 * 1e-8 R of tangency) was still taken for a hit with the origin at the box's edge. The
 * margins are therefore twice the box, with the origin's rounding counted in ulps of its
 * world coordinates as well as of those relative to the center (the FMA kernels took an
 * origin 2.4e-6 outside a radius-2.2 tube, 2.5 ulps of its coordinate 8, for inside). */
#define CYLRAY_SPAWN_SAFETY 2.0

/* One cylinder's exact geometry, from a prepared cylinder or a leaf lane. */
typedef struct geo {
    double c[3], v[3];
    double vv, sv;   /* v.v (exact but for one rounding) and |v| */
    double inv_vv, inv_sv; /* their reciprocals: multiplications below, not divisions */
    double R, H;     /* H = INFINITY: infinite */
    unsigned caps;   /* CYLRAY_CAPPED_LO | CYLRAY_CAPPED_HI */
} geo;

static void geo_finish(geo *g)
{
    g->vv = g->v[0] * g->v[0] + g->v[1] * g->v[1] + g->v[2] * g->v[2];
    g->sv = sqrt(g->vv);
    g->inv_vv = 1.0 / g->vv;
    g->inv_sv = 1.0 / g->sv;
    if (!isfinite(g->H))
        g->caps = 0;
}

static geo geo_prepared(const cylray_prepared *P)
{
    geo g;
    for (int k = 0; k < 3; k++) {
        g.c[k] = P->c[k];
        g.v[k] = P->v[k];
    }
    g.R = P->radius;
    g.H = P->half_height;
    g.caps = P->caps & CYLRAY_CAPPED;
    geo_finish(&g);
    return g;
}

/* Lane `lane` of a leaf of width m, whose fields are geom[f * m + lane]. */
static geo geo_leaf(const float *geom, const uint32_t *meta, size_t m, size_t lane)
{
    geo g;
    for (int k = 0; k < 3; k++) {
        g.c[k] = geom[(CYLRAY_LF_CX + (size_t)k) * m + lane];
        g.v[k] = geom[(CYLRAY_LF_VX + (size_t)k) * m + lane];
    }
    g.R = geom[CYLRAY_LF_R * m + lane];
    g.H = geom[CYLRAY_LF_H * m + lane];
    g.caps = cylray_leaf_caps_(meta, (unsigned)lane);
    geo_finish(&g);
    return g;
}

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static double norm3(const double a[3])
{
    return sqrt(dot3(a, a));
}

/* The spacing of floats at |x| or above it (never less): the exponent of x rounded to
 * float, which can only round up into the next binade. */
static double ulp_f(double x)
{
    float f = (float)fabs(x);
    uint32_t b;
    memcpy(&b, &f, sizeof b);
    b &= 0x7f800000u;
    if (b == 0)
        return 0x1p-149;
    memcpy(&f, &b, sizeof f);
    return (double)f * 0x1p-23;
}

/* fmax and nextafterf are library calls without -ffast-math; these are not, and the
 * inputs here are never NaN where they are used. */
static inline double dmax(double a, double b)
{
    return a > b ? a : b;
}

static inline double max3(double a, double b, double c)
{
    return dmax(a, dmax(b, c));
}

/* The float next to a finite f, above it for s > 0, below it for s < 0. */
static inline float next_float(float f, int s)
{
    uint32_t b;
    memcpy(&b, &f, sizeof b);
    if (f == 0.0f)
        b = s > 0 ? 1u : 0x80000001u;
    else if ((s > 0) == !(b >> 31))
        b++;
    else
        b--;
    memcpy(&f, &b, sizeof f);
    return f;
}

/* A unit vector perpendicular to v, for a point on the axis itself. */
static void any_perp(const geo *g, double r[3])
{
    const double *v = g->v;
    int k = fabs(v[0]) <= fabs(v[1]) ? (fabs(v[0]) <= fabs(v[2]) ? 0 : 2)
                                     : (fabs(v[1]) <= fabs(v[2]) ? 1 : 2);
    double e[3] = {0, 0, 0};
    e[k] = 1;
    r[0] = v[1] * e[2] - v[2] * e[1];
    r[1] = v[2] * e[0] - v[0] * e[2];
    r[2] = v[0] * e[1] - v[1] * e[0];
}

static void hit_point_geo(const geo *g, const float o[3], const float d[3], float t,
                          int32_t part, float p[3], float *err)
{
    double q[3], r[3], m[3], Pd[3];
    for (int k = 0; k < 3; k++)
        q[k] = ((double)o[k] + (double)t * d[k]) - g->c[k]; /* t d_k is exact */
    const int P = part & CYLRAY_PART_MASK;
    const double Hf = isfinite(g->H) ? g->H : 0;
    double s = dot3(q, g->v) * g->inv_vv;
    for (int k = 0; k < 3; k++)
        r[k] = q[k] - s * g->v[k];
    const int on_cap = P == CYLRAY_CAP_LO || P == CYLRAY_CAP_HI;
    const double qn = norm3(q);
    double L = norm3(r);
    if (!(L > 0) && !on_cap) { /* a side point on the axis: any radial direction serves */
        any_perp(g, r);
        L = norm3(r);
    }
    /* A cap point on the axis stays there (r = 0): it is the disc's center. */
    const double inv_L = L > 0 ? 1.0 / L : 0.0;
    double env, rad, gain;
    if (on_cap) {
        s = (P == CYLRAY_CAP_HI ? g->H : -g->H) * g->inv_sv;
        gain = L > g->R ? g->R * inv_L : 1.0; /* into the disc */
        rad = L * gain;
    } else {
        if (isfinite(g->H))
            {
                const double hs = g->H * g->inv_sv;
                s = s < -hs ? -hs : s > hs ? hs : s;
            }
        gain = g->R * inv_L;
        rad = g->R;
    }
    for (int k = 0; k < 3; k++) {
        m[k] = s * g->v[k] + gain * r[k];
        Pd[k] = g->c[k] + m[k];
        p[k] = cylray_round_float_(Pd[k], 0); /* not (float): e below needs the rounding */
    }
    const double Pn = norm3(Pd), side_gain = P == CYLRAY_SIDE ? gain : 0.0;
    env = 0x1p-47 * (g->R + Hf + qn + Pn) * (1 + side_gain) +
          (P == CYLRAY_SIDE ? g->R * (0x1p-49 * qn * inv_L) * (0x1p-49 * qn * inv_L) : 0.0);

    /* e = P - P' exactly; n, the normal at P' */
    double e[3], n[3];
    for (int k = 0; k < 3; k++) {
        e[k] = (double)p[k] - Pd[k];
        n[k] = P == CYLRAY_SIDE ? r[k] * inv_L
               : (P == CYLRAY_CAP_HI ? g->v[k] : -g->v[k]) * g->inv_sv;
    }
    const double en = fabs(dot3(e, n)), ee = dot3(e, e), el = sqrt(ee);
    const double z = fabs(s) * g->sv;
    double dist;
    if (P == CYLRAY_SIDE && el <= 0.5 * g->R && z + el <= (isfinite(g->H) ? g->H : INFINITY))
        dist = en + ee / g->R;
    else if (P != CYLRAY_SIDE && rad + el <= g->R)
        dist = en;
    else
        dist = el;
    /* (1 + 2^-40) covers the few roundings of dist itself */
    double bound = (dist + 3 * env) * (1 + 0x1p-40);
    float f = cylray_round_float_(bound, 0);
    if ((double)f < bound)
        f = next_float(f, 1);
    *err = f;
}

/* The pieces of one surface to clear: outward normal, p's signed distance, margin. */
typedef struct surf {
    double n[3], sigma, a;
    int sign, side;
} surf;

/* side: +1 or -1 puts the origin on that side of the part's own surface (+1: where
 * its outward normal points), 0 on w's side; any other surface it must clear is
 * cleared to w's side. */
static void spawn_geo(const geo *g, const float p[3], float err, int32_t part, int side,
                      const float w[3], float out[3])
{
    const int P = part & CYLRAY_PART_MASK;
    const double Hf = isfinite(g->H) ? g->H : 0;
    double q[3], r[3];
    for (int k = 0; k < 3; k++)
        q[k] = (double)p[k] - g->c[k];
    const double s = dot3(q, g->v) * g->inv_vv, z = s * g->sv;
    for (int k = 0; k < 3; k++)
        r[k] = q[k] - s * g->v[k];
    double rho = norm3(r);
    if (!(rho > 0)) {
        any_perp(g, r);
        const double il = 1.0 / norm3(r);
        for (int k = 0; k < 3; k++)
            r[k] *= il;
        rho = 0;
    } else {
        const double ir = 1.0 / rho;
        for (int k = 0; k < 3; k++)
            r[k] *= ir;
    }
    const double e_d = 0x1p-47 * (fabs(q[0]) + fabs(q[1]) + fabs(q[2]) + g->R + Hf);
    const double vmax = max3(fabs(g->v[0]), fabs(g->v[1]), fabs(g->v[2]));
    const double tilt = 2 * 1.7320508075688774 * ulp_f(vmax) * g->inv_sv;
    const double qmax = max3(fabs(q[0]), fabs(q[1]), fabs(q[2]));
    const double pmax = max3(fabs((double)p[0]), fabs((double)p[1]), fabs((double)p[2]));

    surf S[3];
    int ns = 0;
    /* the side, and the caps that exist */
    for (int i = 0; i < 3; i++) {
        surf *x = &S[ns];
        int here;
        x->side = i == 0;
        if (i == 0) {
            memcpy(x->n, r, sizeof r);
            x->sigma = rho - g->R;
            here = P == CYLRAY_SIDE;
        } else {
            const double sg = i == 1 ? -1.0 : 1.0; /* CAP_LO, CAP_HI */
            for (int k = 0; k < 3; k++)
                x->n[k] = sg * g->v[k] * g->inv_sv;
            x->sigma = sg * z - g->H;
            here = P == (i == 1 ? CYLRAY_CAP_LO : CYLRAY_CAP_HI);
            if (!here && !(g->caps & (i == 1 ? CYLRAY_CAPPED_LO : CYLRAY_CAPPED_HI)))
                continue;
        }
        const double nl1 = fabs(x->n[0]) + fabs(x->n[1]) + fabs(x->n[2]);
        /* the margin at p, for the test of reach; refined below at the origin */
        double m = CYLRAY_SPAWN_SAFETY * (2 * ulp_f(dmax(qmax, pmax)) * nl1 +
                                          (i == 0 ? fabs(z) : rho) * tilt +
                                          2 * ulp_f(i == 0 ? g->R : g->H));
        if (!here && !(fabs(x->sigma) <= (double)err + m + e_d))
            continue;
        x->sign = here && side ? side
                  : dot3(x->n, (const double[3]){w[0], w[1], w[2]}) > 0 ? 1 : -1;
        x->a = dmax(0.0, -x->sign * x->sigma) + e_d + m;
        ns++;
    }

    /* Second pass: the margins at the origin, whose coordinates are bounded by those of
     * p plus the first pass's moves, enlarged by 2^-19 to cover the second's growth. */
    double move = 0;
    for (int i = 0; i < ns; i++)
        move += S[i].a;
    const double wmax = (qmax + move) * (1 + 0x1p-19);
    const double zmax = (fabs(z) + move) * (1 + 0x1p-19);
    const double rmax = (rho + move) * (1 + 0x1p-19);
    const double xmax = (pmax + move) * (1 + 0x1p-19);
    const double rnd = 1.7320508075688774 * ulp_f(xmax);
    double delta[3] = {0, 0, 0};
    for (int i = 0; i < ns; i++) {
        surf *x = &S[i];
        const int is_side = x->side;
        const double nl1 = fabs(x->n[0]) + fabs(x->n[1]) + fabs(x->n[2]);
        double m = CYLRAY_SPAWN_SAFETY * (2 * ulp_f(dmax(wmax, xmax)) * nl1 +
                                          (is_side ? zmax : rmax) * tilt +
                                          2 * ulp_f(is_side ? g->R : g->H));
        double a = dmax(0.0, -x->sign * x->sigma) + e_d + m;
        if (ns > 1)
            a += rnd;
        if (is_side && x->sign < 0)
            a += 2 * rnd * rnd / g->R;
        a *= 1 + 0x1p-20;
        for (int k = 0; k < 3; k++)
            delta[k] += x->sign * a * x->n[k];
    }
    for (int k = 0; k < 3; k++) {
        float f = cylray_round_float_((double)p[k] + delta[k], 0);
        /* never short of the move: the next float beyond, when rounding fell back */
        if (delta[k] > 0 && (double)f - (double)p[k] < delta[k])
            f = next_float(f, 1);
        else if (delta[k] < 0 && (double)f - (double)p[k] > delta[k])
            f = next_float(f, -1);
        out[k] = f;
    }
}

/* ---- the public entry points ---------------------------------------------- */

void cylray_hit_point(const cylray_prepared *cyl, const float o[3], const float d[3],
                      float t, int32_t part, float p[3], float *err)
{
    const geo g = geo_prepared(cyl);
    hit_point_geo(&g, o, d, t, part, p, err);
}

void cylray_spawn_origin(const cylray_prepared *cyl, const float p[3], float err,
                         int32_t part, const float w[3], float out[3])
{
    const geo g = geo_prepared(cyl);
    spawn_geo(&g, p, err, part, 0, w, out);
}

void cylray_spawn_origin_side(const cylray_prepared *cyl, const float p[3], float err,
                              int32_t part, int outward, const float w[3], float out[3])
{
    const geo g = geo_prepared(cyl);
    spawn_geo(&g, p, err, part, outward ? 1 : -1, w, out);
}

/* Packets: one lane at a time through the scalar pair. */
#define CYLRAY_SPAWN_PACKET_(n)                                                          \
    void cylray_hit_points##n(const cylray_prepared *cyl, const cylray_ray##n *ray,      \
                              const cylray_hit##n *hit, uint32_t mask,                   \
                              cylray_points##n *pts)                                     \
    {                                                                                    \
        const geo g = geo_prepared(cyl);                                                 \
        for (; mask; mask &= mask - 1) {                                                 \
            size_t i = CYLRAY_CTZ(mask);                                                 \
            float o[3] = {ray->ox[i], ray->oy[i], ray->oz[i]};                           \
            float d[3] = {ray->dx[i], ray->dy[i], ray->dz[i]}, p[3];                     \
            hit_point_geo(&g, o, d, hit->t[i], hit->part[i], p, &pts->err[i]);           \
            pts->x[i] = p[0];                                                            \
            pts->y[i] = p[1];                                                            \
            pts->z[i] = p[2];                                                            \
        }                                                                                \
    }                                                                                    \
    void cylray_spawn_rays##n(const cylray_prepared *cyl, const cylray_points##n *pts,   \
                              const cylray_hit##n *hit, uint32_t mask,                   \
                              cylray_ray##n *out)                                        \
    {                                                                                    \
        const geo g = geo_prepared(cyl);                                                 \
        for (; mask; mask &= mask - 1) {                                                 \
            size_t i = CYLRAY_CTZ(mask);                                                 \
            float p[3] = {pts->x[i], pts->y[i], pts->z[i]};                              \
            float w[3] = {out->dx[i], out->dy[i], out->dz[i]}, x[3];                     \
            spawn_geo(&g, p, pts->err[i], hit->part[i], 0, w, x);                        \
            out->ox[i] = x[0];                                                           \
            out->oy[i] = x[1];                                                           \
            out->oz[i] = x[2];                                                           \
            out->tmin[i] = 0.0f;                                                         \
        }                                                                                \
    }                                                                                    \
    void cylray_spawn_rays_side##n(const cylray_prepared *cyl, const cylray_points##n *pts, \
                                   const cylray_hit##n *hit, uint32_t mask,              \
                                   uint32_t outward, cylray_ray##n *out)                 \
    {                                                                                    \
        const geo g = geo_prepared(cyl);                                                 \
        for (; mask; mask &= mask - 1) {                                                 \
            size_t i = CYLRAY_CTZ(mask);                                                 \
            float p[3] = {pts->x[i], pts->y[i], pts->z[i]};                              \
            float w[3] = {out->dx[i], out->dy[i], out->dz[i]}, x[3];                     \
            spawn_geo(&g, p, pts->err[i], hit->part[i], outward >> i & 1u ? 1 : -1, w, x); \
            out->ox[i] = x[0];                                                           \
            out->oy[i] = x[1];                                                           \
            out->oz[i] = x[2];                                                           \
            out->tmin[i] = 0.0f;                                                         \
        }                                                                                \
    }
CYLRAY_SPAWN_PACKET_(4)
CYLRAY_SPAWN_PACKET_(8)
CYLRAY_SPAWN_PACKET_(16)
#undef CYLRAY_SPAWN_PACKET_

size_t cylray_hit_points_stream(const cylray_prepared *cyl, const cylray_rays *rays,
                                const cylray_hits *hits, const cylray_points *pts, size_t n)
{
    const geo g = geo_prepared(cyl);
    size_t count = 0;
    for (size_t i = 0; i < n; i++) {
        if ((hits->part[i] & CYLRAY_PART_MASK) == CYLRAY_MISS)
            continue;
        float o[3] = {rays->ox[i], rays->oy[i], rays->oz[i]};
        float d[3] = {rays->dx[i], rays->dy[i], rays->dz[i]}, p[3], err;
        hit_point_geo(&g, o, d, hits->t[i], hits->part[i], p, &err);
        pts->x[i] = p[0];
        pts->y[i] = p[1];
        pts->z[i] = p[2];
        if (pts->err)
            pts->err[i] = err;
        count++;
    }
    return count;
}

void cylray_spawn_stream(const cylray_prepared *cyl, const cylray_points *pts,
                         const int32_t *part, const cylray_points *dirs,
                         const cylray_points *origins, size_t n)
{
    const geo g = geo_prepared(cyl);
    for (size_t i = 0; i < n; i++) {
        if ((part[i] & CYLRAY_PART_MASK) == CYLRAY_MISS)
            continue;
        float p[3] = {pts->x[i], pts->y[i], pts->z[i]};
        float w[3] = {dirs->x[i], dirs->y[i], dirs->z[i]}, x[3];
        spawn_geo(&g, p, pts->err ? pts->err[i] : 0.0f, part[i], 0, w, x);
        origins->x[i] = x[0];
        origins->y[i] = x[1];
        origins->z[i] = x[2];
    }
}

void cylray_spawn_stream_side(const cylray_prepared *cyl, const cylray_points *pts,
                              const int32_t *part, const uint8_t *outward,
                              const cylray_points *dirs, const cylray_points *origins, size_t n)
{
    const geo g = geo_prepared(cyl);
    for (size_t i = 0; i < n; i++) {
        if ((part[i] & CYLRAY_PART_MASK) == CYLRAY_MISS)
            continue;
        float p[3] = {pts->x[i], pts->y[i], pts->z[i]};
        float w[3] = {dirs->x[i], dirs->y[i], dirs->z[i]}, x[3];
        spawn_geo(&g, p, pts->err ? pts->err[i] : 0.0f, part[i], outward[i] ? 1 : -1, w, x);
        origins->x[i] = x[0];
        origins->y[i] = x[1];
        origins->z[i] = x[2];
    }
}

/* Leaves: the lane the hit names. */
#define CYLRAY_SPAWN_LEAF_(m)                                                            \
    void cylray_leaf_hit_point##m(const cylray_leaf##m *leaf, const cylray_ray1 *ray,    \
                                  const cylray_hit1 *hit, float p[3], float *err)        \
    {                                                                                    \
        const geo g = geo_leaf(&leaf->geom_[0][0], leaf->meta_, m, hit->lane % m);       \
        hit_point_geo(&g, ray->o, ray->d, hit->t, hit->part, p, err);                    \
    }                                                                                    \
    void cylray_leaf_spawn_origin##m(const cylray_leaf##m *leaf, const cylray_hit1 *hit, \
                                     const float p[3], float err, const float w[3],      \
                                     float out[3])                                       \
    {                                                                                    \
        const geo g = geo_leaf(&leaf->geom_[0][0], leaf->meta_, m, hit->lane % m);       \
        spawn_geo(&g, p, err, hit->part, 0, w, out);                                     \
    }                                                                                    \
    void cylray_leaf_spawn_origin_side##m(const cylray_leaf##m *leaf,                    \
                                          const cylray_hit1 *hit, const float p[3],      \
                                          float err, int outward, const float w[3],      \
                                          float out[3])                                  \
    {                                                                                    \
        const geo g = geo_leaf(&leaf->geom_[0][0], leaf->meta_, m, hit->lane % m);       \
        spawn_geo(&g, p, err, hit->part, outward ? 1 : -1, w, out);                      \
    }
CYLRAY_SPAWN_LEAF_(4)
CYLRAY_SPAWN_LEAF_(8)
CYLRAY_SPAWN_LEAF_(16)
#undef CYLRAY_SPAWN_LEAF_
