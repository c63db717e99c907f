/* SPDX-License-Identifier: MIT */
/* test_spheres.c - cylray_embree's spheres (cylray_embree_new_spheres), alone and beside
 * cylinders, give the hits that plain cylray calls give: Embree's BVH with one sphere a
 * primitive or leaves of them, at 1, 4, 8 and 16 rays a call, coherent and not,
 * against every shape tried in turn through the same kernel (a prepared sphere; for
 * the leaves a leaf holding that shape alone), bit for bit; and the exact reference's
 * (binary128): no wrong answer outside the 2-ulp band. Also: u and v as pbrt's sphere
 * and Ng outward; the geometry's and the query's filters, every hit offered once;
 * geometry masks; an instance; the packet spawn origins; the descriptions the adapter
 * refuses. */
#include "agree.h"
#include "geom.h"
#include "judge.h"
#include "trace.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { W = 48, H = 48, MAXS = 400 };

static const cylray_kernels *K;
static const eb_scene *S;
static cylray_prepared PREP[MAXS];            /* the segments, then the spheres */
static _Alignas(64) cylray_leaf8 LEAF8[MAXS]; /* each shape alone in a leaf */
static _Alignas(64) cylray_leaf4 LEAF4[MAXS];
static int LEAVES; /* 0: the prepared shapes' kernel; 4 or 8: the one-shape leaves */

static size_t nshapes(void)
{
    return S->ns + S->nsph;
}

/* Shape k of the tables above as an answer's id, and back. */
static uint32_t id_of(size_t k)
{
    return k < S->ns ? (uint32_t)k : EB_SPHERE_BIT | (uint32_t)(k - S->ns);
}

static size_t index_of(uint32_t id)
{
    return id & EB_SPHERE_BIT ? S->ns + (id & ~EB_SPHERE_BIT) : id;
}

static int prepare_all(void)
{
    if (nshapes() > MAXS)
        return -1;
    for (size_t k = 0; k < nshapes(); k++) {
        uint32_t id = 0;
        int bad;
        if (k < S->ns)
            bad = cylray_prepare(&PREP[k], &S->cyl[k]) != CYLRAY_OK ||
                  cylray_leaf_prepare8(&LEAF8[k], &S->cyl[k], &id, 1) != CYLRAY_OK ||
                  cylray_leaf_prepare4(&LEAF4[k], &S->cyl[k], &id, 1) != CYLRAY_OK;
        else
            bad = cylray_prepare_sphere(&PREP[k], &S->sph[k - S->ns]) != CYLRAY_OK ||
                  cylray_leaf_prepare_spheres8(&LEAF8[k], &S->sph[k - S->ns], &id, 1) !=
                      CYLRAY_OK ||
                  cylray_leaf_prepare_spheres4(&LEAF4[k], &S->sph[k - S->ns], &id, 1) !=
                      CYLRAY_OK;
        if (bad)
            return -1;
    }
    return 0;
}

/* The first hit of shape k in [tmin, tmax] by the path the variant under test uses. */
static int first_hit(size_t k, const float o[3], const float d[3], float tmin, float tmax,
                     float *t, float n[3])
{
    if (LEAVES) {
        cylray_ray1 r = {{o[0], o[1], o[2]}, {d[0], d[1], d[2]}, tmin, tmax};
        cylray_hit1 h;
        int got = LEAVES == 8 ? K->leaf_intersect8(&LEAF8[k], &r, &h, CYLRAY_NORMAL)
                              : K->leaf_intersect4(&LEAF4[k], &r, &h, CYLRAY_NORMAL);
        if (!got)
            return 0;
        *t = h.t;
        memcpy(n, h.n, sizeof h.n);
        return 1;
    }
    CYLRAY_ALIGN(16) cylray_ray4 r;
    CYLRAY_ALIGN(16) cylray_hit4 h;
    for (int j = 0; j < 4; j++) {
        r.ox[j] = o[0], r.oy[j] = o[1], r.oz[j] = o[2];
        r.dx[j] = d[0], r.dy[j] = d[1], r.dz[j] = d[2];
        r.tmin[j] = tmin, r.tmax[j] = tmax;
    }
    if (!K->intersect4(&PREP[k], &r, &h, 1, CYLRAY_NORMAL))
        return 0;
    *t = h.t[0];
    n[0] = h.nx[0], n[1] = h.ny[0], n[2] = h.nz[0];
    return 1;
}

/* Every hit of shape k on the ray, in order: the first, then the next beyond it. */
static int all_hits(size_t k, const float o[3], const float d[3], float tmin, float tmax,
                    float t[4], float n[4][3])
{
    int m = 0;
    while (m < 4 && first_hit(k, o, d, tmin, tmax, &t[m], n[m]))
        tmin = nextafterf(t[m++], INFINITY);
    return m;
}

/* The shapes as the shared checks walk them; every fifth camera ray offered. */
static const eb_shapes SHAPES = {nshapes, id_of, all_hits, 5};

/* The closest hit over every shape whose geometry's mask meets `mask` (bit 0: the
 * segments, bit 1: the spheres); with `filtered`, the closest the rule (eb_rejected) accepts. */
static uint32_t brute(const float o[3], const float d[3], float tmin, float tmax, int filtered,
                      unsigned mask, float *t, float nrm[3])
{
    uint32_t best = RTC_INVALID_GEOMETRY_ID;
    for (size_t k = 0; k < nshapes(); k++) {
        if (!(mask & (k < S->ns ? 1u : 2u)))
            continue;
        float ts[4], ns[4][3];
        int m = all_hits(k, o, d, tmin, tmax, ts, ns);
        for (int j = 0; j < m; j++) {
            if (filtered && eb_rejected(id_of(k) & ~EB_SPHERE_BIT, ns[j], d))
                continue;
            if (best == RTC_INVALID_GEOMETRY_ID || ts[j] < *t) {
                best = id_of(k);
                *t = ts[j];
                memcpy(nrm, ns[j], sizeof ns[j]);
            }
            break;
        }
    }
    return best;
}

/* A sphere's hit record: Ng the unit outward normal at the hit point, u and v those of
 * pbrt's sphere from it. */
static int sphere_record_ok(uint32_t id, const float o[3], const float d[3], float t,
                            const float ng[3], float u, float v)
{
    const cylray_sphere *sp = &S->sph[id & ~EB_SPHERE_BIT];
    double p[3], l = 0, out = 0;
    for (int k = 0; k < 3; k++) {
        p[k] = (double)o[k] + (double)t * d[k] - sp->center[k];
        l += (double)ng[k] * ng[k];
        out += p[k] * ng[k];
    }
    if (fabs(sqrt(l) - 1) > 1e-6 || !(out > 0))
        return 0;
    const double pi = 3.14159265358979323846;
    double uu = atan2(ng[1], ng[0]) / (2 * pi);
    uu += uu < 0 ? 1 : 0;
    double vv = 1 - acos(fmax(-1.0, fmin(1.0, ng[2]))) / pi, du = fabs(u - uu);
    return u >= 0 && u < 1 && fmin(du, 1 - du) <= 2e-6 && fabs(v - vv) <= 2e-6;
}

/* brute() over both geometries. */
static uint32_t brute_all(const float o[3], const float d[3], float tmin, float tmax,
                          int filtered, float *t, float n[3])
{
    return brute(o, d, tmin, tmax, filtered, 3u, t, n);
}

/* A hit Embree+cylray records for ray i of r against brute()'s: the same t bit for bit
 * (another shape only at that very t), with the same shape the same normal, and a
 * sphere's record as sphere_record_ok wants. */
static int hit_ok(const eb_rays *r, size_t i, const float o[3], const float d[3], uint32_t got,
                  uint32_t want, float t, const float n[3])
{
    if (index_of(got) >= nshapes())
        return 0;
    float ng[3] = {r->ngx[i], r->ngy[i], r->ngz[i]};
    int ok = r->tfar[i] == t;
    if (ok && got == want)
        ok = memcmp(ng, n, sizeof ng) == 0;
    if (ok && (got & EB_SPHERE_BIT))
        ok = sphere_record_ok(got, o, d, r->tfar[i], ng, r->u[i], r->v[i]);
    return ok;
}

/* Each answer in r against brute() and hit_ok. */
static int check(const char *what, const eb_rays *r, const float *tfar0, const uint8_t *valid0,
                 int occ, int filtered)
{
    static const eb_answers answers = {brute_all, hit_ok};
    return eb_check_answers(what, r, tfar0, valid0, occ, filtered, &answers);
}

/* Every other ray turned around from beyond the scene, the packets told incoherent. */
static void mix_rays(eb_rays *r)
{
    r->incoherent = 1;
    for (size_t i = 1; i < r->n; i += 2) {
        r->ox[i] = r->ox[i] + 60 * r->dx[i];
        r->oy[i] = r->oy[i] + 60 * r->dy[i];
        r->oz[i] = r->oz[i] + 60 * r->dz[i];
        r->dx[i] = -r->dx[i], r->dy[i] = -r->dy[i], r->dz[i] = -r->dz[i];
    }
}

static int passed, failed;

static void report(int bad, const char *what)
{
    printf("%s %s (%d disagreements)\n", bad ? "FAIL" : "ok  ", what, bad);
    bad ? failed++ : passed++;
}

/* The shared packet passes (eb_packet_passes) on this test's camera, rays and check. */
static void packet_passes(RTCScene sc, const char *vn, int filtered, RTCFilterFunctionN qf,
                          eb_rays *r, float *tfar0, uint8_t *valid0)
{
    const eb_passes p = {S, W, H, mix_rays, check};
    eb_packet_passes(&p, sc, vn, filtered, qf, r, tfar0, valid0, &passed, &failed);
}

/* The scene's shapes through the adapter as geometries 0 and EB_SPHERE_GEOM, with
 * options and (when not NULL) filter as the geometries' filter function. */
static RTCScene adapter_scene(RTCDevice dev, unsigned options, RTCFilterFunctionN filter,
                              RTCGeometry geo[2])
{
    cylray_embree_desc d = eb_scene_desc(S, options, K);
    cylray_embree_sphere_desc e = eb_sphere_desc(S, options, K);
    geo[0] = S->ns ? cylray_embree_new_geometry(dev, &d, NULL) : NULL;
    geo[1] = cylray_embree_new_spheres(dev, &e, NULL);
    if ((S->ns && !geo[0]) || !geo[1]) {
        cylray_embree_release_geometry(geo[0]);
        cylray_embree_release_geometry(geo[1]);
        return NULL;
    }
    RTCScene sc = rtcNewScene(dev);
    for (unsigned k = 0; k < 2; k++) {
        if (!geo[k])
            continue;
        if (filter) {
            rtcSetGeometryIntersectFilterFunction(geo[k], filter);
            rtcSetGeometryOccludedFilterFunction(geo[k], filter);
        }
        rtcSetGeometryMask(geo[k], 1u << k);
        rtcCommitGeometry(geo[k]);
        rtcAttachGeometryByID(sc, geo[k], k ? EB_SPHERE_GEOM : 0);
    }
    rtcCommitScene(sc);
    return sc;
}

static void adapter_free(RTCScene sc, RTCGeometry geo[2])
{
    rtcReleaseScene(sc);
    cylray_embree_release_geometry(geo[0]);
    cylray_embree_release_geometry(geo[1]);
}

/* Rays with masks 1 (the segments' geometry), 2 (the spheres') and 3 meet only the
 * geometries their mask names. */
static int masks(RTCScene sc, const eb_rays *r)
{
    int bad = 0;
    for (size_t i = 0; i < r->n; i += 3) {
        float o[3], d[3];
        eb_rays_get(r, i, o, d);
        for (unsigned mask = 1; mask <= 3; mask++) {
            float t = 0, n[3];
            uint32_t want = brute(o, d, 0, INFINITY, 0, mask, &t, n);
            struct RTCRayHit rh;
            eb_trace_mask(sc, o, d, mask, &rh);
            uint32_t got = eb_hit_id(rh.hit.geomID, rh.hit.primID);
            if ((got == RTC_INVALID_GEOMETRY_ID) != (want == RTC_INVALID_GEOMETRY_ID) ||
                (got != RTC_INVALID_GEOMETRY_ID && rh.ray.tfar != t))
                bad++;
        }
    }
    return bad;
}

/* The scene's spheres in an instance moved by (0, 0, 0) and then by (3, 0, 0): the same
 * hits (shifted), instID the instance's geomID, geomID the spheres'. */
static int instance(RTCDevice dev, RTCScene inner, const eb_rays *r)
{
    unsigned iid = RTC_INVALID_GEOMETRY_ID;
    RTCScene outer = eb_shifted(dev, inner, &iid);
    int bad = 0, hits = 0;
    for (size_t i = 0; i < r->n; i += 3) {
        float o[3], d[3], t = 0, n[3];
        eb_rays_get(r, i, o, d);
        uint32_t want = brute(o, d, 0, INFINITY, 0, 3u, &t, n);
        struct RTCRayHit rh;
        eb_trace_mask(outer, (const float[3]){o[0] + 3, o[1], o[2]}, d, 3u, &rh);
        uint32_t got = eb_hit_id(rh.hit.geomID, rh.hit.primID);
        if (want == RTC_INVALID_GEOMETRY_ID || (o[0] + 3) - 3 != o[0])
            continue; /* a miss, or an origin the shift rounds */
        hits++;
        /* the instance's ray is o + 3 - 3 exactly, so the same t within rounding of the
         * transform's arithmetic */
        bad += got != want || rh.hit.instID[0] != iid ||
               fabsf(rh.ray.tfar - t) > 4 * (nextafterf(t, INFINITY) - t);
    }
    rtcReleaseScene(outer);
    return bad + (hits == 0);
}

/* The packet form of the spawn origins on the spheres' geometry, after Embree's own
 * rtcIntersect8: the one-ray form's origin, bit for bit, on every lane that hit a
 * sphere, nothing on the others (misses, invalid lanes, the segments' hits). */
static int packet_spawns(RTCScene sc, RTCGeometry sph, const eb_rays *r, int *lanes)
{
    const uint32_t sentinel = 0x7fc0c0deu;
    int bad = 0;
    *lanes = 0;
    for (size_t b = 0; b + 8 <= r->n; b += 8 * 5) {
        struct RTCRayHit8 rh;
        RTC_ALIGN(32) int valid[8];
        eb_intersect8(sc, r, b, 5, valid, &rh);
        float w[24], out[24];
        for (int j = 0; j < 8; j++) {
            w[j] = rh.hit.Ng_x[j] - 0.5f * rh.ray.dir_x[j];
            w[8 + j] = rh.hit.Ng_y[j] - 0.5f * rh.ray.dir_y[j];
            w[16 + j] = rh.hit.Ng_z[j] - 0.5f * rh.ray.dir_z[j];
        }
        for (int k = 0; k < 24; k++)
            memcpy(&out[k], &sentinel, 4);
        uint32_t got = cylray_embree_spawn_origins(sph, EB_SPHERE_GEOM, valid,
                                                   (struct RTCRayHitN *)&rh, 8, w, out);
        for (int j = 0; j < 8; j++) {
            const int ours =
                valid[j] && rh.hit.geomID[j] == EB_SPHERE_GEOM && isfinite(rh.ray.tfar[j]);
            float o[3] = {rh.ray.org_x[j], rh.ray.org_y[j], rh.ray.org_z[j]};
            float d[3] = {rh.ray.dir_x[j], rh.ray.dir_y[j], rh.ray.dir_z[j]};
            float ng[3] = {rh.hit.Ng_x[j], rh.hit.Ng_y[j], rh.hit.Ng_z[j]};
            float wj[3] = {w[j], w[8 + j], w[16 + j]}, want[3];
            bad += ((got >> j) & 1u) != (uint32_t)ours;
            if (ours) {
                (*lanes)++;
                bad += cylray_embree_spawn_origin(sph, rh.hit.primID[j], o, d, rh.ray.tfar[j],
                                                  ng, wj, want) != 0;
            }
            for (int k = 0; k < 3; k++)
                bad += ours ? memcmp(&out[8 * k + j], &want[k], 4) != 0
                            : memcmp(&out[8 * k + j], &sentinel, 4) != 0;
        }
    }
    return bad + (*lanes == 0);
}

/* The exact reference on camera rays: no unexcused wrong answer; the hit calls on a
 * sphere's hit; secondary rays from the spawn helper never hit their own sphere. */
static void sphere_part(int *bad, const char *what, RTCGeometry geo, unsigned prim, uint32_t id,
                        const eb_sample *x, float t, const float ng[3])
{
    (void)x, (void)t;
    if ((id & EB_SPHERE_BIT) && cylray_embree_hit_part(geo, prim, ng) != CYLRAY_SIDE &&
        (*bad)++ < 3)
        printf("  %s: a sphere's hit part is not the side\n", what);
}

static int exact(const char *what, const eb_geom *g, const eb_ref *ref, const eb_rays *cam,
                 size_t *sec, size_t *self)
{
    eb_err e;
    if (eb_err_init(&e, cam->n))
        return 1;
    static const eb_exact_checks checks = {sphere_part, NULL};
    int bad = eb_exact_secondary(&e, what, g, ref, cam, &checks);
    if (e.wrong || bad)
        printf("  %s: %zu wrong (%zu leaks, %zu phantoms) of %zu against the exact "
               "reference, %zu excused\n",
               what, e.wrong, e.leak, e.phantom, e.rays, e.excused);
    *sec += e.sec, *self += e.self;
    bad += (int)e.wrong;
    eb_err_free(&e);
    return bad;
}

/* What the adapter refuses, and its accessors on a geometry of spheres. */
static int refusals(RTCDevice dev)
{
    int bad = 0;
    cylray_status st = CYLRAY_OK;
    cylray_embree_sphere_desc e = eb_sphere_desc(S, 0, K), x;
    cylray_sphere one[2] = {{{0, 0, 0}, 1}, {{0, 0, 0}, 1}};
    const float nan = NAN;
#define REFUSED(...)                                                                           \
    do {                                                                                       \
        x = e;                                                                                 \
        __VA_ARGS__;                                                                           \
        st = CYLRAY_OK;                                                                        \
        bad += cylray_embree_new_spheres(dev, &x, &st) != NULL || st != CYLRAY_EINVAL;         \
    } while (0)
    REFUSED(x.count = 0);
    REFUSED(x.center = NULL);
    REFUSED(x.radius = NULL);
    REFUSED(x.options = 0x80);
    REFUSED(x.flags = CYLRAY_FACE_FORWARD);
    REFUSED(x.radius = &one[0].center[0]); /* a radius of 0 */
    REFUSED(x.radius_stride = 0, x.radius = &nan);
    REFUSED(x.center = &nan, x.center_stride = 0);
    REFUSED(x.center = one[0].center, x.center_stride = sizeof one[0], x.count = 2,
            x.radius = &one[0].radius, x.radius_stride = sizeof one[0], one[1].radius = -1);
#undef REFUSED
    bad += cylray_embree_new_spheres(NULL, &e, &st) != NULL ||
           cylray_embree_new_spheres(dev, NULL, &st) != NULL;
    RTCGeometry geo = cylray_embree_new_spheres(dev, &e, &st);
    const float up[3] = {0, 0, 1}, z[3] = {0, 0, 0};
    float out[3];
    bad += !geo || st != CYLRAY_OK || !cylray_embree_is_spheres(geo) ||
           cylray_embree_is_cylinders(geo) || cylray_embree_primitives(geo) != S->nsph ||
           cylray_embree_leaf_size(geo) != 0 || cylray_embree_cylinder(geo, 0) == NULL ||
           cylray_embree_cylinder(geo, (unsigned)S->nsph) != NULL ||
           cylray_embree_hit_part(geo, 0, up) != CYLRAY_SIDE ||
           cylray_embree_hit_part(geo, 0, z) != -1 ||
           cylray_embree_hit_part(geo, (unsigned)S->nsph, up) != -1 ||
           cylray_embree_spawn_origin(geo, (unsigned)S->nsph, z, up, 1, up, up, out) != -1;
    cylray_embree_release_geometry(geo);
    e.options = CYLRAY_EMBREE_LEAVES;
    geo = cylray_embree_new_spheres(dev, &e, &st);
    unsigned m = cylray_embree_leaf_size(geo);
    bad += !geo || (m != 4 && m != 8) || cylray_embree_primitives(geo) * m < S->nsph;
    cylray_embree_release_geometry(geo);
    /* a geometry of cylinders is not one of spheres */
    if (S->ns) {
        cylray_embree_desc d = eb_scene_desc(S, 0, K);
        geo = cylray_embree_new_geometry(dev, &d, &st);
        bad += !cylray_embree_is_cylinders(geo) || cylray_embree_is_spheres(geo);
        cylray_embree_release_geometry(geo);
    }
    return bad;
}

/* The scene with and without CYLRAY_EMBREE_NO_ANGLES: the same hits, t and Ng to the
 * bit, a sphere's u = v = 0 with it and a cylinder's v = 0 (its u unchanged).
 * *angled counts the sphere hits whose u or v is not 0 without it. */
static int no_angles(RTCDevice dev, unsigned opt, const eb_rays *r, int *angled)
{
    RTCGeometry ga[2], gn[2];
    RTCScene sa = adapter_scene(dev, opt, NULL, ga);
    RTCScene sn = sa ? adapter_scene(dev, opt | CYLRAY_EMBREE_NO_ANGLES, NULL, gn) : NULL;
    if (!sn) {
        if (sa)
            adapter_free(sa, ga);
        return 1;
    }
    int bad = 0;
    for (size_t i = 0; i < r->n; i++) {
        float o[3], d[3];
        eb_rays_get(r, i, o, d);
        eb_query q;
        eb_query_init(&q, NULL, 0);
        struct RTCRayHit want = eb_rayhit1(o, d, 0, INFINITY), got = want;
        EB_INTERSECT1(sa, &q, &want);
        eb_query_init(&q, NULL, 0);
        EB_INTERSECT1(sn, &q, &got);
        bad += got.hit.geomID != want.hit.geomID;
        if (want.hit.geomID == RTC_INVALID_GEOMETRY_ID)
            continue;
        const int sph = want.hit.geomID == EB_SPHERE_GEOM;
        *angled += sph && (want.hit.u != 0 || want.hit.v != 0);
        bad += !eb_same_hit(&got, &want) || got.hit.v != 0 ||
               got.hit.u != (sph ? 0.0f : want.hit.u);
    }
    adapter_free(sa, ga);
    adapter_free(sn, gn);
    return bad;
}

/* One scene through every ISA and arrangement. */
static void run(RTCDevice dev, const eb_scene *s, eb_rays *r, float *tfar0, uint8_t *valid0,
                size_t *sec, size_t *self)
{
    S = s;
    eb_ref ref;
    if (eb_ref_init(&ref, dev, s)) {
        report(1, "the exact reference's scene");
        return;
    }
    static const eb_variant vs[2] = {EB_SINGLE, EB_LEAF};
    for (int isa = 0; isa < CYLRAY_ISA_COUNT; isa++) {
        if (!(K = cylray_kernels_for((cylray_isa)isa)))
            continue;
        if (prepare_all()) {
            report(1, "prepare");
            continue;
        }
        for (int vi = 0; vi < 2; vi++) {
            eb_variant v = vs[vi];
            LEAVES = v != EB_LEAF                                         ? 0
                     : isa == CYLRAY_ISA_AVX2 || isa == CYLRAY_ISA_AVX512 ? 8
                                                                          : 4;
            char vn[96], what[160];
            snprintf(vn, sizeof vn, "%s %s %s", s->name, cylray_isa_name((cylray_isa)isa),
                     eb_variant_name(v));
            eb_geom g;
            if (eb_geom_build(&g, dev, s, v, K)) {
                snprintf(what, sizeof what, "%s: build", vn);
                report(1, what);
                continue;
            }
            snprintf(what, sizeof what, "%s: leaves of %d", vn, LEAVES);
            report(cylray_embree_leaf_size(g.sph) != (unsigned)LEAVES, what);
            packet_passes(g.scene, vn, 0, NULL, r, tfar0, valid0);
            eb_camera_rays(r, s, W, H);
            snprintf(what, sizeof what, "%s: the exact reference", vn);
            report(exact(vn, &g, &ref, r, sec, self), what);
            eb_geom_free(&g);

            const unsigned opt = v == EB_LEAF ? eb_leaf_options : 0u;
            RTCGeometry geo[2];
            RTCScene sc = adapter_scene(dev, opt | CYLRAY_EMBREE_FILTER, eb_rule_filter, geo);
            if (sc) {
                packet_passes(sc, vn, 1, NULL, r, tfar0, valid0);
                adapter_free(sc, geo);
            }
            sc = adapter_scene(dev, opt | CYLRAY_EMBREE_CONTEXT, NULL, geo);
            if (sc) {
                packet_passes(sc, vn, 1, eb_rule_filter, r, tfar0, valid0);
                eb_camera_rays(r, s, W, H);
                snprintf(what, sizeof what, "%s: the query's filter offered every hit once",
                         vn);
                report(eb_offer_all(&SHAPES, vn, sc, r), what);
                /* Embree 3 built without ray masks ignores them */
                if (rtcGetDeviceProperty(dev, RTC_DEVICE_PROPERTY_RAY_MASK_SUPPORTED)) {
                    snprintf(what, sizeof what, "%s: geometry masks", vn);
                    report(masks(sc, r), what);
                }
                snprintf(what, sizeof what, "%s: in an instance", vn);
                report(instance(dev, sc, r), what);
                int lanes = 0, bad = packet_spawns(sc, geo[1], r, &lanes);
                snprintf(what, sizeof what,
                         "%s: packet spawn origins as the one-ray ones, %d lanes", vn, lanes);
                report(bad, what);
                adapter_free(sc, geo);
            }
            if (!sc)
                report(1, "the filtered geometries' build");
            eb_camera_rays(r, s, W, H);
            int angled = 0, bad = no_angles(dev, opt, r, &angled);
            snprintf(what, sizeof what, "%s: no angles, the rest unchanged (%d with u or v)",
                     vn, angled);
            report(bad + (angled == 0), what);
        }
    }
    LEAVES = 0;
    K = cylray_kernels_best();
    prepare_all();
    report(refusals(dev), "refused descriptions, and the accessors on spheres");
    eb_ref_free(&ref);
}

int main(void)
{
    RTCDevice dev = rtcNewDevice(NULL);
    eb_rays r;
    static float tfar0[W * H];
    static uint8_t valid0[W * H];
    if (!dev || eb_rays_alloc(&r, W * H))
        return 1;
    size_t sec = 0, self = 0;
    eb_scene s;
    /* spheres alone, then spheres among cylinders */
    if (eb_scene_small_spheres(&s, 0, 160, 2024) == 0) {
        snprintf(s.name, sizeof s.name, "spheres");
        run(dev, &s, &r, tfar0, valid0, &sec, &self);
        eb_scene_free(&s);
    } else {
        report(1, "the spheres' scene");
    }
    if (eb_scene_small_spheres(&s, 120, 120, 4048) == 0) {
        snprintf(s.name, sizeof s.name, "mixed");
        run(dev, &s, &r, tfar0, valid0, &sec, &self);
        eb_scene_free(&s);
    } else {
        report(1, "the mixed scene");
    }
    /* the spawn helper's origins: none of the secondary rays leaving a front face hits
     * the surface it leaves */
    char what[96];
    snprintf(what, sizeof what, "%zu of %zu secondary rays hit their own shape", self, sec);
    report(self != 0 || sec == 0, what);
    eb_rays_free(&r);
    rtcReleaseDevice(dev);
    printf("%d passed, %d failed\n", passed, failed);
    return failed != 0 || passed == 0;
}
