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

typedef struct ceb_shape ceb_shape;

typedef struct ceb {
    uint32_t magic;
    const cylray_kernels *k;
    unsigned options, iflags, oflags; /* intersect and occluded kernel flags */
    size_t n;                         /* shapes */
    cylray_prepared *prep;            /* n */
    frame *fr;                        /* n; NULL when the shape has none (spheres) */
    /* n spheres (the elements) when the shape asks for single.c's test of rays leaving
     * them, else NULL: a per-geometry test on the hot path, no indirect call */
    const cylray_sphere *sphere_test;
    const ceb_shape *shape;
    void *elems;           /* n of shape->size; NULL after the build unless sphere_test */
    size_t nprim;          /* Embree's primitives */
    uint32_t *prim_cyl;    /* split: primitive -> cylinder */
    uint32_t *prim_piece;  /* split: primitive -> its piece of that cylinder */
    struct RTCBounds *box; /* one per primitive */
    void *leaves;          /* leaves: cylray_leafM[nprim] */
    int m;                 /* leaf width: 4 or 8 */
    RTCGeometry geom;
} ceb;

typedef struct hitrec {
    float t, n[3], u, v;
    unsigned prim;
} hitrec;

/* One kind of shape, as the build of a geometry asks for it: a const row per kind
 * (shapes.c), the one place that knows which kind it is. Its functions run while a
 * geometry is built, never per ray: what a query needs to know is set in the ceb then
 * (fr, sphere_test). e is one element, elems the geometry's array of them. */
struct ceb_shape {
    size_t size; /* one element's bytes */
    /* e prepared for the kernels; not CYLRAY_OK: the caller's input is refused */
    cylray_status (*prepare)(cylray_prepared *p, const void *e);
    /* e's frame for u, v and the split boxes; NULL: the shape has none, its u, v come
     * from the normal alone and it keeps one box (a sphere's is tight) */
    void (*frame)(frame *f, const void *e);
    /* e's widest radius (with frame only): e is split as the cylinder of that radius */
    float (*rmax)(const void *e);
    /* e's whole box; p is e prepared */
    void (*box)(const void *e, const cylray_prepared *p, struct RTCBounds *b);
    /* the leaf of elements elems[ids[0..n)], n <= M */
    cylray_status (*leaf4)(cylray_leaf4 *lv, const void *elems, const uint32_t *ids, size_t n);
    cylray_status (*leaf8)(cylray_leaf8 *lv, const void *elems, const uint32_t *ids, size_t n);
    /* 1: the elements are cylray_spheres, a ray leaving one is rejected before the
     * kernel (single.c) */
    int sphere_test;
};

/* shapes.c: cylinders and cones (elements cylray_cone, r1 = r0 for a cylinder),
 * spheres (cylray_sphere) */
extern const ceb_shape ceb_cylinders, ceb_cones, ceb_spheres;

/* Element i of geometry g. */
static inline const void *ceb_elem(const ceb *g, size_t i)
{
    return (const char *)g->elems + g->shape->size * i;
}

/* boxes.c: a cylinder's or cone's frame and its boxes */
void ceb_frame_init(frame *f, const float p0[3], const float p1[3], float r0, float r1);
void ceb_set_box(struct RTCBounds *b, const float lo[3], const float hi[3], float pad);
void ceb_whole_box(const cylray_prepared *p, struct RTCBounds *b);
void ceb_sphere_box(const cylray_sphere *s, struct RTCBounds *b);
void ceb_box_of(const ceb *g, size_t i, struct RTCBounds *b);
/* Whether split boxes would cut any of g's shapes (its frames made). */
int ceb_would_split(const ceb *g);
int ceb_make_boxes(ceb *g);
void *ceb_alloc_aligned(size_t bytes);

/* group.c: g's shapes grouped into leaves with Embree's SAH builder */
int ceb_group_leaves(ceb *g, RTCDevice dev);

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
