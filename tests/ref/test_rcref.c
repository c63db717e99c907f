/* SPDX-License-Identifier: MIT */
/* test_rcref.c - tests of the exact round-cone reference: an independent computation of the
 * hull's entry and exit (a convex function minimised and bisected, no quadratic, no tangent
 * slab), the band's verdicts on answers from inside its box, seams, and the defects the band
 * must catch (its hand-computed answers: test_rchand.c). */
#include "bandutil.h"
#include "quad.h"
#include "rcref_eval.h"
#include "test_ref.h"

#include "../support/rng.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* ---- random round cones and rays ------------------------------------------------------ */

enum {
    RC_ORDINARY,
    RC_FAR,     /* origins 1e3..1e6 hull sizes away */
    RC_STRONG,  /* r1 / r0 in 1e-3..1e3 */
    RC_SLIGHT,  /* r1 = r0 +- 1..4 ulps */
    RC_CAPSULE, /* r1 = r0 */
    RC_POINT,   /* one radius 0 */
    RC_NESTED,  /* |p1 - p0| < |r1 - r0| */
    RC_ZERO,    /* p1 = p0 */
    RC_THIN,    /* length / radius about 1e4 */
    RC_EDGE,    /* |p1 - p0| just above |r1 - r0| */
    RC_COUNT
};

static const char *const rc_names[RC_COUNT] = {
    "ordinary", "far",    "strong taper", "slight taper", "capsule",
    "point",    "nested", "zero length",  "long thin",    "almost nested"};

typedef struct {
    rcref_round_cone rc;
    float o[3], d[3], tmin, tmax;
} rc_case;

static double unif(uint64_t *s, double lo, double hi)
{
    const double u = rng_unit(rng_splitmix64(s));
    return lo + (hi - lo) * u;
}

static void unit3(uint64_t *s, double v[3])
{
    double len;
    do {
        v[0] = unif(s, -1, 1);
        v[1] = unif(s, -1, 1);
        v[2] = unif(s, -1, 1);
        len = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    } while (len < 0.1 || len > 1);
    for (int k = 0; k < 3; k++)
        v[k] /= len;
}

static void rc_make(int cat, uint64_t seed, int n, rc_case *out)
{
    uint64_t s = seed * 0x9e3779b97f4a7c15u + (uint64_t)cat;
    for (int i = 0; i < n; i++) {
        rc_case *c = &out[i];
        double p0[3], u[3], L, r0, r1;
        for (int k = 0; k < 3; k++)
            p0[k] = unif(&s, -4, 4);
        unit3(&s, u);
        r0 = unif(&s, 0.2, 1.5);
        r1 = unif(&s, 0.2, 1.5);
        L = unif(&s, 0.5, 4);
        const double f = unif(&s, 0, 1), g = unif(&s, 0, 1);
        switch (cat) {
        case RC_STRONG:
            r0 = unif(&s, 0.05, 1);
            r1 = r0 * pow(10, (f < 0.5 ? -1 : 1) * (1 + 2 * g));
            L = fabs(r1 - r0) * (1 + pow(10, unif(&s, -2, 0.5)));
            break;
        case RC_SLIGHT:
            r1 = r0;
            for (int j = 0; j < 1 + (int)(4 * f); j++)
                r1 = nextafterf((float)r1, g < 0.5 ? 0.0f : 2.0f);
            break;
        case RC_CAPSULE:
            r1 = r0;
            break;
        case RC_POINT:
            if (f < 0.5)
                r0 = 0;
            else
                r1 = 0;
            L = fmax(L, 1.2 * fmax(r0, r1));
            break;
        case RC_NESTED:
            L = fabs(r1 - r0) * g * 0.99;
            break;
        case RC_ZERO:
            L = 0;
            break;
        case RC_THIN:
            r0 = unif(&s, 1e-3, 1e-2);
            r1 = r0 * (0.8 + 0.45 * g);
            L = r0 * 1e4 * (0.5 + 0.5 * f);
            break;
        case RC_EDGE:
            L = fabs(r1 - r0) * (1 + pow(2, -8 - 12 * g));
            break;
        }
        for (int k = 0; k < 3; k++) {
            c->rc.p0[k] = (float)p0[k];
            c->rc.p1[k] = (float)(p0[k] + L * u[k]);
        }
        c->rc.r0 = (float)r0;
        c->rc.r1 = (float)r1;
        c->rc.flags = i % 4 == 3 ? (unsigned)(i / 4 % 4) : CYLRAY_CAPPED;
        /* the ray: aimed at a point about the segment, from 2..8 hull sizes away (far:
         * 1e3..1e6), or from that point itself; d unnormalized */
        const double rmax = fmax(c->rc.r0, c->rc.r1), size = L / 2 + rmax;
        double x[3], v[3], dir[3];
        const double at = unif(&s, -0.2, 1.2), off = unif(&s, 0, 1.3) * rmax;
        unit3(&s, v);
        unit3(&s, dir);
        double dist = size * unif(&s, 2, 8);
        if (cat == RC_FAR)
            dist *= pow(10, unif(&s, 3, 6));
        if (i % 7 == 6)
            dist = 0;
        const double sc = pow(10, unif(&s, -1, 1));
        for (int k = 0; k < 3; k++) {
            x[k] = (double)c->rc.p0[k] + at * ((double)c->rc.p1[k] - c->rc.p0[k]) + off * v[k];
            c->o[k] = (float)(x[k] - dist * dir[k]);
            c->d[k] = (float)(dir[k] * sc);
        }
        const double tt = dist / sc, h = unif(&s, 0, 1);
        c->tmin = i % 5 == 4 ? (float)(tt * (0.9 + 0.2 * h)) : 0;
        c->tmax = i % 6 == 5 ? (float)(tt * (0.95 + 0.4 * h)) : INFINITY;
    }
}

/* ---- the independent computation ------------------------------------------------------ *
 * The hull is {x : g(x) <= 0} with g(x) = min over sigma in [0, L] of
 * |x - p0 - sigma u| - (r0 + k sigma), k = dr / L: a function jointly convex in (x, sigma)
 * minimised over sigma, so convex in x and along the ray in t. The inner minimum is where
 * the derivative in sigma vanishes, -(zeta - sigma) / dist = k with zeta the axial
 * coordinate and rho the distance from the axis: sigma* = zeta + k rho / sqrt(1 - k^2),
 * clamped to [0, L] (|k| >= 1: the end of the larger radius). Along the ray a golden-section
 * search finds g's least value, bisection each of its zeros, all in binary128; the part is
 * where the clamped sigma* lies (0: sphere 0, L: sphere 1, between: the side). */
typedef struct {
    cylq W[3], d[3], a[3], L, r0, r1, dr;
} ind_geo;

static cylq ind_g(const ind_geo *g, cylq t, cylq *sigma)
{
    cylq X[3];
    for (int k = 0; k < 3; k++)
        X[k] = g->W[k] + t * g->d[k];
    if (g->L == 0 || q_abs(g->dr) >= g->L) {
        const int one = g->r1 > g->r0;
        cylq Y[3];
        for (int k = 0; k < 3; k++)
            Y[k] = one ? X[k] - g->a[k] : X[k];
        *sigma = one ? g->L : 0;
        return q_sqrt(Y[0] * Y[0] + Y[1] * Y[1] + Y[2] * Y[2]) - (one ? g->r1 : g->r0);
    }
    const cylq c[3] = {X[1] * g->a[2] - X[2] * g->a[1], X[2] * g->a[0] - X[0] * g->a[2],
                       X[0] * g->a[1] - X[1] * g->a[0]};
    const cylq rho = q_sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]) / g->L;
    const cylq zeta = (X[0] * g->a[0] + X[1] * g->a[1] + X[2] * g->a[2]) / g->L;
    const cylq k = g->dr / g->L, adr = q_abs(g->dr);
    const cylq cosa = q_sqrt((g->L - adr) * (g->L + adr)) / g->L;
    cylq s = zeta + k * rho / cosa;
    *sigma = s;
    s = s < 0 ? 0 : s > g->L ? g->L : s;
    const cylq dz = zeta - s;
    return q_sqrt(dz * dz + rho * rho) - (g->r0 + k * s);
}

typedef struct {
    int hit;
    cylq te, tx;    /* entry and exit */
    cylq se, sx;    /* sigma* there, unclamped */
    cylq gmin, tol; /* g's least value; the scale of t */
    double size;    /* |p1 - p0| / 2 + the larger radius */
    double slope;   /* |g'| / |d| at the worse of the two zeros: the cosine of incidence */
} ind_out;

static void ind_solve(const rc_case *c, ind_out *out)
{
    ind_geo g;
    cylq aa = 0, dd = 0, wd = 0;
    for (int k = 0; k < 3; k++) {
        g.W[k] = (cylq)c->o[k] - c->rc.p0[k];
        g.d[k] = c->d[k];
        g.a[k] = (cylq)c->rc.p1[k] - c->rc.p0[k];
        aa += g.a[k] * g.a[k];
        dd += g.d[k] * g.d[k];
    }
    for (int k = 0; k < 3; k++)
        wd += (g.W[k] - g.a[k] / 2) * g.d[k];
    g.L = q_sqrt(aa);
    g.r0 = c->rc.r0;
    g.r1 = c->rc.r1;
    g.dr = g.r1 - g.r0;
    const cylq size = g.L / 2 + q_max(g.r0, g.r1), dl = q_sqrt(dd);
    const cylq mid = -wd / dd, reach = size / dl * (cylq)1.25;
    out->tol = q_abs(mid) + reach;
    out->size = (double)size;
    cylq a = mid - reach, b = mid + reach, sg;
    const cylq phi = (cylq)0.6180339887498948482045868343656381L;
    cylq x1 = b - phi * (b - a), x2 = a + phi * (b - a);
    cylq g1 = ind_g(&g, x1, &sg), g2 = ind_g(&g, x2, &sg);
    for (int it = 0; it < 120; it++) {
        if (g1 < g2) {
            b = x2, x2 = x1, g2 = g1;
            x1 = b - phi * (b - a);
            g1 = ind_g(&g, x1, &sg);
        } else {
            a = x1, x1 = x2, g1 = g2;
            x2 = a + phi * (b - a);
            g2 = ind_g(&g, x2, &sg);
        }
    }
    const cylq tm = g1 < g2 ? x1 : x2;
    out->gmin = q_min(g1, g2);
    out->hit = out->gmin <= 0;
    if (!out->hit)
        return;
    cylq ends[2];
    for (int e = 0; e < 2; e++) {
        cylq lo = e ? tm : mid - reach, hi = e ? mid + reach : tm; /* g changes sign */
        for (int it = 0; it < 400; it++) {
            const cylq m = (lo + hi) / 2;
            if (m == lo || m == hi)
                break;
            const int in = ind_g(&g, m, &sg) <= 0;
            if (in == (e == 0))
                hi = m;
            else
                lo = m;
        }
        ends[e] = (lo + hi) / 2;
    }
    out->te = ends[0];
    out->tx = ends[1];
    ind_g(&g, out->te, &out->se);
    ind_g(&g, out->tx, &out->sx);
    const cylq h = reach * (cylq)1e-7;
    const cylq se = (ind_g(&g, out->te - h, &sg) - ind_g(&g, out->te, &sg)) / h;
    const cylq sx = (ind_g(&g, out->tx + h, &sg) - ind_g(&g, out->tx, &sg)) / h;
    out->slope = (double)(q_min(se, sx) / dl);
}

/* The part at sigma*: -1 where it is within 1e-9 of a seam (or the hull is one sphere of
 * two equal ones), where either part is right to the precision of the search. */
static int ind_part(const rc_case *c, cylq sigma)
{
    double aa = 0;
    for (int k = 0; k < 3; k++) {
        const double a = (double)c->rc.p1[k] - c->rc.p0[k];
        aa += a * a;
    }
    const double L = sqrt(aa), dr = (double)c->rc.r1 - c->rc.r0, s = (double)sigma;
    if (L == 0 || fabs(dr) >= L) {
        if (c->rc.r0 == c->rc.r1 || fabs(fabs(dr) - L) <= 1e-9 * L)
            return -1;
        return c->rc.r1 > c->rc.r0 ? CYLRAY_CAP_HI : CYLRAY_CAP_LO;
    }
    if (fabs(s) <= 1e-9 * L || fabs(s - L) <= 1e-9 * L)
        return -1;
    if (s < 0)
        return c->rc.r0 > 0 ? CYLRAY_CAP_LO : -1;
    if (s > L)
        return c->rc.r1 > 0 ? CYLRAY_CAP_HI : -1;
    return CYLRAY_SIDE;
}

static int present(unsigned flags, int part)
{
    return part == CYLRAY_SIDE ||
           (flags & (part == CYLRAY_CAP_LO ? CYLRAY_CAPPED_LO : CYLRAY_CAPPED_HI));
}

typedef struct {
    long cases, compared, hits, backs, open, skipped_grazing, skipped_seam, parts;
    double worst;
    int worst_cat, worst_i;
} ind_counts;

static void compare_one(ind_counts *n, const rc_case *c, int cat, int i, unsigned fl)
{
    ind_out x;
    ind_solve(c, &x);
    n->cases++;
    if (fabs((double)x.gmin) < 1e-9 * x.size || (x.hit && x.slope < 1e-4)) {
        n->skipped_grazing++;
        return;
    }
    const cylq tmin = c->tmin, tmax = c->tmax;
    const int pe = x.hit ? ind_part(c, x.se) : 0, px = x.hit ? ind_part(c, x.sx) : 0;
    int hit = 0, part = 0;
    cylq t = 0;
    if (x.hit) {
        const cylq eps = (cylq)1e-15 * x.tol;
        if (q_abs(x.te - tmin) < eps || q_abs(x.te - tmax) < eps || q_abs(x.tx - tmin) < eps ||
            q_abs(x.tx - tmax) < eps || pe < 0 || px < 0) {
            n->skipped_seam++;
            return;
        }
        if (x.te > tmax) {
        } else if (x.te >= tmin && present(c->rc.flags, pe)) {
            hit = 1, t = x.te, part = pe;
        } else if (x.tx >= tmin && x.tx <= tmax && present(c->rc.flags, px) &&
                   !(fl & CYLRAY_CULL_BACK)) {
            hit = 1, t = x.tx, part = px | CYLRAY_BACKFACE;
        }
    }
    rin_q q;
    rrec r;
    rcref_in_(&c->rc, c->o, c->d, &q);
    rcref_eval_(&q, -1, tmin, tmax, &r);
    const int xr = rcref_decide_(&r, c->rc.flags | (fl & CYLRAY_CULL_BACK));
    cylref_hit h;
    rcref_intersect(&c->rc, c->o, c->d, c->tmin, c->tmax, fl, &h);
    n->compared++;
    CHECK(h.hit == (xr >= 0), "%s #%d: intersect %d, eval %d", rc_names[cat], i, h.hit, xr);
    CHECK(hit == h.hit, "%s #%d flags %u/%u: independent %d (gmin %.3g), reference %d",
          rc_names[cat], i, c->rc.flags, fl, hit, (double)x.gmin, h.hit);
    if (!hit || !h.hit || xr < 0)
        return;
    n->hits++;
    n->backs += (part & CYLRAY_BACKFACE) != 0;
    n->open += c->rc.flags != CYLRAY_CAPPED;
    const cylq tr = rcref_t_(&r, xr);
    const double rel = (double)(q_abs(tr - t) / x.tol);
    if (rel > n->worst) {
        n->worst = rel;
        n->worst_cat = cat;
        n->worst_i = i;
    }
    CHECK(rel <= 1e-20, "%s #%d: t %.25g vs independent %.25g (%.3g relative)", rc_names[cat],
          i, (double)tr, (double)t, rel);
    CHECK(h.t == (double)tr, "%s #%d: intersect's t %.17g, eval's %.17g", rc_names[cat], i, h.t,
          (double)tr);
    n->parts++;
    CHECK(h.part == part, "%s #%d: part %#x, independent %#x", rc_names[cat], i,
          (unsigned)h.part, (unsigned)part);
    const double len = sqrt(h.n[0] * h.n[0] + h.n[1] * h.n[1] + h.n[2] * h.n[2]);
    CHECK(fabs(len - 1) < 1e-14, "%s #%d: |n| %.17g", rc_names[cat], i, len);
}

static void test_independent(void)
{
    enum { N = 240 };
    static rc_case cs[N];
    ind_counts n;
    memset(&n, 0, sizeof n);
    for (int cat = 0; cat < RC_COUNT; cat++) {
        rc_make(cat, 2026, N, cs);
        for (int i = 0; i < N; i++)
            compare_one(&n, &cs[i], cat, i, i % 3 == 2 ? CYLRAY_CULL_BACK : 0);
    }
    printf("rcref vs minimised convex distance: %ld cases, %ld compared (%ld hits, %ld back, "
           "%ld open ends, %ld parts), %ld grazing and %ld at seams or range ends skipped; "
           "worst t %.3g relative (%s #%d)\n",
           n.cases, n.compared, n.hits, n.backs, n.open, n.parts, n.skipped_grazing,
           n.skipped_seam, n.worst, rc_names[n.worst_cat], n.worst_i);
    CHECK(n.compared > RC_COUNT * N * 3 / 4 && n.hits > RC_COUNT * N / 4,
          "too few compared: %ld, %ld hits", n.compared, n.hits);
}

/* ---- a solver in double ---------------------------------------------------------------- *
 * What a kernel in double might write, in the textbook frame: the unit axis u, z in
 * lengths, the frustum's quadratic |x_perp|^2 n_rho^2 - (r0 + k z)^2 from subtracted
 * perpendicular parts; the hull's entry and exit as the least and greatest of the pieces',
 * rounded once to float. It must be inside every band, as the double solvers of the
 * sphere and the cone are. */
typedef struct {
    int ex;
    double lo, hi, face;
} dbl_piece;

static void dbl_sphere(const double W[3], const double d[3], double rad, dbl_piece *p)
{
    const double x[3] = {W[1] * d[2] - W[2] * d[1], W[2] * d[0] - W[0] * d[2],
                         W[0] * d[1] - W[1] * d[0]};
    const double A = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    const double B = W[0] * d[0] + W[1] * d[1] + W[2] * d[2];
    const double C = W[0] * W[0] + W[1] * W[1] + W[2] * W[2] - rad * rad;
    const double D = A * rad * rad - (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
    p->ex = rad > 0 && D >= 0;
    if (!p->ex)
        return;
    const double sq = sqrt(D), q = -(B + copysign(sq, B));
    const double t1 = q / A, t2 = q != 0 ? C / q : t1;
    p->lo = fmin(t1, t2);
    p->hi = fmax(t1, t2);
    p->face = sq;
}

static void dbl_frustum(const double W[3], const double d[3], const double a[3], double r0,
                        double r1, dbl_piece *p)
{
    double aa = 0, zw = 0, zd = 0, wp[3], dp[3];
    for (int k = 0; k < 3; k++)
        aa += a[k] * a[k];
    const double L = sqrt(aa), dr = r1 - r0, k = dr / L;
    const double nr2 = fmax(0, (L - fabs(dr)) * (L + fabs(dr))) / aa;
    for (int j = 0; j < 3; j++) {
        zw += W[j] * a[j] / L;
        zd += d[j] * a[j] / L;
    }
    for (int j = 0; j < 3; j++) {
        wp[j] = W[j] - zw * a[j] / L;
        dp[j] = d[j] - zd * a[j] / L;
    }
    const double rw = r0 + k * zw;
    const double A = nr2 * (dp[0] * dp[0] + dp[1] * dp[1] + dp[2] * dp[2]) - k * k * zd * zd;
    const double B = nr2 * (wp[0] * dp[0] + wp[1] * dp[1] + wp[2] * dp[2]) - k * zd * rw;
    const double C = nr2 * (wp[0] * wp[0] + wp[1] * wp[1] + wp[2] * wp[2]) - rw * rw;
    const double D = B * B - A * C;
    double cl = -INFINITY, ch = INFINITY, sl = -INFINITY, sh = INFINITY;
    p->ex = 0;
    const double sq = sqrt(fmax(D, 0)), q = -(B + copysign(sq, B));
    const double ra = q / A, rc = q != 0 ? C / q : ra;
    const double tm = B >= 0 ? ra : rc, tp = B >= 0 ? rc : ra;
    if (A > 0) {
        if (D < 0)
            return;
        cl = tm, ch = tp;
    } else if (A < 0 && D >= 0) {
        if (k * zd > 0)
            cl = tm;
        else
            ch = tp;
    } else if (A == 0) {
        if (B != 0) {
            if (B < 0)
                cl = -C / (2 * B);
            else
                ch = -C / (2 * B);
        } else if (C > 0) {
            return;
        }
    }
    const double z0 = -r0 * k, z1 = L - r1 * k;
    if (zd != 0) {
        sl = fmin((z0 - zw) / zd, (z1 - zw) / zd);
        sh = fmax((z0 - zw) / zd, (z1 - zw) / zd);
    } else if (zw < z0 || zw > z1) {
        return;
    }
    p->lo = fmax(cl, sl);
    p->hi = fmin(ch, sh);
    p->face = ch <= sh ? sq : A * p->hi + B;
    p->ex = p->lo <= p->hi && isfinite(p->lo) && isfinite(p->hi);
}

static int dbl_solve(const rc_case *c, unsigned fl, float *t, int *part)
{
    double w[3], d[3], a[3], W0[3], W1[3], wd = 0, dd = 0, aa = 0;
    for (int k = 0; k < 3; k++) {
        w[k] = (double)c->o[k] - ((double)c->rc.p0[k] + c->rc.p1[k]) / 2;
        d[k] = c->d[k];
        a[k] = (double)c->rc.p1[k] - c->rc.p0[k];
        wd += w[k] * d[k];
        dd += d[k] * d[k];
        aa += a[k] * a[k];
    }
    const double s0 = -wd / dd, r0 = c->rc.r0, r1 = c->rc.r1, dr = r1 - r0;
    for (int k = 0; k < 3; k++) {
        W0[k] = w[k] + s0 * d[k] + a[k] / 2;
        W1[k] = w[k] + s0 * d[k] - a[k] / 2;
    }
    dbl_piece pc[3] = {{0, 0, 0, 0}, {0, 0, 0, 0}, {0, 0, 0, 0}}; /* F, S0, S1 */
    const int nested = !(aa - dr * dr > 0), big = r1 > r0;
    if (!nested || !big)
        dbl_sphere(W0, d, r0, &pc[1]);
    if (!nested || big)
        dbl_sphere(W1, d, r1, &pc[2]);
    if (!nested)
        dbl_frustum(W0, d, a, r0, r1, &pc[0]);
    int e = -1, x = -1;
    for (int p = 0; p < 3; p++) {
        if (!pc[p].ex)
            continue;
        if (e < 0 || pc[p].lo < pc[e].lo)
            e = p;
        if (x < 0 || pc[p].hi > pc[x].hi)
            x = p;
    }
    if (e < 0)
        return 0;
    static const int parts[3] = {CYLRAY_SIDE, CYLRAY_CAP_LO, CYLRAY_CAP_HI};
    const unsigned caps[3] = {0, CYLRAY_CAPPED_LO, CYLRAY_CAPPED_HI};
    const double te = s0 + pc[e].lo, tx = s0 + pc[x].hi;
    const int back = pc[x].face > 0;
    if (te > c->tmax)
        return 0;
    if (te >= c->tmin && (e == 0 || (c->rc.flags & caps[e]))) {
        *t = (float)te;
        *part = parts[e];
        return 1;
    }
    if (tx >= c->tmin && tx <= c->tmax && (x == 0 || (c->rc.flags & caps[x])) &&
        !((fl & CYLRAY_CULL_BACK) && back)) {
        *t = (float)tx;
        *part = parts[x] | (back ? CYLRAY_BACKFACE : 0);
        return 1;
    }
    return 0;
}

/* ---- the band ------------------------------------------------------------------------- */

/* The answer for inputs moved to a random point inside the band's box (up to 1.9 of its 2
 * ulps in each input): the band must allow it. */
static int inside_box(const rc_case *c, unsigned flags, uint64_t *s, int *part, float *t)
{
    rin_q q;
    rcref_in_(&c->rc, c->o, c->d, &q);
    const cylq sw = ref_vec_step(q.w), sd = ref_vec_step(q.d), sa = ref_vec_step(q.a);
    for (int k = 0; k < 3; k++) {
        const double u1 = unif(s, -1.9, 1.9);
        const double u2 = unif(s, -1.9, 1.9);
        const double u3 = unif(s, -1.9, 1.9);
        q.w[k] += sw * (cylq)u1;
        q.d[k] += sd * (cylq)u2;
        q.a[k] += sa * (cylq)u3;
    }
    const double u4 = unif(s, -1.9, 1.9);
    const double u5 = unif(s, -1.9, 1.9);
    if (q.r0 > 0)
        q.r0 += (cylq)(u4 * ref_float_ulp(c->rc.r0));
    if (q.r1 > 0)
        q.r1 += (cylq)(u5 * ref_float_ulp(c->rc.r1));
    rrec r;
    rcref_eval_(&q, -1, c->tmin, c->tmax, &r);
    const int x = rcref_decide_(&r, c->rc.flags | (flags & CYLRAY_CULL_BACK));
    if (x < 0)
        return 0;
    *part = rcref_part_(&r, x);
    *t = (float)rcref_t_(&r, x);
    return 1;
}

static void test_band(void)
{
    enum { N = 96, INNER = 4 };
    static rc_case cs[N];
    uint64_t s = 0x626e64;
    for (int cat = 0; cat < RC_COUNT; cat++) {
        rc_make(cat, 7, N, cs);
        int dbad = 0;
        double dworst = 0;
        int hits = 0, unstable = 0, hit_unstable = 0, bad = 0, caught = 0, caught_of = 0,
            wn = 0;
        double wsum = 0, worst = 0;
        for (int i = 0; i < N; i++) {
            const rc_case *c = &cs[i];
            for (unsigned fl = 0; fl <= CYLRAY_CULL_BACK; fl += CYLRAY_CULL_BACK) {
                cylref_band b;
                double ub;
                rcref_band_eval(&c->rc, c->o, c->d, c->tmin, c->tmax, fl, &b);
                hits += b.exact.hit;
                unstable += b.decision_unstable;
                hit_unstable += b.hit_unstable;
                CHECK(rcref_judge(&b, b.exact.hit, b.exact.part, (float)b.exact.t, &ub) == 0 &&
                          (!b.exact.hit || ub == 0),
                      "%s #%d: the exact answer fails its band", rc_names[cat], i);
                if (b.exact.hit) {
                    wsum += 0.5 * (b.t_hi - b.t_lo) / cylref_float_ulp(b.exact.t);
                    wn++;
                }
                for (int j = 0; j < INNER; j++) {
                    int part = 0;
                    float t = 0;
                    const int hit = inside_box(c, fl, &s, &part, &t);
                    const int v = rcref_judge(&b, hit, part, t, &ub);
                    if (v || ub > 0.5) {
                        if (bad++ < 4)
                            printf(
                                "  %s #%d flags %u: inside the box %d t %.9g part %#x judged "
                                "%d, %.3g ulps beyond (exact %d t %.9g part %#x)\n",
                                rc_names[cat], i, fl, hit, (double)t, part, v, ub, b.exact.hit,
                                b.exact.t, b.exact.part);
                    }
                    if (!v && hit)
                        worst = fmax(worst, ub);
                }
                {
                    int part = 0;
                    float t = 0;
                    const int hit = dbl_solve(c, fl, &t, &part);
                    const int v = rcref_judge(&b, hit, part, t, &ub);
                    if (v || ub > 1) {
                        if (dbad++ < 4)
                            printf("  %s #%d flags %u: double solver %d t %.9g part %#x judged "
                                   "%d, %.3g ulps beyond (exact %d t %.9g part %#x)\n",
                                   rc_names[cat], i, fl, hit, (double)t, part, v, ub,
                                   b.exact.hit, b.exact.t, b.exact.part);
                    }
                    if (!v && hit)
                        dworst = fmax(dworst, ub);
                }
                /* On a stable hit: 16 ulps past the band, a miss and the other face are
                 * all caught. */
                if (b.exact.hit && !b.decision_unstable) {
                    const float late = (float)(b.t_hi + 16 * cylref_float_ulp(b.t_hi));
                    caught_of++;
                    caught += rcref_judge(&b, 1, b.exact.part, late, &ub) == 0 && ub > 8;
                    caught += rcref_judge(&b, 0, 0, 0, &ub) == 1;
                    caught += rcref_judge(&b, 1, b.exact.part ^ CYLRAY_BACKFACE,
                                          (float)b.exact.t, &ub) == 2;
                }
            }
        }
        printf("rc band %-13s %3d/%d hits, %3d unstable (%d hit or miss), %d of %d answers "
               "from inside the box "
               "judged bad (worst %.3g ulps beyond), %d/%d defects caught, band +-%.3g ulps on "
               "average\n",
               rc_names[cat], hits, 2 * N, unstable, hit_unstable, bad, 2 * N * INNER, worst,
               caught, 3 * caught_of, wn ? wsum / wn : 0.0);
        printf("rc band %-13s double solver: %d judged bad, worst %.3g ulps beyond\n",
               rc_names[cat], dbad, dworst);
        CHECK(bad == 0, "%s: answers from inside the box fail the band %d times", rc_names[cat],
              bad);
        CHECK(dbad == 0, "%s: the double solver fails its bands %d times", rc_names[cat], dbad);
        CHECK(caught == 3 * caught_of, "%s: defects missed", rc_names[cat]);
        CHECK(hits > N / 4, "%s: too few hits %d", rc_names[cat], hits);
        /* far: the box moves the ray by 2 ulps of 1e3..1e6 hull sizes, so a side or a cap
         * near a seam is often either */
        if (cat == RC_ORDINARY || cat == RC_CAPSULE)
            CHECK(unstable < 2 * N / 10, "%s: too many unstable %d", rc_names[cat], unstable);
        if (cat == RC_FAR)
            CHECK(hit_unstable < 2 * N / 5, "%s: too many unstable %d", rc_names[cat],
                  hit_unstable);
    }
}

/* Rays through a point of a seam (a tangent circle), rounded to floats, entering the hull:
 * a closed hull is hit there, never missed, and the band allows both the side and the cap;
 * with that end open the band allows the side at the seam. */
static void test_seams(void)
{
    enum { N = 400 };
    static rc_case cs[N];
    const int cats[] = {RC_ORDINARY, RC_STRONG, RC_CAPSULE, RC_POINT, RC_THIN, RC_SLIGHT};
    uint64_t s = 0x7365616d;
    int rays = 0, leaks = 0, both = 0, side_open = 0, open = 0;
    for (size_t ci = 0; ci < sizeof cats / sizeof *cats; ci++) {
        rc_make(cats[ci], 99, N, cs);
        for (int i = 0; i < N; i++) {
            rc_case *c = &cs[i];
            double a[3], u[3], e1[3], e2[3], aa = 0;
            for (int k = 0; k < 3; k++) {
                a[k] = (double)c->rc.p1[k] - c->rc.p0[k];
                aa += a[k] * a[k];
            }
            const double L = sqrt(aa), dr = (double)c->rc.r1 - c->rc.r0;
            const int end = i & 1;
            const double rad = end ? c->rc.r1 : c->rc.r0;
            if (!(L > fabs(dr) * (1 + 1e-6)) || !(rad > 0))
                continue;
            for (int k = 0; k < 3; k++)
                u[k] = a[k] / L;
            /* e1, e2: a frame across the axis */
            const double pick[3] = {fabs(u[0]) < 0.6 ? 1 : 0, fabs(u[0]) < 0.6 ? 0 : 1, 0};
            const double pu = pick[0] * u[0] + pick[1] * u[1] + pick[2] * u[2];
            double l1 = 0;
            for (int k = 0; k < 3; k++) {
                e1[k] = pick[k] - pu * u[k];
                l1 += e1[k] * e1[k];
            }
            for (int k = 0; k < 3; k++)
                e1[k] /= sqrt(l1);
            e2[0] = u[1] * e1[2] - u[2] * e1[1];
            e2[1] = u[2] * e1[0] - u[0] * e1[2];
            e2[2] = u[0] * e1[1] - u[1] * e1[0];
            const double k = dr / L, nr = sqrt((L - fabs(dr)) * (L + fabs(dr))) / L;
            const double phi = unif(&s, 0, 6.283185307179586);
            const double tw = unif(&s, -0.6, 0.6), tz = unif(&s, -0.6, 0.6);
            double x[3], n[3], d[3];
            for (int j = 0; j < 3; j++) {
                const double radial = cos(phi) * e1[j] + sin(phi) * e2[j];
                const double tang = -sin(phi) * e1[j] + cos(phi) * e2[j];
                const double at = (end ? c->rc.p1[j] : c->rc.p0[j]) - rad * k * u[j];
                x[j] = at + rad * nr * radial;
                n[j] = nr * radial - k * u[j];
                /* along the surface: tangent to the seam, and along the generator line */
                const double gen = k * radial + nr * u[j];
                d[j] = -n[j] + tw * tang + tz * gen;
            }
            const double size = L / 2 + fmax(c->rc.r0, c->rc.r1);
            for (int j = 0; j < 3; j++) {
                c->o[j] = (float)(x[j] - 3 * size * d[j]);
                c->d[j] = (float)d[j];
            }
            c->tmin = 0;
            c->tmax = INFINITY;
            c->rc.flags = i % 4 < 2 ? CYLRAY_CAPPED : end ? CYLRAY_CAPPED_LO : CYLRAY_CAPPED_HI;
            const int cap = end ? CYLRAY_CAP_HI : CYLRAY_CAP_LO;
            cylref_band b;
            double ub1, ub2;
            rcref_band_eval(&c->rc, c->o, c->d, 0, INFINITY, 0, &b);
            const float t = (float)(3 * size);
            if (c->rc.flags == CYLRAY_CAPPED) {
                rays++;
                const int leak = !b.exact.hit || fabs(b.exact.t - 3 * size) > 1e-4 * size ||
                                 rcref_judge(&b, 0, 0, 0, &ub1) != 1;
                leaks += leak;
                if (leak && leaks < 4)
                    printf("  seam %s #%d: exact %d t %.9g (seam at %.9g) part %#x, "
                           "hit_unstable %d\n",
                           rc_names[cats[ci]], i, b.exact.hit, b.exact.t, 3 * size,
                           b.exact.part, b.hit_unstable);
                both += rcref_judge(&b, 1, CYLRAY_SIDE, t, &ub1) == 0 && ub1 < 1 &&
                        rcref_judge(&b, 1, cap, t, &ub2) == 0 && ub2 < 1;
            } else {
                open++;
                side_open += rcref_judge(&b, 1, CYLRAY_SIDE, t, &ub1) == 0 && ub1 < 1;
            }
        }
    }
    printf(
        "rc seams: %d rays at closed seams, %d missed or judged missable, %d with both parts "
        "allowed; %d at open seams, %d with the side allowed\n",
        rays, leaks, both, open, side_open);
    CHECK(rays > 300 && leaks == 0, "seams: %d leaks of %d", leaks, rays);
    CHECK(both >= rays * 9 / 10, "seams: both parts allowed at %d of %d", both, rays);
    CHECK(side_open >= open * 9 / 10, "open seams: the side allowed at %d of %d", side_open,
          open);
}

void test_rcref(void)
{
    test_independent();
    test_band();
    test_seams();
}
