/* SPDX-License-Identifier: MIT */
/* stats.h - order statistics of samples: median, quartiles, extremes. */
#ifndef CYLBENCH_STATS_H
#define CYLBENCH_STATS_H

#include <stddef.h>

typedef struct stat5 {
    double med, min, max, q1, q3;
} stat5;

/* Sorts x[0..n) in place and summarises it; all zero when n == 0. */
void stat_summary(double *x, size_t n, stat5 *out);

/* The q-quantile (0..1) of sorted x, by linear interpolation between order statistics. */
double stat_quantile(const double *sorted, size_t n, double q);

void stat_sort(double *x, size_t n);

#endif
