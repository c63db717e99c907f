/* SPDX-License-Identifier: MIT */
/* stores.c - cylstores: what the store of a vector's hit lanes costs, per policy.
 *
 * The kernel stores six fields of a hit vector (t, tmax, part and the normal's three
 * components) through vstore_hits (src/simd/x86_stores.h), writing the lanes
 * that hit and no other. This times the store stage alone, with the policies that
 * header offers, from the header itself (vstore_hits), for a vector whose lanes are
 * all active:
 *   masked  the AVX masked store (vmaskmovps) of each field (Intel);
 *   blend   load, blend the hit lanes in, store each field (AMD, and SSE);
 *   lanes   a plain store of each field when every lane hit, else one loop over the
 *           hit lanes that stores all six fields of a lane (a partly active vector);
 * on 8 lanes (ymm) and 4 (xmm), over hit masks drawn as a tracer's rays make them:
 * every lane, none but one, and each lane with probability 1/2, 3/4 and 7/8 (random,
 * so that a branch on the mask mispredicts as it would on incoherent rays). Reported:
 * TSC ticks and nanoseconds per vector, the median of --reps runs, and the machine.
 *
 *     build/rel/bench/stores/cylstores [--reps=N]
 *
 * It measures one core's store path in isolation; whether a policy pays inside the
 * kernel, where the stores overlap a long dependency chain, is what the A/B runs of
 * the whole harness decide (docs/performance.md). */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "clock.h"
#include "internal/variants.h"
#include "machine.h"
#include "stats.h"

#if (defined(__x86_64__) || defined(__i386__)) && defined(__AVX2__) && defined(__FMA__)
#include <immintrin.h>

#define X86_FMA 1
#define X86_KMASK 0

/* One instantiation of the header per width: the store stage of a hit vector with
 * normals, as the kernel runs it (vstore_hits), with every lane active. */
#define RUN_(name)                                                                             \
    static void name(unsigned pol, float *const *f, int32_t *part, const uint32_t *m,          \
                     size_t nv)                                                                \
    {                                                                                          \
        for (size_t v = 0; v < nv; v++) {                                                      \
            const vm mk = mfrom_bits(m[v]);                                                    \
            const vf x = vset1((float)v);                                                      \
            const size_t o = (v & 63u) * VW;                                                   \
            vstore_hits(mk, VFULL, pol, 1, f[0] + o, f[1] + o, part + o, f[2] + o, f[3] + o,   \
                        f[4] + o, x, vadd(x, vset1(1.0f)), vadd(x, vset1(2.0f)),               \
                        vadd(x, vset1(3.0f)), vadd(x, vset1(4.0f)));                           \
        }                                                                                      \
    }
#define VW 8
#define KFN(n) n##_8
#include "simd/x86.h"
#include "simd/x86_stores.h"
RUN_(run8)
#include "simd/undef.h"
#undef KFN

#define VW 4
#define KFN(n) n##_4
#include "simd/x86.h"
#include "simd/x86_stores.h"
RUN_(run4)
#include "simd/undef.h"
#undef KFN

typedef void (*run_fn)(unsigned, float *const *, int32_t *, const uint32_t *, size_t);

static uint64_t rng(uint64_t *s)
{
    uint64_t z = (*s += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

int main(int argc, char **argv)
{
    int reps = 15;
    for (int a = 1; a < argc; a++)
        if (strncmp(argv[a], "--reps=", 7) == 0)
            reps = atoi(argv[a] + 7);
    if (reps < 1 || reps > 1000)
        reps = 15;
    machine_info mi;
    machine_probe(&mi);
    printf("cylstores: %s (%s), %s, %s build, %s\n", mi.cpu, mi.cpuid, mi.compiler,
           mi.buildtype, mi.pinned);
    printf("TSC %.2f GHz, core ~%.2f GHz; ticks and ns per vector of six field stores "
           "(median of %d)\n\n",
           mi.tsc_ghz, mi.core_ghz, reps);

    enum { NV = 1 << 16 };
    static uint32_t masks[NV];
    static float fields[5][64 * 8];
    static int32_t part[64 * 8];
    float *const f[5] = {fields[0], fields[1], fields[2], fields[3], fields[4]};
    const struct {
        const char *name;
        int w;
        run_fn fn;
        unsigned policy;
    } pol[] = {{"masked", 8, run8, CYLRAY_STORE_MASKED},
               {"blend", 8, run8, CYLRAY_STORE_BLEND},
               {"lanes", 8, run8, CYLRAY_STORE_LANES},
               {"blend", 4, run4, CYLRAY_STORE_BLEND},
               {"lanes", 4, run4, CYLRAY_STORE_LANES}};
    const struct {
        const char *name;
        int p16; /* per-lane hit probability in 16ths; 16 every lane, 0 one lane */
    } mix[] = {{"all lanes", 16}, {"one lane", 0}, {"p=1/2", 8}, {"p=3/4", 12}, {"p=7/8", 14}};
    printf("%-12s %5s", "policy", "lanes");
    for (size_t x = 0; x < sizeof mix / sizeof mix[0]; x++)
        printf(" %17s", mix[x].name);
    printf("\n");
    for (size_t pi = 0; pi < sizeof pol / sizeof pol[0]; pi++) {
        printf("%-12s %5d", pol[pi].name, pol[pi].w);
        for (size_t x = 0; x < sizeof mix / sizeof mix[0]; x++) {
            uint64_t s = 12345 + x;
            const uint32_t full = (1u << pol[pi].w) - 1u;
            for (size_t v = 0; v < NV; v++) {
                uint32_t m = 0;
                if (mix[x].p16 == 16)
                    m = full;
                else if (mix[x].p16 == 0)
                    m = 1u << (rng(&s) % (uint64_t)pol[pi].w);
                else
                    for (int l = 0; l < pol[pi].w; l++)
                        m |= (rng(&s) % 16u < (uint64_t)mix[x].p16 ? 1u : 0u) << l;
                masks[v] = m ? m : 1u; /* the store stage runs only for a hit vector */
            }
            double t[1000], ns[1000];
            pol[pi].fn(pol[pi].policy, f, part, masks, NV); /* warm */
            for (int r = 0; r < reps; r++) {
                const double n0 = clk_ns();
                const uint64_t t0 = clk_ticks();
                pol[pi].fn(pol[pi].policy, f, part, masks, NV);
                t[r] = (double)(clk_ticks() - t0) / NV;
                ns[r] = (clk_ns() - n0) / NV;
            }
            stat5 st, sn;
            stat_summary(t, (size_t)reps, &st);
            stat_summary(ns, (size_t)reps, &sn);
            printf(" %7.2f t %6.2f ns", st.med, sn.med);
        }
        printf("\n");
    }
    /* Keep the stores alive. */
    unsigned sum = 0;
    for (int i = 0; i < 64 * 8; i++)
        sum += (unsigned)part[i] + (unsigned)fields[4][i];
    printf("\n(checksum %u)\n", sum & 1u);
    return 0;
}
#else
int main(void)
{
    printf("cylstores: built without AVX2+FMA (x86 only); nothing to measure\n");
    return 0;
}
#endif
