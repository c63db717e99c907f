/* SPDX-License-Identifier: MIT */
/* sphkernel.c - the double-precision sphere kernel of sphkernel.h: Lagrange's
 * discriminant and the stable quadratic in double, which for float inputs is accurate
 * to well below a float ulp away from a tangency. */
#include "sphkernel.h"

#include <math.h>
#include <stddef.h>

/* One lane: 1 and t, part, the normal (when `normal`) on a hit. */
static int lane(const cylray_prepared *P, const float o[3], const float d[3], float tmin,
                float tmax, unsigned flags, float *t, int32_t *part, float n[3])
{
    if (!P->magic || !(P->radius > 0) || tmin != tmin || tmax != tmax)
        return 0;
    double w[3], dd[3], A = 0, B = 0, C = 0, R = P->radius;
    for (int k = 0; k < 3; k++) {
        if (!isfinite(o[k]) || !isfinite(d[k]))
            return 0;
        w[k] = (double)o[k] - P->c[k];
        dd[k] = d[k];
        A += dd[k] * dd[k];
        B += w[k] * dd[k];
        C += w[k] * w[k];
    }
    if (!(A > 0))
        return 0;
    double x2 = 0;
    for (int k = 0; k < 3; k++) {
        double x = w[(k + 1) % 3] * dd[(k + 2) % 3] - w[(k + 2) % 3] * dd[(k + 1) % 3];
        x2 += x * x;
    }
    const double D = A * R * R - x2;
    if (!(D >= 0))
        return 0;
    const double sq = sqrt(D), q = -(B + copysign(sq, B));
    const double r1 = q / A, r2 = q != 0 ? (C - R * R) / q : r1;
    const double tn = fmin(r1, r2), tf = fmax(r1, r2);
    double th;
    int back;
    if (tn >= tmin && tn <= tmax) {
        th = tn;
        back = 0;
    } else if (!(flags & CYLRAY_CULL_BACK) && tf >= tmin && tf <= tmax && tf != tn) {
        th = tf;
        back = 1;
    } else {
        return 0;
    }
    *t = (float)th;
    *part = CYLRAY_SIDE | (back ? CYLRAY_BACKFACE : 0);
    if (flags & CYLRAY_NORMAL) {
        double p[3], l = 0;
        for (int k = 0; k < 3; k++) {
            p[k] = w[k] + th * dd[k];
            l += p[k] * p[k];
        }
        const double s = (back && (flags & CYLRAY_FACE_FORWARD) ? -1 : 1) / sqrt(l);
        for (int k = 0; k < 3; k++)
            n[k] = (float)(p[k] * s);
    }
    return 1;
}

#define PACKET(W)                                                                              \
    static uint32_t isect##W(const cylray_prepared *P, cylray_ray##W *r, cylray_hit##W *h,     \
                             uint32_t active, unsigned flags)                                  \
    {                                                                                          \
        uint32_t m = 0;                                                                        \
        for (int j = 0; j < W; j++) {                                                          \
            if (!(active >> j & 1))                                                            \
                continue;                                                                      \
            const float o[3] = {r->ox[j], r->oy[j], r->oz[j]};                                 \
            const float d[3] = {r->dx[j], r->dy[j], r->dz[j]};                                 \
            float t, n[3];                                                                     \
            int32_t part;                                                                      \
            if (!lane(P, o, d, r->tmin[j], r->tmax[j], flags, &t, &part, n))                   \
                continue;                                                                      \
            m |= 1u << j;                                                                      \
            h->t[j] = r->tmax[j] = t;                                                          \
            h->part[j] = part;                                                                 \
            if (flags & CYLRAY_NORMAL)                                                         \
                h->nx[j] = n[0], h->ny[j] = n[1], h->nz[j] = n[2];                             \
        }                                                                                      \
        return m;                                                                              \
    }                                                                                          \
    static uint32_t occ##W(const cylray_prepared *P, const cylray_ray##W *r, uint32_t active,  \
                           unsigned flags)                                                     \
    {                                                                                          \
        uint32_t m = 0;                                                                        \
        for (int j = 0; j < W; j++) {                                                          \
            const float o[3] = {r->ox[j], r->oy[j], r->oz[j]};                                 \
            const float d[3] = {r->dx[j], r->dy[j], r->dz[j]};                                 \
            float t, n[3];                                                                     \
            int32_t part;                                                                      \
            if ((active >> j & 1) &&                                                           \
                lane(P, o, d, r->tmin[j], r->tmax[j], flags & ~CYLRAY_NORMAL, &t, &part, n))   \
                m |= 1u << j;                                                                  \
        }                                                                                      \
        return m;                                                                              \
    }
PACKET(4)
PACKET(8)
PACKET(16)

static size_t isect_stream(const cylray_prepared *P, const cylray_rays *r, const cylray_hits *h,
                           size_t n, unsigned flags)
{
    size_t count = 0;
    for (size_t i = 0; i < n; i++) {
        const float o[3] = {r->ox[i], r->oy[i], r->oz[i]};
        const float d[3] = {r->dx[i], r->dy[i], r->dz[i]};
        float t, nn[3];
        int32_t part;
        if (!lane(P, o, d, r->tmin[i], r->tmax[i], flags, &t, &part, nn))
            continue;
        count++;
        h->t[i] = r->tmax[i] = t;
        h->part[i] = part;
        if (flags & CYLRAY_NORMAL)
            h->nx[i] = nn[0], h->ny[i] = nn[1], h->nz[i] = nn[2];
    }
    return count;
}

static size_t occ_stream(const cylray_prepared *P, const cylray_rays *r, uint8_t *occ, size_t n,
                         unsigned flags)
{
    size_t count = 0;
    for (size_t i = 0; i < n; i++) {
        const float o[3] = {r->ox[i], r->oy[i], r->oz[i]};
        const float d[3] = {r->dx[i], r->dy[i], r->dz[i]};
        float t, nn[3];
        int32_t part;
        if (lane(P, o, d, r->tmin[i], r->tmax[i], flags & ~CYLRAY_NORMAL, &t, &part, nn)) {
            occ[i] = 1;
            count++;
        }
    }
    return count;
}

const cylray_kernels *sphere_double_kernels(void)
{
    static const cylray_kernels k = {
        .isa = CYLRAY_ISA_SCALAR,
        .name = "sphere-double",
        .intersect4 = isect4,
        .intersect8 = isect8,
        .intersect16 = isect16,
        .occluded4 = occ4,
        .occluded8 = occ8,
        .occluded16 = occ16,
        .intersect_stream = isect_stream,
        .occluded_stream = occ_stream,
    };
    return &k;
}
