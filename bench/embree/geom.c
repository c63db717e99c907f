/* SPDX-License-Identifier: MIT */
/* geom.c - builds the three Embree scenes of one eb_scene and holds the user-geometry
 * callbacks through which Embree's BVH calls cylray. */
#include "geom.h"

#include "clock.h"
#include "rays.h"

#include <embree3/rtcore_builder.h>
#include <math.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "morton.h"

const char *eb_variant_name(eb_variant v)
{
    static const char *const n[EB_NVARIANTS] = {"embree-curve", "cylray-single", "cylray-leaf"};
    return v < EB_NVARIANTS ? n[v] : "?";
}

/* ---- Embree's SoA ray and hit layout for N rays (rtcore_ray.h, RTCRayHitN) ------------ */

/* Ray fields: org x y z, tnear, dir x y z, time, tfar, mask, id, flags; then the hit:
 * Ng x y z, u, v, primID, geomID, instID[levels]. Each is an array of N. */
enum { R_OX, R_OY, R_OZ, R_TNEAR, R_DX, R_DY, R_DZ, R_TIME, R_TFAR };
enum { H_NGX = 12, H_NGY, H_NGZ, H_U, H_V, H_PRIM, H_GEOM, H_INST };
#define EB_F(base, N, field, i) (((float *)(base))[(field) * (N) + (i)])
#define EB_U(base, N, field, i) (((unsigned *)(base))[(field) * (N) + (i)])

float eb_curve_u(const eb_scene *s, uint32_t i, const float p[3])
{
    const float *a = s->vert[s->first[i]], *b = s->vert[s->first[i] + 1];
    double ab = 0, ap = 0;
    for (int k = 0; k < 3; k++) {
        ab += ((double)b[k] - a[k]) * ((double)b[k] - a[k]);
        ap += ((double)p[k] - a[k]) * ((double)b[k] - a[k]);
    }
    double u = ap / ab;
    return (float)(u < 0 ? 0 : u > 1 ? 1 : u);
}

void eb_cylinder_bounds(const eb_scene *s, uint32_t i, struct RTCBounds *b)
{
    const float *p = s->vert[s->first[i]], *q = s->vert[s->first[i] + 1];
    double a[3], aa = 0;
    for (int k = 0; k < 3; k++)
        a[k] = (double)q[k] - p[k], aa += a[k] * a[k];
    float lo[3], hi[3];
    for (int k = 0; k < 3; k++) {
        /* a disc of radius r perpendicular to a reaches r sqrt(1 - a_k^2) along k */
        double e = s->radius * sqrt(fmax(0.0, 1 - a[k] * a[k] / aa)) * (1 + 0x1p-18);
        double mn = fmin(p[k], q[k]) - e, mx = fmax(p[k], q[k]) + e;
        double pad = 0x1p-20 * fmax(fabs(mn), fabs(mx)) + 0x1p-20 * s->radius;
        lo[k] = nextafterf((float)(mn - pad), -INFINITY);
        hi[k] = nextafterf((float)(mx + pad), INFINITY);
    }
    b->lower_x = lo[0], b->lower_y = lo[1], b->lower_z = lo[2];
    b->upper_x = hi[0], b->upper_y = hi[1], b->upper_z = hi[2];
}

/* Writes a hit into lane i of Embree's RTCRayHitN (N wide). v, which a curve uses for
 * the place around its circumference, carries cylray's part (side or cap, and whether
 * met from inside): the spawn helper needs it for the secondary rays. */
static void put_hit(const struct RTCIntersectFunctionNArguments *a, const eb_scene *s,
                    unsigned i, float t, const float n[3], uint32_t prim, int32_t part)
{
    void *rh = a->rayhit;
    unsigned N = a->N;
    float p[3];
    for (int k = 0; k < 3; k++)
        p[k] = EB_F(rh, N, R_OX + k, i) + t * EB_F(rh, N, R_DX + k, i);
    EB_F(rh, N, R_TFAR, i) = t;
    EB_F(rh, N, H_NGX, i) = n[0];
    EB_F(rh, N, H_NGY, i) = n[1];
    EB_F(rh, N, H_NGZ, i) = n[2];
    EB_F(rh, N, H_U, i) = eb_curve_u(s, prim, p);
    EB_F(rh, N, H_V, i) = (float)part;
    EB_U(rh, N, H_PRIM, i) = prim;
    EB_U(rh, N, H_GEOM, i) = a->geomID;
    for (unsigned l = 0; l < RTC_MAX_INSTANCE_LEVEL_COUNT; l++)
        EB_U(rh, N, H_INST + l, i) = a->context->instID[l];
}

/* The valid lanes of a call, in order. */
static unsigned active_lanes(const int *valid, unsigned N, unsigned lane[16])
{
    unsigned n = 0;
    for (unsigned i = 0; i < N; i++)
        if (valid[i])
            lane[n++] = i;
    return n;
}

/* ---- single cylinders: one user primitive per cylinder, cylray's packet kernels ------ */

/* Embree calls with N = 1, 4, 8 or 16 and often only a few valid lanes (its hybrid
 * traversal hands a packet of K over with one lane set). The valid lanes are packed into
 * the narrowest cylray packet that holds them, so a lone ray costs a 4-wide call. The
 * unused lanes repeat the first ray rather than hold stack garbage, which a kernel
 * without its own guard computed at the price of microcode assists (subnormals). */
#define EB_GATHER(pk, base, N, lane, n, W)                                                 \
    do {                                                                                   \
        for (unsigned j = 0; j < (W); j++) {                                               \
            unsigned i_ = (lane)[j < (n) ? j : 0];                                         \
            (pk).ox[j] = EB_F(base, N, R_OX, i_), (pk).oy[j] = EB_F(base, N, R_OY, i_);    \
            (pk).oz[j] = EB_F(base, N, R_OZ, i_), (pk).dx[j] = EB_F(base, N, R_DX, i_);    \
            (pk).dy[j] = EB_F(base, N, R_DY, i_), (pk).dz[j] = EB_F(base, N, R_DZ, i_);    \
            (pk).tmin[j] = EB_F(base, N, R_TNEAR, i_);                                     \
            (pk).tmax[j] = EB_F(base, N, R_TFAR, i_);                                      \
        }                                                                                  \
    } while (0)

#define EB_SINGLE_ISECT(W)                                                                 \
    static void single_isect##W(const struct RTCIntersectFunctionNArguments *a,            \
                                const eb_geom *g, const unsigned *lane, unsigned n)        \
    {                                                                                      \
        cylray_ray##W ray;                                                                 \
        cylray_hit##W hit;                                                                 \
        EB_GATHER(ray, a->rayhit, a->N, lane, n, W);                                       \
        uint32_t m = g->k->intersect##W(&g->prep[a->primID], &ray, &hit,                   \
                                        (uint32_t)((1ull << n) - 1), CYLRAY_NORMAL);       \
        for (unsigned j = 0; m; j++, m >>= 1)                                              \
            if (m & 1) {                                                                   \
                float nn[3] = {hit.nx[j], hit.ny[j], hit.nz[j]};                           \
                put_hit(a, g->src, lane[j], hit.t[j], nn, a->primID, hit.part[j]);         \
            }                                                                              \
    }
EB_SINGLE_ISECT(4)
EB_SINGLE_ISECT(8)
EB_SINGLE_ISECT(16)

#define EB_SINGLE_OCC(W)                                                                   \
    static void single_occ##W(const struct RTCOccludedFunctionNArguments *a,               \
                              const eb_geom *g, const unsigned *lane, unsigned n)          \
    {                                                                                      \
        cylray_ray##W ray;                                                                 \
        EB_GATHER(ray, a->ray, a->N, lane, n, W);                                          \
        uint32_t m = g->k->occluded##W(&g->prep[a->primID], &ray,                          \
                                       (uint32_t)((1ull << n) - 1), 0);                    \
        for (unsigned j = 0; m; j++, m >>= 1)                                              \
            if (m & 1)                                                                     \
                EB_F(a->ray, a->N, R_TFAR, lane[j]) = -INFINITY;                           \
    }
EB_SINGLE_OCC(4)
EB_SINGLE_OCC(8)
EB_SINGLE_OCC(16)

/* The callback for one of Embree's query kinds: the active lanes, in the narrowest
 * packet that holds them. */
#define EB_SINGLE_CALLBACK(name, args, fn)                                                 \
    static void name(const struct args *a)                                                 \
    {                                                                                      \
        const eb_geom *g = a->geometryUserPtr;                                             \
        unsigned lane[16], n = active_lanes(a->valid, a->N, lane);                         \
        if (n == 0)                                                                        \
            return;                                                                        \
        if (n <= 4)                                                                        \
            fn##4(a, g, lane, n);                                                          \
        else if (n <= 8)                                                                   \
            fn##8(a, g, lane, n);                                                          \
        else                                                                               \
            fn##16(a, g, lane, n);                                                         \
    }
EB_SINGLE_CALLBACK(single_intersect, RTCIntersectFunctionNArguments, single_isect)
EB_SINGLE_CALLBACK(single_occluded, RTCOccludedFunctionNArguments, single_occ)

static void single_bounds(const struct RTCBoundsFunctionArguments *a)
{
    const eb_geom *g = a->geometryUserPtr;
    eb_cylinder_bounds(g->src, a->primID, a->bounds_o);
}

/* ---- leaves: one user primitive per M cylinders, one ray at a time ------------------- */

static void load_ray1(cylray_ray1 *r, const void *base, unsigned N, unsigned i)
{
    for (int k = 0; k < 3; k++) {
        r->o[k] = EB_F(base, N, R_OX + k, i);
        r->d[k] = EB_F(base, N, R_DX + k, i);
    }
    r->tmin = EB_F(base, N, R_TNEAR, i);
    r->tmax = EB_F(base, N, R_TFAR, i);
}

#define EB_LEAF_FNS(M)                                                                     \
    static void leaf_intersect##M(const struct RTCIntersectFunctionNArguments *a)          \
    {                                                                                      \
        const eb_geom *g = a->geometryUserPtr;                                             \
        const cylray_leaf##M *leaf = (const cylray_leaf##M *)g->leaves + a->primID;        \
        for (unsigned i = 0; i < a->N; i++) {                                              \
            if (!a->valid[i])                                                              \
                continue;                                                                  \
            cylray_ray1 r;                                                                 \
            cylray_hit1 h;                                                                 \
            load_ray1(&r, a->rayhit, a->N, i);                                             \
            if (g->k->leaf_intersect##M(leaf, &r, &h, CYLRAY_NORMAL))                      \
                put_hit(a, g->src, i, h.t, h.n, h.id, h.part);                             \
        }                                                                                  \
    }                                                                                      \
    static void leaf_occluded##M(const struct RTCOccludedFunctionNArguments *a)            \
    {                                                                                      \
        const eb_geom *g = a->geometryUserPtr;                                             \
        const cylray_leaf##M *leaf = (const cylray_leaf##M *)g->leaves + a->primID;        \
        for (unsigned i = 0; i < a->N; i++) {                                              \
            if (!a->valid[i])                                                              \
                continue;                                                                  \
            cylray_ray1 r;                                                                 \
            load_ray1(&r, a->ray, a->N, i);                                                \
            if (g->k->leaf_occluded##M(leaf, &r, 0))                                       \
                EB_F(a->ray, a->N, R_TFAR, i) = -INFINITY;                                 \
        }                                                                                  \
    }
EB_LEAF_FNS(4)
EB_LEAF_FNS(8)
EB_LEAF_FNS(16)

static void leaf_bounds(const struct RTCBoundsFunctionArguments *a)
{
    const eb_geom *g = a->geometryUserPtr;
    *a->bounds_o = g->lbox[a->primID];
}

typedef struct keyed {
    uint32_t key, id;
} keyed;

static int by_key(const void *pa, const void *pb)
{
    const keyed *a = pa, *b = pb;
    return a->key != b->key ? (a->key < b->key ? -1 : 1) : (a->id < b->id ? -1 : a->id > b->id);
}

/* Cylinder ids sorted along a Morton curve through their centres, so that the M of a
 * leaf lie close together and its box stays small. */
static uint32_t *morton_order(const eb_scene *s)
{
    keyed *k = malloc(s->ns * sizeof *k);
    uint32_t *order = malloc(s->ns * sizeof *order);
    if (!k || !order) {
        free(k);
        free(order);
        return NULL;
    }
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < s->ns; i++)
        for (int c = 0; c < 3; c++) {
            lo[c] = fminf(lo[c], s->cyl[i].center[c]);
            hi[c] = fmaxf(hi[c], s->cyl[i].center[c]);
        }
    for (size_t i = 0; i < s->ns; i++) {
        uint32_t code = 0;
        for (int c = 0; c < 3; c++) {
            double ext = (double)hi[c] - lo[c];
            double f = ext > 0 ? ((double)s->cyl[i].center[c] - lo[c]) / ext : 0;
            code |= morton_spread3((uint32_t)(f * 1023.0)) << c;
        }
        k[i].key = code;
        k[i].id = (uint32_t)i;
    }
    qsort(k, s->ns, sizeof *k, by_key);
    for (size_t i = 0; i < s->ns; i++)
        order[i] = k[i].id;
    free(k);
    return order;
}

/* ---- building ---------------------------------------------------------------------- */

static RTCGeometry native_geometry(RTCDevice dev, const eb_scene *s)
{
    RTCGeometry geo = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_CONE_LINEAR_CURVE);
    float *v = rtcSetNewGeometryBuffer(geo, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4,
                                       4 * sizeof(float), s->nv);
    unsigned *idx = rtcSetNewGeometryBuffer(geo, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT,
                                            sizeof(unsigned), s->ns);
    unsigned char *fl = rtcSetNewGeometryBuffer(geo, RTC_BUFFER_TYPE_FLAGS, 0,
                                                RTC_FORMAT_UCHAR, 1, s->ns);
    if (!v || !idx || !fl) {
        rtcReleaseGeometry(geo);
        return NULL;
    }
    for (size_t i = 0; i < s->nv; i++) {
        memcpy(v + 4 * i, s->vert[i], 3 * sizeof(float));
        v[4 * i + 3] = s->radius;
    }
    /* A segment is closed where it has no neighbour: Embree caps a cone curve's end
     * unless the flag says a segment joins there. */
    for (size_t i = 0; i < s->ns; i++) {
        idx[i] = s->first[i];
        fl[i] = (unsigned char)(((s->caps[i] & CYLRAY_CAPPED_LO) ? 0
                                                                 : RTC_CURVE_FLAG_NEIGHBOR_LEFT) |
                                ((s->caps[i] & CYLRAY_CAPPED_HI) ? 0
                                                                 : RTC_CURVE_FLAG_NEIGHBOR_RIGHT));
    }
    return geo;
}

static int prepare_all(eb_geom *g)
{
    const eb_scene *s = g->src;
    g->prep = bench_alloc(s->ns * sizeof *g->prep);
    if (!g->prep)
        return -1;
    for (size_t i = 0; i < s->ns; i++)
        if (cylray_prepare(&g->prep[i], &s->cyl[i]) != CYLRAY_OK)
            return -1;
    return 0;
}

/* ---- grouping cylinders into leaves ------------------------------------------------- */

/* Leaf l holds the cylinders order[first[l] .. first[l] + count[l]). */
typedef struct grouping {
    uint32_t *order;
    size_t *first, *count;
    size_t n;
} grouping;

static int grouping_alloc(grouping *gr, size_t ns)
{
    gr->n = 0;
    gr->order = malloc(ns * sizeof *gr->order);
    gr->first = malloc(ns * sizeof *gr->first);
    gr->count = malloc(ns * sizeof *gr->count);
    return gr->order && gr->first && gr->count ? 0 : -1;
}

static void grouping_free(grouping *gr)
{
    free(gr->order);
    free(gr->first);
    free(gr->count);
}

/* Consecutive runs of M along the Morton curve. */
static int group_morton(const eb_scene *s, int M, grouping *gr)
{
    uint32_t *order = morton_order(s);
    if (!order || grouping_alloc(gr, s->ns)) {
        free(order);
        return -1;
    }
    memcpy(gr->order, order, s->ns * sizeof *order);
    free(order);
    for (size_t a = 0; a < s->ns; a += (size_t)M) {
        gr->first[gr->n] = a;
        gr->count[gr->n++] = s->ns - a < (size_t)M ? s->ns - a : (size_t)M;
    }
    return 0;
}

/* Embree's own SAH builder (rtcBuildBVH) cuts the cylinders into leaves of at most M;
 * only its leaves are kept. Its callbacks run on several threads: a leaf takes its
 * slots with atomic counters. */
typedef struct sah_ctx {
    grouping *gr;
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
        c->gr->order[at + i] = p[i].primID;
    c->gr->first[l] = at;
    c->gr->count[l] = n;
    return rtcThreadLocalAlloc(al, 16, 16);
}

static int group_sah(RTCDevice dev, const eb_scene *s, int M, grouping *gr)
{
    struct RTCBuildPrimitive *prims = bench_alloc(s->ns * sizeof *prims);
    if (!prims || grouping_alloc(gr, s->ns)) {
        bench_free(prims);
        return -1;
    }
    for (size_t i = 0; i < s->ns; i++) {
        struct RTCBounds b;
        eb_cylinder_bounds(s, (uint32_t)i, &b);
        prims[i] = (struct RTCBuildPrimitive){b.lower_x, b.lower_y, b.lower_z, 0,
                                              b.upper_x, b.upper_y, b.upper_z, (unsigned)i};
    }
    sah_ctx c = {.gr = gr};
    atomic_init(&c.used, 0);
    atomic_init(&c.leaves, 0);
    RTCBVH bvh = rtcNewBVH(dev);
    struct RTCBuildArguments a = rtcDefaultBuildArguments();
    a.buildQuality = RTC_BUILD_QUALITY_MEDIUM;
    a.maxDepth = 64;
    /* a leaf is one vector test whether it holds 1 or M: split only above M */
    a.minLeafSize = (unsigned)M;
    a.maxLeafSize = (unsigned)M;
    a.bvh = bvh;
    a.primitives = prims;
    a.primitiveCount = a.primitiveArrayCapacity = s->ns;
    a.createNode = sah_node;
    a.setNodeChildren = sah_children;
    a.setNodeBounds = sah_bounds;
    a.createLeaf = sah_leaf;
    a.userPtr = &c;
    void *root = rtcBuildBVH(&a);
    rtcReleaseBVH(bvh);
    bench_free(prims);
    gr->n = atomic_load(&c.leaves);
    return root && atomic_load(&c.used) == s->ns ? 0 : -1;
}

#define EB_LEAF_BUILD(M)                                                                   \
    static int build_leaves##M(eb_geom *g, const grouping *gr)                             \
    {                                                                                      \
        const eb_scene *s = g->src;                                                        \
        cylray_leaf##M *lv = bench_alloc(g->nleaves * sizeof *lv);                         \
        if (!lv)                                                                           \
            return -1;                                                                     \
        g->leaves = lv;                                                                    \
        for (size_t l = 0; l < g->nleaves; l++) {                                          \
            const uint32_t *ids = gr->order + gr->first[l];                                \
            cylray_cylinder c[M];                                                          \
            for (size_t j = 0; j < gr->count[l]; j++)                                      \
                c[j] = s->cyl[ids[j]];                                                     \
            if (cylray_leaf_prepare##M(&lv[l], c, ids, gr->count[l]) != CYLRAY_OK)         \
                return -1;                                                                 \
        }                                                                                  \
        return 0;                                                                          \
    }
EB_LEAF_BUILD(4)
EB_LEAF_BUILD(8)
EB_LEAF_BUILD(16)

static RTCGeometry leaf_geometry(RTCDevice dev, eb_geom *g, eb_grouping how)
{
    const eb_scene *s = g->src;
    int M = g->leaf_m;
    grouping gr;
    memset(&gr, 0, sizeof gr);
    int bad = how == EB_GROUP_SAH ? group_sah(dev, s, M, &gr) : group_morton(s, M, &gr);
    g->nleaves = gr.n;
    g->lbox = bad ? NULL : malloc(g->nleaves * sizeof *g->lbox);
    bad = bad || !g->lbox || (M == 4   ? build_leaves4(g, &gr)
                              : M == 8 ? build_leaves8(g, &gr)
                                       : build_leaves16(g, &gr));
    for (size_t l = 0; !bad && l < g->nleaves; l++) {
        struct RTCBounds *u = &g->lbox[l];
        for (size_t j = 0; j < gr.count[l]; j++) {
            struct RTCBounds b;
            eb_cylinder_bounds(s, gr.order[gr.first[l] + j], &b);
            if (j == 0)
                *u = b;
            u->lower_x = fminf(u->lower_x, b.lower_x), u->upper_x = fmaxf(u->upper_x, b.upper_x);
            u->lower_y = fminf(u->lower_y, b.lower_y), u->upper_y = fmaxf(u->upper_y, b.upper_y);
            u->lower_z = fminf(u->lower_z, b.lower_z), u->upper_z = fmaxf(u->upper_z, b.upper_z);
        }
    }
    grouping_free(&gr);
    if (bad)
        return NULL;
    RTCGeometry geo = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_USER);
    rtcSetGeometryUserPrimitiveCount(geo, (unsigned)g->nleaves);
    rtcSetGeometryUserData(geo, g);
    rtcSetGeometryBoundsFunction(geo, leaf_bounds, NULL);
    g->isect = M == 4 ? leaf_intersect4 : M == 8 ? leaf_intersect8 : leaf_intersect16;
    g->occ = M == 4 ? leaf_occluded4 : M == 8 ? leaf_occluded8 : leaf_occluded16;
    rtcSetGeometryIntersectFunction(geo, g->isect);
    rtcSetGeometryOccludedFunction(geo, g->occ);
    return geo;
}

int eb_geom_build(eb_geom *g, RTCDevice dev, const eb_scene *s, eb_variant v, int leaf_m,
                  eb_grouping how, const cylray_kernels *k)
{
    memset(g, 0, sizeof *g);
    g->variant = v;
    g->src = s;
    g->k = k;
    g->leaf_m = leaf_m;
    double t0 = clk_ns();
    RTCGeometry geo = NULL;
    if (v == EB_NATIVE) {
        geo = native_geometry(dev, s);
    } else if (prepare_all(g) == 0) {
        if (v == EB_SINGLE) {
            geo = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_USER);
            rtcSetGeometryUserPrimitiveCount(geo, (unsigned)s->ns);
            rtcSetGeometryUserData(geo, g);
            rtcSetGeometryBoundsFunction(geo, single_bounds, NULL);
            rtcSetGeometryIntersectFunction(geo, g->isect = single_intersect);
            rtcSetGeometryOccludedFunction(geo, g->occ = single_occluded);
        } else if (leaf_m == 4 || leaf_m == 8 || leaf_m == 16) {
            geo = leaf_geometry(dev, g, how);
        }
    }
    if (!geo) {
        eb_geom_free(g);
        return -1;
    }
    rtcCommitGeometry(geo);
    g->scene = rtcNewScene(dev);
    rtcAttachGeometry(g->scene, geo);
    rtcReleaseGeometry(geo);
    rtcCommitScene(g->scene);
    g->build_s = (clk_ns() - t0) * 1e-9;
    return rtcGetDeviceError(dev) == RTC_ERROR_NONE ? 0 : -1;
}

void eb_geom_free(eb_geom *g)
{
    if (g->scene)
        rtcReleaseScene(g->scene);
    bench_free(g->prep);
    bench_free(g->leaves);
    free(g->lbox);
    memset(g, 0, sizeof *g);
}
