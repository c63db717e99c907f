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

void narrow_packet(const cylray_ray16 *ray, const cylray_hit16 *hit, cylray_ray8 *r8,
                   cylray_hit8 *h8, cylray_ray4 *r4, cylray_hit4 *h4)
{
    for (int i = 0; i < 8; i++) {
        r8->ox[i] = ray->ox[i], r8->oy[i] = ray->oy[i], r8->oz[i] = ray->oz[i];
        r8->dx[i] = ray->dx[i], r8->dy[i] = ray->dy[i], r8->dz[i] = ray->dz[i];
        h8->t[i] = hit->t[i], h8->part[i] = hit->part[i];
        h8->nx[i] = hit->nx[i], h8->ny[i] = hit->ny[i], h8->nz[i] = hit->nz[i];
        if (i < 4) {
            r4->ox[i] = ray->ox[i], r4->oy[i] = ray->oy[i], r4->oz[i] = ray->oz[i];
            r4->dx[i] = ray->dx[i], r4->dy[i] = ray->dy[i], r4->dz[i] = ray->dz[i];
            h4->t[i] = hit->t[i], h4->part[i] = hit->part[i];
            h4->nx[i] = hit->nx[i], h4->ny[i] = hit->ny[i], h4->nz[i] = hit->nz[i];
        }
    }
}

int spawn_groups(long n, uint64_t seed, void (*group)(cylgen_rng *rng, long g, spawn_tally *t),
                 spawn_tally *t)
{
    cylgen_rng rng;
    cylgen_seed(&rng, seed);
    for (long g = 0; g < n; g++)
        group(&rng, g, t);
    return t->compared > 0 && t->differ == 0;
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
