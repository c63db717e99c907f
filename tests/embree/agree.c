/* SPDX-License-Identifier: MIT */
/* agree.c - what every shape's agreement test shares (agree.h). */
#include "agree.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

int eb_rejected(uint32_t prim, const float n[3], const float d[3])
{
    return prim % 2 == 0 && n[0] * d[0] + n[1] * d[1] + n[2] * d[2] < 0;
}

void eb_rule_filter(const struct RTCFilterFunctionNArguments *a)
{
    unsigned N = a->N;
    const float *ray = (const float *)a->ray, *hit = (const float *)a->hit;
    for (unsigned i = 0; i < N; i++) {
        if (!a->valid[i])
            continue;
        float n[3] = {hit[0 * N + i], hit[1 * N + i], hit[2 * N + i]};
        float d[3] = {ray[4 * N + i], ray[5 * N + i], ray[6 * N + i]};
        uint32_t prim = ((const uint32_t *)hit)[5 * N + i];
        /* the ray's tfar is the hit's t while the filter runs, as with Embree's own */
        float t = ray[8 * N + i];
        if (eb_rejected(prim, n, d) || !(t >= 0))
            a->valid[i] = 0;
    }
}

/* The hits offered to record_filter, each as an answer's id and its t. */
static struct {
    uint32_t id[64];
    float t[64];
    int n;
} OFFERED;

/* The query's filter that rejects every hit and records each one offered. */
static void record_filter(const struct RTCFilterFunctionNArguments *a)
{
    const float *ray = (const float *)a->ray, *hit = (const float *)a->hit;
    for (unsigned i = 0; i < a->N; i++)
        if (a->valid[i]) {
            const uint32_t *h = (const uint32_t *)hit;
            if (OFFERED.n < 64) {
                OFFERED.id[OFFERED.n] = eb_hit_id(h[6 * a->N + i], h[5 * a->N + i]);
                OFFERED.t[OFFERED.n++] = ray[8 * a->N + i];
            }
            a->valid[i] = 0;
        }
}

int eb_offer_all(const eb_shapes *sh, const char *what, RTCScene scene, const eb_rays *r)
{
    int bad = 0;
    for (size_t i = 0; i < r->n; i += sh->offer_step) {
        float o[3], d[3];
        eb_rays_get(r, i, o, d);
        for (int occ = 0; occ < 2; occ++) {
            eb_query q;
            eb_query_init(&q, record_filter, 0);
            OFFERED.n = 0;
            struct RTCRayHit rh = eb_rayhit1(o, d, 0, INFINITY);
            if (occ)
                EB_OCCLUDED1(scene, &q, &rh.ray);
            else
                EB_INTERSECT1(scene, &q, &rh);
            int fine = rh.ray.tfar == INFINITY && rh.hit.geomID == RTC_INVALID_GEOMETRY_ID;
            int want = 0;
            for (size_t k = 0; k < sh->count(); k++) {
                float ts[4], ns[4][3];
                int m = sh->all_hits(k, o, d, 0, INFINITY, ts, ns);
                want += m;
                for (int j = 0; j < m; j++) {
                    int seen = 0;
                    for (int x = 0; x < OFFERED.n; x++)
                        seen += OFFERED.id[x] == sh->id_of(k) && OFFERED.t[x] == ts[j];
                    fine &= seen == 1;
                }
            }
            fine &= OFFERED.n == want;
            if (!fine && bad++ < 5)
                printf("  %s ray %zu %s: %d hits offered, %d exist%s\n", what, i,
                       occ ? "occluded" : "intersect", OFFERED.n, want,
                       rh.ray.tfar == INFINITY ? "" : ", and the ray was changed");
        }
    }
    return bad;
}

RTCScene eb_scene_of(RTCDevice dev, RTCGeometry g, unsigned *id)
{
    rtcCommitGeometry(g);
    RTCScene sc = rtcNewScene(dev);
    const unsigned got = rtcAttachGeometry(sc, g);
    if (id)
        *id = got;
    rtcCommitScene(sc);
    return sc;
}

RTCScene eb_shifted(RTCDevice dev, RTCScene inner, unsigned *iid)
{
    RTCScene outer = rtcNewScene(dev);
    RTCGeometry inst = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_INSTANCE);
    rtcSetGeometryInstancedScene(inst, inner);
    const float xf[12] = {1, 0, 0, 0, 1, 0, 0, 0, 1, 3, 0, 0};
    rtcSetGeometryTransform(inst, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, xf);
    rtcSetGeometryMask(inst, 0xffffffffu);
    rtcCommitGeometry(inst);
    if (*iid == RTC_INVALID_GEOMETRY_ID)
        *iid = rtcAttachGeometry(outer, inst);
    else
        rtcAttachGeometryByID(outer, inst, *iid);
    rtcReleaseGeometry(inst);
    rtcCommitScene(outer);
    return outer;
}

void eb_trace_mask(RTCScene scene, const float o[3], const float d[3], unsigned mask,
                   struct RTCRayHit *rh)
{
    eb_query q;
    eb_query_init(&q, NULL, 0);
    *rh = eb_rayhit1(o, d, 0, INFINITY);
    rh->ray.mask = mask;
    EB_INTERSECT1(scene, &q, rh);
}

void eb_intersect8(RTCScene sc, const eb_rays *r, size_t b, int off, int valid[8],
                   struct RTCRayHit8 *rh)
{
    memset(rh, 0, sizeof *rh);
    for (int j = 0; j < 8; j++) {
        size_t i = b + (size_t)j;
        rh->ray.org_x[j] = r->ox[i], rh->ray.org_y[j] = r->oy[i], rh->ray.org_z[j] = r->oz[i];
        rh->ray.dir_x[j] = r->dx[i], rh->ray.dir_y[j] = r->dy[i], rh->ray.dir_z[j] = r->dz[i];
        rh->ray.tnear[j] = 0, rh->ray.tfar[j] = INFINITY, rh->ray.mask[j] = ~0u;
        rh->hit.geomID[j] = RTC_INVALID_GEOMETRY_ID;
        valid[j] = j == off ? 0 : -1;
    }
#if CYLRAY_EMBREE_RTC_MAJOR >= 4
    rtcIntersect8(valid, sc, rh, NULL);
#else
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    rtcIntersect8(valid, sc, &ctx, rh);
#endif
}

int eb_skipped_lane(const char *what, const eb_rays *r, size_t i, const float *tfar0,
                    const uint8_t *valid0, int *bad)
{
    if (valid0[i])
        return 0;
    if (r->tfar[i] != tfar0[i] && (*bad)++ < 5)
        printf("  %s ray %zu: invalid lane written\n", what, i);
    return 1;
}

void eb_occlusion(const char *what, const eb_rays *r, size_t i, const float *tfar0,
                  uint32_t want, int *bad)
{
    int got = r->tfar[i] == -INFINITY;
    if ((got != (want != RTC_INVALID_GEOMETRY_ID) || (!got && r->tfar[i] != tfar0[i])) &&
        (*bad)++ < 5)
        printf("  %s ray %zu: occluded %d, cylray says %d\n", what, i, got,
               want != RTC_INVALID_GEOMETRY_ID);
}

/* Camera ray i solved exactly (*x) and traced through scene, the answer judged into e
 * against the exact one: its id, *t and ng. */
static uint32_t exact_first(eb_err *e, const eb_ref *ref, RTCScene scene, const eb_rays *cam,
                            size_t i, eb_sample *x, float *t, float ng[3])
{
    eb_rays_get(cam, i, x->o, x->d);
    x->tmin = 0, x->tmax = INFINITY, x->pixel = SIZE_MAX;
    eb_sample_solve(x, ref);
    uint32_t id = eb_trace1(scene, x->o, x->d, 0, INFINITY, t, ng);
    eb_judge(e, ref, x, id, *t, ng);
    return id;
}

/* The secondary rays from a hit with normal ng on a ray of direction d: a reflection
 * (w[0]) and a refraction-like continuation (w[1]). */
static void continuations(const float ng[3], const float d[3], float w[2][3])
{
    float n[3];
    eb_facing_normal(ng, d, n);
    float dn = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
    for (int k = 0; k < 3; k++)
        w[0][k] = d[k] - 2 * dn * n[k], w[1][k] = d[k];
}

int eb_exact_secondary(eb_err *e, const char *what, const eb_geom *g, const eb_ref *ref,
                       const eb_rays *cam, const eb_exact_checks *c)
{
    int bad = 0;
    for (size_t i = 0; i < cam->n; i++) {
        eb_sample x;
        float t = 0, ng[3] = {0, 0, 0};
        uint32_t id = exact_first(e, ref, g->scene, cam, i, &x, &t, ng);
        if (id == RTC_INVALID_GEOMETRY_ID || id != x.xid || !x.xhit)
            continue;
        unsigned prim;
        RTCGeometry geo = eb_geom_of(g, id, &prim);
        if (c->hit)
            c->hit(&bad, what, geo, prim, id, &x, t, ng);
        float w[2][3], org[3];
        continuations(ng, x.d, w);
        for (int s = 0; s < 2; s++) {
            if (cylray_embree_spawn_origin(geo, prim, x.o, x.d, t, ng, w[s], org) ||
                !isfinite(org[0]) || !isfinite(org[1]) || !isfinite(org[2])) {
                if (bad++ < 3)
                    printf("  %s: no usable spawn origin on %#x\n", what, id);
                continue;
            }
            float st, sn[3];
            uint32_t hit = eb_trace1(g->scene, org, w[s], 0, INFINITY, &st, sn);
            eb_judge_secondary(e, &x, w[s], hit);
            if (c->secondary)
                c->secondary(&bad, what, geo, prim, &x, t, ng, w[s], org);
        }
    }
    return bad;
}

/* An answer's id as a failure shows it. */
static void id_text(char buf[24], uint32_t id)
{
    if (id == RTC_INVALID_GEOMETRY_ID)
        snprintf(buf, 24, "none");
    else
        snprintf(buf, 24, "%s %u", id & EB_SPHERE_BIT ? "sphere" : "prim",
                 (unsigned)(id & ~EB_SPHERE_BIT));
}

int eb_check_answers(const char *what, const eb_rays *r, const float *tfar0,
                     const uint8_t *valid0, int occ, int filtered, const eb_answers *a)
{
    int bad = 0;
    for (size_t i = 0; i < r->n; i++) {
        float o[3], d[3], t = 0, n[3] = {0, 0, 0};
        eb_rays_get(r, i, o, d);
        if (eb_skipped_lane(what, r, i, tfar0, valid0, &bad))
            continue;
        const uint32_t want = a->want(o, d, r->tnear[i], tfar0[i], filtered, &t, n);
        if (occ) {
            eb_occlusion(what, r, i, tfar0, want, &bad);
            continue;
        }
        const uint32_t got = r->prim[i];
        int ok;
        if (want == RTC_INVALID_GEOMETRY_ID)
            ok = got == want && r->tfar[i] == tfar0[i];
        else
            ok = got != RTC_INVALID_GEOMETRY_ID && a->hit_ok(r, i, o, d, got, want, t, n);
        if (!ok && bad++ < 5) {
            char g[24], w[24];
            id_text(g, got);
            id_text(w, want);
            printf("  %s ray %zu: Embree+cylray %s t %.9g u %g v %g, cylray %s t %.9g\n", what,
                   i, g, r->tfar[i], r->u[i], r->v[i], w, t);
        }
    }
    return bad;
}

void eb_packet_passes(const eb_passes *p, RTCScene sc, const char *vn, int filtered,
                      RTCFilterFunctionN qf, eb_rays *r, float *tfar0, uint8_t *valid0,
                      int *passed, int *failed)
{
    static const int packets[4] = {1, 4, 8, 16};
    for (int k = 0; k < 4; k++)
        for (int m = 0; m < 4; m++) {
            const int occ = m & 1, mixed = m >> 1;
            eb_agree_rays(r, p->scene, p->w, p->h, tfar0, valid0);
            if (mixed)
                p->mix(r);
            eb_trace_filtered(sc, r, packets[k], 2, occ, NULL, qf);
            char what[128];
            snprintf(what, sizeof what, "%s%s packet %d%s %s", vn,
                     !filtered ? ""
                     : qf      ? " query-filtered"
                               : " filtered",
                     packets[k], mixed ? " incoherent" : "", occ ? "occluded" : "intersect");
            const int bad = p->check(what, r, tfar0, valid0, occ, filtered);
            printf("%s %s (%d disagreements)\n", bad ? "FAIL" : "ok  ", what, bad);
            bad ? (*failed)++ : (*passed)++;
        }
}

void eb_agree_rays(eb_rays *r, const eb_scene *s, int w, int h, float *tfar0, uint8_t *valid0)
{
    eb_camera_rays(r, s, w, h);
    r->incoherent = 0;
    eb_rng gen = {99};
    for (size_t i = 0; i < r->n; i++) {
        r->valid[i] = i % 7 != 3;
        if (i % 3 == 0)
            r->tfar[i] = (float)eb_range(&gen, 5, 40);
        tfar0[i] = r->tfar[i];
        valid0[i] = r->valid[i];
    }
}
