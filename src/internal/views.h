/* SPDX-License-Identifier: MIT */
/* internal/views.h - the rays and hits a kernel reads and writes, as per-field
 * arrays, with the coordinates renamed for an axis-aligned cylinder. */
#ifndef CYLRAY_INTERNAL_VIEWS_H
#define CYLRAY_INTERNAL_VIEWS_H

#include "cylray.h"

/* A cylinder along a coordinate axis is handled with the coordinates renamed by a
 * rotation (so cross products keep their form) that makes its axis the third one:
 * along x, (x, y, z) is read as (y, z, x); along y, as (z, x, y). cylray_prepare stores
 * the renamed center (cr); the kernels rename the rays' and the hits' coordinate
 * arrays, once per call, and then read and write them in place. */
static inline void cylray_axis_order_(const cylray_prepared *P, int aligned, size_t k[3])
{
    for (int j = 0; j < 3; j++)
        k[j] = aligned ? P->order[j] : (size_t)j;
}

/* The views of a packet struct (cylray_rayN, cylray_hitN): field f of n lanes each
 * at ray + f n, renamed when aligned. */
static inline cylray_rays cylray_packet_rays_(const cylray_prepared *P, float *ray, size_t n,
                                              int aligned)
{
    size_t k[3];
    cylray_axis_order_(P, aligned, k);
    cylray_rays q = {ray + k[0] * n,       ray + k[1] * n,       ray + k[2] * n,
                     ray + (3 + k[0]) * n, ray + (3 + k[1]) * n, ray + (3 + k[2]) * n,
                     ray + 6 * n,          ray + 7 * n};
    return q;
}

static inline cylray_hits cylray_packet_hits_(const cylray_prepared *P, float *hit, size_t n,
                                              int aligned)
{
    size_t k[3];
    cylray_axis_order_(P, aligned, k);
    cylray_hits q = {hit, hit + (1 + k[0]) * n, hit + (1 + k[1]) * n, hit + (1 + k[2]) * n,
                     (int32_t *)(void *)(hit + 4 * n)};
    return q;
}

/* The same renaming for a stream's separate arrays. */
static inline cylray_rays cylray_rays_renamed_(const cylray_prepared *P, const cylray_rays *r)
{
    const float *o[3] = {r->ox, r->oy, r->oz}, *d[3] = {r->dx, r->dy, r->dz};
    size_t k[3];
    cylray_axis_order_(P, 1, k);
    cylray_rays q = {o[k[0]], o[k[1]], o[k[2]], d[k[0]], d[k[1]], d[k[2]], r->tmin, r->tmax};
    return q;
}

static inline cylray_hits cylray_hits_renamed_(const cylray_prepared *P, const cylray_hits *h)
{
    float *nv[3] = {h->nx, h->ny, h->nz};
    size_t k[3];
    cylray_axis_order_(P, 1, k);
    cylray_hits q = {h->t, nv[k[0]], nv[k[1]], nv[k[2]], h->part};
    return q;
}

#endif
