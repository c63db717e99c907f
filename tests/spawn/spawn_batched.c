/* SPDX-License-Identifier: MIT */
/* spawn_batched.c - spawn_test batched and axis: the packet, stream and leaf forms
 * equal the scalar pair bit for bit; rays down the axis onto a disc's center. */

#include "spawn_common.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- batched forms -------------------------------------------------------------- */

/* The batched forms of ISA K (packets 4/8/16, a stream cut at every length, leaves one
 * at a time and in bulk) on the lanes in m, against the scalar pair (p, err, x). */
static long batched_isa(const cylray_kernels *K, const cylray_prepared *P, const cylgen_case *c,
                        const cylray_ray16 *ray, const cylray_hit16 *hit, uint32_t m,
                        const float p[16][3], const float err[16], const float w[16][3],
                        const float x[16][3], uint32_t outward, const float xs[16][3],
                        const cylray_leaf16 *leaf, uint32_t lane, long *lanes)
{
    long diff = 0;
    /* the side forms: packets, a stream, leaves in bulk */
    {
        cylray_points16 q16;
        cylray_points8 q8;
        cylray_points4 q4;
        cylray_ray16 o16 = *ray;
        cylray_ray8 o8;
        cylray_ray4 o4;
        float px[16], py[16], pz[16], pe[16], wx[16], wy[16], wz[16], ox[16], oy[16], oz[16];
        int32_t part[16];
        uint8_t outb[16];
        const cylray_leaf16 *lv[16];
        cylray_hit1 h1[16];
        memset(&o8, 0, sizeof o8), memset(&o4, 0, sizeof o4);
        memset(&q8, 0, sizeof q8), memset(&q4, 0, sizeof q4), memset(&q16, 0, sizeof q16);
        for (int i = 0; i < 16; i++) {
            q16.x[i] = px[i] = p[i][0], q16.y[i] = py[i] = p[i][1], q16.z[i] = pz[i] = p[i][2];
            q16.err[i] = pe[i] = err[i];
            o16.dx[i] = wx[i] = w[i][0], o16.dy[i] = wy[i] = w[i][1],
            o16.dz[i] = wz[i] = w[i][2];
            ox[i] = oy[i] = oz[i] = -3.0f;
            part[i] = m >> i & 1u ? hit->part[i] : CYLRAY_MISS;
            outb[i] = (uint8_t)(outward >> i & 1u);
            lv[i] = leaf;
            cylray_hit1 h = {hit->t[i], {0, 0, 0}, part[i], 0, lane};
            h1[i] = h;
            if (i < 8) {
                q8.x[i] = p[i][0], q8.y[i] = p[i][1], q8.z[i] = p[i][2], q8.err[i] = err[i];
                o8.dx[i] = w[i][0], o8.dy[i] = w[i][1], o8.dz[i] = w[i][2];
            }
            if (i < 4) {
                q4.x[i] = p[i][0], q4.y[i] = p[i][1], q4.z[i] = p[i][2], q4.err[i] = err[i];
                o4.dx[i] = w[i][0], o4.dy[i] = w[i][1], o4.dz[i] = w[i][2];
            }
        }
        K->spawn_rays_side16(P, &q16, hit, m, outward, &o16);
        {
            cylray_hit8 h8;
            cylray_hit4 h4;
            memset(&h8, 0, sizeof h8), memset(&h4, 0, sizeof h4);
            for (int i = 0; i < 8; i++)
                h8.part[i] = hit->part[i];
            for (int i = 0; i < 4; i++)
                h4.part[i] = hit->part[i];
            K->spawn_rays_side8(P, &q8, &h8, m & 0xffu, outward, &o8);
            K->spawn_rays_side4(P, &q4, &h4, m & 0xfu, outward, &o4);
        }
        cylray_points sp = {px, py, pz, pe}, dirs = {wx, wy, wz, NULL};
        cylray_points org = {ox, oy, oz, NULL};
        K->spawn_stream_side(P, &sp, part, outb, &dirs, &org, 16);
        /* leaves in bulk: the hits only, compacted */
        cylray_hit1 hc[16];
        float cx[16], cy[16], cz[16], ce[16], cwx[16], cwy[16], cwz[16];
        uint8_t cb[16];
        int nc = 0;
        for (int i = 0; i < 16; i++)
            if (m >> i & 1u) {
                hc[nc] = h1[i], cb[nc] = outb[i];
                cx[nc] = p[i][0], cy[nc] = p[i][1], cz[nc] = p[i][2], ce[nc] = err[i];
                cwx[nc] = w[i][0], cwy[nc] = w[i][1], cwz[nc] = w[i][2];
                nc++;
            }
        cylray_points lp = {cx, cy, cz, ce}, ld = {cwx, cwy, cwz, NULL};
        K->leaf_spawn_origins_side16(lv, hc, &lp, cb, &ld, &ld, (size_t)nc);
        for (int i = 0, j = 0; i < 16; i++) {
            if (!(m >> i & 1u)) {
                if (ox[i] != -3.0f || oy[i] != -3.0f || oz[i] != -3.0f) {
                    diff++;
                    fail("batched", &c[i], "a side stream wrote a lane it does not own");
                }
                continue;
            }
            const float a[3] = {o16.ox[i], o16.oy[i], o16.oz[i]}, b[3] = {ox[i], oy[i], oz[i]};
            const float l[3] = {cwx[j], cwy[j], cwz[j]};
            j++;
            int bad = !sref_same3(a, xs[i]) || o16.tmin[i] != 0.0f || !sref_same3(b, xs[i]) ||
                      !sref_same3(l, xs[i]);
            if (i < 8) {
                const float a8[3] = {o8.ox[i], o8.oy[i], o8.oz[i]};
                bad |= !sref_same3(a8, xs[i]);
            }
            if (i < 4) {
                const float a4[3] = {o4.ox[i], o4.oy[i], o4.oz[i]};
                bad |= !sref_same3(a4, xs[i]);
            }
            if (bad) {
                diff++;
                char s[96];
                snprintf(s, sizeof s, "%s: a side form differs from cylray_spawn_origin_side",
                         K->name);
                fail("batched", &c[i], s);
            }
        }
    }
    cylray_points16 pts;
    K->hit_points16(P, ray, hit, m, &pts);
    cylray_ray16 out = *ray;
    for (int i = 0; i < 16; i++)
        out.dx[i] = w[i][0], out.dy[i] = w[i][1], out.dz[i] = w[i][2];
    K->spawn_rays16(P, &pts, hit, m, &out);
    cylray_ray8 r8;
    cylray_hit8 h8;
    cylray_points8 p8;
    cylray_ray4 r4;
    cylray_hit4 h4;
    cylray_points4 p4;
    narrow_packet(ray, hit, &r8, &h8, &r4, &h4);
    K->hit_points8(P, &r8, &h8, m & 0xffu, &p8);
    K->hit_points4(P, &r4, &h4, m & 0xfu, &p4);
    for (int i = 0; i < 8; i++) {
        r8.dx[i] = w[i][0], r8.dy[i] = w[i][1], r8.dz[i] = w[i][2];
        if (i < 4)
            r4.dx[i] = w[i][0], r4.dy[i] = w[i][1], r4.dz[i] = w[i][2];
    }
    K->spawn_rays8(P, &p8, &h8, m & 0xffu, &r8);
    K->spawn_rays4(P, &p4, &h4, m & 0xfu, &r4);
    /* streams of every length 1..16 from lane 16 - len on, so that each length meets
     * full vectors and a tail of every size; what a stream does not cover stays */
    float wx[16], wy[16], wz[16];
    int32_t spart[16];
    for (int i = 0; i < 16; i++) {
        wx[i] = w[i][0], wy[i] = w[i][1], wz[i] = w[i][2];
        spart[i] = m >> i & 1u ? hit->part[i] : CYLRAY_MISS;
    }
    for (int len = 1; len <= 16; len++) {
        const int b = 16 - len;
        float sx[16], sy[16], sz[16], se[16], ox[16], oy[16], oz[16];
        for (int i = 0; i < 16; i++)
            sx[i] = sy[i] = sz[i] = se[i] = ox[i] = oy[i] = oz[i] = -5.0f;
        cylray_rays rs = {
            ray->ox + b, ray->oy + b, ray->oz + b,   ray->dx + b,
            ray->dy + b, ray->dz + b, ray->tmin + b, (float *)(uintptr_t)ray->tmax + b};
        cylray_hits hs = {(float *)(uintptr_t)hit->t + b, NULL, NULL, NULL, spart + b};
        cylray_points sp = {sx + b, sy + b, sz + b, se + b};
        cylray_points dirs = {wx + b, wy + b, wz + b, NULL},
                      org = {ox + b, oy + b, oz + b, NULL};
        size_t ns = K->hit_points_stream(P, &rs, &hs, &sp, (size_t)len);
        K->spawn_stream(P, &sp, spart + b, &dirs, &org, (size_t)len);
        if (ns != (size_t)popcount(m >> b)) {
            diff++;
            fail("batched", &c[0], "the stream's count of points is wrong");
        }
        for (int i = 0; i < 16; i++) {
            const int hitlane = i >= b && (m >> i & 1u);
            const float s1[3] = {sx[i], sy[i], sz[i]}, s2[3] = {ox[i], oy[i], oz[i]};
            const int bad =
                hitlane
                    ? !sref_same3(s1, p[i]) || se[i] != err[i] || !sref_same3(s2, x[i])
                    : sx[i] != -5.0f || sy[i] != -5.0f || sz[i] != -5.0f || se[i] != -5.0f ||
                          ox[i] != -5.0f || oy[i] != -5.0f || oz[i] != -5.0f;
            if (bad) {
                diff++;
                fail("batched", &c[i],
                     hitlane ? "a stream differs from the scalar pair"
                             : "a stream wrote a lane it does not own");
            }
        }
    }
    /* the leaf in bulk: the hits (in lane `lane`) in one call, through the same leaf */
    const cylray_leaf16 *lv[16];
    cylray_ray1 r1[16];
    cylray_hit1 h1[16];
    float lx[16], ly[16], lz[16], le[16], lwx[16], lwy[16], lwz[16];
    size_t nl = 0;
    for (int i = 0; i < 16; i++) {
        if (!(m >> i & 1u))
            continue;
        lv[nl] = leaf;
        cylray_ray1 r = {{c[i].o[0], c[i].o[1], c[i].o[2]},
                         {c[i].d[0], c[i].d[1], c[i].d[2]},
                         c[i].tmin,
                         hit->t[i]};
        cylray_hit1 h = {hit->t[i], {0, 0, 0}, hit->part[i], 7, lane};
        r1[nl] = r, h1[nl] = h;
        lwx[nl] = w[i][0], lwy[nl] = w[i][1], lwz[nl] = w[i][2];
        nl++;
    }
    cylray_points lp = {lx, ly, lz, le}, ldirs = {lwx, lwy, lwz, NULL};
    K->leaf_hit_points16(lv, r1, h1, &lp, nl);
    K->leaf_spawn_origins16(lv, h1, &lp, &ldirs, &ldirs, nl);
    for (int i = 0, j = 0; i < 16; i++) {
        if (!(m >> i & 1u))
            continue;
        (*lanes)++;
        const float a[3] = {pts.x[i], pts.y[i], pts.z[i]};
        const float bb[3] = {out.ox[i], out.oy[i], out.oz[i]};
        int bad = !sref_same3(a, p[i]) || pts.err[i] != err[i] || !sref_same3(bb, x[i]) ||
                  out.tmin[i] != 0.0f;
        if (i < 8) {
            const float a8[3] = {p8.x[i], p8.y[i], p8.z[i]};
            const float b8[3] = {r8.ox[i], r8.oy[i], r8.oz[i]};
            bad |= !sref_same3(a8, p[i]) || p8.err[i] != err[i] || !sref_same3(b8, x[i]);
        }
        if (i < 4) {
            const float a4[3] = {p4.x[i], p4.y[i], p4.z[i]};
            const float b4[3] = {r4.ox[i], r4.oy[i], r4.oz[i]};
            bad |= !sref_same3(a4, p[i]) || p4.err[i] != err[i] || !sref_same3(b4, x[i]);
        }
        const float q[3] = {lx[j], ly[j], lz[j]}, o[3] = {lwx[j], lwy[j], lwz[j]};
        bad |= !sref_same3(q, p[i]) || le[j] != err[i] || !sref_same3(o, x[i]);
        j++;
        if (bad) {
            diff++;
            char s[96];
            snprintf(s, sizeof s, "%s: a batched form differs from the scalar pair", K->name);
            fail("batched", &c[i], s);
        }
    }
    return diff;
}

int run_batched(void)
{
    const long G = groups_for(4000);
    long lanes = 0, diff = 0;
    cylgen_rng rng;
    cylgen_seed(&rng, 99);
    for (long g = 0; g < G; g++) {
        cylgen_case c[SREF_GROUP];
        sref_group((int)(g % SREF_COUNT), 9000 + (uint64_t)g, c);
        cylray_prepared P;
        if (cylray_prepare(&P, &c[0].cyl) != CYLRAY_OK)
            continue;
        cylray_ray16 ray;
        cylray_hit16 hit;
        uint32_t m = trace_group(isas[g % nisa], &P, c, &ray, &hit);
        /* the scalar pair */
        float p[16][3], err[16], w[16][3], x[16][3], xs[16][3];
        const uint32_t outward = (uint32_t)(cylgen_uniform(&rng) * 65536.0);
        for (int i = 0; i < 16; i++) {
            double u[3];
            sref_unit(&rng, u);
            for (int k = 0; k < 3; k++)
                w[i][k] = (float)u[k];
            if (m >> i & 1u) {
                cylray_hit_point(&P, c[i].o, c[i].d, hit.t[i], hit.part[i], p[i], &err[i]);
                cylray_spawn_origin(&P, p[i], err[i], hit.part[i], w[i], x[i]);
                cylray_spawn_origin_side(&P, p[i], err[i], hit.part[i], outward >> i & 1u, w[i],
                                         xs[i]);
            }
        }
        /* the plain entry points (the path in use): packets of 16, and of 8 and 4 (their
         * lanes are the first ones) */
        cylray_points16 pts;
        cylray_hit_points16(&P, &ray, &hit, m, &pts);
        cylray_ray16 out = ray;
        for (int i = 0; i < 16; i++)
            out.dx[i] = w[i][0], out.dy[i] = w[i][1], out.dz[i] = w[i][2];
        cylray_spawn_rays16(&P, &pts, &hit, m, &out);
        cylray_ray8 r8;
        cylray_hit8 h8;
        cylray_points8 p8;
        cylray_ray4 r4;
        cylray_hit4 h4;
        cylray_points4 p4;
        narrow_packet(&ray, &hit, &r8, &h8, &r4, &h4);
        cylray_hit_points8(&P, &r8, &h8, m & 0xffu, &p8);
        cylray_hit_points4(&P, &r4, &h4, m & 0xfu, &p4);
        for (int i = 0; i < 8; i++) {
            r8.dx[i] = w[i][0], r8.dy[i] = w[i][1], r8.dz[i] = w[i][2];
            if (i < 4)
                r4.dx[i] = w[i][0], r4.dy[i] = w[i][1], r4.dz[i] = w[i][2];
        }
        cylray_spawn_rays8(&P, &p8, &h8, m & 0xffu, &r8);
        cylray_spawn_rays4(&P, &p4, &h4, m & 0xfu, &r4);
        /* the side forms, on copies of the packets */
        cylray_ray16 out_s = out;
        cylray_ray8 r8s = r8;
        cylray_ray4 r4s = r4;
        cylray_spawn_rays_side16(&P, &pts, &hit, m, outward, &out_s);
        cylray_spawn_rays_side8(&P, &p8, &h8, m & 0xffu, outward, &r8s);
        cylray_spawn_rays_side4(&P, &p4, &h4, m & 0xfu, outward, &r4s);
        /* a stream, and a leaf of 16 holding the cylinder in lane 5 */
        float sx[16], sy[16], sz[16], se[16], ox[16], oy[16], oz[16];
        float wx[16], wy[16], wz[16];
        for (int i = 0; i < 16; i++)
            wx[i] = w[i][0], wy[i] = w[i][1], wz[i] = w[i][2];
        int32_t spart[16];
        for (int i = 0; i < 16; i++)
            spart[i] = m >> i & 1u ? hit.part[i] : CYLRAY_MISS;
        cylray_rays rs = {ray.ox, ray.oy, ray.oz, ray.dx, ray.dy, ray.dz, ray.tmin, ray.tmax};
        cylray_hits hs = {hit.t, NULL, NULL, NULL, spart};
        cylray_points sp = {sx, sy, sz, se}, dirs = {wx, wy, wz, NULL},
                      org = {ox, oy, oz, NULL};
        size_t ns = cylray_hit_points_stream(&P, &rs, &hs, &sp, 16);
        cylray_spawn_stream(&P, &sp, spart, &dirs, &org, 16);
        float qx[16], qy[16], qz[16];
        uint8_t outw[16];
        for (int i = 0; i < 16; i++)
            outw[i] = (uint8_t)(outward >> i & 1u);
        cylray_points org_s = {qx, qy, qz, NULL};
        cylray_spawn_stream_side(&P, &sp, spart, outw, &dirs, &org_s, 16);
        if (ns != (size_t)popcount(m)) {
            diff++;
            fail("batched", &c[0], "cylray_hit_points_stream's count is wrong");
        }
        /* a leaf of 6 with the cylinder in lane 5 behind five others */
        cylray_leaf16 leaf;
        cylray_cylinder six[6];
        const uint32_t lane = 5;
        for (int j = 0; j < 5; j++) {
            six[j] = c[0].cyl;
            six[j].center[0] += 1e5f;
            six[j].radius = 1.0f + (float)j;
        }
        six[lane] = c[0].cyl;
        if (cylray_leaf_prepare16(&leaf, six, NULL, 6) != CYLRAY_OK) {
            diff++;
            fail("batched", &c[0], "cylray_leaf_prepare16 refused the cylinder");
            continue;
        }
        for (int i = 0; i < 16; i++) {
            if (!(m >> i & 1u))
                continue;
            cylray_ray1 r1 = {{c[i].o[0], c[i].o[1], c[i].o[2]},
                              {c[i].d[0], c[i].d[1], c[i].d[2]},
                              c[i].tmin,
                              hit.t[i]};
            cylray_hit1 h1 = {hit.t[i], {0, 0, 0}, hit.part[i], 7, lane};
            float lp[3], le, lx[3];
            cylray_leaf_hit_point16(&leaf, &r1, &h1, lp, &le);
            cylray_leaf_spawn_origin16(&leaf, &h1, lp, le, w[i], lx);
            const float a[3] = {pts.x[i], pts.y[i], pts.z[i]};
            const float b[3] = {out.ox[i], out.oy[i], out.oz[i]};
            const float s1[3] = {sx[i], sy[i], sz[i]}, s2[3] = {ox[i], oy[i], oz[i]};
            int bad = !sref_same3(a, p[i]) || pts.err[i] != err[i] || !sref_same3(b, x[i]) ||
                      out.tmin[i] != 0.0f || !sref_same3(s1, p[i]) || se[i] != err[i] ||
                      !sref_same3(s2, x[i]);
            if (i < 8) {
                const float a8[3] = {p8.x[i], p8.y[i], p8.z[i]};
                const float b8[3] = {r8.ox[i], r8.oy[i], r8.oz[i]};
                bad |= !sref_same3(a8, p[i]) || p8.err[i] != err[i] || !sref_same3(b8, x[i]);
            }
            if (i < 4) {
                const float a4[3] = {p4.x[i], p4.y[i], p4.z[i]};
                const float b4[3] = {r4.ox[i], r4.oy[i], r4.oz[i]};
                bad |= !sref_same3(a4, p[i]) || p4.err[i] != err[i] || !sref_same3(b4, x[i]);
            }
            bad |= !sref_same3(lp, p[i]) || le != err[i] || !sref_same3(lx, x[i]);
            /* the side forms */
            float ls[3];
            cylray_leaf_spawn_origin_side16(&leaf, &h1, lp, le, outward >> i & 1u, w[i], ls);
            const float s16[3] = {out_s.ox[i], out_s.oy[i], out_s.oz[i]};
            const float ss[3] = {qx[i], qy[i], qz[i]};
            bad |= !sref_same3(ls, xs[i]) || !sref_same3(s16, xs[i]) ||
                   !sref_same3(ss, xs[i]) || out_s.tmin[i] != 0.0f;
            if (i < 8) {
                const float s8[3] = {r8s.ox[i], r8s.oy[i], r8s.oz[i]};
                bad |= !sref_same3(s8, xs[i]);
            }
            if (i < 4) {
                const float s4[3] = {r4s.ox[i], r4s.oy[i], r4s.oz[i]};
                bad |= !sref_same3(s4, xs[i]);
            }
            /* the side w lies on, by a clear margin: the side form is the plain one
             * (where floats resolve the cylinder at p: a point far off a tiny radius
             * may lie next to the axis, where the radial direction is noise) */
            double ne[3];
            sref_normal(&c[i].cyl, p[i], hit.part[i] & CYLRAY_PART_MASK, ne);
            const double wn = ne[0] * w[i][0] + ne[1] * w[i][1] + ne[2] * w[i][2];
            if (fabs(wn) > 1e-6 &&
                err[i] < 0x1p-10 * fmin(c[i].cyl.radius, c[i].cyl.half_height)) {
                float xw[3];
                cylray_spawn_origin_side(&P, p[i], err[i], hit.part[i], wn > 0, w[i], xw);
                bad |= !sref_same3(xw, x[i]);
            }
            if (bad) {
                diff++;
                fail("batched", &c[i],
                     "a plain entry point or a leaf's scalar form differs "
                     "from the scalar pair");
            }
        }
        /* every ISA's table, and the plain entry points (the path in use) */
        for (int k = 0; k < nisa; k++)
            diff += batched_isa(isas[k], &P, c, &ray, &hit, m, (const float(*)[3])p, err,
                                (const float(*)[3])w, (const float(*)[3])x, outward,
                                (const float(*)[3])xs, &leaf, lane, &lanes);
        {
            cylray_points16 pts;
            cylray_hit_points16(&P, &ray, &hit, m, &pts);
            for (int i = 0; i < 16; i++) {
                const float a[3] = {pts.x[i], pts.y[i], pts.z[i]};
                if ((m >> i & 1u) && (!sref_same3(a, p[i]) || pts.err[i] != err[i])) {
                    diff++;
                    fail("batched", &c[i], "cylray_hit_points16 differs from the scalar pair");
                }
            }
        }
    }
    /* the normal forms: hits traced with normals, the point at the kernel's azimuth */
    long nlanes = 0;
    for (long g = 0; g < G; g++) {
        cylgen_case c[SREF_GROUP];
        sref_group((int)(g % SREF_COUNT), 19000 + (uint64_t)g, c);
        cylray_prepared P;
        cylray_leaf8 leaf;
        if (cylray_prepare(&P, &c[0].cyl) != CYLRAY_OK ||
            cylray_leaf_prepare8(&leaf, &c[0].cyl, NULL, 1) != CYLRAY_OK)
            continue;
        cylray_ray16 ray;
        cylray_hit16 hit;
        memset(&ray, 0, sizeof ray);
        memset(&hit, 0, sizeof hit);
        for (int i = 0; i < SREF_GROUP; i++) {
            ray.ox[i] = c[i].o[0], ray.oy[i] = c[i].o[1], ray.oz[i] = c[i].o[2];
            ray.dx[i] = c[i].d[0], ray.dy[i] = c[i].d[1], ray.dz[i] = c[i].d[2];
            ray.tmin[i] = c[i].tmin, ray.tmax[i] = c[i].tmax;
        }
        const cylray_ray16 ray0 = ray;
        const uint32_t m = isas[g % nisa]->intersect16(
            &P, &ray, &hit, 0xffffu, CYLRAY_NORMAL | (g & 1 ? CYLRAY_FACE_FORWARD : 0));
        cylray_points16 p16;
        cylray_points8 p8;
        cylray_points4 p4;
        cylray_ray8 r8;
        cylray_hit8 h8;
        cylray_ray4 r4;
        cylray_hit4 h4;
        memset(&r8, 0, sizeof r8), memset(&h8, 0, sizeof h8);
        memset(&r4, 0, sizeof r4), memset(&h4, 0, sizeof h4);
        narrow_packet(&ray, &hit, &r8, &h8, &r4, &h4);
        cylray_hit_points_normal16(&P, &ray, &hit, m, &p16);
        cylray_hit_points_normal8(&P, &r8, &h8, m & 0xffu, &p8);
        cylray_hit_points_normal4(&P, &r4, &h4, m & 0xfu, &p4);
        float sx[16], sy[16], sz[16], se[16];
        int32_t spart[16];
        for (int i = 0; i < 16; i++)
            spart[i] = m >> i & 1u ? hit.part[i] : CYLRAY_MISS;
        cylray_rays rs = {ray.ox, ray.oy, ray.oz, ray.dx, ray.dy, ray.dz, ray.tmin, ray.tmax};
        cylray_hits hs = {hit.t, hit.nx, hit.ny, hit.nz, spart};
        cylray_points sp = {sx, sy, sz, se};
        if (cylray_hit_points_normal_stream(&P, &rs, &hs, &sp, 16) != (size_t)popcount(m))
            diff++;
        for (int i = 0; i < 16; i++) {
            if (!(m >> i & 1u))
                continue;
            nlanes++;
            const float o[3] = {ray0.ox[i], ray0.oy[i], ray0.oz[i]};
            const float d[3] = {ray0.dx[i], ray0.dy[i], ray0.dz[i]};
            const float n[3] = {hit.nx[i], hit.ny[i], hit.nz[i]};
            float p[3], err, lp[3], le;
            cylray_hit_point_normal(&P, o, d, hit.t[i], hit.part[i], n, p, &err);
            cylray_ray1 r1 = {{o[0], o[1], o[2]}, {d[0], d[1], d[2]}, 0, hit.t[i]};
            cylray_hit1 h1 = {hit.t[i], {n[0], n[1], n[2]}, hit.part[i], 0, 0};
            cylray_leaf_hit_point_normal8(&leaf, &r1, &h1, lp, &le);
            const float a[3] = {p16.x[i], p16.y[i], p16.z[i]}, b[3] = {sx[i], sy[i], sz[i]};
            int bad = !sref_same3(a, p) || p16.err[i] != err || !sref_same3(b, p) ||
                      se[i] != err || !sref_same3(lp, p) || le != err;
            if (i < 8) {
                const float a8[3] = {p8.x[i], p8.y[i], p8.z[i]};
                bad |= !sref_same3(a8, p) || p8.err[i] != err;
            }
            if (i < 4) {
                const float a4[3] = {p4.x[i], p4.y[i], p4.z[i]};
                bad |= !sref_same3(a4, p) || p4.err[i] != err;
            }
            /* the bound holds for this point too */
            bad |= !(sref_dist_part(&c[i].cyl, p, hit.part[i]) <= err);
            /* every ISA's normal forms: packets of 16, a stream, leaves in bulk */
            for (int k = 0; k < nisa; k++) {
                const cylray_kernels *K = isas[k];
                cylray_points16 q;
                float qx[16], qy[16], qz[16], qe[16];
                cylray_points qs = {qx, qy, qz, qe};
                const cylray_leaf8 *lv[1] = {&leaf};
                K->hit_points_normal16(&P, &ray, &hit, 1u << i, &q);
                K->hit_points_normal_stream(&P, &rs, &hs, &qs, 16);
                const float a16[3] = {q.x[i], q.y[i], q.z[i]}, as[3] = {qx[i], qy[i], qz[i]};
                float bx, by, bz, be;
                cylray_points qb = {&bx, &by, &bz, &be};
                K->leaf_hit_points_normal8(lv, &r1, &h1, &qb, 1);
                const float ab[3] = {bx, by, bz};
                bad |= !sref_same3(a16, p) || q.err[i] != err || !sref_same3(as, p) ||
                       qe[i] != err || !sref_same3(ab, p) || be != err;
            }
            if (bad) {
                diff++;
                fail("batched", &c[i],
                     "a normal form differs from the scalar one, or its bound");
            }
        }
    }
    printf("batched: %ld lanes of the normal forms compared (and their bounds)\n", nlanes);
    printf("batched: %ld lanes compared over %d ISAs (packets 4/8/16, streams of every "
           "length, leaves one by one and in bulk; plain, side and normal forms), %ld "
           "differ\n",
           lanes, nisa, diff);
    return diff == 0 && lanes > 0;
}

/* Rays down the axis onto a disc's center (a point where the radial direction is
 * undefined): the hit point stays at the center, within its bound of the cap's plane,
 * and the reflected ray's origin stays near the axis on the ray's side. */
int run_axis(void)
{
    static const float axes[][3] = {
        {0, 0, 1}, {0, -3, 0}, {1, 0, 0}, {0.3f, -0.5f, 0.8f}, {-1e-3f, 2e-3f, 5e-4f}};
    static const float centers[][3] = {{0, 0, 0}, {1.5f, -2, 7}, {1e4f, -3e4f, 2e3f}};
    static const float radii[] = {1e-2f, 1, 250};
    long bad = 0, n = 0;
    for (size_t ai = 0; ai < sizeof axes / sizeof axes[0]; ai++)
        for (size_t ci = 0; ci < sizeof centers / sizeof centers[0]; ci++)
            for (size_t ri = 0; ri < sizeof radii / sizeof radii[0]; ri++)
                for (int end = 0; end < 2; end++) {
                    const float *a = axes[ai], *c0 = centers[ci];
                    const float R = radii[ri], H = 2 * R;
                    cylray_cylinder cyl = {
                        {c0[0], c0[1], c0[2]}, {a[0], a[1], a[2]}, R, H, CYLRAY_CAPPED};
                    cylray_prepared P;
                    if (cylray_prepare(&P, &cyl) != CYLRAY_OK)
                        continue;
                    /* floats must resolve the disc there (the guarantee's condition) */
                    const double cmax = fmax(fabs(c0[0]), fmax(fabs(c0[1]), fabs(c0[2])));
                    if (256 * cmax * 0x1p-24 > R)
                        continue;
                    const double al =
                        sqrt((double)a[0] * a[0] + (double)a[1] * a[1] + (double)a[2] * a[2]);
                    const double sg = end ? 1 : -1; /* the ray comes from beyond that end */
                    float o[3], d[3];
                    for (int k = 0; k < 3; k++) {
                        o[k] = (float)(c0[k] + sg * 3 * H * a[k] / al);
                        d[k] = (float)(-sg * a[k] / al);
                    }
                    const int32_t part = end ? CYLRAY_CAP_HI : CYLRAY_CAP_LO;
                    cylray_ray4 ray;
                    cylray_hit4 hit;
                    for (int l = 0; l < 4; l++) {
                        ray.ox[l] = o[0], ray.oy[l] = o[1], ray.oz[l] = o[2];
                        ray.dx[l] = d[0], ray.dy[l] = d[1], ray.dz[l] = d[2];
                        ray.tmin[l] = 0, ray.tmax[l] = INFINITY;
                    }
                    if (!(cylray_intersect4(&P, &ray, &hit, 1u, 0) & 1u) ||
                        hit.part[0] != part) {
                        bad++;
                        fprintf(stderr, "axis: no cap hit (axis %zu center %zu R %g end %d)\n",
                                ai, ci, (double)R, end);
                        continue;
                    }
                    float p[3], err, org[3];
                    cylray_hit_point(&P, o, d, hit.t[0], part, p, &err);
                    const float w[3] = {-d[0], -d[1], -d[2]};
                    cylray_spawn_origin(&P, p, err, part, w, org);
                    double zp = 0, zo = 0, rp2 = 0, ro2 = 0;
                    double pc[3], oc[3];
                    for (int k = 0; k < 3; k++) {
                        pc[k] = (double)p[k] - c0[k];
                        oc[k] = (double)org[k] - c0[k];
                        zp += pc[k] * a[k] / al;
                        zo += oc[k] * a[k] / al;
                    }
                    for (int k = 0; k < 3; k++) {
                        rp2 += (pc[k] - zp * a[k] / al) * (pc[k] - zp * a[k] / al);
                        ro2 += (oc[k] - zo * a[k] / al) * (oc[k] - zo * a[k] / al);
                    }
                    const int ok = sqrt(rp2) <= 0.25 * R && fabs(fabs(zp) - H) <= err &&
                                   sqrt(ro2) <= 0.25 * R && sg * zo > H;
                    n++;
                    if (!ok) {
                        bad++;
                        fprintf(stderr,
                                "axis: axis %zu center %zu R %g end %d: point %g from the "
                                "axis, %g off the plane (err %g); origin %g from the axis, "
                                "%g beyond the plane\n",
                                ai, ci, (double)R, end, sqrt(rp2), fabs(fabs(zp) - H),
                                (double)err, sqrt(ro2), sg * zo - H);
                    }
                }
    printf("axis: %ld disc centers, %ld failures\n", n, bad);
    return n > 0 && bad == 0;
}
