/* SPDX-License-Identifier: MIT */
/* agree.h - what the adapter's tests of every shape share (test_agree.c: cylinders and
 * cones, test_spheres.c: spheres beside cylinders, test_cones.c: the rest of the cones):
 * the filter rule and its filter, the query's filter that offers every hit, the camera
 * rays with their left-out and shortened ones, the scenes of one geometry and the shifted
 * instance. A shape's test describes its shapes in an eb_shapes and keeps only what is
 * its own. */
#ifndef EB_AGREE_H
#define EB_AGREE_H

#include "geom.h"
#include "judge.h"
#include "trace.h"

#include <stddef.h>
#include <stdint.h>

/* A test's shapes, as the shared checks walk them. */
typedef struct eb_shapes {
    size_t (*count)(void);
    uint32_t (*id_of)(size_t k); /* shape k as an answer's id (eb_hit_id) */
    /* every hit of shape k on the ray in [tmin, tmax], in order of t, by the path the
     * variant under test uses */
    int (*all_hits)(size_t k, const float o[3], const float d[3], float tmin, float tmax,
                    float t[4], float n[4][3]);
    size_t offer_step; /* eb_offer_all: every offer_step-th camera ray */
} eb_shapes;

/* The filter rule of the tests: front faces of shapes with an even primID are rejected
 * (a transparency that lets rays in but not out, say), so a ray that meets one first
 * must be given that shape's next hit, or another shape's. */
int eb_rejected(uint32_t prim, const float n[3], const float d[3]);

/* The geometry's filter (and the query's), for intersection and occlusion alike. */
void eb_rule_filter(const struct RTCFilterFunctionNArguments *a);

/* Every hit of every shape on the ray offered to the query's filter once, none twice,
 * and the query then reports a miss (intersection) or not occluded (occlusion). Returns
 * the rays where that fails. */
int eb_offer_all(const eb_shapes *sh, const char *what, RTCScene scene, const eb_rays *r);

/* g committed, alone in a new committed scene; *id (where id is not NULL) its geomID. */
RTCScene eb_scene_of(RTCDevice dev, RTCGeometry g, unsigned *id);

/* inner instanced with a shift of (3, 0, 0), every mask bit set, in a committed scene of
 * its own as geometry *iid (RTC_INVALID_GEOMETRY_ID: the first free one, *iid then set
 * to it), so that a record saying 0 is told apart where *iid is not 0. */
RTCScene eb_shifted(RTCDevice dev, RTCScene inner, unsigned *iid);

/* One ray through scene with the given mask: the hit's geomID, primID, t and Ng. */
void eb_trace_mask(RTCScene scene, const float o[3], const float d[3], unsigned mask,
                   struct RTCRayHit *rh);

/* Embree's own rtcIntersect8 on rays b to b + 7 of r from t = 0, every mask bit set,
 * lane `off` left out (valid[] says which lanes were traced), so that the packet forms
 * after it meet a lane Embree did not write. */
void eb_intersect8(RTCScene sc, const eb_rays *r, size_t b, int off, int valid[8],
                   struct RTCRayHit8 *rh);

/* The checks of ray i that need no hit record, the start of every test's check: an
 * invalid lane must be left as it was (1: the lane is one, no more to check), an
 * occlusion answer must say occluded exactly where want, the test's own answer, is a
 * hit and leave tfar alone where not. Each disagreement is counted in *bad and the
 * first five printed. */
int eb_skipped_lane(const char *what, const eb_rays *r, size_t i, const float *tfar0,
                    const uint8_t *valid0, int *bad);
void eb_occlusion(const char *what, const eb_rays *r, size_t i, const float *tfar0,
                  uint32_t want, int *bad);

/* A shape's own checks on the exact reference's answers (eb_exact_secondary): on an
 * exact hit of prim (geometry geo, answer id) at t with normal ng, and on each secondary
 * ray w spawned from it at org, after it is judged. Each counts its disagreements in
 * *bad and prints the first three; NULL: none. */
typedef struct eb_exact_checks {
    void (*hit)(int *bad, const char *what, RTCGeometry geo, unsigned prim, uint32_t id,
                const eb_sample *x, float t, const float ng[3]);
    void (*secondary)(int *bad, const char *what, RTCGeometry geo, unsigned prim,
                      const eb_sample *x, float t, const float ng[3], const float w[3],
                      const float org[3]);
} eb_exact_checks;

/* Each camera ray solved exactly and traced through g's scene, the answer judged into
 * e; from each exact hit a reflection and a refraction-like continuation spawned at the
 * adapter's origin, traced and judged as secondary rays, and the shape's checks c made.
 * Returns the disagreements beside e's: c's, and spawn origins refused or not finite
 * (such a ray is not traced: Embree's debug builds assert on it). */
int eb_exact_secondary(eb_err *e, const char *what, const eb_geom *g, const eb_ref *ref,
                       const eb_rays *cam, const eb_exact_checks *c);

/* A test's answers for eb_check_answers: want, its brute force's first hit on the ray
 * from tmin to tmax (its id, RTC_INVALID_GEOMETRY_ID for none; *t and n), with the
 * filter rule where filtered; hit_ok, 1 when the hit got (an id) that ray i of r records
 * agrees with want's at t with normal n. */
typedef struct eb_answers {
    uint32_t (*want)(const float o[3], const float d[3], float tmin, float tmax, int filtered,
                     float *t, float n[3]);
    int (*hit_ok)(const eb_rays *r, size_t i, const float o[3], const float d[3], uint32_t got,
                  uint32_t want, float t, const float n[3]);
} eb_answers;

/* Each answer in r against a's: invalid lanes untouched (eb_skipped_lane), occlusion
 * where a hit is wanted (eb_occlusion), a miss where none is, with tfar left alone, and
 * otherwise a hit that a->hit_ok accepts. Returns the disagreements; prints the first
 * five. */
int eb_check_answers(const char *what, const eb_rays *r, const float *tfar0,
                     const uint8_t *valid0, int occ, int filtered, const eb_answers *a);

/* A test's camera for the packet passes: its scene and image size, how it turns its rays
 * incoherent, and its check of the answers in r against its own brute force (returns
 * the disagreements). */
typedef struct eb_passes {
    const eb_scene *scene;
    int w, h;
    void (*mix)(eb_rays *r);
    int (*check)(const char *what, const eb_rays *r, const float *tfar0, const uint8_t *valid0,
                 int occ, int filtered);
} eb_passes;

/* Every packet size (1, 4, 8, 16), intersect and occluded, on the camera rays and on
 * the incoherent ones, through qf as the query's filter where not NULL: each pass's
 * answers held to p->check, a line printed for it and it counted in *passed or
 * *failed. */
void eb_packet_passes(const eb_passes *p, RTCScene sc, const char *vn, int filtered,
                      RTCFilterFunctionN qf, eb_rays *r, float *tfar0, uint8_t *valid0,
                      int *passed, int *failed);

/* Camera rays of s, every seventh left out, and a finite tmax on a third so that some
 * hits lie beyond it; tfar0 and valid0 keep the inputs. */
void eb_agree_rays(eb_rays *r, const eb_scene *s, int w, int h, float *tfar0, uint8_t *valid0);

#endif
