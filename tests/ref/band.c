/* SPDX-License-Identifier: MIT */
/* band.c - the tolerance band: which answers a float kernel may give for these float
 * inputs, and where their t may lie, from exact evaluations of perturbed inputs.
 *
 * Linearisation does the main work: one evaluation per input moved by 2 ulps gives
 * the change of every margin and t; the sum of their magnitudes bounds the change over
 * the whole +-2 ulp box to first order. A margin whose bound (plus a few ulps of the
 * values it compares) reaches 0 is undecided, and every combination of the undecided
 * margins is replayed through the decision logic. Extra evaluations at the box's
 * vertices (where t is extreme, and random ones) catch what is not linear. */
#include "exact.h"
#include "bandutil.h"

#include "../support/rng.h"

#include <stdint.h>
#include <string.h>

/* The perturbed inputs: the relative position w = o - c, d, the axis, R, H. The center
 * is not moved on its own: t does not change when o and c move together, and a kernel
 * that forms o - c exactly (docs/design.md 2.4) owes accuracy relative to |o - c|, not to
 * |c|. Moving c by 2 of its own ulps would excuse any answer for a 1e-4 cylinder at
 * 1e4 (ulp 1e-3); moving w instead excuses only what float can't resolve there. */
enum { IN_W = 0, IN_D = 3, IN_V = 6, IN_R = 9, IN_H = 10, IN_COUNT = 11 };
#define MAX_ENUM_BITS 14
#define MAX_OUTCOMES 12

static uint64_t fbits(float f)
{
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    return u;
}

typedef struct {
    qin base;
    cylq step[IN_COUNT];
    int n_in; /* IN_COUNT, or IN_H for an infinite cylinder (H is not moved) */
} pert_ctx;

static void perturb(const pert_ctx *c, const signed char k[IN_COUNT], qin *out)
{
    *out = c->base;
    for (int i = 0; i < c->n_in; i++) {
        if (!k[i])
            continue;
        cylq s = c->step[i] * k[i];
        if (i < IN_D)
            out->o[i - IN_W] += s; /* o moves, c stays: w moves */
        else if (i < IN_V)
            out->d[i - IN_D] += s;
        else if (i < IN_R)
            out->v[i - IN_V] += s;
        else if (i == IN_R)
            out->R += s;
        else
            out->H += s;
    }
    if (!(out->R > 0))
        out->R = c->base.R;
    if (!(out->H > 0))
        out->H = c->base.H;
}

typedef struct {
    qout o;
    double lo, hi; /* t range (hits) */
} outcome;

typedef struct {
    outcome v[MAX_OUTCOMES];
    int n;
    int overflow;
} outcome_set;

static int same(qout a, qout b)
{
    return a.hit == b.hit && (!a.hit || a.part == b.part);
}

static void add_outcome(outcome_set *s, qout o, double lo, double hi)
{
    for (int i = 0; i < s->n; i++) {
        if (same(s->v[i].o, o)) {
            if (o.hit) {
                s->v[i].lo = fmin(s->v[i].lo, lo);
                s->v[i].hi = fmax(s->v[i].hi, hi);
            }
            return;
        }
    }
    if (s->n == MAX_OUTCOMES) {
        s->overflow = 1;
        return;
    }
    s->v[s->n].o = o;
    s->v[s->n].lo = o.hit ? lo : NAN;
    s->v[s->n].hi = o.hit ? hi : NAN;
    s->n++;
}

void cylref_band_eval(const cylray_cylinder *cyl, const float o[3], const float d[3],
                      float tmin, float tmax, unsigned flags, cylref_band *out)
{
    memset(out, 0, sizeof *out);
    out->t_lo = out->t_hi = NAN;
    pert_ctx pc;
    if (!cyl || !qin_from_float(&pc.base, cyl, o, d) || tmin != tmin || tmax != tmax)
        return;
    const int cull = (flags & CYLRAY_CULL_BACK) != 0, ff = (flags & CYLRAY_FACE_FORWARD) != 0;

    cylq w[3];
    for (int k = 0; k < 3; k++)
        w[k] = pc.base.o[k] - pc.base.c[k];
    for (int k = 0; k < 3; k++) {
        pc.step[IN_W + k] = ref_vec_step(w);
        pc.step[IN_D + k] = ref_vec_step(pc.base.d);
        pc.step[IN_V + k] = ref_vec_step(pc.base.v);
    }
    pc.step[IN_R] = (cylq)ref_float_ulp(cyl->radius);
    pc.step[IN_H] = isfinite(cyl->half_height) ? (cylq)ref_float_ulp(cyl->half_height) : 0;
    pc.n_in = isfinite(cyl->half_height) ? IN_COUNT : IN_H;

    qrec r0;
    q_eval(&pc.base, tmin, tmax, &r0);
    unsigned char b0[M_COUNT];
    q_bools(&r0, b0);
    const qout x0 = q_decide(&r0, b0, cull);
    out->evals = 1;
    double n0[3] = {0, 0, 0};
    if (x0.hit) {
        out->exact.hit = 1;
        out->exact.t = (double)r0.tp[x0.prim];
        out->exact.part = x0.part;
        q_normal(&r0, x0, ff, n0);
        memcpy(out->exact.n, n0, sizeof n0);
    }

    outcome_set set = {0};
    add_outcome(&set, x0, out->exact.t, out->exact.t);

    double sum_m[M_COUNT] = {0}, sum_t[P_COUNT] = {0}, dt[IN_COUNT] = {0}, nsum = 0, nmax = 0;
    qrec r;
    unsigned char b[M_COUNT];

    /* One input at a time: the gradient. */
    for (int i = 0; i < pc.n_in; i++) {
        signed char k[IN_COUNT] = {0};
        k[i] = 2;
        qin q;
        perturb(&pc, k, &q);
        q_eval(&q, tmin, tmax, &r);
        out->evals++;
        for (int m = 0; m < M_COUNT; m++)
            sum_m[m] += ref_qdiff(r.m[m], r0.m[m]);
        for (int p = 0; p < P_COUNT; p++)
            sum_t[p] += ref_qdiff(r.tp[p], r0.tp[p]);
        if (x0.hit) {
            cylq dd = r.tp[x0.prim] - r0.tp[x0.prim];
            dt[i] = q_isfinite(dd) ? (double)dd : 0;
        }
        q_bools(&r, b);
        qout x = q_decide(&r, b, cull);
        double t = x.hit ? (double)r.tp[x.prim] : NAN;
        add_outcome(&set, x, t, t);
        if (x0.hit && same(x, x0)) {
            double n[3];
            q_normal(&r, x, ff, n);
            nsum += ref_normal_move(n, n0);
        }
    }

    /* Vertices: the two where t is extreme (to first order), then random ones. The
     * random generator is seeded from the inputs, so a band is reproducible. */
    uint64_t seed = 0x63796c72u;
    for (int k = 0; k < 3; k++)
        seed = seed * 0x100000001b3u ^ fbits(o[k]) ^ fbits(d[k]) << 32 ^
               fbits(cyl->center[k]) << 7 ^ fbits(cyl->axis[k]) << 19;
    seed ^= fbits(cyl->radius) << 11 ^ fbits(cyl->half_height) << 29;
    for (int vtx = 0; vtx < 2 + REF_RANDOM_VERTICES; vtx++) {
        signed char k[IN_COUNT] = {0};
        uint64_t bits = rng_splitmix64(&seed);
        for (int i = 0; i < pc.n_in; i++) {
            int s = (bits >> i) & 1 ? 1 : -1;
            if (vtx < 2 && x0.hit)
                s = (dt[i] >= 0 ? 1 : -1) * (vtx == 0 ? 1 : -1);
            k[i] = (signed char)(2 * s);
        }
        qin q;
        perturb(&pc, k, &q);
        q_eval(&q, tmin, tmax, &r);
        out->evals++;
        q_bools(&r, b);
        qout x = q_decide(&r, b, cull);
        double t = x.hit ? (double)r.tp[x.prim] : NAN;
        add_outcome(&set, x, t, t);
        if (x0.hit && same(x, x0)) {
            double n[3];
            q_normal(&r, x, ff, n);
            nmax = fmax(nmax, ref_angle3(n, n0));
        }
    }

    /* The undecided margins, and every answer their combinations give. */
    int undecided[M_COUNT], nu = 0;
    for (int m = 0; m < M_COUNT; m++) {
        if (!r0.mrel[m] || !q_isfinite(r0.m[m]))
            continue;
        if (m == M_NOTPAR && r0.par_exact)
            continue; /* exactly parallel: a tilt puts the side beyond any float range */
        double mag = (double)q_abs(r0.m[m]);
        if (mag <= sum_m[m] + (double)r0.mw[m] || !(sum_m[m] < INFINITY))
            undecided[nu++] = m;
    }
    int enum_bits = nu < MAX_ENUM_BITS ? nu : MAX_ENUM_BITS;
    for (uint32_t combo = 1; combo < (1u << enum_bits); combo++) {
        memcpy(b, b0, sizeof b);
        for (int j = 0; j < enum_bits; j++)
            if (combo >> j & 1)
                b[undecided[j]] = !b[undecided[j]];
        qout x = q_decide(&r0, b, cull);
        double t = x.hit ? (double)r0.tp[x.prim] : NAN;
        add_outcome(&set, x, t, t);
    }

    /* Every hit outcome's t range: what was seen, widened by the linear bound. */
    int hits = 0, misses = 0;
    for (int i = 0; i < set.n; i++) {
        outcome *s = &set.v[i];
        if (!s->o.hit) {
            misses++;
            continue;
        }
        hits++;
        double t = (double)r0.tp[s->o.prim], w = sum_t[s->o.prim];
        if (q_isfinite(r0.tp[s->o.prim])) {
            s->lo = fmin(s->lo, t - w);
            s->hi = fmax(s->hi, t + w);
        }
        ref_band_keep(out, x0.hit && same(s->o, x0), s->o.part, s->lo, s->hi);
    }
    ref_band_decide(out, hits, misses, nu > MAX_ENUM_BITS || set.overflow);
    out->n_spread = fmax(nsum, nmax);
    /* A side's normal is the direction of the point across the axis. A t anywhere in
     * the band (and its 4 ulps of tolerance) puts the point up to |d_perp| dt away from
     * the exact hit, which turns that direction by up to asin(|d_perp| dt / R): on a
     * grazing ray, or one leaving the surface, the band is wide and the samples above,
     * which keep the exact outcome, do not move far along it. */
    if (x0.hit && (x0.part & 0xf) == CYLRAY_SIDE && out->t_lo == out->t_lo) {
        double vv = 0, dv = 0, dd = 0;
        for (int k = 0; k < 3; k++) {
            vv += (double)pc.base.v[k] * (double)pc.base.v[k];
            dv += (double)pc.base.d[k] * (double)pc.base.v[k];
            dd += (double)pc.base.d[k] * (double)pc.base.d[k];
        }
        const double t = out->exact.t,
                     tol = 4 * ref_float_ulp(fmax(fabs(out->t_lo), fabs(out->t_hi)));
        const double dt = fmax(t - out->t_lo, out->t_hi - t) + tol;
        const double dperp = sqrt(fmax(0, dd - dv * dv / vv)), move = dperp * dt;
        const double R = (double)pc.base.R;
        out->n_spread = fmax(out->n_spread, move < R ? asin(move / R) : 3.14159265358979323846);
    }
}

double cylref_ulps(float t, double exact)
{
    double d = fabs((double)t - exact);
    if (d == 0)
        return 0;
    double r = d / ref_float_ulp(exact);
    return r == r ? r : INFINITY;
}

static double beyond(double t, double lo, double hi)
{
    if (t != t || lo != lo || hi != hi)
        return INFINITY;
    if (t < lo)
        return (lo - t) / ref_float_ulp(lo);
    if (t > hi)
        return (t - hi) / ref_float_ulp(hi);
    return 0;
}

double cylref_ulps_beyond(float t, const cylref_band *b)
{
    if (!b->exact.hit)
        return INFINITY;
    return beyond(t, b->t_lo, b->t_hi);
}

int cylref_judge(const cylref_band *b, int hit, int part, float t, double *ulps_beyond)
{
    double ub = 0;
    int verdict = 0;
    if (!hit) {
        verdict = b->exact.hit && !b->hit_unstable;
    } else if (b->exact.hit && part == b->exact.part) {
        ub = cylref_ulps_beyond(t, b);
    } else if (!b->exact.hit && !b->hit_unstable) {
        verdict = 1;
    } else {
        int found = 0;
        for (int i = 0; i < b->n_alt; i++) {
            if (b->alt[i].part == part) {
                double u = beyond(t, b->alt[i].t_lo, b->alt[i].t_hi);
                ub = found ? fmin(ub, u) : u;
                found = 1;
            }
        }
        if (!found)
            verdict = 2;
    }
    if (ulps_beyond)
        *ulps_beyond = ub;
    return verdict;
}

double cylref_angle(const float n[3], const double exact[3])
{
    double a[3] = {n[0], n[1], n[2]};
    double l = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    if (!(l > 0) || !(l < INFINITY))
        return INFINITY;
    return ref_angle3(a, exact);
}
