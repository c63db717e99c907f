/* SPDX-License-Identifier: MIT */
/* stats.c - order statistics for timing samples and error distributions. */
#include "stats.h"

#include <stdlib.h>

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

void stat_sort(double *x, size_t n)
{
    qsort(x, n, sizeof *x, cmp_double);
}

double stat_quantile(const double *s, size_t n, double q)
{
    if (n == 0)
        return 0;
    double pos = q * (double)(n - 1);
    size_t i = (size_t)pos;
    if (i + 1 >= n)
        return s[n - 1];
    double f = pos - (double)i;
    return s[i] + f * (s[i + 1] - s[i]);
}

void stat_summary(double *x, size_t n, stat5 *out)
{
    stat5 r = {0, 0, 0, 0, 0};
    if (n) {
        stat_sort(x, n);
        r.med = stat_quantile(x, n, 0.5);
        r.q1 = stat_quantile(x, n, 0.25);
        r.q3 = stat_quantile(x, n, 0.75);
        r.min = x[0];
        r.max = x[n - 1];
    }
    *out = r;
}
