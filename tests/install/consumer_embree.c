/* SPDX-License-Identifier: MIT */
/* consumer_embree.c - a renderer's use of an installed cylray_embree: its own struct of
 * rods handed over with byte strides, an Embree scene, one ray, the hit record, a
 * shadow ray from the spawn helper. consumers.py builds it against the installed tree
 * with pkg-config and with CMake; it fails unless the answers worked out below come
 * back. */
#include <cylray_embree.h>

#include <math.h>
#include <stdio.h>

/* Embree 4 takes optional arguments after the ray, Embree 3 a context before it. */
#if CYLRAY_EMBREE_RTC_MAJOR >= 4
#define INTERSECT1(scene, rh) rtcIntersect1(scene, rh, NULL)
#define OCCLUDED1(scene, ray) rtcOccluded1(scene, ray, NULL)
#else
static struct RTCIntersectContext ctx;
#define INTERSECT1(scene, rh) (rtcInitIntersectContext(&ctx), rtcIntersect1(scene, &ctx, rh))
#define OCCLUDED1(scene, ray) (rtcInitIntersectContext(&ctx), rtcOccluded1(scene, &ctx, ray))
#endif

/* The renderer's own record of a rod. */
typedef struct rod {
    float a[3], b[3];
    float radius;
    unsigned caps;
    int material;
} rod;

int main(void)
{
    /* Two rods along z: x = 0 and x = 3, radius 1, z from -2 to 2. */
    const rod rods[2] = {{{0, 0, -2}, {0, 0, 2}, 1.0f, CYLRAY_CAPPED, 7},
                         {{3, 0, -2}, {3, 0, 2}, 1.0f, CYLRAY_CAPPED, 8}};
    RTCDevice dev = rtcNewDevice(NULL);
    cylray_embree_desc d = {.count = 2,
                            .p0 = rods[0].a,
                            .p0_stride = sizeof(rod),
                            .p1 = rods[0].b,
                            .p1_stride = sizeof(rod),
                            .radius = &rods[0].radius,
                            .radius_stride = sizeof(rod),
                            .caps = &rods[0].caps,
                            .caps_stride = sizeof(rod),
                            .options = CYLRAY_EMBREE_SPLIT};
    RTCGeometry geom = cylray_embree_new_geometry(dev, &d, NULL);
    if (!dev || !geom) {
        fprintf(stderr, "consumer_embree: no device or no geometry\n");
        return 1;
    }
    rtcCommitGeometry(geom);
    RTCScene scene = rtcNewScene(dev);
    unsigned id = rtcAttachGeometry(scene, geom);
    rtcCommitScene(scene);

    /* Along -x at y = 0, z = 1 from x = 10: the side of rod 1 at x = 4, t = 6, normal +x,
     * u = 3/4 (z = 1 of -2..2). */
    struct RTCRayHit rh = {
        {10, 0, 1, 0, -1, 0, 0, 0, INFINITY, ~0u, 0, 0},
        {0, 0, 0, 0, 0, RTC_INVALID_GEOMETRY_ID, RTC_INVALID_GEOMETRY_ID, {0}}};
    INTERSECT1(scene, &rh);
    int bad = rh.hit.geomID != id || rh.hit.primID != 1 || fabsf(rh.ray.tfar - 6) > 1e-5f ||
              fabsf(rh.hit.Ng_x - 1) > 1e-6f || fabsf(rh.hit.u - 0.75f) > 1e-6f ||
              !(rh.hit.v >= 0 && rh.hit.v < 1);
    if (bad) {
        fprintf(stderr, "consumer_embree: hit prim %u t %g Ng_x %g u %g v %g\n", rh.hit.primID,
                rh.ray.tfar, rh.hit.Ng_x, rh.hit.u, rh.hit.v);
        return 1;
    }
    float o[3] = {rh.ray.org_x, rh.ray.org_y, rh.ray.org_z};
    float dd[3] = {rh.ray.dir_x, rh.ray.dir_y, rh.ray.dir_z}, w[3] = {-1, 0, 0}, org[3];
    float ng[3] = {rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z};
    if (cylray_embree_spawn_origin(geom, rh.hit.primID, o, dd, rh.ray.tfar, ng, w, org)) {
        fprintf(stderr, "consumer_embree: the spawn helper refused a hit\n");
        return 1;
    }
    /* leaving rod 1 inward, through it: the next hit is its far side at x = 2 */
    struct RTCRayHit s = {
        {org[0], org[1], org[2], 0, w[0], w[1], w[2], 0, INFINITY, ~0u, 0, 0},
        {0, 0, 0, 0, 0, RTC_INVALID_GEOMETRY_ID, RTC_INVALID_GEOMETRY_ID, {0}}};
    INTERSECT1(scene, &s);
    struct RTCRay occ = {org[0], org[1], org[2], 0, w[0], w[1], w[2], 0, INFINITY, ~0u, 0, 0};
    OCCLUDED1(scene, &occ);
    if (s.hit.primID != 1 || fabsf(org[0] + s.ray.tfar * w[0] - 2) > 1e-5f ||
        occ.tfar != -INFINITY) {
        fprintf(stderr, "consumer_embree: secondary ray: prim %u t %g, occluded tfar %g\n",
                s.hit.primID, s.ray.tfar, occ.tfar);
        return 1;
    }
    rtcReleaseScene(scene);
    cylray_embree_release_geometry(geom);
    rtcReleaseDevice(dev);
    printf("consumer_embree: cylray %d.%d.%d with Embree %s (built against %s): hit, record "
           "and spawned ray as expected\n",
           CYLRAY_VERSION_MAJOR, CYLRAY_VERSION_MINOR, CYLRAY_VERSION_PATCH, RTC_VERSION_STRING,
           CYLRAY_EMBREE_RTC_BUILT);
    return 0;
}
