/* SPDX-License-Identifier: MIT */
/* bandutil.h - what the three shapes' references (band.c, sphref.c, conref.c and
 * conref_band.c, and the round cone's rcref.c and rcref_band.c) share: the ray they take,
 * the sequence of their exact answer, and what their bands measure and keep their
 * outcomes with. */
#ifndef CYLREF_BANDUTIL_H
#define CYLREF_BANDUTIL_H

#include "exact.h"
#include "quad.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

/* 1 when the ray can hit anything: o and d given and finite, d not zero, neither end
 * of the interval NaN (an empty interval is a miss the solver finds itself). */
static inline int ref_ray_ok(const float *o, const float *d, float tmin, float tmax)
{
    if (!o || !d || tmin != tmin || tmax != tmax)
        return 0;
    for (int k = 0; k < 3; k++)
        if (!isfinite(o[k]) || !isfinite(d[k]))
            return 0;
    return d[0] != 0 || d[1] != 0 || d[2] != 0;
}

static inline cylq ref_dot3(const cylq a[3], const cylq b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* |x - y| of two margins or t values, INFINITY when not comparable. */
static inline double ref_qdiff(cylq x, cylq y)
{
    if (x == y)
        return 0;
    cylq d = x - y;
    return q_isfinite(d) ? (double)q_abs(d) : INFINITY;
}

static inline uint32_t ref_fbits(float f)
{
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    return u;
}

/* c = a x b, in double. */
static inline void ref_cross3(const double a[3], const double b[3], double c[3])
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

/* The angle between two directions, accurate near 0 and near pi. */
static inline double ref_angle3(const double a[3], const double b[3])
{
    double c[3];
    ref_cross3(a, b, c);
    return atan2(sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]),
                 a[0] * b[0] + a[1] * b[1] + a[2] * b[2]);
}

/* 2 ulps, norm-wise: a float dot or cross product is backward stable relative to the
 * vector's size, not to each component, so a zero component may move as much as the
 * largest one. */
static inline cylq ref_vec_step(const cylq a[3])
{
    cylq m = q_max(q_abs(a[0]), q_max(q_abs(a[1]), q_abs(a[2])));
    return (cylq)ref_float_ulp((double)m);
}

/* A gradient sample's move of the exact outcome's t (t at the sample, t0 at the center);
 * 0 where either is not finite, so that the extreme vertices follow the other inputs. */
static inline double ref_dt(cylq t, cylq t0)
{
    const cylq dd = t - t0;
    return q_isfinite(dd) ? (double)dd : 0;
}

/* The random vertices of the box a band visits after the two where t is extreme. */
#define REF_RANDOM_VERTICES 8

/* The steps (+-2) of n inputs at the box's vertex vtx: for a hit (along, with dt its t's
 * change per input) vertices 0 and 1 are where t is extreme to first order; the others,
 * and all of them for a miss, are drawn from bits. */
static inline void ref_vertex(signed char *k, int n, int vtx, uint64_t bits, const double *dt,
                              int along)
{
    for (int i = 0; i < n; i++) {
        int s = (bits >> i) & 1 ? 1 : -1;
        if (vtx < 2 && along)
            s = (dt[i] >= 0 ? 1 : -1) * (vtx == 0 ? 1 : -1);
        k[i] = (signed char)(2 * s);
    }
}

/* The outcomes a band saw: a part (-1: the miss) and the t range it was seen over. The
 * parts are the side and the two discs, each front or back, and the miss: 7, so the set
 * never fills. */
typedef struct {
    int part;
    double lo, hi;
} ref_outcome;

typedef struct {
    ref_outcome v[7];
    int n;
} ref_set;

static inline void ref_add(ref_set *set, int part, double t)
{
    for (int i = 0; i < set->n; i++) {
        ref_outcome *x = &set->v[i];
        if (x->part == part) {
            if (part >= 0) {
                x->lo = fmin(x->lo, t);
                x->hi = fmax(x->hi, t);
            }
            return;
        }
    }
    if (set->n == (int)(sizeof set->v / sizeof *set->v))
        return;
    ref_outcome *x = &set->v[set->n++];
    x->part = part;
    x->lo = x->hi = part < 0 ? NAN : t;
}

static inline void ref_add_range(ref_set *set, int part, double lo, double hi)
{
    ref_add(set, part, lo);
    ref_add(set, part, hi);
}

/* Moves the ray's inputs of a box's vertex k (steps step): the origin relative to the
 * shape w (inputs 0-2) and d (3-5), every shape's first six; the shape's own follow. */
static inline void ref_perturb_ray(cylq w[3], cylq d[3], const cylq *step, const signed char *k)
{
    for (int i = 0; i < 3; i++) {
        w[i] += step[i] * k[i];
        d[i] += step[3 + i] * k[3 + i];
    }
}

/* 1 when a shape between two ends (the cone, the round cone) has ends and radii its
 * reference takes (cylray.h): every coordinate of the ends within 2^62, each radius 0 or
 * in 2^-60..2^62, not both 0. */
static inline int ref_ends_ok(const float p0[3], const float p1[3], float r0, float r1)
{
    for (int k = 0; k < 3; k++)
        if (!(fabsf(p0[k]) <= 0x1p62f) || !(fabsf(p1[k]) <= 0x1p62f))
            return 0;
    const float r[2] = {r0, r1};
    for (int i = 0; i < 2; i++)
        if (!(r[i] == 0 || (r[i] >= 0x1p-60f && r[i] <= 0x1p62f)))
            return 0;
    return !(r0 == 0 && r1 == 0);
}

/* The inputs of a shape between two ends p0 and p1 (the cone's, the round cone's), in
 * binary128: the origin from the ends' midpoint w, the direction d and the axis a = p1 - p0. */
static inline void ref_axis_in(const float p0[3], const float p1[3], const float o[3],
                               const float d[3], cylq w[3], cylq dq[3], cylq a[3])
{
    for (int k = 0; k < 3; k++) {
        const cylq ctr = ((cylq)p0[k] + (cylq)p1[k]) / 2;
        w[k] = (cylq)o[k] - ctr;
        dq[k] = d[k];
        a[k] = (cylq)p1[k] - (cylq)p0[k];
    }
}

/* The steps of a shape between two ends (ref_axis_in's inputs w, d, a, then r0 and r1:
 * step[REF_AXIS_W..]): w's, d's and a's 2 ulps norm-wise (ref_vec_step), w's grown by an
 * ulp of the midpoint's largest coordinate where the midpoint (p0 + p1) / 2 is not a float
 * (w is o less it); the radii's an ulp each. */
enum {
    REF_AXIS_W = 0,
    REF_AXIS_D = 3,
    REF_AXIS_A = 6,
    REF_AXIS_R0 = 9,
    REF_AXIS_R1 = 10,
    REF_AXIS_COUNT = 11
};
static inline void ref_axis_steps(const float p0[3], const float p1[3], float r0, float r1,
                                  const cylq w[3], const cylq d[3], const cylq a[3],
                                  cylq step[REF_AXIS_COUNT])
{
    int center_float = 1;
    cylq cmax = 0;
    for (int k = 0; k < 3; k++) {
        const cylq ctr = ((cylq)p0[k] + (cylq)p1[k]) / 2;
        center_float &= (cylq)(float)ctr == ctr;
        cmax = q_max(cmax, q_abs(ctr));
    }
    for (int k = 0; k < 3; k++) {
        step[REF_AXIS_W + k] = ref_vec_step(w);
        if (!center_float)
            step[REF_AXIS_W + k] += (cylq)ref_float_ulp((double)cmax);
        step[REF_AXIS_D + k] = ref_vec_step(d);
        step[REF_AXIS_A + k] = ref_vec_step(a);
    }
    step[REF_AXIS_R0] = (cylq)ref_float_ulp(r0);
    step[REF_AXIS_R1] = (cylq)ref_float_ulp(r1);
}

/* A side's quadratic F(t) and its half derivative F1, with the reach S and S1 of the
 * box's inputs at t: what ref_reach_scan samples. */
typedef struct {
    cylq F, F1, S, S1;
} ref_reach;

/* A ray that runs beside a side over a stretch (along a generator line, within the box's
 * reach of the surface) has no isolated roots: wherever |F(t)| <= S(t) some input of the
 * box puts a root at t, to first order. Samples [ta, tb] at 512 points (at(ctx, t, &x));
 * each run of two or more samples within reach is an outcome of the side, facing either
 * way where F1 is within reach of 0 too, unless keep(ctx, lo) (NULL: always) says a
 * candidate sure to be taken comes first; the back face only where back. Isolated roots
 * are runs of one sample at most and keep their own bands. */
static inline void ref_reach_scan(ref_set *set, cylq ta, cylq tb,
                                  void (*at)(const void *ctx, cylq t, ref_reach *x),
                                  int (*keep)(const void *ctx, double lo), const void *ctx,
                                  int back)
{
    enum { N = 512 };
    if (!(ta < tb) || !q_isfinite(ta) || !q_isfinite(tb))
        return;
    const cylq h = (tb - ta) / (N - 1);
    int run = 0, both = 0, fsign = 0;
    cylq first = 0;
    for (int i = 0; i <= N; i++) {
        const cylq t = ta + h * i;
        int in = 0;
        if (i < N) {
            ref_reach x;
            at(ctx, t, &x);
            in = q_abs(x.F) <= x.S;
            if (in) {
                if (!run)
                    first = t, both = 0, fsign = 0;
                both |= q_abs(x.F1) <= x.S1;
                fsign |= x.F1 < 0 ? 1 : 2;
                run++;
            }
        }
        if (!in && run) {
            const double lo = (double)(first - h), hi = (double)t;
            if (run >= 2 && (!keep || keep(ctx, lo))) {
                if (both || (fsign & 1))
                    ref_add_range(set, CYLRAY_SIDE, lo, hi);
                if ((both || (fsign & 2)) && back)
                    ref_add_range(set, CYLRAY_SIDE | CYLRAY_BACKFACE, lo, hi);
            }
            run = 0;
        }
    }
}

/* A shape's band evaluates its exact answer at points of the box: name(base, step, k,
 * tmin, tmax, &r, out) moves base's inputs by k steps (perturb(base, step, k, &q)),
 * evaluates them (eval(&q, tmin, tmax, &r)) and counts the evaluation in the band out;
 * each shape's in_t and rec_t are its own. */
#define REF_SAMPLE_DEFINE(name, in_t, rec_t, perturb, eval)                                    \
    static void name(const in_t *base, const cylq *step, const signed char *k, cylq tmin,      \
                     cylq tmax, rec_t *r, cylref_band *out)                                    \
    {                                                                                          \
        in_t q;                                                                                \
        perturb(base, step, k, &q);                                                            \
        eval(&q, tmin, tmax, r);                                                               \
        out->evals++;                                                                          \
    }

/* |a - b| of two unit normals: the gradient samples' sum of normal moves. */
static inline double ref_normal_move(const double a[3], const double b[3])
{
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                (a[2] - b[2]) * (a[2] - b[2]));
}

/* Keeps a hit outcome's t range in the band: the exact outcome's as t_lo, t_hi, any
 * other as an alternative (past CYLREF_MAX_ALT it is dropped). */
static inline void ref_band_keep(cylref_band *out, int is_exact, int part, double lo, double hi)
{
    if (is_exact) {
        out->t_lo = lo;
        out->t_hi = hi;
    } else if (out->n_alt < CYLREF_MAX_ALT) {
        cylref_alt *a = &out->alt[out->n_alt++];
        a->part = part;
        a->t_lo = lo;
        a->t_hi = hi;
    }
}

/* The band's verdicts on the decisions, from the counts of hit and miss outcomes it
 * kept; unknown: outcomes may have gone unseen, so every decision is unstable. */
static inline void ref_band_decide(cylref_band *out, int hits, int misses, int unknown)
{
    out->hit_unstable = (hits > 0 && misses > 0) || unknown;
    out->part_unstable = hits > 1 || unknown;
    out->decision_unstable = out->hit_unstable || out->part_unstable;
}

/* Starts a band: empty, t's range NaN; returns 0 when there is none to evaluate (a shape
 * its reference refuses, valid 0, or a ray that cannot hit). */
static inline int ref_band_begin(cylref_band *out, int valid, const float *o, const float *d,
                                 float tmin, float tmax)
{
    memset(out, 0, sizeof *out);
    out->t_lo = out->t_hi = NAN;
    return valid && ref_ray_ok(o, d, tmin, tmax);
}

/* The band's exact answer: a hit at t with part and normal n. */
static inline void ref_band_exact(cylref_band *out, double t, int part, const double n[3])
{
    out->exact.hit = 1;
    out->exact.t = t;
    out->exact.part = part;
    memcpy(out->exact.n, n, sizeof out->exact.n);
}

/* Keeps every hit outcome of a band's set (exact_part's as the exact outcome's t range;
 * -1: the exact answer is a miss) and sets the decisions' verdicts from how many hit
 * and miss outcomes there were: a shape whose set holds every outcome its box allows. */
static inline void ref_band_keep_set(cylref_band *out, const ref_set *set, int exact_part)
{
    int hits = 0, misses = 0;
    for (int i = 0; i < set->n; i++) {
        const ref_outcome *x = &set->v[i];
        if (x->part < 0) {
            misses++;
            continue;
        }
        hits++;
        ref_band_keep(out, x->part == exact_part, x->part, x->lo, x->hi);
    }
    ref_band_decide(out, hits, misses, 0);
}

/* A shape's exact answer, prefix_intersect (cylref.h's CYLREF_SHAPE_DECLARE), from its
 * row: valid(shape); in(shape, o, d, &q) the inputs in binary128 (in_t); eval(&q, tmin,
 * tmax, &r) every candidate with its margins (rec_t); decide(&r, shape, flags) the
 * outcome taken, -1 for a miss; and that outcome's t_of(&r, x) (binary128), part_of(&r,
 * x) and normal_of(&r, x, face_forward, n). The band evaluates the same steps over the
 * box, so a shape states them once for both. */
#define REF_INTERSECT_DEFINE(prefix, shape_t, in_t, rec_t, valid, in, eval, decide, t_of,      \
                             part_of, normal_of)                                               \
    int prefix##_intersect(const shape_t *s, const float o[3], const float d[3], float tmin,   \
                           float tmax, unsigned flags, cylref_hit *out)                        \
    {                                                                                          \
        memset(out, 0, sizeof *out);                                                           \
        if (!valid(s))                                                                         \
            return -1;                                                                         \
        if (!ref_ray_ok(o, d, tmin, tmax))                                                     \
            return 0;                                                                          \
        in_t q;                                                                                \
        in(s, o, d, &q);                                                                       \
        rec_t r;                                                                               \
        eval(&q, tmin, tmax, &r);                                                              \
        const int x = decide(&r, s, flags);                                                    \
        if (x < 0)                                                                             \
            return 0;                                                                          \
        out->hit = 1;                                                                          \
        out->t = (double)t_of(&r, x);                                                          \
        out->part = part_of(&r, x);                                                            \
        normal_of(&r, x, (flags & CYLRAY_FACE_FORWARD) != 0, out->n);                          \
        return 1;                                                                              \
    }

/* A shape's band, prefix_band_eval (cylref.h's CYLREF_SHAPE_DECLARE), from its row: a
 * band begun (ref_band_begin, valid(s)) is band(s, o, d, tmin, tmax, vflags, ff, out)'s
 * to fill, vflags the flags its answer reads (the shape's closed ends, s->flags, and the
 * call's culling), ff 1 for CYLRAY_FACE_FORWARD. */
#define REF_BAND_DEFINE(prefix, shape_t, valid, band)                                          \
    void prefix##_band_eval(const shape_t *s, const float o[3], const float d[3], float tmin,  \
                            float tmax, unsigned flags, cylref_band *out)                      \
    {                                                                                          \
        if (!ref_band_begin(out, valid(s), o, d, tmin, tmax))                                  \
            return;                                                                            \
        band(s, o, d, tmin, tmax, s->flags | (flags & CYLRAY_CULL_BACK),                       \
             (flags & CYLRAY_FACE_FORWARD) != 0, out);                                         \
    }

#endif
