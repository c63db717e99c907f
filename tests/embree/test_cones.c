/* SPDX-License-Identifier: MIT */
/* test_cones.c - what a geometry of cones (cylray_embree_desc.radius1) does besides its
 * answers, which test_agree.c checks (run with "cones"): the descriptions of cones the
 * adapter refuses; cones whose radii agree are the cylinders of a description without
 * radius1 (the same prepared shapes, boxes and leaves); a geometry mask; the geometry
 * in a translated instance, each variant: the same hits as the geometry itself, with
 * instID the instance's. */
#include "agree.h"
#include "geom.h"
#include "trace.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

enum { W = 48, H = 48, NCONE = 300 };

static int passed, failed;

static void report(int bad, const char *what)
{
    printf("%s %s (%d)\n", bad ? "FAIL" : "ok  ", what, bad);
    bad ? failed++ : passed++;
}

/* The refused descriptions (cylray_prepare_cone's rules: both radii 0, a negative or
 * NaN radius at p1) and a tip accepted. */
static int refusals(RTCDevice dev, const eb_scene *s)
{
    cylray_embree_desc d = eb_scene_desc(s, 0, NULL);
    cylray_status st = CYLRAY_OK;
    float zero = 0, neg = -0.5f, nan = NAN;
    int bad = 0;
    d.radius = d.radius1 = &zero, d.radius_stride = d.radius1_stride = 0;
    bad += cylray_embree_new_geometry(dev, &d, &st) != NULL || st != CYLRAY_EINVAL;
    /* r0 the cylinders' radius, the larger one, never 0 */
    d.radius = &s->cyl[0].radius, d.radius_stride = sizeof s->cyl[0];
    d.radius1 = &neg;
    bad += cylray_embree_new_geometry(dev, &d, &st) != NULL || st != CYLRAY_EINVAL;
    d.radius1 = &nan;
    bad += cylray_embree_new_geometry(dev, &d, &st) != NULL || st != CYLRAY_EINVAL;
    d.radius1 = &zero; /* a tip at every p1 */
    RTCGeometry geo = cylray_embree_new_geometry(dev, &d, &st);
    bad += !geo || st != CYLRAY_OK || !cylray_embree_is_cylinders(geo);
    cylray_embree_release_geometry(geo);
    return bad;
}

/* radius1 == radius, variant by variant: what radius1 NULL makes, bit for bit. */
static int equal_radii(RTCDevice dev, const eb_scene *s)
{
    int bad = 0;
    for (int v = EB_SINGLE; v < EB_NVARIANTS; v++) {
        cylray_embree_desc c = eb_scene_desc(s, eb_variant_options((eb_variant)v), NULL);
        c.radius = &s->cyl[0].radius, c.radius_stride = sizeof s->cyl[0];
        c.radius1 = c.radius, c.radius1_stride = c.radius_stride;
        cylray_embree_desc y = c;
        y.radius1 = NULL;
        cylray_status st;
        RTCGeometry gc = cylray_embree_new_geometry(dev, &c, &st),
                    gy = cylray_embree_new_geometry(dev, &y, &st);
        bad += !gc || !gy || cylray_embree_primitives(gc) != cylray_embree_primitives(gy) ||
               cylray_embree_leaf_size(gc) != cylray_embree_leaf_size(gy);
        for (unsigned i = 0; gc && gy && i < s->ns; i++)
            bad += memcmp(cylray_embree_cylinder(gc, i), cylray_embree_cylinder(gy, i),
                          sizeof(cylray_prepared)) != 0;
        cylray_embree_release_geometry(gc);
        cylray_embree_release_geometry(gy);
    }
    return bad;
}

/* The variant's geometry with mask 2: rays of mask 1 miss it, rays of mask 2 get what
 * the geometry with every mask bit gives; then that geometry instanced with a shift of
 * (3, 0, 0): the same hits for origins the shift leaves exact, instID the instance's.
 * *hits counts the rays that hit. */
static int masks_instance(RTCDevice dev, const eb_scene *s, eb_variant v, const eb_rays *r,
                          int *hits)
{
    cylray_embree_desc d = eb_scene_desc(s, eb_variant_options(v), NULL);
    RTCGeometry all = cylray_embree_new_geometry(dev, &d, NULL),
                two = cylray_embree_new_geometry(dev, &d, NULL);
    if (!all || !two)
        return 1;
    rtcSetGeometryMask(all, 0xffffffffu);
    rtcSetGeometryMask(two, 2u);
    unsigned ga;
    RTCScene sa = eb_scene_of(dev, all, &ga), s2 = eb_scene_of(dev, two, NULL);
    unsigned iid = 5; /* not 0: a record that says 0 is told apart */
    RTCScene outer = eb_shifted(dev, sa, &iid);
    int masks = (int)rtcGetDeviceProperty(dev, RTC_DEVICE_PROPERTY_RAY_MASK_SUPPORTED);
    int bad = 0;
    for (size_t i = 0; i < r->n; i++) {
        float o[3], dd[3];
        eb_rays_get(r, i, o, dd);
        struct RTCRayHit want, got;
        eb_trace_mask(sa, o, dd, 1u, &want);
        if (want.hit.geomID == RTC_INVALID_GEOMETRY_ID)
            continue;
        (*hits)++;
        if (masks) {
            eb_trace_mask(s2, o, dd, 1u, &got);
            bad += got.hit.geomID != RTC_INVALID_GEOMETRY_ID;
        }
        eb_trace_mask(s2, o, dd, 2u, &got);
        bad += got.hit.geomID != ga || !eb_same_hit(&got, &want);
        const float os[3] = {o[0] + 3, o[1], o[2]};
        if (os[0] - 3 != o[0])
            continue; /* an origin the shift rounds */
        eb_trace_mask(outer, os, dd, 1u, &got);
        /* the instance's ray is o + 3 - 3 exactly: the same t within the rounding of the
         * transform's arithmetic */
        float t = want.ray.tfar;
        bad += got.hit.geomID != ga || got.hit.primID != want.hit.primID ||
               got.hit.instID[0] != iid ||
               fabsf(got.ray.tfar - t) > 4 * (nextafterf(t, INFINITY) - t);
    }
    rtcReleaseScene(outer);
    rtcReleaseScene(sa);
    rtcReleaseScene(s2);
    cylray_embree_release_geometry(all);
    cylray_embree_release_geometry(two);
    return bad;
}

/* The variant's geometry with and without CYLRAY_EMBREE_NO_ANGLES: the same hits, t,
 * Ng and u to the bit, v = 0 with it. *angled counts the hits whose v is not 0
 * without it. */
static int no_angles(RTCDevice dev, const eb_scene *s, eb_variant v, const eb_rays *r,
                     int *angled)
{
    cylray_embree_desc d = eb_scene_desc(s, eb_variant_options(v), NULL);
    cylray_embree_desc dn = d;
    dn.options |= CYLRAY_EMBREE_NO_ANGLES;
    RTCGeometry ga = cylray_embree_new_geometry(dev, &d, NULL),
                gn = cylray_embree_new_geometry(dev, &dn, NULL);
    if (!ga || !gn)
        return 1;
    RTCScene sa = eb_scene_of(dev, ga, NULL), sn = eb_scene_of(dev, gn, NULL);
    int bad = 0;
    for (size_t i = 0; i < r->n; i++) {
        float o[3], dd[3];
        eb_rays_get(r, i, o, dd);
        struct RTCRayHit want, got;
        eb_trace_mask(sa, o, dd, 0xffffffffu, &want);
        eb_trace_mask(sn, o, dd, 0xffffffffu, &got);
        bad += got.hit.geomID != want.hit.geomID;
        if (want.hit.geomID == RTC_INVALID_GEOMETRY_ID)
            continue;
        *angled += want.hit.v != 0;
        bad += !eb_same_hit(&got, &want) || got.hit.u != want.hit.u || got.hit.v != 0;
    }
    rtcReleaseScene(sa);
    rtcReleaseScene(sn);
    cylray_embree_release_geometry(ga);
    cylray_embree_release_geometry(gn);
    return bad;
}

int main(void)
{
    eb_scene s;
    if (eb_scene_small_cones(&s, NCONE, 12345)) {
        printf("scene failed\n");
        return 1;
    }
    RTCDevice dev = rtcNewDevice(NULL);
    eb_rays r;
    if (!dev || eb_rays_alloc(&r, W * H))
        return 1;
    eb_camera_rays(&r, &s, W, H);
    report(refusals(dev, &s), "refused descriptions of cones, and a tip accepted");
    report(equal_radii(dev, &s), "cones of equal radii are the cylinders, bit for bit");
    for (int v = EB_SINGLE; v < EB_NVARIANTS; v++) {
        int hits = 0, bad = masks_instance(dev, &s, (eb_variant)v, &r, &hits);
        char what[96];
        snprintf(what, sizeof what, "%s: a geometry mask, and an instance (%d hits)",
                 eb_variant_name((eb_variant)v), hits);
        report(bad + (hits == 0), what);
        int angled = 0;
        bad = no_angles(dev, &s, (eb_variant)v, &r, &angled);
        snprintf(what, sizeof what, "%s: no angles, the rest unchanged (%d hits with v)",
                 eb_variant_name((eb_variant)v), angled);
        report(bad + (angled == 0), what);
    }
    eb_rays_free(&r);
    rtcReleaseDevice(dev);
    eb_scene_free(&s);
    printf("%d passed, %d failed\n", passed, failed);
    return failed != 0 || passed == 0;
}
