/* SPDX-License-Identifier: MIT */
/* sphref.h - the exact ray/sphere answer and its tolerance band, for the error side of
 * the sphere scenarios: binary128 as tests/ref evaluates the cylinder, with the band in
 * tests/ref's form (cylref_band) so that cylref_judge and cylref_ulps judge it. A
 * stand-in, small on purpose, until tests/ref has a sphere of its own. */
#ifndef CYLBENCH_SPHREF_H
#define CYLBENCH_SPHREF_H

#include "cylray.h"
#include "cylref.h"

/* The first hit in the closed [tmin, tmax]: part CYLRAY_SIDE, | CYLRAY_BACKFACE on the
 * way out; the outward normal. Returns out->hit. */
int sphref_intersect(const cylray_sphere *s, const float o[3], const float d[3], float tmin,
                     float tmax, cylref_hit *out);

/* The band: w = o - c and d moved by 2 ulps of their largest component, R by 2 of its
 * ulps, one input at a time and at 8 random vertices of that box; a decision (tangency,
 * either root against tmin or tmax) is unstable when its margin can change sign in the
 * box or the t values it compares lie within 4 float ulps. */
void sphref_band_eval(const cylray_sphere *s, const float o[3], const float d[3], float tmin,
                      float tmax, cylref_band *out);

#endif
