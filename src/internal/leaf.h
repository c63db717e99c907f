/* SPDX-License-Identifier: MIT */
/* internal/leaf.h - the layout of a leaf, as the kernels read it. */
#ifndef CYLRAY_INTERNAL_LEAF_H
#define CYLRAY_INTERNAL_LEAF_H

#include "cylray.h"

/* A leaf's fields: geom_[LF_*][lane], the meta_ bits, and its lane count by type. The
 * axis v is the user's scaled by a power of two (exact), as in cylray_prepared. */
enum {
    CYLRAY_LF_CX,
    CYLRAY_LF_CY,
    CYLRAY_LF_CZ, /* center */
    CYLRAY_LF_VX,
    CYLRAY_LF_VY,
    CYLRAY_LF_VZ,     /* axis */
    CYLRAY_LF_R,      /* radius, as given */
    CYLRAY_LF_H,      /* half height, as given (INFINITY: infinite) */
    CYLRAY_LF_RRVV,   /* R^2 v.v */
    CYLRAY_LF_HV,     /* H |v| */
    CYLRAY_LF_SQS,    /* |v| / g_s */
    CYLRAY_LF_GS,     /* g_s = 2^-j (cylray_prepared.g_s) */
    CYLRAY_LF_NSCALE, /* 1 / (R v.v) */
    CYLRAY_LF_BOUND2, /* squared bounding-sphere radius; -1 for padding */
    CYLRAY_LF_COUNT
};
/* meta_ holds lane masks (bit k: lane k): [0] the lanes in use, [1] those whose low
 * disc is part of the surface, [2] those whose high disc is, [3] those that are
 * spheres in its low 16 bits and those that are cones in its high 16 (bit 16 + k). A
 * leaf holds cylinders, spheres, or cones (cylinders among them as cones of equal
 * radii). The leaf starts with the fields a kernel reads, so it is passed to one as a
 * float pointer.
 *
 * A cone's lane reads some rows otherwise: CYLRAY_LF_R is its radius at the center
 * rm, CYLRAY_LF_RRVV its slope kap and CYLRAY_LF_NSCALE its cnrm (cylray_prepared). */
enum { CYLRAY_LM_USED, CYLRAY_LM_LO, CYLRAY_LM_HI, CYLRAY_LM_SPHERE };
#define CYLRAY_LM_CONE_SHIFT 16
static inline uint32_t cylray_leaf_spheres_(const uint32_t *meta)
{
    return meta[CYLRAY_LM_SPHERE] & 0xffffu;
}
static inline uint32_t cylray_leaf_cones_(const uint32_t *meta)
{
    return meta[CYLRAY_LM_SPHERE] >> CYLRAY_LM_CONE_SHIFT;
}
static inline unsigned cylray_leaf_caps_(const uint32_t *meta, unsigned lane)
{
    return ((meta[CYLRAY_LM_LO] >> lane) & 1u ? CYLRAY_CAPPED_LO : 0u) |
           ((meta[CYLRAY_LM_HI] >> lane) & 1u ? CYLRAY_CAPPED_HI : 0u);
}

#endif
