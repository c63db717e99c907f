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
 * rotation (so cross products keep their form) that makes its axis the third one.
 * cylray_prepare stores the renamed center (cr); the entry points rename the rays' and
 * the hits' coordinate arrays, once per call, so that the kernel reads and writes them
 * in place. The pointers are renamed by value: a copy of a pointer struct just stored
 * by the caller would read across several stores, which store forwarding cannot serve
 * (it cost about 100 cycles a call). */
static inline cylray_rays cylray_rays_renamed_(const cylray_prepared *P, const cylray_rays *r)
{
    const float *x = r->ox, *y = r->oy, *z = r->oz, *u = r->dx, *v = r->dy, *w = r->dz;
    cylray_rays q = {x, y, z, u, v, w, r->tmin, r->tmax};
    if (P->axis_id == 1u) {
        q.ox = y, q.oy = z, q.oz = x, q.dx = v, q.dy = w, q.dz = u;
    } else if (P->axis_id == 2u) {
        q.ox = z, q.oy = x, q.oz = y, q.dx = w, q.dy = u, q.dz = v;
    }
    return q;
}

static inline cylray_hits cylray_hits_renamed_(const cylray_prepared *P, const cylray_hits *h)
{
    float *x = h->nx, *y = h->ny, *z = h->nz;
    cylray_hits q = {h->t, x, y, z, h->part};
    if (P->axis_id == 1u) {
        q.nx = y, q.ny = z, q.nz = x;
    } else if (P->axis_id == 2u) {
        q.nx = z, q.ny = x, q.nz = y;
    }
    return q;
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
