/* SPDX-License-Identifier: MIT */
/* internal/leaf.h - the layout of a leaf, as the kernels read it. */
#ifndef CYLRAY_INTERNAL_LEAF_H
#define CYLRAY_INTERNAL_LEAF_H

#include "cylray.h"
#include "variants.h"

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
/* The rows a cone's lane reads otherwise: the radius of its narrower end
 * (cylray_cone_ra_), its slope kap and its normal's length cnrm (cylray_prepared). */
enum {
    CYLRAY_LF_RA = CYLRAY_LF_R,
    CYLRAY_LF_KAP = CYLRAY_LF_RRVV,
    CYLRAY_LF_CNRM = CYLRAY_LF_NSCALE,
};
/* meta_ holds lane masks (bit k: lane k): [0] the lanes in use (in its high 16 bits,
 * bit 16 + k, the cones with a tiny end), [1] those whose low
 * disc is part of the surface, [2] those whose high disc is, [3] those that are
 * spheres in its low 16 bits and those that are cones in its high 16 (bit 16 + k). A
 * leaf holds cylinders, spheres, or cones (cylinders among them as cones of equal
 * radii). The leaf starts with the fields a kernel reads, so it is passed to one as a
 * float pointer.
 * A cone's radius is formed from its narrower end (cylray_cone_ra_,
 * internal/variants.h). */
/* The same radius in double at the axial coordinate z, hv = H |v| (never below 0; a
 * slope of 0, a leaf's cylinder, is ra at every z). */
static inline double cylray_cone_radius_(double ra, double kap, double hv, double z)
{
    const double za = kap > 0 ? -hv : kap < 0 ? hv : 0.0, r = ra + kap * (z - za);
    return r > 0 ? r : 0.0;
}

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
/* The lanes whose cone has a tiny end (cylray_cone_tiny_), in the high 16 bits of
 * meta_[CYLRAY_LM_USED]: a leaf that has any runs the kernels for them (CYLRAY_KF_TINY). */
static inline uint32_t cylray_leaf_tiny_(const uint32_t *meta)
{
    return meta[CYLRAY_LM_USED] >> CYLRAY_LM_CONE_SHIFT;
}
/* The lanes of slender shapes (cylray_slender_), in the high half of the low caps' word. */
static inline uint32_t cylray_leaf_slender_(const uint32_t *meta)
{
    return meta[CYLRAY_LM_LO] >> CYLRAY_LM_CONE_SHIFT;
}
/* The leaves' rows of the leaf tables, as CYLRAY_VARIANT_ROWS (internal/variants.h) is
 * the prepared shapes': X(name, the kernel flags its kernels are stamped with beside a
 * leaf's own, which of its flag sets are specialised). A leaf holds one shape, and its
 * row is the one whose kernels serve every lane it holds (cylray_leaf_row_). */
#define CYLRAY_LEAF_ROWS(X)                                                                    \
    X(CYLINDERS, 0u, FULL)                                                                     \
    X(SPHERES, CYLRAY_KF_SPHERE, FULL)                                                         \
    X(CONES, CYLRAY_KF_CONE, THIRD)                                                            \
    X(CONES_TINY, CYLRAY_KF_CONE | CYLRAY_KF_TINY, THIRD)                                      \
    X(SLENDER, CYLRAY_KF_SLENDER, ANY)                                                         \
    X(CONES_SLENDER, CYLRAY_KF_CONE | CYLRAY_KF_TINY | CYLRAY_KF_SLENDER, ANY)
#define CYLRAY_LEAF_ENUM_(name, kf, set) CYLRAY_LEAF_##name,
enum { CYLRAY_LEAF_ROWS(CYLRAY_LEAF_ENUM_) CYLRAY_LEAF_ROW_COUNT };
#undef CYLRAY_LEAF_ENUM_
/* A slender lane or a tiny-ended cone needs its kernels' extra work, which serves the
 * leaf's other lanes as well. */
static inline unsigned cylray_leaf_row_(const uint32_t *meta)
{
    const int cones = cylray_leaf_cones_(meta) != 0;
    if (cylray_leaf_spheres_(meta))
        return CYLRAY_LEAF_SPHERES;
    if (cylray_leaf_slender_(meta))
        return cones ? CYLRAY_LEAF_CONES_SLENDER : CYLRAY_LEAF_SLENDER;
    if (cylray_leaf_tiny_(meta))
        return CYLRAY_LEAF_CONES_TINY;
    return cones ? CYLRAY_LEAF_CONES : CYLRAY_LEAF_CYLINDERS;
}
static inline unsigned cylray_leaf_caps_(const uint32_t *meta, unsigned lane)
{
    return ((meta[CYLRAY_LM_LO] >> lane) & 1u ? CYLRAY_CAPPED_LO : 0u) |
           ((meta[CYLRAY_LM_HI] >> lane) & 1u ? CYLRAY_CAPPED_HI : 0u);
}

#endif
