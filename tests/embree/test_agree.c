/* SPDX-License-Identifier: MIT */
/* test_agree.c - cylray_embree gives the hits that plain cylray calls give, and the
 * exact reference's: Embree's BVH with the adapter (one cylinder a primitive, split
 * boxes, leaves) at 1, 4, 8 and 16 rays a call, against every cylinder tried in turn;
 * the hit record's u and v against cylray_surface; filter functions (the
 * geometry's and the query's: Embree 3's context filter, Embree 4's argument filter
 * through the adapter's extended context) offered every hit once, in order along each cylinder,
 * with the next hit of a cylinder taken when one is rejected; the spawn helper's
 * origins never hitting their own cylinder again. With the argument "cones", all of it
 * for a geometry of cones (cylray_embree_desc.radius1): tips, cylinders and steep
 * cones among them, the kernels' answers those of cylray_prepare_cone's shapes and the
 * exact ones tests/ref's cone reference's (the rest of a geometry of cones:
 * test_cones.c). */
#include "agree.h"
#include "geom.h"
#include "judge.h"
#include "trace.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { W = 64, H = 64, NCYL = 300 };

static const cylray_kernels *K;
static cylray_prepared PREP[NCYL];
static const eb_scene *S;
static int CONES; /* the scene's segments are cones (S->cone) */
/* Cones: each alone in a leaf, for the variant with leaves, whose leaf query answers a
 * cone as that leaf does (cylinders: as the prepared cylinder) */
static _Alignas(64) cylray_leaf8 LEAF8[NCYL];
static _Alignas(64) cylray_leaf4 LEAF4[NCYL];
static int LEAVES; /* 0: the prepared shapes' kernel; 4 or 8: the one-cone leaves */

/* Every hit of cylinder i on the ray in [tmin, tmax], in order of t, through the
 * 4-wide kernel: the first, then the next beyond it. */
static int all_hits(size_t i, const float o[3], const float d[3], float tmin, float tmax,
                    float t[4], float n[4][3])
{
    CYLRAY_ALIGN(16) cylray_ray4 r;
    CYLRAY_ALIGN(16) cylray_hit4 h;
    int m = 0;
    while (LEAVES && m < 4) {
        cylray_ray1 r1 = {{o[0], o[1], o[2]}, {d[0], d[1], d[2]}, tmin, tmax};
        cylray_hit1 h1;
        if (!(LEAVES == 8 ? K->leaf_intersect8(&LEAF8[i], &r1, &h1, CYLRAY_NORMAL)
                          : K->leaf_intersect4(&LEAF4[i], &r1, &h1, CYLRAY_NORMAL)))
            return m;
        t[m] = h1.t;
        memcpy(n[m++], h1.n, sizeof h1.n);
        tmin = nextafterf(h1.t, INFINITY);
    }
    while (m < 4) {
        for (int j = 0; j < 4; j++) {
            r.ox[j] = o[0], r.oy[j] = o[1], r.oz[j] = o[2];
            r.dx[j] = d[0], r.dy[j] = d[1], r.dz[j] = d[2];
            r.tmin[j] = tmin, r.tmax[j] = tmax;
        }
        if (!K->intersect4(&PREP[i], &r, &h, 1, CYLRAY_NORMAL))
            break;
        t[m] = h.t[0];
        n[m][0] = h.nx[0], n[m][1] = h.ny[0], n[m][2] = h.nz[0];
        m++;
        tmin = nextafterf(h.t[0], INFINITY);
    }
    return m;
}

/* The closest hit over every cylinder, one at a time; with `filtered`, the closest the
 * filter rule (eb_rejected) accepts. */
static uint32_t brute(const float o[3], const float d[3], float tmin, float tmax, int filtered,
                      float *t, float nrm[3])
{
    uint32_t best = RTC_INVALID_GEOMETRY_ID;
    for (uint32_t i = 0; i < S->ns; i++) {
        float ts[4], ns[4][3];
        int m = all_hits(i, o, d, tmin, tmax, ts, ns);
        for (int j = 0; j < m; j++) {
            if (filtered && eb_rejected(i, ns[j], d))
                continue;
            /* a hit at exactly tmax counts in cylray, so an equal t would replace; keep
             * the first, and compare t only where two cylinders tie */
            if (best == RTC_INVALID_GEOMETRY_ID || ts[j] < *t) {
                best = i;
                *t = ts[j];
                memcpy(nrm, ns[j], sizeof ns[j]);
            }
            break;
        }
    }
    return best;
}

/* u and v of a hit: those cylray_surface gives at the hit point o + t d (the part from
 * the normal: a disc's is the axis), within the rounding of that point and of the
 * adapter's azimuth; any v at the centre of a disc. */
static int uv_ok(uint32_t prim, const float o[3], const float d[3], float t, const float ng[3],
                 float u, float v)
{
    const float *p0 = S->p0[prim], *p1 = S->p1[prim];
    double a[3], aa = 0;
    for (int k = 0; k < 3; k++)
        a[k] = (double)p1[k] - p0[k], aa += a[k] * a[k];
    double cap = (ng[0] * a[0] + ng[1] * a[1] + ng[2] * a[2]) / sqrt(aa);
    /* halfway between the side's axial component (a cone's: -(r1 - r0) / slant
     * length) and the discs' +-1 */
    double dr = CONES ? (double)S->cone[prim].r1 - S->cone[prim].r0 : 0;
    double ns = -dr / sqrt(aa + dr * dr);
    int32_t part = cap > 0.5 * (1 + ns)   ? CYLRAY_CAP_HI
                   : cap < 0.5 * (ns - 1) ? CYLRAY_CAP_LO
                                          : CYLRAY_SIDE;
    float p[3] = {o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2]}, uv[2] = {-1, -1};
    float dpdu[3], dpdv[3];
    cylray_surface(&PREP[prim], p, part, uv, dpdu, dpdv);
    if (part != CYLRAY_SIDE ? u != uv[0] : fabsf(u - uv[0]) > 1e-5f)
        return 0;
    if (!(v >= 0 && v < 1))
        return 0;
    /* the radial distance: |dpdv| / 2pi on a disc, R on the side */
    double rho = sqrt((double)dpdv[0] * dpdv[0] + (double)dpdv[1] * dpdv[1] +
                      (double)dpdv[2] * dpdv[2]) /
                 (2 * 3.14159265358979323846);
    if (rho < 1e-3 * S->radius)
        return 1;
    double dv = fabs((double)v - uv[1]);
    return fmin(dv, 1 - dv) <= 1e-4;
}

/* Whether this pass's variant gives the kernel's t to the bit (hit_ok's tolerance). */
static int EXACT_T;

/* A hit Embree+cylray records for ray i of r against brute()'s: the same t (with one
 * cylinder a query's, the same bits, and the same normal), and u, v as uv_ok wants. */
static int hit_ok(const eb_rays *r, size_t i, const float o[3], const float d[3], uint32_t got,
                  uint32_t want, float t, const float n[3])
{
    if (got >= S->ns)
        return 0;
    float ng[3] = {r->ngx[i], r->ngy[i], r->ngz[i]};
    double tol = EXACT_T ? 0 : 2 * (nextafterf(fabsf(t), INFINITY) - fabsf(t));
    int ok = fabs((double)r->tfar[i] - t) <= tol;
    if (ok && got == want)
        ok = fabsf(ng[0] - n[0]) <= 1e-6f && fabsf(ng[1] - n[1]) <= 1e-6f &&
             fabsf(ng[2] - n[2]) <= 1e-6f;
    if (ok)
        ok = uv_ok(got, o, d, r->tfar[i], ng, r->u[i], r->v[i]);
    return ok;
}

/* The shapes as the shared checks walk them: the cylinders (or cones), geometry 0, each
 * answered as its index; every third camera ray offered. */
static size_t count(void)
{
    return S->ns;
}

static uint32_t id_of(size_t k)
{
    return (uint32_t)k;
}

static const eb_shapes SHAPES = {count, id_of, all_hits, 3};

/* The adapter's hit calls on a hit of prim at t: the part read from Ng is the part the
 * kernel gives for the same hit (where it finds the same t), and the point and surface
 * are cylray's own for that part. 0 when they agree. */
static int hit_calls(RTCGeometry geo, uint32_t prim, const float o[3], const float d[3],
                     float t, const float ng[3])
{
    CYLRAY_ALIGN(16) cylray_ray4 r;
    CYLRAY_ALIGN(16) cylray_hit4 h;
    for (int j = 0; j < 4; j++) {
        r.ox[j] = o[0], r.oy[j] = o[1], r.oz[j] = o[2];
        r.dx[j] = d[0], r.dy[j] = d[1], r.dz[j] = d[2];
        r.tmin[j] = 0, r.tmax[j] = INFINITY;
    }
    int part = cylray_embree_hit_part(geo, prim, ng);
    if (part < 0)
        return 1;
    if (!K->intersect4(&PREP[prim], &r, &h, 1, CYLRAY_NORMAL) || h.t[0] != t)
        return 0; /* another t (a leaf's query): no kernel part to hold it to */
    if (part != (h.part[0] & CYLRAY_PART_MASK))
        return 1;
    float p[3], err = -1, q[3], e, p2[3], uv[2], uv2[2], du[3], dv[3], du2[3], dv2[3];
    cylray_hit_point_normal(&PREP[prim], o, d, t, part, ng, q, &e);
    if (cylray_embree_hit_point(geo, prim, o, d, t, ng, p, &err) || memcmp(p, q, sizeof p) ||
        err != e)
        return 1;
    cylray_surface(&PREP[prim], q, part, uv2, du2, dv2);
    return cylray_embree_surface(geo, prim, o, d, t, ng, p2, uv, du, dv) != part ||
           memcmp(p2, q, sizeof q) || memcmp(uv, uv2, sizeof uv) ||
           memcmp(du, du2, sizeof du) || memcmp(dv, dv2, sizeof dv);
}

/* The adapter's hit calls on an exact hit agree with cylray's (hit_calls). */
static void exact_hit(int *bad, const char *what, RTCGeometry geo, unsigned prim, uint32_t id,
                      const eb_sample *x, float t, const float ng[3])
{
    (void)id;
    if (hit_calls(geo, prim, x->o, x->d, t, ng) && (*bad)++ < 3)
        printf("  %s: the hit calls disagree with cylray's on prim %u at t %.9g\n", what, prim,
               t);
}

/* The side form, the side being w's: the same origin, bit for bit, where w is clearly on
 * one side. */
static void side_form(int *bad, const char *what, RTCGeometry geo, unsigned prim,
                      const eb_sample *x, float t, const float ng[3], const float w[3],
                      const float org[3])
{
    float c = (w[0] * ng[0] + w[1] * ng[1] + w[2] * ng[2]), org2[3];
    if (cylray_embree_spawn_origin_side(geo, prim, x->o, x->d, t, ng, c > 0, w, org2) ||
        (fabsf(c) > 1e-3f && memcmp(org, org2, sizeof org2) != 0)) {
        if ((*bad)++ < 3)
            printf("  %s: the side form's origin differs\n", what);
    }
}

/* The exact reference: the scene's first hit in binary128 (tests/ref), each answer
 * judged as the comparison's tables judge it; no unexcused wrong answer. Secondary
 * rays from the spawn helper must not hit their own cylinder. */
static int exact(const char *what, const eb_geom *g, const eb_ref *ref, const eb_rays *cam)
{
    eb_err e;
    if (eb_err_init(&e, cam->n))
        return 1;
    static const eb_exact_checks checks = {exact_hit, side_form};
    int bad = eb_exact_secondary(&e, what, g, ref, cam, &checks);
    if (e.wrong || e.self || bad)
        printf("  %s: %zu wrong of %zu against the exact reference, %zu of %zu secondary "
               "rays hit their own cylinder\n",
               what, e.wrong, e.rays, e.self, e.sec);
    bad += (int)(e.wrong + e.self);
    eb_err_free(&e);
    return bad;
}

/* The same rays with every other one turned around from beyond the scene, and the
 * context told they are incoherent: the packets then mix direction octants, and
 * cylray_embree_intersectN / occludedN trace them one ray a call. */
static void mix_rays(eb_rays *r)
{
    const double dist = 2 * sqrt((double)(S->look[0] - S->eye[0]) * (S->look[0] - S->eye[0]) +
                                 (double)(S->look[1] - S->eye[1]) * (S->look[1] - S->eye[1]) +
                                 (double)(S->look[2] - S->eye[2]) * (S->look[2] - S->eye[2]));
    r->incoherent = 1;
    for (size_t i = 1; i < r->n; i += 2) {
        r->ox[i] = (float)(r->ox[i] + dist * r->dx[i]);
        r->oy[i] = (float)(r->oy[i] + dist * r->dy[i]);
        r->oz[i] = (float)(r->oz[i] + dist * r->dz[i]);
        r->dx[i] = -r->dx[i], r->dy[i] = -r->dy[i], r->dz[i] = -r->dz[i];
    }
}

/* Each answer in r against brute() and hit_ok. */
static int check_pass(const char *what, const eb_rays *r, const float *tfar0,
                      const uint8_t *valid0, int occ, int filtered)
{
    static const eb_answers answers = {brute, hit_ok};
    return eb_check_answers(what, r, tfar0, valid0, occ, filtered, &answers);
}

/* The shared packet passes (eb_packet_passes) on this test's camera, rays and check. */
static void packet_passes(RTCScene sc, const char *vn, int exact_t, int filtered,
                          RTCFilterFunctionN query_filter, eb_rays *r, float *tfar0,
                          uint8_t *valid0, int *passed, int *failed)
{
    const eb_passes p = {S, W, H, mix_rays, check_pass};
    EXACT_T = exact_t;
    eb_packet_passes(&p, sc, vn, filtered, query_filter, r, tfar0, valid0, passed, failed);
}

/* The packet forms of the spawn origins against the one-ray forms, lane by lane, after
 * Embree's own packet call of 8 rays: the same origins bit for bit on the lanes that hit
 * this geometry, and nothing written on the others (an invalid lane, a miss, a hit on
 * another geometry: a triangle beside the cylinders takes some rays). Returns the
 * disagreements; *lanes counts the lanes compared. */
static int packet_spawns(RTCDevice dev, RTCGeometry geo, const eb_rays *r, int *lanes)
{
    RTCScene sc = rtcNewScene(dev);
    RTCGeometry tri = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
    float *v = rtcSetNewGeometryBuffer(tri, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                       3 * sizeof(float), 3);
    unsigned *ix = rtcSetNewGeometryBuffer(tri, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                           3 * sizeof(unsigned), 1);
    /* a large triangle through the camera's view, so that some lanes hit it first */
    const float tv[9] = {-1e3f, -1e3f, 0, 1e3f, -1e3f, 0, 0, 1e3f, 0};
    memcpy(v, tv, sizeof tv);
    ix[0] = 0, ix[1] = 1, ix[2] = 2;
    rtcSetGeometryMask(tri, 0xffffffffu);
    rtcCommitGeometry(tri);
    unsigned gid = rtcAttachGeometry(sc, geo), tid = rtcAttachGeometry(sc, tri);
    rtcReleaseGeometry(tri);
    rtcCommitScene(sc);
    const uint32_t sentinel = 0x7fc0c0deu;
    int bad = 0, theirs = 0, tris = 0;
    *lanes = 0;
    for (size_t b = 0; b + 8 <= r->n; b += 8 * 7) {
        struct RTCRayHit8 rh;
        RTC_ALIGN(32) int valid[8];
        eb_intersect8(sc, r, b, 3, valid, &rh);
        float w[24], out[2][24];
        int outward[8];
        for (int j = 0; j < 8; j++) {
            /* a reflection-like direction on even lanes, a transmission-like one on odd */
            float sg = j & 1 ? -1.0f : 1.0f;
            w[j] = sg * rh.hit.Ng_x[j] + 0.3f * rh.ray.dir_x[j];
            w[8 + j] = sg * rh.hit.Ng_y[j] + 0.3f * rh.ray.dir_y[j];
            w[16 + j] = sg * rh.hit.Ng_z[j] + 0.3f * rh.ray.dir_z[j];
            outward[j] = j % 3 != 1;
        }
        for (int k = 0; k < 48; k++)
            memcpy(&out[k / 24][k % 24], &sentinel, 4);
        uint32_t got[2] = {cylray_embree_spawn_origins(geo, gid, valid,
                                                       (struct RTCRayHitN *)&rh, 8, w, out[0]),
                           cylray_embree_spawn_origins_side(geo, gid, valid,
                                                            (struct RTCRayHitN *)&rh, 8,
                                                            outward, w, out[1])};
        for (int j = 0; j < 8; j++) {
            const int ours = valid[j] && rh.hit.geomID[j] == gid && isfinite(rh.ray.tfar[j]);
            theirs += valid[j] && rh.hit.geomID[j] == tid;
            float o[3] = {rh.ray.org_x[j], rh.ray.org_y[j], rh.ray.org_z[j]};
            float d[3] = {rh.ray.dir_x[j], rh.ray.dir_y[j], rh.ray.dir_z[j]};
            float ng[3] = {rh.hit.Ng_x[j], rh.hit.Ng_y[j], rh.hit.Ng_z[j]};
            float wj[3] = {w[j], w[8 + j], w[16 + j]}, want[2][3];
            if (ours) {
                (*lanes)++;
                bad += cylray_embree_spawn_origin(geo, rh.hit.primID[j], o, d, rh.ray.tfar[j],
                                                  ng, wj, want[0]) != 0;
                bad +=
                    cylray_embree_spawn_origin_side(geo, rh.hit.primID[j], o, d, rh.ray.tfar[j],
                                                    ng, outward[j], wj, want[1]) != 0;
            }
            for (int f = 0; f < 2; f++) {
                bad += ((got[f] >> j) & 1u) != (uint32_t)ours;
                for (int k = 0; k < 3; k++)
                    bad += ours ? memcmp(&out[f][8 * k + j], &want[f][k], 4) != 0
                                : memcmp(&out[f][8 * k + j], &sentinel, 4) != 0;
            }
        }
        tris += theirs;
    }
    rtcReleaseScene(sc);
    /* the test means something only if both kinds of lanes occurred */
    return bad + (*lanes == 0) + (tris == 0);
}

int main(int argc, char **argv)
{
    eb_scene s;
    CONES = argc > 1 && !strcmp(argv[1], "cones");
    if (CONES ? eb_scene_small_cones(&s, NCYL, 12345) : eb_scene_small(&s, NCYL, 12345)) {
        printf("scene failed\n");
        return 1;
    }
    S = &s;
    K = cylray_kernels_best();
    for (size_t i = 0; i < s.ns; i++) {
        uint32_t id = (uint32_t)i;
        if ((CONES ? cylray_prepare_cone(&PREP[i], &s.cone[i])
                   : cylray_prepare(&PREP[i], &s.cyl[i])) != CYLRAY_OK ||
            (CONES && (cylray_leaf_prepare_cones8(&LEAF8[i], &s.cone[i], &id, 1) ||
                       cylray_leaf_prepare_cones4(&LEAF4[i], &s.cone[i], &id, 1))))
            return 1;
    }
    RTCDevice dev = rtcNewDevice(NULL);
    eb_rays r;
    eb_ref ref;
    if (!dev || eb_rays_alloc(&r, W * H) || eb_ref_init(&ref, dev, &s))
        return 1;
    static float tfar0[W * H];
    static uint8_t valid0[W * H];
    int passed = 0, failed = 0;
#define REPORT(bad, ...)                                                                       \
    do {                                                                                       \
        char what_[128];                                                                       \
        snprintf(what_, sizeof what_, __VA_ARGS__);                                            \
        printf("%s %s (%d disagreements)\n", (bad) ? "FAIL" : "ok  ", what_, (bad));           \
        (bad) ? failed++ : passed++;                                                           \
    } while (0)

    /* every path this CPU runs: the leaves are 4 wide on the scalar and SSE4.1 paths,
     * 8 wide on the others */
    for (int isa = 0; isa < CYLRAY_ISA_COUNT; isa++) {
        const cylray_kernels *kisa = cylray_kernels_for((cylray_isa)isa);
        if (!kisa)
            continue;
        K = kisa;
        for (int v = EB_SINGLE; v < EB_NVARIANTS; v++) {
            char vn[64];
            snprintf(vn, sizeof vn, "%s %s", cylray_isa_name((cylray_isa)isa),
                     eb_variant_name((eb_variant)v));
            eb_geom g;
            if (eb_geom_build(&g, dev, &s, (eb_variant)v, K)) {
                REPORT(1, "%s: build", vn);
                continue;
            }
            /* the small scene's long cylinders must get split boxes (or the split variant
         * tests nothing new) */
            if (v == EB_SPLIT)
                REPORT(g.nprim <= s.ns, "%s: %zu boxes for %zu cylinders", vn, g.nprim, s.ns);
            unsigned m = cylray_embree_leaf_size(g.cyl),
                     want = v != EB_LEAF                                         ? 0
                            : isa == CYLRAY_ISA_AVX2 || isa == CYLRAY_ISA_AVX512 ? 8
                                                                                 : 4;
            REPORT(m != want || (m && g.nprim * m < s.ns), "%s: leaves of %u, %zu primitives",
                   vn, m, g.nprim);
            LEAVES = CONES ? (int)m : 0;
            packet_passes(g.scene, vn, v != EB_LEAF, 0, NULL, &r, tfar0, valid0, &passed,
                          &failed);
            eb_camera_rays(&r, &s, W, H);
            int bad = exact(vn, &g, &ref, &r);
            REPORT(bad, "%s: the exact reference, and the spawn helper's secondary rays", vn);
            eb_geom_free(&g);

            /* the same geometry with filters */
            cylray_embree_desc d =
                eb_scene_desc(&s, eb_variant_options((eb_variant)v) | CYLRAY_EMBREE_FILTER, K);
            RTCGeometry geo = cylray_embree_new_geometry(dev, &d, NULL);
            if (!geo) {
                REPORT(1, "%s: build with filters", vn);
                continue;
            }
            rtcSetGeometryIntersectFilterFunction(geo, eb_rule_filter);
            rtcSetGeometryOccludedFilterFunction(geo, eb_rule_filter);
            RTCScene sc = eb_scene_of(dev, geo, NULL);
            packet_passes(sc, vn, v != EB_LEAF, 1, NULL, &r, tfar0, valid0, &passed, &failed);
            rtcReleaseScene(sc);
            cylray_embree_release_geometry(geo);

            /* the same rule as the query's filter, as a renderer passes it (query.h:
             * Embree 3's context filter; Embree 4's argument filter, which reaches the
             * adapter through the extended context only), the geometry without one */
            d.options = (d.options & ~CYLRAY_EMBREE_FILTER) | CYLRAY_EMBREE_CONTEXT;
            geo = cylray_embree_new_geometry(dev, &d, NULL);
            if (!geo) {
                REPORT(1, "%s: build with the extended context", vn);
                continue;
            }
            sc = eb_scene_of(dev, geo, NULL);
            packet_passes(sc, vn, v != EB_LEAF, 1, eb_rule_filter, &r, tfar0, valid0, &passed,
                          &failed);
            rtcReleaseScene(sc);
            cylray_embree_release_geometry(geo);

            /* without FILTER: the query's filter is still called */
            geo = cylray_embree_new_geometry(dev, &d, NULL);
            if (!geo) {
                REPORT(1, "%s: build with the extended context", vn);
                continue;
            }
            sc = eb_scene_of(dev, geo, NULL);
            eb_camera_rays(&r, &s, W, H);
            bad = eb_offer_all(&SHAPES, vn, sc, &r);
            REPORT(bad, "%s: the query's filter offered every hit once", vn);
            rtcReleaseScene(sc);
            cylray_embree_release_geometry(geo);
        }
    }
    K = cylray_kernels_best();
    LEAVES = 0;

    /* what the adapter refuses */
    {
        cylray_embree_desc d = eb_scene_desc(&s, 0, K);
        cylray_status st = CYLRAY_OK;
        int bad = 0;
        d.flags = CYLRAY_FACE_FORWARD;
        bad += cylray_embree_new_geometry(dev, &d, &st) != NULL || st != CYLRAY_EINVAL;
        d.flags = 0, d.options = 0x80;
        bad += cylray_embree_new_geometry(dev, &d, &st) != NULL || st != CYLRAY_EINVAL;
        d.options = 0, d.p1 = d.p0; /* p0 == p1 */
        bad += cylray_embree_new_geometry(dev, &d, &st) != NULL || st != CYLRAY_EINVAL;
        d = eb_scene_desc(&s, 0, K);
        d.count = 0;
        bad += cylray_embree_new_geometry(dev, &d, &st) != NULL || st != CYLRAY_EINVAL;
        RTCGeometry tri = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
        bad += cylray_embree_is_cylinders(tri) || cylray_embree_primitives(tri) != 0 ||
               cylray_embree_leaf_size(tri) != 0;
        const float up[3] = {0, 0, 1};
        bad += cylray_embree_hit_part(tri, 0, up) != -1;
        rtcReleaseGeometry(tri);
        /* split boxes by default: as many primitives as with CYLRAY_EMBREE_SPLIT */
        d = eb_scene_desc(&s, CYLRAY_EMBREE_SPLIT, K);
        RTCGeometry geo = cylray_embree_new_geometry(dev, &d, &st);
        size_t nsplit = cylray_embree_primitives(geo);
        cylray_embree_release_geometry(geo);
        d = eb_scene_desc(&s, 0, K);
        geo = cylray_embree_new_geometry(dev, &d, &st);
        bad += nsplit <= s.ns || cylray_embree_primitives(geo) != nsplit;
        cylray_embree_release_geometry(geo);
        /* leaves asked for where split boxes would cut a shape: split boxes, unless
         * no splitting is asked for as well */
        d = eb_scene_desc(&s, CYLRAY_EMBREE_LEAVES, K);
        geo = cylray_embree_new_geometry(dev, &d, &st);
        bad += !geo || cylray_embree_leaf_size(geo) != 0 ||
               cylray_embree_primitives(geo) != nsplit;
        cylray_embree_release_geometry(geo);
        d = eb_scene_desc(&s, CYLRAY_EMBREE_LEAVES | CYLRAY_EMBREE_NO_SPLIT, K);
        geo = cylray_embree_new_geometry(dev, &d, &st);
        bad +=
            !geo || cylray_embree_leaf_size(geo) == 0 || cylray_embree_primitives(geo) >= s.ns;
        cylray_embree_release_geometry(geo);
        d = eb_scene_desc(&s, CYLRAY_EMBREE_NO_SPLIT, K);
        geo = cylray_embree_new_geometry(dev, &d, &st);
        float z[3] = {0, 0, 0}, one[3] = {1, 0, 0}, out[3];
        bad +=
            !geo || st != CYLRAY_OK || !cylray_embree_is_cylinders(geo) ||
            cylray_embree_primitives(geo) != s.ns || cylray_embree_leaf_size(geo) != 0 ||
            cylray_embree_cylinder(geo, (unsigned)s.ns) != NULL ||
            cylray_embree_cylinder(geo, 0) == NULL ||
            cylray_embree_spawn_origin(geo, (unsigned)s.ns, z, one, 1, one, one, out) != -1 ||
            cylray_embree_spawn_origin(geo, 0, z, one, 1, z, one, out) != -1 ||
            cylray_embree_spawn_origin_side(geo, 0, z, one, 1, z, 1, one, out) != -1 ||
            cylray_embree_hit_part(geo, (unsigned)s.ns, one) != -1 ||
            cylray_embree_hit_part(geo, 0, z) != -1 ||
            cylray_embree_hit_point(geo, 0, z, one, 1, z, out, NULL) != -1 ||
            cylray_embree_surface(geo, (unsigned)s.ns, z, one, 1, one, out, NULL, NULL, NULL) !=
                -1;
        cylray_embree_release_geometry(geo);
        cylray_embree_release_geometry(NULL);
        REPORT(bad, "refused input, and the accessors");
        uint32_t none = cylray_embree_spawn_origins(NULL, 0, NULL, NULL, 8, NULL, NULL);
        d = eb_scene_desc(&s, 0, K);
        geo = cylray_embree_new_geometry(dev, &d, &st);
        rtcCommitGeometry(geo);
        int lanes = 0;
        eb_agree_rays(&r, S, W, H, tfar0, valid0);
        bad = (int)none + packet_spawns(dev, geo, &r, &lanes);
        cylray_embree_release_geometry(geo);
        REPORT(bad, "packet spawn origins as the one-ray ones, %d lanes", lanes);
    }

    eb_ref_free(&ref);
    eb_rays_free(&r);
    rtcReleaseDevice(dev);
    eb_scene_free(&s);
    printf("%d passed, %d failed\n", passed, failed);
    return failed != 0 || passed == 0;
}
