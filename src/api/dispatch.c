/* SPDX-License-Identifier: MIT */
/* api/dispatch.c - choosing a path once, and the plain entry points that use it.
 *
 * The choice is made on the first call and kept in an atomic pointer: threads racing
 * on that first call compute the same answer, so the race is harmless. */
#include "cylray_internal.h"

#if defined(__AVX__) || defined(__AVX2__) || defined(__AVX512F__)
#error "api/dispatch.c runs before the CPU is known: compile it without AVX"
#endif

#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const cylray_kernels *const built[CYLRAY_ISA_COUNT] = {
    &cylray_kernels_scalar_,
#ifdef CYLRAY_HAVE_SSE41
    &cylray_kernels_sse41_,
#else
    NULL,
#endif
#ifdef CYLRAY_HAVE_AVX2
    &cylray_kernels_avx2_,
#else
    NULL,
#endif
#ifdef CYLRAY_HAVE_AVX512
    &cylray_kernels_avx512_,
#else
    NULL,
#endif
#ifdef CYLRAY_HAVE_NEON
    &cylray_kernels_neon_,
#else
    NULL,
#endif
};

static const char *const names[CYLRAY_ISA_COUNT] = {"scalar", "sse41", "avx2", "avx512",
                                                    "neon"};

const char *cylray_isa_name(cylray_isa isa)
{
    return (unsigned)isa < CYLRAY_ISA_COUNT ? names[isa] : "unknown";
}

/* The store policies of the x86 kernels (CYLRAY_STORE_*), chosen once per process:
 * AVX2 takes the CPU's (cylray_cpu_store_policy_), SSE4.1, which has no masked store,
 * the blends on every CPU; CYLRAY_STORES=masked|blend|lanes forces one on both (to
 * test each on any CPU; masked stores as lanes on SSE; another value is ignored).
 * Threads racing on the first call compute the same answer. */
#if defined(CYLRAY_HAVE_SSE41) || defined(CYLRAY_HAVE_AVX2)
static atomic_uint stores_chosen; /* 1 + AVX2's policy + 4 SSE4.1's; 0: not yet */
static unsigned store_policies(void)
{
    unsigned p = atomic_load_explicit(&stores_chosen, memory_order_relaxed);
    if (p)
        return p - 1u;
    unsigned avx = cylray_cpu_store_policy_(), sse = CYLRAY_STORE_BLEND;
    const char *want = getenv("CYLRAY_STORES");
    static const char *const names[3] = {"masked", "blend", "lanes"};
    for (unsigned i = 0; want && i < 3; i++)
        if (strcmp(want, names[i]) == 0)
            avx = sse = i;
    p = avx + 4u * sse;
    atomic_store_explicit(&stores_chosen, p + 1u, memory_order_relaxed);
    return p;
}
#endif

/* An ISA's table, with its store policy where it has several. */
static const cylray_kernels *with_stores(cylray_isa isa)
{
#if defined(CYLRAY_HAVE_SSE41) || defined(CYLRAY_HAVE_AVX2)
    const unsigned p = store_policies(), avx = p % 4u, sse = p / 4u;
    (void)avx, (void)sse; /* one of them, where one ISA alone is built */
#endif
#ifdef CYLRAY_HAVE_SSE41
    if (isa == CYLRAY_ISA_SSE41)
        return sse == CYLRAY_STORE_BLEND ? &cylray_kernels_sse41_blend_
                                         : &cylray_kernels_sse41_;
#endif
#ifdef CYLRAY_HAVE_AVX2
    if (isa == CYLRAY_ISA_AVX2)
        return avx == CYLRAY_STORE_BLEND   ? &cylray_kernels_avx2_blend_
               : avx == CYLRAY_STORE_LANES ? &cylray_kernels_avx2_lanes_
                                           : &cylray_kernels_avx2_;
#endif
    return built[isa];
}

const cylray_kernels *cylray_kernels_for(cylray_isa isa)
{
    if ((unsigned)isa >= CYLRAY_ISA_COUNT || !built[isa] || !cylray_cpu_has_(isa))
        return NULL;
    return with_stores(isa);
}

/* The warning, as one line from one fprintf call; a name that is no path at all (a
 * misspelling, another case) gets the list of the names that are. */
static void warn_isa(const char *want, int known, const char *used)
{
    if (known) {
        fprintf(stderr, "cylray: CYLRAY_ISA=%s is not available here; using %s\n", want, used);
        return;
    }
    char list[96] = "";
    size_t len = 0;
    for (int i = 0; i < CYLRAY_ISA_COUNT && len < sizeof list; i++)
        len += (size_t)snprintf(list + len, sizeof list - len, "%s%s", i ? ", " : "", names[i]);
    fprintf(stderr, "cylray: CYLRAY_ISA=%s is unknown (known: %s); using %s\n", want, list,
            used);
}

static const cylray_kernels *choose(void)
{
    const cylray_kernels *best = built[CYLRAY_ISA_SCALAR];
    for (int i = CYLRAY_ISA_COUNT - 1; i > CYLRAY_ISA_SCALAR; i--) {
        const cylray_kernels *k = cylray_kernels_for((cylray_isa)i);
        if (k) {
            best = k;
            break;
        }
    }
    const char *want = getenv("CYLRAY_ISA");
    if (want && *want) {
        int known = 0;
        for (int i = 0; i < CYLRAY_ISA_COUNT; i++) {
            if (strcmp(want, names[i]) == 0) {
                const cylray_kernels *k = cylray_kernels_for((cylray_isa)i);
                if (k)
                    return k;
                known = 1;
                break;
            }
        }
        static atomic_int warned;
        if (!atomic_exchange(&warned, 1))
            warn_isa(want, known, best->name);
    }
    return best;
}

static _Atomic(const cylray_kernels *) chosen;

const cylray_kernels *cylray_kernels_best(void)
{
    const cylray_kernels *k = atomic_load_explicit(&chosen, memory_order_acquire);
    if (!k) {
        k = choose();
        atomic_store_explicit(&chosen, k, memory_order_release);
    }
    return k;
}

uint32_t cylray_intersect4(const cylray_prepared *cyl, cylray_ray4 *ray, cylray_hit4 *hit,
                           uint32_t active, unsigned flags)
{
    return cylray_kernels_best()->intersect4(cyl, ray, hit, active, flags);
}
uint32_t cylray_intersect8(const cylray_prepared *cyl, cylray_ray8 *ray, cylray_hit8 *hit,
                           uint32_t active, unsigned flags)
{
    return cylray_kernels_best()->intersect8(cyl, ray, hit, active, flags);
}
uint32_t cylray_intersect16(const cylray_prepared *cyl, cylray_ray16 *ray, cylray_hit16 *hit,
                            uint32_t active, unsigned flags)
{
    return cylray_kernels_best()->intersect16(cyl, ray, hit, active, flags);
}
uint32_t cylray_occluded4(const cylray_prepared *cyl, const cylray_ray4 *ray, uint32_t active,
                          unsigned flags)
{
    return cylray_kernels_best()->occluded4(cyl, ray, active, flags);
}
uint32_t cylray_occluded8(const cylray_prepared *cyl, const cylray_ray8 *ray, uint32_t active,
                          unsigned flags)
{
    return cylray_kernels_best()->occluded8(cyl, ray, active, flags);
}
uint32_t cylray_occluded16(const cylray_prepared *cyl, const cylray_ray16 *ray, uint32_t active,
                           unsigned flags)
{
    return cylray_kernels_best()->occluded16(cyl, ray, active, flags);
}
size_t cylray_intersect_stream(const cylray_prepared *cyl, const cylray_rays *rays,
                               const cylray_hits *hits, size_t n, unsigned flags)
{
    return cylray_kernels_best()->intersect_stream(cyl, rays, hits, n, flags);
}
size_t cylray_occluded_stream(const cylray_prepared *cyl, const cylray_rays *rays,
                              uint8_t *occluded, size_t n, unsigned flags)
{
    return cylray_kernels_best()->occluded_stream(cyl, rays, occluded, n, flags);
}

#define LEAF_ENTRY_(m)                                                                         \
    int cylray_leaf_intersect##m(const cylray_leaf##m *leaf, cylray_ray1 *ray,                 \
                                 cylray_hit1 *hit, unsigned flags)                             \
    {                                                                                          \
        return cylray_kernels_best()->leaf_intersect##m(leaf, ray, hit, flags);                \
    }                                                                                          \
    int cylray_leaf_occluded##m(const cylray_leaf##m *leaf, const cylray_ray1 *ray,            \
                                unsigned flags)                                                \
    {                                                                                          \
        return cylray_kernels_best()->leaf_occluded##m(leaf, ray, flags);                      \
    }
LEAF_ENTRY_(4)
LEAF_ENTRY_(8)
LEAF_ENTRY_(16)
