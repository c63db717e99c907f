/* SPDX-License-Identifier: MIT */
/* spawn_common.h - what the modes of spawn_test share: the failure report, tracing a
 * group of cases on a path, and the exact checks of a spawned origin's side (the paths
 * and the failure count are every spawn executable's: spawn_main.h). Each mode
 * (spawn_<mode>.c) is one run_<mode>(), returning nonzero when every check held;
 * spawn_test.c's table names them. */
#ifndef SPAWN_COMMON_H
#define SPAWN_COMMON_H

#include "cylray.h"
#include "cylray_internal.h"
#include "cylref.h"
#include "spawn_main.h"
#include "spawnref.h"

#include <stdint.h>

void fail(const char *what, const cylgen_case *c, const char *detail);
uint32_t trace_group(const cylray_kernels *k, const cylray_prepared *P, const cylgen_case *c,
                     cylray_ray16 *ray, cylray_hit16 *hit);
uint32_t trace16(const cylray_kernels *k, int width, const cylray_prepared *P,
                 const float x[][3], const float w[][3], const float *tmax, uint32_t mask,
                 float *t, int32_t *part);
long popcount(uint32_t m);
int cmp(const void *a, const void *b);
long groups_for(long full);
long isa_points(const cylray_kernels *k, const cylray_prepared *P, const cylray_ray16 *ray,
                const cylray_hit16 *hit, uint32_t m, float p[16][3], float err[16]);
long isa_origins(const cylray_kernels *k, const cylray_prepared *P, const cylray_hit16 *hit,
                 uint32_t m, const float p[16][3], const float err[16], const float w[16][3],
                 float x0[16][3]);
unsigned near_surfaces(const cylray_cylinder *cyl, const float p[3], float err, int P);
int strictly_on_side(const cylray_cylinder *cyl, const float p[3], unsigned surf,
                     const float w[3], const float x0[3]);

int run_bounds(void);
int run_self(void);
int run_nested(void);
int run_batched(void);
int run_axis(void);
int run_side(void);
int run_reintersect(void);
int run_round(void);

#endif
