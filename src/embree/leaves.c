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

/* With filters, a rejected hit lets the leaf be asked again beyond it: the next hit
 * of any of its cylinders (of the same cylinder too), so that every hit is offered in
 * order of t. */
#define CEB_LEAF(M)                                                                            \
    static void leaf_intersect##M(const struct RTCIntersectFunctionNArguments *a)              \
    {                                                                                          \
        const ceb *g = a->geometryUserPtr;                                                     \
        const cylray_leaf##M *leaf = (const cylray_leaf##M *)g->leaves + a->primID;            \
        int filt = (g->options & CYLRAY_EMBREE_FILTER) || CEB_CONTEXT_FILTER(a);               \
        for (unsigned i = 0; i < a->N; i++) {                                                  \
            if (!a->valid[i])                                                                  \
                continue;                                                                      \
            cylray_ray1 r;                                                                     \
            cylray_hit1 h;                                                                     \
            load_ray1(&r, a->rayhit, a->N, i);                                                 \
            for (int tries = 0; tries < 2 * (M) + 2; tries++) {                                \
                if (!g->k->leaf_intersect##M(leaf, &r, &h, g->iflags))                         \
                    break;                                                                     \
                hitrec hr = {h.t, {h.n[0], h.n[1], h.n[2]}, 0, 0, h.id};                       \
                hit_uv(&g->fr[h.id], r.o, r.d, h.t, h.part, h.n, &hr.u, &hr.v);                \
                if (!filt) {                                                                   \
                    put_hit(a, i, &hr);                                                        \
                    break;                                                                     \
                }                                                                              \
                if (ceb_filter_hit(a, i, &hr))                                                 \
                    break;                                                                     \
                r.tmin = nextafterf(h.t, INFINITY);                                            \
                r.tmax = RF(a->rayhit, a->N, R_TFAR, i);                                       \
            }                                                                                  \
        }                                                                                      \
    }                                                                                          \
    static void leaf_occluded##M(const struct RTCOccludedFunctionNArguments *a)                \
    {                                                                                          \
        const ceb *g = a->geometryUserPtr;                                                     \
        const cylray_leaf##M *leaf = (const cylray_leaf##M *)g->leaves + a->primID;            \
        int filt = (g->options & CYLRAY_EMBREE_FILTER) || CEB_CONTEXT_FILTER(a);               \
        for (unsigned i = 0; i < a->N; i++) {                                                  \
            if (!a->valid[i])                                                                  \
                continue;                                                                      \
            cylray_ray1 r;                                                                     \
            load_ray1(&r, a->ray, a->N, i);                                                    \
            if (!filt) {                                                                       \
                if (g->k->leaf_occluded##M(leaf, &r, g->oflags))                               \
                    RF(a->ray, a->N, R_TFAR, i) = -INFINITY;                                   \
                continue;                                                                      \
            }                                                                                  \
            cylray_hit1 h;                                                                     \
            for (int tries = 0; tries < 2 * (M) + 2; tries++) {                                \
                if (!g->k->leaf_intersect##M(leaf, &r, &h, g->iflags))                         \
                    break;                                                                     \
                hitrec hr = {h.t, {h.n[0], h.n[1], h.n[2]}, 0, 0, h.id};                       \
                hit_uv(&g->fr[h.id], r.o, r.d, h.t, h.part, h.n, &hr.u, &hr.v);                \
                if (ceb_filter_occ(a, i, &hr))                                                 \
                    break;                                                                     \
                r.tmin = nextafterf(h.t, INFINITY);                                            \
                r.tmax = RF(a->ray, a->N, R_TFAR, i);                                          \
            }                                                                                  \
        }                                                                                      \
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
