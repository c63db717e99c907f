/* SPDX-License-Identifier: MIT */
/* api/estimate_mode.c - test builds only (meson -Destimate=runtime): which stand-in for
 * the hardware's estimates CYLRAY_FAST takes (simd/estimate.h), read once from
 * CYLRAY_TEST_ESTIMATE: hardware (or unset), exact, high, low, table. Another value
 * stops the process: a test that meant to check a stand-in must not pass on another. */
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

unsigned cylray_estimate_mode_(void);

unsigned cylray_estimate_mode_(void)
{
    static const char *const names[] = {"hardware", "exact", "high", "low", "table"};
    static atomic_uint chosen; /* 1 + the mode; 0: not yet */
    unsigned c = atomic_load_explicit(&chosen, memory_order_relaxed);
    if (c)
        return c - 1u;
    const char *want = getenv("CYLRAY_TEST_ESTIMATE");
    unsigned mode = 0;
    if (want && *want) {
        for (mode = 0; mode < sizeof names / sizeof *names; mode++)
            if (strcmp(want, names[mode]) == 0)
                break;
        if (mode == sizeof names / sizeof *names) {
            fprintf(stderr,
                    "cylray: CYLRAY_TEST_ESTIMATE=%s is none of hardware, exact, "
                    "high, low, table\n",
                    want);
            abort();
        }
    }
    atomic_store_explicit(&chosen, mode + 1u, memory_order_relaxed);
    return mode;
}
