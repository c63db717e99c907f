/* SPDX-License-Identifier: MIT */
/* fuzz_shape.h - the fuzz target's checks for a sphere or a cone: the memory contract
 * and occluded == intersect on every path; no hit for a shape prepare refuses, and
 * prepare refusing exactly what the reference calls invalid; and, with the exact
 * reference (HAVE_CYLREF), every lane's answer within its band on every path, its
 * normal unit and within the angle tolerance, for rays inside the working range. */
#ifndef FUZZ_SHAPE_H
#define FUZZ_SHAPE_H

#include <stddef.h>

#include "fuzz_input.h"

/* Sphere and cone inputs run, and their lanes judged against the exact band (for the
 * summary). */
extern unsigned long fz_sphere_cases, fz_sphere_lanes, fz_cone_cases, fz_cone_lanes;

/* c->sphere or c->cone. 0: all held; 1: `why` says what did not. */
int fz_shape(const fz_case *c, const cylray_kernels *const *isas, int nisa, char *why,
             size_t whylen);

#endif
