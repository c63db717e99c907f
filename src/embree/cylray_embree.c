/* SPDX-License-Identifier: MIT */
/* cylray_embree.c - cylray's cylinders, cones and spheres as an Embree 3 or 4 user geometry: the
 * public calls, a geometry made from its description and its options. The rest of src/embree/: the
 * boxes (boxes.c), the grouping into leaves (group.c), the callbacks (single.c,
 * leaves.c), hit records and filters (hit.h, filter.c), secondary rays (spawn.c); what
 * depends on Embree's API version is in rtc.h alone. */
#include "ceb.h"

#include <stdlib.h>

static void prim_bounds(const struct RTCBoundsFunctionArguments *a)
{
    const ceb *g = a->geometryUserPtr;
    *a->bounds_o = g->box[a->primID];
}

/* ---- the public calls ----------------------------------------------------------- */

static const void *elem(const void *base, size_t stride, size_t i)
{
    return (const char *)base + stride * i;
}

static void ceb_free(ceb *g)
{
    if (!g)
        return;
    g->magic = 0;
    free(g->prep);
    free(g->fr);
    free(g->prim_cyl);
    free(g->prim_piece);
    free(g->box);
    free(g->leaves);
    free(g->elems);
    free(g);
}

/* The geometry made from g's prepared shapes and their frames: its boxes or leaves, then
 * Embree's user geometry. NULL on failure, g freed and *st saying why (CYLRAY_OK:
 * Embree refused); else *st is CYLRAY_OK. */
static RTCGeometry ceb_finish(ceb *g, RTCDevice device, cylray_status *st)
{
    RTCGeometry geo = NULL;
    int leaves = (g->options & CYLRAY_EMBREE_LEAVES) != 0, why;
    /* A leaf's box cannot be split: a long tilted shape in one leaves it mostly empty,
     * met by rays that pass far from every shape in it (leaves took 4-7.5x the split
     * boxes' time on the far tapered rods), so such a geometry takes split boxes
     * unless the caller asked for no splitting. */
    if (leaves && !(g->options & CYLRAY_EMBREE_NO_SPLIT) && ceb_would_split(g)) {
        g->options &= ~CYLRAY_EMBREE_LEAVES;
        leaves = 0;
    }
    if (leaves) {
        cylray_isa isa = g->k->isa;
        /* 8 with AVX-512 too: behind Embree's BVH a leaf of 16 covers about twice
         * the space of a leaf of 8, is met by more rays, and its wider query does not
         * gain that back (docs/performance.md: leaves of 8 took 5-12 % less time on
         * the molecule, the pipes and the lattice) */
        g->m = isa == CYLRAY_ISA_AVX512 || isa == CYLRAY_ISA_AVX2 ? 8 : 4;
        why = ceb_group_leaves(g, device);
    } else {
        why = ceb_make_boxes(g);
    }
    *st = why == CEB_BAD_INPUT   ? CYLRAY_EINVAL
          : why == CEB_NO_MEMORY ? CYLRAY_ENOMEM
                                 : CYLRAY_OK;
    if (why) {
        ceb_free(g);
        return NULL;
    }
    geo = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
    if (!geo)
        goto fail;
    g->geom = geo;
    rtcSetGeometryUserPrimitiveCount(geo, (unsigned)g->nprim);
    rtcSetGeometryUserData(geo, g);
    rtcSetGeometryBoundsFunction(geo, prim_bounds, NULL);
    if (leaves) {
        rtcSetGeometryIntersectFunction(geo, ceb_leaf_intersect(g->m));
        rtcSetGeometryOccludedFunction(geo, ceb_leaf_occluded(g->m));
    } else {
        rtcSetGeometryIntersectFunction(geo, ceb_single_intersect);
        rtcSetGeometryOccludedFunction(geo, ceb_single_occluded);
    }
    if (rtcGetDeviceError(device) != RTC_ERROR_NONE)
        goto fail;
    if (!g->sphere_test) { /* no query reads them */
        free(g->elems);
        g->elems = NULL;
    }
    return geo;
fail:
    if (geo)
        rtcReleaseGeometry(geo);
    ceb_free(g);
    return NULL; /* neither the input nor memory: Embree refused */
}

/* A geometry of n shapes of kind sh, their elements not yet read: NULL when out of
 * memory. */
static ceb *ceb_new(size_t n, const ceb_shape *sh, unsigned options, unsigned flags,
                    const cylray_kernels *k)
{
    ceb *g = calloc(1, sizeof *g);
    if (!g)
        return NULL;
    g->magic = CEB_MAGIC;
    g->k = k ? k : cylray_kernels_best();
    g->options = options;
    g->iflags = CYLRAY_NORMAL | (flags & CEB_KFLAGS);
    g->oflags = flags & CEB_KFLAGS;
    g->n = n;
    g->shape = sh;
    g->prep = ceb_alloc_aligned(n * sizeof *g->prep);
    g->elems = malloc(n * sh->size);
    if (!g->prep || !g->elems) {
        ceb_free(g);
        return NULL;
    }
    g->sphere_test = sh->sphere_test ? g->elems : NULL;
    return g;
}

/* The geometry of g (NULL: out of memory), its elements read: each prepared, with its
 * frame when the shape has one, then ceb_finish. g is the geometry's now, or freed;
 * *status (when not NULL) says why there is none, CYLRAY_OK when there is. */
static RTCGeometry ceb_build(ceb *g, RTCDevice device, cylray_status *status)
{
    cylray_status st = CYLRAY_ENOMEM;
    RTCGeometry geo = NULL;
    if (!g || (g->shape->frame && !(g->fr = malloc(g->n * sizeof *g->fr))))
        goto done;
    st = CYLRAY_OK; /* no kernels: not the caller's input */
    if (!g->k)
        goto done;
    for (size_t i = 0; i < g->n; i++) {
        const void *e = ceb_elem(g, i);
        if (g->shape->prepare(&g->prep[i], e) != CYLRAY_OK) {
            st = CYLRAY_EINVAL;
            goto done;
        }
        if (g->fr)
            g->shape->frame(&g->fr[i], e);
    }
    geo = ceb_finish(g, device, &st);
    g = NULL; /* the geometry's now, or freed */
done:
    if (status)
        *status = st;
    ceb_free(g);
    return geo;
}

/* The checks both descriptions share: 1 when the count, options and flags are fine. */
static int desc_ok(RTCDevice device, size_t count, unsigned options, unsigned flags)
{
    return device && count != 0 && count <= 0xffffffffu && !(options & ~CEB_OPTIONS) &&
           !(flags & ~(CEB_KFLAGS | CYLRAY_NORMAL));
}

/* Cylinder or cone i of desc: a cylinder's r1 is its r0. */
static void read_cone(const cylray_embree_desc *desc, size_t i, cylray_cone *c)
{
    const float *p0 = elem(desc->p0, desc->p0_stride, i);
    const float *p1 = elem(desc->p1, desc->p1_stride, i);
    for (int k = 0; k < 3; k++)
        c->p0[k] = p0[k], c->p1[k] = p1[k];
    c->r0 = *(const float *)elem(desc->radius, desc->radius_stride, i);
    c->r1 =
        desc->radius1 ? *(const float *)elem(desc->radius1, desc->radius1_stride, i) : c->r0;
    c->flags =
        desc->caps ? *(const unsigned *)elem(desc->caps, desc->caps_stride, i) : CYLRAY_CAPPED;
}

RTCGeometry cylray_embree_new_geometry(RTCDevice device, const cylray_embree_desc *desc,
                                       cylray_status *status)
{
    if (status)
        *status = CYLRAY_EINVAL;
    if (!desc || !desc_ok(device, desc->count, desc->options, desc->flags) || !desc->p0 ||
        !desc->p1 || !desc->radius)
        return NULL;
    /* cones only where radius1 is given: without it cylinders, as cylray_prepare makes them */
    const ceb_shape *sh = desc->radius1 ? &ceb_cones : &ceb_cylinders;
    ceb *g = ceb_new(desc->count, sh, desc->options, desc->flags, desc->kernels);
    for (size_t i = 0; g && i < g->n; i++)
        read_cone(desc, i, (cylray_cone *)g->elems + i);
    return ceb_build(g, device, status);
}

RTCGeometry cylray_embree_new_spheres(RTCDevice device, const cylray_embree_sphere_desc *desc,
                                      cylray_status *status)
{
    if (status)
        *status = CYLRAY_EINVAL;
    if (!desc || !desc_ok(device, desc->count, desc->options, desc->flags) || !desc->center ||
        !desc->radius)
        return NULL;
    ceb *g = ceb_new(desc->count, &ceb_spheres, desc->options, desc->flags, desc->kernels);
    for (size_t i = 0; g && i < g->n; i++) {
        const float *c = elem(desc->center, desc->center_stride, i);
        cylray_sphere *s = (cylray_sphere *)g->elems + i;
        s->center[0] = c[0], s->center[1] = c[1], s->center[2] = c[2];
        s->radius = *(const float *)elem(desc->radius, desc->radius_stride, i);
    }
    return ceb_build(g, device, status);
}

ceb *ceb_of(RTCGeometry geometry)
{
    if (!geometry)
        return NULL;
    ceb *g = rtcGetGeometryUserData(geometry);
    return g && g->magic == CEB_MAGIC && g->geom == geometry ? g : NULL;
}

void cylray_embree_release_geometry(RTCGeometry geometry)
{
    ceb *g = ceb_of(geometry);
    if (!geometry)
        return;
    rtcReleaseGeometry(geometry);
    ceb_free(g);
}

/* cylinders or cones: what cylray_embree_new_geometry makes */
int cylray_embree_is_cylinders(RTCGeometry geometry)
{
    const ceb *g = ceb_of(geometry);
    return g && (g->shape == &ceb_cylinders || g->shape == &ceb_cones);
}

int cylray_embree_is_spheres(RTCGeometry geometry)
{
    const ceb *g = ceb_of(geometry);
    return g && g->shape == &ceb_spheres;
}

size_t cylray_embree_primitives(RTCGeometry geometry)
{
    const ceb *g = ceb_of(geometry);
    return g ? g->nprim : 0;
}

unsigned cylray_embree_leaf_size(RTCGeometry geometry)
{
    const ceb *g = ceb_of(geometry);
    return g && (g->options & CYLRAY_EMBREE_LEAVES) ? (unsigned)g->m : 0u;
}

const cylray_prepared *cylray_embree_cylinder(RTCGeometry geometry, unsigned primID)
{
    const ceb *g = ceb_of(geometry);
    return g && primID < g->n ? &g->prep[primID] : NULL;
}
