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
 * would pass (bench/peer/meson.build), naming its functions tb_stream_<TB_VARIANT> (the
 * cylinder), tb_sphere_stream_<TB_VARIANT>, tb_sphere_run_<TB_VARIANT>,
 * tb_cone_stream_<TB_VARIANT> and tb_cone_run_<TB_VARIANT>. */
#include "textbook.h"

#include <math.h>
#include <string.h>

#ifndef TB_VARIANT
#error "TB_VARIANT names the build of this file (scalar, sse41, avx2, avx512, neon)"
#endif

#define TB_CAT_(a, b) a##b
#define TB_CAT(a, b) TB_CAT_(a, b)

/* The iterations are independent (the outputs alias no input): say so, as a user
 * chasing speed would. Not in the scalar build (TB_NO_VECTORIZE): clang's
 * assume_safety turns its loop vectorizer back on in spite of -fno-vectorize. */
#if defined(TB_NO_VECTORIZE) && defined(__clang__)
#define TB_INDEPENDENT _Pragma("clang loop vectorize(disable) interleave(disable)")
#elif defined(TB_NO_VECTORIZE)
#define TB_INDEPENDENT
#elif defined(__clang__)
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

/* The textbook cone, in the same loop form and under the same contract. The radius is
 * linear along the axis, r(z) = rm + k z with z = w.v from the center and the slope
 * k = (r1 - r0) / 2H, and the side |w + t d|^2 - z^2 = r(z)^2 is the quadratic
 *
 *   A = d.d - (1+k^2)(d.v)^2,  B = d.w - (1+k^2)(d.v)(w.v) - k rm (d.v),
 *   C = w.w - (1+k^2)(w.v)^2 - 2 k rm (w.v) - rm^2
 *
 * with both roots clipped to the slab |z| <= H (which leaves out the mirror nappe, r
 * being >= 0 between the ends) and the caps as discs: the plane z = -+H met at
 * t = (-+H - w.v) / d.v, a hit when the point's squared distance from the axis is at
 * most r0^2 (r1^2). Normal on the side (w + t d - z v - r(z) k v) / (r(z) sqrt(1+k^2)).
 * A < 0 (rays steeper than the side) needs no case: the slab clip picks the roots. */
static inline int32_t tb_disc(float wx, float wy, float wz, float dx, float dy, float dz,
                              float t, float z, float rr)
{
    const float qx = wx + t * dx, qy = wy + t * dy, qz = wz + t * dz;
    return qx * qx + qy * qy + qz * qz - z * z <= rr; /* z: the plane's, -H or +H */
}

size_t TB_CAT(tb_cone_stream_, TB_VARIANT)(const tb_cone *cn, const cylray_rays *rays,
                                           const cylray_hits *hits, size_t n)
{
    const float *restrict ox = rays->ox, *restrict oy = rays->oy, *restrict oz = rays->oz;
    const float *restrict dxs = rays->dx, *restrict dys = rays->dy, *restrict dzs = rays->dz;
    const float *restrict tmin = rays->tmin;
    float *restrict tmax = rays->tmax;
    float *restrict t = hits->t, *restrict nx = hits->nx, *restrict ny = hits->ny,
                    *restrict nz = hits->nz;
    int32_t *restrict part = hits->part;
    const float cx = cn->c[0], cyy = cn->c[1], cz = cn->c[2];
    const float vx = cn->v[0], vy = cn->v[1], vz = cn->v[2];
    const float rm = cn->rm, kk = cn->k, k1 = 1.0f + kk * kk, h = cn->h;
    const float rr0 = cn->rr0, rr1 = cn->rr1, cnrm = cn->cnrm;
    const int32_t cap_lo = (cn->caps & CYLRAY_CAPPED_LO) != 0;
    const int32_t cap_hi = (cn->caps & CYLRAY_CAPPED_HI) != 0;
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
        const float A = dd - k1 * dv * dv;
        const float B = dw - k1 * dv * wv - kk * rm * dv;
        const float C = ww - k1 * wv * wv - 2.0f * kk * rm * wv - rm * rm;
        const float disc = B * B - A * C;
        const float s = sqrtf(disc); /* NaN when disc < 0: every side test below fails */
        const float t0 = (-B - s) / A, t1 = (-B + s) / A;
        const float tl = (-h - wv) / dv, th = (h - wv) / dv;
        const float lo = tmin[i], hi = tmax[i];

        const int32_t ok0 = (fabsf(wv + t0 * dv) <= h) & (t0 >= lo) & (t0 <= hi);
        const int32_t ok1 = (fabsf(wv + t1 * dv) <= h) & (t1 >= lo) & (t1 <= hi);
        const int32_t okl =
            cap_lo & tb_disc(wx, wy, wz, dx, dy, dz, tl, -h, rr0) & (tl >= lo) & (tl <= hi);
        const int32_t okh =
            cap_hi & tb_disc(wx, wy, wz, dx, dy, dz, th, h, rr1) & (th >= lo) & (th <= hi);

        /* the closest candidate: 1, 2 the side's roots, 3 low cap, 4 high cap */
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

        const float zb = wv + best * dv, rz = rm + kk * zb;
        const int32_t side = k <= 2;
        const float cs = k == 4 ? 1.0f : -1.0f, inv = cnrm / rz;
        const float mx = side ? (wx + best * dx - (zb + rz * kk) * vx) * inv : cs * vx;
        const float my = side ? (wy + best * dy - (zb + rz * kk) * vy) * inv : cs * vy;
        const float mz = side ? (wz + best * dz - (zb + rz * kk) * vz) * inv : cs * vz;
        int32_t p = side ? CYLRAY_SIDE : k == 4 ? CYLRAY_CAP_HI : CYLRAY_CAP_LO;
        p |= dx * mx + dy * my + dz * mz > 0 ? CYLRAY_BACKFACE : 0;

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

/* One ray against cones one at a time, as tb_sphere_run_ (the leaf's textbook loop):
 * the same formulas, with early outs where a scalar loop would take them. */
uint32_t TB_CAT(tb_cone_run_, TB_VARIANT)(const tb_cone *cn, int n, cylray_ray1 *ray,
                                          cylray_hit1 *hit, unsigned flags, int occluded)
{
    const float dx = ray->d[0], dy = ray->d[1], dz = ray->d[2];
    const float dd = dx * dx + dy * dy + dz * dz, lo = ray->tmin;
    float hi = ray->tmax;
    uint32_t found = 0;
    int32_t fpart = 0;
    for (int j = 0; j < n; j++) {
        const tb_cone *q = &cn[j];
        const float wx = ray->o[0] - q->c[0], wy = ray->o[1] - q->c[1],
                    wz = ray->o[2] - q->c[2];
        const float vx = q->v[0], vy = q->v[1], vz = q->v[2], h = q->h;
        const float kk = q->k, k1 = 1.0f + kk * kk, rm = q->rm;
        const float dv = dx * vx + dy * vy + dz * vz;
        const float wv = wx * vx + wy * vy + wz * vz;
        const float dw = dx * wx + dy * wy + dz * wz;
        const float ww = wx * wx + wy * wy + wz * wz;
        const float A = dd - k1 * dv * dv;
        const float B = dw - k1 * dv * wv - kk * rm * dv;
        const float C = ww - k1 * wv * wv - 2.0f * kk * rm * wv - rm * rm;
        const float disc = B * B - A * C;
        float best = INFINITY;
        int32_t k = 0;
        if (disc >= 0) {
            const float s = sqrtf(disc);
            const float t0 = (-B - s) / A, t1 = (-B + s) / A;
            if (fabsf(wv + t0 * dv) <= h && t0 >= lo && t0 <= hi)
                best = t0, k = 1;
            if (fabsf(wv + t1 * dv) <= h && t1 >= lo && t1 <= hi && t1 < best)
                best = t1, k = 1;
        }
        if (q->caps && dv != 0) {
            const float tl = (-h - wv) / dv, th = (h - wv) / dv;
            if ((q->caps & CYLRAY_CAPPED_LO) && tl >= lo && tl <= hi && tl < best &&
                tb_disc(wx, wy, wz, dx, dy, dz, tl, -h, q->rr0))
                best = tl, k = 3;
            if ((q->caps & CYLRAY_CAPPED_HI) && th >= lo && th <= hi && th < best &&
                tb_disc(wx, wy, wz, dx, dy, dz, th, h, q->rr1))
                best = th, k = 4;
        }
        if (!k)
            continue;
        found = (uint32_t)j + 1;
        if (occluded)
            return found;
        hi = best;
        fpart = k;
    }
    if (found && !occluded) {
        const tb_cone *q = &cn[found - 1];
        const float wx = ray->o[0] - q->c[0], wy = ray->o[1] - q->c[1],
                    wz = ray->o[2] - q->c[2];
        const float vx = q->v[0], vy = q->v[1], vz = q->v[2];
        const float zb = wx * vx + wy * vy + wz * vz + hi * (dx * vx + dy * vy + dz * vz);
        const float rz = q->rm + q->k * zb, inv = q->cnrm / rz, cs = fpart == 4 ? 1.0f : -1.0f;
        float m[3];
        if (fpart == 1) {
            m[0] = (wx + hi * dx - (zb + rz * q->k) * vx) * inv;
            m[1] = (wy + hi * dy - (zb + rz * q->k) * vy) * inv;
            m[2] = (wz + hi * dz - (zb + rz * q->k) * vz) * inv;
        } else {
            m[0] = cs * vx, m[1] = cs * vy, m[2] = cs * vz;
        }
        hit->t = hi;
        hit->part = fpart == 1 ? CYLRAY_SIDE : fpart == 4 ? CYLRAY_CAP_HI : CYLRAY_CAP_LO;
        hit->part |= dx * m[0] + dy * m[1] + dz * m[2] > 0 ? CYLRAY_BACKFACE : 0;
        if (flags & CYLRAY_NORMAL)
            memcpy(hit->n, m, sizeof m);
        hit->lane = found - 1;
        ray->tmax = hi;
    }
    return found;
}
