/* SPDX-License-Identifier: MIT */
/* clock.h - the harness's clocks: nanoseconds from CLOCK_MONOTONIC, ticks from the TSC,
 * and pinning the thread to the core it runs on. */
#ifndef CYLBENCH_CLOCK_H
#define CYLBENCH_CLOCK_H

#include <stddef.h>
#include <stdint.h>

/* Monotonic wall time in nanoseconds. */
double clk_ns(void);

/* CPU time of the calling thread in nanoseconds: it stops while the thread is
 * descheduled, so comparing it with clk_ns() shows whether a sample was interrupted. */
double clk_cpu_ns(void);

/* The time stamp counter (a constant-rate counter on this CPU kind; on machines without
 * one, nanoseconds stand in and clk_tsc_ghz() returns 1). */
uint64_t clk_ticks(void);

/* TSC ticks per nanosecond, measured once against clk_ns over about 50 ms. */
double clk_tsc_ghz(void);

/* Pins the calling thread to the CPU it is on now, so that a migration cannot split a
 * sample between two cores' caches. Writes what happened into desc; returns 1 if pinned. */
int clk_pin(char *desc, size_t n);

/* Makes this thread's floating point treat subnormal inputs as zero and flush
 * subnormal results to zero (x86: MXCSR DAZ and FTZ; AArch64: FPCR.FZ). A diagnostic:
 * it shows whether subnormals cost time, at the price of results that differ from the
 * default environment's. Returns 1 when set, 0 where unsupported. */
int clk_flush_subnormals(void);

#endif
