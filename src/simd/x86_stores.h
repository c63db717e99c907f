/* SPDX-License-Identifier: MIT */
/* simd/x86_stores.h - how the x86 kernels store the lanes that hit: whole vectors for
 * scratch, mask-register stores on AVX-512, and on SSE and AVX blends, masked stores
 * or one lane at a time, by the store policy of the table the dispatch chose.
 *
 * Included after simd/x86.h, with the same VW and X86_KMASK; simd/undef.h
 * takes every name back. */

/* Whole-vector stores, for scratch that the caller reads back at the hit lanes only. */
#define vstoreu(p, x) VX(storeu_ps)(p, x)
#define vstoreu_part(p, x) VXI(storeu)((vi_ *)(void *)(p), VX(cvttps_epi32)(x))

#if X86_KMASK
#define vstore_m(p, m, x) VX(mask_storeu_ps)(p, m, x)
#define vstore_part_m(p, m, x) VX(mask_storeu_epi32)(p, m, VX(cvttps_epi32)(x))
#else /* vector masks */
/* The stores of the hit lanes, by the policy the dispatch chose with the table
 * (CYLRAY_STORE_*, internal/variants.h; docs/performance.md, "Stores by vendor"). AVX's
 * masked store is two uops on Intel cores but microcode on AMD Zen 1 to 4 (11-17
 * cycles each for 256 bits); SSE has none. A missed lane keeps its value, and may be
 * stored back unchanged in a whole-vector store, but an inactive lane is never
 * touched: so a vector whose lanes are all active may load each field, blend the hit
 * lanes in and store it whole, which every core runs at a plain store's cost. The
 * fields are stored together: a plain store each when every lane hit; else, by the
 * policy, the masked stores, the blends (all lanes active) or one loop over the hit
 * lanes that stores every field of a lane, whose exit is the one branch that a mix of
 * hits and misses mispredicts. */
/* A partly hit vector, a lane at a time: every field of a lane, then the next. */
static inline __attribute__((always_inline)) void
KFN(store_lanes)(uint32_t b, int normal, float *pt, float *ptmax, int32_t *ppart, float *pnx,
                 float *pny, float *pnz, vf t, vi_ ip, vf nx, vf ny, vf nz)
{
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
/* The six fields of a hit vector (the part as its bits), each through ST(p, x). */
#define KFIELDS_(ST)                                                                           \
    do {                                                                                       \
        ST(pt, t);                                                                             \
        ST(ptmax, t);                                                                          \
        ST((float *)(void *)ppart, VCASTF(ip));                                                \
        if (normal) {                                                                          \
            ST(pnx, nx);                                                                       \
            ST(pny, ny);                                                                       \
            ST(pnz, nz);                                                                       \
        }                                                                                      \
    } while (0)
#define KPLAIN_(p, x) VX(storeu_ps)(p, x)
/* a vector whose lanes are all active: the hit lanes blended into what is there */
#define KBLEND_(p, x) VX(storeu_ps)(p, VX(blendv_ps)(VX(loadu_ps)(p), x, m))
#define KMASKED_(p, x) VX(maskstore_ps)(p, VCASTI(m), x)
static inline __attribute__((always_inline)) void
KFN(store_hits)(vm m, uint32_t active, unsigned stores, int normal, float *pt, float *ptmax,
                int32_t *ppart, float *pnx, float *pny, float *pnz, vf t, vf part, vf nx, vf ny,
                vf nz)
{
    const vi_ ip = VX(cvttps_epi32)(part);
    const uint32_t b = mbits(m);
    if (b == VFULL) {
        KFIELDS_(KPLAIN_);
        return;
    }
    if (stores == CYLRAY_STORE_BLEND && active == VFULL) {
        KFIELDS_(KBLEND_);
        return;
    }
#if X86_AVX
    if (stores == CYLRAY_STORE_MASKED) {
        KFIELDS_(KMASKED_);
        return;
    }
#endif
    /* Inline: out of line, with vectors for arguments, gcc 12 left the upper halves of
     * the ymm registers dirty on return from a one-vector packet, and the caller's SSE
     * code then ran 4x slower. */
    KFN(store_lanes)(b, normal, pt, ptmax, ppart, pnx, pny, pnz, t, ip, nx, ny, nz);
}
#undef KFIELDS_
#undef KPLAIN_
#undef KBLEND_
#undef KMASKED_
#define vstore_hits KFN(store_hits)
#endif
