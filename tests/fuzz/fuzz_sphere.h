/* SPDX-License-Identifier: MIT */
/* fuzz_sphere.h - the fuzz target's checks for a sphere: the memory contract and
 * occluded == intersect on every path; no hit for a sphere prepare refuses, and
 * prepare refusing exactly what the reference calls invalid; and, with the exact
 * reference (HAVE_CYLREF), every lane's answer within its band on every path, its
 * normal unit and within the angle tolerance, for rays inside the working range. */
#ifndef FUZZ_SPHERE_H
#define FUZZ_SPHERE_H

#include <stddef.h>

#include "fuzz_input.h"

/* Sphere inputs run, and lanes judged against the exact band (for the summary). */
extern unsigned long fz_sphere_cases, fz_sphere_lanes;

/* 0: all held; 1: `why` says what did not. */
int fz_sphere(const fz_case *c, const cylray_kernels *const *isas, int nisa, char *why,
              size_t whylen);

#endif
