/* SPDX-License-Identifier: MIT */
/* api/dispatch.c - the one place a path is chosen: its table (with the store policy and
 * FAST's choice the path takes), through which api/forward.c sends every plain entry point, and the
 * toolkit's instance that goes with it.
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

/* Which of names[0..n) the environment variable var holds, or -1 (unset, or another
 * value). */
static int env_pick(const char *var, const char *const *names, int n)
{
    const char *want = getenv(var);
    for (int i = 0; want && i < n; i++)
        if (strcmp(want, names[i]) == 0)
            return i;
    return -1;
}

/* The store policies of the x86 kernels (CYLRAY_STORE_*), chosen once per process:
 * AVX2 takes the CPU's (cylray_cpu_store_policy_), SSE4.1, which has no masked store,
 * the blends on every CPU; CYLRAY_STORES=masked|blend|lanes forces one on both (to
 * test each on any CPU; masked stores as lanes on SSE; another value is ignored).
 * Threads racing on the first call compute the same answer. */
static atomic_uint stores_chosen; /* 1 + AVX2's policy + 4 SSE4.1's; 0: not yet */
static unsigned store_policies(void)
{
    unsigned p = atomic_load_explicit(&stores_chosen, memory_order_relaxed);
    if (p)
        return p - 1u;
    unsigned avx = cylray_cpu_store_policy_(), sse = CYLRAY_STORE_BLEND;
    static const char *const names[3] = {"masked", "blend", "lanes"}; /* CYLRAY_STORE_* */
    const int forced = env_pick("CYLRAY_STORES", names, 3);
    if (forced >= 0)
        avx = sse = (unsigned)forced;
    p = avx + 4u * sse;
    atomic_store_explicit(&stores_chosen, p + 1u, memory_order_relaxed);
    return p;
}

/* Whether the x86 paths serve CYLRAY_FAST with their exact kernels, as where the CPU
 * divides quickly (cylray_cpu_divides_fast_), chosen once per process;
 * CYLRAY_ESTIMATES=on|off forces the estimates or the divisions (to test each on any
 * CPU; another value is ignored). */
static atomic_uint fast_chosen; /* 1 + the choice; 0: not yet */
static int fast_divides(void)
{
    const unsigned c = atomic_load_explicit(&fast_chosen, memory_order_relaxed);
    if (c)
        return (int)c - 1;
    static const char *const names[2] = {"on", "off"}; /* off: divide */
    const int forced = env_pick("CYLRAY_ESTIMATES", names, 2);
    const int divide = forced >= 0 ? forced : cylray_cpu_divides_fast_();
    atomic_store_explicit(&fast_chosen, 1u + (unsigned)divide, memory_order_relaxed);
    return divide;
}

/* The x86 tables that serve CYLRAY_FAST with the exact kernels, filled once each, when
 * first chosen (isa/table.h): the CPU runs the fill's ISA by then. A thread that finds
 * one being filled waits the few stores it takes. */
enum {
    DIV_SSE41,
    DIV_SSE41_BLEND,
    DIV_AVX2,
    DIV_AVX2_BLEND,
    DIV_AVX2_LANES,
    DIV_AVX512,
    DIV_N
};
static cylray_kernels divided_tables[DIV_N];
static atomic_uint divided_state[DIV_N]; /* 0 empty, 1 being filled, 2 filled */
CYLRAY_MAYBE_UNUSED static const cylray_kernels *divided(unsigned i,
                                                         void (*fill)(cylray_kernels *))
{
    unsigned s = atomic_load_explicit(&divided_state[i], memory_order_acquire);
    if (s != 2u && atomic_compare_exchange_strong(&divided_state[i], &s, 1u)) {
        fill(&divided_tables[i]);
        atomic_store_explicit(&divided_state[i], 2u, memory_order_release);
    }
    while (atomic_load_explicit(&divided_state[i], memory_order_acquire) != 2u)
        ;
    return &divided_tables[i];
}
#define PICK_(i, name) (divide ? divided(i, cylray_divided_##name) : &cylray_kernels_##name)

/* An ISA's table with the store policy p (store_policies' encoding) where it has
 * several, and FAST's choice (fast_divides) on x86. Both travel in the table: its
 * entry points pass the policy down and drop FAST where they divide
 * (kernel/query_slots.h), so no kernel reads either from anywhere else. */
static const cylray_kernels *with_choices(cylray_isa isa, unsigned p, int divide)
{
    const unsigned avx = p % 4u, sse = p / 4u;
    (void)avx, (void)sse, (void)divide; /* unread where fewer x86 ISAs are built */
#ifdef CYLRAY_HAVE_SSE41
    if (isa == CYLRAY_ISA_SSE41)
        return sse == CYLRAY_STORE_BLEND ? PICK_(DIV_SSE41_BLEND, sse41_blend_)
                                         : PICK_(DIV_SSE41, sse41_);
#endif
#ifdef CYLRAY_HAVE_AVX2
    if (isa == CYLRAY_ISA_AVX2)
        return avx == CYLRAY_STORE_BLEND   ? PICK_(DIV_AVX2_BLEND, avx2_blend_)
               : avx == CYLRAY_STORE_LANES ? PICK_(DIV_AVX2_LANES, avx2_lanes_)
                                           : PICK_(DIV_AVX2, avx2_);
#endif
#ifdef CYLRAY_HAVE_AVX512
    if (isa == CYLRAY_ISA_AVX512)
        return PICK_(DIV_AVX512, avx512_);
#endif
    return built[isa];
}
#undef PICK_

static const cylray_kernels *kernels_for(cylray_isa isa, unsigned p, int divide)
{
    if ((unsigned)isa >= CYLRAY_ISA_COUNT || !built[isa] || !cylray_cpu_has_(isa))
        return NULL;
    return with_choices(isa, p, divide);
}

const cylray_kernels *cylray_kernels_for(cylray_isa isa)
{
    return kernels_for(isa, store_policies(), fast_divides());
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

/* The path, its store policy and FAST's choice, chosen together. */
static const cylray_kernels *choose(void)
{
    const unsigned stores = store_policies();
    const int divide = fast_divides();
    const cylray_kernels *best = built[CYLRAY_ISA_SCALAR];
    for (int i = CYLRAY_ISA_COUNT - 1; i > CYLRAY_ISA_SCALAR; i--) {
        const cylray_kernels *k = kernels_for((cylray_isa)i, stores, divide);
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
                const cylray_kernels *k = kernels_for((cylray_isa)i, stores, divide);
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

/* The toolkit's surface coordinates take their FMA instance (toolkit/surface_cylinder.c) where
 * the path chosen is AVX2 or AVX-512: the CPU has FMA, and CYLRAY_ISA did not ask for
 * less. */
int cylray_surface_fma_(void)
{
    const cylray_isa isa = cylray_kernels_best()->isa;
    return isa == CYLRAY_ISA_AVX2 || isa == CYLRAY_ISA_AVX512;
}
