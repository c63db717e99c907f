/* SPDX-License-Identifier: MIT */
/* spawn.c - secondary rays: where they start, which way they go. */
#include "spawn.h"

#include "pending.h"
#include "rays.h"

#include <float.h>
#include <math.h>

void eb_facing_normal(const float ng[3], const float d[3], float n[3])
{
    double l = sqrt((double)ng[0] * ng[0] + (double)ng[1] * ng[1] + (double)ng[2] * ng[2]);
    double s = ((double)ng[0] * d[0] + (double)ng[1] * d[1] + (double)ng[2] * d[2]) > 0 ? -1 : 1;
    for (int k = 0; k < 3; k++)
        n[k] = l > 0 ? (float)(s * ng[k] / l) : 0;
}

static float maxabs3(const float p[3])
{
    return fmaxf(fabsf(p[0]), fmaxf(fabsf(p[1]), fabsf(p[2])));
}

/* A cosine-distributed direction around n. */
static void cosine_dir(rng *g, const float n[3], float w[3])
{
    double u1 = rng_unit(g), u2 = rng_unit(g), r = sqrt(u1), ph = 2 * 3.14159265358979 * u2;
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

static void set_ray(eb_rays *r, size_t i, const float o[3], const float w[3], float tnear,
                    float tfar)
{
    r->ox[i] = o[0], r->oy[i] = o[1], r->oz[i] = o[2];
    r->dx[i] = w[0], r->dy[i] = w[1], r->dz[i] = w[2];
    r->tnear[i] = tnear;
    r->tfar[i] = tfar;
    r->valid[i] = 1;
}

/* Where a secondary ray in direction w starts, and its tnear. */
static int origin_for(const eb_geom *g, const eb_rays *prim, size_t i, const float p[3],
                      float perr, const float nf[3], const float w[3], float out[3],
                      float *tnear)
{
    uint32_t id = prim->prim[i];
    if (g->variant == EB_NATIVE) {
        /* Embree's path tracer tutorial: start at the hit point, skip a relative
         * epsilon of the larger of the coordinates and the distance travelled. */
        for (int k = 0; k < 3; k++)
            out[k] = p[k];
        *tnear = 32.0f * FLT_EPSILON * fmaxf(maxabs3(p), prim->tfar[i]);
        return 0;
    }
    *tnear = 0;
    int32_t part = (int32_t)prim->v[i];
    if (cylray_spawn_origin) {
        cylray_spawn_origin(&g->prep[id], p, perr, part, w, out);
        return 0;
    }
    /* Stand-in until the library has cylray_spawn_origin: a relative offset along the
     * normal, to w's side. */
    float e = 0x1p-16f * fmaxf(maxabs3(p), g->src->radius);
    float s = nf[0] * w[0] + nf[1] * w[1] + nf[2] * w[2] >= 0 ? e : -e;
    for (int k = 0; k < 3; k++)
        out[k] = p[k] + s * nf[k];
    return 1;
}

int eb_spawn(const eb_geom *g, const eb_rays *prim, eb_rays *shadow, eb_rays *bounce)
{
    const eb_scene *s = g->src;
    int stand_in = 0;
    shadow->incoherent = 0;
    bounce->incoherent = 1;
    for (size_t i = 0; i < prim->n; i++) {
        shadow->valid[i] = bounce->valid[i] = 0;
        if (prim->prim[i] == RTC_INVALID_GEOMETRY_ID)
            continue;
        float o[3], d[3], ng[3] = {prim->ngx[i], prim->ngy[i], prim->ngz[i]}, nf[3], p[3];
        float perr = 0;
        eb_rays_get(prim, i, o, d);
        eb_facing_normal(ng, d, nf);
        float t = prim->tfar[i];
        if (g->variant != EB_NATIVE && cylray_hit_point)
            cylray_hit_point(&g->prep[prim->prim[i]], o, d, t, (int32_t)prim->v[i], p, &perr);
        else
            for (int k = 0; k < 3; k++)
                p[k] = o[k] + t * d[k];

        float l[3], ll = 0, org[3], tn;
        for (int k = 0; k < 3; k++)
            l[k] = s->light[k] - p[k], ll += l[k] * l[k];
        ll = sqrtf(ll);
        for (int k = 0; k < 3; k++)
            l[k] /= ll;
        if (l[0] * nf[0] + l[1] * nf[1] + l[2] * nf[2] > 0) {
            stand_in |= origin_for(g, prim, i, p, perr, nf, l, org, &tn);
            float dl = 0;
            for (int k = 0; k < 3; k++)
                dl += (s->light[k] - org[k]) * (s->light[k] - org[k]);
            set_ray(shadow, i, org, l, tn, sqrtf(dl));
        }

        rng gen = {0x5eed0000ull + i};
        float w[3];
        cosine_dir(&gen, nf, w);
        stand_in |= origin_for(g, prim, i, p, perr, nf, w, org, &tn);
        set_ray(bounce, i, org, w, tn, INFINITY);
    }
    return stand_in;
}
