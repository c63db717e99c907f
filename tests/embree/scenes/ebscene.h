/* SPDX-License-Identifier: MIT */
/* ebscene.h - the procedural scenes of the Embree comparison: polylines of cylinders of
 * one radius, or of cones whose radius is given at each vertex, and spheres, with a
 * camera and a point light. */
#ifndef EB_SCENE_H
#define EB_SCENE_H

#include "cylray.h"

#include <stddef.h>
#include <stdint.h>

/* Segment s runs from vert[first[s]] to vert[first[s] + 1]. Consecutive segments of a
 * polyline share their joint vertex, as Embree's linear curves expect (a segment with a
 * left neighbour may read the vertex before its first). caps[s] says which ends are
 * closed: CYLRAY_CAPPED_LO at the first vertex, CYLRAY_CAPPED_HI at the second; a
 * polyline is closed only at its two ends. cyl[s] is the same segment in cylray's
 * endpoint form. */
typedef struct eb_scene {
    char name[32];
    size_t nv, ns;
    float (*vert)[3];
    uint32_t *first;
    unsigned *caps;
    cylray_cylinder *cyl;
    float (*p0)[3], (*p1)[3]; /* segment s from p0[s] to p1[s], for cylray_embree */
    float radius;             /* every segment's; in a tapered scene only a scale */
    float *vrad;              /* tapered scenes: each vertex's radius (NULL: radius for all) */
    /* tapered scenes: segment s as a cone (NULL otherwise); cyl[s] is then the cylinder
     * of its larger radius, which holds it */
    cylray_cone *cone;
    size_t nsph;        /* spheres besides the segments (none in the cylinder scenes) */
    cylray_sphere *sph; /* their answers carry EB_SPHERE_BIT with the sphere's index */
    float eye[3], look[3], up[3], fov_deg;
    float light[3];
    float scale; /* a typical size of the scene, for the bounce rays' reach */
} eb_scene;

/* An answer's id: segment s is s, sphere i is EB_SPHERE_BIT | i (the scenes' sphere
 * geometry has geomID EB_SPHERE_GEOM, the segments' 0). */
#define EB_SPHERE_BIT 0x80000000u
#define EB_SPHERE_GEOM 1u

/* The scene names, in the order of eb_scene_make's `which`: the cylinder scenes, then
 * those with spheres (balls: the molecule with its atoms; far-cloud: spheres alone),
 * then the tapered ones (molecule-taper: the molecule's bonds between atoms of three
 * radii; reducers: the pipes, narrowing through short cones; far-taper: the far rods
 * narrowing from end to end). */
enum {
    EB_MOLECULE,
    EB_PIPES,
    EB_FAR_RODS,
    EB_LATTICE,
    EB_BALLS,
    EB_FAR_CLOUD,
    EB_MOLECULE_TAPER,
    EB_REDUCERS,
    EB_FAR_TAPER,
    EB_NSCENES
};
const char *eb_scene_name(int which);
/* Returns the index of a scene name, or -1. */
int eb_scene_find(const char *name);

/* The scenes' draws, and the bounce directions' and the tests' too: splitmix64 from the
 * exact reference's generators (cylgen_splitmix64), so that a seed gives the same scene
 * on every platform. */
typedef struct eb_rng {
    uint64_t s;
} eb_rng;
double eb_unit(eb_rng *g); /* uniform in [0, 1) */
double eb_range(eb_rng *g, double a, double b);

/* Builds scene `which`, the same for a given seed. 0 on success. */
int eb_scene_make(eb_scene *s, int which, uint64_t seed);
/* A scene of n random cylinders of every cap kind, for the agreement test. */
int eb_scene_small(eb_scene *s, size_t n, uint64_t seed);
/* The same with nsph random spheres among them (n may be 0). */
int eb_scene_small_spheres(eb_scene *s, size_t n, size_t nsph, uint64_t seed);
/* n random cones of every cap kind: tips (an end of radius 0), cylinders (r0 == r1)
 * and steep and slender ones among them. */
int eb_scene_small_cones(eb_scene *s, size_t n, uint64_t seed);
void eb_scene_free(eb_scene *s);

#endif
