/* SPDX-License-Identifier: MIT */
/* test_nomem.c - cylray_embree_new_geometry and cylray_embree_new_spheres when memory
 * runs out: NULL with CYLRAY_ENOMEM, for each of their allocations in turn, in each way
 * of building a geometry (one box a cylinder, split boxes, leaves; the same of cones;
 * one box a sphere, leaves of spheres).
 *
 * The adapter's objects are linked into this program with --wrap for the allocation
 * functions (tests/embree/meson.build), so the wrappers below see the adapter's
 * allocations and none of Embree's: a failure made here is always one the adapter
 * must report, and the k-th allocation fails on the k-th try whatever the allocator. */
#include "cylray_embree.h"
#include "tcheck.h"

#include <errno.h>
#include <stddef.h>
#include <stdlib.h>

void *__real_malloc(size_t size);
void *__real_calloc(size_t n, size_t size);
void *__real_realloc(void *p, size_t size);
void *__real_aligned_alloc(size_t align, size_t size);
int __real_posix_memalign(void **p, size_t align, size_t size);
void *__wrap_malloc(size_t size);
void *__wrap_calloc(size_t n, size_t size);
void *__wrap_realloc(void *p, size_t size);
void *__wrap_aligned_alloc(size_t align, size_t size);
int __wrap_posix_memalign(void **p, size_t align, size_t size);

static long fail_at = -1; /* the allocation (counted from 0) that fails; -1: none */
static long calls;
static int failed;

static int fail_now(void)
{
    if (fail_at < 0 || calls++ != fail_at)
        return 0;
    failed = 1;
    return 1;
}

void *__wrap_malloc(size_t size)
{
    return fail_now() ? NULL : __real_malloc(size);
}

void *__wrap_calloc(size_t n, size_t size)
{
    return fail_now() ? NULL : __real_calloc(n, size);
}

void *__wrap_realloc(void *p, size_t size)
{
    return fail_now() ? NULL : __real_realloc(p, size);
}

void *__wrap_aligned_alloc(size_t align, size_t size)
{
    return fail_now() ? NULL : __real_aligned_alloc(align, size);
}

int __wrap_posix_memalign(void **p, size_t align, size_t size)
{
    return fail_now() ? ENOMEM : __real_posix_memalign(p, align, size);
}

enum { N = 40 };

/* Tilted rods along x, 10 radii long but every fourth 100, for which split boxes are
 * made. */
static void scene(float p0[N][3], float p1[N][3], float radius[N])
{
    for (int i = 0; i < N; i++) {
        float len = i % 4 == 0 ? 10.0f : 1.0f;
        p0[i][0] = (float)i, p0[i][1] = 0.5f * (float)(i % 3), p0[i][2] = 0;
        p1[i][0] = p0[i][0] + 0.6f * len, p1[i][1] = p0[i][1] + 0.5f * len;
        p1[i][2] = p0[i][2] + 0.62f * len;
        radius[i] = 0.1f;
    }
}

/* Fails each of the adapter's allocations in turn until a try makes none fail; returns
 * how many allocations that successful try made. */
static long each_failure(RTCDevice dev, const cylray_embree_desc *d,
                         const cylray_embree_sphere_desc *sd, const char *what)
{
    for (long k = 0;; k++) {
        cylray_status st = CYLRAY_EINVAL;
        calls = 0, failed = 0, fail_at = k;
        RTCGeometry geo = d ? cylray_embree_new_geometry(dev, d, &st)
                            : cylray_embree_new_spheres(dev, sd, &st);
        fail_at = -1;
        if (!geo) {
            CHECK(failed, "%s: NULL with no allocation failed (try %ld)", what, k);
            CHECK(st == CYLRAY_ENOMEM, "%s: allocation %ld failed, status %d, not %d", what, k,
                  (int)st, (int)CYLRAY_ENOMEM);
            if (!failed)
                return -1;
            continue;
        }
        CHECK(!failed, "%s: a geometry although allocation %ld failed", what, k);
        CHECK(st == CYLRAY_OK, "%s: a geometry with status %d", what, (int)st);
        cylray_embree_release_geometry(geo);
        return calls;
    }
}

int main(void)
{
    RTCDevice dev = rtcNewDevice(NULL);
    CHECK(dev != NULL, "no Embree device");
    if (!dev)
        return tc_report("embree-nomem");
    static float p0[N][3], p1[N][3], radius[N];
    scene(p0, p1, radius);
    cylray_embree_desc d = {.count = N,
                            .p0 = p0[0],
                            .p0_stride = sizeof p0[0],
                            .p1 = p1[0],
                            .p1_stride = sizeof p1[0],
                            .radius = radius,
                            .radius_stride = sizeof radius[0]};
    const struct {
        unsigned options;
        const char *what;
        long least; /* allocations the way makes at least */
    } ways[] = {
        {CYLRAY_EMBREE_NO_SPLIT, "one box a cylinder", 5},
        {CYLRAY_EMBREE_SPLIT, "split boxes", 7},
        {CYLRAY_EMBREE_LEAVES | CYLRAY_EMBREE_NO_SPLIT, "leaves", 10},
        {CYLRAY_EMBREE_LEAVES, "leaves declined for long rods", 7},
    };
    for (size_t w = 0; w < sizeof ways / sizeof ways[0]; w++) {
        d.options = ways[w].options;
        long made = each_failure(dev, &d, NULL, ways[w].what);
        CHECK(made >= ways[w].least, "%s: %ld allocations, not the %ld or more expected",
              ways[w].what, made, ways[w].least);
    }
    /* the same rods as cones (radius1 given), narrowing to half their radius at p1,
     * every third a cylinder (r0 == r1) among them */
    static float radius1[N];
    for (int i = 0; i < N; i++)
        radius1[i] = i % 3 == 0 ? radius[i] : 0.5f * radius[i];
    d.radius1 = radius1, d.radius1_stride = sizeof radius1[0];
    const struct {
        unsigned options;
        const char *what;
        long least;
    } cways[] = {
        {CYLRAY_EMBREE_NO_SPLIT, "one box a cone", 5},
        {CYLRAY_EMBREE_SPLIT, "split boxes of cones", 7},
        {CYLRAY_EMBREE_LEAVES | CYLRAY_EMBREE_NO_SPLIT, "leaves of cones", 10},
    };
    for (size_t w = 0; w < sizeof cways / sizeof cways[0]; w++) {
        d.options = cways[w].options;
        long made = each_failure(dev, &d, NULL, cways[w].what);
        CHECK(made >= cways[w].least, "%s: %ld allocations, not the %ld or more expected",
              cways[w].what, made, cways[w].least);
    }
    /* spheres at the rods' first ends, one box a sphere or leaves */
    cylray_embree_sphere_desc sd = {.count = N,
                                    .center = p0[0],
                                    .center_stride = sizeof p0[0],
                                    .radius = radius,
                                    .radius_stride = sizeof radius[0]};
    const struct {
        unsigned options;
        const char *what;
        long least;
    } sways[] = {{0, "one box a sphere", 4}, {CYLRAY_EMBREE_LEAVES, "leaves of spheres", 9}};
    for (size_t w = 0; w < sizeof sways / sizeof sways[0]; w++) {
        sd.options = sways[w].options;
        long made = each_failure(dev, NULL, &sd, sways[w].what);
        CHECK(made >= sways[w].least, "%s: %ld allocations, not the %ld or more expected",
              sways[w].what, made, sways[w].least);
    }
    rtcReleaseDevice(dev);
    return tc_report("embree-nomem");
}
