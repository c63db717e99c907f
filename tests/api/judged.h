/* SPDX-License-Identifier: MIT */
/* judged.h - the API tests' batch of edge rays through every width and path of every
 * ISA on one prepared shape, each lane judged against the shape's exact band. */
#ifndef JUDGED_H
#define JUDGED_H

#include <stddef.h>

#include "cylref.h"
#include "guarded.h"

/* The shape's exact band (sphref_band_eval, conref_band_eval), behind one signature. */
typedef void (*judged_band_fn)(const void *shape, const float o[3], const float d[3],
                               float tmin, float tmax, unsigned flags, cylref_band *out);

/* Rays b[0..n) through each width and path of every ISA on P; judged against the band
 * of `shape` (non-NULL), or required to miss (NULL: a zeroed prepared struct). The
 * batch repeats its first `distinct` (at most 4) rays, whose bands are evaluated once. */
void judged_rays(const cylray_prepared *P, judged_band_fn band_of, const void *shape,
                 const gbatch *b, size_t n, size_t distinct, const char *what);

/* Fills the batch with n rays repeating the k given ones (o, d, tmin, tmax). */
void judged_fill(gbatch *b, const float (*rays)[8], size_t k, size_t n);

#endif
