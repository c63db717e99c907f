/* SPDX-License-Identifier: MIT */
/* congen.h - deterministic stress rays for cones, as sphgen.h's for spheres.
 *
 * Output is a pure function of (category, seed, index) on every platform (only +, -, *,
 * /, sqrt and exact scalings in double). The cone changes every CYLGEN_BATCH cases; its
 * cap mode (none, CAPPED_LO, CAPPED_HI, both) is drawn with it. */
#ifndef CONGEN_H
#define CONGEN_H

#include <stddef.h>
#include <stdint.h>

#include "cylray.h"
#include "gen.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The categories, in a fixed order (names are stable; the order may only grow). */
enum {
    CONGEN_ORDINARY, /* "cone-ordinary" */
    CONGEN_FAR,      /* "cone-far": origin 1e3-1e6 radii away */
    CONGEN_GRAZING,  /* "cone-grazing": tangent to the side, 1e-7-1e-2 R off */
    CONGEN_SURFACE,  /* "cone-surface": origin a float-rounded point of the side or a disc */
    CONGEN_INSIDE,   /* "cone-inside" */
    CONGEN_RIM,      /* "cone-rim": aimed at a rim */
    CONGEN_APEX,     /* "cone-apex": tip cones, aimed at and near the apex */
    CONGEN_NEARCYL,  /* "cone-nearcyl": r0 and r1 a few ulps apart */
    CONGEN_FLAT,     /* "cone-flat": length 1e-3-1e-1 of the radius */
    CONGEN_LONG,     /* "cone-long": length 1e4 radii */
    CONGEN_TINY,     /* "cone-tiny": radii 1e-4..1e-3 around 1e4 */
    CONGEN_HUGE,     /* "cone-huge": radii 1e4..1e6 around 1e5..1e6 */
    CONGEN_UNNORM,   /* "cone-unnorm": |d| 2^-30..2^30 */
    CONGEN_AXIAL,    /* "cone-axial": along the axis and along generator lines */
    CONGEN_CAMERA,   /* "cone-camera": 4 x 4 pixel blocks */
    CONGEN_BAD,      /* "cone-bad": NaN/Inf/zero/empty lanes among good ones */
    CONGEN_SCALED,   /* "cone-scaled": scenes scaled by 2^+-(21..50), |d| 2^+-20 */
    CONGEN_TINYEND,  /* "cone-tinyend": one end 2^-40..2^-12 of the other or a tip */
    CONGEN_COUNT
};

CYLGEN_SHAPE_DECLARE(congen, cylray_cone, cone);

/* One random cone of a category (for leaves). */
void congen_cone(int category, cylgen_rng *r, cylray_cone *out);
/* One ray of a category at a given cone. */
void congen_ray(int category, cylgen_rng *r, cylgen_rng *cam, size_t index,
                const cylray_cone *cone, congen_case *out);

#ifdef __cplusplus
}
#endif

#endif /* CONGEN_H */
