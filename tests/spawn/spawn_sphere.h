/* SPDX-License-Identifier: MIT */
/* spawn_sphere.h - what spawn_sphere's modes share: the spheres and rays they are given,
 * the exact geometry they are judged by (the paths: spawn_main.h). */
#ifndef SPAWN_SPHERE_H
#define SPAWN_SPHERE_H

#include "cylray.h"
#include "cylref.h"
#include "spawn_main.h"
#include "spawnref.h"

#include <stdint.h>

enum { K_NEAR, K_FAR, K_TINY, K_HUGE, K_COUNT };

void fail(const char *what, const cylray_sphere *s, const char *fmt, double a, double b);
void make_sphere(cylgen_rng *r, int kind, cylray_sphere *s);
void make_ray(cylgen_rng *r, const cylray_sphere *s, float o[3], float d[3]);
/* Group g's sphere (its kind g % K_COUNT) prepared, and 16 rays at it; 0, and no rays
 * drawn, where the sphere is refused, so that the generator's sequence is the one every
 * mode has always drawn. */
int sphere_rays(cylgen_rng *r, long g, cylray_sphere *s, cylray_prepared *P, float o[16][3],
                float d[16][3]);
int too_soon(const cylray_sphere *s, const float x0[3], const float w[3], float tk);
int side_of(const cylray_sphere *s, const float x[3]);
int w_side(const cylray_sphere *s, const float p[3], const float w[3]);
int double_hit(const cylray_sphere *s, const float o[3], const float d[3], float *t,
               int32_t *part, float n[3]);
uint32_t trace(const cylray_kernels *K, const cylray_prepared *P, int cnt, const float o[][3],
               const float d[][3], const float *tmax, float t[16], int32_t part[16],
               float n[16][3]);

int run_spawns(int side_form); /* spawn_sphere_self.c */
int run_batched(void);         /* spawn_sphere_batched.c */

#endif
