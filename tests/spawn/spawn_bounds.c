/* SPDX-License-Identifier: MIT */
/* spawn_bounds.c - spawn_test bounds: the hit point's bound holds its exact distance. */

#include "spawn_common.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- bounds ------------------------------------------------------------------- */

int run_bounds(void)
{
    long hits = 0, viol = 0, disagree = 0;
    const long G = groups_for(2000);
    printf("%-13s %9s %10s %12s %12s %12s\n", "category", "hits", "violations", "err/ulp p50",
           "err/ulp max", "err/exact p50");
    for (int cat = 0; cat < SREF_COUNT; cat++) {
        long ch = 0, cv = 0;
        static double rel[2000 * 16 * CYLRAY_ISA_COUNT], ulps[2000 * 16 * CYLRAY_ISA_COUNT];
        long nr = 0, nu = 0;
        double umax = 0;
        for (long g = 0; g < G; g++) {
            cylgen_case c[SREF_GROUP];
            sref_group(cat, 1000 + (uint64_t)g, c);
            cylray_prepared P;
            if (cylray_prepare(&P, &c[0].cyl) != CYLRAY_OK)
                continue;
            for (int k = 0; k < nisa; k++) {
                cylray_ray16 ray;
                cylray_hit16 hit;
                uint32_t m = trace_group(isas[k], &P, c, &ray, &hit);
                /* the points of this ISA's stream form, the same as the scalar pair's */
                float pk[16][3], ek[16];
                if (isa_points(isas[k], &P, &ray, &hit, m, pk, ek)) {
                    disagree++;
                    fail("bound", &c[0], "the stream form differs from cylray_hit_point");
                }
                for (int i = 0; i < SREF_GROUP; i++) {
                    if (!(m >> i & 1u))
                        continue;
                    const float *p = pk[i], err = ek[i];
                    const double dist = sref_dist_part(&c[i].cyl, p, hit.part[i]);
                    ch++;
                    if (!(dist <= err) || !isfinite(err)) {
                        cv++;
                        char s[160];
                        snprintf(s, sizeof s, "%s part %d: distance %.3g > bound %.3g",
                                 isas[k]->name, hit.part[i], dist, (double)err);
                        fail("bound", &c[i], s);
                        continue;
                    }
                    double pm = fmax(fabs(p[0]), fmax(fabs(p[1]), fabs(p[2])));
                    double u = err / cylref_float_ulp(pm);
                    ulps[nu++] = u;
                    umax = fmax(umax, u);
                    if (dist > 0)
                        rel[nr++] = err / dist;
                }
            }
        }
        qsort(ulps, (size_t)nu, sizeof *ulps, cmp);
        qsort(rel, (size_t)nr, sizeof *rel, cmp);
        printf("%-13s %9ld %10ld %12.3g %12.3g %12.3g\n", sref_category_name(cat), ch, cv,
               nu ? ulps[nu / 2] : 0.0, umax, nr ? rel[nr / 2] : 0.0);
        hits += ch;
        viol += cv;
    }
    printf("bounds: %ld hits over %d ISAs (each ISA's hits through its own stream form), "
           "%ld violations, %ld groups where the stream form differs from the scalar one\n",
           hits, nisa, viol, disagree);
    return viol == 0 && disagree == 0 && hits > 0;
}
