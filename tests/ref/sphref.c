/* SPDX-License-Identifier: MIT */
/* sphref.c - the exact ray/sphere intersection and its tolerance band.
 *
 * With w = o - c:  A t^2 + 2 B t + C = 0,  A = d.d,  B = w.d,  C = w.w - R^2,
 *                  B^2 - A C = A R^2 - |w x d|^2   (Lagrange's identity),
 * roots q / A and C / q with q = -(B + copysign(sqrt(disc), B)). At the near root
 * d.n_out = -sqrt(disc) / R <= 0 (a front face), at the far root +sqrt(disc) / R
 * (a back face unless tangent). w is exact in binary128 for every valid sphere and
 * realistic origin (a difference of two floats); the rest rounds at 2^-113. */
#include "sphref.h"
#include "bandutil.h"

#include "exact.h"

#include "../support/rng.h"

#include <stdint.h>
#include <string.h>

/* The margins; each is true when >= 0. */
enum {
    S_DISC, /* A R^2 - |w x d|^2: the line meets the sphere */
    S_NGE,  /* near root - tmin */
    S_NLE,  /* tmax - near root */
    S_FGE,  /* far root - tmin */
    S_FLE,  /* tmax - far root */
    S_COUNT
};

typedef struct sin_q {
    cylq w[3], d[3], R;
} sin_q;

typedef struct srec {
    cylq tn, tf;
    cylq m[S_COUNT], mw[S_COUNT];
    cylq w[3], d[3];
} srec;

/* An outcome: 0 miss, 1 the near root (front), 2 the far root (back). */
enum { SO_MISS, SO_NEAR, SO_FAR };

int sphref_valid(const cylray_sphere *s)
{
    if (!s)
        return 0;
    for (int k = 0; k < 3; k++)
        if (!(fabsf(s->center[k]) <= 0x1p62f))
            return 0;
    return s->radius >= 0x1p-60f && s->radius <= 0x1p62f;
}

/* 4 float ulps of the larger of the values a comparison looks at: within that a float
 * kernel's comparison may go either way (as the cylinder reference's margins). */
static cylq widen(cylq mag)
{
    return (cylq)(4 * ref_float_ulp((double)q_abs(mag)));
}

static void s_eval(const sin_q *q, cylq tmin, cylq tmax, srec *r)
{
    memset(r, 0, sizeof *r);
    memcpy(r->w, q->w, sizeof r->w);
    memcpy(r->d, q->d, sizeof r->d);
    const cylq *w = q->w, *d = q->d;
    const cylq x[3] = {w[1] * d[2] - w[2] * d[1], w[2] * d[0] - w[0] * d[2],
                       w[0] * d[1] - w[1] * d[0]};
    const cylq A = ref_dot3(d, d), B = ref_dot3(w, d), RR = q->R * q->R;
    const cylq C = ref_dot3(w, w) - RR, AR2 = A * RR;
    const cylq D = AR2 - ref_dot3(x, x);
    /* sqrt(max(D, 0)): the roots move continuously through a tangency, so that a
     * perturbation making D negative still has a t to compare. */
    const cylq sq = q_sqrt(q_max(D, 0));
    const cylq qq = -(B + q_copysign(sq, B));
    const cylq r1 = qq / A, r2 = qq != 0 ? C / qq : r1;
    r->tn = q_min(r1, r2);
    r->tf = q_max(r1, r2);
    r->m[S_DISC] = D;
    r->mw[S_DISC] = widen(AR2);
    r->m[S_NGE] = r->tn - tmin;
    r->mw[S_NGE] = widen(q_max(q_abs(r->tn), q_abs(tmin)));
    r->m[S_NLE] = tmax - r->tn;
    r->mw[S_NLE] = widen(q_max(q_abs(r->tn), q_abs(tmax)));
    r->m[S_FGE] = r->tf - tmin;
    r->mw[S_FGE] = widen(q_max(q_abs(r->tf), q_abs(tmin)));
    r->m[S_FLE] = tmax - r->tf;
    r->mw[S_FLE] = widen(q_max(q_abs(r->tf), q_abs(tmax)));
}

static int s_decide(const unsigned char b[S_COUNT], int cull)
{
    if (!b[S_DISC])
        return SO_MISS;
    if (b[S_NGE] && b[S_NLE])
        return SO_NEAR;
    if (!cull && b[S_FGE] && b[S_FLE])
        return SO_FAR;
    return SO_MISS;
}

static void s_bools(const srec *r, unsigned char b[S_COUNT])
{
    for (int k = 0; k < S_COUNT; k++)
        b[k] = r->m[k] >= 0;
}

static int s_part(const srec *r, int o)
{
    /* At a tangency both roots are the one point where d.n = 0: a front face. */
    return o == SO_FAR && r->tf != r->tn ? CYLRAY_SIDE | CYLRAY_BACKFACE : CYLRAY_SIDE;
}

static cylq s_t(const srec *r, int o)
{
    return o == SO_NEAR ? r->tn : r->tf;
}

/* The unit normal at outcome o: outward, or facing the ray for a back face with ff. */
static void s_normal(const srec *r, int o, int ff, double n[3])
{
    cylq p[3], t = s_t(r, o);
    for (int k = 0; k < 3; k++)
        p[k] = r->w[k] + t * r->d[k];
    cylq len = q_sqrt(ref_dot3(p, p));
    n[0] = n[1] = n[2] = 0;
    if (!(len > 0))
        return;
    cylq s = (ff && (s_part(r, o) & CYLRAY_BACKFACE)) ? -1 / len : 1 / len;
    for (int k = 0; k < 3; k++)
        n[k] = (double)(p[k] * s);
}

static void s_in(const cylray_sphere *s, const float o[3], const float d[3], sin_q *q)
{
    for (int k = 0; k < 3; k++) {
        q->w[k] = (cylq)o[k] - (cylq)s->center[k];
        q->d[k] = d[k];
    }
    q->R = s->radius;
}

/* The outcome taken, -1 for a miss (REF_INTERSECT_DEFINE's convention). */
static int s_answer(const srec *r, const cylray_sphere *s, unsigned flags)
{
    (void)s;
    unsigned char b[S_COUNT];
    s_bools(r, b);
    const int x = s_decide(b, (flags & CYLRAY_CULL_BACK) != 0);
    return x == SO_MISS ? -1 : x;
}

REF_INTERSECT_DEFINE(sphref, cylray_sphere, sin_q, srec, sphref_valid, s_in, s_eval, s_answer,
                     s_t, s_part, s_normal)

/* ---- the band ----------------------------------------------------------------------- */

enum { IN_W = 0, IN_D = 3, IN_R = 6, IN_COUNT = 7 };

static void s_perturb(const sin_q *base, const cylq step[IN_COUNT],
                      const signed char k[IN_COUNT], sin_q *out)
{
    *out = *base;
    ref_perturb_ray(out->w, out->d, step, k);
    out->R += step[IN_R] * k[IN_R];
    if (!(out->R > 0))
        out->R = base->R;
}

REF_SAMPLE_DEFINE(s_at, sin_q, srec, s_perturb, s_eval)

/* How far the normal at a hit may turn over the box, from the geometry: the ray's line
 * moves sideways by up to db (w by 2 ulps of its largest component in each, d likewise
 * over the distance t |d|, R by 2 ulps), so the impact parameter b = |w x d| / |d| lies
 * in [b - db, b + db], and the hit point's height above the plane through the center
 * across the ray, sqrt(R^2 - b^2), in the matching range. Where the samples above
 * stop hitting (a ray that only just grazes, or a sphere far smaller than the ulps of
 * the ray), they cannot see how far a hit's normal may turn; this bound can. */
static double box_turn(const sin_q *q, double t)
{
    double w[3], d[3], wm = 0, dm = 0, dd = 0, x2 = 0;
    for (int k = 0; k < 3; k++) {
        w[k] = (double)q->w[k];
        d[k] = (double)q->d[k];
        wm = fmax(wm, fabs(w[k]));
        dm = fmax(dm, fabs(d[k]));
        dd += d[k] * d[k];
    }
    for (int k = 0; k < 3; k++) {
        double x = w[(k + 1) % 3] * d[(k + 2) % 3] - w[(k + 2) % 3] * d[(k + 1) % 3];
        x2 += x * x;
    }
    const double R = (double)q->R, b = fmin(R, sqrt(x2 / dd));
    const double db = 2 * sqrt(3.0) * (ref_float_ulp(wm) + fabs(t) * ref_float_ulp(dm)) +
                      2 * ref_float_ulp(R);
    const double h0 = sqrt(R * R - b * b), bl = fmax(0, b - db), bh = fmin(R, b + db);
    const double dh = fmax(h0 - sqrt(R * R - bh * bh), sqrt(R * R - bl * bl) - h0);
    const double chord = sqrt(db * db + dh * dh) / R;
    return 2 * asin(fmin(1, chord / 2));
}

void sphref_band_eval(const cylray_sphere *s, const float o[3], const float d[3], float tmin,
                      float tmax, unsigned flags, cylref_band *out)
{
    if (!ref_band_begin(out, sphref_valid(s), o, d, tmin, tmax))
        return;
    const int cull = (flags & CYLRAY_CULL_BACK) != 0, ff = (flags & CYLRAY_FACE_FORWARD) != 0;
    sin_q base;
    s_in(s, o, d, &base);
    cylq step[IN_COUNT];
    for (int k = 0; k < 3; k++) {
        step[IN_W + k] = ref_vec_step(base.w);
        step[IN_D + k] = ref_vec_step(base.d);
    }
    step[IN_R] = (cylq)ref_float_ulp(s->radius);

    srec r0, r;
    s_eval(&base, tmin, tmax, &r0);
    unsigned char b0[S_COUNT], b[S_COUNT];
    s_bools(&r0, b0);
    const int x0 = s_decide(b0, cull);
    const int p0 = x0 == SO_MISS ? 0 : s_part(&r0, x0);
    out->evals = 1;
    double n0[3] = {0, 0, 0};
    if (x0 != SO_MISS) {
        s_normal(&r0, x0, ff, n0);
        ref_band_exact(out, (double)s_t(&r0, x0), p0, n0);
    }
    ref_set set = {0};
    ref_add(&set, x0 == SO_MISS ? -1 : p0, out->exact.t);

    double sum_m[S_COUNT] = {0}, sum_tn = 0, sum_tf = 0, dt[IN_COUNT] = {0};
    double nsum = 0, nmax = 0;
    for (int i = 0; i < IN_COUNT; i++) {
        signed char k[IN_COUNT] = {0};
        k[i] = 2;
        s_at(&base, step, k, tmin, tmax, &r, out);
        for (int m = 0; m < S_COUNT; m++)
            sum_m[m] += ref_qdiff(r.m[m], r0.m[m]);
        sum_tn += ref_qdiff(r.tn, r0.tn);
        sum_tf += ref_qdiff(r.tf, r0.tf);
        if (x0 != SO_MISS)
            dt[i] = ref_dt(s_t(&r, x0), s_t(&r0, x0));
        s_bools(&r, b);
        int x = s_decide(b, cull);
        int p = x == SO_MISS ? 0 : s_part(&r, x);
        ref_add(&set, x == SO_MISS ? -1 : p, x == SO_MISS ? NAN : (double)s_t(&r, x));
        if (x0 != SO_MISS && x == x0 && p == p0) {
            double n[3];
            s_normal(&r, x, ff, n);
            nsum += ref_normal_move(n, n0);
        }
    }

    /* The two vertices where t is extreme to first order, then random ones seeded from
     * the inputs, so that a band is reproducible. */
    uint64_t seed = 0x73706872u;
    for (int k = 0; k < 3; k++)
        seed = seed * 0x100000001b3u ^ ref_fbits(o[k]) ^ (uint64_t)ref_fbits(d[k]) << 32 ^
               (uint64_t)ref_fbits(s->center[k]) << 7;
    seed ^= (uint64_t)ref_fbits(s->radius) << 11;
    for (int vtx = 0; vtx < 2 + REF_RANDOM_VERTICES; vtx++) {
        signed char k[IN_COUNT];
        uint64_t bits = rng_splitmix64(&seed);
        ref_vertex(k, IN_COUNT, vtx, bits, dt, x0 != SO_MISS);
        s_at(&base, step, k, tmin, tmax, &r, out);
        s_bools(&r, b);
        int x = s_decide(b, cull);
        int p = x == SO_MISS ? 0 : s_part(&r, x);
        ref_add(&set, x == SO_MISS ? -1 : p, x == SO_MISS ? NAN : (double)s_t(&r, x));
        if (x0 != SO_MISS && x == x0 && p == p0) {
            double n[3];
            s_normal(&r, x, ff, n);
            nmax = fmax(nmax, ref_angle3(n, n0));
        }
    }

    /* Every combination of the undecided margins (5 at most: 31 replays). */
    int undecided[S_COUNT], nu = 0;
    for (int m = 0; m < S_COUNT; m++) {
        if (!q_isfinite(r0.m[m]))
            continue; /* an infinite tmin or tmax: that comparison cannot flip */
        double mag = (double)q_abs(r0.m[m]);
        if (mag <= sum_m[m] + (double)r0.mw[m] || !(sum_m[m] < INFINITY))
            undecided[nu++] = m;
    }
    for (uint32_t combo = 1; combo < (1u << nu); combo++) {
        memcpy(b, b0, sizeof b);
        for (int j = 0; j < nu; j++)
            if (combo >> j & 1)
                b[undecided[j]] = !b[undecided[j]];
        int x = s_decide(b, cull);
        /* A replayed far root is a back face even at a tangency: the perturbation
         * that makes the far root the answer also separates the two. */
        int p = x == SO_MISS ? 0 : x == SO_FAR ? CYLRAY_SIDE | CYLRAY_BACKFACE : CYLRAY_SIDE;
        ref_add(&set, x == SO_MISS ? -1 : p, x == SO_MISS ? NAN : (double)s_t(&r0, x));
    }

    /* Each hit outcome widened by the linear bound of the root its part belongs to. */
    for (int i = 0; i < set.n; i++) {
        ref_outcome *x = &set.v[i];
        const int back = (x->part & CYLRAY_BACKFACE) != 0;
        const double t = (double)(back ? r0.tf : r0.tn), w = back ? sum_tf : sum_tn;
        if (x->part >= 0 && q_isfinite(back ? r0.tf : r0.tn)) {
            x->lo = fmin(x->lo, t - w);
            x->hi = fmax(x->hi, t + w);
        }
    }
    ref_band_keep_set(out, &set, x0 != SO_MISS ? p0 : -1);
    out->n_spread = fmax(fmax(nsum, nmax), x0 != SO_MISS ? box_turn(&base, out->exact.t) : 0);
}

int sphref_judge(const cylref_band *b, int hit, int part, float t, double *ulps_beyond)
{
    return cylref_judge(b, hit, part, t, ulps_beyond);
}
