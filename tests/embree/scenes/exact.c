/* SPDX-License-Identifier: MIT */
/* exact.c - the scene-wide exact reference: Embree lists the candidate cylinders, cones
 * and spheres (boxes only), the binary128 reference of tests/ref answers each (cylref,
 * conref, sphref), nearest box first. */
#include "exact.h"

#include "geom.h"
#include "conref.h"
#include "quad.h"
#include "sphref.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

typedef struct collect_ctx {
    cylray_embree_rtc_context ctx; /* first: Embree hands this pointer back */
    uint32_t *ids;
    size_t n, cap;
    int overflow;
} collect_ctx;

/* The collecting geometry's primitive i: the segments, then the spheres. */
static uint32_t collect_id(const eb_scene *s, unsigned i)
{
    return i < s->ns ? i : EB_SPHERE_BIT | (uint32_t)(i - s->ns);
}

static void collect_bounds(const struct RTCBoundsFunctionArguments *a)
{
    const eb_scene *s = a->geometryUserPtr;
    eb_shape_bounds(s, collect_id(s, a->primID), a->bounds_o);
}

static void collect_isect(const struct RTCIntersectFunctionNArguments *a)
{
    collect_ctx *c = (collect_ctx *)a->context;
    if (!a->valid[0])
        return;
    a->valid[0] = 0; /* no hit: the traversal goes on (Embree 4 reads valid back) */
    if (c->n == c->cap) {
        size_t cap = c->cap ? 2 * c->cap : 256;
        uint32_t *p = realloc(c->ids, cap * sizeof *p);
        if (!p) {
            c->overflow = 1;
            return;
        }
        c->ids = p, c->cap = cap;
    }
    c->ids[c->n++] = collect_id(a->geometryUserPtr, a->primID);
}

int eb_shape_intersect(const eb_scene *s, uint32_t id, const float o[3], const float d[3],
                       float tmin, float tmax, cylref_hit *h)
{
    if (id & EB_SPHERE_BIT)
        return sphref_intersect(&s->sph[id & ~EB_SPHERE_BIT], o, d, tmin, tmax, 0, h) == 1;
    if (s->cone)
        return conref_intersect(&s->cone[id], o, d, tmin, tmax, 0, h) == 1;
    return cylref_intersect(&s->cyl[id], o, d, tmin, tmax, 0, h) == 1;
}

void eb_shape_band(const eb_scene *s, uint32_t id, const float o[3], const float d[3],
                   float tmin, float tmax, cylref_band *b)
{
    if (id & EB_SPHERE_BIT)
        sphref_band_eval(&s->sph[id & ~EB_SPHERE_BIT], o, d, tmin, tmax, 0, b);
    else if (s->cone)
        conref_band_eval(&s->cone[id], o, d, tmin, tmax, 0, b);
    else
        cylref_band_eval(&s->cyl[id], o, d, tmin, tmax, 0, b);
}

int eb_ref_init(eb_ref *r, RTCDevice dev, const eb_scene *s)
{
    r->s = s;
    RTCGeometry geo = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_USER);
    rtcSetGeometryUserPrimitiveCount(geo, (unsigned)(s->ns + s->nsph));
    rtcSetGeometryUserData(geo, (void *)s);
    rtcSetGeometryBoundsFunction(geo, collect_bounds, NULL);
    rtcSetGeometryIntersectFunction(geo, collect_isect);
    rtcCommitGeometry(geo);
    r->collect = rtcNewScene(dev);
    rtcAttachGeometry(r->collect, geo);
    rtcReleaseGeometry(geo);
    rtcCommitScene(r->collect);
    return rtcGetDeviceError(dev) == RTC_ERROR_NONE ? 0 : -1;
}

void eb_ref_free(eb_ref *r)
{
    if (r->collect)
        rtcReleaseScene(r->collect);
    memset(r, 0, sizeof *r);
}

/* Where the ray enters box b, in double (or INFINITY). */
static double box_entry(const struct RTCBounds *b, const float o[3], const float d[3])
{
    const float lo[3] = {b->lower_x, b->lower_y, b->lower_z};
    const float hi[3] = {b->upper_x, b->upper_y, b->upper_z};
    double t0 = -INFINITY, t1 = INFINITY;
    for (int k = 0; k < 3; k++) {
        if (d[k] == 0) {
            if (o[k] < lo[k] || o[k] > hi[k])
                return INFINITY;
            continue;
        }
        double a = ((double)lo[k] - o[k]) / d[k], c = ((double)hi[k] - o[k]) / d[k];
        t0 = fmax(t0, fmin(a, c));
        t1 = fmin(t1, fmax(a, c));
    }
    return t0 <= t1 ? t0 : INFINITY;
}

typedef struct cand {
    double t;
    uint32_t id;
} cand;

static int by_t(const void *pa, const void *pb)
{
    const cand *a = pa, *b = pb;
    return a->t < b->t ? -1 : a->t > b->t ? 1 : (a->id > b->id) - (a->id < b->id);
}

int eb_ref_closest(const eb_ref *r, const float o[3], const float d[3], float tmin, float tmax,
                   uint32_t *id, cylref_hit *h)
{
    collect_ctx c;
    memset(&c, 0, sizeof c);
    struct RTCRayHit rh = eb_rayhit1(o, d, tmin, tmax);
#if CYLRAY_EMBREE_RTC_MAJOR >= 4
    rtcInitRayQueryContext(&c.ctx);
    struct RTCIntersectArguments args;
    rtcInitIntersectArguments(&args);
    args.context = &c.ctx;
    rtcIntersect1(r->collect, &rh, &args);
#else
    rtcInitIntersectContext(&c.ctx);
    rtcIntersect1(r->collect, &c.ctx, &rh);
#endif
    cand *cs = malloc((c.n ? c.n : 1) * sizeof *cs);
    int found = 0;
    if (cs) {
        for (size_t i = 0; i < c.n; i++) {
            struct RTCBounds b;
            eb_shape_bounds(r->s, c.ids[i], &b);
            cs[i].t = box_entry(&b, o, d);
            cs[i].id = c.ids[i];
        }
        qsort(cs, c.n, sizeof *cs, by_t);
        for (size_t i = 0; i < c.n; i++) {
            /* boxes are padded, so a box entered beyond the best hit holds no nearer one */
            if (found && cs[i].t > h->t)
                break;
            cylref_hit x;
            if (eb_shape_intersect(r->s, cs[i].id, o, d, tmin, tmax, &x) == 1 &&
                (!found || x.t < h->t || (x.t == h->t && cs[i].id < *id))) {
                *h = x;
                *id = cs[i].id;
                found = 1;
            }
        }
    }
    free(cs);
    free(c.ids);
    return found;
}
