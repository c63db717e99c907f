/* SPDX-License-Identifier: MIT */
/* embree/rtc.h - Embree's API as the adapter uses it: the include, the version check,
 * the SoA ray and hit layout the callbacks read and write, the query context, and how
 * a hit is offered to the filter functions.
 *
 * Everything in src/embree/ that depends on which Embree it is built against is here;
 * the other files name only what Embree 3 and 4 share (RTCBounds, the builder, the
 * geometry and callback-argument structs' common fields). A port to Embree 4 stays a
 * small visible change of this file and of the include in cylray_embree.h: the
 * headers move to embree4/, RTCIntersectContext becomes RTCRayQueryContext (instID
 * stays), whether filters run is read from the query's RTCIntersectArguments /
 * RTCOccludedArguments rather than the context, and rtcFilterIntersection /
 * rtcFilterOcclusion become rtcInvokeIntersectFilterFromGeometry /
 * rtcInvokeOccludedFilterFromGeometry, which report through valid[] the same way. */
#ifndef CYLRAY_EMBREE_RTC_H
#define CYLRAY_EMBREE_RTC_H

#define CYLRAY_EMBREE_BUILDING
#include "cylray_embree.h"

#include <embree3/rtcore_builder.h>

#if !defined(RTC_VERSION_MAJOR) || RTC_VERSION_MAJOR != 3
#error "cylray_embree is written for Embree 3's API (RTC_VERSION_MAJOR == 3)"
#endif

#include <stddef.h>

/* ---- Embree's SoA ray and hit layout (rtcore_ray.h: RTCRayHitN, RTCHitN) --------- */

/* Ray fields: org x y z, tnear, dir x y z, time, tfar, mask, id, flags; then the hit:
 * Ng x y z, u, v, primID, geomID, instID[levels]. Each is an array of N. The C++
 * accessors of rtcore_ray.h (RTCRayN_org_x, ...) compute the same offsets. */
enum { R_OX, R_OY, R_OZ, R_TNEAR, R_DX, R_DY, R_DZ, R_TIME, R_TFAR, R_NFIELDS = 12 };
enum {
    H_NGX,
    H_NGY,
    H_NGZ,
    H_U,
    H_V,
    H_PRIM,
    H_GEOM,
    H_INST,
    H_NFIELDS = H_INST + RTC_MAX_INSTANCE_LEVEL_COUNT
};
#define RF(base, N, field, i) (((float *)(base))[(size_t)(field) * (N) + (i)])
#define RU(base, N, field, i) (((unsigned *)(base))[(size_t)(field) * (N) + (i)])

/* ---- the query context ------------------------------------------------------------ */

typedef struct RTCIntersectContext ceb_context;

/* Whether the query has a filter function of its own (a is the arguments of an
 * intersect or occluded callback). */
#define CEB_CONTEXT_FILTER(a) ((a)->context->filter != NULL)

static inline unsigned ceb_inst_id(const ceb_context *ctx, unsigned level)
{
    return ctx->instID[level];
}

/* Offers the hits of f to the geometry's and the context's filter functions. */
static inline void ceb_filter_intersection(const struct RTCIntersectFunctionNArguments *a,
                                           const struct RTCFilterFunctionNArguments *f)
{
    rtcFilterIntersection(a, f);
}

static inline void ceb_filter_occlusion(const struct RTCOccludedFunctionNArguments *a,
                                        const struct RTCFilterFunctionNArguments *f)
{
    rtcFilterOcclusion(a, f);
}

#endif
