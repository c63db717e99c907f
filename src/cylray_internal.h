/* cylray_internal.h - what the library's translation units share and users never see. */
#ifndef CYLRAY_INTERNAL_H
#define CYLRAY_INTERNAL_H

#include "cylray.h"

#include <float.h>
#include <math.h>

#define CYLRAY_KIND_INFINITE 0u
#define CYLRAY_KIND_OPEN 1u   /* finite, no end discs: a tube */
#define CYLRAY_KIND_CAPPED 2u /* finite, closed solid */
#define CYLRAY_KIND_COUNT 3u

#define CYLRAY_MAGIC 0x63796c72u /* "cylr" */

/* Internal kernel flags, beside the public CYLRAY_* kernel flags (all below 0x20). */
#define CYLRAY_KF_OCCLUDED 0x100u
#define CYLRAY_KF_ALIGNED 0x200u
#define CYLRAY_KF_KIND_SHIFT 10

/* The kernel tables are indexed by the cylinder's variant (its kind, plus 3 when the
 * axis is a coordinate axis) and the flags that select a kernel, packed into 4 bits;
 * face-forward is a sign flip applied to the result and needs no kernel of its own. */
static inline unsigned cylray_variant_(const cylray_prepared *p)
{
    return p->kind + (p->axis_id ? CYLRAY_KIND_COUNT : 0u);
}
static inline unsigned cylray_isect_index_(unsigned kind, unsigned flags)
{
    return kind * 16u + (flags & CYLRAY_NORMAL) + ((flags & (CYLRAY_CULL_BACK | CYLRAY_REFINE |
                                                          CYLRAY_FAST)) >> 1);
}
static inline unsigned cylray_occ_index_(unsigned kind, unsigned flags)
{
    return kind * 8u + ((flags & (CYLRAY_CULL_BACK | CYLRAY_REFINE | CYLRAY_FAST)) >> 2);
}

static inline int cylray_prepared_ok_(const cylray_prepared *p)
{
    return p != 0 && p->magic == CYLRAY_MAGIC && p->kind < CYLRAY_KIND_COUNT &&
           p->axis_id <= 3u;
}

#if defined(__GNUC__) || defined(__clang__)
#define CYLRAY_INLINE static inline __attribute__((always_inline))
#define CYLRAY_POPCOUNT(x) ((unsigned)__builtin_popcount(x))
#define CYLRAY_CTZ(x) ((size_t)__builtin_ctz(x))
#else
#define CYLRAY_INLINE static inline
static inline unsigned CYLRAY_POPCOUNT(unsigned x)
{
    unsigned n = 0;
    for (; x; x &= x - 1) n++;
    return n;
}
static inline size_t CYLRAY_CTZ(unsigned x)
{
    size_t n = 0;
    for (; !(x & 1u); x >>= 1) n++;
    return n;
}
#endif

/* A cylinder along a coordinate axis is handled with the coordinates renamed by a
 * rotation (so cross products keep their form) that makes its axis the third one:
 * renames the cylinder's, the rays' and the hits' coordinates once per call, so that
 * the kernel reads and writes them in place, without a per-lane permutation. */
static inline void cylray_rename_(const cylray_prepared **P, const cylray_rays **R,
                                  const cylray_hits **H, cylray_prepared *Q,
                                  cylray_rays *RQ, cylray_hits *HQ)
{
    const unsigned k2 = (*P)->axis_id - 1u, k0 = (k2 + 1u) % 3u, k1 = (k2 + 2u) % 3u;
    const unsigned k[3] = {k0, k1, k2};
    *Q = **P;
    for (int j = 0; j < 3; j++) {
        Q->c[j] = (*P)->c[k[j]];
        Q->v[j] = (*P)->v[k[j]];
        Q->n[j] = (*P)->n[k[j]];
        Q->vk[j] = (*P)->vk[k[j]];
    }
    const float *o[3] = {(*R)->ox, (*R)->oy, (*R)->oz}, *d[3] = {(*R)->dx, (*R)->dy, (*R)->dz};
    *RQ = **R;
    RQ->ox = o[k0], RQ->oy = o[k1], RQ->oz = o[k2];
    RQ->dx = d[k0], RQ->dy = d[k1], RQ->dz = d[k2];
    if (*H) {
        float *n[3] = {(*H)->nx, (*H)->ny, (*H)->nz};
        *HQ = **H;
        HQ->nx = n[k0], HQ->ny = n[k1], HQ->nz = n[k2];
        *H = HQ;
    }
    *P = Q;
    *R = RQ;
}

#define CYLRAY_CAT_(a, b) a##b
#define CYLRAY_CAT(a, b) CYLRAY_CAT_(a, b)

extern const cylray_kernels cylray_kernels_scalar_;
extern const cylray_kernels cylray_kernels_sse41_;
extern const cylray_kernels cylray_kernels_avx2_;
extern const cylray_kernels cylray_kernels_avx512_;
extern const cylray_kernels cylray_kernels_neon_;

/* CPU support, from cpu.c: nonzero when the CPU and the OS can run that ISA. */
int cylray_cpu_has_(cylray_isa isa);

#endif
