/* SPDX-License-Identifier: MIT */
/* exact.h - the exact answer for a ray against a whole scene (every cylinder, cone and
 * sphere, nearest first, in binary128: tests/ref's cylinders, cones and spheres). */
#ifndef EB_EXACT_H
#define EB_EXACT_H

#include "cylref.h"
#include "ebscene.h"

#include <cylray_embree.h>

/* A collecting scene: every cylinder's box, so that one traversal lists every cylinder
 * a ray may meet. */
typedef struct eb_ref {
    const eb_scene *s;
    RTCScene collect;
} eb_ref;

int eb_ref_init(eb_ref *r, RTCDevice dev, const eb_scene *s);
void eb_ref_free(eb_ref *r);

/* The exact first hit of shape `id` (an answer's id, ebscene.h: a cylinder through
 * tests/ref, a sphere in binary128 here): 1 with *h, or 0. */
int eb_shape_intersect(const eb_scene *s, uint32_t id, const float o[3], const float d[3],
                       float tmin, float tmax, cylref_hit *h);
/* Its tolerance band, as cylref_band_eval's (tests/ref/cylref.h) for the same +-2 ulp
 * box of the inputs: a sphere's from the box's 128 vertices (o - c, d and the radius
 * each at either end) and its center, where a sphere's t and its hit/miss margin take
 * their extremes; where hit and miss both occur, also the last hit toward each vertex
 * that misses (t there runs to a tangency, or to 0 for an origin on the surface). */
void eb_shape_band(const eb_scene *s, uint32_t id, const float o[3], const float d[3],
                   float tmin, float tmax, cylref_band *b);

/* The exact first hit over the scene: 1 with *id and *h, or 0. */
int eb_ref_closest(const eb_ref *r, const float o[3], const float d[3], float tmin, float tmax,
                   uint32_t *id, cylref_hit *h);

#endif
