/* SPDX-License-Identifier: MIT */
/* embree/leaves.c - the callbacks of a geometry of leaves (CYLRAY_EMBREE_LEAVES): one
 * leaf query per valid ray. */
#include "hit.h"

/* ---- leaves: one leaf query per valid ray --------------------------------------- */

static void load_ray1(cylray_ray1 *r, const void *base, unsigned N, unsigned i)
{
    for (int k = 0; k < 3; k++) {
        r->o[k] = RF(base, N, R_OX + k, i);
        r->d[k] = RF(base, N, R_DX + k, i);
    }
    r->tmin = RF(base, N, R_TNEAR, i);
    r->tmax = RF(base, N, R_TFAR, i);
}

/* After a rejected hit at t: the rest of the ray, up to its current tfar. */
static void beyond(cylray_ray1 *r, float t, const void *base, unsigned N, unsigned i)
{
    r->tmin = nextafterf(t, INFINITY);
    r->tmax = RF(base, N, R_TFAR, i);
}

/* With filters, a rejected hit lets the leaf be asked again beyond it: the next hit
 * of any of its cylinders or spheres (of the same one too), so that every hit is offered
 * in order of t. A leaf of M holds at most 2 M hits along a ray. */
#define CEB_LEAF(M)                                                                            \
    static int next##M(const ceb *g, const cylray_leaf##M *leaf, cylray_ray1 *r, hitrec *hr)   \
    {                                                                                          \
        cylray_hit1 h;                                                                         \
        if (!g->k->leaf_intersect##M(leaf, r, &h, g->iflags))                                  \
            return 0;                                                                          \
        *hr = (hitrec){h.t, {h.n[0], h.n[1], h.n[2]}, 0, 0, h.id};                             \
        ceb_uv(g, h.id, r->o, r->d, h.t, h.part, h.n, &hr->u, &hr->v);                         \
        return 1;                                                                              \
    }                                                                                          \
    /* occ: a_ is an occlusion query's arguments, else an intersection's */                    \
    static void leaf_query##M(const void *a_, int occ)                                         \
    {                                                                                          \
        const struct RTCIntersectFunctionNArguments *ai = a_;                                  \
        const struct RTCOccludedFunctionNArguments *ao = a_;                                   \
        const ceb *g = occ ? ao->geometryUserPtr : ai->geometryUserPtr;                        \
        const unsigned N = occ ? ao->N : ai->N, prim = occ ? ao->primID : ai->primID;          \
        const int *valid = occ ? ao->valid : ai->valid;                                        \
        void *base = occ ? (void *)ao->ray : (void *)ai->rayhit;                               \
        const cylray_leaf##M *leaf = (const cylray_leaf##M *)g->leaves + prim;                 \
        int filt = (g->options & CYLRAY_EMBREE_FILTER) ||                                      \
                   ceb_query_filter(occ ? ao->context : ai->context, g->options);              \
        uint32_t got = 0; /* the lanes reported */                                             \
        for (unsigned i = 0; i < N; i++) {                                                     \
            if (!valid[i])                                                                     \
                continue;                                                                      \
            cylray_ray1 r;                                                                     \
            hitrec hr;                                                                         \
            load_ray1(&r, base, N, i);                                                         \
            if (occ && !filt) {                                                                \
                if (g->k->leaf_occluded##M(leaf, &r, g->oflags)) {                             \
                    RF(base, N, R_TFAR, i) = -INFINITY;                                        \
                    got |= 1u << i;                                                            \
                }                                                                              \
                continue;                                                                      \
            }                                                                                  \
            for (int tries = 0; tries < 2 * (M) + 2 && next##M(g, leaf, &r, &hr); tries++) {   \
                if (!occ && !filt) {                                                           \
                    put_hit(ai, i, &hr);                                                       \
                    got |= 1u << i;                                                            \
                    break;                                                                     \
                }                                                                              \
                if (occ ? ceb_filter_occ(ao, i, &hr) : ceb_filter_hit(ai, i, &hr)) {           \
                    got |= 1u << i;                                                            \
                    break;                                                                     \
                }                                                                              \
                beyond(&r, hr.t, base, N, i);                                                  \
            }                                                                                  \
        }                                                                                      \
        ceb_report(occ ? ao->valid : ai->valid, N, got);                                       \
    }                                                                                          \
    static void leaf_intersect##M(const struct RTCIntersectFunctionNArguments *a)              \
    {                                                                                          \
        leaf_query##M(a, 0);                                                                   \
    }                                                                                          \
    static void leaf_occluded##M(const struct RTCOccludedFunctionNArguments *a)                \
    {                                                                                          \
        leaf_query##M(a, 1);                                                                   \
    }
CEB_LEAF(4)
CEB_LEAF(8)

RTCIntersectFunctionN ceb_leaf_intersect(int m)
{
    return m == 4 ? leaf_intersect4 : leaf_intersect8;
}

RTCOccludedFunctionN ceb_leaf_occluded(int m)
{
    return m == 4 ? leaf_occluded4 : leaf_occluded8;
}
