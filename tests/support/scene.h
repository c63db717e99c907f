/* SPDX-License-Identifier: MIT */
/* scene.h - deterministic batches of ordinary rays around one cylinder, for tests that
 * need many varied lanes (hits from outside, exits from inside, caps, misses, short
 * [tmin, tmax] windows) rather than particular numerical difficulty. The rays' answers
 * are not known here; tests compare paths with each other or check invariants. */
#ifndef SCENE_H
#define SCENE_H

#include <stddef.h>
#include <stdint.h>

#include "cylray.h"
#include "gen.h"
#include "guarded.h"

/* Uniform in [lo, hi), drawn with rng_splitmix64 (rng.h): the same sequence on every
 * platform. */
double scene_uniform(uint64_t *state, double lo, double hi);

/* Fills rays [first, first + n) of b (first + n <= G_MAX) for cylinder c. */
void scene_rays(uint64_t seed, const cylray_cylinder *c, gbatch *b, size_t first, size_t n);

/* A handful of cylinders of every kind: axis-aligned and oblique, infinite, open,
 * capped, small and large. Returns how many (at most SCENE_MAX_CYL). */
#define SCENE_MAX_CYL 12
int scene_cylinders(cylray_cylinder out[SCENE_MAX_CYL]);

#endif
