/* SPDX-License-Identifier: MIT */
/* exact.c - the scene-wide exact reference: Embree lists the candidate cylinders (boxes
 * only), the binary128 reference of tests/ref answers each, nearest box first. */
#include "exact.h"

#include "geom.h"
#include "quad.h"

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

/* ---- the exact sphere -------------------------------------------------------------- */

/* The first hit in [tmin, tmax] of the sphere of radius R about the origin, the ray
 * starting at w (o - c) in direction d; everything in binary128, where the products of
 * float inputs are exact, and the discriminant in Lagrange's form a R^2 - |w x d|^2,
 * free of the cancellation of b^2 - a c for a sphere far away. Part CYLRAY_SIDE, with
 * CYLRAY_BACKFACE for the exit point; n outward. */
static int sphere_exact(const cylq w[3], const cylq d[3], cylq R, cylq tmin, cylq tmax,
                        cylref_hit *h)
{
    memset(h, 0, sizeof *h);
    cylq a = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    cylq b = w[0] * d[0] + w[1] * d[1] + w[2] * d[2];
    cylq c = w[0] * w[0] + w[1] * w[1] + w[2] * w[2] - R * R;
    cylq x[3] = {w[1] * d[2] - w[2] * d[1], w[2] * d[0] - w[0] * d[2],
                 w[0] * d[1] - w[1] * d[0]};
    cylq disc = a * R * R - (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
    if (!(a > 0) || disc < 0)
        return 0;
    cylq sq = q_sqrt(disc), q = -(b + q_copysign(sq, b));
    cylq t1 = q / a, t2 = q != 0 ? c / q : t1;
    cylq t[2] = {q_min(t1, t2), q_max(t1, t2)};
    for (int k = 0; k < 2; k++) {
        if (!(t[k] >= tmin && t[k] <= tmax))
            continue;
        h->hit = 1;
        h->t = (double)t[k];
        h->part = CYLRAY_SIDE | (k ? CYLRAY_BACKFACE : 0);
        for (int j = 0; j < 3; j++)
            h->n[j] = (double)((w[j] + t[k] * d[j]) / R);
        return 1;
    }
    return 0;
}

static int sphere_intersect(const cylray_sphere *s, const float o[3], const float d[3],
                            float tmin, float tmax, cylref_hit *h)
{
    cylq w[3], dq[3];
    for (int k = 0; k < 3; k++)
        w[k] = (cylq)o[k] - (cylq)s->center[k], dq[k] = d[k];
    return sphere_exact(w, dq, s->radius, tmin, tmax, h);
}

int eb_shape_intersect(const eb_scene *s, uint32_t id, const float o[3], const float d[3],
                       float tmin, float tmax, cylref_hit *h)
{
    if (id & EB_SPHERE_BIT)
        return sphere_intersect(&s->sph[id & ~EB_SPHERE_BIT], o, d, tmin, tmax, h);
    return cylref_intersect(&s->cyl[id], o, d, tmin, tmax, 0, h) == 1;
}

static void band_add(cylref_band *b, const cylref_hit *x)
{
    if (!x->hit) {
        b->hit_unstable |= b->exact.hit;
        return;
    }
    if (!b->exact.hit) {
        b->hit_unstable = 1;
    } else if (x->part == b->exact.part) {
        b->t_lo = fmin(b->t_lo, x->t), b->t_hi = fmax(b->t_hi, x->t);
        return;
    }
    for (int i = 0; i < b->n_alt; i++)
        if (b->alt[i].part == x->part) {
            b->alt[i].t_lo = fmin(b->alt[i].t_lo, x->t);
            b->alt[i].t_hi = fmax(b->alt[i].t_hi, x->t);
            return;
        }
    if (b->n_alt < CYLREF_MAX_ALT)
        b->alt[b->n_alt++] = (cylref_alt){x->part, x->t, x->t};
}

void eb_shape_band(const eb_scene *s, uint32_t id, const float o[3], const float d[3],
                   float tmin, float tmax, cylref_band *b)
{
    if (!(id & EB_SPHERE_BIT)) {
        cylref_band_eval(&s->cyl[id], o, d, tmin, tmax, 0, b);
        return;
    }
    const cylray_sphere *sp = &s->sph[id & ~EB_SPHERE_BIT];
    memset(b, 0, sizeof *b);
    cylq w[3], dq[3], mw = 0, md = 0;
    for (int k = 0; k < 3; k++) {
        w[k] = (cylq)o[k] - (cylq)sp->center[k], dq[k] = d[k];
        mw = q_max(mw, q_abs(w[k])), md = q_max(md, q_abs(dq[k]));
    }
    sphere_exact(w, dq, sp->radius, tmin, tmax, &b->exact);
    b->t_lo = b->t_hi = b->exact.t;
    b->evals = 1;
    const cylq ew = 2 * (cylq)cylref_float_ulp((double)mw),
               ed = 2 * (cylq)cylref_float_ulp((double)md),
               er = 2 * (cylq)cylref_float_ulp(sp->radius);
    /* the inputs at fraction f of the way to vertex v */
#define AT(v, f, x)                                                                            \
    do {                                                                                       \
        cylq wv[3], dv[3];                                                                     \
        for (int k = 0; k < 3; k++) {                                                          \
            wv[k] = w[k] + (f) * ((v) >> k & 1 ? ew : -ew);                                    \
            dv[k] = dq[k] + (f) * ((v) >> (3 + k) & 1 ? ed : -ed);                             \
        }                                                                                      \
        sphere_exact(wv, dv, (cylq)sp->radius + (f) * ((v) >> 6 & 1 ? er : -er), tmin, tmax,   \
                     x);                                                                       \
    } while (0)
    uint8_t hits[128];
    for (unsigned v = 0; v < 128; v++, b->evals++) {
        cylref_hit x;
        AT(v, (cylq)1, &x);
        band_add(b, &x);
        hits[v] = (uint8_t)x.hit;
    }
    /* Where hit and miss both occur, t runs on inside the box up to where the hit
     * ends (a tangency, or an origin reaching the surface: t near 0), which no vertex
     * shows: bisect toward each vertex whose outcome differs for the last hit. */
    for (unsigned v = 0; b->hit_unstable && v < 128; v++) {
        if (hits[v] == b->exact.hit)
            continue;
        cylq lo = 0, hi = 1; /* lo: the exact outcome; hi: the vertex's */
        cylref_hit last = b->exact;
        for (int it = 0; it < 60; it++, b->evals++) {
            cylq mid = (lo + hi) * (cylq)0.5;
            cylref_hit x;
            AT(v, mid, &x);
            if (x.hit == b->exact.hit)
                lo = mid, last = x;
            else
                hi = mid;
        }
        band_add(b, &last);
    }
#undef AT
    b->part_unstable = b->n_alt > 0;
    b->decision_unstable = b->hit_unstable || b->part_unstable;
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
