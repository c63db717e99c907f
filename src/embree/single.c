/* SPDX-License-Identifier: MIT */
/* embree/single.c - the callbacks of a geometry of one cylinder (or one piece of a split
 * one, or one sphere) a primitive: Embree's N = 1, 4, 8 and 16 lanes through cylray's packet
 * kernels. */
#include "resolve.h"

/* ---- one cylinder a primitive: cylray's packet kernels ------------------------- */

/* The valid lanes, in order. Embree's hybrid traversal of incoherent packets calls with
 * N = 8 or 16 and one valid lane more often than not: the mask is built without a
 * branch per lane (a loop of constant length the compiler vectorises), and only the
 * valid lanes are visited. */
static uint32_t valid_bits(const int *valid, unsigned N)
{
    uint32_t m = 0;
    switch (N) {
    case 16:
        for (unsigned i = 0; i < 16; i++)
            m |= (uint32_t)(valid[i] != 0) << i;
        return m;
    case 8:
        for (unsigned i = 0; i < 8; i++)
            m |= (uint32_t)(valid[i] != 0) << i;
        return m;
    case 4:
        for (unsigned i = 0; i < 4; i++)
            m |= (uint32_t)(valid[i] != 0) << i;
        return m;
    default:
        for (unsigned i = 0; i < N && i < 32; i++)
            m |= (uint32_t)(valid[i] != 0) << i;
        return m;
    }
}

static unsigned active_lanes(const int *valid, unsigned N, unsigned lane[16])
{
    uint32_t m = valid_bits(valid, N);
    unsigned n = 0;
    for (unsigned i = 0; m; i++, m >>= 1) {
        lane[n] = i;
        n += m & 1;
    }
    return n;
}

/* The valid lanes packed into the narrowest cylray packet that holds them; unused
 * lanes repeat the first ray. */
#define CEB_GATHER(pk, base, N, lane, n, W)                                                    \
    do {                                                                                       \
        for (unsigned j = 0; j < (W); j++) {                                                   \
            unsigned i_ = (lane)[j < (n) ? j : 0];                                             \
            (pk).ox[j] = RF(base, N, R_OX, i_), (pk).oy[j] = RF(base, N, R_OY, i_);            \
            (pk).oz[j] = RF(base, N, R_OZ, i_), (pk).dx[j] = RF(base, N, R_DX, i_);            \
            (pk).dy[j] = RF(base, N, R_DY, i_), (pk).dz[j] = RF(base, N, R_DZ, i_);            \
            (pk).tmin[j] = RF(base, N, R_TNEAR, i_);                                           \
            (pk).tmax[j] = RF(base, N, R_TFAR, i_);                                            \
        }                                                                                      \
    } while (0)

/* The packet callbacks return the lanes (bits of Embree's lane index) they reported. */
#define CEB_SINGLE(W)                                                                          \
    static uint32_t isect##W(const struct RTCIntersectFunctionNArguments *a, const ceb *g,     \
                             uint32_t c, const unsigned *lane, unsigned n, int filt)           \
    {                                                                                          \
        cylray_ray##W ray;                                                                     \
        cylray_hit##W hit;                                                                     \
        CEB_GATHER(ray, a->rayhit, a->N, lane, n, W);                                          \
        uint32_t m = g->k->intersect##W(&g->prep[c], &ray, &hit, (uint32_t)((1ull << n) - 1),  \
                                        g->iflags);                                            \
        uint32_t got = 0;                                                                      \
        for (unsigned j = 0; m; j++, m >>= 1)                                                  \
            if (m & 1) {                                                                       \
                float nn[3] = {hit.nx[j], hit.ny[j], hit.nz[j]};                               \
                if (resolve_hit(g, a, filt, lane[j], c, hit.t[j], nn, hit.part[j]))            \
                    got |= 1u << lane[j];                                                      \
            }                                                                                  \
        return got;                                                                            \
    }                                                                                          \
    static uint32_t occ##W(const struct RTCOccludedFunctionNArguments *a, const ceb *g,        \
                           uint32_t c, const unsigned *lane, unsigned n, int filt)             \
    {                                                                                          \
        cylray_ray##W ray;                                                                     \
        CEB_GATHER(ray, a->ray, a->N, lane, n, W);                                             \
        uint32_t act = (uint32_t)((1ull << n) - 1), got = 0;                                   \
        if (!filt) {                                                                           \
            uint32_t m = g->k->occluded##W(&g->prep[c], &ray, act, g->oflags);                 \
            for (unsigned j = 0; m; j++, m >>= 1)                                              \
                if (m & 1) {                                                                   \
                    RF(a->ray, a->N, R_TFAR, lane[j]) = -INFINITY;                             \
                    got |= 1u << lane[j];                                                      \
                }                                                                              \
            return got;                                                                        \
        }                                                                                      \
        cylray_hit##W hit;                                                                     \
        uint32_t m = g->k->intersect##W(&g->prep[c], &ray, &hit, act, g->iflags);              \
        for (unsigned j = 0; m; j++, m >>= 1)                                                  \
            if (m & 1) {                                                                       \
                float nn[3] = {hit.nx[j], hit.ny[j], hit.nz[j]};                               \
                if (resolve_occ(g, a, filt, lane[j], c, hit.t[j], nn, hit.part[j]))            \
                    got |= 1u << lane[j];                                                      \
            }                                                                                  \
        return got;                                                                            \
    }
CEB_SINGLE(4)
CEB_SINGLE(8)
CEB_SINGLE(16)

/* The cylinder of primitive prim. Its frame, which only a hit reads, is fetched now, so
 * that the cache miss overlaps the intersection test rather than follow it: in a scene
 * larger than the caches that miss cost more than the test. */
static uint32_t cyl_of(const ceb *g, unsigned prim)
{
    uint32_t c = g->prim_cyl ? g->prim_cyl[prim] : prim;
    if (g->fr) { /* a sphere's u, v come from its normal alone */
        const char *f = (const char *)&g->fr[c];
        __builtin_prefetch(f);
        __builtin_prefetch(f + sizeof(frame) - 1);
    }
    return c;
}

/* A ray that starts outside sphere c, clearly (by 2^-13 R, far beyond the kernels'
 * tolerance band of a few ulps), and moves away from its center (w.d > 0 by a margin
 * far beyond the rounding of the dot product in double) never meets it at t >= 0: the
 * kernel would miss too. A secondary ray leaving a sphere, the most common call on a
 * sphere it has just hit, starts that way a few ulps off the surface, where the
 * kernel's own bounding-sphere rejection cannot end it early. */
static int sphere_behind(const ceb *g, uint32_t c, const float o[3], const float d[3],
                         float tmin)
{
    const cylray_sphere *s = &g->sphere_test[c];
    double w[3], wd = 0, ww = 0, dd = 0;
    for (int k = 0; k < 3; k++) {
        w[k] = (double)o[k] - s->center[k];
        wd += w[k] * d[k], ww += w[k] * w[k], dd += (double)d[k] * d[k];
    }
    double rr = (double)s->radius * s->radius;
    return tmin >= 0 && ww > rr * (1 + 0x1p-12) && wd > 0 && wd * wd > 0x1p-40 * ww * dd;
}

/* One valid lane, as Embree's hybrid traversal of incoherent packets calls: the ray is
 * broadcast, not gathered. */
static int isect1(const struct RTCIntersectFunctionNArguments *a, const ceb *g, uint32_t c,
                  unsigned i, int filt)
{
    float o[3], d[3], t, n[3];
    int32_t part;
    ray_of(a->rayhit, a->N, i, o, d);
    if (g->sphere_test && sphere_behind(g, c, o, d, RF(a->rayhit, a->N, R_TNEAR, i)))
        return 0;
    return one_ray(g, c, o, d, RF(a->rayhit, a->N, R_TNEAR, i), RF(a->rayhit, a->N, R_TFAR, i),
                   &t, n, &part) &&
           resolve_hit(g, a, filt, i, c, t, n, part);
}

static int occ1(const struct RTCOccludedFunctionNArguments *a, const ceb *g, uint32_t c,
                unsigned i, int filt)
{
    float o[3], d[3], t, n[3];
    int32_t part;
    ray_of(a->ray, a->N, i, o, d);
    float tmin = RF(a->ray, a->N, R_TNEAR, i), tmax = RF(a->ray, a->N, R_TFAR, i);
    if (g->sphere_test && sphere_behind(g, c, o, d, tmin))
        return 0;
    if (!filt) {
        cylray_ray4 r;
        for (int j = 0; j < 4; j++) {
            r.ox[j] = o[0], r.oy[j] = o[1], r.oz[j] = o[2];
            r.dx[j] = d[0], r.dy[j] = d[1], r.dz[j] = d[2];
            r.tmin[j] = tmin, r.tmax[j] = tmax;
        }
        if (!g->k->occluded4(&g->prep[c], &r, 0xFu, g->oflags))
            return 0;
        RF(a->ray, a->N, R_TFAR, i) = -INFINITY;
        return 1;
    }
    return one_ray(g, c, o, d, tmin, tmax, &t, n, &part) &&
           resolve_occ(g, a, filt, i, c, t, n, part);
}

/* Several valid lanes: the narrowest packet that holds them. Out of line, so that a
 * call for one ray (rtcIntersect1's, N = 1, and most of the hybrid traversal's) does
 * not set up the packets' frame or build a lane list. */
static CEB_NOINLINE uint32_t isect_n(const struct RTCIntersectFunctionNArguments *a,
                                     const ceb *g, uint32_t c, int filt)
{
    unsigned lane[16], n = active_lanes(a->valid, a->N, lane);
    if (n == 1)
        return (uint32_t)isect1(a, g, c, lane[0], filt) << lane[0];
    if (n > 1 && n <= 4)
        return isect4(a, g, c, lane, n, filt);
    if (n > 4 && n <= 8)
        return isect8(a, g, c, lane, n, filt);
    return n > 8 ? isect16(a, g, c, lane, n, filt) : 0;
}

static CEB_NOINLINE uint32_t occ_n(const struct RTCOccludedFunctionNArguments *a, const ceb *g,
                                   uint32_t c, int filt)
{
    unsigned lane[16], n = active_lanes(a->valid, a->N, lane);
    if (n == 1)
        return (uint32_t)occ1(a, g, c, lane[0], filt) << lane[0];
    if (n > 1 && n <= 4)
        return occ4(a, g, c, lane, n, filt);
    if (n > 4 && n <= 8)
        return occ8(a, g, c, lane, n, filt);
    return n > 8 ? occ16(a, g, c, lane, n, filt) : 0;
}

void ceb_single_intersect(const struct RTCIntersectFunctionNArguments *a)
{
    const ceb *g = a->geometryUserPtr;
    int filt = (g->options & CYLRAY_EMBREE_FILTER) || ceb_query_filter(a->context, g->options);
    uint32_t c = cyl_of(g, a->primID);
    if (a->N == 1) {
        if (a->valid[0])
            ceb_report(a->valid, 1, (uint32_t)isect1(a, g, c, 0, filt));
        return;
    }
    ceb_report(a->valid, a->N, isect_n(a, g, c, filt));
}

void ceb_single_occluded(const struct RTCOccludedFunctionNArguments *a)
{
    const ceb *g = a->geometryUserPtr;
    int filt = (g->options & CYLRAY_EMBREE_FILTER) || ceb_query_filter(a->context, g->options);
    uint32_t c = cyl_of(g, a->primID);
    if (a->N == 1) {
        if (a->valid[0])
            ceb_report(a->valid, 1, (uint32_t)occ1(a, g, c, 0, filt));
        return;
    }
    ceb_report(a->valid, a->N, occ_n(a, g, c, filt));
}
