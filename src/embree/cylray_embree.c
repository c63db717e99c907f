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
    free(g->sph);
    free(g);
}

/* The geometry made from g's prepared shapes (cylinders or cones: src, their frames in g;
 * spheres: g->sph, src's both NULL): its boxes or leaves, then Embree's user geometry.
 * NULL on failure, g freed and *st saying why (CYLRAY_OK: Embree refused); else *st is
 * CYLRAY_OK. */
static RTCGeometry ceb_finish(ceb *g, RTCDevice device, const ceb_src *src, cylray_status *st)
{
    RTCGeometry geo = NULL;
    int leaves = (g->options & CYLRAY_EMBREE_LEAVES) != 0, why;
    if (leaves) {
        cylray_isa isa = g->k->isa;
        /* 8 with AVX-512 too: behind Embree's BVH a leaf of 16 covers about twice
         * the space of a leaf of 8, is met by more rays, and its wider query does not
         * gain that back (docs/performance.md: leaves of 8 took 5-12 % less time on
         * the molecule, the pipes and the lattice) */
        g->m = isa == CYLRAY_ISA_AVX512 || isa == CYLRAY_ISA_AVX2 ? 8 : 4;
        why = ceb_group_leaves(g, device, src);
    } else if (src->cyl || src->cone) {
        why = ceb_make_boxes(g, src);
    } else {
        /* a sphere's box is tight: one box a sphere */
        g->nprim = g->n;
        g->box = malloc(g->n * sizeof *g->box);
        why = g->box ? 0 : CEB_NO_MEMORY;
        for (size_t i = 0; !why && i < g->n; i++)
            ceb_sphere_box(&g->sph[i], &g->box[i]);
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
    return geo;
fail:
    if (geo)
        rtcReleaseGeometry(geo);
    ceb_free(g);
    return NULL; /* neither the input nor memory: Embree refused */
}

/* The state shared by both shapes' geometries, before their shapes: NULL when out of
 * memory. */
static ceb *ceb_new(size_t n, unsigned options, unsigned flags, const cylray_kernels *k)
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
    g->prep = ceb_alloc_aligned(n * sizeof *g->prep);
    if (!g->prep) {
        ceb_free(g);
        return NULL;
    }
    return g;
}

/* The checks both descriptions share: 1 when the count, options and flags are fine. */
static int desc_ok(RTCDevice device, size_t count, unsigned options, unsigned flags)
{
    return device && count != 0 && count <= 0xffffffffu && !(options & ~CEB_OPTIONS) &&
           !(flags & ~(CEB_KFLAGS | CYLRAY_NORMAL));
}

/* Cone i of desc (radius1 not NULL), read as cylinder i is below. */
static void read_cone(const cylray_embree_desc *desc, size_t i, cylray_cone *c)
{
    const float *p0 = elem(desc->p0, desc->p0_stride, i);
    const float *p1 = elem(desc->p1, desc->p1_stride, i);
    for (int k = 0; k < 3; k++)
        c->p0[k] = p0[k], c->p1[k] = p1[k];
    c->r0 = *(const float *)elem(desc->radius, desc->radius_stride, i);
    c->r1 = *(const float *)elem(desc->radius1, desc->radius1_stride, i);
    c->flags =
        desc->caps ? *(const unsigned *)elem(desc->caps, desc->caps_stride, i) : CYLRAY_CAPPED;
}

RTCGeometry cylray_embree_new_geometry(RTCDevice device, const cylray_embree_desc *desc,
                                       cylray_status *status)
{
    cylray_status st = CYLRAY_EINVAL;
    ceb *g = NULL;
    cylray_cylinder *cyl = NULL;
    cylray_cone *cone = NULL;
    RTCGeometry geo = NULL;
    if (status)
        *status = CYLRAY_EINVAL;
    if (!desc || !desc_ok(device, desc->count, desc->options, desc->flags) || !desc->p0 ||
        !desc->p1 || !desc->radius)
        return NULL;
    size_t n = desc->count;
    st = CYLRAY_ENOMEM;
    g = ceb_new(n, desc->options, desc->flags, desc->kernels);
    /* cones only where radius1 is given: without it the cylinders' path, unchanged */
    if (desc->radius1)
        cone = malloc(n * sizeof *cone);
    else
        cyl = malloc(n * sizeof *cyl);
    if (!g || !(cyl || cone) || !(g->fr = malloc(n * sizeof *g->fr)))
        goto fail_st;
    st = CYLRAY_OK; /* no kernels: not the caller's input */
    if (!g->k)
        goto fail_st;
    for (size_t i = 0; i < n; i++) {
        const float *p0 = elem(desc->p0, desc->p0_stride, i);
        const float *p1 = elem(desc->p1, desc->p1_stride, i);
        if (cone) {
            read_cone(desc, i, &cone[i]);
            if (cylray_prepare_cone(&g->prep[i], &cone[i]) != CYLRAY_OK) {
                st = CYLRAY_EINVAL;
                goto fail_st;
            }
            ceb_frame_init(&g->fr[i], p0, p1, cone[i].r0, cone[i].r1);
            continue;
        }
        float r = *(const float *)elem(desc->radius, desc->radius_stride, i);
        unsigned caps = desc->caps ? *(const unsigned *)elem(desc->caps, desc->caps_stride, i)
                                   : CYLRAY_CAPPED;
        if (cylray_cylinder_from_endpoints(&cyl[i], p0, p1, r, caps) != CYLRAY_OK ||
            cylray_prepare(&g->prep[i], &cyl[i]) != CYLRAY_OK) {
            st = CYLRAY_EINVAL;
            goto fail_st;
        }
        ceb_frame_init(&g->fr[i], p0, p1, r, r);
    }
    geo = ceb_finish(g, device, &(ceb_src){cyl, cone}, &st);
    g = NULL; /* the geometry's now, or freed */
fail_st:
    if (status)
        *status = st;
    free(cyl);
    free(cone);
    ceb_free(g);
    return geo;
}

RTCGeometry cylray_embree_new_spheres(RTCDevice device, const cylray_embree_sphere_desc *desc,
                                      cylray_status *status)
{
    cylray_status st = CYLRAY_EINVAL;
    ceb *g = NULL;
    RTCGeometry geo = NULL;
    if (status)
        *status = CYLRAY_EINVAL;
    if (!desc || !desc_ok(device, desc->count, desc->options, desc->flags) || !desc->center ||
        !desc->radius)
        return NULL;
    size_t n = desc->count;
    st = CYLRAY_ENOMEM;
    g = ceb_new(n, desc->options, desc->flags, desc->kernels);
    if (!g || !(g->sph = malloc(n * sizeof *g->sph)))
        goto fail_st;
    st = CYLRAY_OK;
    if (!g->k)
        goto fail_st;
    for (size_t i = 0; i < n; i++) {
        const float *c = elem(desc->center, desc->center_stride, i);
        cylray_sphere *s = &g->sph[i];
        s->center[0] = c[0], s->center[1] = c[1], s->center[2] = c[2];
        s->radius = *(const float *)elem(desc->radius, desc->radius_stride, i);
        if (cylray_prepare_sphere(&g->prep[i], s) != CYLRAY_OK) {
            st = CYLRAY_EINVAL;
            goto fail_st;
        }
    }
    geo = ceb_finish(g, device, &(ceb_src){NULL, NULL}, &st);
    g = NULL;
fail_st:
    if (status)
        *status = st;
    ceb_free(g);
    return geo;
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

int cylray_embree_is_cylinders(RTCGeometry geometry)
{
    const ceb *g = ceb_of(geometry);
    return g && !g->sph;
}

int cylray_embree_is_spheres(RTCGeometry geometry)
{
    const ceb *g = ceb_of(geometry);
    return g && g->sph;
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
