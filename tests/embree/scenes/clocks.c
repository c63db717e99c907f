/* SPDX-License-Identifier: MIT */
/* clocks.c - CLOCK_MONOTONIC and CLOCK_PROCESS_CPUTIME_ID in seconds. */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
#include "clocks.h"

#include <time.h>

static double seconds(clockid_t id)
{
    struct timespec ts;
    clock_gettime(id, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

double eb_wall_s(void)
{
    return seconds(CLOCK_MONOTONIC);
}

double eb_cpu_s(void)
{
    return seconds(CLOCK_PROCESS_CPUTIME_ID);
}
