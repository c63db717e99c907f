/* SPDX-License-Identifier: MIT */
/* clock.c - nanoseconds, TSC ticks and CPU pinning for the timing loops. */
#if defined(__linux__)
#define _GNU_SOURCE /* sched_setaffinity, sched_getcpu: Linux extensions */
#include <sched.h>
#else
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
#endif
#include "clock.h"

#include <stdio.h>
#include <time.h>

#if defined(__x86_64__) || defined(__i386__)
#include <x86intrin.h>
#define HAVE_TSC 1
#else
#define HAVE_TSC 0
#endif

int clk_flush_subnormals(void)
{
#if HAVE_TSC
    _mm_setcsr(_mm_getcsr() | 0x8040u); /* DAZ (bit 6) | FTZ (bit 15) */
    return 1;
#elif defined(__aarch64__)
    uint64_t fpcr;
    __asm__ volatile("mrs %0, fpcr" : "=r"(fpcr));
    fpcr |= (uint64_t)1 << 24; /* FZ */
    __asm__ volatile("msr fpcr, %0" : : "r"(fpcr));
    return 1;
#else
    return 0;
#endif
}

double clk_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e9 + (double)ts.tv_nsec;
}

double clk_cpu_ns(void)
{
    struct timespec ts;
    if (clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts) != 0)
        return clk_ns(); /* no thread clock: every sample then looks uninterrupted */
    return (double)ts.tv_sec * 1e9 + (double)ts.tv_nsec;
}

uint64_t clk_ticks(void)
{
#if HAVE_TSC
    /* No fence: a sample spans a millisecond or more, so a few instructions
     * reordered across the read cannot matter. */
    return __rdtsc();
#else
    return (uint64_t)clk_ns();
#endif
}

double clk_tsc_ghz(void)
{
    static double ghz;
    if (ghz > 0)
        return ghz;
#if HAVE_TSC
    /* Three 20 ms windows; the median resists one interrupted window. */
    double r[3];
    for (int k = 0; k < 3; k++) {
        double n0 = clk_ns();
        uint64_t t0 = clk_ticks();
        while (clk_ns() - n0 < 20e6) {
        }
        double n1 = clk_ns();
        uint64_t t1 = clk_ticks();
        r[k] = (double)(t1 - t0) / (n1 - n0);
    }
    double a = r[0], b = r[1], c = r[2];
    ghz = a > b ? (b > c ? b : (a > c ? c : a)) : (a > c ? a : (b > c ? c : b));
#else
    ghz = 1.0;
#endif
    return ghz;
}

int clk_pin(char *desc, size_t n)
{
#if defined(__linux__)
    int cpu = sched_getcpu();
    if (cpu >= 0) {
        cpu_set_t set;
        CPU_ZERO(&set);
        CPU_SET(cpu, &set);
        if (sched_setaffinity(0, sizeof set, &set) == 0) {
            snprintf(desc, n, "pinned to cpu %d", cpu);
            return 1;
        }
    }
#endif
    snprintf(desc, n, "not pinned");
    return 0;
}
