/* SPDX-License-Identifier: MIT */
/* internal/variants.h - the kinds of cylinder, the kernel flags, the variant of a
 * prepared cylinder and how it and the flags index the kernel tables: each encoded
 * here and decoded here. */
#ifndef CYLRAY_INTERNAL_VARIANTS_H
#define CYLRAY_INTERNAL_VARIANTS_H

#include "cylray.h"
#include "compiler.h"

#define CYLRAY_KIND_INFINITE 0u
#define CYLRAY_KIND_OPEN 1u   /* finite, no end discs: a tube */
#define CYLRAY_KIND_CAPPED 2u /* finite, closed solid */
#define CYLRAY_KIND_COUNT 3u
#define CYLRAY_KIND_LEAF 3u   /* in the kernel flags only: a leaf's lanes, of any kind */
#define CYLRAY_KIND_SPHERE 4u /* cylray_prepared.kind of a sphere (CYLRAY_KF_SPHERE) */
#define CYLRAY_KIND_CONE 5u   /* cylray_prepared.kind of a cone (CYLRAY_KF_CONE) */
#define CYLRAY_KIND_ROUND 6u  /* cylray_prepared.kind of a round cone (CYLRAY_KF_ROUND) */

#define CYLRAY_MAGIC 0x63796c72u /* "cylr" */

/* A cone's radius is formed from its narrower end (kernel/shape/cone_frame.h, cone_anchor): ra,
 * that end's radius as given (r0 where kap > 0, r1 elsewhere), plus kap (z - za) with za
 * its axial coordinate, -H|v| or +H|v|. */
static inline float cylray_cone_ra_(const cylray_prepared *p)
{
    return p->kap > 0 ? p->r0 : p->r1;
}
/* Whether a cone's narrower end is under 1/64 of the wider one (a tip among them): the
 * cones whose kernels measure from that end near it (CYLRAY_KF_TINY). */
static inline int cylray_cone_tiny_(const cylray_prepared *p)
{
    return cylray_cone_ra_(p) * 64.0f < (p->r0 > p->r1 ? p->r0 : p->r1);
}

/* Whether a finite shape is slender: longer than 16 of its widest radius (H |v| >
 * 8 R |v|, in the prepared cylinder's R^2 v.v; a cone's R is its wider end's). Its
 * lanes take their frame where the ray passes rather than at the center (kernel/anchor.h):
 * the center lies up to half its length from where a ray meets it, and p, f and C
 * rounded at that size would lose the local radius. */
static inline int cylray_slender_(const cylray_prepared *p)
{
    const double hv = p->h_v;
    return p->kind != CYLRAY_KIND_INFINITE && p->kind != CYLRAY_KIND_SPHERE && hv < 0x1p128 &&
           hv * hv > 64.0 * p->rr_vv;
}

/* A ray is parallel to the axis where A <= CYLRAY_PAR_EPS v.v d.d: an angle below
 * 2^-23 rad, about one float ulp of the direction, where the side's roots are noise. */
#define CYLRAY_PAR_EPS 0x1p-46

/* Internal kernel flags, beside the public CYLRAY_* kernel flags (all below 0x20). */
#define CYLRAY_KF_OCCLUDED 0x100u
#define CYLRAY_KF_ALIGNED 0x200u
#define CYLRAY_KF_KIND_SHIFT 10
#define CYLRAY_KF_SCALED 0x1000u  /* the rare-lane instance: d scaled to near unit length */
#define CYLRAY_KF_ONE_END 0x2000u /* a capped cylinder with one disc only */
/* A sphere (the kind bits then 0): the stages that differ from the cylinder's take
 * their sphere branch; the drivers, stores and tables are the cylinder's. */
#define CYLRAY_KF_SPHERE 0x10000u
/* A cone (the kind bits then those of a capped cylinder, whose slab logic it runs): the
 * side's quadratic and its normal take the cone's branch. */
#define CYLRAY_KF_CONE 0x20000u
/* A cone whose narrower end is under 1/64 of the other (cylray_cone_tiny_), or a leaf
 * that holds one: rays near that end measure from it (kernel/shape/cone_frame.h). */
#define CYLRAY_KF_TINY 0x40000u
/* A slender shape (cylray_slender_), or a leaf that holds one: each lane takes its
 * frame where the ray passes (kernel/anchor.h). Only the drivers that read their flags
 * at run time carry it: a prepared slender shape has a generic variant, a leaf that
 * holds one the run-time leaf driver, and every other kernel none of its work. */
#define CYLRAY_KF_SLENDER 0x80000u
/* A round cone: the solid of a capped cylinder or cone (its tangent frustum, whose
 * discs are never on the surface) joined to the spheres at its ends, cut where an end
 * is open (kernel/shape/round_cone.h). */
#define CYLRAY_KF_ROUND 0x100000u
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

/* The specialised variants, the rows of the kernel tables in table order: X(name, the
 * kernel flags its kernels are stamped with, which of its flag sets are specialised:
 * FULL, THIRD or ANY, kernel/tables.h). The kernels, the tables and their static checks
 * are stamped from this list; a shape adds its rows here, its leaf rows to
 * CYLRAY_LEAF_ROWS (internal/leaf.h) and its work to kernel/shape.h.
 *   a cylinder of each kind, then the same three along a coordinate axis;
 *   the sphere (the kind bits then 0: the stages that differ from the cylinder's take its
 *   branch, the drivers, stores and tables are the cylinder's);
 *   the capped cone, which runs a capped cylinder's slab logic with the cone's side;
 *   the capped cone with a tiny end (cylray_cone_tiny_) or slender (cylray_slender_),
 *   whose kernels carry CYLRAY_KF_SLENDER and ask the prepared cone whether to take the
 *   frame (other slender shapes take the generic variant).
 * The cone specialises a third of its flag sets: CYLRAY_FAST takes its plain kernels
 * as they are (the estimates buy a cone nothing: its divisions are few, and the accurate
 * kernel is within FAST's promise), and CYLRAY_REFINE, the rarer flag, the drivers that
 * read their flags at run time. That keeps the library within its size. */
#define CYLRAY_KF_KIND_(k) ((unsigned)(k) << CYLRAY_KF_KIND_SHIFT)
#define CYLRAY_VARIANT_ROWS(X)                                                                 \
    X(INFINITE, CYLRAY_KF_KIND_(CYLRAY_KIND_INFINITE), FULL)                                   \
    X(OPEN, CYLRAY_KF_KIND_(CYLRAY_KIND_OPEN), FULL)                                           \
    X(CAPPED, CYLRAY_KF_KIND_(CYLRAY_KIND_CAPPED), FULL)                                       \
    X(INFINITE_AXIS, CYLRAY_KF_KIND_(CYLRAY_KIND_INFINITE) | CYLRAY_KF_ALIGNED, FULL)          \
    X(OPEN_AXIS, CYLRAY_KF_KIND_(CYLRAY_KIND_OPEN) | CYLRAY_KF_ALIGNED, FULL)                  \
    X(CAPPED_AXIS, CYLRAY_KF_KIND_(CYLRAY_KIND_CAPPED) | CYLRAY_KF_ALIGNED, FULL)              \
    X(SPHERE, CYLRAY_KF_SPHERE, FULL)                                                          \
    X(CONE, CYLRAY_KF_CONE | CYLRAY_KF_KIND_(CYLRAY_KIND_CAPPED), THIRD)                       \
    X(CONE_TINY,                                                                               \
      CYLRAY_KF_CONE | CYLRAY_KF_TINY | CYLRAY_KF_SLENDER |                                    \
          CYLRAY_KF_KIND_(CYLRAY_KIND_CAPPED),                                                 \
      THIRD)
/* The tables are indexed by the variant and the flags a kernel is specialised for
 * (normals, CYLRAY_FAST, CYLRAY_REFINE). A shape whose radius is far from 1 (j != 0), a
 * cylinder or cone with one disc only, or a slender cylinder has a variant from
 * CYLRAY_VARIANT_GENERIC on (its kind's offset from there, a sphere's 3, a cone's 4),
 * and runs the generic kernel, which reads its flags at run time. */
#define CYLRAY_VARIANT_ENUM_(name, kf, set) CYLRAY_VARIANT_##name,
enum { CYLRAY_VARIANT_ROWS(CYLRAY_VARIANT_ENUM_) CYLRAY_VARIANT_GENERIC };
#undef CYLRAY_VARIANT_ENUM_
_Static_assert(CYLRAY_VARIANT_INFINITE == CYLRAY_KIND_INFINITE &&
                   CYLRAY_VARIANT_OPEN == CYLRAY_KIND_OPEN &&
                   CYLRAY_VARIANT_CAPPED == CYLRAY_KIND_CAPPED &&
                   CYLRAY_VARIANT_INFINITE_AXIS == CYLRAY_KIND_COUNT + CYLRAY_KIND_INFINITE &&
                   CYLRAY_VARIANT_CAPPED_AXIS == CYLRAY_KIND_COUNT + CYLRAY_KIND_CAPPED,
               "a cylinder's variant is its kind, plus CYLRAY_KIND_COUNT along an axis");
static inline unsigned cylray_variant_of_(unsigned kind, unsigned axis_id, int radius_scaled,
                                          unsigned caps, int tiny, int slender)
{
    if (kind == CYLRAY_KIND_SPHERE)
        return radius_scaled ? CYLRAY_VARIANT_GENERIC + CYLRAY_KIND_COUNT
                             : CYLRAY_VARIANT_SPHERE;
    if (kind == CYLRAY_KIND_ROUND) /* the generic kernel, for now */
        return CYLRAY_VARIANT_GENERIC + 5u;
    if (kind == CYLRAY_KIND_CONE) /* a cone with one disc or none: the generic one */
        return radius_scaled || caps != CYLRAY_CAPPED ? CYLRAY_VARIANT_GENERIC + 4u
               : tiny || slender                      ? CYLRAY_VARIANT_CONE_TINY
                                                      : CYLRAY_VARIANT_CONE;
    if (radius_scaled || slender || (kind == CYLRAY_KIND_CAPPED && caps != CYLRAY_CAPPED))
        return CYLRAY_VARIANT_GENERIC + kind;
    return kind + (axis_id ? CYLRAY_KIND_COUNT : 0u);
}
static inline int cylray_generic_(const cylray_prepared *p)
{
    return p->variant >= CYLRAY_VARIANT_GENERIC;
}
/* The kernel flags of a generic variant, which the generic drivers read at run time:
 * the kind, one disc or two, and the public flags that select the kernel's branches. */
static inline unsigned cylray_generic_kf_(const cylray_prepared *P, unsigned flags, int occ)
{
    if (P->kind == CYLRAY_KIND_SPHERE)
        return CYLRAY_KF_SPHERE | (occ ? CYLRAY_KF_OCCLUDED : 0u) |
               (flags & ((occ ? 0u : CYLRAY_NORMAL) | CYLRAY_REFINE | CYLRAY_FAST)) |
               CYLRAY_KF_SCALED;
    if (P->kind == CYLRAY_KIND_ROUND && P->h_v == 0) /* one sphere within the other */
        return CYLRAY_KF_ROUND | CYLRAY_KF_SPHERE | (occ ? CYLRAY_KF_OCCLUDED : 0u) |
               (flags & ((occ ? 0u : CYLRAY_NORMAL) | CYLRAY_REFINE | CYLRAY_FAST)) |
               CYLRAY_KF_SCALED;
    if (P->kind == CYLRAY_KIND_ROUND) /* its frustum a cone, or a cylinder (kap = 0) */
        return CYLRAY_KF_ROUND | CYLRAY_KF_KIND_(CYLRAY_KIND_CAPPED) | CYLRAY_KF_ONE_END |
               (P->kap != 0 ? CYLRAY_KF_CONE : 0u) | (occ ? CYLRAY_KF_OCCLUDED : 0u) |
               (flags & ((occ ? 0u : CYLRAY_NORMAL) | CYLRAY_REFINE | CYLRAY_FAST)) |
               (cylray_slender_(P) ? CYLRAY_KF_SLENDER : 0u) | CYLRAY_KF_SCALED;
    if (P->kind == CYLRAY_KIND_CONE)
        return CYLRAY_KF_CONE | CYLRAY_KF_KIND_(CYLRAY_KIND_CAPPED) |
               (occ ? CYLRAY_KF_OCCLUDED : 0u) |
               (flags & ((occ ? 0u : CYLRAY_NORMAL) | CYLRAY_REFINE | CYLRAY_FAST)) |
               (P->caps != CYLRAY_CAPPED ? CYLRAY_KF_ONE_END : 0u) |
               (cylray_cone_tiny_(P) ? CYLRAY_KF_TINY : 0u) |
               (cylray_slender_(P) ? CYLRAY_KF_SLENDER : 0u) | CYLRAY_KF_SCALED;
    return CYLRAY_KF_KIND_(P->kind) | (occ ? CYLRAY_KF_OCCLUDED : 0u) |
           (flags & ((occ ? 0u : CYLRAY_NORMAL) | CYLRAY_REFINE | CYLRAY_FAST)) |
           (P->kind == CYLRAY_KIND_CAPPED && P->caps != CYLRAY_CAPPED ? CYLRAY_KF_ONE_END
                                                                      : 0u) |
           (cylray_slender_(P) ? CYLRAY_KF_SLENDER : 0u) | CYLRAY_KF_SCALED;
}
/* The one encoding of the specialised flags: bit 0 normals, bit 1 FAST, bit 2 REFINE
 * (CYLRAY_SPEC_KF_ below decodes it; cylray_occ_spec_ drops the normals): the
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
/* The flags a specialisation b stands for, b as cylray_spec_ encodes them, or as
 * cylray_occ_spec_ does for occlusion; constant expressions, for the tables. */
#define CYLRAY_SPEC_KF_(b)                                                                     \
    (((b)&1 ? CYLRAY_NORMAL : 0u) | ((b)&2 ? CYLRAY_FAST : 0u) | ((b)&4 ? CYLRAY_REFINE : 0u))
#define CYLRAY_OCC_SPEC_KF_(b) (CYLRAY_SPEC_KF_((b) << 1) | CYLRAY_KF_OCCLUDED)
static inline unsigned cylray_isect_index_(unsigned variant, unsigned flags)
{
    return variant * CYLRAY_SPECS + cylray_spec_(flags);
}
static inline unsigned cylray_occ_index_(unsigned variant, unsigned flags)
{
    return variant * CYLRAY_OCC_SPECS + cylray_occ_spec_(flags);
}

/* What an instantiation's flags decide. Every field but the run-time ones (cull, ff,
 * stores) is a compile-time constant where a kernel is specialised, and its branches
 * fold. scratch: the hits go to a leaf's own scratch, read back at the hit lanes only,
 * so whole vectors may be stored there; stores: the store policy (CYLRAY_STORE_*). */
typedef struct {
    unsigned kind;
    int sphere, cone, round, tiny, slender, leaf, capped, finite, one_end, aligned, scaled, occ,
        normal, cull, ff, refine, fast;
    int scratch;
    unsigned stores;
} cylray_kflags_;

/* The kernel flags decoded, FL the specialised ones and rt those read at run time. */
CYLRAY_INLINE cylray_kflags_ cylray_kflags_of_(unsigned FL, unsigned rt)
{
    cylray_kflags_ F;
    F.kind = (FL >> CYLRAY_KF_KIND_SHIFT) & 3u;
    F.sphere = (FL & CYLRAY_KF_SPHERE) != 0;
    F.cone = (FL & CYLRAY_KF_CONE) != 0;
    F.round = (FL & CYLRAY_KF_ROUND) != 0;
    F.tiny = F.cone && (FL & CYLRAY_KF_TINY) != 0;
    F.leaf = F.kind == CYLRAY_KIND_LEAF;
    /* A leaf's lanes are cylinders of any kind: each runs the capped solid's logic with
     * its own discs (an open tube has none, an infinite one an infinite slab). */
    F.capped = (F.kind == CYLRAY_KIND_CAPPED || F.leaf) && !F.sphere;
    /* A sphere runs as an infinite cylinder would (no slab, no ends) but for its bounding
     * sphere, which is itself. */
    F.finite = F.kind != CYLRAY_KIND_INFINITE || F.sphere;
    F.one_end = (F.leaf || (FL & CYLRAY_KF_ONE_END) != 0) && !F.sphere;
    F.slender = (FL & CYLRAY_KF_SLENDER) != 0 && F.finite && !F.sphere;
    F.aligned = (FL & CYLRAY_KF_ALIGNED) != 0;
    F.scaled = (FL & CYLRAY_KF_SCALED) != 0;
    F.occ = (FL & CYLRAY_KF_OCCLUDED) != 0;
    F.normal = (FL & CYLRAY_NORMAL) && !F.occ;
    F.cull = ((FL | rt) & CYLRAY_CULL_BACK) != 0;
    F.ff = (rt & CYLRAY_FACE_FORWARD) != 0;
    F.refine = (FL & CYLRAY_REFINE) != 0;
    F.fast = (FL & CYLRAY_FAST) != 0;
    F.scratch = F.leaf;
    F.stores = (rt & CYLRAY_KF_STORE_MASK) >> CYLRAY_KF_STORE_SHIFT;
    return F;
}

static inline int cylray_prepared_ok_(const cylray_prepared *p)
{
    return p != 0 && p->magic == CYLRAY_MAGIC &&
           (p->kind < CYLRAY_KIND_COUNT || p->kind == CYLRAY_KIND_SPHERE ||
            p->kind == CYLRAY_KIND_CONE || p->kind == CYLRAY_KIND_ROUND) &&
           p->axis_id <= 3u && (p->caps & ~CYLRAY_CAPPED) == 0 &&
           p->variant == cylray_variant_of_(p->kind, p->axis_id, p->g_s != 1.0f, p->caps,
                                            p->kind == CYLRAY_KIND_CONE && cylray_cone_tiny_(p),
                                            cylray_slender_(p));
}

#endif
