/* SPDX-License-Identifier: MIT */
/* embree/hit.h - a hit's u and v, and its record written into Embree's ray: what every
 * callback does per hit, kept inline in each. */
#ifndef CYLRAY_EMBREE_HIT_H
#define CYLRAY_EMBREE_HIT_H

#include "ceb.h"

#include <math.h>
#include <string.h>

/* The axial coordinate of the point o + t d on cylinder f: 0 at p0, 1 at p1, clamped;
 * the end discs give 0 and 1 exactly. */
static inline float axial_u(const frame *f, const float o[3], const float d[3], float t,
                            int part)
{
    part &= CYLRAY_PART_MASK;
    if (part == CYLRAY_CAP_LO)
        return 0.0f;
    if (part == CYLRAY_CAP_HI)
        return 1.0f;
    double s = 0;
    for (int k = 0; k < 3; k++)
        s += ((double)o[k] + (double)t * d[k] - f->p0[k]) * f->a[k];
    s *= f->inv_aa;
    return s <= 0 ? 0.0f : s >= 1 ? 1.0f : (float)s;
}

/* One of two floats by a condition, through their bits: the conditions below depend on
 * the hit's direction, which no branch predictor guesses. (Measured on Zen 4 the selects
 * and the branches they replace are alike within noise; the selects keep the time
 * independent of the scene.) */
static inline float pick(int c, float a, float b)
{
    uint32_t ua, ub, m = 0u - (uint32_t)(c != 0);
    memcpy(&ua, &a, 4);
    memcpy(&ub, &b, 4);
    ua = (ua & m) | (ub & ~m);
    memcpy(&a, &ua, 4);
    return a;
}

/* atan2(y, x) / 2pi in [0, 1). Every hit a query reports is written with its v, most of
 * them overwritten by a closer one, and libm's atan2f cost as much as the intersection
 * test: a polynomial for atan on [0, 1] (absolute error below 3e-6 rad, 4e-7 in v)
 * with the octant folded in serves. */
static inline float turns(float y, float x)
{
    /* Comparisons, not fmaxf / fminf: without -ffast-math those stay calls into libm
     * (their NaN rules are not one instruction's), two calls a hit. */
    float ax = fabsf(x), ay = fabsf(y);
    int flat = ax > ay;
    float mx = pick(flat, ax, ay), mn = pick(flat, ay, ax);
    if (mx == 0)
        return 0.0f;
    float a = mn / mx, s = a * a;
    /* Estrin's scheme: half the dependent steps of Horner's (within noise of it on
     * Zen 4; the frame's prefetch in single.c is what paid). */
    float s2 = s * s, s4 = s2 * s2;
    float r = a * ((0.99997726f + s * -0.33262347f) + s2 * (0.19354346f + s * -0.11643287f) +
                   s4 * (0.05265332f + s * -0.01172120f));
    const float half_pi = 1.57079632679489662f, pi = 3.14159265358979324f;
    r = pick(ay > ax, half_pi - r, r);
    r = pick(x < 0, pi - r, r);
    r = pick(y < 0, -r, r);
    float v = r * (float)(0.5 / 3.14159265358979323846);
    v = pick(v < 0, v + 1.0f, v);
    return pick(v >= 1.0f, 0.0f, v);
}

/* The azimuth in [0, 1) of the radial vector r in the frame (b1, b2). */
static inline float azimuth_v(const frame *f, const float r[3])
{
    float x = r[0] * f->b1[0] + r[1] * f->b1[1] + r[2] * f->b1[2];
    float y = r[0] * f->b2[0] + r[1] * f->b2[1] + r[2] * f->b2[2];
    return turns(y, x);
}

/* u and v of a hit: on the side the outward normal is the radial direction; on a disc
 * the radial vector comes from the hit point. */
static inline void hit_uv(const frame *f, const float o[3], const float d[3], float t, int part,
                          const float n[3], float *u, float *v)
{
    *u = axial_u(f, o, d, t, part);
    if ((part & CYLRAY_PART_MASK) == CYLRAY_SIDE) {
        *v = azimuth_v(f, n);
        return;
    }
    double q[3], s = 0;
    for (int k = 0; k < 3; k++) {
        q[k] = (double)o[k] + (double)t * d[k] - f->p0[k];
        s += q[k] * f->n[k];
    }
    float r[3];
    for (int k = 0; k < 3; k++)
        r[k] = (float)(q[k] - s * f->n[k]);
    *v = azimuth_v(f, r);
}

/* u and v of a sphere's hit from its unit outward normal n, as pbrt-v4's full sphere:
 * u = atan2(y, x) / 2pi in [0, 1); v = 1 - theta / pi, 0 at the -z pole, taken as
 * 1/2 + asin(z) / pi through the same atan (acos would be a libm call, and ill
 * conditioned at the poles). */
static inline void sphere_uv(const float n[3], float *u, float *v)
{
    *u = turns(n[1], n[0]);
    float a = turns(n[2], sqrtf(n[0] * n[0] + n[1] * n[1])); /* [0, 1/4] or (3/4, 1) */
    a = pick(a > 0.5f, a - 1.0f, a);
    *v = 0.5f + 2.0f * a;
}

/* u and v of a hit on shape c of the geometry: from its frame, or from the normal for a
 * shape without one (a sphere). */
static inline void ceb_uv(const ceb *g, uint32_t c, const float o[3], const float d[3], float t,
                          int part, const float n[3], float *u, float *v)
{
    if (g->options & CYLRAY_EMBREE_NO_ANGLES) {
        *u = g->fr ? axial_u(&g->fr[c], o, d, t, part) : 0.0f;
        *v = 0.0f;
    } else if (g->fr)
        hit_uv(&g->fr[c], o, d, t, part, n, u, v);
    else
        sphere_uv(n, u, v);
}

/* Hit h written into lane i of the hit record hb (of N lanes). */
static inline void hit_fields(float *hb, unsigned N, unsigned i, const hitrec *h,
                              unsigned geomID, const ceb_context *ctx)
{
    RF(hb, N, H_NGX, i) = h->n[0];
    RF(hb, N, H_NGY, i) = h->n[1];
    RF(hb, N, H_NGZ, i) = h->n[2];
    RF(hb, N, H_U, i) = h->u;
    RF(hb, N, H_V, i) = h->v;
    RU(hb, N, H_PRIM, i) = h->prim;
    RU(hb, N, H_GEOM, i) = geomID;
    for (unsigned l = 0; l < RTC_MAX_INSTANCE_LEVEL_COUNT; l++) {
        RU(hb, N, H_INST + l, i) = ceb_inst_id(ctx, l);
        if (CEB_INST_PRIM)
            RU(hb, N, H_INST_PRIM + l, i) = ceb_inst_prim_id(ctx, l);
    }
}

/* Hit h written into lane i's ray and hit record. */
static inline void put_hit(const struct RTCIntersectFunctionNArguments *a, unsigned i,
                           const hitrec *h)
{
    RF(a->rayhit, a->N, R_TFAR, i) = h->t;
    hit_fields((float *)a->rayhit + R_NFIELDS * a->N, a->N, i, h, a->geomID, a->context);
}

/* Lane i's ray origin and direction. */
static inline void ray_of(const void *base, unsigned N, unsigned i, float o[3], float d[3])
{
    for (int k = 0; k < 3; k++) {
        o[k] = RF(base, N, R_OX + k, i);
        d[k] = RF(base, N, R_DX + k, i);
    }
}

#endif
