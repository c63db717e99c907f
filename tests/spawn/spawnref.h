/* SPDX-License-Identifier: MIT */
/* spawnref.h - what the secondary-ray tests and the bench's comparison share: hits of
 * every category, exact distances of a float point from a cylinder's surfaces, new
 * directions on a chosen side, and the test of a self-intersection. */
#ifndef SPAWNREF_H
#define SPAWNREF_H

#include "cylray.h"
#include "gen.h"

#include <stdint.h>

/* The categories: those of gen.h, then two more of this area's own. */
enum {
    SREF_LONG = CYLGEN_COUNT, /* "long": H/R 1e2-1e4, hits anywhere along it */
    SREF_FARCENTER,           /* "far-center": center 1e3-1e6 from the world origin,
                                 radius 1e-4-1e4 */
    SREF_COUNT
};
#define SREF_GROUP 16 /* cases per cylinder */

const char *sref_category_name(int cat);
/* SREF_GROUP cases on one cylinder, a pure function of (cat, seed). */
void sref_group(int cat, uint64_t seed, cylgen_case out[SREF_GROUP]);

/* Exact (binary128) signed distance of x from surface `part` of cyl taken as unbounded:
 * the side's cylinder (rho - R) or a cap's plane (+-z - H), positive outward. */
double sref_sigma(const cylray_cylinder *cyl, const float x[3], int part);
/* Exact distance of x from the part itself: the finite side, or the disc. */
double sref_dist_part(const cylray_cylinder *cyl, const float x[3], int part);
/* The outward unit normal of surface `part` at (or next to) x, in double. */
void sref_normal(const cylray_cylinder *cyl, const float x[3], int part, double n[3]);

/* A direction on the side `side` (+1: along n, -1: against it) of the plane normal to
 * n; one in five grazes the plane (1e-7 to 1e-2 rad, or exactly along it). */
void sref_direction(cylgen_rng *rng, const double n[3], int side, float w[3]);
/* A uniform unit vector. */
void sref_unit(cylgen_rng *rng, double u[3]);
/* A secondary ray's direction w and tmax from a hit with unit outward normal n on a
 * shape of size `size`: a shadow ray to a light at size e^(0..7) in a random direction
 * (tmax 1), else as sref_direction on the side `side` (tmax INFINITY). */
void sref_secondary(cylgen_rng *rng, const double n[3], double size, int shadow, int side,
                    float w[3], float *tmax);

/* 1 when a hit at t (of part hit_part) of the ray x0 + t w, traced after leaving part
 * left_part, is that surface met again at the point left: the same part, nearer than
 * half of the least distance at which the exact ray from x0 can meet it (from inside
 * the side's cylinder: its chord; a plane, or the side from outside: never). */
int sref_self_hit(const cylray_cylinder *cyl, const float x0[3], const float w[3],
                  int left_part, int hit_part, float t);

/* The nested pair: an outer cylinder at a unit-scale place (radius 1e-4 to 1e4, center
 * within 4 R of the world origin, where floats resolve 1e-5 R), a coaxial inner one
 * 1e-5 R inside it (radius and, where capped, half height), and a ray from outside
 * aimed at a point of the outer side. */
void sref_nested(cylgen_rng *rng, cylray_cylinder *out, cylray_cylinder *in, float o[3],
                 float d[3]);
/* A transmitted direction: against n, at least 0.05 rad off the tangent plane, so that
 * the exact ray surely meets a surface 1e-5 R further in. */
void sref_transmitted(cylgen_rng *rng, const double n[3], float w[3]);
/* x lies inside the solid bounded by the side and both end planes (exact). */
int sref_inside_solid(const cylray_cylinder *cyl, const float x[3]);

/* a and b hold the same three floats, bit for bit. */
int sref_same3(const float a[3], const float b[3]);

/* One ray from x along w (tmin 0, tmax inf) by ISA k, no normals: 1 with its t and part
 * on a hit, 0 on a miss. */
int sref_trace1(const cylray_kernels *k, const cylray_prepared *P, const float x[3],
                const float w[3], float *t, int32_t *part);

#endif
