/* SPDX-License-Identifier: MIT */
/* hitcheck.h - is a reported hit geometrically possible? A verifier, not a reference.
 *
 * Given the float inputs and one kernel answer, it evaluates the hit point o + t d in
 * double and checks that it lies on the part the kernel named, within a tolerance that
 * scales with what float arithmetic cannot avoid (see hc_tolerance). It cannot tell
 * whether an earlier hit was missed: that needs the exact reference (tests/ref). It
 * serves the bad-input tests and the fuzzer, where the answer for arbitrary inputs is
 * not known in advance but a false hit must still be caught. */
#ifndef HITCHECK_H
#define HITCHECK_H

#include <stddef.h>
#include <stdint.h>

#include "cylray.h"

/* The cylinder in double: center, unit axis, radius, half height. */
typedef struct hc_cyl {
    double c[3], u[3], R, H;
    int capped; /* end discs are part of the surface (finite H only) */
} hc_cyl;

void hc_from(hc_cyl *g, const cylray_cylinder *cyl);

/* Where a point lies relative to the cylinder: axial coordinate z, distance r from the
 * axis, and the perpendicular part (unnormalised) in p[3]. */
void hc_locate(const hc_cyl *g, const double x[3], double *z, double *r, double p[3]);

/* The position tolerance for a hit at t: 2^-18 (32 float epsilons) times the size of
 * the numbers the kernel handles, |o - c| + |t d| + R: rounding the float t alone moves
 * the point by half an ulp of |t d|, and forming o - c and the shifted origin costs a
 * few ulps of |o - c|. `slack` multiplies it (CYLRAY_FAST uses a larger one). */
double hc_tolerance(const hc_cyl *g, const float o[3], const float d[3], float t, double slack);

/* Returns 0 when the hit is possible; otherwise 1 and a reason in why. n may be NULL
 * (no normal to check). flags: the kernel flags of the call. */
int hc_verify(const cylray_cylinder *cyl, const float o[3], const float d[3], float tmin,
              float tmax, float t, int32_t part, const float *n, unsigned flags, double slack,
              char *why, size_t whylen);

#endif
