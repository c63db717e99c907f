/* SPDX-License-Identifier: MIT */
/* spawn_self.c - spawn_test self and nested: spawned rays never meet the surface they
 * leave; a coaxial cylinder just inside is still met. */

#include "spawn_common.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- self-intersection ------------------------------------------------------------ */
enum { K_REFL, K_TRANS, K_SHADOW, K_DIRS = 5 };

int run_self(void)
{
    const long G = groups_for(200000);
    long spawns = 0, traced[CYLRAY_ISA_COUNT] = {0}, self[CYLRAY_ISA_COUNT] = {0};
    long wrong_side = 0, exact_checked = 0, exact_self = 0, too_big = 0, kernel_faults = 0;
    long disagree = 0;
    long too_big_cat[SREF_COUNT] = {0};
    cylgen_rng rng;
    cylgen_seed(&rng, 77);
    for (long g = 0; g < G; g++) {
        const int cat = (int)(g % SREF_COUNT);
        cylgen_case c[SREF_GROUP];
        sref_group(cat, 5000 + (uint64_t)g, c);
        const cylray_cylinder *cyl = &c[0].cyl;
        cylray_prepared P;
        if (cylray_prepare(&P, cyl) != CYLRAY_OK)
            continue;
        /* hits from one ISA per group, in turn */
        cylray_ray16 ray;
        cylray_hit16 hit;
        const cylray_kernels *ks = isas[g % nisa];
        uint32_t m = trace_group(ks, &P, c, &ray, &hit);
        if (!m)
            continue;
        /* points and origins from that ISA's stream forms, checked against the scalar
         * pair bit for bit */
        float p[16][3], err[16];
        if (isa_points(ks, &P, &ray, &hit, m, p, err)) {
            disagree++;
            fail("self", &c[0], "the stream form differs from cylray_hit_point");
        }
        const double lim = 0.25 * fmin(cyl->radius, cyl->half_height);
        for (int dir = 0; dir < K_DIRS; dir++) {
            const int kind = dir < 2 ? K_REFL : dir < 4 ? K_TRANS : K_SHADOW;
            float x0[16][3], w[16][3], tmax[16];
            uint32_t use = 0;
            for (int i = 0; i < 16; i++) {
                if (!(m >> i & 1u))
                    continue;
                const int part = hit.part[i], Pm = part & CYLRAY_PART_MASK;
                double n[3];
                sref_normal(cyl, p[i], Pm, n);
                const int refl = part & CYLRAY_BACKFACE ? -1 : 1; /* the incident side */
                sref_secondary(&rng, n, cyl->radius, kind == K_SHADOW,
                               kind == K_REFL ? refl : -refl, w[i], &tmax[i]);
                use |= 1u << i;
            }
            if (isa_origins(ks, &P, &hit, use, (const float(*)[3])p, err, (const float(*)[3])w,
                            x0)) {
                disagree++;
                fail("self", &c[0], "the stream form differs from cylray_spawn_origin");
            }
            const uint32_t spawned = use;
            use = 0;
            for (int i = 0; i < 16; i++) {
                if (!(spawned >> i & 1u))
                    continue;
                const int part = hit.part[i], Pm = part & CYLRAY_PART_MASK;
                double mv = 0;
                for (int k = 0; k < 3; k++)
                    mv += ((double)x0[i][k] - p[i][k]) * ((double)x0[i][k] - p[i][k]);
                if (!(sqrt(mv) <= lim)) {
                    too_big++; /* outside the guarantee: the float grid is too coarse */
                    too_big_cat[cat]++;
                    continue;
                }
                spawns++;
                use |= 1u << i;
                unsigned surf = near_surfaces(cyl, p[i], err[i], Pm);
                if (!strictly_on_side(cyl, p[i], surf, w[i], x0[i])) {
                    wrong_side++;
                    fail("side", &c[i], "spawned origin not strictly on the ray's side");
                }
                if ((spawns & 31) == 0) {
                    cylref_hit h;
                    exact_checked++;
                    if (cylref_intersect(cyl, x0[i], w[i], 0.0f, tmax[i], 0, &h) == 1 &&
                        sref_self_hit(cyl, x0[i], w[i], part, h.part, (float)h.t)) {
                        exact_self++;
                        fail("self (exact)", &c[i], "the exact ray meets the surface left");
                    }
                }
            }
            for (int k = 0; k < nisa; k++) {
                float t[16];
                int32_t hp[16];
                const int width = 4 << ((dir + k) % 3);
                uint32_t got = trace16(isas[k], width, &P, (const float(*)[3])x0,
                                       (const float(*)[3])w, tmax, use, t, hp);
                traced[k] += popcount(use);
                for (int i = 0; i < 16; i++)
                    if ((got >> i & 1u) &&
                        sref_self_hit(cyl, x0[i], w[i], hit.part[i], hp[i], t[i])) {
                        self[k]++;
                        /* Is the kernel itself within its tolerance band there? If not,
                         * the fault is the kernel's, and the message says so. */
                        cylref_band b;
                        cylref_band_eval(cyl, x0[i], w[i], 0.0f, tmax[i], 0, &b);
                        const int kernel_fault = cylref_judge(&b, 1, hp[i], t[i], NULL) != 0;
                        kernel_faults += kernel_fault;
                        char s[400];
                        snprintf(s, sizeof s,
                                 "%s width %d%s: part %d left at (%a %a %a) err %a, "
                                 "spawned (%a %a %a) w (%a %a %a), hit part %d at t %a",
                                 isas[k]->name, width,
                                 kernel_fault
                                     ? " (an answer outside the kernel's tolerance band)"
                                     : "",
                                 hit.part[i], p[i][0], p[i][1], p[i][2], err[i], x0[i][0],
                                 x0[i][1], x0[i][2], w[i][0], w[i][1], w[i][2], hp[i], t[i]);
                        fail("self", &c[i], s);
                    }
            }
        }
    }
    long bad = wrong_side + exact_self + disagree;
    printf("self: points and origins from each ISA's stream forms in turn; %ld groups where "
           "they differ from the scalar pair\n",
           disagree);
    printf("self: outside the guarantee by category:");
    for (int c = 0; c < SREF_COUNT; c++)
        if (too_big_cat[c])
            printf(" %s %ld", sref_category_name(c), too_big_cat[c]);
    printf("\n");
    for (int k = 0; k < nisa; k++) {
        printf("self: %-7s %10ld spawned rays traced, %ld self-intersections\n", isas[k]->name,
               traced[k], self[k]);
        bad += self[k];
    }
    printf("self: %ld spawns, %ld not strictly on their side, %ld exact self-intersections "
           "in %ld checked exactly, %ld outside the guarantee (offset > min(R, H)/4); of the "
           "kernels' self-intersections, %ld are answers outside their own tolerance band\n",
           spawns, wrong_side, exact_self, exact_checked, too_big, kernel_faults);
    return bad == 0 && spawns > 0;
}

/* ---- nested ------------------------------------------------------------------ */

int run_nested(void)
{
    const long N = quick ? 2000 : 200000;
    long tried = 0, inside_inner = 0, exact_hits = 0, missed[CYLRAY_ISA_COUNT] = {0};
    long excused = 0;
    cylgen_rng rng;
    cylgen_seed(&rng, 4242);
    for (long n = 0; n < N; n++) {
        cylgen_case c; /* the outer cylinder and the primary ray, for the messages */
        cylray_cylinder in;
        sref_nested(&rng, &c.cyl, &in, c.o, c.d);
        cylray_prepared Po, Pi;
        if (cylray_prepare(&Po, &c.cyl) || cylray_prepare(&Pi, &in))
            continue;
        cylray_ray4 r4;
        cylray_hit4 h4;
        memset(&r4, 0, sizeof r4);
        r4.ox[0] = c.o[0], r4.oy[0] = c.o[1], r4.oz[0] = c.o[2];
        r4.dx[0] = c.d[0], r4.dy[0] = c.d[1], r4.dz[0] = c.d[2];
        r4.tmax[0] = INFINITY;
        if (!isas[n % nisa]->intersect4(&Po, &r4, &h4, 1u, 0) || (h4.part[0] & CYLRAY_BACKFACE))
            continue;
        float p[3], err, w[3], x0[3];
        cylray_hit_point(&Po, c.o, c.d, h4.t[0], h4.part[0], p, &err);
        double nn[3];
        sref_normal(&c.cyl, p, h4.part[0], nn);
        sref_transmitted(&rng, nn, w);
        cylray_spawn_origin(&Po, p, err, h4.part[0], w, x0);
        tried++;
        if (sref_inside_solid(&in, x0)) {
            inside_inner++;
            fail("nested", &c, "the spawned origin is already inside the inner cylinder");
            continue;
        }
        cylref_hit eh;
        if (cylref_intersect(&in, x0, w, 0.0f, INFINITY, 0, &eh) != 1)
            continue;
        exact_hits++;
        for (int k = 0; k < nisa; k++) {
            float tq;
            int32_t pq;
            if (sref_trace1(isas[k], &Pi, x0, w, &tq, &pq))
                continue;
            cylref_band b;
            cylref_band_eval(&in, x0, w, 0.0f, INFINITY, 0, &b);
            if (b.hit_unstable) {
                excused++;
                continue;
            }
            missed[k]++;
            fail("nested", &c, isas[k]->name);
        }
    }
    long bad = inside_inner;
    printf("nested: %ld transmitted rays, %ld origins inside the inner cylinder, %ld with an "
           "exact hit on it",
           tried, inside_inner, exact_hits);
    for (int k = 0; k < nisa; k++) {
        printf(", %s missed %ld", isas[k]->name, missed[k]);
        bad += missed[k];
    }
    printf(" (%ld excused: a graze within the tolerance band)\n", excused);
    return bad == 0 && exact_hits > tried / 2;
}
