/* SPDX-License-Identifier: MIT */
/* embree/ceb.h - what the adapter's files share: a geometry's state, a hit record, and
 * the functions one file gives the others. Names shared between files start with ceb_:
 * they are hidden in the shared library, but a static one links them into the user's
 * program. */
#ifndef CYLRAY_EMBREE_CEB_H
#define CYLRAY_EMBREE_CEB_H

#include "rtc.h"

#include <stdint.h>

#define CEB_MAGIC 0x63656232u /* "ceb2" */
#define CEB_KFLAGS (CYLRAY_CULL_BACK | CYLRAY_FAST | CYLRAY_REFINE)
#define CEB_OPTIONS                                                                            \
    (CYLRAY_EMBREE_LEAVES | CYLRAY_EMBREE_SPLIT | CYLRAY_EMBREE_FILTER |                       \
     CYLRAY_EMBREE_CONTEXT | CYLRAY_EMBREE_NO_SPLIT | CYLRAY_EMBREE_NO_ANGLES)
#if defined(__GNUC__)
#define CEB_NOINLINE __attribute__((noinline))
#else
#define CEB_NOINLINE
#endif

/* Per cylinder or cone, what a hit record needs beyond the prepared shape: the
 * endpoint form for u, the unit axis and the frame of Duff et al. for v, and the axial
 * component of the side's unit outward normal, which tells the side's normals from the
 * discs' (0 for a cylinder). */
typedef struct frame {
    float p0[3], a[3]; /* p0 and p1 - p0 */
    float inv_aa;      /* 1 / |a|^2 */
    float n[3];        /* the unit axis */
    float b1[3], b2[3];
    uint32_t pieces; /* split boxes along the axis (1: one box) */
    float ns; /* n . (the side's outward normal): -(r1 - r0) / sqrt(|a|^2 + (r1 - r0)^2) */
} frame;

typedef struct ceb {
    uint32_t magic;
    const cylray_kernels *k;
    unsigned options, iflags, oflags; /* intersect and occluded kernel flags */
    size_t n;                         /* cylinders or spheres */
    cylray_prepared *prep;            /* n */
    frame *fr;                        /* n; NULL for spheres, whose u, v need none */
    cylray_sphere *sph;               /* n spheres (their boxes); NULL for cylinders */
    size_t nprim;                     /* Embree's primitives */
    uint32_t *prim_cyl;               /* split: primitive -> cylinder */
    uint32_t *prim_piece;             /* split: primitive -> its piece of that cylinder */
    struct RTCBounds *box;            /* one per primitive */
    void *leaves;                     /* leaves: cylray_leafM[nprim] */
    int m;                            /* leaf width: 4 or 8 */
    RTCGeometry geom;
} ceb;

typedef struct hitrec {
    float t, n[3], u, v;
    unsigned prim;
} hitrec;

/* The shapes a geometry is built from, read only while it is made: cylinders (cyl) or
 * cones (cone), one of them NULL; spheres: both NULL, and g->sph. */
typedef struct ceb_src {
    const cylray_cylinder *cyl;
    const cylray_cone *cone;
} ceb_src;

/* boxes.c: a cylinder's or cone's frame and its boxes */
void ceb_frame_init(frame *f, const float p0[3], const float p1[3], float r0, float r1);
void ceb_set_box(struct RTCBounds *b, const float lo[3], const float hi[3], float pad);
void ceb_whole_box(const cylray_prepared *p, struct RTCBounds *b);
void ceb_sphere_box(const cylray_sphere *s, struct RTCBounds *b);
void ceb_box_of(const ceb *g, size_t i, struct RTCBounds *b);
int ceb_make_boxes(ceb *g, const ceb_src *src);
void *ceb_alloc_aligned(size_t bytes);

/* group.c: cylinders, cones or spheres (src) grouped into leaves with Embree's SAH
 * builder */
int ceb_group_leaves(ceb *g, RTCDevice dev, const ceb_src *src);

/* Why ceb_make_boxes or ceb_group_leaves failed (they return 0 otherwise): the caller
 * of cylray_embree_new_geometry is told CYLRAY_EINVAL for the first, CYLRAY_ENOMEM for
 * the second; for the third (Embree's builder, or a cylray call, refused) none applies. */
#define CEB_BAD_INPUT 1
#define CEB_NO_MEMORY 2
#define CEB_REFUSED 3

/* filter.c: a hit offered to the filter functions */
int ceb_filter_hit(const struct RTCIntersectFunctionNArguments *a, unsigned i, const hitrec *h);
int ceb_filter_occ(const struct RTCOccludedFunctionNArguments *a, unsigned i, const hitrec *h);

/* single.c, leaves.c: the intersect and occluded callbacks */
void ceb_single_intersect(const struct RTCIntersectFunctionNArguments *a);
void ceb_single_occluded(const struct RTCOccludedFunctionNArguments *a);
RTCIntersectFunctionN ceb_leaf_intersect(int m);
RTCOccludedFunctionN ceb_leaf_occluded(int m);

/* cylray_embree.c: the adapter's state of a geometry, NULL when it is not one */
ceb *ceb_of(RTCGeometry geometry);

#endif
