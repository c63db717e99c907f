/* SPDX-License-Identifier: MIT */
/* embree/spawn.c - what a renderer asks about a hit Embree reported: its part, its
 * point, its surface frame, and secondary rays from it (cylray's hit point and spawned
 * origin), the part read back from the hit's normal. */
#include "hit.h"

#include <math.h>

/* The hit's part from its normal: the discs' normals are the axis, the side's are
 * perpendicular to it (a cone's tilted by its slope); a sphere is all side. -1 for a
 * geometry or primID not ours, or a useless Ng. */
static int hit_part(const ceb *g, unsigned primID, const float Ng[3])
{
    if (!g || primID >= g->n || !isfinite(Ng[0]) || !isfinite(Ng[1]) || !isfinite(Ng[2]) ||
        (Ng[0] == 0 && Ng[1] == 0 && Ng[2] == 0))
        return -1;
    if (!g->fr)
        return CYLRAY_SIDE; /* a sphere */
    /* the thresholds halfway between the side's axial component ns and the discs' +-1
     * (a cylinder's: +-1/2) */
    const frame *f = &g->fr[primID];
    const float *n = f->n;
    float c = Ng[0] * n[0] + Ng[1] * n[1] + Ng[2] * n[2];
    float l = sqrtf(Ng[0] * Ng[0] + Ng[1] * Ng[1] + Ng[2] * Ng[2]);
    float hi = 0.5f * (1.0f + f->ns), lo = 0.5f * (f->ns - 1.0f);
    return c > hi * l ? CYLRAY_CAP_HI : c < lo * l ? CYLRAY_CAP_LO : CYLRAY_SIDE;
}

/* The hit point of primID's hit at t on o + t d, with its bound and part: 0, or -1 for a
 * hit this geometry cannot place. */
static int point_of(const ceb *g, unsigned primID, const float o[3], const float d[3], float t,
                    const float Ng[3], float p[3], float *err, int *part)
{
    *part = hit_part(g, primID, Ng);
    if (*part < 0)
        return -1;
    cylray_hit_point(&g->prep[primID], o, d, t, *part, p, err);
    return 0;
}

int cylray_embree_spawn_origin(RTCGeometry geometry, unsigned primID, const float o[3],
                               const float d[3], float t, const float Ng[3], const float w[3],
                               float out[3])
{
    const ceb *g = ceb_of(geometry);
    float p[3], err;
    int part;
    if (point_of(g, primID, o, d, t, Ng, p, &err, &part))
        return -1;
    cylray_spawn_origin(&g->prep[primID], p, err, part, w, out);
    return 0;
}

int cylray_embree_spawn_origin_side(RTCGeometry geometry, unsigned primID, const float o[3],
                                    const float d[3], float t, const float Ng[3], int outward,
                                    const float w[3], float out[3])
{
    const ceb *g = ceb_of(geometry);
    float p[3], err;
    int part;
    if (point_of(g, primID, o, d, t, Ng, p, &err, &part))
        return -1;
    cylray_spawn_origin_side(&g->prep[primID], p, err, part, outward, w, out);
    return 0;
}

int cylray_embree_hit_part(RTCGeometry geometry, unsigned primID, const float Ng[3])
{
    return hit_part(ceb_of(geometry), primID, Ng);
}

int cylray_embree_hit_point(RTCGeometry geometry, unsigned primID, const float o[3],
                            const float d[3], float t, const float Ng[3], float p[3],
                            float *err)
{
    const ceb *g = ceb_of(geometry);
    int part = hit_part(g, primID, Ng);
    if (part < 0)
        return -1;
    float e;
    /* the normal form: Ng is the kernel's own normal, and with it the point stays at
     * the kernel's azimuth where float t alone cannot place it */
    cylray_hit_point_normal(&g->prep[primID], o, d, t, part, Ng, p, &e);
    if (err)
        *err = e;
    return 0;
}

int cylray_embree_surface(RTCGeometry geometry, unsigned primID, const float o[3],
                          const float d[3], float t, const float Ng[3], float p[3], float uv[2],
                          float dpdu[3], float dpdv[3])
{
    const ceb *g = ceb_of(geometry);
    int part = hit_part(g, primID, Ng);
    if (part < 0)
        return -1;
    float q[3], e;
    cylray_hit_point_normal(&g->prep[primID], o, d, t, part, Ng, q, &e);
    cylray_surface(&g->prep[primID], q, part, uv, dpdu, dpdv);
    if (p)
        p[0] = q[0], p[1] = q[1], p[2] = q[2];
    return part;
}

/* Lane i's ray and hit, read from the packet rh of N lanes. */
static void lane_of(const void *rh, unsigned N, unsigned i, float o[3], float d[3], float *t,
                    float Ng[3], unsigned *prim)
{
    const float *hb = (const float *)rh + (size_t)R_NFIELDS * N;
    ray_of(rh, N, i, o, d);
    for (int k = 0; k < 3; k++)
        Ng[k] = RF(hb, N, H_NGX + k, i);
    *t = RF(rh, N, R_TFAR, i);
    *prim = RU(hb, N, H_PRIM, i);
}

/* The packet forms: every valid lane whose hit is geomID's, one lane at a time (the
 * lanes' cylinders differ, and a scalar call per lane costs less than gathering them
 * into a packet per cylinder). outward: NULL for the plain form. */
static uint32_t spawn_lanes(RTCGeometry geometry, unsigned geomID, const int *valid,
                            const void *rh, unsigned N, const int *outward, const float *w,
                            float *out)
{
    const ceb *g = ceb_of(geometry);
    if (!g || !valid || !rh || !w || !out || N == 0 || N > 16)
        return 0;
    const float *hb = (const float *)rh + (size_t)R_NFIELDS * N;
    uint32_t done = 0;
    for (unsigned i = 0; i < N; i++) {
        if (!valid[i] || RU(hb, N, H_GEOM, i) != geomID)
            continue;
        float o[3], d[3], t, Ng[3], p[3], err, wi[3], org[3];
        unsigned prim;
        int part;
        lane_of(rh, N, i, o, d, &t, Ng, &prim);
        if (!isfinite(t) || point_of(g, prim, o, d, t, Ng, p, &err, &part))
            continue;
        for (int k = 0; k < 3; k++)
            wi[k] = w[(size_t)k * N + i];
        if (outward)
            cylray_spawn_origin_side(&g->prep[prim], p, err, part, outward[i], wi, org);
        else
            cylray_spawn_origin(&g->prep[prim], p, err, part, wi, org);
        for (int k = 0; k < 3; k++)
            out[(size_t)k * N + i] = org[k];
        done |= 1u << i;
    }
    return done;
}

uint32_t cylray_embree_spawn_origins(RTCGeometry geometry, unsigned geomID, const int *valid,
                                     const struct RTCRayHitN *rayhit, unsigned N,
                                     const float *w, float *out)
{
    return spawn_lanes(geometry, geomID, valid, rayhit, N, NULL, w, out);
}

uint32_t cylray_embree_spawn_origins_side(RTCGeometry geometry, unsigned geomID,
                                          const int *valid, const struct RTCRayHitN *rayhit,
                                          unsigned N, const int *outward, const float *w,
                                          float *out)
{
    if (!outward)
        return 0;
    return spawn_lanes(geometry, geomID, valid, rayhit, N, outward, w, out);
}
