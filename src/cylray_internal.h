/* SPDX-License-Identifier: MIT */
/* cylray_internal.h - what the library's translation units share and users never see. */
#ifndef CYLRAY_INTERNAL_H
#define CYLRAY_INTERNAL_H

#include "cylray.h"

#include <float.h>
#include <math.h>
#include <stdatomic.h>

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
#define CYLRAY_KF_SCALED 0x1000u /* the rare-lane instance: d scaled to near unit length */
#define CYLRAY_KF_ONE_END 0x2000u /* a capped cylinder with one disc only */
/* The hits go to the driver's own scratch, which reads back the hit lanes alone: the
 * kernel may store whole vectors there (the stream tail; a leaf always does). */
#define CYLRAY_KF_SCRATCH 0x4000u
/* The public flags every kernel reads at run time rather than being specialised for. */
#define CYLRAY_KF_RUNTIME (CYLRAY_FACE_FORWARD | CYLRAY_CULL_BACK)
/* What KFN(block) returns for a vector the rare instance must do (no lane is 31) */
#define CYLRAY_RARE_ 0x80000000u

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
static inline unsigned cylray_variant_(const cylray_prepared *p)
{
    return p->variant;
}
static inline int cylray_generic_(const cylray_prepared *p)
{
    return p->variant >= CYLRAY_VARIANT_GENERIC;
}
/* The one encoding of the specialised flags: bit 0 normals, bit 1 FAST, bit 2 REFINE
 * (the kernel template's KFL_ decodes it; cylray_occ_spec_ drops the normals). */
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
    return variant * 8u + cylray_spec_(flags);
}
static inline unsigned cylray_occ_index_(unsigned variant, unsigned flags)
{
    return variant * 4u + cylray_occ_spec_(flags);
}

static inline int cylray_prepared_ok_(const cylray_prepared *p)
{
    return p != 0 && p->magic == CYLRAY_MAGIC && p->kind < CYLRAY_KIND_COUNT &&
           p->axis_id <= 3u && (p->caps & ~CYLRAY_CAPPED) == 0 &&
           p->variant == cylray_variant_of_(p->kind, p->axis_id, p->g_s != 1.0f, p->caps);
}

#if defined(__GNUC__) || defined(__clang__)
#define CYLRAY_INLINE static inline __attribute__((always_inline))
#define CYLRAY_NOINLINE static __attribute__((noinline, cold))
/* Makes the compiler read memory again after this point instead of keeping what it
 * read before in registers (or in spill slots). */
#define CYLRAY_REREAD() __asm__ volatile("" ::: "memory")
#define CYLRAY_MAYBE_UNUSED __attribute__((unused))
#define CYLRAY_POPCOUNT(x) ((unsigned)__builtin_popcount(x))
#define CYLRAY_CTZ(x) ((size_t)__builtin_ctz(x))
#else
#define CYLRAY_INLINE static inline
#define CYLRAY_NOINLINE static
#define CYLRAY_REREAD() ((void)0)
#define CYLRAY_MAYBE_UNUSED
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

/* Whether the AVX kernels store a hit vector's lanes one by one (with a plain store
 * when every lane hit) instead of with AVX's masked stores, which AMD Zen 1 to 3 run
 * as microcode (docs/performance.md, "Stores by vendor"). Set by cylray_kernels_for
 * from the CPU, or CYLRAY_STORES=lanes|masked; read by every kernel call. Atomic, as
 * the first calls of several threads may set it (to the same value) while others run. */
extern atomic_int cylray_stores_by_lane_v_;
static inline int cylray_stores_by_lane_(void)
{
    return atomic_load_explicit(&cylray_stores_by_lane_v_, memory_order_relaxed);
}
int cylray_cpu_stores_by_lane_(void);

/* A cylinder along a coordinate axis is handled with the coordinates renamed by a
 * rotation (so cross products keep their form) that makes its axis the third one:
 * along x, (x, y, z) is read as (y, z, x); along y, as (z, x, y). cylray_prepare stores
 * the renamed center (cr); the kernels rename the rays' and the hits' coordinate
 * arrays, once per call, and then read and write them in place. */
static inline void cylray_axis_order_(const cylray_prepared *P, int aligned, size_t k[3])
{
    for (int j = 0; j < 3; j++)
        k[j] = aligned ? P->order[j] : (size_t)j;
}

/* The views of a packet struct (cylray_rayN, cylray_hitN): field f of n lanes each
 * at ray + f n, renamed when aligned. */
static inline cylray_rays cylray_packet_rays_(const cylray_prepared *P, float *ray, size_t n,
                                              int aligned)
{
    size_t k[3];
    cylray_axis_order_(P, aligned, k);
    cylray_rays q = {ray + k[0] * n,       ray + k[1] * n,       ray + k[2] * n,
                     ray + (3 + k[0]) * n, ray + (3 + k[1]) * n, ray + (3 + k[2]) * n,
                     ray + 6 * n,          ray + 7 * n};
    return q;
}

static inline cylray_hits cylray_packet_hits_(const cylray_prepared *P, float *hit, size_t n,
                                              int aligned)
{
    size_t k[3];
    cylray_axis_order_(P, aligned, k);
    cylray_hits q = {hit, hit + (1 + k[0]) * n, hit + (1 + k[1]) * n, hit + (1 + k[2]) * n,
                     (int32_t *)(void *)(hit + 4 * n)};
    return q;
}

/* The same renaming for a stream's separate arrays. */
static inline cylray_rays cylray_rays_renamed_(const cylray_prepared *P, const cylray_rays *r)
{
    const float *o[3] = {r->ox, r->oy, r->oz}, *d[3] = {r->dx, r->dy, r->dz};
    size_t k[3];
    cylray_axis_order_(P, 1, k);
    cylray_rays q = {o[k[0]], o[k[1]], o[k[2]], d[k[0]], d[k[1]], d[k[2]], r->tmin, r->tmax};
    return q;
}

static inline cylray_hits cylray_hits_renamed_(const cylray_prepared *P, const cylray_hits *h)
{
    float *nv[3] = {h->nx, h->ny, h->nz};
    size_t k[3];
    cylray_axis_order_(P, 1, k);
    cylray_hits q = {h->t, nv[k[0]], nv[k[1]], nv[k[2]], h->part};
    return q;
}

/* A leaf's fields: geom_[LF_*][lane], the meta_ bits, and its lane count by type. The
 * axis v is the user's scaled by a power of two (exact), as in cylray_prepared. */
enum {
    CYLRAY_LF_CX, CYLRAY_LF_CY, CYLRAY_LF_CZ, /* center */
    CYLRAY_LF_VX, CYLRAY_LF_VY, CYLRAY_LF_VZ, /* axis */
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
 * disc is part of the surface, [2] those whose high disc is; [3] is 0. The leaf
 * starts with the fields a kernel reads, so it is passed to one as a float pointer. */
enum { CYLRAY_LM_USED, CYLRAY_LM_LO, CYLRAY_LM_HI };
static inline unsigned cylray_leaf_caps_(const uint32_t *meta, unsigned lane)
{
    return ((meta[CYLRAY_LM_LO] >> lane) & 1u ? CYLRAY_CAPPED_LO : 0u) |
           ((meta[CYLRAY_LM_HI] >> lane) & 1u ? CYLRAY_CAPPED_HI : 0u);
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
