/* SPDX-License-Identifier: MIT */
/* naive.c - the textbook intersection as a tracer author would write it in an afternoon:
 * one branch-free loop over SoA rays, plain float, left to the compiler's vectorizer.
 *
 *   A = d.d - (d.v)^2,  B = d.w - (d.v)(w.v),  C = w.w - (w.v)^2 - R^2   (w = o - c)
 *   disc = B^2 - A C,   t = (-B -/+ sqrt(disc)) / A
 *
 * with a float-normalised axis v, the finite clip |z| <= H on the axial coordinate
 * z = w.v + t d.v of each root, and flat caps by the slab: the planes z = -H and z = +H
 * are met at t = (-+H - w.v) / d.v, and count where the ray is inside the infinite
 * cylinder there (between the two roots). The closest of the four candidates in
 * [tmin, tmax] wins. Nothing is guarded: parallel rays divide by zero, far origins
 * cancel catastrophically in C, grazing rays lose the discriminant. That is the point:
 * this is the speed a user gets without accuracy.
 *
 * The file is compiled once per ISA into its own static library with the flags a user
 * would pass (bench/meson.build), naming its functions tb_stream_<TB_VARIANT> (the
 * cylinder), tb_sphere_stream_<TB_VARIANT> and tb_sphere_run_<TB_VARIANT>. */
#include "textbook.h"

#include <math.h>

#ifndef TB_VARIANT
#error "TB_VARIANT names the build of this file (scalar, sse41, avx2, avx512, neon)"
#endif

#define TB_CAT_(a, b) a##b
#define TB_CAT(a, b) TB_CAT_(a, b)

/* The iterations are independent (the outputs alias no input): say so, as a user
 * chasing speed would. */
#if defined(__clang__)
#define TB_INDEPENDENT _Pragma("clang loop vectorize(assume_safety)")
#elif defined(__GNUC__)
#define TB_INDEPENDENT _Pragma("GCC ivdep")
#else
#define TB_INDEPENDENT
#endif

size_t TB_CAT(tb_stream_, TB_VARIANT)(const tb_cylinder *cy, const cylray_rays *rays,
                                      const cylray_hits *hits, size_t n)
{
    const float *restrict ox = rays->ox, *restrict oy = rays->oy, *restrict oz = rays->oz;
    const float *restrict dxs = rays->dx, *restrict dys = rays->dy, *restrict dzs = rays->dz;
    const float *restrict tmin = rays->tmin;
    float *restrict tmax = rays->tmax;
    float *restrict t = hits->t, *restrict nx = hits->nx, *restrict ny = hits->ny,
                    *restrict nz = hits->nz;
    int32_t *restrict part = hits->part;
    const float cx = cy->c[0], cyy = cy->c[1], cz = cy->c[2];
    const float vx = cy->v[0], vy = cy->v[1], vz = cy->v[2];
    const float rr = cy->rr, inv_r = cy->inv_r, h = cy->h;
    const int32_t cap_lo = (cy->caps & CYLRAY_CAPPED_LO) != 0;
    const int32_t cap_hi = (cy->caps & CYLRAY_CAPPED_HI) != 0;
    int32_t count = 0;

    TB_INDEPENDENT
    for (size_t i = 0; i < n; i++) {
        const float dx = dxs[i], dy = dys[i], dz = dzs[i];
        const float wx = ox[i] - cx, wy = oy[i] - cyy, wz = oz[i] - cz;
        const float dd = dx * dx + dy * dy + dz * dz;
        const float dv = dx * vx + dy * vy + dz * vz;
        const float wv = wx * vx + wy * vy + wz * vz;
        const float dw = dx * wx + dy * wy + dz * wz;
        const float ww = wx * wx + wy * wy + wz * wz;
        const float A = dd - dv * dv;
        const float B = dw - dv * wv;
        const float C = ww - wv * wv - rr;
        const float disc = B * B - A * C;
        const float s = sqrtf(disc); /* NaN when disc < 0: every test below fails */
        const float t0 = (-B - s) / A, t1 = (-B + s) / A;
        const float tl = (-h - wv) / dv, th = (h - wv) / dv;
        const float lo = tmin[i], hi = tmax[i];

        /* & rather than &&: every test is cheap, and a branch would stop the vectorizer */
        const int32_t ok0 = (fabsf(wv + t0 * dv) <= h) & (t0 >= lo) & (t0 <= hi);
        const int32_t ok1 = (fabsf(wv + t1 * dv) <= h) & (t1 >= lo) & (t1 <= hi);
        const int32_t okl = cap_lo & (tl >= t0) & (tl <= t1) & (tl >= lo) & (tl <= hi);
        const int32_t okh = cap_hi & (th >= t0) & (th <= t1) & (th >= lo) & (th <= hi);

        /* the closest candidate: 1 entering side, 2 leaving side, 3 low cap, 4 high cap */
        float best = ok0 ? t0 : INFINITY;
        int32_t k = ok0 ? 1 : 0;
        const int32_t take1 = ok1 & (t1 < best);
        best = take1 ? t1 : best;
        k = take1 ? 2 : k;
        const int32_t takel = okl & (tl < best);
        best = takel ? tl : best;
        k = takel ? 3 : k;
        const int32_t takeh = okh & (th < best);
        best = takeh ? th : best;
        k = takeh ? 4 : k;

        /* the outward normal: the hit point minus its projection on the axis, over R,
         * on the side; the axis, signed by the cap, on a cap */
        const float zb = wv + best * dv;
        const int32_t side = k <= 2;
        const float cs = k == 4 ? 1.0f : -1.0f;
        const float mx = side ? (wx + best * dx - zb * vx) * inv_r : cs * vx;
        const float my = side ? (wy + best * dy - zb * vy) * inv_r : cs * vy;
        const float mz = side ? (wz + best * dz - zb * vz) * inv_r : cs * vz;
        int32_t p = side ? CYLRAY_SIDE : k == 4 ? CYLRAY_CAP_HI : CYLRAY_CAP_LO;
        p |= dx * mx + dy * my + dz * mz > 0 ? CYLRAY_BACKFACE : 0;

        /* Every output is written for every ray (t = INFINITY and part = CYLRAY_MISS on a
         * miss): "keep the old value on a miss" is a conditional store, which gcc will
         * not vectorize without masked stores (SSE4.1 has none). */
        const int32_t hit = k != 0;
        t[i] = best;
        tmax[i] = best < hi ? best : hi;
        nx[i] = mx;
        ny[i] = my;
        nz[i] = mz;
        part[i] = hit ? p : CYLRAY_MISS;
        count += hit;
    }
    return (size_t)count;
}

/* The textbook sphere, in the same loop form and under the same contract:
 *
 *   b = w.d,  c = w.w - R^2,  disc = b^2 - (d.d) c,  t = (-b -/+ sqrt(disc)) / d.d
 *
 * the near root when it lies in [tmin, tmax], else the far one (the ray starts inside),
 * normal (w + t d) / R. Far origins cancel in c and in -b + sqrt(disc) alike. */
size_t TB_CAT(tb_sphere_stream_, TB_VARIANT)(const tb_sphere *sp, const cylray_rays *rays,
                                             const cylray_hits *hits, size_t n)
{
    const float *restrict ox = rays->ox, *restrict oy = rays->oy, *restrict oz = rays->oz;
    const float *restrict dxs = rays->dx, *restrict dys = rays->dy, *restrict dzs = rays->dz;
    const float *restrict tmin = rays->tmin;
    float *restrict tmax = rays->tmax;
    float *restrict t = hits->t, *restrict nx = hits->nx, *restrict ny = hits->ny,
                    *restrict nz = hits->nz;
    int32_t *restrict part = hits->part;
    const float cx = sp->c[0], cyy = sp->c[1], cz = sp->c[2];
    const float rr = sp->rr, inv_r = sp->inv_r;
    int32_t count = 0;

    TB_INDEPENDENT
    for (size_t i = 0; i < n; i++) {
        const float dx = dxs[i], dy = dys[i], dz = dzs[i];
        const float wx = ox[i] - cx, wy = oy[i] - cyy, wz = oz[i] - cz;
        const float dd = dx * dx + dy * dy + dz * dz;
        const float b = dx * wx + dy * wy + dz * wz;
        const float c = wx * wx + wy * wy + wz * wz - rr;
        const float disc = b * b - dd * c;
        const float s = sqrtf(disc); /* NaN when disc < 0: every test below fails */
        const float t0 = (-b - s) / dd, t1 = (-b + s) / dd;
        const float lo = tmin[i], hi = tmax[i];
        const int32_t ok0 = (t0 >= lo) & (t0 <= hi);
        const int32_t ok1 = (t1 >= lo) & (t1 <= hi);
        const int32_t hit = ok0 | ok1;
        const float best = ok0 ? t0 : ok1 ? t1 : INFINITY;
        const float mx = (wx + best * dx) * inv_r;
        const float my = (wy + best * dy) * inv_r;
        const float mz = (wz + best * dz) * inv_r;
        const int32_t p =
            dx * mx + dy * my + dz * mz > 0 ? CYLRAY_SIDE | CYLRAY_BACKFACE : CYLRAY_SIDE;
        t[i] = best;
        tmax[i] = best < hi ? best : hi;
        nx[i] = mx;
        ny[i] = my;
        nz[i] = mz;
        part[i] = hit ? p : CYLRAY_MISS;
        count += hit;
    }
    return (size_t)count;
}

/* One ray against spheres one at a time, closest hit kept through tmax (any hit for
 * occlusion): the scalar loop over a leaf's spheres a tracer would write. Only the
 * build without the vectorizer is used (the leaf scenario's textbook loop). Returns the
 * index + 1 of the sphere hit, 0 for none. */
uint32_t TB_CAT(tb_sphere_run_, TB_VARIANT)(const tb_sphere *sp, int n, cylray_ray1 *ray,
                                            cylray_hit1 *hit, unsigned flags, int occluded)
{
    const float dx = ray->d[0], dy = ray->d[1], dz = ray->d[2];
    const float dd = dx * dx + dy * dy + dz * dz, lo = ray->tmin;
    float hi = ray->tmax;
    uint32_t found = 0;
    for (int k = 0; k < n; k++) {
        const tb_sphere *q = &sp[k];
        const float wx = ray->o[0] - q->c[0], wy = ray->o[1] - q->c[1],
                    wz = ray->o[2] - q->c[2];
        const float b = dx * wx + dy * wy + dz * wz;
        const float c = wx * wx + wy * wy + wz * wz - q->rr;
        const float disc = b * b - dd * c;
        if (!(disc >= 0))
            continue;
        const float s = sqrtf(disc);
        float tt = (-b - s) / dd;
        if (!(tt >= lo))
            tt = (-b + s) / dd;
        if (!(tt >= lo && tt <= hi))
            continue;
        found = (uint32_t)k + 1;
        if (occluded)
            return found;
        hi = tt;
    }
    if (found && !occluded) {
        const tb_sphere *q = &sp[found - 1];
        const float wx = ray->o[0] - q->c[0], wy = ray->o[1] - q->c[1],
                    wz = ray->o[2] - q->c[2];
        const float mx = (wx + hi * dx) * q->inv_r, my = (wy + hi * dy) * q->inv_r,
                    mz = (wz + hi * dz) * q->inv_r;
        hit->t = hi;
        hit->part =
            dx * mx + dy * my + dz * mz > 0 ? CYLRAY_SIDE | CYLRAY_BACKFACE : CYLRAY_SIDE;
        if (flags & CYLRAY_NORMAL) {
            hit->n[0] = mx;
            hit->n[1] = my;
            hit->n[2] = mz;
        }
        hit->lane = found - 1;
        ray->tmax = hi;
    }
    return found;
}
