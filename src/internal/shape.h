/* SPDX-License-Identifier: MIT */
/* internal/shape.h - a shape as the code around the kernels reads it (the toolkit, the
 * hit points of spawned rays): which shape it is and its few numbers, from a prepared
 * shape or from one lane of a leaf. The kernels read their own layouts; everything
 * else reads this, so that a shape's numbers are named in one place, not read back
 * from the rows a leaf shares between shapes. */
#ifndef CYLRAY_INTERNAL_SHAPE_H
#define CYLRAY_INTERNAL_SHAPE_H

#include "leaf.h"
#include "variants.h"

#include <math.h>

enum { CYLRAY_SHAPE_CYLINDER, CYLRAY_SHAPE_SPHERE, CYLRAY_SHAPE_CONE };

typedef struct {
    unsigned shape; /* CYLRAY_SHAPE_* */
    unsigned caps;  /* the end discs on the surface (CYLRAY_CAPPED_LO, _HI) */
    float c[3];     /* the center */
    float v[3];     /* the axis, as prepared (a sphere's: unused) */
    float r;        /* the radius; a cone's at its narrower end (cylray_cone_ra_) */
    float kap;      /* a cone's radius per axial unit; 0 for the others and for a
                     * leaf's cylinder given as a cone */
    float h;        /* the half height, INFINITY for an infinite cylinder (a sphere's: 0) */
} cylray_shape_;

static inline cylray_shape_ cylray_shape_of_(const cylray_prepared *p)
{
    cylray_shape_ s;
    s.shape = p->kind == CYLRAY_KIND_SPHERE ? CYLRAY_SHAPE_SPHERE
              : p->kind == CYLRAY_KIND_CONE ? CYLRAY_SHAPE_CONE
                                            : CYLRAY_SHAPE_CYLINDER;
    s.caps = p->caps;
    for (int k = 0; k < 3; k++)
        s.c[k] = p->c[k], s.v[k] = p->v[k];
    s.r = s.shape == CYLRAY_SHAPE_CONE ? cylray_cone_ra_(p) : p->radius;
    s.kap = s.shape == CYLRAY_SHAPE_CONE ? p->kap : 0.0f;
    s.h = p->half_height;
    if (p->kind == CYLRAY_KIND_ROUND) /* not yet read here: NaN points, never a wrong one */
        s.c[0] = s.c[1] = s.c[2] = NAN;
    return s;
}

/* Lane i of a leaf of m lanes: geom[field * m + lane], meta past the fields
 * (internal/leaf.h). A cone's lane keeps its shape with a slope of 0 (a cylinder given
 * as a cone): its box is a cone's, its surface coordinates a cylinder's. */
static inline cylray_shape_ cylray_leaf_shape_(const float *geom, const uint32_t *meta,
                                               size_t m, size_t i)
{
    cylray_shape_ s;
    s.shape = (cylray_leaf_spheres_(meta) >> i) & 1u ? CYLRAY_SHAPE_SPHERE
              : (cylray_leaf_cones_(meta) >> i) & 1u ? CYLRAY_SHAPE_CONE
                                                     : CYLRAY_SHAPE_CYLINDER;
    s.caps = cylray_leaf_caps_(meta, (unsigned)i);
    for (int k = 0; k < 3; k++) {
        s.c[k] = geom[(CYLRAY_LF_CX + k) * m + i];
        s.v[k] = geom[(CYLRAY_LF_VX + k) * m + i];
    }
    s.r = geom[CYLRAY_LF_R * m + i];
    s.kap = s.shape == CYLRAY_SHAPE_CONE ? geom[CYLRAY_LF_KAP * m + i] : 0.0f;
    s.h = geom[CYLRAY_LF_H * m + i];
    return s;
}

#endif
