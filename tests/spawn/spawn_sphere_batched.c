/* SPDX-License-Identifier: MIT */
/* spawn_sphere_batched.c - spawn_sphere batched: the packet, stream and leaf forms
 * against the scalar ones bit for bit, a comparison of forms rather than of geometry. */
#include "spawn_sphere.h"
#include "tcheck.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- the batched forms, bit for bit ------------------------------------------------- */

static long diff3(const float a[3], const float b[3])
{
    return !sref_same3(a, b);
}

/* The differences of n points in bulk from the scalar ones (point j is hit idx[j]'s). */
static long points_differ(const cylray_points *pts, int n, const int *idx, const float p[][3],
                          const float *e)
{
    long diff = 0;
    for (int j = 0; j < n; j++) {
        const float a[3] = {pts->x[j], pts->y[j], pts->z[j]};
        diff += diff3(a, p[idx[j]]) + !tc_same(pts->err[j], e[idx[j]]);
    }
    return diff;
}

static void batched_group(cylgen_rng *rng, long g, spawn_tally *tally)
{
    cylray_sphere s[16];
    for (int i = 0; i < 16; i++)
        make_sphere(rng, (int)((g + (uint64_t)i * (g & 1)) % K_COUNT), &s[i]);
    cylray_prepared P;
    if (cylray_prepare_sphere(&P, &s[0]) != CYLRAY_OK)
        return;
    cylray_leaf16 leaf;
    cylray_leaf8 leaf8;
    cylray_leaf4 leaf4;
    if (cylray_leaf_prepare_spheres16(&leaf, s, NULL, 16) != CYLRAY_OK ||
        cylray_leaf_prepare_spheres8(&leaf8, s, NULL, 8) != CYLRAY_OK ||
        cylray_leaf_prepare_spheres4(&leaf4, s, NULL, 4) != CYLRAY_OK)
        return;
    /* rays at sphere 0 (the packet forms) and hits in double, with a few lanes given
     * a hit that is not one (t from elsewhere), which the forms must treat alike */
    cylray_ray16 ray;
    cylray_hit16 hit;
    memset(&ray, 0, sizeof ray);
    memset(&hit, 0, sizeof hit);
    uint32_t m = 0;
    float w[16][3], tl[16], nl[16][3];
    int32_t pl[16];
    cylray_ray1 r1[16];
    uint32_t lane[16];
    float ol[16][3], dl[16][3];
    for (int i = 0; i < 16; i++) {
        float o[3], d[3], t, n[3];
        int32_t part;
        make_ray(rng, &s[0], o, d);
        if (!double_hit(&s[0], o, d, &t, &part, n)) {
            t = (float)uni(rng, 0, 10), part = CYLRAY_SIDE;
            n[0] = 1, n[1] = n[2] = 0;
        }
        if (cylgen_uniform(rng) < 0.3) /* face-forwarded */
            for (int k = 0; k < 3; k++)
                n[k] = part & CYLRAY_BACKFACE ? -n[k] : n[k];
        ray.ox[i] = o[0], ray.oy[i] = o[1], ray.oz[i] = o[2];
        ray.dx[i] = d[0], ray.dy[i] = d[1], ray.dz[i] = d[2];
        hit.t[i] = t, hit.part[i] = part;
        hit.nx[i] = n[0], hit.ny[i] = n[1], hit.nz[i] = n[2];
        if (cylgen_uniform(rng) < 0.9)
            m |= 1u << i;
        double u[3];
        sref_unit(rng, u);
        for (int k = 0; k < 3; k++)
            w[i][k] = (float)(u[k] * pow(10, uni(rng, -3, 3)));
        /* the leaf's lane i: a ray at its own sphere */
        lane[i] = (uint32_t)(cylgen_next(rng) % 16);
        make_ray(rng, &s[lane[i]], ol[i], dl[i]);
        if (!double_hit(&s[lane[i]], ol[i], dl[i], &tl[i], &pl[i], nl[i]))
            tl[i] = 1, pl[i] = CYLRAY_SIDE, nl[i][0] = 0, nl[i][1] = 1, nl[i][2] = 0;
        memcpy(r1[i].o, ol[i], sizeof ol[i]);
        memcpy(r1[i].d, dl[i], sizeof dl[i]);
        r1[i].tmin = 0, r1[i].tmax = INFINITY;
    }
    const uint32_t outward = (uint32_t)cylgen_next(rng) & 0xffffu;
    /* the scalar answers */
    float p[2][16][3], e[2][16], x[2][16][3];
    float lp[2][16][3], le[2][16], lx[2][16][3];
    cylray_hit1 h1[16];
    for (int i = 0; i < 16; i++) {
        const float o[3] = {ray.ox[i], ray.oy[i], ray.oz[i]},
                    d[3] = {ray.dx[i], ray.dy[i], ray.dz[i]},
                    n[3] = {hit.nx[i], hit.ny[i], hit.nz[i]};
        cylray_hit_point(&P, o, d, hit.t[i], hit.part[i], p[0][i], &e[0][i]);
        cylray_hit_point_normal(&P, o, d, hit.t[i], hit.part[i], n, p[1][i], &e[1][i]);
        cylray_spawn_origin(&P, p[0][i], e[0][i], hit.part[i], w[i], x[0][i]);
        cylray_spawn_origin_side(&P, p[0][i], e[0][i], hit.part[i], outward >> i & 1u, w[i],
                                 x[1][i]);
        cylray_hit1 h = {tl[i], {nl[i][0], nl[i][1], nl[i][2]}, pl[i], 0, lane[i]};
        h1[i] = h;
        cylray_leaf_hit_point16(&leaf, &r1[i], &h1[i], lp[0][i], &le[0][i]);
        cylray_leaf_hit_point_normal16(&leaf, &r1[i], &h1[i], lp[1][i], &le[1][i]);
        cylray_leaf_spawn_origin16(&leaf, &h1[i], lp[0][i], le[0][i], w[i], lx[0][i]);
        cylray_leaf_spawn_origin_side16(&leaf, &h1[i], lp[0][i], le[0][i], outward >> i & 1u,
                                        w[i], lx[1][i]);
        /* the leaf's lane is sphere lane[i]: its scalar answers as a prepared sphere */
        cylray_prepared Q;
        float qp[3], qe, qx[3];
        cylray_prepare_sphere(&Q, &s[lane[i]]);
        cylray_hit_point_normal(&Q, ol[i], dl[i], tl[i], pl[i], nl[i], qp, &qe);
        cylray_spawn_origin(&Q, lp[0][i], le[0][i], pl[i], w[i], qx);
        tally->differ += diff3(qp, lp[1][i]) + !tc_same(qe, le[1][i]) + diff3(qx, lx[0][i]);
        if (lane[i] < 8) {
            float a[3], ae, b[3];
            cylray_leaf_hit_point_normal8(&leaf8, &r1[i], &h1[i], a, &ae);
            tally->differ += diff3(a, lp[1][i]) + !tc_same(ae, le[1][i]);
            cylray_leaf_spawn_origin_side8(&leaf8, &h1[i], lp[0][i], le[0][i],
                                           outward >> i & 1u, w[i], b);
            tally->differ += diff3(b, lx[1][i]);
        }
        if (lane[i] < 4) {
            float a[3], ae, b[3];
            cylray_leaf_hit_point4(&leaf4, &r1[i], &h1[i], a, &ae);
            tally->differ += diff3(a, lp[0][i]) + !tc_same(ae, le[0][i]);
            cylray_leaf_spawn_origin4(&leaf4, &h1[i], lp[0][i], le[0][i], w[i], b);
            tally->differ += diff3(b, lx[0][i]);
        }
    }
    for (int ki = 0; ki < nisa; ki++) {
        const cylray_kernels *K = isas[ki];
        for (int normal = 0; normal < 2; normal++) {
            /* packets of 16, 8 and 4 */
            cylray_points16 q16;
            memset(&q16, 0, sizeof q16);
            (normal ? K->hit_points_normal16 : K->hit_points16)(&P, &ray, &hit, m, &q16);
            cylray_ray8 ray8;
            cylray_hit8 hit8;
            cylray_ray4 ray4;
            cylray_hit4 hit4;
            narrow_packet(&ray, &hit, &ray8, &hit8, &ray4, &hit4);
            cylray_points8 q8;
            cylray_points4 q4;
            memset(&q8, 0, sizeof q8);
            memset(&q4, 0, sizeof q4);
            (normal ? K->hit_points_normal8 : K->hit_points8)(&P, &ray8, &hit8, m & 0xffu, &q8);
            (normal ? K->hit_points_normal4 : K->hit_points4)(&P, &ray4, &hit4, m & 0xfu, &q4);
            for (int i = 0; i < 16; i++) {
                if (!(m >> i & 1u))
                    continue;
                tally->compared++;
                const float a[3] = {q16.x[i], q16.y[i], q16.z[i]};
                tally->differ += diff3(a, p[normal][i]) + !tc_same(q16.err[i], e[normal][i]);
                if (i < 8) {
                    const float b[3] = {q8.x[i], q8.y[i], q8.z[i]};
                    tally->differ += diff3(b, p[normal][i]) + !tc_same(q8.err[i], e[normal][i]);
                }
                if (i < 4) {
                    const float b[3] = {q4.x[i], q4.y[i], q4.z[i]};
                    tally->differ += diff3(b, p[normal][i]) + !tc_same(q4.err[i], e[normal][i]);
                }
            }
            /* spawned rays from the plain points: packets, and the side form */
            cylray_points16 s16;
            for (int i = 0; i < 16; i++) {
                s16.x[i] = p[0][i][0], s16.y[i] = p[0][i][1], s16.z[i] = p[0][i][2];
                s16.err[i] = e[0][i];
            }
            cylray_ray16 out = ray;
            for (int i = 0; i < 16; i++)
                out.dx[i] = w[i][0], out.dy[i] = w[i][1], out.dz[i] = w[i][2];
            if (normal)
                K->spawn_rays_side16(&P, &s16, &hit, m, outward, &out);
            else
                K->spawn_rays16(&P, &s16, &hit, m, &out);
            cylray_points8 s8;
            cylray_ray8 out8;
            cylray_points4 s4;
            cylray_ray4 out4;
            memset(&out8, 0, sizeof out8);
            memset(&out4, 0, sizeof out4);
            for (int i = 0; i < 8; i++) {
                s8.x[i] = s16.x[i], s8.y[i] = s16.y[i], s8.z[i] = s16.z[i];
                s8.err[i] = s16.err[i];
                out8.dx[i] = w[i][0], out8.dy[i] = w[i][1], out8.dz[i] = w[i][2];
                if (i < 4) {
                    s4.x[i] = s16.x[i], s4.y[i] = s16.y[i], s4.z[i] = s16.z[i];
                    s4.err[i] = s16.err[i];
                    out4.dx[i] = w[i][0], out4.dy[i] = w[i][1], out4.dz[i] = w[i][2];
                }
            }
            if (normal) {
                K->spawn_rays_side8(&P, &s8, &hit8, m & 0xffu, outward & 0xffu, &out8);
                K->spawn_rays_side4(&P, &s4, &hit4, m & 0xfu, outward & 0xfu, &out4);
            } else {
                K->spawn_rays8(&P, &s8, &hit8, m & 0xffu, &out8);
                K->spawn_rays4(&P, &s4, &hit4, m & 0xfu, &out4);
            }
            for (int i = 0; i < 16; i++) {
                if (!(m >> i & 1u))
                    continue;
                const float a[3] = {out.ox[i], out.oy[i], out.oz[i]};
                tally->differ += diff3(a, x[normal][i]) + (out.tmin[i] != 0.0f);
                if (i < 8) {
                    const float b[3] = {out8.ox[i], out8.oy[i], out8.oz[i]};
                    tally->differ += diff3(b, x[normal][i]);
                }
                if (i < 4) {
                    const float b[3] = {out4.ox[i], out4.oy[i], out4.oz[i]};
                    tally->differ += diff3(b, x[normal][i]);
                }
            }
            /* streams of every length up to 16 */
            for (int len = 1; len <= 16; len += 1 + (int)(cylgen_next(rng) % 4)) {
                float px[16], py[16], pz[16], pe[16], fx[16], fy[16], fz[16];
                float wx[16], wy[16], wz[16];
                int32_t pp[16];
                uint8_t ob[16];
                for (int i = 0; i < 16; i++) {
                    pp[i] = m >> i & 1u ? hit.part[i] : CYLRAY_MISS;
                    wx[i] = w[i][0], wy[i] = w[i][1], wz[i] = w[i][2];
                    ob[i] = (uint8_t)(outward >> i & 1u);
                    fx[i] = fy[i] = fz[i] = px[i] = py[i] = pz[i] = pe[i] = -7.0f;
                }
                const cylray_rays rays = {ray.ox, ray.oy, ray.oz, ray.dx,
                                          ray.dy, ray.dz, NULL,   NULL};
                const cylray_hits hits = {hit.t, hit.nx, hit.ny, hit.nz, pp};
                const cylray_points pts = {px, py, pz, pe};
                (normal ? K->hit_points_normal_stream : K->hit_points_stream)(&P, &rays, &hits,
                                                                              &pts, len);
                const cylray_points sp = {s16.x, s16.y, s16.z, s16.err};
                const cylray_points dirs = {wx, wy, wz, NULL}, org = {fx, fy, fz, NULL};
                if (normal)
                    K->spawn_stream_side(&P, &sp, pp, ob, &dirs, &org, len);
                else
                    K->spawn_stream(&P, &sp, pp, &dirs, &org, len);
                for (int i = 0; i < len; i++) {
                    if (!(m >> i & 1u))
                        continue;
                    const float a[3] = {px[i], py[i], pz[i]}, b[3] = {fx[i], fy[i], fz[i]};
                    tally->differ += diff3(a, p[normal][i]) + !tc_same(pe[i], e[normal][i]) +
                                     diff3(b, x[normal][i]);
                }
            }
            /* leaves in bulk, 16 hits of 16-, 8- and 4-lane leaves */
            {
                const cylray_leaf16 *lv[16];
                float px[16], py[16], pz[16], pe[16], fx[16], fy[16], fz[16];
                float wx[16], wy[16], wz[16];
                uint8_t ob[16];
                for (int i = 0; i < 16; i++) {
                    lv[i] = &leaf;
                    wx[i] = w[i][0], wy[i] = w[i][1], wz[i] = w[i][2];
                    ob[i] = (uint8_t)(outward >> i & 1u);
                }
                const cylray_points pts = {px, py, pz, pe};
                (normal ? K->leaf_hit_points_normal16 : K->leaf_hit_points16)(lv, r1, h1, &pts,
                                                                              16);
                const cylray_points sp = {px, py, pz, pe};
                const cylray_points dirs = {wx, wy, wz, NULL}, org = {fx, fy, fz, NULL};
                float lpx[16], lpy[16], lpz[16], lpe[16];
                for (int i = 0; i < 16; i++)
                    lpx[i] = lp[0][i][0], lpy[i] = lp[0][i][1], lpz[i] = lp[0][i][2],
                    lpe[i] = le[0][i];
                const cylray_points sp0 = {lpx, lpy, lpz, lpe};
                (void)sp;
                if (normal)
                    K->leaf_spawn_origins_side16(lv, h1, &sp0, ob, &dirs, &org, 16);
                else
                    K->leaf_spawn_origins16(lv, h1, &sp0, &dirs, &org, 16);
                for (int i = 0; i < 16; i++) {
                    const float a[3] = {px[i], py[i], pz[i]}, b[3] = {fx[i], fy[i], fz[i]};
                    tally->differ += diff3(a, lp[normal][i]) + !tc_same(pe[i], le[normal][i]) +
                                     diff3(b, lx[normal][i]);
                }
                /* 8- and 4-lane leaves: the hits that name their lanes */
                const cylray_leaf8 *l8[16];
                const cylray_leaf4 *l4[16];
                cylray_ray1 r8[16], r4[16];
                cylray_hit1 h8[16], h4[16];
                int i8[16], i4[16], n8 = 0, n4 = 0;
                for (int i = 0; i < 16; i++) {
                    if (lane[i] < 8)
                        l8[n8] = &leaf8, r8[n8] = r1[i], h8[n8] = h1[i], i8[n8++] = i;
                    if (lane[i] < 4)
                        l4[n4] = &leaf4, r4[n4] = r1[i], h4[n4] = h1[i], i4[n4++] = i;
                }
                (normal ? K->leaf_hit_points_normal8 : K->leaf_hit_points8)(l8, r8, h8, &pts,
                                                                            (size_t)n8);
                tally->differ +=
                    points_differ(&pts, n8, i8, (const float(*)[3])lp[normal], le[normal]);
                (normal ? K->leaf_hit_points_normal4 : K->leaf_hit_points4)(l4, r4, h4, &pts,
                                                                            (size_t)n4);
                tally->differ +=
                    points_differ(&pts, n4, i4, (const float(*)[3])lp[normal], le[normal]);
                for (int j = 0; j < n8; j++) {
                    lpx[j] = lp[0][i8[j]][0], lpy[j] = lp[0][i8[j]][1];
                    lpz[j] = lp[0][i8[j]][2], lpe[j] = le[0][i8[j]];
                    wx[j] = w[i8[j]][0], wy[j] = w[i8[j]][1], wz[j] = w[i8[j]][2];
                    ob[j] = (uint8_t)(outward >> i8[j] & 1u);
                }
                if (normal)
                    K->leaf_spawn_origins_side8(l8, h8, &sp0, ob, &dirs, &org, (size_t)n8);
                else
                    K->leaf_spawn_origins8(l8, h8, &sp0, &dirs, &org, (size_t)n8);
                for (int j = 0; j < n8; j++) {
                    const float b[3] = {fx[j], fy[j], fz[j]};
                    tally->differ += diff3(b, lx[normal][i8[j]]);
                }
            }
        }
    }
    if (tally->differ && failures++ < 20)
        printf("FAIL batched: group %ld, sphere c=(%a, %a, %a) R=%a: %ld differences so "
               "far\n",
               g, (double)s[0].center[0], (double)s[0].center[1], (double)s[0].center[2],
               (double)s[0].radius, tally->differ);
}

int run_batched(void)
{
    spawn_tally t = {0, 0};
    const int ok = spawn_groups(scaled(4000), 4404, batched_group, &t);
    printf("batched: %ld packet lanes on %d paths (packets 4/8/16, streams, leaves), %ld "
           "differences from the scalar forms\n",
           t.compared, nisa, t.differ);
    return ok;
}
