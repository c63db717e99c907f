/* SPDX-License-Identifier: MIT */
/* run.h - what one run of the Embree comparison measures, row by row. */
#ifndef EB_RUN_H
#define EB_RUN_H

#include "judge.h"

#include <stdio.h>

enum { EB_PRIMARY, EB_SHADOW, EB_BOUNCE, EB_NPHASES };
enum { EB_NPACKETS = 4, EB_MAXT = 64 };
enum { EB_SET_CAMERA, EB_SET_RIM, EB_SET_AXIS, EB_NSETS };

extern const int eb_packets[EB_NPACKETS]; /* 1, 4, 8, 16 */

/* One variant on one scene with one ISA. */
typedef struct eb_row {
    char isa[16], scene[32], variant[16];
    int leaf_m, threads, skipped;
    char why[80];
    size_t ns, nsph, nprim; /* cylinders, spheres, Embree's primitives */
    double build_s;
    double mrays[EB_NPHASES][EB_NPACKETS]; /* at `threads` threads; NAN: not run */
    double scaling[EB_MAXT + 1];           /* primary, one ray a call, at 1..threads */
    double cores[EB_MAXT + 1];             /* CPU time / wall time in those runs */
    eb_err err[EB_NSETS];
    size_t diff_pixels; /* red + yellow against embree-curve */
} eb_row;

const char *eb_set_name(int set);
void eb_report(FILE *f, const eb_row *rows, size_t n, const char *machine);
void eb_report_csv(FILE *f, const eb_row *rows, size_t n);

#endif
