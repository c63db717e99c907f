/* cylray_embree.h - cylray's cylinders, cones and spheres as an Embree 3 or Embree 4 geometry.
 * SPDX-License-Identifier: MIT
 *
 * An optional part of cylray, in its own library (cylray_embree; pkg-config
 * cylray_embree, CMake cylray::cylray_embree), built against the Embree the build found:
 * CYLRAY_EMBREE_RTC_MAJOR (3 or 4, from cylray_embree_config.h, installed beside this
 * header) says which, and that header includes Embree's own (embree3/rtcore.h or
 * embree4/rtcore.h). Including another major version of Embree's headers before this
 * one is an error. It turns the caller's cylinders into one RTCGeometry of Embree's user
 * type that a renderer attaches to its own scene next to its triangles and curves.
 * Embree's BVH finds the candidates; cylray's kernels answer them, and the hits land in
 * Embree's record as a curve's would:
 *
 *   tfar     the hit distance
 *   Ng       the unit outward normal of the surface hit (never flipped toward the ray)
 *   u        the axial coordinate: 0 at p0, 1 at p1 (0 or 1 on the end discs)
 *   v        the azimuth in [0, 1): atan2(r.b2, r.b1) / 2pi for the radial vector r of
 *            the hit point, (b1, b2) the orthonormal frame of Duff et al. (JCGT 2017)
 *            built from the unit axis p1 - p0
 *   primID   the cylinder's index in the caller's arrays
 *   geomID, instID   as Embree hands them to the geometry (instID copied from the
 *            query context); on Embree 4 built with instance arrays
 *            (RTC_GEOMETRY_INSTANCE_ARRAY), instPrimID likewise
 *
 * A miss writes nothing; an occluded ray gets tfar = -INFINITY. Rays are x(t) = o + t d
 * for t in [tnear, tfar]. On Embree 4 the callbacks also write valid[] back, -1 for a
 * lane they reported a hit (or occlusion) for and 0 for the others, as that version
 * asks of user geometry.
 *
 * Filter functions see each hit before it is accepted; when one is rejected, the next
 * hit of the same cylinder along the ray is offered, as Embree's curves do. Which
 * filters run:
 *   the geometry's    (rtcSetGeometryIntersectFilterFunction /
 *                     rtcSetGeometryOccludedFilterFunction) with CYLRAY_EMBREE_FILTER:
 *                     Embree 3 through rtcFilterIntersection / rtcFilterOcclusion,
 *                     Embree 4 through rtcInvokeIntersectFilterFromGeometry /
 *                     rtcInvokeOccludedFilterFromGeometry
 *   the query's       Embree 3: the context's (RTCIntersectContext.filter), always, as
 *                     rtcFilterIntersection calls it. Embree 4: the filter of
 *                     RTCIntersectArguments / RTCOccludedArguments is never seen by a
 *                     user geometry (Embree does not pass the arguments to its
 *                     callbacks; Embree's documentation advises a context struct of the
 *                     renderer's that begins with RTCRayQueryContext), so it comes in a
 *                     cylray_embree_context (below) as well, to a geometry made with
 *                     CYLRAY_EMBREE_CONTEXT, and is called after the geometry's, as
 *                     Embree calls an argument filter
 * cylray_embree_init_context puts a query's filter where each version looks for it, so
 * one renderer source serves both.
 * Each filter gets the whole ray packet with one lane valid, the hit in the hit record,
 * and the ray's tfar set to the hit's t while it runs.
 *
 * Embree 4 also starts geometries with mask 0x1 and tests ray masks (Embree 3 starts
 * them at 0xFFFFFFFF): a geometry made here keeps Embree's default, so there a ray
 * whose mask lacks bit 0 misses it; rtcSetGeometryMask sets another.
 *
 * The floating-point modes Embree asks renderers to set (flush-to-zero and
 * denormals-are-zero in MXCSR) are neither needed nor harmful here: the answers do not
 * depend on them, but for subnormal inputs, which denormals-are-zero reads as 0. */
#ifndef CYLRAY_EMBREE_H
#define CYLRAY_EMBREE_H

#include "cylray_embree_config.h"

#if !defined(RTC_VERSION_MAJOR) || RTC_VERSION_MAJOR != CYLRAY_EMBREE_RTC_MAJOR
#error "cylray_embree was built against another major version of Embree than the one included"
#endif

#include "cylray.h"

#ifdef __cplusplus
extern "C" {
#endif

#if defined(_WIN32) || defined(__CYGWIN__)
#if defined(CYLRAY_STATIC)
#define CYLRAY_EMBREE_API
#elif defined(CYLRAY_EMBREE_BUILDING)
#define CYLRAY_EMBREE_API __declspec(dllexport)
#else
#define CYLRAY_EMBREE_API __declspec(dllimport)
#endif
#elif defined(CYLRAY_EMBREE_BUILDING) && (defined(__GNUC__) || defined(__clang__))
#define CYLRAY_EMBREE_API __attribute__((visibility("default")))
#else
#define CYLRAY_EMBREE_API
#endif

/* cylray_embree_desc.options, OR'ed. */
/* Leaves: the cylinders are grouped by Embree's SAH builder into leaves of 8 (4 with
 * the SSE4.1 and scalar kernels), one user primitive a leaf, each answered
 * by one leaf query per ray. Without it, one cylinder (or one piece of a split one) is
 * one primitive, answered for
 * every valid ray of Embree's packet at once by cylray's packet kernels.
 * A leaf's box cannot be split, so a geometry with a shape that split boxes would cut
 * (longer than 16 radii and tilted) takes split boxes instead, as without this option
 * (cylray_embree_leaf_size then says 0); with CYLRAY_EMBREE_NO_SPLIT it is grouped into
 * leaves whatever its shapes. On AMD Zen 5 (Embree 3, AVX-512) leaves were as fast as
 * the default one ray a call on a dense molecule and lattice and slower elsewhere:
 * 1.1-1.6x its time one ray a call, 1.3-2.6x in packets of 8, and 5-18x on long tilted
 * rods, which therefore take split boxes (docs/performance.md). */
#define CYLRAY_EMBREE_LEAVES 0x1u
/* Split boxes, the default: a cylinder longer than 16 radii and tilted off the
 * coordinate axes gets several boxes along its axis instead of one (its single box
 * would be mostly empty and make Embree call the geometry for rays that pass far from
 * it): the slices of cylray_split_boxes, as many as its own rule (k = 0) gives. Each
 * hit is reported by the one box whose stretch of the axis holds it. A shorter
 * cylinder keeps one box: its pieces would cost more primitives and callbacks than its
 * box wastes (bonds 10 radii long: 4-6 % more time split; rods of 1e4 radii: 2.9x less).
 * CYLRAY_EMBREE_SPLIT asks for it by name; CYLRAY_EMBREE_NO_SPLIT gives every cylinder
 * one box (with CYLRAY_EMBREE_LEAVES: leaves whatever the shapes' length). */
#define CYLRAY_EMBREE_SPLIT 0x2u
#define CYLRAY_EMBREE_NO_SPLIT 0x10u
/* Filters: offer every hit to the geometry's filter functions (see the top of this
 * file). Embree does not tell a user geometry whether filter functions were set on it,
 * so say so here; without it only the query's filter, when there is one, is called,
 * and occlusion stops at the first hit without one. */
#define CYLRAY_EMBREE_FILTER 0x4u
/* Extended context: every query that can reach this geometry passes a
 * cylray_embree_context (initialised with cylray_embree_init_context) as its context,
 * whose filter the adapter then calls. Without it the adapter never reads past Embree's
 * own context struct. */
#define CYLRAY_EMBREE_CONTEXT 0x8u
/* No angles: a hit's angle around the axis, the one costly coordinate of a hit record
 * (written for every hit a query reports), is left out: v = 0 on a cylinder or cone
 * (u along p0 -> p1 stays; Embree's cone curves report the same), u = v = 0 on a
 * sphere. For a renderer that shades without textures. */
#define CYLRAY_EMBREE_NO_ANGLES 0x20u

/* The query context as Embree's version names it. */
#if CYLRAY_EMBREE_RTC_MAJOR >= 4
typedef struct RTCRayQueryContext cylray_embree_rtc_context;
#else
typedef struct RTCIntersectContext cylray_embree_rtc_context;
#endif

#define CYLRAY_EMBREE_CONTEXT_TAG 0x63796c63u /* "cylc" */

/* A context that carries what the callbacks need and Embree 4 does not hand them: the
 * query's filter (what a renderer sets as RTCIntersectArguments.filter /
 * RTCOccludedArguments.filter for its other geometries; NULL for none) and a pointer of
 * its own. Pass &ctx.rtc as the query's context (Embree 4: the arguments' context;
 * Embree 3: the context argument) and make the geometry with CYLRAY_EMBREE_CONTEXT; a
 * filter reaches user by casting its args->context back to cylray_embree_context. */
typedef struct cylray_embree_context {
    cylray_embree_rtc_context rtc; /* first: Embree hands this pointer to the callbacks */
    unsigned tag;                  /* CYLRAY_EMBREE_CONTEXT_TAG */
    RTCFilterFunctionN filter;     /* called by the adapter after the geometry's filter */
    void *user;
} cylray_embree_context;

/* Embree's own initialisation of ctx->rtc, the tag, user NULL, and the query's filter
 * where each version's queries look for it: Embree 4 in ctx->filter (the adapter calls
 * it; Embree's own geometries call the arguments' filter, which the renderer sets to
 * the same function with RTC_RAY_QUERY_FLAG_INVOKE_ARGUMENT_FILTER), Embree 3 in
 * ctx->rtc.filter, which Embree calls for every geometry, the adapter's included, and
 * ctx->filter NULL (set by hand, it would be called after that one). One renderer
 * source then serves both. */
static inline void cylray_embree_init_context(cylray_embree_context *ctx,
                                              RTCFilterFunctionN filter)
{
#if CYLRAY_EMBREE_RTC_MAJOR >= 4
    rtcInitRayQueryContext(&ctx->rtc);
    ctx->filter = filter;
#else
    rtcInitIntersectContext(&ctx->rtc);
    ctx->rtc.filter = filter;
    ctx->filter = 0;
#endif
    ctx->tag = CYLRAY_EMBREE_CONTEXT_TAG;
    ctx->user = 0;
}

/* The caller's cylinders in endpoint form: cylinder i runs from p0 to p1 with radius r
 * and the end discs caps says (CYLRAY_CAPPED_LO is the disc at p0), read from
 *   (const char *)p0 + i * p0_stride            three floats
 *   (const char *)p1 + i * p1_stride            three floats
 *   (const char *)radius + i * radius_stride    one float
 *   (const char *)caps + i * caps_stride        one unsigned (caps NULL: CYLRAY_CAPPED)
 * Strides are in bytes, so the fields of a renderer's own struct serve; a stride of 0
 * gives every cylinder the same value (one radius for all, say). The arrays are read
 * during cylray_embree_new_geometry only.
 *
 * Cones: with radius1 not NULL, primitive i is instead the truncated cone from the disc
 * of radius r0 = radius[i] at p0 to the disc of radius r1 at p1, r1 read from
 *   (const char *)radius1 + i * radius1_stride  one float
 * and prepared by cylray_prepare_cone (an end of radius 0 is a tip, its disc no
 * surface whatever caps says; a primitive with r0 == r1 is the cylinder of that radius,
 * as fast as one, and a leaf whose primitives all have r0 == r1 is a leaf of
 * cylinders). Everything below holds for cones as for cylinders: boxes (each the hull
 * of the cone's two discs), split boxes (a cone is split where the cylinder of its
 * larger radius is, each slice the hull of its two discs), leaves, the callbacks,
 * filters, masks, instancing, the hit record (u, v as for a cylinder; Ng the cone's
 * outward normal, tilted by its slope on the side), the hit point, surface and spawn
 * calls. radius1 NULL: the cylinders above, by the same code as without the field. */
typedef struct cylray_embree_desc {
    size_t count;
    const float *p0;
    size_t p0_stride;
    const float *p1;
    size_t p1_stride;
    const float *radius;
    size_t radius_stride;
    const unsigned *caps;
    size_t caps_stride;
    unsigned options;              /* CYLRAY_EMBREE_* */
    unsigned flags;                /* kernel flags: CYLRAY_CULL_BACK, CYLRAY_FAST,
                                     * CYLRAY_REFINE (normals are always computed) */
    const cylray_kernels *kernels; /* the path to call; NULL: cylray_kernels_best() */
    /* last, so that an initializer naming the fields above keeps its meaning */
    const float *radius1; /* the radius at p1 (cones); NULL: cylinders */
    size_t radius1_stride;
} cylray_embree_desc;

/* A new RTCGeometry on device holding desc's cylinders (or cones), not yet committed:
 * set what else the renderer sets (mask, filter functions), then rtcCommitGeometry and
 * rtcAttachGeometry. NULL when a cylinder is refused by the rules of
 * cylray_cylinder_from_endpoints (a cone: by those of cylray_prepare_cone), when count
 * is 0 or beyond 2^32 - 1 (or the split boxes would be), when an option or flag is
 * unknown (CYLRAY_FACE_FORWARD is: Ng is outward), when memory runs out or Embree
 * refuses; *status (when not NULL) says CYLRAY_EINVAL for the first three,
 * CYLRAY_ENOMEM when cylray's own allocations fail, and CYLRAY_OK when Embree
 * refused. */
CYLRAY_EMBREE_API RTCGeometry cylray_embree_new_geometry(RTCDevice device,
                                                         const cylray_embree_desc *desc,
                                                         cylray_status *status);

/* The caller's spheres: sphere i has its center and radius at
 *   (const char *)center + i * center_stride    three floats
 *   (const char *)radius + i * radius_stride    one float
 * strides in bytes as above (a stride of 0: one radius for all); read during
 * cylray_embree_new_spheres only. */
typedef struct cylray_embree_sphere_desc {
    size_t count;
    const float *center;
    size_t center_stride;
    const float *radius;
    size_t radius_stride;
    unsigned options;              /* CYLRAY_EMBREE_LEAVES, _FILTER, _CONTEXT; a sphere's
                                     * box is tight, so _SPLIT and _NO_SPLIT change nothing */
    unsigned flags;                /* as cylray_embree_desc.flags */
    const cylray_kernels *kernels; /* the path to call; NULL: cylray_kernels_best() */
} cylray_embree_sphere_desc;

/* A new RTCGeometry of spheres, as cylray_embree_new_geometry makes one of cylinders:
 * the same leaves, callbacks, filters, masks, instancing and Embree 3 / 4 behaviour
 * (the top of this file), and the same statuses (a sphere refused by the rules of
 * cylray_prepare_sphere: CYLRAY_EINVAL). Its hits fill Embree's record with
 *   tfar     the hit distance
 *   Ng       the unit outward normal (from the center to the hit point)
 *   u        phi / 2pi in [0, 1), phi = atan2(y, x) of the normal (pbrt-v4's full
 *            sphere, as cylray_surface gives it; within 4e-7 of it)
 *   v        1 - theta / pi: 0 at the -z pole, 1 at the +z pole (within 8e-7)
 *   primID   the sphere's index in the caller's arrays; geomID, instID as above
 * Every call below that takes "such a geometry" takes one of spheres too, its part then
 * CYLRAY_SIDE; cylray_embree_cylinder gives the prepared sphere. */
CYLRAY_EMBREE_API RTCGeometry cylray_embree_new_spheres(RTCDevice device,
                                                        const cylray_embree_sphere_desc *desc,
                                                        cylray_status *status);

/* Instead of rtcReleaseGeometry for such a geometry: drops the caller's reference and
 * frees cylray's data, which Embree (3 and 4) gives no way to tie to the geometry's own
 * end (a user geometry holds no buffers, and nothing is called when it goes).
 * rtcReleaseGeometry alone leaks that data.
 * Call it once no scene can trace the geometry any more (the scenes holding it
 * released, or it detached and those scenes committed again). NULL is ignored. */
CYLRAY_EMBREE_API void cylray_embree_release_geometry(RTCGeometry geometry);

/* 1 when geometry was made by cylray_embree_new_geometry (cylinders or cones), 0
 * otherwise. */
CYLRAY_EMBREE_API int cylray_embree_is_cylinders(RTCGeometry geometry);
/* 1 when geometry was made by cylray_embree_new_spheres, 0 otherwise. */
CYLRAY_EMBREE_API int cylray_embree_is_spheres(RTCGeometry geometry);

/* How many primitives Embree got from such a geometry: one per cylinder (or sphere),
 * per split box, or per leaf; 0 for another geometry. */
CYLRAY_EMBREE_API size_t cylray_embree_primitives(RTCGeometry geometry);

/* How many cylinders (or spheres) a leaf of such a geometry holds at most (made with
 * CYLRAY_EMBREE_LEAVES: 8 or 4, by the kernels' path); 0 without leaves or for another
 * geometry. */
CYLRAY_EMBREE_API unsigned cylray_embree_leaf_size(RTCGeometry geometry);

/* The prepared form of cylinder (or cone, or sphere) primID of such a geometry, for
 * cylray's own calls (cylray_hit_point, cylray_spawn_origin, the kernels); NULL when out
 * of range. */
CYLRAY_EMBREE_API const cylray_prepared *cylray_embree_cylinder(RTCGeometry geometry,
                                                                unsigned primID);

/* What a renderer asks about a hit on such a geometry (o, d the ray, t the tfar it came
 * back with, primID and Ng from its hit record). Embree's hit record has no field to
 * spare for the part hit; Ng says it (a disc's normal is the axis), and these read it
 * from there.
 *
 * The part: CYLRAY_SIDE, CYLRAY_CAP_LO (the disc at p0) or CYLRAY_CAP_HI; -1 when
 * primID is out of range, geometry is not such a geometry, or Ng is zero or not
 * finite. */
CYLRAY_EMBREE_API int cylray_embree_hit_part(RTCGeometry geometry, unsigned primID,
                                             const float Ng[3]);

/* The hit point p on that part, with *err (when err is not NULL) a bound on its distance
 * from the exact surface: cylray_hit_point_normal's, so the point keeps the normal's
 * azimuth where float t cannot place it (a ray from far away). 0, or -1 (nothing
 * written) as cylray_embree_hit_part. */
CYLRAY_EMBREE_API int cylray_embree_hit_point(RTCGeometry geometry, unsigned primID,
                                              const float o[3], const float d[3], float t,
                                              const float Ng[3], float p[3], float *err);

/* The surface at that hit point: cylray_surface's uv, dpdu and dpdv (see cylray.h; any
 * of p, uv, dpdu, dpdv may be NULL), and the point itself into p. Returns the part, or
 * -1 (nothing written) as cylray_embree_hit_part. The hit record's u and v are the same
 * coordinates (v from a faster azimuth, within 4e-7). */
CYLRAY_EMBREE_API int cylray_embree_surface(RTCGeometry geometry, unsigned primID,
                                            const float o[3], const float d[3], float t,
                                            const float Ng[3], float p[3], float uv[2],
                                            float dpdu[3], float dpdv[3]);

/* Secondary rays. For a hit on this geometry of the ray o + t d (t the tfar it came back
 * with, primID and Ng from its hit record): the origin of a new ray leaving that hit in
 * direction w, to be traced with tnear = 0. It never hits again the surface it leaves
 * there (at a rim, either surface), with the guarantee of cylray_spawn_origin. The ray
 * is needed because (u, v) do not place a hit on an end disc. Returns 0,
 * or -1 (out untouched) when primID is out of range or Ng is zero or not finite. */
CYLRAY_EMBREE_API int cylray_embree_spawn_origin(RTCGeometry geometry, unsigned primID,
                                                 const float o[3], const float d[3], float t,
                                                 const float Ng[3], const float w[3],
                                                 float out[3]);

/* The same with the side chosen by the renderer (cylray_spawn_origin_side): outward != 0
 * starts on the side Ng points to, 0 on the other, whatever w says; a renderer whose
 * shading decided reflection or transmission says which. */
CYLRAY_EMBREE_API int cylray_embree_spawn_origin_side(RTCGeometry geometry, unsigned primID,
                                                      const float o[3], const float d[3],
                                                      float t, const float Ng[3], int outward,
                                                      const float w[3], float out[3]);

/* The same for the hits of a packet as Embree left them (RTCRayHitN of N = 4, 8 or 16
 * lanes, after rtcIntersectN or cylray_embree_intersectN): for every lane i with
 * valid[i] whose hit is on this geometry (its geomID equals geomID, the ID this
 * geometry has in the scene traced) and whose tfar is finite, the origin for direction
 * (w[i], w[N + i], w[2N + i]) goes to (out[i], out[N + i], out[2N + i]), rows as in
 * Embree's SoA packets; other lanes of out are untouched. Returns the lanes written,
 * bit i for lane i. The _side form takes outward[i] per lane. */
CYLRAY_EMBREE_API uint32_t cylray_embree_spawn_origins(RTCGeometry geometry, unsigned geomID,
                                                       const int *valid,
                                                       const struct RTCRayHitN *rayhit,
                                                       unsigned N, const float *w, float *out);
CYLRAY_EMBREE_API uint32_t cylray_embree_spawn_origins_side(RTCGeometry geometry,
                                                            unsigned geomID, const int *valid,
                                                            const struct RTCRayHitN *rayhit,
                                                            unsigned N, const int *outward,
                                                            const float *w, float *out);

/* Packets through a scene that holds such a geometry, in place of rtcIntersect4/8/16 and
 * rtcOccluded4/8/16 (the same arguments in the same order as the Embree version's own
 * call, aligned as Embree requires: valid and the packet to 16, 32, 64 bytes for 4, 8,
 * 16 rays; same results): Embree's packet call where the packet is coherent (the
 * query's flags say so: Embree 3's context flags RTC_INTERSECT_CONTEXT_FLAG_COHERENT,
 * Embree 4's argument flags RTC_RAY_QUERY_FLAG_COHERENT; or at least three valid rays
 * share one direction octant), and otherwise rtcIntersect1 / rtcOccluded1 for each
 * valid ray with the same context (and arguments). Embree traverses user geometry in
 * packets without ever dropping to one ray at a time, so an incoherent packet would
 * cost more than its rays one a call. Filter functions run as with Embree's own calls
 * (with N = 1 for rays traced one a call). */
#if CYLRAY_EMBREE_RTC_MAJOR >= 4
CYLRAY_EMBREE_API void cylray_embree_intersect4(const int *valid, RTCScene scene,
                                                struct RTCRayHit4 *rayhit,
                                                struct RTCIntersectArguments *args);
CYLRAY_EMBREE_API void cylray_embree_intersect8(const int *valid, RTCScene scene,
                                                struct RTCRayHit8 *rayhit,
                                                struct RTCIntersectArguments *args);
CYLRAY_EMBREE_API void cylray_embree_intersect16(const int *valid, RTCScene scene,
                                                 struct RTCRayHit16 *rayhit,
                                                 struct RTCIntersectArguments *args);
CYLRAY_EMBREE_API void cylray_embree_occluded4(const int *valid, RTCScene scene,
                                               struct RTCRay4 *ray,
                                               struct RTCOccludedArguments *args);
CYLRAY_EMBREE_API void cylray_embree_occluded8(const int *valid, RTCScene scene,
                                               struct RTCRay8 *ray,
                                               struct RTCOccludedArguments *args);
CYLRAY_EMBREE_API void cylray_embree_occluded16(const int *valid, RTCScene scene,
                                                struct RTCRay16 *ray,
                                                struct RTCOccludedArguments *args);
#else
CYLRAY_EMBREE_API void cylray_embree_intersect4(const int *valid, RTCScene scene,
                                                struct RTCIntersectContext *context,
                                                struct RTCRayHit4 *rayhit);
CYLRAY_EMBREE_API void cylray_embree_intersect8(const int *valid, RTCScene scene,
                                                struct RTCIntersectContext *context,
                                                struct RTCRayHit8 *rayhit);
CYLRAY_EMBREE_API void cylray_embree_intersect16(const int *valid, RTCScene scene,
                                                 struct RTCIntersectContext *context,
                                                 struct RTCRayHit16 *rayhit);
CYLRAY_EMBREE_API void cylray_embree_occluded4(const int *valid, RTCScene scene,
                                               struct RTCIntersectContext *context,
                                               struct RTCRay4 *ray);
CYLRAY_EMBREE_API void cylray_embree_occluded8(const int *valid, RTCScene scene,
                                               struct RTCIntersectContext *context,
                                               struct RTCRay8 *ray);
CYLRAY_EMBREE_API void cylray_embree_occluded16(const int *valid, RTCScene scene,
                                                struct RTCIntersectContext *context,
                                                struct RTCRay16 *ray);
#endif

#ifdef __cplusplus
}
#endif

#endif /* CYLRAY_EMBREE_H */
