/* SPDX-License-Identifier: MIT */
/* spawn_sphere_self.c - spawn_sphere self and side: rays spawned from kernel hits, judged
 * against the exact sphere, apart from the modes that need no spawned ray. */
#include "spawn_sphere.h"
#include "tcheck.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- self-intersection ------------------------------------------------------------- */

enum { D_REFL, D_TRANS, D_SHADOW, D_COUNT };

/* Spawns from kernel hits on every path; side: 0 the plain form, 1 the side form. */
int run_spawns(int side_form)
{
    const long N = scaled(side_form ? 6000 : 24000); /* groups of 16 rays a path */
    long spawns[CYLRAY_ISA_COUNT] = {0}, self[CYLRAY_ISA_COUNT] = {0};
    long wrong_side = 0, along_plane = 0, disagree = 0, hits_back = 0, too_big = 0;
    long same_as_plain = 0;
    double far = 0; /* the largest |sigma(x0)| over ulp(max|x0_k|) + ulp(R) */
    cylgen_rng rng;
    cylgen_seed(&rng, side_form ? 4303 : 4202);
    for (int ki = 0; ki < nisa; ki++) {
        const cylray_kernels *K = isas[ki];
        for (long g = 0; g < N; g++) {
            cylray_sphere s;
            cylray_prepared P;
            float o[16][3], d[16][3], t[16], n[16][3];
            int32_t part[16];
            if (!sphere_rays(&rng, g, &s, &P, o, d))
                continue;
            const uint32_t m =
                trace(K, &P, 16, (const float(*)[3])o, (const float(*)[3])d, NULL, t, part, n);
            if (!m)
                continue;
            /* the path's stream forms, against the scalar ones */
            float px[16], py[16], pz[16], pe[16], ox[16], oy[16], oz[16], tt[16], nx[16],
                ny[16], nz[16];
            float dx[16], dy[16], dz[16], fx[16], fy[16], fz[16];
            int32_t pp[16];
            for (int i = 0; i < 16; i++) {
                ox[i] = o[i][0], oy[i] = o[i][1], oz[i] = o[i][2];
                dx[i] = d[i][0], dy[i] = d[i][1], dz[i] = d[i][2];
                tt[i] = t[i], nx[i] = n[i][0], ny[i] = n[i][1], nz[i] = n[i][2];
                pp[i] = m >> i & 1u ? part[i] : CYLRAY_MISS;
            }
            const cylray_rays rays = {ox, oy, oz, dx, dy, dz, NULL, NULL};
            const cylray_hits hits = {tt, nx, ny, nz, pp};
            const cylray_points pts = {px, py, pz, pe};
            K->hit_points_normal_stream(&P, &rays, &hits, &pts, 16);
            /* the scalar forms, in one group of four (spawn_sphere batched compares all) */
            const int scalar = (g & 3) == 0;
            for (int i = 0; i < 16 && scalar; i++) {
                const float p[3] = {px[i], py[i], pz[i]};
                if (m >> i & 1u) {
                    float ps[3], es;
                    cylray_hit_point_normal(&P, o[i], d[i], t[i], part[i], n[i], ps, &es);
                    if (!sref_same3(p, ps) || !tc_same(es, pe[i]))
                        disagree++;
                }
            }
            for (int dir = 0; dir < D_COUNT; dir++) {
                float w[16][3], tmax[16], x0[16][3];
                int want[16];
                uint8_t outb[16];
                for (int i = 0; i < 16; i++) {
                    const float p[3] = {px[i], py[i], pz[i]};
                    double nn[3], l = 0;
                    for (int k = 0; k < 3; k++) {
                        nn[k] = (double)p[k] - s.center[k];
                        l += nn[k] * nn[k];
                    }
                    l = sqrt(l);
                    for (int k = 0; k < 3; k++)
                        nn[k] /= l;
                    const int inc = part[i] & CYLRAY_BACKFACE ? -1 : 1;
                    sref_secondary(&rng, nn, s.radius, dir == D_SHADOW,
                                   dir == D_REFL ? inc : -inc, w[i], &tmax[i]);
                    /* the side form: the side from the kernel's (outward) normal, or at
                     * random one time in four */
                    const double wn = w[i][0] * n[i][0] + w[i][1] * n[i][1] + w[i][2] * n[i][2];
                    outb[i] = (uint8_t)(cylgen_uniform(&rng) < 0.25 ? cylgen_uniform(&rng) < 0.5
                                                                    : wn > 0);
                    want[i] = side_form ? (outb[i] ? 1 : -1) : w_side(&s, p, w[i]);
                    dx[i] = w[i][0], dy[i] = w[i][1], dz[i] = w[i][2];
                }
                const cylray_points dirs = {dx, dy, dz, NULL}, org = {fx, fy, fz, NULL};
                if (side_form)
                    K->spawn_stream_side(&P, &pts, pp, outb, &dirs, &org, 16);
                else
                    K->spawn_stream(&P, &pts, pp, &dirs, &org, 16);
                uint32_t use = 0;
                for (int i = 0; i < 16; i++) {
                    x0[i][0] = fx[i], x0[i][1] = fy[i], x0[i][2] = fz[i];
                    if (!(m >> i & 1u))
                        continue;
                    const float p[3] = {px[i], py[i], pz[i]};
                    float xs[3];
                    if (side_form)
                        cylray_spawn_origin_side(&P, p, pe[i], part[i], outb[i], w[i], xs);
                    else if (scalar)
                        cylray_spawn_origin(&P, p, pe[i], part[i], w[i], xs);
                    if ((side_form || scalar) && !sref_same3(xs, x0[i]))
                        disagree++;
                    /* the side asked for being w's side: the plain form's origin */
                    if (side_form && want[i] == w_side(&s, p, w[i])) {
                        float xp[3];
                        cylray_spawn_origin(&P, p, pe[i], part[i], w[i], xp);
                        same_as_plain++;
                        if (!sref_same3(xp, xs)) {
                            disagree++;
                            fail("side", &s,
                                 "not the plain form's origin where the side is w's", 0, 0);
                        }
                    }
                    double mv = 0;
                    for (int k = 0; k < 3; k++)
                        mv += ((double)x0[i][k] - p[k]) * ((double)x0[i][k] - p[k]);
                    if (!(sqrt(mv) <= 0.25 * s.radius)) {
                        too_big++; /* outside the guarantee: the float grid is too coarse */
                        continue;
                    }
                    use |= 1u << i;
                    spawns[ki]++;
                    const int sd = side_of(&s, x0[i]);
                    if (want[i] == 0) {
                        along_plane++; /* either side is w's: strictly off it */
                        if (sd == 0) {
                            wrong_side++;
                            fail("side", &s, "origin on the sphere (%a, %a)", x0[i][0],
                                 x0[i][1]);
                        }
                    } else if (sd != want[i]) {
                        wrong_side++;
                        fail("side", &s, "origin on the wrong side: want %g, got %g",
                             (double)want[i], (double)sd);
                    }
                    double aa = 0;
                    for (int k = 0; k < 3; k++)
                        aa +=
                            ((double)x0[i][k] - s.center[k]) * ((double)x0[i][k] - s.center[k]);
                    const double sig = fabs(sqrt(aa) - s.radius);
                    const double xm =
                        fmax(fabs(x0[i][0]), fmax(fabs(x0[i][1]), fabs(x0[i][2])));
                    int e1, e2;
                    frexp(xm, &e1);
                    frexp(s.radius, &e2);
                    far = fmax(far, sig / (ldexp(1, e1 - 24) + ldexp(1, e2 - 24)));
                }
                float th[16], nh[16][3];
                int32_t ph[16];
                const uint32_t mh = trace(K, &P, 16, (const float(*)[3])x0,
                                          (const float(*)[3])w, tmax, th, ph, nh);
                for (int i = 0; i < 16; i++) {
                    if (!((use & mh) >> i & 1u))
                        continue;
                    hits_back++;
                    if (too_soon(&s, x0[i], w[i], th[i])) {
                        self[ki]++;
                        fail("self", &s,
                             "the spawned ray meets the sphere again at t = %a (%g)", th[i],
                             (double)ph[i]);
                        printf("   p=(%a, %a, %a) err=%a part=%d w=(%a, %a, %a) x0=(%a, %a, %a)"
                               " path %s\n",
                               px[i], py[i], pz[i], pe[i], part[i], w[i][0], w[i][1], w[i][2],
                               x0[i][0], x0[i][1], x0[i][2], K->name);
                    }
                }
            }
        }
    }
    if (side_form)
        printf("side: %ld origins where the side asked for is w's: the plain form's\n",
               same_as_plain);
    long total_self = 0;
    for (int ki = 0; ki < nisa; ki++) {
        printf("%s: %s: %ld spawns, %ld self-intersections\n", side_form ? "side" : "self",
               isas[ki]->name, spawns[ki], self[ki]);
        total_self += self[ki];
    }
    printf("%s: %ld hits of spawned rays checked exactly or in double, %ld origins on the "
           "wrong side (%ld directions along the tangent plane), %ld stream/scalar "
           "differences; origins at most %.3g ulps (of the largest coordinate and of R) off "
           "the sphere; %ld spawns moved beyond R/4 (outside the guarantee) left out\n",
           side_form ? "side" : "self", hits_back, wrong_side, along_plane, disagree, far,
           too_big);
    return total_self == 0 && wrong_side == 0 && disagree == 0 && spawns[0] > 0;
}
