/* SPDX-License-Identifier: MIT */
/* build.h - how ebscene.c and small.c build a scene: a growing scene, its vertices,
 * segments and spheres, and the last step that derives the segments' other forms. */
#ifndef EB_BUILD_H
#define EB_BUILD_H

#include "ebscene.h"

/* A growing scene under construction. */
typedef struct eb_builder {
    eb_scene *s;
    size_t cap_v, cap_f, cap_c, cap_s, cap_r;
    double quantum;
    int failed;
} eb_builder;

/* A vertex at p rounded to the scene's grid: its index. */
uint32_t eb_add_vertex(eb_builder *b, const double p[3]);
/* The segment from vertex v0 to v0 + 1, closed where caps says. */
void eb_add_segment(eb_builder *b, uint32_t v0, unsigned caps);
/* Vertex v's radius, in a tapered scene (every vertex gets one). */
void eb_set_vrad(eb_builder *b, uint32_t v, float r);
/* A sphere at p (rounded to the scene's grid) of radius r. */
void eb_add_sphere(eb_builder *b, const double p[3], float r);
void eb_set3(float o[3], double x, double y, double z);
/* The segments' endpoint forms, cylinders and cones, checked: 0, or -1 (the scene is
 * then to be freed). */
int eb_scene_finish(eb_builder *b);

#endif
