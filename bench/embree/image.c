/* SPDX-License-Identifier: MIT */
/* image.c - shading and difference pictures of the traced frames. */
#include "image.h"

#include "cylref.h"
#include "trace.h"

#include <math.h>

static void put(uint8_t *rgb, int w, int x, int y, const double c[3])
{
    for (int k = 0; k < 3; k++) {
        double v = c[k] <= 0 ? 0 : c[k] >= 1 ? 1 : sqrt(c[k]);
        rgb[3 * ((size_t)y * (size_t)w + (size_t)x) + (size_t)k] = (uint8_t)(255 * v + 0.5);
    }
}

void eb_shade(const eb_scene *s, const eb_rays *prim, const eb_rays *shadow,
              const eb_rays *bounce, int w, int h, uint8_t *rgb)
{
    for (size_t i = 0; i < prim->n; i++) {
        int x, y;
        eb_pixel_of(i, w, h, &x, &y);
        double c[3];
        uint32_t id = prim->prim[i];
        if (id == RTC_INVALID_GEOMETRY_ID) {
            double f = 0.5 + 0.5 * prim->dy[i];
            c[0] = 0.25 + 0.2 * f, c[1] = 0.3 + 0.25 * f, c[2] = 0.4 + 0.35 * f;
            put(rgb, w, x, y, c);
            continue;
        }
        uint32_t hsh = id * 2654435761u;
        double alb[3] = {0.35 + 0.5 * ((hsh >> 8) & 255) / 255.0,
                         0.35 + 0.5 * ((hsh >> 16) & 255) / 255.0,
                         0.35 + 0.5 * ((hsh >> 24) & 255) / 255.0};
        float o[3], d[3], ng[3] = {prim->ngx[i], prim->ngy[i], prim->ngz[i]}, n[3];
        eb_rays_get(prim, i, o, d);
        eb_facing_normal(ng, d, n);
        double lit = 0;
        if (shadow->valid[i] && shadow->tfar[i] != -INFINITY)
            lit = n[0] * shadow->dx[i] + n[1] * shadow->dy[i] + n[2] * shadow->dz[i];
        double ao = bounce->valid[i] && bounce->prim[i] != RTC_INVALID_GEOMETRY_ID &&
                            bounce->tfar[i] < 0.05f * s->scale
                        ? 0.5
                        : 1;
        for (int k = 0; k < 3; k++)
            c[k] = alb[k] * (0.2 * ao + 0.8 * lit);
        put(rgb, w, x, y, c);
    }
}

size_t eb_diff(const eb_rays *pa, const eb_rays *sa, const eb_rays *pb, const eb_rays *sb,
               int w, int h, uint8_t *rgb)
{
    size_t bad = 0;
    for (size_t i = 0; i < pa->n; i++) {
        int x, y;
        eb_pixel_of(i, w, h, &x, &y);
        int ha = pa->prim[i] != RTC_INVALID_GEOMETRY_ID;
        int hb = pb->prim[i] != RTC_INVALID_GEOMETRY_ID;
        double c[3] = {0, 0, 0};
        if (ha != hb) {
            c[0] = 1, bad++;
        } else if (ha && pa->prim[i] != pb->prim[i] &&
                   fabs((double)pa->tfar[i] - pb->tfar[i]) >
                       8 * cylref_float_ulp(pa->tfar[i])) {
            c[0] = c[1] = 1, bad++;
        } else if (ha && (sa->valid[i] && sa->tfar[i] == -INFINITY) !=
                             (sb->valid[i] && sb->tfar[i] == -INFINITY)) {
            c[1] = c[2] = 1;
        } else if (ha) {
            double u = fabs((double)pa->tfar[i] - pb->tfar[i]) / cylref_float_ulp(pa->tfar[i]);
            double g = log2(1 + u) / 10;
            c[0] = c[1] = c[2] = g * g;
        }
        put(rgb, w, x, y, c);
    }
    return bad;
}
