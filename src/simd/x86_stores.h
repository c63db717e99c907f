/* SPDX-License-Identifier: MIT */
/* simd/x86_stores.h - how the x86 kernels store the lanes that hit: whole vectors for
 * scratch, mask-register stores on AVX-512, and on SSE and AVX either masked stores or
 * one lane at a time, as the dispatch chose for the CPU.
 *
 * Included after simd/x86.h, with the same VW, X86_FMA and X86_KMASK, and optionally:
 *   X86_STORES_BY_LANE  1 to store a lane at a time on AVX, 0 for the masked stores;
 *                       the dispatch's choice (cylray_stores_by_lane_) when not set
 * simd/undef.h takes every name back. */

/* Whole-vector stores, for scratch that the caller reads back at the hit lanes only. */
#define vstoreu(p, x) VX(storeu_ps)(p, x)
#define vstoreu_part(p, x) VXI(storeu)((vi_ *)(void *)(p), VX(cvttps_epi32)(x))

#if X86_KMASK
#define vstore_m(p, m, x) VX(mask_storeu_ps)(p, m, x)
#define vstore_part_m(p, m, x) VX(mask_storeu_epi32)(p, m, VX(cvttps_epi32)(x))
#else /* vector masks */
/* The stores of the hit lanes (docs/performance.md, "Stores by vendor"). A lane that
 * did not hit is never written, so nothing may be read back and blended in. AVX has
 * a masked store, two uops on Intel cores but microcoded on AMD Zen 1 to 3 (42 uops
 * and 12 cycles for 256 bits); SSE has none at all. So the hit vector's fields are
 * stored together (vstore_hits): a plain store each when every lane hit, else either
 * the masked stores or one loop over the hit lanes that stores every field of a lane,
 * whose exit is the one branch that a mix of hits and misses mispredicts.
 * X86_STORES_BY_LANE says which on AVX: the choice the dispatch made for this CPU
 * (cylray_stores_by_lane_, cylray_internal.h); a constant where the includer sets it. */
#if X86_FMA && !defined(X86_STORES_BY_LANE)
#define X86_STORES_BY_LANE cylray_stores_by_lane_()
#endif
#define vstore_m(p, m, x) KFN(store_m)(p, m, x)
#define vstore_part_m(p, m, x) KFN(store_part_m)(p, m, x)
/* A partly hit vector, a lane at a time: every field of a lane, then the next. */
static inline __attribute__((always_inline)) void
KFN(store_lanes)(uint32_t b, int normal, float *pt, float *ptmax, int32_t *ppart, float *pnx,
                 float *pny, float *pnz, vf t, vi_ ip, vf nx, vf ny, vf nz)
{
    if (b == VFULL) {
        VX(storeu_ps)(pt, t);
        VX(storeu_ps)(ptmax, t);
        VXI(storeu)((vi_ *)(void *)ppart, ip);
        if (normal) {
            VX(storeu_ps)(pnx, nx);
            VX(storeu_ps)(pny, ny);
            VX(storeu_ps)(pnz, nz);
        }
        return;
    }
    float lt[VW], lx[VW], ly[VW], lz[VW];
    int32_t lp[VW];
    VX(storeu_ps)(lt, t);
    VXI(storeu)((vi_ *)(void *)lp, ip);
    if (normal) {
        VX(storeu_ps)(lx, nx);
        VX(storeu_ps)(ly, ny);
        VX(storeu_ps)(lz, nz);
    }
    for (uint32_t r = b; r; r &= r - 1u) {
        const unsigned j = (unsigned)__builtin_ctz(r);
        pt[j] = lt[j];
        ptmax[j] = lt[j];
        ppart[j] = lp[j];
        if (normal) {
            pnx[j] = lx[j];
            pny[j] = ly[j];
            pnz[j] = lz[j];
        }
    }
}
static inline __attribute__((always_inline)) void
KFN(store_hits)(vm m, int normal, float *pt, float *ptmax, int32_t *ppart, float *pnx,
                float *pny, float *pnz, vf t, vf part, vf nx, vf ny, vf nz)
{
    const vi_ ip = VX(cvttps_epi32)(part);
#if X86_FMA
    if (__builtin_expect(!X86_STORES_BY_LANE, 1)) {
        VX(maskstore_ps)(pt, VCASTI(m), t);
        VX(maskstore_ps)(ptmax, VCASTI(m), t);
        VX(maskstore_epi32)((int *)ppart, VCASTI(m), ip);
        if (normal) {
            VX(maskstore_ps)(pnx, VCASTI(m), nx);
            VX(maskstore_ps)(pny, VCASTI(m), ny);
            VX(maskstore_ps)(pnz, VCASTI(m), nz);
        }
        return;
    }
#endif
    /* Inline: out of line, with vectors for arguments, gcc 12 left the upper halves of
     * the ymm registers dirty on return from a one-vector packet, and the caller's SSE
     * code then ran 4x slower. */
    KFN(store_lanes)(mbits(m), normal, pt, ptmax, ppart, pnx, pny, pnz, t, ip, nx, ny, nz);
}
/* One field alone, as vstore_hits stores it. */
static inline __attribute__((always_inline)) void KFN(store_m)(float *p, vm m, vf x)
{
#if X86_FMA
    if (!X86_STORES_BY_LANE) {
        VX(maskstore_ps)(p, VCASTI(m), x);
        return;
    }
#endif
    const uint32_t b = mbits(m);
    if (b == VFULL) {
        VX(storeu_ps)(p, x);
        return;
    }
    float l[VW];
    VX(storeu_ps)(l, x);
    for (uint32_t r = b; r; r &= r - 1u)
        p[__builtin_ctz(r)] = l[__builtin_ctz(r)];
}
static inline __attribute__((always_inline)) void KFN(store_part_m)(int32_t *p, vm m, vf x)
{
    const vi_ xi = VX(cvttps_epi32)(x);
#if X86_FMA
    if (!X86_STORES_BY_LANE) {
        VX(maskstore_epi32)((int *)p, VCASTI(m), xi);
        return;
    }
#endif
    const uint32_t b = mbits(m);
    if (b == VFULL) {
        VXI(storeu)((vi_ *)(void *)p, xi);
        return;
    }
    int32_t l[VW];
    VXI(storeu)((vi_ *)(void *)l, xi);
    for (uint32_t r = b; r; r &= r - 1u)
        p[__builtin_ctz(r)] = l[__builtin_ctz(r)];
}
#define vstore_hits(m, normal, pt, ptmax, ppart, pnx, pny, pnz, t, part, nx, ny, nz)           \
    KFN(store_hits)(m, normal, pt, ptmax, ppart, pnx, pny, pnz, t, part, nx, ny, nz)
#endif
