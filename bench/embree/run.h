/* SPDX-License-Identifier: MIT */
/* run.h - what the Embree comparison measures, row by row. */
#ifndef EB_RUN_H
#define EB_RUN_H

#include "judge.h"

#include <stdio.h>

enum { EB_PRIMARY, EB_SHADOW, EB_BOUNCE, EB_NPHASES };
enum { EB_NPACKETS = 4, EB_MAXT = 64, EB_MAXRUNS = 99 };
enum { EB_SET_CAMERA, EB_SET_RIM, EB_SET_AXIS, EB_NSETS };

extern const int eb_packets[EB_NPACKETS]; /* 1, 4, 8, 16 */

/* One variant on one scene with one ISA. */
typedef struct eb_row {
    char isa[16], scene[32], variant[16];
    int leaf_m, threads, skipped;
    int runs, reps; /* timing runs, each the best of `reps` passes */
    char why[80];
    size_t ns, nsph, nprim; /* cylinders, spheres, Embree's primitives */
    double build_s;
    /* at `threads` threads, each run's rate (NAN: not run) and their median */
    double mrays_run[EB_NPHASES][EB_NPACKETS][EB_MAXRUNS];
    double mrays[EB_NPHASES][EB_NPACKETS];
    /* medians over the runs: primary, one ray a call, at 1..threads; the CPU time over
     * the wall time in those passes */
    double scaling[EB_MAXT + 1];
    double cores[EB_MAXT + 1];
    eb_err err[EB_NSETS];
    size_t diff_pixels; /* red + yellow against embree-curve */
} eb_row;

/* The median, min and max of the values of x[0..n) that are not NAN (all NAN if none). */
typedef struct eb_spread {
    double med, lo, hi;
} eb_spread;
eb_spread eb_spread_of(const double *x, int n);

const char *eb_set_name(int set);
void eb_report(FILE *f, const eb_row *rows, size_t n, const char *machine);
void eb_report_csv(FILE *f, const eb_row *rows, size_t n);

#endif
