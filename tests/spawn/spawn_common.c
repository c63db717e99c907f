/* SPDX-License-Identifier: MIT */
/* spawn_common.c - what the modes of spawn_test share (spawn_common.h). */

#include "spawn_common.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void fail(const char *what, const cylgen_case *c, const char *detail)
{
    if (failures++ < 20)
        fprintf(stderr,
                "FAIL %s: cyl c=(%a %a %a) v=(%a %a %a) R=%a H=%a flags=%u o=(%a %a %a) "
                "d=(%a %a %a): %s\n",
                what, c->cyl.center[0], c->cyl.center[1], c->cyl.center[2], c->cyl.axis[0],
                c->cyl.axis[1], c->cyl.axis[2], c->cyl.radius, c->cyl.half_height, c->cyl.flags,
                c->o[0], c->o[1], c->o[2], c->d[0], c->d[1], c->d[2], detail);
}

/* The hits of one ISA's 16-wide kernel on a group of cases; returns the hit mask. */
uint32_t trace_group(const cylray_kernels *k, const cylray_prepared *P, const cylgen_case *c,
                     cylray_ray16 *ray, cylray_hit16 *hit)
{
    memset(ray, 0, sizeof *ray);
    memset(hit, 0, sizeof *hit);
    for (int i = 0; i < SREF_GROUP; i++) {
        ray->ox[i] = c[i].o[0], ray->oy[i] = c[i].o[1], ray->oz[i] = c[i].o[2];
        ray->dx[i] = c[i].d[0], ray->dy[i] = c[i].d[1], ray->dz[i] = c[i].d[2];
        ray->tmin[i] = c[i].tmin, ray->tmax[i] = c[i].tmax;
    }
    return k->intersect16(P, ray, hit, 0xffffu, 0);
}

/* A packet of 16 rays (origins x, directions w, tmax) traced by ISA k at width 4, 8 or
 * 16 (cycling), one cylinder. */
uint32_t trace16(const cylray_kernels *k, int width, const cylray_prepared *P,
                 const float x[][3], const float w[][3], const float *tmax, uint32_t mask,
                 float *t, int32_t *part)
{
    uint32_t got = 0;
    for (int base = 0; base < 16; base += width) {
        cylray_ray16 r;
        cylray_hit16 h;
        memset(&h, 0, sizeof h);
        /* the 4- and 8-wide structs are prefixes of the same field order, at their own
         * strides: fill each layout explicitly */
        float *f = (float *)(void *)&r;
        for (int i = 0; i < width; i++) {
            int j = base + i;
            for (int a = 0; a < 3; a++) {
                f[a * width + i] = x[j][a];
                f[(3 + a) * width + i] = w[j][a];
            }
            f[6 * width + i] = 0.0f;
            f[7 * width + i] = tmax[j];
        }
        uint32_t m = (mask >> base) & ((1u << width) - 1u), res;
        if (width == 4)
            res = k->intersect4(P, (cylray_ray4 *)(void *)&r, (cylray_hit4 *)(void *)&h, m, 0);
        else if (width == 8)
            res = k->intersect8(P, (cylray_ray8 *)(void *)&r, (cylray_hit8 *)(void *)&h, m, 0);
        else
            res = k->intersect16(P, &r, &h, m, 0);
        const float *ht = (const float *)(void *)&h;
        const int32_t *hp = (const int32_t *)(const void *)(ht + 4 * width);
        for (int i = 0; i < width; i++)
            if (res >> i & 1u) {
                t[base + i] = ht[i];
                part[base + i] = hp[i];
            }
        got |= res << base;
    }
    return got;
}

long popcount(uint32_t m)
{
    long n = 0;
    for (; m; m &= m - 1)
        n++;
    return n;
}

int cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

long groups_for(long full)
{
    return quick ? full / 100 + 1 : full;
}

/* ISA k's stream form of the hit points of the lanes set in m (the others are passed as
 * CYLRAY_MISS and must stay unwritten), checked against the scalar pair bit for bit.
 * Returns the number of lanes that differ. */
long isa_points(const cylray_kernels *k, const cylray_prepared *P, const cylray_ray16 *ray,
                const cylray_hit16 *hit, uint32_t m, float p[16][3], float err[16])
{
    float x[16], y[16], z[16], e[16];
    int32_t part[16];
    for (int i = 0; i < 16; i++) {
        part[i] = m >> i & 1u ? hit->part[i] : CYLRAY_MISS;
        x[i] = y[i] = z[i] = e[i] = -7.0f;
    }
    cylray_rays rs = {ray->ox, ray->oy, ray->oz,   ray->dx,
                      ray->dy, ray->dz, ray->tmin, (float *)(uintptr_t)ray->tmax};
    cylray_hits hs = {(float *)(uintptr_t)hit->t, NULL, NULL, NULL, part};
    cylray_points pts = {x, y, z, e};
    long bad = k->hit_points_stream(P, &rs, &hs, &pts, 16) != (size_t)popcount(m);
    for (int i = 0; i < 16; i++) {
        if (!(m >> i & 1u)) {
            bad += x[i] != -7.0f || y[i] != -7.0f || z[i] != -7.0f || e[i] != -7.0f;
            continue;
        }
        float sp[3], se;
        const float o[3] = {ray->ox[i], ray->oy[i], ray->oz[i]};
        const float d[3] = {ray->dx[i], ray->dy[i], ray->dz[i]};
        cylray_hit_point(P, o, d, hit->t[i], hit->part[i], sp, &se);
        p[i][0] = x[i], p[i][1] = y[i], p[i][2] = z[i], err[i] = e[i];
        bad += memcmp(sp, p[i], sizeof sp) != 0 || memcmp(&se, &err[i], sizeof se) != 0;
    }
    return bad;
}

/* ISA k's stream form of the origins of the lanes set in m, against the scalar pair. */
long isa_origins(const cylray_kernels *k, const cylray_prepared *P, const cylray_hit16 *hit,
                 uint32_t m, const float p[16][3], const float err[16], const float w[16][3],
                 float x0[16][3])
{
    float px[16], py[16], pz[16], pe[16], wx[16], wy[16], wz[16];
    int32_t part[16];
    for (int i = 0; i < 16; i++) {
        part[i] = m >> i & 1u ? hit->part[i] : CYLRAY_MISS;
        px[i] = p[i][0], py[i] = p[i][1], pz[i] = p[i][2], pe[i] = err[i];
        wx[i] = w[i][0], wy[i] = w[i][1], wz[i] = w[i][2];
    }
    /* the origins over the directions, as the header allows */
    cylray_points pts = {px, py, pz, pe}, dirs = {wx, wy, wz, NULL};
    k->spawn_stream(P, &pts, part, &dirs, &dirs, 16);
    long bad = 0;
    for (int i = 0; i < 16; i++) {
        if (!(m >> i & 1u)) { /* untouched, bit for bit: an unused lane may hold a NaN */
            bad += memcmp(&wx[i], &w[i][0], sizeof wx[i]) != 0 ||
                   memcmp(&wy[i], &w[i][1], sizeof wy[i]) != 0 ||
                   memcmp(&wz[i], &w[i][2], sizeof wz[i]) != 0;
            continue;
        }
        float sx[3];
        cylray_spawn_origin(P, p[i], err[i], hit->part[i], w[i], sx);
        x0[i][0] = wx[i], x0[i][1] = wy[i], x0[i][2] = wz[i];
        bad += memcmp(sx, x0[i], sizeof sx) != 0;
    }
    return bad;
}

/* The surfaces a spawned origin must clear: the part left, and a cap or the side
 * within err of p (a rim). Bit s for surface s = SIDE, CAP_LO, CAP_HI. */
unsigned near_surfaces(const cylray_cylinder *cyl, const float p[3], float err, int P)
{
    unsigned s = 1u << P;
    if (!isfinite(cyl->half_height))
        return s;
    if (P != CYLRAY_SIDE && sref_dist_part(cyl, p, CYLRAY_SIDE) <= err)
        s |= 1u << CYLRAY_SIDE;
    for (int c = CYLRAY_CAP_LO; c <= CYLRAY_CAP_HI; c++)
        if (P != c &&
            (cyl->flags & (c == CYLRAY_CAP_LO ? CYLRAY_CAPPED_LO : CYLRAY_CAPPED_HI)) &&
            sref_dist_part(cyl, p, c) <= err)
            s |= 1u << c;
    return s;
}

/* The origin x0 lies strictly on w's side of every surface in `surf` (exact); a
 * direction within 1e-9 rad of a surface may go either way, but not onto it. */
int strictly_on_side(const cylray_cylinder *cyl, const float p[3], unsigned surf,
                     const float w[3], const float x0[3])
{
    for (int s = CYLRAY_SIDE; s <= CYLRAY_CAP_HI; s++) {
        if (!(surf >> s & 1u))
            continue;
        double n[3], wl = sqrt((double)w[0] * w[0] + (double)w[1] * w[1] + (double)w[2] * w[2]);
        sref_normal(cyl, p, s, n);
        const double wn = (n[0] * w[0] + n[1] * w[1] + n[2] * w[2]) / wl;
        const double sig = sref_sigma(cyl, x0, s);
        if (fabs(wn) <= 1e-9 ? sig == 0 : (wn > 0) != (sig > 0))
            return 0;
    }
    return 1;
}
