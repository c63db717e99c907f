/* SPDX-License-Identifier: MIT */
/* textbook.h - the peer a tracer author would write instead of using cylray: the
 * textbook formulas in one plain loop (naive.c), built per ISA and auto-vectorized. */
#ifndef CYLBENCH_TEXTBOOK_H
#define CYLBENCH_TEXTBOOK_H

#include "cylray.h"

#include <stddef.h>

/* What such a loop precomputes: the axis normalised in float, R^2, 1 / R, the half
 * height in world units (INFINITY: infinite) and which ends are capped. */
typedef struct tb_cylinder {
    float c[3], v[3];
    float rr, inv_r, h;
    unsigned caps;
} tb_cylinder;

void tb_prepare(tb_cylinder *out, const cylray_cylinder *in);

/* A sphere as such a loop takes it: center, R^2 and 1 / R. */
typedef struct tb_sphere {
    float c[3];
    float rr, inv_r;
} tb_sphere;

void tb_prepare_sphere(tb_sphere *out, const cylray_sphere *in);

/* A cone as such a loop takes it: the center (p0 + p1) / 2 and the axis normalised in
 * float, the half height H, the radius at the center rm, the slope k = (r1 - r0) / 2H,
 * 1 / sqrt(1 + k^2), the end radii squared and which ends are capped. */
typedef struct tb_cone {
    float c[3], v[3];
    float h, rm, k, cnrm, rr0, rr1;
    unsigned caps;
} tb_cone;

void tb_prepare_cone(tb_cone *out, const cylray_cone *in);

/* The builds of naive.c: the scalar one (vectorizer off) and one per ISA. */
enum { TB_SCALAR, TB_SSE41, TB_AVX2, TB_AVX512, TB_NEON, TB_COUNT };

/* The cylray stream contract with CYLRAY_NORMAL on a hit (t, the outward normal, part,
 * tmax = t), except that a miss writes too: t = INFINITY, part = CYLRAY_MISS, a
 * meaningless normal, tmax unchanged. Returns the number of hits. */
typedef size_t (*tb_stream_fn)(const tb_cylinder *cy, const cylray_rays *rays,
                               const cylray_hits *hits, size_t n);

typedef size_t (*tb_sphere_fn)(const tb_sphere *sp, const cylray_rays *rays,
                               const cylray_hits *hits, size_t n);

typedef size_t (*tb_cone_fn)(const tb_cone *cn, const cylray_rays *rays,
                             const cylray_hits *hits, size_t n);

/* NULL when that build is absent or this CPU cannot run it. */
tb_stream_fn tb_variant(int v);
tb_sphere_fn tb_sphere_variant(int v);
tb_cone_fn tb_cone_variant(int v);

/* One ray against n spheres one at a time with the textbook formula (the scalar build):
 * the closest hit (t, part, the normal with CYLRAY_NORMAL, lane = its index; ray->tmax
 * = t), or with `occluded` the first. Returns the sphere's index + 1, or 0. */
uint32_t tb_sphere_run_scalar(const tb_sphere *sp, int n, cylray_ray1 *ray, cylray_hit1 *hit,
                              unsigned flags, int occluded);
/* The same for cones (the textbook cone, naive.c). */
uint32_t tb_cone_run_scalar(const tb_cone *cn, int n, cylray_ray1 *ray, cylray_hit1 *hit,
                            unsigned flags, int occluded);
/* "textbook" for the scalar build, "auto-<isa>" for the vectorized ones. */
const char *tb_variant_name(int v);

#endif
