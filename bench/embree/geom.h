/* SPDX-License-Identifier: MIT */
/* geom.h - one scene as an Embree scene, three ways: Embree's own cone curves, cylray
 * single cylinders as user primitives, and cylray leaves as user primitives. */
#ifndef EB_GEOM_H
#define EB_GEOM_H

#include "ebscene.h"

#include <embree3/rtcore.h>

typedef enum eb_variant { EB_NATIVE, EB_SINGLE, EB_LEAF, EB_NVARIANTS } eb_variant;

/* How the leaf variant groups cylinders: Embree's SAH builder (rtcBuildBVH) cuts them
 * into leaves of at most M, or runs of M along a Morton curve through the centres. */
typedef enum eb_grouping { EB_GROUP_SAH, EB_GROUP_MORTON } eb_grouping;

const char *eb_variant_name(eb_variant v);

typedef struct eb_geom {
    eb_variant variant;
    RTCScene scene;
    const eb_scene *src;
    const cylray_kernels *k;  /* the cylray path the callbacks call */
    cylray_prepared *prep;    /* one per cylinder (the cylray variants) */
    void *leaves;             /* cylray_leafM[nleaves] (the leaf variant) */
    size_t nleaves;
    struct RTCBounds *lbox;   /* a box per leaf: the union of its cylinders' */
    int leaf_m;               /* 4, 8 or 16 */
    double build_s;           /* seconds to prepare and to build Embree's BVH */
    RTCIntersectFunctionN isect; /* the user variants' callbacks, for direct tests */
    RTCOccludedFunctionN occ;
} eb_geom;

/* Builds the variant; leaf_m (4, 8, 16) and how only for EB_LEAF. 0 on success. */
int eb_geom_build(eb_geom *g, RTCDevice dev, const eb_scene *s, eb_variant v, int leaf_m,
                  eb_grouping how, const cylray_kernels *k);
void eb_geom_free(eb_geom *g);

/* The axial parameter of point p on cylinder i, 0 at its first vertex and 1 at its
 * second: what the callbacks report as u, as Embree's curves do. */
float eb_curve_u(const eb_scene *s, uint32_t i, const float p[3]);

/* A conservative box around cylinder i (a radius around both end discs, padded by the
 * rounding of the coordinates). */
void eb_cylinder_bounds(const eb_scene *s, uint32_t i, struct RTCBounds *b);

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

#endif
