/* SPDX-License-Identifier: MIT */
/* rays.h - ray sets for the scenarios: SoA storage, cylinder presets and generators. */
#ifndef CYLBENCH_RAYS_H
#define CYLBENCH_RAYS_H

#include "cylray.h"

#include <stddef.h>
#include <stdint.h>

/* Rays in structure-of-arrays form, each array 64-byte aligned. */
typedef struct raysoa {
    size_t n;
    float *ox, *oy, *oz, *dx, *dy, *dz, *tmin, *tmax;
} raysoa;

int raysoa_alloc(raysoa *r, size_t n); /* 0 on success */
void raysoa_free(raysoa *r);
void raysoa_get(const raysoa *r, size_t i, float o[3], float d[3]);

/* 64-byte aligned, zeroed memory; NULL when out of memory. */
void *bench_alloc(size_t bytes);
void bench_free(void *p);

typedef struct rng {
    uint64_t s;
} rng;
double rng_unit(rng *g); /* uniform in [0, 1) */
double rng_range(rng *g, double a, double b);

/* How a ray set is drawn. Each is described where it is generated (rays.c). */
typedef enum ray_kind {
    RK_INCOHERENT, /* random origins a few sizes away, aimed at the cylinder's box */
    RK_CAMERA,     /* a pinhole camera's pixels, 4x4 tiles in ray order */
    RK_SHADOW,     /* from a floor below the cylinder toward a point light */
    RK_MISS_MIX,   /* 90 % misses, 10 % hits, shuffled across lanes */
    RK_HIT_MIX,    /* 90 % hits */
    RK_ALL_MISS,   /* every ray misses even the infinite cylinder */
    RK_ALL_HIT,    /* every ray hits */
    RK_FAR,        /* origins 1e2..1e5 radii away, aimed at the cylinder's box */
    RK_CLUSTER,    /* random rays through a box holding many cylinders */
    RK_VERY_FAR    /* origins 1e4..1e6 radii away, aimed at the solid's box */
} ray_kind;

/* Fills r (already allocated with r->n rays) with rays of that kind for the solid
 * `geom`. For RK_CLUSTER, `geom` is only the centre of the cluster's box, whose half
 * size is `extent`. Rays are drawn in double and rounded once to float. */
void rays_generate(raysoa *r, ray_kind kind, const cylray_cylinder *geom, double extent,
                   rng *g);

/* Presets. The general cylinder's axis and center are arbitrary floats, not a rotation
 * of anything simple; the aligned one has axis +z. `kind` is 0 infinite, 1 open,
 * 2 capped. */
cylray_cylinder cyl_general(int kind);
cylray_cylinder cyl_aligned(int kind);

/* The sphere of the sphere scenarios (center and radius of cyl_general), and the
 * stand-in solid its rays are drawn for: a cylinder of half height R around it, whose
 * box is the sphere's. */
cylray_sphere sph_general(void);
cylray_cylinder sph_box(const cylray_sphere *s);

/* The cones of the cone scenarios, around cyl_general(2)'s axis and over its length,
 * capped at both ends: kind 0 radii 1.0 and 0.4 (a frustum), 1 radii 1.0 and 0 (a tip
 * cone, apex at p1), 2 radii 0.75 and 0.75 + 3 ulps (a near-cylinder). con_box is the
 * stand-in solid their rays are drawn for: cyl_general(2) of the larger radius. */
cylray_cone con_general(int kind);
cylray_cylinder con_box(const cylray_cone *c);

/* Rotates a ray set drawn around cyl_aligned(k) into the frame of cyl_general(k):
 * same local rays, general axis (rounded once). */
void rays_to_general(raysoa *dst, const raysoa *src);

/* Scatters n capped cylinders in a cube of half size `extent` around the origin. */
void cyl_cluster(cylray_cylinder *out, int n, double extent, rng *g);

/* Classifies a ray against a cylinder in double precision; only for drawing scenario
 * mixes (the error side uses the exact reference). 0: misses even the infinite
 * cylinder, 1: misses the finite one, 2: hits. */
int rays_classify(const cylray_cylinder *c, const double o[3], const double d[3], double tmin,
                  double tmax);

#endif
