/* SPDX-License-Identifier: MIT */
/* internal/variants.h - the kinds of cylinder, the kernel flags, and how they index
 * the kernel tables. */
#ifndef CYLRAY_INTERNAL_VARIANTS_H
#define CYLRAY_INTERNAL_VARIANTS_H

#include "cylray.h"

#define CYLRAY_KIND_INFINITE 0u
#define CYLRAY_KIND_OPEN 1u   /* finite, no end discs: a tube */
#define CYLRAY_KIND_CAPPED 2u /* finite, closed solid */
#define CYLRAY_KIND_COUNT 3u
#define CYLRAY_KIND_LEAF 3u /* in the kernel flags only: a leaf's lanes, of any kind */

#define CYLRAY_MAGIC 0x63796c72u /* "cylr" */

/* A ray is parallel to the axis where A <= CYLRAY_PAR_EPS v.v d.d: an angle below
 * 2^-23 rad, about one float ulp of the direction, where the side's roots are noise. */
#define CYLRAY_PAR_EPS 0x1p-46

/* Internal kernel flags, beside the public CYLRAY_* kernel flags (all below 0x20). */
#define CYLRAY_KF_OCCLUDED 0x100u
#define CYLRAY_KF_ALIGNED 0x200u
#define CYLRAY_KF_KIND_SHIFT 10
#define CYLRAY_KF_SCALED 0x1000u  /* the rare-lane instance: d scaled to near unit length */
#define CYLRAY_KF_ONE_END 0x2000u /* a capped cylinder with one disc only */
/* How the x86 kernels store a hit vector (docs/performance.md, "Stores by vendor"):
 * the policy is a property of the kernel table the dispatch chose for the CPU, whose
 * entry points pass it down with the run-time flags.
 *   MASKED  AVX's masked stores (vmaskmovps); where there are none (SSE), as LANES
 *   BLEND   a vector whose lanes are all active: load, blend the hit lanes in, store
 *           (the missed lanes' values go back unchanged); others as LANES
 *   LANES   a plain store per field when every lane hit, else a loop over the hit
 *           lanes
 * AVX-512 stores through its mask registers whatever the policy. */
#define CYLRAY_KF_STORE_SHIFT 14
#define CYLRAY_KF_STORE_MASK (3u << CYLRAY_KF_STORE_SHIFT)
#define CYLRAY_STORE_MASKED 0u
#define CYLRAY_STORE_BLEND 1u
#define CYLRAY_STORE_LANES 2u
/* The public flags every kernel reads at run time rather than being specialised for,
 * and the store policy, which its table sets. */
#define CYLRAY_KF_RUNTIME (CYLRAY_FACE_FORWARD | CYLRAY_CULL_BACK | CYLRAY_KF_STORE_MASK)

/* The kernel tables are indexed by the cylinder's variant (its kind, plus 3 when the
 * axis is a coordinate axis) and the flags a kernel is specialised for (normals,
 * CYLRAY_FAST, CYLRAY_REFINE). A cylinder whose radius is far from 1 (j != 0) or that
 * has one disc only has a variant from CYLRAY_VARIANT_GENERIC on, and runs the generic
 * kernel, which reads its flags at run time. */
#define CYLRAY_VARIANT_GENERIC (2u * CYLRAY_KIND_COUNT)
static inline unsigned cylray_variant_of_(unsigned kind, unsigned axis_id, int radius_scaled,
                                          unsigned caps)
{
    if (radius_scaled || (kind == CYLRAY_KIND_CAPPED && caps != CYLRAY_CAPPED))
        return CYLRAY_VARIANT_GENERIC + kind;
    return kind + (axis_id ? CYLRAY_KIND_COUNT : 0u);
}
static inline int cylray_generic_(const cylray_prepared *p)
{
    return p->variant >= CYLRAY_VARIANT_GENERIC;
}
/* The one encoding of the specialised flags: bit 0 normals, bit 1 FAST, bit 2 REFINE
 * (the kernel template's KFL_ decodes it; cylray_occ_spec_ drops the normals): the
 * tables have CYLRAY_SPECS entries per variant, CYLRAY_OCC_SPECS for occlusion. */
#define CYLRAY_SPECS 8u
#define CYLRAY_OCC_SPECS 4u
static inline unsigned cylray_spec_(unsigned flags)
{
    return (flags & CYLRAY_NORMAL) | ((flags & CYLRAY_FAST) ? 2u : 0u) |
           ((flags & CYLRAY_REFINE) ? 4u : 0u);
}
static inline unsigned cylray_occ_spec_(unsigned flags)
{
    return cylray_spec_(flags) >> 1;
}
static inline unsigned cylray_isect_index_(unsigned variant, unsigned flags)
{
    return variant * CYLRAY_SPECS + cylray_spec_(flags);
}
static inline unsigned cylray_occ_index_(unsigned variant, unsigned flags)
{
    return variant * CYLRAY_OCC_SPECS + cylray_occ_spec_(flags);
}

static inline int cylray_prepared_ok_(const cylray_prepared *p)
{
    return p != 0 && p->magic == CYLRAY_MAGIC && p->kind < CYLRAY_KIND_COUNT &&
           p->axis_id <= 3u && (p->caps & ~CYLRAY_CAPPED) == 0 &&
           p->variant == cylray_variant_of_(p->kind, p->axis_id, p->g_s != 1.0f, p->caps);
}

#endif
