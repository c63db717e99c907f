/* SPDX-License-Identifier: MIT */
/* geom.h - one scene as an Embree scene, four ways: Embree's own cone curves and sphere
 * points, and cylray's adapter (cylray_embree.h) with one cylinder or sphere a
 * primitive, with split boxes along long tilted cylinders, and with leaves. */
#ifndef EB_GEOM_H
#define EB_GEOM_H

#include "ebscene.h"

#include <cylray_embree.h>

typedef enum eb_variant { EB_NATIVE, EB_SINGLE, EB_SPLIT, EB_LEAF, EB_NVARIANTS } eb_variant;

const char *eb_variant_name(eb_variant v);

struct eb_geom;

typedef struct eb_geom {
    eb_variant variant;
    RTCScene scene;
    const eb_scene *src;
    RTCGeometry cyl; /* the cylray variants' geometry (cylray_embree_new_geometry) */
    RTCGeometry sph; /* and their spheres' (cylray_embree_new_spheres), geomID 1 */
    size_t nprim;    /* Embree's primitives: segments, boxes or leaves, and spheres */
    double build_s;  /* seconds to prepare and to build Embree's BVH */
} eb_geom;

/* The options cylray_embree_new_geometry gets for a cylray variant. */
unsigned eb_variant_options(eb_variant v);
/* OR'ed into every cylray variant's options (cylembree --no-angles); 0 by default. */
extern unsigned eb_cylray_options;
/* The leaf variant's options: leaves of every scene by default (CYLRAY_EMBREE_NO_SPLIT
 * with CYLRAY_EMBREE_LEAVES), so that the tests reach the leaf callbacks on long shapes
 * too; the bench asks for leaves alone, as a user does, and gets split boxes where the
 * adapter declines them. */
extern unsigned eb_leaf_options;

/* The adapter's description of scene s (endpoints, one radius, caps). */
cylray_embree_desc eb_scene_desc(const eb_scene *s, unsigned options, const cylray_kernels *k);

/* The adapter's description of the scene's spheres. */
cylray_embree_sphere_desc eb_sphere_desc(const eb_scene *s, unsigned options,
                                         const cylray_kernels *k);

/* The adapter's geometry that answered `id` (an answer's id, ebscene.h) and its primID
 * there. */
static inline RTCGeometry eb_geom_of(const struct eb_geom *g, uint32_t id, unsigned *prim)
{
    *prim = id & ~EB_SPHERE_BIT;
    return id & EB_SPHERE_BIT ? g->sph : g->cyl;
}

/* An answer's id from Embree's hit record. */
static inline uint32_t eb_hit_id(unsigned geomID, unsigned primID)
{
    return geomID == RTC_INVALID_GEOMETRY_ID ? RTC_INVALID_GEOMETRY_ID
           : geomID == EB_SPHERE_GEOM        ? EB_SPHERE_BIT | primID
                                             : primID;
}

/* Builds the variant with cylray's path k: the segments as geometry 0, the spheres as
 * geometry EB_SPHERE_GEOM (Embree's own: sphere points). 0 on success. */
int eb_geom_build(eb_geom *g, RTCDevice dev, const eb_scene *s, eb_variant v,
                  const cylray_kernels *k);
void eb_geom_free(eb_geom *g);

/* A conservative box around cylinder i (a radius around both end discs, padded by the
 * rounding of the coordinates). */
void eb_cylinder_bounds(const eb_scene *s, uint32_t i, struct RTCBounds *b);
/* The same for shape `id` (an answer's id: a cylinder or a sphere). */
void eb_shape_bounds(const eb_scene *s, uint32_t id, struct RTCBounds *b);

/* One ray for rtcIntersect1, no hit yet. */
static inline struct RTCRayHit eb_rayhit1(const float o[3], const float d[3], float tnear,
                                          float tfar)
{
    struct RTCRayHit rh;
    rh.ray.org_x = o[0], rh.ray.org_y = o[1], rh.ray.org_z = o[2];
    rh.ray.dir_x = d[0], rh.ray.dir_y = d[1], rh.ray.dir_z = d[2];
    rh.ray.tnear = tnear, rh.ray.tfar = tfar, rh.ray.time = 0;
    rh.ray.mask = ~0u, rh.ray.id = 0, rh.ray.flags = 0;
    rh.hit.geomID = rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
    return rh;
}

/* Whether two answers name the same primitive at the same t with the same Ng, to the
 * bit (the geometry's ID is the caller's to compare: an instance renames it). */
static inline int eb_same_hit(const struct RTCRayHit *a, const struct RTCRayHit *b)
{
    return a->hit.primID == b->hit.primID && a->ray.tfar == b->ray.tfar &&
           a->hit.Ng_x == b->hit.Ng_x && a->hit.Ng_y == b->hit.Ng_y &&
           a->hit.Ng_z == b->hit.Ng_z;
}

#endif
