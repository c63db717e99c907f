/* SPDX-License-Identifier: MIT */
/* trace.c - ray storage, the camera, and the threaded tile loop around Embree's
 * rtcIntersect and rtcOccluded calls. */
#include "trace.h"

#include "clocks.h"
#include "geom.h"

#include <float.h>
#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

/* 64-byte aligned and zeroed, so that each array starts on a cache line; NULL when out
 * of memory. */
static void *alloc64(size_t bytes)
{
    size_t b = (bytes + 63) & ~(size_t)63; /* aligned_alloc wants a multiple */
    void *p = aligned_alloc(64, b ? b : 64);
    if (p)
        memset(p, 0, b ? b : 64);
    return p;
}

int eb_rays_alloc(eb_rays *r, size_t n)
{
    memset(r, 0, sizeof *r);
    r->n = n;
    float **f[13] = {&r->ox,   &r->oy,  &r->oz,  &r->dx,  &r->dy, &r->dz, &r->tnear,
                     &r->tfar, &r->ngx, &r->ngy, &r->ngz, &r->u,  &r->v};
    int bad = 0;
    for (int k = 0; k < 13; k++)
        bad |= !(*f[k] = alloc64(n * sizeof(float)));
    bad |= !(r->prim = alloc64(n * sizeof *r->prim));
    bad |= !(r->valid = alloc64(n));
    if (bad)
        eb_rays_free(r);
    return bad ? -1 : 0;
}

void eb_rays_free(eb_rays *r)
{
    void *p[15] = {r->ox,  r->oy,  r->oz,  r->dx, r->dy, r->dz,   r->tnear, r->tfar,
                   r->ngx, r->ngy, r->ngz, r->u,  r->v,  r->prim, r->valid};
    for (int k = 0; k < 15; k++)
        free(p[k]);
    memset(r, 0, sizeof *r);
}

void eb_rays_get(const eb_rays *r, size_t i, float o[3], float d[3])
{
    o[0] = r->ox[i], o[1] = r->oy[i], o[2] = r->oz[i];
    d[0] = r->dx[i], d[1] = r->dy[i], d[2] = r->dz[i];
}

void eb_pixel_of(size_t idx, int w, int h, int *x, int *y)
{
    (void)h;
    size_t tile = idx / 256, in = idx % 256, block = in / 16, px = in % 16;
    size_t tiles_x = (size_t)w / 16;
    *x = (int)((tile % tiles_x) * 16 + (block % 4) * 4 + px % 4);
    *y = (int)((tile / tiles_x) * 16 + (block / 4) * 4 + px / 4);
}

void eb_camera_ray(const eb_scene *s, int w, int h, double x, double y, float o[3], float d[3])
{
    double f[3], r[3], u[3], fl = 0, rl = 0;
    for (int k = 0; k < 3; k++)
        f[k] = (double)s->look[k] - s->eye[k], fl += f[k] * f[k];
    for (int k = 0; k < 3; k++)
        f[k] /= sqrt(fl);
    r[0] = f[1] * s->up[2] - f[2] * s->up[1];
    r[1] = f[2] * s->up[0] - f[0] * s->up[2];
    r[2] = f[0] * s->up[1] - f[1] * s->up[0];
    for (int k = 0; k < 3; k++)
        rl += r[k] * r[k];
    for (int k = 0; k < 3; k++)
        r[k] /= sqrt(rl);
    u[0] = r[1] * f[2] - r[2] * f[1];
    u[1] = r[2] * f[0] - r[0] * f[2];
    u[2] = r[0] * f[1] - r[1] * f[0];
    double tn = tan(s->fov_deg * 3.14159265358979 / 360), asp = (double)w / h;
    double sx = (2 * x / w - 1) * tn * asp, sy = (1 - 2 * y / h) * tn, dd[3], dl = 0;
    for (int k = 0; k < 3; k++)
        dd[k] = f[k] + sx * r[k] + sy * u[k], dl += dd[k] * dd[k];
    for (int k = 0; k < 3; k++) {
        o[k] = s->eye[k];
        d[k] = (float)(dd[k] / sqrt(dl));
    }
}

void eb_camera_rays(eb_rays *r, const eb_scene *s, int w, int h)
{
    for (size_t i = 0; i < r->n; i++) {
        int x, y;
        float o[3], d[3];
        eb_pixel_of(i, w, h, &x, &y);
        eb_camera_ray(s, w, h, x + 0.5, y + 0.5, o, d);
        r->ox[i] = o[0], r->oy[i] = o[1], r->oz[i] = o[2];
        r->dx[i] = d[0], r->dy[i] = d[1], r->dz[i] = d[2];
        r->tnear[i] = 0;
        r->tfar[i] = INFINITY;
        r->valid[i] = 1;
    }
}

/* ---- tracing -------------------------------------------------------------------- */

/* Copies rays [i, i + N) into an Embree packet, traces it as a renderer with
 * cylray_embree would (cylray_embree_intersectN: a coherent packet as one, an
 * incoherent one a ray a call), copies the answers back. */
#define EB_PACKET(N)                                                                           \
    static void packet##N(RTCScene sc, eb_rays *r, size_t i0, int occ,                         \
                          RTCFilterFunctionN filter)                                           \
    {                                                                                          \
        struct RTCRayHit##N rh;                                                                \
        _Alignas(64) int valid[N]; /* Embree loads the mask as one vector */                   \
        eb_query q;                                                                            \
        eb_query_init(&q, filter, !r->incoherent);                                             \
        int any = 0;                                                                           \
        for (int j = 0; j < N; j++) {                                                          \
            size_t i = i0 + (size_t)j;                                                         \
            valid[j] = i < r->n && r->valid[i] ? -1 : 0;                                       \
            any |= valid[j];                                                                   \
            if (i >= r->n)                                                                     \
                i = r->n - 1;                                                                  \
            rh.ray.org_x[j] = r->ox[i], rh.ray.org_y[j] = r->oy[i];                            \
            rh.ray.org_z[j] = r->oz[i], rh.ray.tnear[j] = r->tnear[i];                         \
            rh.ray.dir_x[j] = r->dx[i], rh.ray.dir_y[j] = r->dy[i];                            \
            rh.ray.dir_z[j] = r->dz[i], rh.ray.time[j] = 0;                                    \
            rh.ray.tfar[j] = r->tfar[i], rh.ray.mask[j] = ~0u;                                 \
            rh.ray.id[j] = (unsigned)j, rh.ray.flags[j] = 0;                                   \
            rh.hit.geomID[j] = RTC_INVALID_GEOMETRY_ID;                                        \
            rh.hit.primID[j] = RTC_INVALID_GEOMETRY_ID;                                        \
        }                                                                                      \
        if (!any)                                                                              \
            return;                                                                            \
        if (occ)                                                                               \
            EB_OCCLUDED_N(N, valid, sc, &q, &rh.ray);                                          \
        else                                                                                   \
            EB_INTERSECT_N(N, valid, sc, &q, &rh);                                             \
        for (int j = 0; j < N; j++) {                                                          \
            size_t i = i0 + (size_t)j;                                                         \
            if (!valid[j])                                                                     \
                continue;                                                                      \
            r->tfar[i] = rh.ray.tfar[j];                                                       \
            if (occ)                                                                           \
                continue;                                                                      \
            r->prim[i] = eb_hit_id(rh.hit.geomID[j], rh.hit.primID[j]);                        \
            r->ngx[i] = rh.hit.Ng_x[j], r->ngy[i] = rh.hit.Ng_y[j];                            \
            r->ngz[i] = rh.hit.Ng_z[j], r->u[i] = rh.hit.u[j], r->v[i] = rh.hit.v[j];          \
        }                                                                                      \
    }
EB_PACKET(4)
EB_PACKET(8)
EB_PACKET(16)

static void single(RTCScene sc, eb_rays *r, size_t i, int occ, RTCFilterFunctionN filter)
{
    if (!r->valid[i])
        return;
    eb_query q;
    eb_query_init(&q, filter, !r->incoherent);
    struct RTCRayHit rh;
    rh.ray.org_x = r->ox[i], rh.ray.org_y = r->oy[i], rh.ray.org_z = r->oz[i];
    rh.ray.dir_x = r->dx[i], rh.ray.dir_y = r->dy[i], rh.ray.dir_z = r->dz[i];
    rh.ray.tnear = r->tnear[i], rh.ray.tfar = r->tfar[i], rh.ray.time = 0;
    rh.ray.mask = ~0u, rh.ray.id = 0, rh.ray.flags = 0;
    rh.hit.geomID = rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
    if (occ) {
        EB_OCCLUDED1(sc, &q, &rh.ray);
        r->tfar[i] = rh.ray.tfar;
        return;
    }
    EB_INTERSECT1(sc, &q, &rh);
    r->tfar[i] = rh.ray.tfar;
    r->prim[i] = eb_hit_id(rh.hit.geomID, rh.hit.primID);
    r->ngx[i] = rh.hit.Ng_x, r->ngy[i] = rh.hit.Ng_y, r->ngz[i] = rh.hit.Ng_z;
    r->u[i] = rh.hit.u, r->v[i] = rh.hit.v;
}

uint32_t eb_trace1(RTCScene scene, const float o[3], const float d[3], float tnear, float tfar,
                   float *t, float ng[3])
{
    eb_query q;
    eb_query_init(&q, NULL, 0);
    struct RTCRayHit rh = eb_rayhit1(o, d, tnear, tfar);
    EB_INTERSECT1(scene, &q, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID)
        return RTC_INVALID_GEOMETRY_ID;
    *t = rh.ray.tfar;
    ng[0] = rh.hit.Ng_x, ng[1] = rh.hit.Ng_y, ng[2] = rh.hit.Ng_z;
    return eb_hit_id(rh.hit.geomID, rh.hit.primID);
}

typedef struct job {
    RTCScene scene;
    eb_rays *r;
    int packet, occ;
    RTCFilterFunctionN filter;
    atomic_size_t next;
} job;

static void *worker(void *arg)
{
    job *jb = arg;
    for (;;) {
        size_t a = atomic_fetch_add(&jb->next, 256);
        if (a >= jb->r->n)
            return NULL;
        size_t b = a + 256 < jb->r->n ? a + 256 : jb->r->n;
        if (!jb->occ)
            for (size_t i = a; i < b; i++)
                jb->r->prim[i] = RTC_INVALID_GEOMETRY_ID;
        for (size_t i = a; i < b; i += (size_t)jb->packet) {
            switch (jb->packet) {
            case 4:
                packet4(jb->scene, jb->r, i, jb->occ, jb->filter);
                break;
            case 8:
                packet8(jb->scene, jb->r, i, jb->occ, jb->filter);
                break;
            case 16:
                packet16(jb->scene, jb->r, i, jb->occ, jb->filter);
                break;
            default:
                single(jb->scene, jb->r, i, jb->occ, jb->filter);
                break;
            }
        }
    }
}

double eb_trace(RTCScene scene, eb_rays *r, int packet, int threads, int occluded,
                double *cpu_s)
{
    return eb_trace_filtered(scene, r, packet, threads, occluded, cpu_s, NULL);
}

double eb_trace_filtered(RTCScene scene, eb_rays *r, int packet, int threads, int occluded,
                         double *cpu_s, RTCFilterFunctionN filter)
{
    enum { MAXT = 256 };
    job jb = {.scene = scene, .r = r, .packet = packet, .occ = occluded, .filter = filter};
    atomic_init(&jb.next, 0);
    pthread_t th[MAXT];
    if (threads < 1)
        threads = 1;
    if (threads > MAXT)
        threads = MAXT;
    double t0 = eb_wall_s(), c0 = eb_cpu_s();
    int started = 0;
    for (int k = 1; k < threads; k++)
        if (pthread_create(&th[started], NULL, worker, &jb) == 0)
            started++;
    worker(&jb);
    for (int k = 0; k < started; k++)
        pthread_join(th[k], NULL);
    if (cpu_s)
        *cpu_s = eb_cpu_s() - c0;
    return eb_wall_s() - t0;
}

/* ---- secondary rays ------------------------------------------------------------ */

void eb_facing_normal(const float ng[3], const float d[3], float n[3])
{
    double l = sqrt((double)ng[0] * ng[0] + (double)ng[1] * ng[1] + (double)ng[2] * ng[2]);
    double s =
        ((double)ng[0] * d[0] + (double)ng[1] * d[1] + (double)ng[2] * d[2]) > 0 ? -1 : 1;
    for (int k = 0; k < 3; k++)
        n[k] = l > 0 ? (float)(s * ng[k] / l) : 0;
}

static float maxabs3(const float p[3])
{
    return fmaxf(fabsf(p[0]), fmaxf(fabsf(p[1]), fabsf(p[2])));
}

/* A cosine-distributed direction around n. */
static void cosine_dir(eb_rng *g, const float n[3], float w[3])
{
    double u1 = eb_unit(g), u2 = eb_unit(g), r = sqrt(u1), ph = 2 * 3.14159265358979 * u2;
    double a[3] = {fabs(n[0]) < 0.6 ? 1 : 0, fabs(n[0]) < 0.6 ? 0 : 1, 0}, b[3], c[3];
    b[0] = n[1] * a[2] - n[2] * a[1], b[1] = n[2] * a[0] - n[0] * a[2];
    b[2] = n[0] * a[1] - n[1] * a[0];
    double bl = sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
    for (int k = 0; k < 3; k++)
        b[k] /= bl;
    c[0] = n[1] * b[2] - n[2] * b[1], c[1] = n[2] * b[0] - n[0] * b[2];
    c[2] = n[0] * b[1] - n[1] * b[0];
    double x = r * cos(ph), y = r * sin(ph), z = sqrt(fmax(0, 1 - u1)), wl = 0, ww[3];
    for (int k = 0; k < 3; k++)
        ww[k] = x * b[k] + y * c[k] + z * n[k], wl += ww[k] * ww[k];
    for (int k = 0; k < 3; k++)
        w[k] = (float)(ww[k] / sqrt(wl));
}

/* A ray whose origin is not finite (a spawn helper that cannot place one) stays
 * invalid: Embree's assertions, where built in, stop on such a ray. */
static void set_ray(eb_rays *r, size_t i, const float o[3], const float w[3], float tnear,
                    float tfar)
{
    if (!isfinite(o[0]) || !isfinite(o[1]) || !isfinite(o[2]))
        return;
    r->ox[i] = o[0], r->oy[i] = o[1], r->oz[i] = o[2];
    r->dx[i] = w[0], r->dy[i] = w[1], r->dz[i] = w[2];
    r->tnear[i] = tnear;
    r->tfar[i] = tfar;
    r->valid[i] = 1;
}

/* Where a secondary ray in direction w starts, and its tnear. */
static void origin_for(const eb_geom *g, const eb_rays *prim, size_t i, const float p[3],
                       const float w[3], float out[3], float *tnear)
{
    if (g->variant == EB_NATIVE) {
        /* Embree's path tracer tutorial: start at the hit point, skip a relative
         * epsilon of the larger of the coordinates and the distance travelled. */
        for (int k = 0; k < 3; k++)
            out[k] = p[k];
        *tnear = 32.0f * FLT_EPSILON * fmaxf(maxabs3(p), prim->tfar[i]);
        return;
    }
    float o[3], d[3], ng[3] = {prim->ngx[i], prim->ngy[i], prim->ngz[i]};
    eb_rays_get(prim, i, o, d);
    *tnear = 0;
    unsigned id;
    RTCGeometry geo = eb_geom_of(g, prim->prim[i], &id);
    cylray_embree_spawn_origin(geo, id, o, d, prim->tfar[i], ng, w, out);
}

void eb_spawn(const eb_geom *g, const eb_rays *prim, eb_rays *shadow, eb_rays *bounce)
{
    const eb_scene *s = g->src;
    shadow->incoherent = 0;
    bounce->incoherent = 1;
    for (size_t i = 0; i < prim->n; i++) {
        shadow->valid[i] = bounce->valid[i] = 0;
        if (prim->prim[i] == RTC_INVALID_GEOMETRY_ID)
            continue;
        float o[3], d[3], ng[3] = {prim->ngx[i], prim->ngy[i], prim->ngz[i]}, nf[3], p[3];
        eb_rays_get(prim, i, o, d);
        eb_facing_normal(ng, d, nf);
        for (int k = 0; k < 3; k++)
            p[k] = o[k] + prim->tfar[i] * d[k];

        float l[3], ll = 0, org[3], tn;
        for (int k = 0; k < 3; k++)
            l[k] = s->light[k] - p[k], ll += l[k] * l[k];
        ll = sqrtf(ll);
        for (int k = 0; k < 3; k++)
            l[k] /= ll;
        if (l[0] * nf[0] + l[1] * nf[1] + l[2] * nf[2] > 0) {
            origin_for(g, prim, i, p, l, org, &tn);
            float dl = 0;
            for (int k = 0; k < 3; k++)
                dl += (s->light[k] - org[k]) * (s->light[k] - org[k]);
            set_ray(shadow, i, org, l, tn, sqrtf(dl));
        }

        eb_rng gen = {0x5eed0000ull + i};
        float w[3];
        cosine_dir(&gen, nf, w);
        origin_for(g, prim, i, p, w, org, &tn);
        set_ray(bounce, i, org, w, tn, INFINITY);
    }
}
