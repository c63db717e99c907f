/* SPDX-License-Identifier: MIT */
/* kernels.c - the per-ISA table: cylray_kernels_for gives a complete table exactly for
 * the ISAs that were built and that this CPU runs (checked against the compiler's own
 * CPU detection, not the library's), names match cylray_isa_name, and the plain entry
 * points use the best of them when CYLRAY_ISA is not set. */
#define _POSIX_C_SOURCE 200809L
#include <stdlib.h>
#include <string.h>

#include "cylray.h"
#include "tcheck.h"

/* Which ISAs this build contains comes from meson (BUILT_ISAS, e.g. "scalar,sse41");
 * whether the CPU runs them, from the compiler's __builtin_cpu_supports. */
#ifndef BUILT_ISAS
#error "BUILT_ISAS must name the ISAs the library was built with"
#endif

static int built(const char *name)
{
    const char *list = BUILT_ISAS;
    const size_t n = strlen(name);
    for (const char *p = list; (p = strstr(p, name)) != NULL; p += n)
        if ((p == list || p[-1] == ',') && (p[n] == ',' || p[n] == '\0'))
            return 1;
    return 0;
}

static int cpu_runs(cylray_isa isa)
{
#if (defined(__x86_64__) || defined(__i386__)) && (defined(__GNUC__) || defined(__clang__))
    __builtin_cpu_init();
    switch (isa) {
    case CYLRAY_ISA_SCALAR:
        return 1;
    case CYLRAY_ISA_SSE41:
        return __builtin_cpu_supports("sse4.1");
    case CYLRAY_ISA_AVX2:
        return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
    case CYLRAY_ISA_AVX512:
        return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
               __builtin_cpu_supports("avx512dq");
    default:
        return 0;
    }
#elif defined(__aarch64__)
    return isa == CYLRAY_ISA_SCALAR || isa == CYLRAY_ISA_NEON;
#else
    return isa == CYLRAY_ISA_SCALAR;
#endif
}

int main(void)
{
    static const char *const names[CYLRAY_ISA_COUNT] = {"scalar", "sse41", "avx2", "avx512",
                                                        "neon"};
    /* The choice below must be the automatic one. */
    unsetenv("CYLRAY_ISA");

    const cylray_kernels *best = NULL;
    for (int i = 0; i < CYLRAY_ISA_COUNT; i++) {
        const cylray_isa isa = (cylray_isa)i;
        const char *nm = cylray_isa_name(isa);
        CHECK(nm && strcmp(nm, names[i]) == 0, "cylray_isa_name(%d) = \"%s\", expected \"%s\"",
              i, nm ? nm : "(null)", names[i]);
        const cylray_kernels *k = cylray_kernels_for(isa);
        const int want = built(names[i]) && cpu_runs(isa);
        CHECK(!!k == want, "cylray_kernels_for(%s) is %s, expected %s (built: %d, CPU: %d)",
              names[i], k ? "a table" : "NULL", want ? "a table" : "NULL", built(names[i]),
              cpu_runs(isa));
        if (!k)
            continue;
        best = k;
        CHECK(k->isa == isa, "table for %s says isa %d", names[i], (int)k->isa);
        CHECK(k->name && strcmp(k->name, names[i]) == 0, "table for %s is named \"%s\"",
              names[i], k->name ? k->name : "(null)");
        CHECK(k->intersect4 && k->intersect8 && k->intersect16 && k->occluded4 &&
                  k->occluded8 && k->occluded16 && k->intersect_stream && k->occluded_stream,
              "table for %s has a NULL entry", names[i]);
        CHECK(cylray_kernels_for(isa) == k, "cylray_kernels_for(%s) is not stable", names[i]);
    }
    CHECK(cylray_kernels_for(CYLRAY_ISA_SCALAR) != NULL, "no scalar path");
    CHECK(cylray_kernels_for(CYLRAY_ISA_COUNT) == NULL, "a table for CYLRAY_ISA_COUNT");
    CHECK(cylray_kernels_for((cylray_isa)-1) == NULL, "a table for ISA -1");
    CHECK(cylray_kernels_for((cylray_isa)1000) == NULL, "a table for ISA 1000");
    const char *unk = cylray_isa_name(CYLRAY_ISA_COUNT);
    CHECK(unk != NULL, "cylray_isa_name(COUNT) is NULL");
    for (int i = 0; unk && i < CYLRAY_ISA_COUNT; i++)
        CHECK(strcmp(unk, names[i]) != 0, "cylray_isa_name(COUNT) names a real ISA");
    CHECK(cylray_isa_name((cylray_isa)-7) != NULL, "cylray_isa_name(-7) is NULL");

    /* Without CYLRAY_ISA the plain entry points use the last (best) available path. */
    const cylray_kernels *b = cylray_kernels_best();
    CHECK(b == best, "cylray_kernels_best() is %s, the best available is %s",
          b ? b->name : "NULL", best ? best->name : "NULL");
    CHECK(cylray_kernels_best() == b, "cylray_kernels_best() changed between calls");
    return tc_report("api-kernels");
}
