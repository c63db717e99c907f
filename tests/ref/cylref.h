/* SPDX-License-Identifier: MIT */
/* cylref.h - the exact ray/cylinder reference (binary128), written apart from the kernels.
 *
 * Everything here is evaluated in IEEE binary128 (__float128 on x86-64, long double on
 * AArch64) from the float inputs taken as exact binary values, with the same cures as
 * docs/design.md section 2 (cross products, Lagrange's discriminant, the stable quadratic)
 * so that the only rounding left is binary128's own: about 2^-100 relative on t, far
 * below a float ulp, except at a genuine tangency, which the tolerance band covers.
 * It never calls a cylray kernel; it only shares the input types of cylray.h.
 *
 * Semantics are docs/design.md sections 1-3: the smallest t in the closed [tmin, tmax];
 * a capped cylinder is the infinite solid cut by the slab |z| <= H, an open tube keeps
 * the side roots with |z| <= H, an infinite one (half_height = INFINITY) is not cut. */
#ifndef CYLREF_H
#define CYLREF_H

#include "cylray.h"

#ifdef __cplusplus
extern "C" {
#endif

/* One exact answer. t and n are binary128 rounded to double; part is CYLRAY_SIDE,
 * CYLRAY_CAP_LO or CYLRAY_CAP_HI, OR'ed with CYLRAY_BACKFACE for an exit point;
 * n is the outward unit normal, or faces the ray with CYLRAY_FACE_FORWARD. */
typedef struct cylref_hit {
    int hit;
    double t;
    int part;
    double n[3];
} cylref_hit;

/* Returns out->hit (1 or 0), or -1 (and a miss) for a cylinder that describes no solid
 * (NaN/Inf coordinates, zero axis, radius <= 0, half height <= 0 or NaN). A ray with
 * NaN/Inf components or a zero direction misses. flags: CYLRAY_CULL_BACK and
 * CYLRAY_FACE_FORWARD act; NORMAL, REFINE, FAST change nothing in exact arithmetic
 * (the normal is always returned). */
int cylref_intersect(const cylray_cylinder *cyl, const float o[3], const float d[3], float tmin,
                     float tmax, unsigned flags, cylref_hit *out);

/* A result that is legitimately possible for a float kernel, beside the exact one. */
typedef struct cylref_alt {
    int part;          /* CYLRAY_SIDE..CAP_HI | BACKFACE */
    double t_lo, t_hi; /* where its t may lie */
} cylref_alt;

#define CYLREF_MAX_ALT 6

/* The tolerance band: what a float kernel may answer for these float inputs.
 *
 * The inputs (except tmin and tmax) are perturbed by up to +-2 ulps - norm-wise for the
 * vectors (each component by 2 ulps of the vector's largest component: the backward
 * error of float dot and cross products) - and the result re-evaluated exactly: once
 * per input (a finite-difference gradient of t, the normal and every decision margin),
 * at the two vertices of the +-2 ulp box where t is extreme, and at 8 random vertices
 * (22 evaluations in all). The perturbed inputs are the origin relative to the center
 * w = o - c (2 ulps of |w|), d, the axis, the radius and the half height. The center is
 * not moved on its own: moving o and c together changes no t, and a kernel that forms
 * o - c exactly (docs/design.md 2.4) owes accuracy relative to |o - c|; 2 ulps of |c| would
 * excuse any answer for a 1e-4 cylinder at 1e4. A decision (does the ray meet the side,
 * which of entry and exit, side or cap, inside [tmin, tmax]?) is unstable when its
 * margin can change sign inside the box, or when the two t values it compares are
 * within 4 float ulps; every combination of the unstable decisions is then replayed.
 *
 *   exact             the exact answer
 *   t_lo, t_hi        range of t for the exact outcome over the box (hits only)
 *   decision_unstable hit_unstable || part_unstable
 *   hit_unstable      hit and miss are both possible
 *   part_unstable     more than one part (or front/back) is possible among hits
 *   alt[]             every possible hit outcome other than the exact one, with its t range
 *   n_spread          radians: how far the exact outcome's normal turns over the box
 *   evals             exact evaluations spent */
typedef struct cylref_band {
    cylref_hit exact;
    double t_lo, t_hi;
    int decision_unstable;
    int hit_unstable, part_unstable;
    int n_alt;
    cylref_alt alt[CYLREF_MAX_ALT];
    double n_spread;
    int evals;
} cylref_band;

void cylref_band_eval(const cylray_cylinder *cyl, const float o[3], const float d[3],
                      float tmin, float tmax, unsigned flags, cylref_band *out);

/* |t - exact| in float ulps at `exact` (the float spacing at |exact|; 2^-149 at 0). */
double cylref_ulps(float t, double exact);
/* Float ulps by which t lies outside [b->t_lo, b->t_hi]; 0 inside, INFINITY when the
 * exact answer is a miss. */
double cylref_ulps_beyond(float t, const cylref_band *b);

/* Judges one kernel answer against the band. hit: the kernel hit; part and t are
 * its outputs (ignored on a miss). Returns 0 when the outcome (hit/miss and part) is
 * allowed, 1 for an unexcused hit/miss disagreement, 2 for an unexcused part
 * disagreement. *ulps_beyond gets the t error beyond the band of the matching outcome
 * (0 for misses). */
int cylref_judge(const cylref_band *b, int hit, int part, float t, double *ulps_beyond);

/* The angle in radians between a float normal and the exact one (NaN-safe: a NaN or
 * zero normal gives INFINITY). */
double cylref_angle(const float n[3], const double exact[3]);

/* Float ulp at |x| (the spacing of floats there), in double. */
double cylref_float_ulp(double x);

/* Another shape's reference, declared from its row (prefix, shape type), with the
 * cylinder's answer, band and judge types so that one checker judges every shape:
 *   prefix_valid(s)         1 when cylray_prepare_<shape> must accept s
 *   prefix_intersect(...)   the exact answer: returns out->hit, or -1 (and a miss) for
 *                           a shape prefix_valid refuses
 *   prefix_band_eval(...)   the tolerance band, as cylref_band_eval's
 *   prefix_judge(...)       as cylref_judge
 * Each shape's header says what its validity, answer and band are. */
#define CYLREF_SHAPE_DECLARE(prefix, shape_t)                                                  \
    int prefix##_valid(const shape_t *s);                                                      \
    int prefix##_intersect(const shape_t *s, const float o[3], const float d[3], float tmin,   \
                           float tmax, unsigned flags, cylref_hit *out);                       \
    void prefix##_band_eval(const shape_t *s, const float o[3], const float d[3], float tmin,  \
                            float tmax, unsigned flags, cylref_band *out);                     \
    int prefix##_judge(const cylref_band *b, int hit, int part, float t, double *ulps_beyond)

#ifdef __cplusplus
}
#endif

#endif /* CYLREF_H */
