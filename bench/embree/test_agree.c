/* SPDX-License-Identifier: MIT */
/* test_agree.c - the user-geometry path gives the hits that plain cylray calls give:
 * Embree's BVH with cylray callbacks (single cylinders, and leaves where the library has
 * them), at 1, 4, 8 and 16 rays a call, against every cylinder tried in turn. */
#include "geom.h"
#include "rays.h"
#include "trace.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

enum { W = 64, H = 64, NCYL = 300 };

/* The closest hit over every cylinder, one at a time through the 4-wide kernel. */
static uint32_t brute(const cylray_kernels *k, const cylray_prepared *prep, size_t n,
                      const float o[3], const float d[3], float tmin, float tmax, float *t,
                      float nrm[3])
{
    CYLRAY_ALIGN(16) cylray_ray4 r;
    CYLRAY_ALIGN(16) cylray_hit4 h;
    memset(&r, 0, sizeof r);
    r.ox[0] = o[0], r.oy[0] = o[1], r.oz[0] = o[2];
    r.dx[0] = d[0], r.dy[0] = d[1], r.dz[0] = d[2];
    r.tmin[0] = tmin, r.tmax[0] = tmax;
    uint32_t best = RTC_INVALID_GEOMETRY_ID;
    for (size_t i = 0; i < n; i++) {
        float before = r.tmax[0];
        /* a hit at exactly tmax counts, so an equal t would replace: keep the first */
        if (k->intersect4(&prep[i], &r, &h, 1, CYLRAY_NORMAL) && h.t[0] < before) {
            best = (uint32_t)i;
            *t = h.t[0];
            nrm[0] = h.nx[0], nrm[1] = h.ny[0], nrm[2] = h.nz[0];
        } else {
            r.tmax[0] = before;
        }
    }
    return best;
}

static int check(const char *what, const eb_geom *g, const eb_rays *r, const float *tfar0,
                 const uint8_t *valid0, int occ, int exact_t)
{
    const cylray_kernels *k = g->k;
    int bad = 0;
    for (size_t i = 0; i < r->n; i++) {
        float o[3], d[3], t = 0, n[3] = {0, 0, 0};
        eb_rays_get(r, i, o, d);
        if (!valid0[i]) {
            if (r->tfar[i] != tfar0[i] && !(isnan(r->tfar[i]) && isnan(tfar0[i]))) {
                if (bad++ < 5)
                    printf("  %s ray %zu: invalid lane written\n", what, i);
            }
            continue;
        }
        uint32_t want = brute(k, g->prep, g->src->ns, o, d, r->tnear[i], tfar0[i], &t, n);
        if (occ) {
            int got = r->tfar[i] == -INFINITY;
            if (got != (want != RTC_INVALID_GEOMETRY_ID) ||
                (!got && r->tfar[i] != tfar0[i])) {
                if (bad++ < 5)
                    printf("  %s ray %zu: occluded %d, cylray says %d\n", what, i, got,
                           want != RTC_INVALID_GEOMETRY_ID);
            }
            continue;
        }
        uint32_t got = r->prim[i];
        int ok;
        if (want == RTC_INVALID_GEOMETRY_ID)
            ok = got == want && r->tfar[i] == tfar0[i];
        else if (got == RTC_INVALID_GEOMETRY_ID)
            ok = 0;
        else {
            /* the same t; with single cylinders the same bits, and the same normal */
            double tol = exact_t ? 0 : 2 * (nextafterf(fabsf(t), INFINITY) - fabsf(t));
            ok = fabs((double)r->tfar[i] - t) <= tol;
            if (ok && got == want)
                ok = fabsf(r->ngx[i] - n[0]) <= 1e-6f && fabsf(r->ngy[i] - n[1]) <= 1e-6f &&
                     fabsf(r->ngz[i] - n[2]) <= 1e-6f;
        }
        if (!ok && bad++ < 5)
            printf("  %s ray %zu: Embree+cylray prim %u t %.9g, cylray prim %u t %.9g\n",
                   what, i, got, r->tfar[i], want, t);
    }
    return bad;
}

/* Calls the intersect callback directly, as Embree would with N rays and a valid mask,
 * for primitive `prim`: valid lanes must answer as the plain calls do for that
 * primitive's cylinders, invalid ones must keep every byte. */
static int direct(const eb_geom *g, const eb_rays *r, unsigned N, uint32_t prim)
{
    enum { FIELDS = 12 + 7 + RTC_MAX_INSTANCE_LEVEL_COUNT };
    float buf[FIELDS * 16], before[FIELDS * 16];
    int valid[16], bad = 0;
    for (unsigned i = 0; i < N; i++) {
        size_t j = (prim * 131u + i * 17u) % r->n;
        float f[12] = {r->ox[j], r->oy[j], r->oz[j], 0, r->dx[j], r->dy[j], r->dz[j], 0,
                       INFINITY, 0, 0, 0};
        for (int k = 0; k < FIELDS; k++)
            buf[k * N + i] = k < 12 ? f[k] : -1.0f;
        valid[i] = (i * 5 + prim) % 3 ? -1 : 0;
    }
    memcpy(before, buf, sizeof buf);
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    struct RTCIntersectFunctionNArguments a = {valid, (void *)g, prim, &ctx,
                                               (struct RTCRayHitN *)buf, N, 0};
    g->isect(&a);
    for (unsigned i = 0; i < N; i++) {
        int changed = 0;
        for (int k = 0; k < FIELDS; k++)
            changed |= memcmp(&buf[k * N + i], &before[k * N + i], sizeof(float)) != 0;
        if (!valid[i]) {
            if (changed && bad++ < 3)
                printf("  direct N=%u: invalid lane %u written\n", N, i);
            continue;
        }
        float o[3] = {before[0 * N + i], before[1 * N + i], before[2 * N + i]};
        float d[3] = {before[4 * N + i], before[5 * N + i], before[6 * N + i]}, t = 0, n[3];
        uint32_t want = RTC_INVALID_GEOMETRY_ID;
        if (g->variant == EB_SINGLE) {
            want = brute(g->k, &g->prep[prim], 1, o, d, 0, INFINITY, &t, n);
            if (want != RTC_INVALID_GEOMETRY_ID)
                want = prim;
        }
        uint32_t got = changed ? ((uint32_t *)buf)[(12 + 5) * N + i] : RTC_INVALID_GEOMETRY_ID;
        if (g->variant == EB_SINGLE &&
            (got != want || (changed && buf[8 * N + i] != t)) && bad++ < 3)
            printf("  direct N=%u lane %u: prim %u, want %u\n", N, i, got, want);
    }
    return bad;
}

int main(void)
{
    eb_scene s;
    if (eb_scene_small(&s, NCYL, 12345)) {
        printf("scene failed\n");
        return 1;
    }
    RTCDevice dev = rtcNewDevice(NULL);
    const cylray_kernels *k = cylray_kernels_best();
    eb_rays r;
    if (!dev || eb_rays_alloc(&r, W * H))
        return 1;
    static float tfar0[W * H];
    static uint8_t valid0[W * H];
    int passed = 0, failed = 0;
    for (int v = EB_SINGLE; v < EB_NVARIANTS; v++) {
        /* leaves of 4, 8, 16, grouped by Embree's SAH builder and along the Morton curve */
        int ms[3] = {4, 8, 16};
        for (int mi = 0; mi < (v == EB_LEAF ? 6 : 1); mi++) {
            eb_geom g;
            eb_grouping how = mi < 3 ? EB_GROUP_SAH : EB_GROUP_MORTON;
            if (eb_geom_build(&g, dev, &s, (eb_variant)v, ms[mi % 3], how, k)) {
                printf("FAIL %s: build\n", eb_variant_name((eb_variant)v));
                failed++;
                continue;
            }
            static const int packets[4] = {1, 4, 8, 16};
            for (int p = 0; p < 4; p++)
                for (int occ = 0; occ < 2; occ++) {
                    /* camera rays, every seventh left out, and a finite tmax on a third
                     * so that some hits lie beyond it */
                    eb_camera_rays(&r, &s, W, H);
                    rng gen = {99};
                    for (size_t i = 0; i < r.n; i++) {
                        r.valid[i] = i % 7 != 3;
                        if (i % 3 == 0)
                            r.tfar[i] = (float)rng_range(&gen, 5, 40);
                        tfar0[i] = r.tfar[i];
                        valid0[i] = r.valid[i];
                    }
                    eb_trace(g.scene, &r, packets[p], 2, occ, NULL);
                    char what[96];
                    snprintf(what, sizeof what, "%s M=%d%s packet %d %s",
                             eb_variant_name((eb_variant)v), v == EB_LEAF ? ms[mi % 3] : 1,
                             v != EB_LEAF ? "" : how == EB_GROUP_SAH ? " sah" : " morton",
                             packets[p], occ ? "occluded" : "intersect");
                    int bad = check(what, &g, &r, tfar0, valid0, occ, v == EB_SINGLE);
                    printf("%s %s (%d disagreements)\n", bad ? "FAIL" : "ok  ", what, bad);
                    bad ? failed++ : passed++;
                }
            if (v == EB_SINGLE) {
                eb_camera_rays(&r, &s, W, H);
                int bad = 0;
                for (unsigned N = 1; N <= 16; N *= 2)
                    for (uint32_t p = 0; N != 2 && p < g.src->ns; p++)
                        bad += direct(&g, &r, N, p);
                printf("%s %s: direct callback calls, valid masks (%d disagreements)\n",
                       bad ? "FAIL" : "ok  ", eb_variant_name((eb_variant)v), bad);
                bad ? failed++ : passed++;
            }
            eb_geom_free(&g);
        }
    }
    eb_rays_free(&r);
    rtcReleaseDevice(dev);
    eb_scene_free(&s);
    printf("%d passed, %d failed\n", passed, failed);
    return failed != 0 || passed == 0;
}
