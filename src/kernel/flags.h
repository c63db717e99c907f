/* SPDX-License-Identifier: MIT */
/* kernel/flags.h - what an instantiation's flags decide, and where one vector's lanes
 * come from (shared by every instantiation, defined once). */

#ifndef CYLRAY_KERNEL_FLAGS_H
#define CYLRAY_KERNEL_FLAGS_H

/* What an instantiation's flags decide. Every field but the run-time ones (cull, ff,
 * stores) is a compile-time constant where a kernel is specialised, and its branches
 * fold. scratch: the hits go to a leaf's own scratch, read back at the hit lanes only,
 * so whole vectors may be stored there; stores: the store policy (CYLRAY_STORE_*). */
typedef struct {
    unsigned kind;
    int leaf, capped, finite, one_end, aligned, scaled, occ, normal, cull, ff, refine, fast;
    int scratch;
    unsigned stores;
} cylray_kflags_;

CYLRAY_INLINE cylray_kflags_ cylray_kflags_of_(unsigned FL, unsigned rt)
{
    cylray_kflags_ F;
    F.kind = (FL >> CYLRAY_KF_KIND_SHIFT) & 3u;
    F.leaf = F.kind == CYLRAY_KIND_LEAF;
    /* A leaf's lanes are cylinders of any kind: each runs the capped solid's logic with
     * its own discs (an open tube has none, an infinite one an infinite slab). */
    F.capped = F.kind == CYLRAY_KIND_CAPPED || F.leaf;
    F.finite = F.kind != CYLRAY_KIND_INFINITE;
    F.one_end = F.leaf || (FL & CYLRAY_KF_ONE_END) != 0;
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

/* Where one vector's lanes come from and go to: the cylinder (P) or the leaf (L, lm
 * lanes), the rays and hits, the first lane i and the active lanes. An aligned
 * cylinder comes with its rays' coordinates already renamed by the drivers
 * (internal/views.h), so that its axis is the third one; c3 is its center renamed
 * the same way. */
typedef struct {
    const cylray_prepared *P;
    const cylray_rays *R;
    const cylray_hits *H;
    const float *L;
    size_t lm, i;
    uint32_t bits;
    const float *c3;
} cylray_kat_;

/* What the block functions report: the hit lanes of each vector (one, or two in
 * flight), how many of them the cheap rejections ended, and whether the rare instance
 * must take them. */
typedef struct {
    uint32_t hit[2];
    uint32_t rejected;
    int rare;
} cylray_kres_;

CYLRAY_INLINE const float *cylray_kcenter_(const cylray_prepared *P, const cylray_kflags_ F)
{
    return F.leaf ? NULL : F.aligned ? P->cr : P->c;
}
#endif
