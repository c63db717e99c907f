/* SPDX-License-Identifier: MIT */
/* query.h - one ray query as the Embree the adapter was built against takes it, set up
 * as a renderer on that version sets it up: the context (cylray_embree_context, which
 * the adapter reads only from geometries made with CYLRAY_EMBREE_CONTEXT), the query's
 * filter and whether its packets are coherent. Embree 3 carries both in the context;
 * Embree 4 in RTCIntersectArguments / RTCOccludedArguments, which a user geometry never
 * sees, so cylray_embree_init_context puts the filter into the extended context too. */
#ifndef EB_QUERY_H
#define EB_QUERY_H

#include <cylray_embree.h>

typedef struct eb_query {
    cylray_embree_context ctx;
#if CYLRAY_EMBREE_RTC_MAJOR >= 4
    struct RTCIntersectArguments iargs;
    struct RTCOccludedArguments oargs;
#endif
} eb_query;

/* filter: the query's filter function (NULL: none); coherent: the packets' hint. The
 * query must not move afterwards (the arguments point at its context). */
static inline void eb_query_init(eb_query *q, RTCFilterFunctionN filter, int coherent)
{
#if CYLRAY_EMBREE_RTC_MAJOR >= 4
    cylray_embree_init_context(&q->ctx, filter);
    rtcInitIntersectArguments(&q->iargs);
    rtcInitOccludedArguments(&q->oargs);
    const enum RTCRayQueryFlags f = (enum RTCRayQueryFlags)(
        (coherent ? RTC_RAY_QUERY_FLAG_COHERENT : RTC_RAY_QUERY_FLAG_INCOHERENT) |
        (filter ? RTC_RAY_QUERY_FLAG_INVOKE_ARGUMENT_FILTER : 0));
    q->iargs.flags = q->oargs.flags = f;
    q->iargs.context = q->oargs.context = &q->ctx.rtc;
    q->iargs.filter = q->oargs.filter = filter;
#else
    cylray_embree_init_context(&q->ctx, filter);
    q->ctx.rtc.flags =
        coherent ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
#endif
}

#if CYLRAY_EMBREE_RTC_MAJOR >= 4
#define EB_INTERSECT1(scene, q, rh) rtcIntersect1(scene, rh, &(q)->iargs)
#define EB_OCCLUDED1(scene, q, ray) rtcOccluded1(scene, ray, &(q)->oargs)
#define EB_INTERSECT_N(N, valid, scene, q, rh)                                                 \
    cylray_embree_intersect##N(valid, scene, rh, &(q)->iargs)
#define EB_OCCLUDED_N(N, valid, scene, q, ray)                                                 \
    cylray_embree_occluded##N(valid, scene, ray, &(q)->oargs)
#else
#define EB_INTERSECT1(scene, q, rh) rtcIntersect1(scene, &(q)->ctx.rtc, rh)
#define EB_OCCLUDED1(scene, q, ray) rtcOccluded1(scene, &(q)->ctx.rtc, ray)
#define EB_INTERSECT_N(N, valid, scene, q, rh)                                                 \
    cylray_embree_intersect##N(valid, scene, &(q)->ctx.rtc, rh)
#define EB_OCCLUDED_N(N, valid, scene, q, ray)                                                 \
    cylray_embree_occluded##N(valid, scene, &(q)->ctx.rtc, ray)
#endif

#endif
