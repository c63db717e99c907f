/* SPDX-License-Identifier: MIT */
/* embree/filter.c - a hit offered to the filter functions, as Embree's own geometries
 * offer theirs. */
#include "hit.h"

/* The arguments of a filter call offering hit h of lane i, as Embree's own geometries
 * make them: the whole packet with only lane i valid, the hit in hb, and the ray's tfar
 * set to the hit's t meanwhile (its old value returned, to put back on a rejection). */
static float offer(unsigned N, unsigned i, const hitrec *h, unsigned geomID,
                   const ceb_context *ctx, void *ray, int valid[16], float *hb)
{
    for (unsigned j = 0; j < N; j++)
        valid[j] = 0;
    valid[i] = -1;
    hit_fields(hb, N, i, h, geomID, ctx);
    const float old = RF(ray, N, R_TFAR, i);
    RF(ray, N, R_TFAR, i) = h->t;
    return old;
}

/* Offers hit h of lane i to the filter functions: 1 when accepted (the hit is then in
 * the record), 0 when rejected (tfar back). */
int ceb_filter_hit(const struct RTCIntersectFunctionNArguments *a, unsigned i, const hitrec *h)
{
    const unsigned N = a->N;
    _Alignas(64) float hb[H_NFIELDS * 16];
    _Alignas(64) int valid[16]; /* as Embree aligns a packet's mask */
    const float old = offer(N, i, h, a->geomID, a->context, a->rayhit, valid, hb);
    struct RTCFilterFunctionNArguments f = {valid,
                                            a->geometryUserPtr,
                                            a->context,
                                            (struct RTCRayN *)a->rayhit,
                                            (struct RTCHitN *)hb,
                                            N};
    ceb_filter_intersection(a, &f, ((const ceb *)a->geometryUserPtr)->options, i);
    if (!valid[i]) {
        RF(a->rayhit, N, R_TFAR, i) = old;
        return 0;
    }
    put_hit(a, i, h);
    return 1;
}

int ceb_filter_occ(const struct RTCOccludedFunctionNArguments *a, unsigned i, const hitrec *h)
{
    const unsigned N = a->N;
    _Alignas(64) float hb[H_NFIELDS * 16];
    _Alignas(64) int valid[16]; /* as Embree aligns a packet's mask */
    const float old = offer(N, i, h, a->geomID, a->context, a->ray, valid, hb);
    struct RTCFilterFunctionNArguments f = {valid,  a->geometryUserPtr,   a->context,
                                            a->ray, (struct RTCHitN *)hb, N};
    ceb_filter_occlusion(a, &f, ((const ceb *)a->geometryUserPtr)->options, i);
    if (!valid[i]) {
        RF(a->ray, N, R_TFAR, i) = old;
        return 0;
    }
    RF(a->ray, N, R_TFAR, i) = -INFINITY;
    return 1;
}
