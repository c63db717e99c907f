/* SPDX-License-Identifier: MIT */
/* embree/resolve.h - one ray against one cylinder, for the rarer paths: whether a hit is
 * the primitive's to report and, when it is not or a filter rejects it, the next hit.
 * Included by single.c alone: inline in its callbacks, as hit.h's helpers are. */
#ifndef CYLRAY_EMBREE_RESOLVE_H
#define CYLRAY_EMBREE_RESOLVE_H

#include "hit.h"

/* The first hit of one ray on cylinder c in [tmin, tmax] through the 4-wide kernel,
 * the ray repeated in every lane (the lanes stay valid numbers, never stack garbage,
 * whose subnormals would cost microcode assists). Every lane is active: the kernels
 * then store a whole vector where a partial one would take a masked store, or a blend
 * or lane loop by the store policy, and the reload of lane 0 below is forwarded from a
 * plain store (4 % of a tapered molecule's time in Embree's AVX2 mode, Zen 4). h is
 * cleared first: a blend store reads the fields it keeps. */
static int one_ray(const ceb *g, uint32_t c, const float o[3], const float d[3], float tmin,
                   float tmax, float *t, float n[3], int32_t *part)
{
    cylray_ray4 r;
    cylray_hit4 h;
    memset(&h, 0, sizeof h);
    for (int j = 0; j < 4; j++) {
        r.ox[j] = o[0], r.oy[j] = o[1], r.oz[j] = o[2];
        r.dx[j] = d[0], r.dy[j] = d[1], r.dz[j] = d[2];
        r.tmin[j] = tmin, r.tmax[j] = tmax;
    }
    if (!g->k->intersect4(&g->prep[c], &r, &h, 0xFu, g->iflags))
        return 0;
    *t = h.t[0];
    n[0] = h.nx[0], n[1] = h.ny[0], n[2] = h.nz[0];
    *part = h.part[0];
    return 1;
}

/* Does this hit belong to primitive prim? With split boxes each hit is reported by the
 * one piece whose stretch of the axis holds its u; the pieces' boxes are padded by more
 * than u's rounding, so that piece's box holds the hit point. */
static int owns(const ceb *g, unsigned prim, uint32_t c, float u)
{
    if (!g->prim_piece)
        return 1;
    uint32_t K = g->fr[c].pieces; /* spheres have no prim_piece: never here */
    if (K == 1)
        return 1;
    float x = u * (float)K;
    uint32_t piece = x <= 0 ? 0 : x >= (float)(K - 1) ? K - 1 : (uint32_t)x;
    return piece == g->prim_piece[prim];
}

/* A hit the kernel found for lane i on cylinder c: reported when primitive prim owns
 * it and the filters (when called) accept it; otherwise the next hit of c along the
 * ray is tried, until one is reported or there is none. The query is an intersection's
 * (ai) or an occlusion's (ao), the other NULL: resolve_hit and resolve_occ below, so
 * that neither struct is read as the other. Returns 1 when a hit was reported. */
static int resolve(const ceb *g, const struct RTCIntersectFunctionNArguments *ai,
                   const struct RTCOccludedFunctionNArguments *ao, int filt, unsigned i,
                   uint32_t c, float t, float n[3], int32_t part)
{
    const int occ = ao != NULL;
    unsigned prim = occ ? ao->primID : ai->primID, N = occ ? ao->N : ai->N;
    const void *base = occ ? (const void *)ao->ray : (const void *)ai->rayhit;
    float o[3], d[3];
    ray_of(base, N, i, o, d);
    /* a cylinder or sphere has at most two hits along a ray; the bound only guards the
     * loop */
    for (int tries = 0; tries < 8; tries++) {
        hitrec h = {t, {n[0], n[1], n[2]}, 0, 0, (unsigned)c};
        ceb_uv(g, c, o, d, t, part, n, &h.u, &h.v);
        if (owns(g, prim, c, h.u)) {
            if (occ ? (filt ? ceb_filter_occ(ao, i, &h)
                            : (RF(ao->ray, N, R_TFAR, i) = -INFINITY, 1))
                    : (filt ? ceb_filter_hit(ai, i, &h) : (put_hit(ai, i, &h), 1)))
                return 1;
        }
        float tmax = RF(base, N, R_TFAR, i);
        if (!one_ray(g, c, o, d, nextafterf(t, INFINITY), tmax, &t, n, &part))
            return 0;
    }
    return 0;
}

static inline int resolve_hit(const ceb *g, const struct RTCIntersectFunctionNArguments *a,
                              int filt, unsigned i, uint32_t c, float t, float n[3],
                              int32_t part)
{
    return resolve(g, a, NULL, filt, i, c, t, n, part);
}

static inline int resolve_occ(const ceb *g, const struct RTCOccludedFunctionNArguments *a,
                              int filt, unsigned i, uint32_t c, float t, float n[3],
                              int32_t part)
{
    return resolve(g, NULL, a, filt, i, c, t, n, part);
}

#endif
