/* SPDX-License-Identifier: MIT */
/* spawn_reintersect.c - spawn_test reintersect: pbrt-v4's Reintersect setup. */

#include "spawn_common.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- pbrt-v4's Reintersect ------------------------------------------------------ */

/* 10^u, u uniform in [-e, e] (pbrt's pExp). */
static double pexp(cylgen_rng *r, double e)
{
    return pow(10.0, (2 * cylgen_uniform(r) - 1) * e);
}

/* Traces 16 rays (x0, w) on ISA k at width 4 << (which % 3) and returns the mask of
 * those with any hit in [0, inf). */
static uint32_t occluded16(const cylray_kernels *k, int which, const cylray_prepared *P,
                           const float x0[16][3], const float w[16][3])
{
    const float tmax[16] = {INFINITY, INFINITY, INFINITY, INFINITY, INFINITY, INFINITY,
                            INFINITY, INFINITY, INFINITY, INFINITY, INFINITY, INFINITY,
                            INFINITY, INFINITY, INFINITY, INFINITY};
    float t[16];
    int32_t part[16];
    return trace16(k, 4 << (which % 3), P, x0, w, tmax, 0xffffu, t, part);
}

/* One tube of pbrt's test on one ISA: the primary hit with its normal, then `rays`
 * spawned rays, face-forwarded to the kernel's normal, in two ways: the README's (the
 * point at the kernel's azimuth, the side form, outward) and the plain pair (the point
 * from o + t d, the side from w). Adds the re-hits of each. */
static void reintersect_one(const cylray_kernels *k, const cylray_cylinder *cyl,
                            const float o[3], const float d[3], int rays, cylgen_rng *rng,
                            long *hits, long *spawned, long *rehit_readme, long *rehit_plain,
                            long *big, long *rehit_big)
{
    cylray_prepared P;
    if (cylray_prepare(&P, cyl) != CYLRAY_OK)
        return;
    cylray_ray4 r;
    cylray_hit4 h;
    memset(&r, 0, sizeof r);
    r.ox[0] = o[0], r.oy[0] = o[1], r.oz[0] = o[2];
    r.dx[0] = d[0], r.dy[0] = d[1], r.dz[0] = d[2];
    r.tmax[0] = INFINITY;
    if (!(k->intersect4(&P, &r, &h, 1u, CYLRAY_NORMAL) & 1u))
        return;
    ++*hits;
    const float n[3] = {h.nx[0], h.ny[0], h.nz[0]};
    float pn[3], en, pp[3], ep;
    cylray_hit_point_normal(&P, o, d, h.t[0], h.part[0], n, pn, &en);
    cylray_hit_point(&P, o, d, h.t[0], h.part[0], pp, &ep);
    const double lim = 0.25 * fmin(cyl->radius, cyl->half_height);
    for (int j = 0; j < rays; j += 16) {
        float xa[16][3], xb[16][3], w[16][3];
        int far_a[16];
        for (int i = 0; i < 16; i++) {
            double u[3];
            sref_unit(rng, u);
            const double un = u[0] * n[0] + u[1] * n[1] + u[2] * n[2];
            for (int c = 0; c < 3; c++)
                w[i][c] = (float)(un < 0 ? -u[c] : u[c]);
            cylray_spawn_origin_side(&P, pn, en, h.part[0], 1, w[i], xa[i]);
            cylray_spawn_origin(&P, pp, ep, h.part[0], w[i], xb[i]);
            double mv = 0;
            for (int c = 0; c < 3; c++)
                mv += ((double)xa[i][c] - pn[c]) * ((double)xa[i][c] - pn[c]);
            far_a[i] = !(sqrt(mv) <= lim);
            *big += far_a[i];
        }
        *spawned += 16;
        const uint32_t ma =
            occluded16(k, j / 16, &P, (const float(*)[3])xa, (const float(*)[3])w);
        const uint32_t mb =
            occluded16(k, j / 16, &P, (const float(*)[3])xb, (const float(*)[3])w);
        for (int i = 0; i < 16; i++) {
            if (ma >> i & 1u) {
                ++*rehit_readme;
                *rehit_big += far_a[i];
                if (*rehit_readme <= 5) {
                    char s[400];
                    snprintf(s, sizeof s,
                             "%s: hit t %a part %d n (%a %a %a), p (%a %a %a) err %a, "
                             "origin (%a %a %a) w (%a %a %a)%s",
                             k->name, h.t[0], h.part[0], n[0], n[1], n[2], pn[0], pn[1], pn[2],
                             en, xa[i][0], xa[i][1], xa[i][2], w[i][0], w[i][1], w[i][2],
                             far_a[i] ? " (outside the guarantee's condition)" : "");
                    cylgen_case c;
                    memset(&c, 0, sizeof c);
                    c.cyl = *cyl;
                    memcpy(c.o, o, sizeof c.o);
                    memcpy(c.d, d, sizeof c.d);
                    fail("reintersect", &c, s);
                }
            }
            *rehit_plain += mb >> i & 1u;
        }
    }
}

int run_reintersect(void)
{
    const int ncyl = quick ? 100 : 1000, rays = quick ? 160 : 1008;
    long hits[CYLRAY_ISA_COUNT] = {0}, spawned[CYLRAY_ISA_COUNT] = {0};
    long readme[CYLRAY_ISA_COUNT] = {0}, plain[CYLRAY_ISA_COUNT] = {0};
    long big[CYLRAY_ISA_COUNT] = {0}, readme_big[CYLRAY_ISA_COUNT] = {0};
    long refused = 0;
    for (int i = 0; i < ncyl; i++) {
        cylgen_rng rng;
        cylgen_seed(&rng, 0x5eed0000u + (uint64_t)i);
        /* pbrt's tube: radius, zmin, zmax (pExp(4), random signs), then a random
         * rotation, uniform scale and translation (pExp(8)) */
        const double R = pexp(&rng, 4);
        double z0 = pexp(&rng, 4);
        z0 *= cylgen_uniform(&rng) < 0.5 ? -1 : 1;
        double z1 = pexp(&rng, 4);
        z1 *= cylgen_uniform(&rng) < 0.5 ? -1 : 1;
        if (z0 > z1) {
            const double t = z0;
            z0 = z1, z1 = t;
        }
        double axis[3], tr[3];
        sref_unit(&rng, axis);
        const double scale = pexp(&rng, 8);
        for (int k = 0; k < 3; k++) {
            tr[k] = pexp(&rng, 8);
            tr[k] *= cylgen_uniform(&rng) < 0.5 ? -1 : 1;
        }
        cylray_cylinder cyl;
        memset(&cyl, 0, sizeof cyl);
        for (int k = 0; k < 3; k++) {
            cyl.axis[k] = (float)axis[k];
            cyl.center[k] = (float)(tr[k] + scale * 0.5 * (z0 + z1) * axis[k]);
        }
        cyl.radius = (float)(scale * R);
        cyl.half_height = (float)(scale * 0.5 * (z1 - z0));
        cyl.flags = 0; /* pbrt's cylinder is a tube */
        cylray_prepared P;
        if (cylray_prepare(&P, &cyl) != CYLRAY_OK || !(cyl.half_height > 0)) {
            refused++;
            continue;
        }
        /* the ray: from pExp(8) in each coordinate toward a random point of the
         * tube's bounding box, its direction normalised half the time */
        float o[3], d[3];
        double dd[3], dl = 0;
        const double al =
            sqrt((double)cyl.axis[0] * cyl.axis[0] + (double)cyl.axis[1] * cyl.axis[1] +
                 (double)cyl.axis[2] * cyl.axis[2]);
        for (int k = 0; k < 3; k++) {
            o[k] = (float)pexp(&rng, 8);
            const double ak = cyl.axis[k] / al;
            const double ext =
                fabs(ak) * cyl.half_height + cyl.radius * sqrt(fmax(0, 1 - ak * ak));
            const double tgt = cyl.center[k] + (2 * cylgen_uniform(&rng) - 1) * ext;
            dd[k] = tgt - o[k];
            dl += dd[k] * dd[k];
        }
        const int normalise = cylgen_uniform(&rng) < 0.5;
        for (int k = 0; k < 3; k++)
            d[k] = (float)(normalise ? dd[k] / sqrt(dl) : dd[k]);
        for (int k = 0; k < nisa; k++) {
            cylgen_rng r2 = rng; /* the same spawned directions on every ISA */
            reintersect_one(isas[k], &cyl, o, d, rays, &r2, &hits[k], &spawned[k], &readme[k],
                            &plain[k], &big[k], &readme_big[k]);
        }
    }
    long bad = 0;
    for (int k = 0; k < nisa; k++) {
        printf("reintersect: %-7s %5ld hits of %d tubes (%ld refused), %8ld spawned rays: "
               "%ld re-hits following the README (%ld of them outside the guarantee's "
               "condition, which %ld spawns were), %ld with the point from o + t d and the "
               "side from w\n",
               isas[k]->name, hits[k], ncyl, refused, spawned[k], readme[k], readme_big[k],
               big[k], plain[k]);
        bad += readme[k];
    }
    return bad == 0 && hits[0] > ncyl / 10;
}
