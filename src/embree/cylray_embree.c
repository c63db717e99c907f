/* SPDX-License-Identifier: MIT */
/* cylray_embree.c - cylray's cylinders as an Embree 3 user geometry: the bounds Embree
 * builds its BVH over, the callbacks through which its traversal asks cylray's kernels,
 * the filter protocol, and the secondary-ray helper.
 *
 * Every line that depends on Embree's API is in this file. Embree 4 renamed the
 * include directory, replaced RTCIntersectContext by RTCRayQueryContext and the
 * arguments' context by a ray query context plus RTCIntersectArguments, and reports
 * filter results through args->valid the same way; a port changes this file (and the
 * include in cylray_embree.h), nothing else. */
#define CYLRAY_EMBREE_BUILDING
#include "cylray_embree.h"

#include <embree3/rtcore_builder.h>

#if !defined(RTC_VERSION_MAJOR) || RTC_VERSION_MAJOR != 3
#error "cylray_embree is written for Embree 3's API (RTC_VERSION_MAJOR == 3)"
#endif

#include <math.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* ---- Embree's SoA ray and hit layout (rtcore_ray.h: RTCRayHitN, RTCHitN) --------- */

/* Ray fields: org x y z, tnear, dir x y z, time, tfar, mask, id, flags; then the hit:
 * Ng x y z, u, v, primID, geomID, instID[levels]. Each is an array of N. The C++
 * accessors of rtcore_ray.h (RTCRayN_org_x, ...) compute the same offsets. */
enum { R_OX, R_OY, R_OZ, R_TNEAR, R_DX, R_DY, R_DZ, R_TIME, R_TFAR, R_NFIELDS = 12 };
enum { H_NGX, H_NGY, H_NGZ, H_U, H_V, H_PRIM, H_GEOM, H_INST,
       H_NFIELDS = H_INST + RTC_MAX_INSTANCE_LEVEL_COUNT };
#define RF(base, N, field, i) (((float *)(base))[(size_t)(field) * (N) + (i)])
#define RU(base, N, field, i) (((unsigned *)(base))[(size_t)(field) * (N) + (i)])

#define CEB_MAGIC 0x63656232u /* "ceb2" */
#define CEB_KFLAGS (CYLRAY_CULL_BACK | CYLRAY_FAST | CYLRAY_REFINE)
#define CEB_OPTIONS (CYLRAY_EMBREE_LEAVES | CYLRAY_EMBREE_SPLIT | CYLRAY_EMBREE_FILTER)
#define CEB_MAX_PIECES 1024u

/* Per cylinder, what a hit record needs beyond the prepared cylinder: the endpoint
 * form for u, the unit axis and the frame of Duff et al. for v. */
typedef struct frame {
    float p0[3], a[3]; /* p0 and p1 - p0 */
    float inv_aa;      /* 1 / |a|^2 */
    float n[3];        /* the unit axis */
    float b1[3], b2[3];
    uint32_t pieces;   /* split boxes along the axis (1: one box) */
} frame;

typedef struct ceb {
    uint32_t magic;
    const cylray_kernels *k;
    unsigned options, iflags, oflags; /* intersect and occluded kernel flags */
    size_t n;                         /* cylinders */
    cylray_prepared *prep;            /* n */
    frame *fr;                        /* n */
    size_t nprim;                     /* Embree's primitives */
    uint32_t *prim_cyl;               /* split: primitive -> cylinder */
    uint32_t *prim_piece;             /* split: primitive -> its piece of that cylinder */
    struct RTCBounds *box;            /* one per primitive */
    void *leaves;                     /* leaves: cylray_leafM[nprim] */
    int m;                            /* 4, 8 or 16 */
    RTCGeometry geom;
} ceb;

/* ---- geometry of one cylinder -------------------------------------------------- */

static void frame_init(frame *f, const float p0[3], const float p1[3])
{
    double a[3], aa = 0;
    for (int k = 0; k < 3; k++) {
        f->p0[k] = p0[k];
        a[k] = (double)p1[k] - p0[k];
        f->a[k] = (float)a[k];
        aa += a[k] * a[k];
    }
    f->inv_aa = (float)(1.0 / aa);
    double l = sqrt(aa), n[3] = {a[0] / l, a[1] / l, a[2] / l};
    /* Duff et al., "Building an Orthonormal Basis, Revisited" (JCGT 2017) */
    double s = n[2] >= 0 ? 1.0 : -1.0, q = -1.0 / (s + n[2]), b = n[0] * n[1] * q;
    double b1[3] = {1.0 + s * n[0] * n[0] * q, s * b, -s * n[0]};
    double b2[3] = {b, s + n[1] * n[1] * q, -n[1]};
    for (int k = 0; k < 3; k++) {
        f->n[k] = (float)n[k];
        f->b1[k] = (float)b1[k];
        f->b2[k] = (float)b2[k];
    }
    f->pieces = 1;
}

static void set_box(struct RTCBounds *b, const float lo[3], const float hi[3], float pad)
{
    b->lower_x = lo[0] - pad, b->lower_y = lo[1] - pad, b->lower_z = lo[2] - pad;
    b->upper_x = hi[0] + pad, b->upper_y = hi[1] + pad, b->upper_z = hi[2] + pad;
    b->align0 = b->align1 = 0;
}

/* The box of the whole cylinder: cylray_bounds, the exact box rounded outward. */
static void whole_box(const cylray_prepared *p, struct RTCBounds *b)
{
    float lo[3], hi[3];
    cylray_bounds(p, lo, hi);
    set_box(b, lo, hi, 0);
}

/* How many boxes a cylinder gets with CYLRAY_EMBREE_SPLIT: its single box is wider
 * than the cylinder by about L sin(theta) across, theta the angle from the nearest
 * coordinate axis; pieces of a length whose lateral spread is about 8 radii keep each
 * box within a few diameters of its stretch of the cylinder, while short or
 * axis-aligned cylinders keep one box (more boxes only mean more calls there). */
static uint32_t pieces_for(const frame *f, float R)
{
    double aa = 0, mx = 0;
    for (int k = 0; k < 3; k++) {
        double c = (double)f->a[k] * f->a[k];
        aa += c;
        mx = fmax(mx, c);
    }
    double L = sqrt(aa), lat = sqrt(fmax(0.0, 1 - mx / aa));
    double k = floor(L * lat / (8.0 * R));
    return k < 1 ? 1u : k > CEB_MAX_PIECES ? CEB_MAX_PIECES : (uint32_t)k;
}

/* The axial coordinate of the point o + t d on cylinder f: 0 at p0, 1 at p1, clamped;
 * the end discs give 0 and 1 exactly. */
static float axial_u(const frame *f, const float o[3], const float d[3], float t, int part)
{
    part &= CYLRAY_PART_MASK;
    if (part == CYLRAY_CAP_LO)
        return 0.0f;
    if (part == CYLRAY_CAP_HI)
        return 1.0f;
    double s = 0;
    for (int k = 0; k < 3; k++)
        s += ((double)o[k] + (double)t * d[k] - f->p0[k]) * f->a[k];
    s *= f->inv_aa;
    return s <= 0 ? 0.0f : s >= 1 ? 1.0f : (float)s;
}

/* atan2(y, x) / 2pi in [0, 1). Every hit a query reports is written with its v, most of
 * them overwritten by a closer one, and libm's atan2f cost as much as the intersection
 * test: a polynomial for atan on [0, 1] (absolute error below 3e-6 rad, 4e-7 in v)
 * with the octant folded in serves. */
static float turns(float y, float x)
{
    float ax = fabsf(x), ay = fabsf(y), mx = fmaxf(ax, ay), mn = fminf(ax, ay);
    if (mx == 0)
        return 0.0f;
    float a = mn / mx, s = a * a;
    float r = a * (0.99997726f +
                   s * (-0.33262347f +
                        s * (0.19354346f + s * (-0.11643287f + s * (0.05265332f +
                                                                    s * -0.01172120f)))));
    const float half_pi = 1.57079632679489662f, pi = 3.14159265358979324f;
    if (ay > ax)
        r = half_pi - r;
    if (x < 0)
        r = pi - r;
    if (y < 0)
        r = -r;
    float v = r * (float)(0.5 / 3.14159265358979323846);
    if (v < 0)
        v += 1.0f;
    return v >= 1.0f ? 0.0f : v;
}

/* The azimuth in [0, 1) of the radial vector r in the frame (b1, b2). */
static float azimuth_v(const frame *f, const float r[3])
{
    float x = r[0] * f->b1[0] + r[1] * f->b1[1] + r[2] * f->b1[2];
    float y = r[0] * f->b2[0] + r[1] * f->b2[1] + r[2] * f->b2[2];
    return turns(y, x);
}

/* u and v of a hit: on the side the outward normal is the radial direction; on a disc
 * the radial vector comes from the hit point. */
static void hit_uv(const frame *f, const float o[3], const float d[3], float t, int part,
                   const float n[3], float *u, float *v)
{
    *u = axial_u(f, o, d, t, part);
    if ((part & CYLRAY_PART_MASK) == CYLRAY_SIDE) {
        *v = azimuth_v(f, n);
        return;
    }
    double q[3], s = 0;
    for (int k = 0; k < 3; k++) {
        q[k] = (double)o[k] + (double)t * d[k] - f->p0[k];
        s += q[k] * f->n[k];
    }
    float r[3];
    for (int k = 0; k < 3; k++)
        r[k] = (float)(q[k] - s * f->n[k]);
    *v = azimuth_v(f, r);
}

/* ---- one ray against one cylinder, for the rarer paths ------------------------- */

/* The first hit of one ray on cylinder c in [tmin, tmax] through the 4-wide kernel,
 * the ray repeated in every lane (the lanes stay valid numbers, never stack garbage,
 * whose subnormals would cost microcode assists). */
static int one_ray(const ceb *g, uint32_t c, const float o[3], const float d[3], float tmin,
                   float tmax, float *t, float n[3], int32_t *part)
{
    cylray_ray4 r;
    cylray_hit4 h;
    for (int j = 0; j < 4; j++) {
        r.ox[j] = o[0], r.oy[j] = o[1], r.oz[j] = o[2];
        r.dx[j] = d[0], r.dy[j] = d[1], r.dz[j] = d[2];
        r.tmin[j] = tmin, r.tmax[j] = tmax;
    }
    if (!g->k->intersect4(&g->prep[c], &r, &h, 1u, g->iflags))
        return 0;
    *t = h.t[0];
    n[0] = h.nx[0], n[1] = h.ny[0], n[2] = h.nz[0];
    *part = h.part[0];
    return 1;
}

/* Does this hit belong to primitive prim? With split boxes each hit is reported by the
 * one piece whose stretch of the axis holds its u; the pieces' boxes are padded by more
 * than u's rounding, so that piece's box holds the hit point. */
static int owns(const ceb *g, unsigned prim, uint32_t c, float u)
{
    if (!g->prim_piece)
        return 1;
    uint32_t K = g->fr[c].pieces;
    if (K == 1)
        return 1;
    float x = u * (float)K;
    uint32_t piece = x <= 0 ? 0 : x >= (float)(K - 1) ? K - 1 : (uint32_t)x;
    return piece == g->prim_piece[prim];
}

/* ---- writing hits --------------------------------------------------------------- */

typedef struct hitrec {
    float t, n[3], u, v;
    unsigned prim;
} hitrec;

static void put_hit(const struct RTCIntersectFunctionNArguments *a, unsigned i,
                    const hitrec *h)
{
    void *rh = a->rayhit;
    unsigned N = a->N;
    float *hb = (float *)rh + R_NFIELDS * N;
    RF(rh, N, R_TFAR, i) = h->t;
    RF(hb, N, H_NGX, i) = h->n[0];
    RF(hb, N, H_NGY, i) = h->n[1];
    RF(hb, N, H_NGZ, i) = h->n[2];
    RF(hb, N, H_U, i) = h->u;
    RF(hb, N, H_V, i) = h->v;
    RU(hb, N, H_PRIM, i) = h->prim;
    RU(hb, N, H_GEOM, i) = a->geomID;
    for (unsigned l = 0; l < RTC_MAX_INSTANCE_LEVEL_COUNT; l++)
        RU(hb, N, H_INST + l, i) = a->context->instID[l];
}

/* The arguments of a filter call offering hit h of lane i, as Embree's own geometries
 * make them: the whole packet with only lane i valid, the hit in hb, and the ray's tfar
 * set to the hit's t meanwhile (its old value returned, to put back on a rejection). */
static float offer(unsigned N, unsigned i, const hitrec *h, unsigned geomID,
                   const struct RTCIntersectContext *ctx, void *ray, int valid[16], float *hb)
{
    for (unsigned j = 0; j < N; j++)
        valid[j] = 0;
    valid[i] = -1;
    RF(hb, N, H_NGX, i) = h->n[0];
    RF(hb, N, H_NGY, i) = h->n[1];
    RF(hb, N, H_NGZ, i) = h->n[2];
    RF(hb, N, H_U, i) = h->u;
    RF(hb, N, H_V, i) = h->v;
    RU(hb, N, H_PRIM, i) = h->prim;
    RU(hb, N, H_GEOM, i) = geomID;
    for (unsigned l = 0; l < RTC_MAX_INSTANCE_LEVEL_COUNT; l++)
        RU(hb, N, H_INST + l, i) = ctx->instID[l];
    const float old = RF(ray, N, R_TFAR, i);
    RF(ray, N, R_TFAR, i) = h->t;
    return old;
}

/* Offers hit h of lane i to the filter functions: 1 when accepted (the hit is then in
 * the record), 0 when rejected (tfar back). */
static int filter_hit(const struct RTCIntersectFunctionNArguments *a, unsigned i,
                      const hitrec *h)
{
    const unsigned N = a->N;
    float hb[H_NFIELDS * 16];
    int valid[16];
    const float old = offer(N, i, h, a->geomID, a->context, a->rayhit, valid, hb);
    struct RTCFilterFunctionNArguments f = {valid, a->geometryUserPtr, a->context,
                                            (struct RTCRayN *)a->rayhit,
                                            (struct RTCHitN *)hb, N};
    rtcFilterIntersection(a, &f);
    if (!valid[i]) {
        RF(a->rayhit, N, R_TFAR, i) = old;
        return 0;
    }
    put_hit(a, i, h);
    return 1;
}

static int filter_occ(const struct RTCOccludedFunctionNArguments *a, unsigned i,
                      const hitrec *h)
{
    const unsigned N = a->N;
    float hb[H_NFIELDS * 16];
    int valid[16];
    const float old = offer(N, i, h, a->geomID, a->context, a->ray, valid, hb);
    struct RTCFilterFunctionNArguments f = {valid, a->geometryUserPtr, a->context,
                                            a->ray, (struct RTCHitN *)hb, N};
    rtcFilterOcclusion(a, &f);
    if (!valid[i]) {
        RF(a->ray, N, R_TFAR, i) = old;
        return 0;
    }
    RF(a->ray, N, R_TFAR, i) = -INFINITY;
    return 1;
}

static void ray_of(const void *base, unsigned N, unsigned i, float o[3], float d[3])
{
    for (int k = 0; k < 3; k++) {
        o[k] = RF(base, N, R_OX + k, i);
        d[k] = RF(base, N, R_DX + k, i);
    }
}

/* A hit the kernel found for lane i on cylinder c: reported when primitive prim owns
 * it and the filters (when called) accept it; otherwise the next hit of c along the
 * ray is tried, until one is reported or there is none. occ: an occlusion query. */
static void resolve(const ceb *g, const void *a_, int occ, int filt, unsigned i, uint32_t c,
                    float t, float n[3], int32_t part)
{
    const struct RTCIntersectFunctionNArguments *ai = a_;
    const struct RTCOccludedFunctionNArguments *ao = a_;
    unsigned prim = occ ? ao->primID : ai->primID, N = occ ? ao->N : ai->N;
    const void *base = occ ? (const void *)ao->ray : (const void *)ai->rayhit;
    float o[3], d[3];
    ray_of(base, N, i, o, d);
    /* a cylinder has at most two hits along a ray; the bound only guards the loop */
    for (int tries = 0; tries < 8; tries++) {
        hitrec h = {t, {n[0], n[1], n[2]}, 0, 0, (unsigned)c};
        hit_uv(&g->fr[c], o, d, t, part, n, &h.u, &h.v);
        if (owns(g, prim, c, h.u)) {
            if (occ ? (filt ? filter_occ(ao, i, &h)
                            : (RF(ao->ray, N, R_TFAR, i) = -INFINITY, 1))
                    : (filt ? filter_hit(ai, i, &h) : (put_hit(ai, i, &h), 1)))
                return;
        }
        float tmax = RF(base, N, R_TFAR, i);
        if (!one_ray(g, c, o, d, nextafterf(t, INFINITY), tmax, &t, n, &part))
            return;
    }
}

/* ---- one cylinder a primitive: cylray's packet kernels ------------------------- */

/* The valid lanes, in order. Embree's hybrid traversal of incoherent packets calls with
 * N = 8 or 16 and one valid lane more often than not: the mask is built without a
 * branch per lane (a loop of constant length the compiler vectorises), and only the
 * valid lanes are visited. */
static uint32_t valid_bits(const int *valid, unsigned N)
{
    uint32_t m = 0;
    switch (N) {
    case 16:
        for (unsigned i = 0; i < 16; i++)
            m |= (uint32_t)(valid[i] != 0) << i;
        return m;
    case 8:
        for (unsigned i = 0; i < 8; i++)
            m |= (uint32_t)(valid[i] != 0) << i;
        return m;
    case 4:
        for (unsigned i = 0; i < 4; i++)
            m |= (uint32_t)(valid[i] != 0) << i;
        return m;
    default:
        for (unsigned i = 0; i < N && i < 32; i++)
            m |= (uint32_t)(valid[i] != 0) << i;
        return m;
    }
}

static unsigned active_lanes(const int *valid, unsigned N, unsigned lane[16])
{
    uint32_t m = valid_bits(valid, N);
    unsigned n = 0;
    for (unsigned i = 0; m; i++, m >>= 1) {
        lane[n] = i;
        n += m & 1;
    }
    return n;
}

/* The valid lanes packed into the narrowest cylray packet that holds them; unused
 * lanes repeat the first ray. */
#define CEB_GATHER(pk, base, N, lane, n, W)                                                \
    do {                                                                                   \
        for (unsigned j = 0; j < (W); j++) {                                               \
            unsigned i_ = (lane)[j < (n) ? j : 0];                                         \
            (pk).ox[j] = RF(base, N, R_OX, i_), (pk).oy[j] = RF(base, N, R_OY, i_);        \
            (pk).oz[j] = RF(base, N, R_OZ, i_), (pk).dx[j] = RF(base, N, R_DX, i_);        \
            (pk).dy[j] = RF(base, N, R_DY, i_), (pk).dz[j] = RF(base, N, R_DZ, i_);        \
            (pk).tmin[j] = RF(base, N, R_TNEAR, i_);                                       \
            (pk).tmax[j] = RF(base, N, R_TFAR, i_);                                        \
        }                                                                                  \
    } while (0)

#define CEB_SINGLE(W)                                                                      \
    static void isect##W(const struct RTCIntersectFunctionNArguments *a, const ceb *g,     \
                         uint32_t c, const unsigned *lane, unsigned n, int filt)           \
    {                                                                                      \
        cylray_ray##W ray;                                                                 \
        cylray_hit##W hit;                                                                 \
        CEB_GATHER(ray, a->rayhit, a->N, lane, n, W);                                      \
        uint32_t m = g->k->intersect##W(&g->prep[c], &ray, &hit,                           \
                                        (uint32_t)((1ull << n) - 1), g->iflags);           \
        for (unsigned j = 0; m; j++, m >>= 1)                                              \
            if (m & 1) {                                                                   \
                float nn[3] = {hit.nx[j], hit.ny[j], hit.nz[j]};                           \
                resolve(g, a, 0, filt, lane[j], c, hit.t[j], nn, hit.part[j]);             \
            }                                                                              \
    }                                                                                      \
    static void occ##W(const struct RTCOccludedFunctionNArguments *a, const ceb *g,        \
                       uint32_t c, const unsigned *lane, unsigned n, int filt)             \
    {                                                                                      \
        cylray_ray##W ray;                                                                 \
        CEB_GATHER(ray, a->ray, a->N, lane, n, W);                                         \
        uint32_t act = (uint32_t)((1ull << n) - 1);                                        \
        if (!filt) {                                                                       \
            uint32_t m = g->k->occluded##W(&g->prep[c], &ray, act, g->oflags);             \
            for (unsigned j = 0; m; j++, m >>= 1)                                          \
                if (m & 1)                                                                 \
                    RF(a->ray, a->N, R_TFAR, lane[j]) = -INFINITY;                         \
            return;                                                                        \
        }                                                                                  \
        cylray_hit##W hit;                                                                 \
        uint32_t m = g->k->intersect##W(&g->prep[c], &ray, &hit, act, g->iflags);          \
        for (unsigned j = 0; m; j++, m >>= 1)                                              \
            if (m & 1) {                                                                   \
                float nn[3] = {hit.nx[j], hit.ny[j], hit.nz[j]};                           \
                resolve(g, a, 1, filt, lane[j], c, hit.t[j], nn, hit.part[j]);             \
            }                                                                              \
    }
CEB_SINGLE(4)
CEB_SINGLE(8)
CEB_SINGLE(16)

static uint32_t cyl_of(const ceb *g, unsigned prim)
{
    return g->prim_cyl ? g->prim_cyl[prim] : prim;
}

/* One valid lane, as Embree's hybrid traversal of incoherent packets calls: the ray is
 * broadcast, not gathered. */
static void isect1(const struct RTCIntersectFunctionNArguments *a, const ceb *g, uint32_t c,
                   unsigned i, int filt)
{
    float o[3], d[3], t, n[3];
    int32_t part;
    ray_of(a->rayhit, a->N, i, o, d);
    if (one_ray(g, c, o, d, RF(a->rayhit, a->N, R_TNEAR, i), RF(a->rayhit, a->N, R_TFAR, i),
                &t, n, &part))
        resolve(g, a, 0, filt, i, c, t, n, part);
}

static void occ1(const struct RTCOccludedFunctionNArguments *a, const ceb *g, uint32_t c,
                 unsigned i, int filt)
{
    float o[3], d[3], t, n[3];
    int32_t part;
    ray_of(a->ray, a->N, i, o, d);
    float tmin = RF(a->ray, a->N, R_TNEAR, i), tmax = RF(a->ray, a->N, R_TFAR, i);
    if (!filt) {
        cylray_ray4 r;
        for (int j = 0; j < 4; j++) {
            r.ox[j] = o[0], r.oy[j] = o[1], r.oz[j] = o[2];
            r.dx[j] = d[0], r.dy[j] = d[1], r.dz[j] = d[2];
            r.tmin[j] = tmin, r.tmax[j] = tmax;
        }
        if (g->k->occluded4(&g->prep[c], &r, 1u, g->oflags))
            RF(a->ray, a->N, R_TFAR, i) = -INFINITY;
        return;
    }
    if (one_ray(g, c, o, d, tmin, tmax, &t, n, &part))
        resolve(g, a, 1, filt, i, c, t, n, part);
}

static void single_intersect(const struct RTCIntersectFunctionNArguments *a)
{
    const ceb *g = a->geometryUserPtr;
    unsigned lane[16], n = active_lanes(a->valid, a->N, lane);
    int filt = (g->options & CYLRAY_EMBREE_FILTER) || a->context->filter;
    uint32_t c = cyl_of(g, a->primID);
    if (n == 0)
        return;
    if (n == 1)
        isect1(a, g, c, lane[0], filt);
    else if (n <= 4)
        isect4(a, g, c, lane, n, filt);
    else if (n <= 8)
        isect8(a, g, c, lane, n, filt);
    else
        isect16(a, g, c, lane, n, filt);
}

static void single_occluded(const struct RTCOccludedFunctionNArguments *a)
{
    const ceb *g = a->geometryUserPtr;
    unsigned lane[16], n = active_lanes(a->valid, a->N, lane);
    int filt = (g->options & CYLRAY_EMBREE_FILTER) || a->context->filter;
    uint32_t c = cyl_of(g, a->primID);
    if (n == 0)
        return;
    if (n == 1)
        occ1(a, g, c, lane[0], filt);
    else if (n <= 4)
        occ4(a, g, c, lane, n, filt);
    else if (n <= 8)
        occ8(a, g, c, lane, n, filt);
    else
        occ16(a, g, c, lane, n, filt);
}

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
#define CEB_LEAF(M)                                                                        \
    static void leaf_intersect##M(const struct RTCIntersectFunctionNArguments *a)          \
    {                                                                                      \
        const ceb *g = a->geometryUserPtr;                                                 \
        const cylray_leaf##M *leaf = (const cylray_leaf##M *)g->leaves + a->primID;        \
        int filt = (g->options & CYLRAY_EMBREE_FILTER) || a->context->filter;              \
        for (unsigned i = 0; i < a->N; i++) {                                              \
            if (!a->valid[i])                                                              \
                continue;                                                                  \
            cylray_ray1 r;                                                                 \
            cylray_hit1 h;                                                                 \
            load_ray1(&r, a->rayhit, a->N, i);                                             \
            for (int tries = 0; tries < 2 * (M) + 2; tries++) {                            \
                if (!g->k->leaf_intersect##M(leaf, &r, &h, g->iflags))                     \
                    break;                                                                 \
                hitrec hr = {h.t, {h.n[0], h.n[1], h.n[2]}, 0, 0, h.id};                   \
                hit_uv(&g->fr[h.id], r.o, r.d, h.t, h.part, h.n, &hr.u, &hr.v);            \
                if (!filt) {                                                               \
                    put_hit(a, i, &hr);                                                    \
                    break;                                                                 \
                }                                                                          \
                if (filter_hit(a, i, &hr))                                                 \
                    break;                                                                 \
                r.tmin = nextafterf(h.t, INFINITY);                                        \
                r.tmax = RF(a->rayhit, a->N, R_TFAR, i);                                   \
            }                                                                              \
        }                                                                                  \
    }                                                                                      \
    static void leaf_occluded##M(const struct RTCOccludedFunctionNArguments *a)            \
    {                                                                                      \
        const ceb *g = a->geometryUserPtr;                                                 \
        const cylray_leaf##M *leaf = (const cylray_leaf##M *)g->leaves + a->primID;        \
        int filt = (g->options & CYLRAY_EMBREE_FILTER) || a->context->filter;              \
        for (unsigned i = 0; i < a->N; i++) {                                              \
            if (!a->valid[i])                                                              \
                continue;                                                                  \
            cylray_ray1 r;                                                                 \
            load_ray1(&r, a->ray, a->N, i);                                                \
            if (!filt) {                                                                   \
                if (g->k->leaf_occluded##M(leaf, &r, g->oflags))                           \
                    RF(a->ray, a->N, R_TFAR, i) = -INFINITY;                               \
                continue;                                                                  \
            }                                                                              \
            cylray_hit1 h;                                                                 \
            for (int tries = 0; tries < 2 * (M) + 2; tries++) {                            \
                if (!g->k->leaf_intersect##M(leaf, &r, &h, g->iflags))                     \
                    break;                                                                 \
                hitrec hr = {h.t, {h.n[0], h.n[1], h.n[2]}, 0, 0, h.id};                   \
                hit_uv(&g->fr[h.id], r.o, r.d, h.t, h.part, h.n, &hr.u, &hr.v);            \
                if (filter_occ(a, i, &hr))                                                 \
                    break;                                                                 \
                r.tmin = nextafterf(h.t, INFINITY);                                        \
                r.tmax = RF(a->ray, a->N, R_TFAR, i);                                      \
            }                                                                              \
        }                                                                                  \
    }
CEB_LEAF(4)
CEB_LEAF(8)
CEB_LEAF(16)

static void prim_bounds(const struct RTCBoundsFunctionArguments *a)
{
    const ceb *g = a->geometryUserPtr;
    *a->bounds_o = g->box[a->primID];
}

/* ---- grouping into leaves with Embree's SAH builder ----------------------------- */

/* Leaf l holds the cylinders order[first[l] .. first[l] + count[l]). rtcBuildBVH runs
 * its callbacks on several threads: a leaf takes its slots with atomic counters. */
typedef struct sah_ctx {
    uint32_t *order;
    size_t *first, *count;
    atomic_size_t used, leaves;
} sah_ctx;

static void *sah_node(RTCThreadLocalAllocator al, unsigned n, void *u)
{
    (void)n, (void)u;
    return rtcThreadLocalAlloc(al, 16, 16);
}

static void sah_children(void *node, void **c, unsigned n, void *u)
{
    (void)node, (void)c, (void)n, (void)u;
}

static void sah_bounds(void *node, const struct RTCBounds **b, unsigned n, void *u)
{
    (void)node, (void)b, (void)n, (void)u;
}

static void *sah_leaf(RTCThreadLocalAllocator al, const struct RTCBuildPrimitive *p, size_t n,
                      void *u)
{
    sah_ctx *c = u;
    size_t at = atomic_fetch_add(&c->used, n), l = atomic_fetch_add(&c->leaves, 1);
    for (size_t i = 0; i < n; i++)
        c->order[at + i] = p[i].primID;
    c->first[l] = at;
    c->count[l] = n;
    return rtcThreadLocalAlloc(al, 16, 16);
}

static void *alloc_aligned(size_t bytes)
{
    size_t b = (bytes + 63) / 64 * 64;
    return aligned_alloc(64, b ? b : 64);
}

static void box_union(struct RTCBounds *u, const struct RTCBounds *b)
{
    u->lower_x = fminf(u->lower_x, b->lower_x), u->upper_x = fmaxf(u->upper_x, b->upper_x);
    u->lower_y = fminf(u->lower_y, b->lower_y), u->upper_y = fmaxf(u->upper_y, b->upper_y);
    u->lower_z = fminf(u->lower_z, b->lower_z), u->upper_z = fmaxf(u->upper_z, b->upper_z);
}

#define CEB_LEAF_BUILD(M)                                                                  \
    static int build_leaves##M(ceb *g, const cylray_cylinder *cyl, const sah_ctx *c)       \
    {                                                                                      \
        cylray_leaf##M *lv = alloc_aligned(g->nprim * sizeof *lv);                         \
        if (!lv)                                                                           \
            return -1;                                                                     \
        g->leaves = lv;                                                                    \
        for (size_t l = 0; l < g->nprim; l++) {                                            \
            const uint32_t *ids = c->order + c->first[l];                                  \
            cylray_cylinder cc[M];                                                         \
            for (size_t j = 0; j < c->count[l]; j++)                                       \
                cc[j] = cyl[ids[j]];                                                       \
            if (cylray_leaf_prepare##M(&lv[l], cc, ids, c->count[l]) != CYLRAY_OK)         \
                return -1;                                                                 \
        }                                                                                  \
        return 0;                                                                          \
    }
CEB_LEAF_BUILD(4)
CEB_LEAF_BUILD(8)
CEB_LEAF_BUILD(16)

static int group_leaves(ceb *g, RTCDevice dev, const cylray_cylinder *cyl)
{
    int M = g->m, bad = -1;
    size_t n = g->n;
    struct RTCBuildPrimitive *prims = alloc_aligned(n * sizeof *prims);
    sah_ctx c = {.order = malloc(n * sizeof *c.order),
                 .first = malloc(n * sizeof *c.first),
                 .count = malloc(n * sizeof *c.count)};
    atomic_init(&c.used, 0);
    atomic_init(&c.leaves, 0);
    if (prims && c.order && c.first && c.count) {
        for (size_t i = 0; i < n; i++) {
            struct RTCBounds b;
            whole_box(&g->prep[i], &b);
            prims[i] = (struct RTCBuildPrimitive){b.lower_x, b.lower_y, b.lower_z, 0,
                                                  b.upper_x, b.upper_y, b.upper_z, (unsigned)i};
        }
        RTCBVH bvh = rtcNewBVH(dev);
        struct RTCBuildArguments a = rtcDefaultBuildArguments();
        a.buildQuality = RTC_BUILD_QUALITY_MEDIUM;
        a.maxDepth = 64;
        /* a leaf is one vector test whether it holds 1 or M: split only above M */
        a.minLeafSize = (unsigned)M;
        a.maxLeafSize = (unsigned)M;
        a.bvh = bvh;
        a.primitives = prims;
        a.primitiveCount = a.primitiveArrayCapacity = n;
        a.createNode = sah_node;
        a.setNodeChildren = sah_children;
        a.setNodeBounds = sah_bounds;
        a.createLeaf = sah_leaf;
        a.userPtr = &c;
        void *root = bvh ? rtcBuildBVH(&a) : NULL;
        if (bvh)
            rtcReleaseBVH(bvh);
        g->nprim = atomic_load(&c.leaves);
        if (root && atomic_load(&c.used) == n && (g->box = malloc(g->nprim * sizeof *g->box)))
            bad = M == 4 ? build_leaves4(g, cyl, &c) : M == 8 ? build_leaves8(g, cyl, &c)
                                                             : build_leaves16(g, cyl, &c);
        for (size_t l = 0; !bad && l < g->nprim; l++) {
            const uint32_t *ids = c.order + c.first[l];
            /* the builder reorders prims in place: the boxes are made again */
            for (size_t j = 0; j < c.count[l]; j++) {
                struct RTCBounds b;
                whole_box(&g->prep[ids[j]], &b);
                if (j == 0)
                    g->box[l] = b;
                box_union(&g->box[l], &b);
            }
        }
    }
    free(prims);
    free(c.order);
    free(c.first);
    free(c.count);
    return bad;
}

/* ---- one box a primitive, split along long tilted cylinders --------------------- */

static int make_boxes(ceb *g, const cylray_cylinder *cyl)
{
    size_t total = 0;
    int split = (g->options & CYLRAY_EMBREE_SPLIT) != 0;
    for (size_t i = 0; i < g->n; i++) {
        if (split)
            g->fr[i].pieces = pieces_for(&g->fr[i], cyl[i].radius);
        total += g->fr[i].pieces;
    }
    if (total > 0xffffffffu)
        return 1;
    g->nprim = total;
    g->box = malloc(total * sizeof *g->box);
    if (!g->box)
        return -1;
    if (total == g->n) {
        for (size_t i = 0; i < g->n; i++)
            whole_box(&g->prep[i], &g->box[i]);
        return 0;
    }
    g->prim_cyl = malloc(total * sizeof *g->prim_cyl);
    g->prim_piece = malloc(total * sizeof *g->prim_piece);
    float(*lo)[3] = malloc(CEB_MAX_PIECES * sizeof *lo);
    float(*hi)[3] = malloc(CEB_MAX_PIECES * sizeof *hi);
    int bad = !g->prim_cyl || !g->prim_piece || !lo || !hi;
    size_t p = 0;
    for (size_t i = 0; !bad && i < g->n; i++) {
        const frame *f = &g->fr[i];
        uint32_t K = f->pieces;
        if (K == 1) {
            whole_box(&g->prep[i], &g->box[p]);
            g->prim_cyl[p] = (uint32_t)i;
            g->prim_piece[p++] = 0;
            continue;
        }
        /* cylray_split_boxes' slice k holds the stretch u in [k/K, (k+1)/K] exactly; a
         * hit is owned by the slice its rounded u falls in, so each box reaches beyond
         * its stretch by more than that rounding and the hit point's: 2^-16 of the
         * coordinates and the length, in every direction */
        double big = 0, L = 0;
        for (int k = 0; k < 3; k++) {
            big = fmax(big, fabs(f->p0[k]) + fabs(f->a[k]));
            L += (double)f->a[k] * f->a[k];
        }
        float pad = (float)(0x1p-16 * (big + sqrt(L)) + 0x1p-10 * cyl[i].radius);
        if (cylray_split_boxes(&g->prep[i], K, lo, hi) != K) {
            bad = 1;
            break;
        }
        for (uint32_t k = 0; k < K; k++, p++) {
            set_box(&g->box[p], lo[k], hi[k], pad);
            g->prim_cyl[p] = (uint32_t)i;
            g->prim_piece[p] = k;
        }
    }
    free(lo);
    free(hi);
    return bad ? -1 : 0;
}

/* ---- the public calls ----------------------------------------------------------- */

static const void *elem(const void *base, size_t stride, size_t i)
{
    return (const char *)base + stride * i;
}

static void ceb_free(ceb *g)
{
    if (!g)
        return;
    g->magic = 0;
    free(g->prep);
    free(g->fr);
    free(g->prim_cyl);
    free(g->prim_piece);
    free(g->box);
    free(g->leaves);
    free(g);
}

RTCGeometry cylray_embree_new_geometry(RTCDevice device, const cylray_embree_desc *desc,
                                       cylray_status *status)
{
    cylray_status st = CYLRAY_EINVAL;
    ceb *g = NULL;
    cylray_cylinder *cyl = NULL;
    RTCGeometry geo = NULL;
    if (status)
        *status = CYLRAY_EINVAL;
    if (!device || !desc || desc->count == 0 || desc->count > 0xffffffffu || !desc->p0 ||
        !desc->p1 || !desc->radius || (desc->options & ~CEB_OPTIONS) ||
        (desc->flags & ~(CEB_KFLAGS | CYLRAY_NORMAL)))
        return NULL;
    size_t n = desc->count;
    g = calloc(1, sizeof *g);
    cyl = malloc(n * sizeof *cyl);
    if (!g || !cyl)
        goto fail;
    g->magic = CEB_MAGIC;
    g->k = desc->kernels ? desc->kernels : cylray_kernels_best();
    g->options = desc->options;
    g->iflags = CYLRAY_NORMAL | (desc->flags & CEB_KFLAGS);
    g->oflags = desc->flags & CEB_KFLAGS;
    g->n = n;
    g->prep = alloc_aligned(n * sizeof *g->prep);
    g->fr = malloc(n * sizeof *g->fr);
    if (!g->k || !g->prep || !g->fr)
        goto fail;
    for (size_t i = 0; i < n; i++) {
        const float *p0 = elem(desc->p0, desc->p0_stride, i);
        const float *p1 = elem(desc->p1, desc->p1_stride, i);
        float r = *(const float *)elem(desc->radius, desc->radius_stride, i);
        unsigned caps = desc->caps ? *(const unsigned *)elem(desc->caps, desc->caps_stride, i)
                                   : CYLRAY_CAPPED;
        if (cylray_cylinder_from_endpoints(&cyl[i], p0, p1, r, caps) != CYLRAY_OK ||
            cylray_prepare(&g->prep[i], &cyl[i]) != CYLRAY_OK) {
            st = CYLRAY_EINVAL;
            goto fail_st;
        }
        frame_init(&g->fr[i], p0, p1);
    }
    st = CYLRAY_OK;
    int leaves = (desc->options & CYLRAY_EMBREE_LEAVES) != 0;
    if (leaves) {
        cylray_isa isa = g->k->isa;
        g->m = isa == CYLRAY_ISA_AVX512 ? 16 : isa == CYLRAY_ISA_AVX2 ? 8 : 4;
        if (group_leaves(g, device, cyl))
            goto fail;
    } else {
        int r = make_boxes(g, cyl);
        if (r) {
            st = r > 0 ? CYLRAY_EINVAL : CYLRAY_OK;
            goto fail_st;
        }
    }
    free(cyl);
    cyl = NULL;
    geo = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
    if (!geo)
        goto fail;
    g->geom = geo;
    rtcSetGeometryUserPrimitiveCount(geo, (unsigned)g->nprim);
    rtcSetGeometryUserData(geo, g);
    rtcSetGeometryBoundsFunction(geo, prim_bounds, NULL);
    if (leaves) {
        rtcSetGeometryIntersectFunction(geo, g->m == 4   ? leaf_intersect4
                                             : g->m == 8 ? leaf_intersect8
                                                         : leaf_intersect16);
        rtcSetGeometryOccludedFunction(geo, g->m == 4   ? leaf_occluded4
                                            : g->m == 8 ? leaf_occluded8
                                                        : leaf_occluded16);
    } else {
        rtcSetGeometryIntersectFunction(geo, single_intersect);
        rtcSetGeometryOccludedFunction(geo, single_occluded);
    }
    if (rtcGetDeviceError(device) != RTC_ERROR_NONE)
        goto fail;
    if (status)
        *status = CYLRAY_OK;
    return geo;
fail:
    st = CYLRAY_OK; /* not the input's fault: memory or Embree */
fail_st:
    if (status)
        *status = st;
    if (geo)
        rtcReleaseGeometry(geo);
    free(cyl);
    ceb_free(g);
    return NULL;
}

static ceb *ceb_of(RTCGeometry geometry)
{
    if (!geometry)
        return NULL;
    ceb *g = rtcGetGeometryUserData(geometry);
    return g && g->magic == CEB_MAGIC && g->geom == geometry ? g : NULL;
}

void cylray_embree_release_geometry(RTCGeometry geometry)
{
    ceb *g = ceb_of(geometry);
    if (!geometry)
        return;
    rtcReleaseGeometry(geometry);
    ceb_free(g);
}

int cylray_embree_is_cylinders(RTCGeometry geometry)
{
    return ceb_of(geometry) != NULL;
}

size_t cylray_embree_primitives(RTCGeometry geometry)
{
    const ceb *g = ceb_of(geometry);
    return g ? g->nprim : 0;
}

const cylray_prepared *cylray_embree_cylinder(RTCGeometry geometry, unsigned primID)
{
    const ceb *g = ceb_of(geometry);
    return g && primID < g->n ? &g->prep[primID] : NULL;
}

/* The hit's part from its normal: the discs' normals are the axis, the side's are
 * perpendicular to it. -1 for a geometry or primID not ours, or a useless Ng. */
static int hit_part(const ceb *g, unsigned primID, const float Ng[3])
{
    if (!g || primID >= g->n || !isfinite(Ng[0]) || !isfinite(Ng[1]) || !isfinite(Ng[2]) ||
        (Ng[0] == 0 && Ng[1] == 0 && Ng[2] == 0))
        return -1;
    const float *n = g->fr[primID].n;
    float c = Ng[0] * n[0] + Ng[1] * n[1] + Ng[2] * n[2];
    float l = sqrtf(Ng[0] * Ng[0] + Ng[1] * Ng[1] + Ng[2] * Ng[2]);
    return c > 0.5f * l ? CYLRAY_CAP_HI : c < -0.5f * l ? CYLRAY_CAP_LO : CYLRAY_SIDE;
}

int cylray_embree_spawn_origin(RTCGeometry geometry, unsigned primID, const float o[3],
                               const float d[3], float t, const float Ng[3], const float w[3],
                               float out[3])
{
    const ceb *g = ceb_of(geometry);
    int part = hit_part(g, primID, Ng);
    if (part < 0)
        return -1;
    float p[3], err;
    cylray_hit_point(&g->prep[primID], o, d, t, part, p, &err);
    cylray_spawn_origin(&g->prep[primID], p, err, part, w, out);
    return 0;
}

int cylray_embree_spawn_origin_side(RTCGeometry geometry, unsigned primID, const float o[3],
                                    const float d[3], float t, const float Ng[3], int outward,
                                    const float w[3], float out[3])
{
    const ceb *g = ceb_of(geometry);
    int part = hit_part(g, primID, Ng);
    if (part < 0)
        return -1;
    float p[3], err;
    cylray_hit_point(&g->prep[primID], o, d, t, part, p, &err);
    cylray_spawn_origin_side(&g->prep[primID], p, err, part, outward, w, out);
    return 0;
}
