/* SPDX-License-Identifier: MIT */
/* sphgen.h - deterministic stress rays for spheres, as gen.h's for cylinders.
 *
 * Output is a pure function of (category, seed, index) on every platform (only +, -, *,
 * /, sqrt and exact scalings in double), so a seed printed by one tool reproduces in
 * another. The sphere changes every CYLGEN_BATCH cases, so a packet taken at a multiple
 * of its width sees one sphere. */
#ifndef SPHGEN_H
#define SPHGEN_H

#include <stddef.h>
#include <stdint.h>

#include "cylray.h"
#include "gen.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The categories, in a fixed order (names are stable; the order may only grow). */
enum {
    SPHGEN_ORDINARY,     /* "sph-ordinary": from 1.5-10 R at a point within 1.2 R */
    SPHGEN_FAR,          /* "sph-far": origin 1e3-1e6 R from the center */
    SPHGEN_GRAZING,      /* "sph-grazing": closest approach within 1e-7-1e-2 R of R */
    SPHGEN_SURFACE,      /* "sph-surface": origin a float-rounded surface point, tmin 0 */
    SPHGEN_INSIDE,       /* "sph-inside": origin inside */
    SPHGEN_TINY,         /* "sph-tiny": R 1e-4..1e-3, center around 1e4 */
    SPHGEN_HUGE,         /* "sph-huge": R 1e4..1e6, center around 1e5..1e6 */
    SPHGEN_UNNORMALIZED, /* "sph-unnorm": |d| 2^-30..2^30 */
    SPHGEN_CAMERA,       /* "sph-camera": a 4 x 4 pixel block of a pinhole camera */
    SPHGEN_BAD,          /* "sph-bad": NaN/Inf/zero lanes among ordinary ones */
    SPHGEN_SCALED,       /* "sph-scaled": ordinary scenes scaled by 2^+-(21..50), |d| 2^+-20 */
    SPHGEN_COUNT
};

CYLGEN_SHAPE_DECLARE(sphgen, cylray_sphere, sph);

#ifdef __cplusplus
}
#endif

#endif /* SPHGEN_H */
