/* SPDX-License-Identifier: MIT */
/* spawn.h - the secondary rays of a frame: a shadow ray to the point light and one
 * diffuse bounce from every primary hit, spawned the way each variant's user would. */
#ifndef EB_SPAWN_H
#define EB_SPAWN_H

#include "geom.h"
#include "trace.h"

/* From the primary hits in `prim` (traced through g), fills shadow and bounce (both
 * allocated with prim->n rays): Embree's curves start at the hit point with Embree's
 * path-tracer epsilon as tnear; cylray's start at cylray_spawn_origin with tnear 0.
 * The bounce directions depend only on the pixel, so every variant draws the same.
 * Returns 1 when the library lacked the spawn helpers and a relative offset stood in. */
int eb_spawn(const eb_geom *g, const eb_rays *prim, eb_rays *shadow, eb_rays *bounce);

/* The unit normal facing the incoming direction d, from a hit's Ng. */
void eb_facing_normal(const float ng[3], const float d[3], float n[3]);

#endif
