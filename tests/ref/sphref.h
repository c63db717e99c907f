/* SPDX-License-Identifier: MIT */
/* sphref.h - the exact ray/sphere reference (binary128), written apart from the kernels.
 *
 * The float center, radius, origin and direction are taken as exact binary values and
 * everything is evaluated in binary128 (quad.h) with the cures a float kernel needs too
 * (Lagrange's discriminant A R^2 - |w x d|^2, the stable quadratic), so that the only
 * rounding left is binary128's own, except at a genuine tangency, which the band covers.
 * It shares cylref's answer, band and judge types: a sphere's outcomes are a subset of a
 * cylinder's (CYLRAY_SIDE, with CYLRAY_BACKFACE from inside), so the checker judges both
 * with the same code. */
#ifndef SPHREF_H
#define SPHREF_H

#include "cylref.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The sphere's row (cylref.h):
 *   sphref_valid       center coordinates finite with |x| <= 2^62, radius in
 *                      [2^-60, 2^62]
 *   sphref_intersect   a ray with NaN/Inf origin or direction, a zero direction or a
 *                      NaN tmin/tmax misses. The hit is the smallest t in the closed
 *                      [tmin, tmax] with |o + t d - c| = R; part CYLRAY_SIDE,
 *                      | CYLRAY_BACKFACE when dot(d, n_out) > 0; n the outward unit
 *                      normal, or facing the ray with CYLRAY_FACE_FORWARD;
 *                      CYLRAY_CULL_BACK drops back-face hits (NORMAL, REFINE and FAST
 *                      change nothing in exact arithmetic)
 *   sphref_band_eval   w = o - c moved norm-wise by 2 ulps of its largest component, d
 *                      likewise, R by 2 ulps, re-evaluated exactly (once per input for
 *                      the gradient, at the two vertices where t is extreme and at 8
 *                      random ones); the hit/miss decision (the discriminant) and the
 *                      choice of root (each root against tmin and tmax) are unstable
 *                      when their margins can change sign in that box or lie within 4
 *                      float ulps of the values compared
 *   sphref_judge       the same rules as cylref_judge: 0 the kernel's outcome is
 *                      allowed; 1 an unexcused hit/miss disagreement; 2 an unexcused
 *                      part (front/back) disagreement */
CYLREF_SHAPE_DECLARE(sphref, cylray_sphere);

#ifdef __cplusplus
}
#endif

#endif /* SPHREF_H */
