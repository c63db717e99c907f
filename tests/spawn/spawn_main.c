/* SPDX-License-Identifier: MIT */
/* spawn_main.c - what every spawn executable shares (spawn_main.h). */
#include "spawn_main.h"
#include "tcheck.h"

#include <stdio.h>
#include <string.h>

const cylray_kernels *isas[CYLRAY_ISA_COUNT];
int nisa;
int quick;
long failures;

double uni(cylgen_rng *r, double a, double b)
{
    return a + (b - a) * cylgen_uniform(r);
}

long scaled(long full)
{
    return quick ? (full + 99) / 100 : full;
}

void hit_point_form(const cylray_prepared *P, const float o[3], const float d[3], float t,
                    int32_t part, const float n[3], int form, float p[3], float *err)
{
    if (form)
        cylray_hit_point_normal(P, o, d, t, part, n, p, err);
    else
        cylray_hit_point(P, o, d, t, part, p, err);
}

int spawn_main(int argc, char **argv, const char *prog, const spawn_mode *modes, size_t n)
{
    quick = tc_quick();
    for (int i = 0; i < CYLRAY_ISA_COUNT; i++) {
        const cylray_kernels *k = cylray_kernels_for((cylray_isa)i);
        if (k)
            isas[nisa++] = k;
    }
    const char *mode = argc > 1 ? argv[1] : "";
    for (size_t i = 0; i < n; i++)
        if (strcmp(mode, modes[i].name) == 0) {
            const int ok = modes[i].run();
            printf("%s: %s\n", mode, ok ? "ok" : "FAILED");
            return ok ? 0 : 1;
        }
    fprintf(stderr, "usage: %s ", prog);
    for (size_t i = 0; i < n; i++)
        fprintf(stderr, "%s%s", i ? "|" : "", modes[i].name);
    fprintf(stderr, "\n");
    return 2;
}
