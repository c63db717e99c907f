/* SPDX-License-Identifier: MIT */
/* kernel/io.h - where one vector's lanes come from and go to, and what the block
 * functions report (shared by every instantiation, defined once). */

#ifndef CYLRAY_KERNEL_IO_H
#define CYLRAY_KERNEL_IO_H

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
