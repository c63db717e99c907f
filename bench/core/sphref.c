/* SPDX-License-Identifier: MIT */
/* sphref.c - the exact sphere (sphref.h). Every value is binary128 from the float
 * inputs; the forms are the cancellation-free ones, so binary128's own rounding stays
 * far below a float ulp also for origins 1e6 radii away:
 *
 *   disc = (d.d) R^2 - |d x w|^2            (Lagrange: no b^2 - (d.d) c cancellation)
 *   q = -(b + sign(b) sqrt(disc)),  roots q / d.d and c / q   (the stable quadratic) */
#include "sphref.h"

#include "quad.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

/* One exact evaluation: the roots (t0 <= t1) and the tangency margin. */
typedef struct sph_eval {
    cylq disc, t0, t1;
} sph_eval;

static void eval(const cylq w[3], const cylq d[3], cylq r, sph_eval *e)
{
    cylq dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    cylq b = w[0] * d[0] + w[1] * d[1] + w[2] * d[2];
    cylq c = w[0] * w[0] + w[1] * w[1] + w[2] * w[2] - r * r;
    cylq x[3] = {d[1] * w[2] - d[2] * w[1], d[2] * w[0] - d[0] * w[2],
                 d[0] * w[1] - d[1] * w[0]};
    e->disc = dd * r * r - (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
    if (e->disc < 0) {
        e->t0 = e->t1 = -b / dd; /* the closest approach: where the roots would meet */
        return;
    }
    cylq s = q_sqrt(e->disc), q = b >= 0 ? -(b + s) : -(b - s);
    if (q == 0) {
        e->t0 = e->t1 = 0;
        return;
    }
    cylq ta = q / dd, tb = c / q;
    e->t0 = q_min(ta, tb);
    e->t1 = q_max(ta, tb);
}

/* The outcome of an evaluation: 0 miss, else the part of the first root in range. */
static int outcome(const sph_eval *e, double tmin, double tmax, double *t)
{
    if (e->disc < 0)
        return 0;
    double t0 = (double)e->t0, t1 = (double)e->t1;
    if (t0 >= tmin && t0 <= tmax) {
        *t = t0;
        return CYLRAY_SIDE;
    }
    if (t1 >= tmin && t1 <= tmax) {
        *t = t1;
        return CYLRAY_SIDE | CYLRAY_BACKFACE;
    }
    return 0;
}

static void inputs(const cylray_sphere *s, const float o[3], const float dv[3], cylq w[3],
                   cylq d[3], cylq *r)
{
    for (int k = 0; k < 3; k++) {
        w[k] = (cylq)o[k] - (cylq)s->center[k];
        d[k] = dv[k];
    }
    *r = s->radius;
}

static int ray_ok(const float o[3], const float d[3], float tmin, float tmax)
{
    for (int k = 0; k < 3; k++)
        if (!isfinite(o[k]) || !isfinite(d[k]))
            return 0;
    return (d[0] != 0 || d[1] != 0 || d[2] != 0) && !isnan(tmin) && !isnan(tmax) &&
           tmin <= tmax;
}

int sphref_intersect(const cylray_sphere *s, const float o[3], const float d[3], float tmin,
                     float tmax, cylref_hit *out)
{
    out->hit = 0;
    out->t = 0;
    out->part = CYLRAY_MISS;
    if (!ray_ok(o, d, tmin, tmax))
        return 0;
    cylq w[3], dq[3], r;
    inputs(s, o, d, w, dq, &r);
    sph_eval e;
    eval(w, dq, r, &e);
    double t = 0;
    int p = outcome(&e, tmin, tmax, &t);
    if (!p)
        return 0;
    out->hit = 1;
    out->t = t;
    out->part = p;
    cylq tq = p & CYLRAY_BACKFACE ? e.t1 : e.t0;
    for (int k = 0; k < 3; k++)
        out->n[k] = (double)((w[k] + tq * dq[k]) / r);
    return 1;
}

/* 2 float ulps of the largest magnitude among n values. */
static double step_of(const cylq *a, int n)
{
    double m = 0;
    for (int k = 0; k < n; k++)
        m = fmax(m, fabs((double)a[k]));
    return 2 * cylref_float_ulp(m);
}

static uint64_t mix(uint64_t *s)
{
    uint64_t z = (*s += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

/* A range [lo, hi] of t per outcome seen (index: 0 front, 1 back). */
typedef struct range {
    int seen;
    double lo, hi;
} range;

static void widen(range *g, double lo, double hi)
{
    if (!g->seen) {
        g->seen = 1;
        g->lo = lo, g->hi = hi;
    } else {
        g->lo = fmin(g->lo, lo), g->hi = fmax(g->hi, hi);
    }
}

void sphref_band_eval(const cylray_sphere *s, const float o[3], const float d[3], float tmin,
                      float tmax, cylref_band *out)
{
    memset(out, 0, sizeof *out);
    sphref_intersect(s, o, d, tmin, tmax, &out->exact);
    out->evals = 1;
    if (!ray_ok(o, d, tmin, tmax))
        return;
    cylq x0[7], st[7];
    inputs(s, o, d, x0, x0 + 3, &x0[6]);
    double sw = step_of(x0, 3), sd = step_of(x0 + 3, 3);
    for (int k = 0; k < 7; k++)
        st[k] = k < 3 ? sw : k < 6 ? sd : 2 * cylref_float_ulp((double)x0[6]);
    sph_eval e0;
    eval(x0, x0 + 3, x0[6], &e0);

    /* First order: the sum over inputs of each quantity's change bounds its change over
     * the box; the evaluations' own outcomes are kept as seen. */
    double g_disc = 0, g_t0 = 0, g_t1 = 0;
    int seen_miss = 0;
    range rg[2] = {{0, 0, 0}, {0, 0, 0}};
    uint64_t seed = 0x5eed5eedull ^ (uint64_t)out->exact.hit;
    for (int k = 0; k < 2 * 7 + 8; k++) {
        cylq x[7];
        for (int j = 0; j < 7; j++)
            x[j] = x0[j];
        if (k < 14) {
            x[k / 2] += k % 2 ? -st[k / 2] : st[k / 2];
        } else {
            for (int j = 0; j < 7; j++)
                x[j] += mix(&seed) >> 63 ? st[j] : -st[j];
        }
        sph_eval e;
        eval(x, x + 3, x[6], &e);
        out->evals++;
        if (k < 14 && k % 2 == 0) {
            g_disc += fabs((double)(e.disc - e0.disc));
            g_t0 += fabs((double)(e.t0 - e0.t0));
            g_t1 += fabs((double)(e.t1 - e0.t1));
        }
        double t = 0;
        int p = outcome(&e, tmin, tmax, &t);
        if (!p)
            seen_miss = 1;
        else
            widen(&rg[p >> 4 & 1], t, t);
    }

    /* The decisions and their margins against what the box can move them by. */
    double t0 = (double)e0.t0, t1 = (double)e0.t1;
    double u0 = 4 * cylref_float_ulp(t0), u1 = 4 * cylref_float_ulp(t1);
    int tangent = fabs((double)e0.disc) <= g_disc;
    int near0 = fabs(t0 - tmin) <= g_t0 + u0 || fabs(tmax - t0) <= g_t0 + u0;
    int near1 = fabs(t1 - tmin) <= g_t1 + u1 || fabs(tmax - t1) <= g_t1 + u1;
    if (tangent) {
        /* near a tangency t moves with the square root of the discriminant's change */
        double dd = (double)(x0[3] * x0[3] + x0[4] * x0[4] + x0[5] * x0[5]);
        double half = sqrt(fmax((double)e0.disc, 0) + g_disc) / dd;
        double mid = 0.5 * (t0 + t1);
        g_t0 = fmax(g_t0, half + fabs(t0 - mid));
        g_t1 = fmax(g_t1, half + fabs(t1 - mid));
    }
    if (tangent || e0.disc >= 0) {
        widen(&rg[0], t0 - g_t0, t0 + g_t0);
        widen(&rg[1], t1 - g_t1, t1 + g_t1);
    }
    /* a root counts as possible when its t range meets [tmin, tmax] */
    int poss[2];
    poss[0] = rg[0].seen && rg[0].hi >= tmin && rg[0].lo <= tmax;
    poss[1] = rg[1].seen && rg[1].hi >= tmin && rg[1].lo <= tmax;
    out->hit_unstable = out->exact.hit ? (tangent || near0 || near1 || seen_miss)
                                       : (poss[0] || poss[1]) && (tangent || near0 || near1);
    out->part_unstable = out->exact.hit && (near0 || tangent) && poss[0] && poss[1];
    out->decision_unstable = out->hit_unstable || out->part_unstable;
    if (out->exact.hit) {
        const int e = out->exact.part >> 4 & 1;
        const double te = out->exact.t, g = e ? g_t1 : g_t0;
        out->t_lo = fmin(te - g, rg[e].seen ? rg[e].lo : te);
        out->t_hi = fmax(te + g, rg[e].seen ? rg[e].hi : te);
    }
    /* the other outcomes a kernel may pick where a decision is open */
    for (int p = 0; p < 2; p++) {
        const int part = p ? CYLRAY_SIDE | CYLRAY_BACKFACE : CYLRAY_SIDE;
        if (!poss[p] || (out->exact.hit && part == out->exact.part) ||
            !out->decision_unstable || out->n_alt >= CYLREF_MAX_ALT)
            continue;
        out->alt[out->n_alt++] = (cylref_alt){part, rg[p].lo, rg[p].hi};
    }
}
