/* SPDX-License-Identifier: MIT */
/* embree/rtc.h - Embree's API as the adapter uses it: the builder's header, the SoA ray
 * and hit layout the callbacks read and write, the query context, how a hit is offered
 * to the filter functions, and how a callback reports its lanes back.
 *
 * Everything in src/embree/ that depends on which Embree it is built against (3 or 4,
 * CYLRAY_EMBREE_RTC_MAJOR, from the generated cylray_embree_config.h) is here; the
 * other files name only what the two share (RTCBounds, the builder, the geometry and
 * callback-argument structs' common fields). The differences:
 *   context    RTCIntersectContext (3) / RTCRayQueryContext (4); a query's own filter
 *              is the context's `filter` on 3 and invisible to a callback on 4 (it is
 *              in RTCIntersectArguments / RTCOccludedArguments), so on 4 only the
 *              renderer's cylray_embree_context can carry it here
 *   filters    rtcFilterIntersection / rtcFilterOcclusion (3: the geometry's and the
 *              context's) / rtcInvokeIntersectFilterFromGeometry /
 *              rtcInvokeOccludedFilterFromGeometry (4: the geometry's only)
 *   hit        Embree 4 built with instance arrays adds instPrimID rows after instID
 *   valid      Embree 4 reads a callback's valid[] back: -1 where it reported a hit (or
 *              occlusion), 0 elsewhere; Embree 3 ignores it. */
#ifndef CYLRAY_EMBREE_RTC_H
#define CYLRAY_EMBREE_RTC_H

#define CYLRAY_EMBREE_BUILDING
#include "cylray_embree.h"

#if CYLRAY_EMBREE_RTC_MAJOR == 4
#include <embree4/rtcore_builder.h>
#else
#include <embree3/rtcore_builder.h>
#endif

#include <stddef.h>
#include <stdint.h>

/* ---- Embree's SoA ray and hit layout (rtcore_ray.h: RTCRayHitN, RTCHitN) --------- */

/* Ray fields: org x y z, tnear, dir x y z, time, tfar, mask, id, flags; then the hit:
 * Ng x y z, u, v, primID, geomID, instID[levels] (and on Embree 4 with instance arrays
 * instPrimID[levels]). Each is an array of N. The C++ accessors of rtcore_ray.h
 * (RTCRayN_org_x, ...) compute the same offsets. */
enum { R_OX, R_OY, R_OZ, R_TNEAR, R_DX, R_DY, R_DZ, R_TIME, R_TFAR, R_NFIELDS = 12 };
#if CYLRAY_EMBREE_RTC_MAJOR == 4 && defined(RTC_GEOMETRY_INSTANCE_ARRAY)
#define CEB_INST_PRIM 1
#else
#define CEB_INST_PRIM 0
#endif
enum {
    H_NGX,
    H_NGY,
    H_NGZ,
    H_U,
    H_V,
    H_PRIM,
    H_GEOM,
    H_INST,
    H_INST_PRIM = H_INST + RTC_MAX_INSTANCE_LEVEL_COUNT,
    H_NFIELDS = H_INST_PRIM + CEB_INST_PRIM * RTC_MAX_INSTANCE_LEVEL_COUNT
};
#define RF(base, N, field, i) (((float *)(base))[(size_t)(field) * (N) + (i)])
#define RU(base, N, field, i) (((unsigned *)(base))[(size_t)(field) * (N) + (i)])

/* ---- the query context ------------------------------------------------------------ */

#if CYLRAY_EMBREE_RTC_MAJOR == 4
typedef struct RTCRayQueryContext ceb_context;
#else
typedef struct RTCIntersectContext ceb_context;
#endif

/* The renderer's extended context, when the geometry was told that every query passes
 * one (CYLRAY_EMBREE_CONTEXT) and this one carries the tag cylray_embree_init_context
 * writes; NULL otherwise. */
static inline const cylray_embree_context *ceb_ext(const ceb_context *ctx, unsigned options)
{
    if (!(options & CYLRAY_EMBREE_CONTEXT) || !ctx)
        return NULL;
    const cylray_embree_context *x = (const cylray_embree_context *)(const void *)ctx;
    return x->tag == CYLRAY_EMBREE_CONTEXT_TAG ? x : NULL;
}

/* Whether a query needs its hits offered to a filter besides the geometry's: the
 * context's own (Embree 3) or the extended context's. */
static inline int ceb_query_filter(const ceb_context *ctx, unsigned options)
{
    const cylray_embree_context *x = ceb_ext(ctx, options);
#if CYLRAY_EMBREE_RTC_MAJOR == 4
    return x && x->filter;
#else
    return (ctx && ctx->filter) || (x && x->filter);
#endif
}

static inline unsigned ceb_inst_id(const ceb_context *ctx, unsigned level)
{
    return ctx->instID[level];
}

static inline unsigned ceb_inst_prim_id(const ceb_context *ctx, unsigned level)
{
#if CEB_INST_PRIM
    return ctx->instPrimID[level];
#else
    (void)ctx, (void)level;
    return RTC_INVALID_GEOMETRY_ID;
#endif
}

/* Offers the hit in f to the geometry's filter and the query's (Embree 3: the context's;
 * both: the extended context's), in Embree's order, stopping at a rejection. */
static inline void ceb_filter_intersection(const struct RTCIntersectFunctionNArguments *a,
                                           const struct RTCFilterFunctionNArguments *f,
                                           unsigned options, unsigned i)
{
#if CYLRAY_EMBREE_RTC_MAJOR == 4
    rtcInvokeIntersectFilterFromGeometry(a, f);
#else
    rtcFilterIntersection(a, f);
#endif
    const cylray_embree_context *x = ceb_ext(a->context, options);
    if (x && x->filter && f->valid[i])
        x->filter(f);
}

static inline void ceb_filter_occlusion(const struct RTCOccludedFunctionNArguments *a,
                                        const struct RTCFilterFunctionNArguments *f,
                                        unsigned options, unsigned i)
{
#if CYLRAY_EMBREE_RTC_MAJOR == 4
    rtcInvokeOccludedFilterFromGeometry(a, f);
#else
    rtcFilterOcclusion(a, f);
#endif
    const cylray_embree_context *x = ceb_ext(a->context, options);
    if (x && x->filter && f->valid[i])
        x->filter(f);
}

/* ---- what a callback reports through valid[] ------------------------------------- */

/* The lanes of valid[] (N of them, at most 32) that were valid on entry and are not in
 * `hit` become 0, those in `hit` -1: Embree 4's contract for intersect and occluded
 * callbacks. Embree 3 reads only the ray, so nothing is written there. */
static inline void ceb_report(int *valid, unsigned N, uint32_t hit)
{
#if CYLRAY_EMBREE_RTC_MAJOR == 4
    for (unsigned i = 0; i < N; i++)
        if (valid[i])
            valid[i] = (hit >> i & 1u) ? -1 : 0;
#else
    (void)valid, (void)N, (void)hit;
#endif
}

/* ---- the packet calls' query arguments (trace.c) --------------------------------- */

/* The query's own arguments as each version passes them to rtcIntersectN and
 * rtcOccludedN: Embree 3 a context (never NULL) whose flags may say coherent, Embree 4
 * optional arguments whose flags may say so. */
#if CYLRAY_EMBREE_RTC_MAJOR == 4
#define CEB_Q_PARAMS_I(rh_t) rh_t *rayhit, struct RTCIntersectArguments *args
#define CEB_Q_PARAMS_O(r_t) r_t *ray, struct RTCOccludedArguments *args
#define CEB_COHERENT(q) ((q) && ((q)->flags & RTC_RAY_QUERY_FLAG_COHERENT))
#define CEB_I_N(N, valid, scene, rh) rtcIntersect##N(valid, scene, rh, args)
#define CEB_O_N(N, valid, scene, r) rtcOccluded##N(valid, scene, r, args)
#define CEB_I_1(scene, rh) rtcIntersect1(scene, rh, args)
#define CEB_O_1(scene, r) rtcOccluded1(scene, r, args)
#define CEB_Q args
#else
#define CEB_Q_PARAMS_I(rh_t) struct RTCIntersectContext *context, rh_t *rayhit
#define CEB_Q_PARAMS_O(r_t) struct RTCIntersectContext *context, r_t *ray
#define CEB_COHERENT(q) (((q)->flags & RTC_INTERSECT_CONTEXT_FLAG_COHERENT) != 0)
#define CEB_I_N(N, valid, scene, rh) rtcIntersect##N(valid, scene, context, rh)
#define CEB_O_N(N, valid, scene, r) rtcOccluded##N(valid, scene, context, r)
#define CEB_I_1(scene, rh) rtcIntersect1(scene, context, rh)
#define CEB_O_1(scene, r) rtcOccluded1(scene, context, r)
#define CEB_Q context
#endif

#endif
