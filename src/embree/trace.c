/* SPDX-License-Identifier: MIT */
/* embree/trace.c - packets traced the way that pays in a scene with user geometry:
 * Embree's packet call for a coherent packet, one ray a call for an incoherent one.
 *
 * Embree (3 and 4) traverses a user geometry's BVH in packets with its chunk traversal:
 * every node is tested against the whole packet, and, unlike the hybrid traversal of its
 * triangles and curves, it never drops to one ray at a time. Rays that no longer
 * travel together visit the union of their nodes, and the geometry is called for one
 * valid lane in most calls. One ray a call then costs less. */
#include "rtc.h"

#include <stdint.h>

/* A packet is coherent when the renderer says so in the query's flags (said_so), or
 * when at least three rays are valid and their directions share one octant (a camera's
 * tile, shadow rays toward one light from nearby points). Bounce rays scatter over the
 * hemisphere and seldom share one. */
static int coherent(const int *valid, int said_so, const float *dx, const float *dy,
                    const float *dz, int n)
{
    if (said_so)
        return 1;
    int count = 0;
    unsigned any = 0, all = 7u;
    for (int j = 0; j < n; j++) {
        if (!valid[j])
            continue;
        const unsigned oct =
            (unsigned)(dx[j] < 0) | (unsigned)(dy[j] < 0) << 1 | (unsigned)(dz[j] < 0) << 2;
        any |= oct, all &= oct, count++;
    }
    return count >= 3 && any == all;
}

/* Lane j of an SoA ray (and hit) of n lanes to a single ray, and back. Embree's SoA
 * layouts are arrays of n per field, in the order of the single ray's fields (rtc.h),
 * so one loop over the fields serves every width. */
static void lane_get(const void *soa, int n, int j, void *one, int fields)
{
    const uint32_t *s = soa;
    uint32_t *o = one;
    for (int f = 0; f < fields; f++)
        o[f] = s[(size_t)f * (size_t)n + (size_t)j];
}

static void lane_put(void *soa, int n, int j, const void *one, int fields)
{
    uint32_t *s = soa;
    const uint32_t *o = one;
    for (int f = 0; f < fields; f++)
        s[(size_t)f * (size_t)n + (size_t)j] = o[f];
}

enum { RAY_WORDS = R_NFIELDS };
_Static_assert(sizeof(struct RTCRay) == RAY_WORDS * 4, "RTCRay: 12 words");
_Static_assert(sizeof(struct RTCHit) >= H_NFIELDS * 4,
               "RTCHit: Ng, u, v, primID, geomID, instID (, instPrimID)");

/* Embree writes a single ray's tfar, and its whole hit record when it finds a hit;
 * the record's input is geomID and instID invalid. So only the ray goes in, and only
 * what Embree wrote comes back. */
static void one_hit_init(struct RTCHit *h)
{
    h->geomID = RTC_INVALID_GEOMETRY_ID;
    for (int l = 0; l < RTC_MAX_INSTANCE_LEVEL_COUNT; l++) {
        h->instID[l] = RTC_INVALID_GEOMETRY_ID;
#if CEB_INST_PRIM
        h->instPrimID[l] = RTC_INVALID_GEOMETRY_ID;
#endif
    }
}

#define CEB_TRACE(N)                                                                           \
    void cylray_embree_intersect##N(const int *valid, RTCScene scene,                          \
                                    CEB_Q_PARAMS_I(struct RTCRayHit##N))                       \
    {                                                                                          \
        if (coherent(valid, CEB_COHERENT(CEB_Q), rayhit->ray.dir_x, rayhit->ray.dir_y,         \
                     rayhit->ray.dir_z, N)) {                                                  \
            CEB_I_N(N, valid, scene, rayhit);                                                  \
            return;                                                                            \
        }                                                                                      \
        for (int j = 0; j < N; j++) {                                                          \
            if (!valid[j])                                                                     \
                continue;                                                                      \
            struct RTCRayHit one;                                                              \
            lane_get(&rayhit->ray, N, j, &one.ray, RAY_WORDS);                                 \
            one_hit_init(&one.hit);                                                            \
            CEB_I_1(scene, &one);                                                              \
            rayhit->ray.tfar[j] = one.ray.tfar;                                                \
            if (one.hit.geomID != RTC_INVALID_GEOMETRY_ID)                                     \
                lane_put(&rayhit->hit, N, j, &one.hit, H_NFIELDS);                             \
        }                                                                                      \
    }                                                                                          \
    void cylray_embree_occluded##N(const int *valid, RTCScene scene,                           \
                                   CEB_Q_PARAMS_O(struct RTCRay##N))                           \
    {                                                                                          \
        if (coherent(valid, CEB_COHERENT(CEB_Q), ray->dir_x, ray->dir_y, ray->dir_z, N)) {     \
            CEB_O_N(N, valid, scene, ray);                                                     \
            return;                                                                            \
        }                                                                                      \
        for (int j = 0; j < N; j++) {                                                          \
            if (!valid[j])                                                                     \
                continue;                                                                      \
            struct RTCRay one;                                                                 \
            lane_get(ray, N, j, &one, RAY_WORDS);                                              \
            CEB_O_1(scene, &one);                                                              \
            ray->tfar[j] = one.tfar;                                                           \
        }                                                                                      \
    }
CEB_TRACE(4)
CEB_TRACE(8)
CEB_TRACE(16)
