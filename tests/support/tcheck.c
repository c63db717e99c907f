/* SPDX-License-Identifier: MIT */
/* tcheck.c - the failure counter behind CHECK. */
#include "tcheck.h"

#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

long tc_checks_;
long tc_failures_;
int tc_silent_;

/* Past this many, failures are only counted: one bug usually fails thousands of
 * checks, and the first few say everything. */
#define TC_PRINT_MAX 40

void tc_fail_(const char *file, int line, const char *fmt, ...)
{
    tc_failures_++;
    static int verbose = -1;
    if (verbose < 0) {
        const char *v = getenv("CYLRAY_TEST_VERBOSE");
        verbose = v && *v && strcmp(v, "0") != 0;
    }
    if (tc_silent_ || (tc_failures_ > TC_PRINT_MAX && !verbose))
        return;
    fprintf(stderr, "FAIL %s:%d: ", file, line);
    va_list ap;
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fputc('\n', stderr);
    if (tc_failures_ == TC_PRINT_MAX && !verbose)
        fprintf(stderr, "(further failures are counted, not printed; CYLRAY_TEST_VERBOSE=1 "
                        "prints all)\n");
}

int tc_report(const char *name)
{
    printf("%s: %ld checks, %ld failures\n", name, tc_checks_, tc_failures_);
    if (tc_checks_ == 0) {
        printf("%s: no check ran\n", name);
        return 1;
    }
    return tc_failures_ != 0;
}

int tc_quick(void)
{
    const char *q = getenv("CYLRAY_TEST_QUICK");
    return q && *q && strcmp(q, "0") != 0;
}

int tc_same(float a, float b)
{
    return memcmp(&a, &b, sizeof a) == 0;
}

/* Maps floats to integers that are ordered like the floats, so that their difference
 * counts the floats in between. */
static int64_t ordered(float x)
{
    int32_t i;
    memcpy(&i, &x, sizeof i);
    return i < 0 ? -(int64_t)(i & 0x7fffffff) : (int64_t)i;
}

double tc_ulps(float a, float b)
{
    if (!isfinite(a) || !isfinite(b))
        return a == b ? 0.0 : INFINITY;
    int64_t d = ordered(a) - ordered(b);
    return (double)(d < 0 ? -d : d);
}
