/* SPDX-License-Identifier: MIT */
/* rcgen.h - deterministic stress rays for round cones, as congen.h's for cones: what a
 * checker of round-cone kernels draws its cases from (judged by rcref.h's band).
 *
 * Output is a pure function of (category, seed, index) on every platform (only +, -, *,
 * /, sqrt and exact scalings in double). The round cone changes every CYLGEN_BATCH
 * cases; its flags (none, CAPPED_LO, CAPPED_HI, both) are drawn with it, closed half the
 * time. */
#ifndef RCGEN_H
#define RCGEN_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>

#include "gen.h"
#include "rcref.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The categories, in a fixed order (names are stable; the order may only grow). */
enum {
    RCGEN_ORDINARY, /* "rc-ordinary" */
    RCGEN_FAR,      /* "rc-far": origin 1e3-1e6 hull sizes away */
    RCGEN_GRAZING,  /* "rc-grazing": tangent to the side or a cap, 2^-23..2^-7 r off */
    RCGEN_SURFACE,  /* "rc-surface": origin a float-rounded point of the side or a cap */
    RCGEN_INSIDE,   /* "rc-inside": origin inside the hull */
    RCGEN_SEAM,     /* "rc-seam": aimed at a seam (a tangent circle), on it or near */
    RCGEN_POINT,    /* "rc-point": a point end, aimed at and near its apex */
    RCGEN_CAPSULE,  /* "rc-capsule": r0 == r1, or a few ulps apart */
    RCGEN_TAPER,    /* "rc-taper": r1 / r0 in 2^-10..2^10 */
    RCGEN_NESTED,   /* "rc-nested": one sphere inside the other, zero length, almost */
    RCGEN_LONG,     /* "rc-long": length 1e4 radii */
    RCGEN_UNNORM,   /* "rc-unnorm": |d| 2^-30..2^30 */
    RCGEN_AXIAL,    /* "rc-axial": along the axis and along generator lines */
    RCGEN_CAMERA,   /* "rc-camera": 4 x 4 pixel blocks */
    RCGEN_BAD,      /* "rc-bad": NaN/Inf/zero/empty lanes among good ones */
    RCGEN_SCALED,   /* "rc-scaled": scenes scaled by 2^+-(21..50), |d| 2^+-20 */
    RCGEN_COUNT
};

CYLGEN_SHAPE_DECLARE(rcgen, rcref_round_cone, rc);

/* A point end, as rc-point's (and the reference's own tests'): the radius at p0 (at_p0) or
 * at p1 made 0, the length *L at least 1.2 times the other radius, so that the point
 * stands out of the other end's sphere. */
static inline void rcgen_point_end(int at_p0, double *r0, double *r1, double *L)
{
    if (at_p0)
        *r0 = 0;
    else
        *r1 = 0;
    *L = fmax(*L, 1.2 * fmax(*r0, *r1));
}

#ifdef __cplusplus
}
#endif

#endif /* RCGEN_H */
