/* SPDX-License-Identifier: MIT */
/* end_plane.c - rays lying exactly in the plane of an end (d.a = 0, the origin's axial
 * coordinate exactly -H or +H): the closed solid includes its boundary, so such a ray
 * meets the cylinder at the rim where it crosses the side's circle, capped or open, one
 * disc or none; every ISA, packets of 4, 8 and 16 (in every lane), streams, leaves of 4,
 * 8 and 16 (in every lane) and the occlusion forms give the same hit.
 *
 * The case of Mitsuba's test05 (center (0, 0, 0.5), axis z, R 1, H 0.5, a ray from
 * (0, -10, 0) along y: t = 9) and its images along every axis, both ends, both axis
 * signs, other centers and radii, with every flag set and kernel flag. */
#include "cylray.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static long checks, failures;

static void fail(const char *what, const cylray_cylinder *c, const float o[3], const float d[3],
                 const char *isa, float t, int part)
{
    if (failures++ < 20)
        fprintf(stderr,
                "FAIL %s (%s): c (%g %g %g) a (%g %g %g) R %g H %g flags %u, o (%g %g %g) "
                "d (%g %g %g): t %.9g part %d\n",
                what, isa, c->center[0], c->center[1], c->center[2], c->axis[0], c->axis[1],
                c->axis[2], c->radius, c->half_height, c->flags, o[0], o[1], o[2], d[0], d[1],
                d[2], t, part);
}

/* One ray on one path: every form must hit at t_want with one part (that of the first
 * form seen on any path: *part0 < 0 until then). */
static void check_path(const cylray_kernels *k, const cylray_cylinder *cyl, const float o[3],
                       const float d[3], float t_want, unsigned flags, int *part0)
{
    cylray_prepared P;
    if (cylray_prepare(&P, cyl) != CYLRAY_OK) {
        fail("prepare", cyl, o, d, k->name, 0, 0);
        return;
    }
    float t[3 + 1 + 3];
    int32_t part[3 + 1 + 3];
    int ok[3 + 1 + 3] = {0}, occ[3 + 1 + 3] = {0};
    const char *names[] = {"packet4", "packet8", "packet16", "stream",
                           "leaf4",   "leaf8",   "leaf16"};
    for (int wi = 0; wi < 3; wi++) {
        const int w = 4 << wi;
        /* the ray in every lane: all must agree */
        cylray_ray16 r;
        cylray_hit16 h;
        float *f = (float *)(void *)&r;
        for (int i = 0; i < w; i++) {
            for (int a = 0; a < 3; a++)
                f[a * w + i] = o[a], f[(3 + a) * w + i] = d[a];
            f[6 * w + i] = 0.0f, f[7 * w + i] = INFINITY;
        }
        const uint32_t all = w == 16 ? 0xffffu : (1u << w) - 1u;
        cylray_ray16 r2 = r;
        uint32_t m, mo;
        if (w == 4) {
            m = k->intersect4(&P, (cylray_ray4 *)(void *)&r, (cylray_hit4 *)(void *)&h, all,
                              flags);
            mo = k->occluded4(&P, (cylray_ray4 *)(void *)&r2, all, flags);
        } else if (w == 8) {
            m = k->intersect8(&P, (cylray_ray8 *)(void *)&r, (cylray_hit8 *)(void *)&h, all,
                              flags);
            mo = k->occluded8(&P, (cylray_ray8 *)(void *)&r2, all, flags);
        } else {
            m = k->intersect16(&P, &r, &h, all, flags);
            mo = k->occluded16(&P, &r2, all, flags);
        }
        const float *ht = (const float *)(void *)&h;
        const int32_t *hp = (const int32_t *)(const void *)(ht + 4 * w);
        ok[wi] = m == all, occ[wi] = mo == all, t[wi] = ht[0], part[wi] = hp[0];
        for (int i = 1; i < w; i++)
            if (ht[i] != ht[0] || hp[i] != hp[0])
                ok[wi] = 0;
    }
    {
        float tmin = 0, tmax = INFINITY, ht = 0, nx, ny, nz;
        int32_t hp = 0;
        uint8_t oc = 0;
        cylray_rays rs = {&o[0], &o[1], &o[2], &d[0], &d[1], &d[2], &tmin, &tmax};
        cylray_hits hs = {&ht, &nx, &ny, &nz, &hp};
        ok[3] = k->intersect_stream(&P, &rs, &hs, 1, flags) == 1;
        tmax = INFINITY;
        occ[3] = k->occluded_stream(&P, &rs, &oc, 1, flags) == 1 && oc == 1;
        t[3] = ht, part[3] = hp;
    }
    for (int li = 0; li < 3; li++) {
        const int m = 4 << li;
        /* the cylinder in each lane in turn, beside far-away others */
        cylray_cylinder cs[16];
        ok[4 + li] = occ[4 + li] = 1;
        for (int lane = 0; lane < m; lane++) {
            for (int j = 0; j < m; j++) {
                cs[j] = *cyl;
                if (j != lane)
                    cs[j].center[0] += 1e4f;
            }
            static cylray_leaf16 leaf16;
            static cylray_leaf8 leaf8;
            static cylray_leaf4 leaf4;
            cylray_ray1 r1 = {{o[0], o[1], o[2]}, {d[0], d[1], d[2]}, 0.0f, INFINITY};
            cylray_hit1 h1;
            int got, go;
            if (m == 4) {
                got = cylray_leaf_prepare4(&leaf4, cs, NULL, (size_t)m) == CYLRAY_OK &&
                      k->leaf_intersect4(&leaf4, &r1, &h1, flags);
                r1.tmax = INFINITY;
                go = k->leaf_occluded4(&leaf4, &r1, flags);
            } else if (m == 8) {
                got = cylray_leaf_prepare8(&leaf8, cs, NULL, (size_t)m) == CYLRAY_OK &&
                      k->leaf_intersect8(&leaf8, &r1, &h1, flags);
                r1.tmax = INFINITY;
                go = k->leaf_occluded8(&leaf8, &r1, flags);
            } else {
                got = cylray_leaf_prepare16(&leaf16, cs, NULL, (size_t)m) == CYLRAY_OK &&
                      k->leaf_intersect16(&leaf16, &r1, &h1, flags);
                r1.tmax = INFINITY;
                go = k->leaf_occluded16(&leaf16, &r1, flags);
            }
            if (!got || h1.lane != (uint32_t)lane)
                ok[4 + li] = 0;
            if (!go)
                occ[4 + li] = 0;
            if (lane == 0)
                t[4 + li] = h1.t, part[4 + li] = h1.part;
            else if (got && (h1.t != t[4 + li] || h1.part != part[4 + li]))
                ok[4 + li] = 0;
        }
    }
    for (int j = 0; j < 7; j++) {
        checks++;
        /* t within 8 ulps of the exact t (the rule with CYLRAY_FAST), the part alike */
        const float tol = 8 * (nextafterf(t_want, INFINITY) - t_want);
        if (!ok[j] || !occ[j] || !(fabsf(t[j] - t_want) <= tol)) {
            fail(names[j], cyl, o, d, k->name, ok[j] ? t[j] : NAN, ok[j] ? part[j] : -1);
            continue;
        }
        if (*part0 < 0)
            *part0 = part[j];
        else if (part[j] != *part0)
            fail("parts differ", cyl, o, d, k->name, t[j], part[j]);
    }
}

int main(void)
{
    const cylray_kernels *isas[CYLRAY_ISA_COUNT];
    int nisa = 0;
    for (int i = 0; i < CYLRAY_ISA_COUNT; i++)
        if ((isas[nisa] = cylray_kernels_for((cylray_isa)i)) != NULL)
            nisa++;
    static const float centers[][3] = {{0, 0, 0.5f}, {1.5f, -2, 3}, {-40, 8, 0.25f}};
    static const float radii[] = {1, 0.375f, 24};
    static const unsigned cyl_flags[] = {CYLRAY_CAPPED, 0, CYLRAY_CAPPED_LO, CYLRAY_CAPPED_HI};
    static const unsigned kflags[] = {0, CYLRAY_NORMAL, CYLRAY_FAST, CYLRAY_REFINE,
                                      CYLRAY_NORMAL | CYLRAY_FAST | CYLRAY_REFINE};
    long rays = 0;
    for (size_t ci = 0; ci < 3; ci++)
        for (int ax = 0; ax < 3; ax++)
            for (int asg = -1; asg <= 1; asg += 2)
                for (int end = -1; end <= 1; end += 2)
                    for (size_t fi = 0; fi < 4; fi++) {
                        const float R = radii[ci], H = ci == 0 ? 0.5f : 0.75f;
                        cylray_cylinder cyl = {{centers[ci][0], centers[ci][1], centers[ci][2]},
                                               {0, 0, 0},
                                               R,
                                               H,
                                               cyl_flags[fi]};
                        cyl.axis[ax] = (float)asg * (ci == 2 ? 4.0f : 1.0f);
                        /* across the plane of that end, along the next coordinate */
                        const int across = (ax + 1) % 3;
                        float o[3], d[3] = {0, 0, 0};
                        for (int k = 0; k < 3; k++)
                            o[k] = cyl.center[k];
                        o[ax] += (float)(end * asg) * H;
                        o[across] -= 10 * R;
                        d[across] = 1;
                        const float t_want = 9 * R;
                        int part0 = -1;
                        for (size_t kf = 0; kf < sizeof kflags / sizeof kflags[0]; kf++)
                            for (int k = 0; k < nisa; k++)
                                check_path(isas[k], &cyl, o, d, t_want, kflags[kf], &part0);
                        rays++;
                    }
    printf("end-plane: %ld rays, %ld checks over %d ISAs (packets 4/8/16 in every lane, "
           "stream, leaves 4/8/16 in every lane, occlusion), %ld failures\n",
           rays, checks, nisa, failures);
    return failures == 0 && checks > 0 ? 0 : 1;
}
