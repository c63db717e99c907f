/* SPDX-License-Identifier: MIT */
/* fuzz_spawn.c - the secondary-ray helpers on each fuzz input's hits: every hit the
 * scalar path reported goes through the hit point and the spawned origin (back along
 * the ray and on through the surface, with the plain and the side forms), and
 *   - every ISA's batched forms (packets of 16, streams) give the scalar forms' answers
 *     bit for bit;
 *   - the bound contains the exact distance of the point from the part's surface;
 *   - where the guarantee's condition holds (offset below R/4 and H/4), the origin lies
 *     strictly on the side asked for, and no ISA's kernel meets the surface left at
 *     the point left (tests/spawn/spawnref.h). */
#include "fuzz_spawn.h"

#include "spawnref.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

unsigned long fz_spawn_hits, fz_spawn_traced;

int fz_spawn(const fz_case *c, const cylray_prepared *P, const gresult *res,
             const cylray_kernels *const *isas, int nisa, char *why, size_t whylen)
{
    const cylray_cylinder *cyl = &c->cyl;
    for (size_t i = 0; i < c->n; i++) {
        const size_t L = i % 16; /* its lane in a packet of 16 */
        if (!(res->hit >> i & 1u))
            continue;
        const float o[3] = {c->rays.f[G_OX][i], c->rays.f[G_OY][i], c->rays.f[G_OZ][i]};
        const float d[3] = {c->rays.f[G_DX][i], c->rays.f[G_DY][i], c->rays.f[G_DZ][i]};
        const float t = res->t[i];
        const int32_t part = res->part[i];
        const int pm = part & CYLRAY_PART_MASK;
        float p[3], err;
        cylray_hit_point(P, o, d, t, part, p, &err);
        if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2]) || !isfinite(err))
            continue; /* beyond float's range: nothing is promised */
        fz_spawn_hits++;
        const double dist = sref_dist_part(cyl, p, pm);
        if (!(dist <= err)) {
            snprintf(why, whylen,
                     "ray %zu: hit point %.9g %.9g %.9g is %.3g from part %d, "
                     "beyond its bound %.3g",
                     i, p[0], p[1], p[2], dist, pm, (double)err);
            return 1;
        }
        /* back along the ray (the incident side) and on through the surface */
        for (int dir = 0; dir < 2; dir++) {
            const float w[3] = {dir ? d[0] : -d[0], dir ? d[1] : -d[1], dir ? d[2] : -d[2]};
            double n[3];
            sref_normal(cyl, p, pm, n);
            const double wn = n[0] * w[0] + n[1] * w[1] + n[2] * w[2];
            float x0[3], xs[3];
            cylray_spawn_origin(P, p, err, part, w, x0);
            cylray_spawn_origin_side(P, p, err, part, wn > 0, w, xs);
            /* every ISA's batched forms: a packet of 16 with this lane, and a stream */
            for (int k = 0; k < nisa; k++) {
                const cylray_kernels *K = isas[k];
                cylray_ray16 r;
                cylray_hit16 h;
                cylray_points16 q;
                memset(&r, 0, sizeof r), memset(&h, 0, sizeof h);
                r.ox[L] = o[0], r.oy[L] = o[1], r.oz[L] = o[2];
                r.dx[L] = d[0], r.dy[L] = d[1], r.dz[L] = d[2];
                h.t[L] = t, h.part[L] = part;
                K->hit_points16(P, &r, &h, 1u << L, &q);
                const float qp[3] = {q.x[L], q.y[L], q.z[L]};
                r.dx[L] = w[0], r.dy[L] = w[1], r.dz[L] = w[2];
                cylray_ray16 rs = r;
                K->spawn_rays16(P, &q, &h, 1u << L, &r);
                K->spawn_rays_side16(P, &q, &h, 1u << L, (wn > 0) << L, &rs);
                const float qx[3] = {r.ox[L], r.oy[L], r.oz[L]};
                const float qs[3] = {rs.ox[L], rs.oy[L], rs.oz[L]};
                float sx = 0, sy = 0, sz = 0, se = 0;
                const float wx = w[0], wy = w[1], wz = w[2];
                cylray_rays rr = {&o[0], &o[1], &o[2], &d[0], &d[1], &d[2], &t, NULL};
                cylray_hits hh = {(float *)(uintptr_t)&t, NULL, NULL, NULL,
                                  (int32_t *)(uintptr_t)&part};
                cylray_points sp = {&sx, &sy, &sz, &se};
                float ox = 0, oy = 0, oz = 0;
                cylray_points dirs = {(float *)(uintptr_t)&wx, (float *)(uintptr_t)&wy,
                                      (float *)(uintptr_t)&wz, NULL};
                cylray_points org = {&ox, &oy, &oz, NULL};
                K->hit_points_stream(P, &rr, &hh, &sp, 1);
                K->spawn_stream(P, &sp, &part, &dirs, &org, 1);
                const float s3[3] = {sx, sy, sz}, o3[3] = {ox, oy, oz};
                if (!sref_same3(qp, p) || q.err[L] != err || !sref_same3(qx, x0) ||
                    !sref_same3(qs, xs) || !sref_same3(s3, p) || se != err ||
                    !sref_same3(o3, x0)) {
                    snprintf(why, whylen,
                             "ray %zu: %s's batched hit point or origin differs "
                             "from the scalar form's",
                             i, K->name);
                    return 1;
                }
            }
            /* the guarantee's condition, and a direction clear of the tangent plane */
            double mv = 0;
            for (int k = 0; k < 3; k++)
                mv += ((double)x0[k] - p[k]) * ((double)x0[k] - p[k]);
            const double wl =
                sqrt((double)w[0] * w[0] + (double)w[1] * w[1] + (double)w[2] * w[2]);
            if (!(sqrt(mv) <= 0.25 * fmin(cyl->radius, cyl->half_height)) ||
                fabs(wn) <= 1e-6 * wl)
                continue;
            const double sig = sref_sigma(cyl, x0, pm);
            if ((wn > 0) != (sig > 0) || sig == 0) {
                snprintf(why, whylen,
                         "ray %zu: the origin %.9g %.9g %.9g is not strictly on "
                         "w's side of part %d (signed distance %.3g)",
                         i, x0[0], x0[1], x0[2], pm, sig);
                return 1;
            }
            fz_spawn_traced++;
            for (int k = 0; k < nisa; k++) {
                float th;
                int32_t ph;
                if (sref_trace1(isas[k], P, x0, w, &th, &ph) &&
                    sref_self_hit(cyl, x0, w, part, ph, th)) {
                    snprintf(why, whylen,
                             "ray %zu: %s meets the surface it leaves (part %d "
                             "at t %a) from the origin %a %a %a along %a %a %a",
                             i, isas[k]->name, ph, (double)th, x0[0], x0[1], x0[2], w[0], w[1],
                             w[2]);
                    return 1;
                }
            }
        }
    }
    return 0;
}
