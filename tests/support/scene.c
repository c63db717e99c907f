/* SPDX-License-Identifier: MIT */
/* scene.c - the ray batches of scene.h. */
#include "scene.h"

#include <math.h>

#include "frame.h"
#include "rng.h"

double scene_uniform(uint64_t *state, double lo, double hi)
{
    return lo + (hi - lo) * rng_unit(rng_splitmix64(state));
}

static void unit_random(uint64_t *s, double v[3])
{
    double l;
    do {
        for (int k = 0; k < 3; k++)
            v[k] = scene_uniform(s, -1, 1);
        l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    } while (l < 0.1 || l > 1);
    for (int k = 0; k < 3; k++)
        v[k] /= l;
}

/* The point at axial coordinate z, distance r from the axis, angle ang around it. */
static void at(const cylray_cylinder *c, const double u[3], const double e1[3],
               const double e2[3], double z, double r, double ang, double x[3])
{
    for (int k = 0; k < 3; k++)
        x[k] = c->center[k] + z * u[k] + r * (cos(ang) * e1[k] + sin(ang) * e2[k]);
}

void scene_rays(uint64_t seed, const cylray_cylinder *c, gbatch *b, size_t first, size_t n)
{
    uint64_t s = seed * 0x2545f4914f6cdd1dull + 1;
    double u[3], e1[3], e2[3];
    axis_frame(c->axis, u, e1, e2);

    const double R = c->radius;
    const double H = isfinite(c->half_height) ? c->half_height : 4 * R;
    for (size_t i = first; i < first + n; i++) {
        double o[3], d[3], tgt[3], tmin = 0, tmax = INFINITY;
        const double ang = scene_uniform(&s, 0, 6.283185307179586);
        switch (rng_splitmix64(&s) % 6) {
        case 0: /* from outside at a point inside the solid: enters */
        case 1:
            at(c, u, e1, e2, scene_uniform(&s, -0.9, 0.9) * H, scene_uniform(&s, 0, 0.9) * R,
               ang, tgt);
            unit_random(&s, d);
            for (int k = 0; k < 3; k++)
                o[k] = tgt[k] - d[k] * scene_uniform(&s, 2, 6) * (R + H);
            break;
        case 2: /* from inside: leaves through a back face */
            at(c, u, e1, e2, scene_uniform(&s, -0.9, 0.9) * H, scene_uniform(&s, 0, 0.9) * R,
               ang, o);
            unit_random(&s, d);
            break;
        case 3: /* down onto a cap, a little tilted */
            at(c, u, e1, e2, (rng_splitmix64(&s) & 1 ? 1 : -1) * scene_uniform(&s, 1.5, 4) * H,
               scene_uniform(&s, 0, 0.95) * R, ang, o);
            at(c, u, e1, e2, 0, scene_uniform(&s, 0, 0.5) * R, -ang, tgt);
            for (int k = 0; k < 3; k++)
                d[k] = tgt[k] - o[k];
            break;
        case 4: /* aimed beside the cylinder: mostly misses */
            at(c, u, e1, e2, scene_uniform(&s, -2, 2) * H, scene_uniform(&s, 1.2, 3) * R, ang,
               tgt);
            unit_random(&s, d);
            for (int k = 0; k < 3; k++)
                o[k] = tgt[k] - d[k] * scene_uniform(&s, 1, 6) * (R + H);
            break;
        default: /* a short window somewhere along an entering ray */
            at(c, u, e1, e2, scene_uniform(&s, -0.9, 0.9) * H, scene_uniform(&s, 0, 0.9) * R,
               ang, tgt);
            unit_random(&s, d);
            for (int k = 0; k < 3; k++)
                o[k] = tgt[k] - d[k] * 3 * (R + H);
            tmin = scene_uniform(&s, 0, 4) * (R + H);
            tmax = tmin + scene_uniform(&s, 0, 2) * (R + H);
            break;
        }
        /* directions of varied length: the kernel must not assume unit d */
        const double dl = scene_uniform(&s, 0.25, 4);
        for (int k = 0; k < 3; k++) {
            b->f[G_OX + k][i] = (float)o[k];
            b->f[G_DX + k][i] = (float)(d[k] * dl);
        }
        b->f[G_TMIN][i] = (float)(tmin / dl);
        b->f[G_TMAX][i] = (float)(tmax / dl);
    }
}

int scene_cylinders(cylray_cylinder out[SCENE_MAX_CYL])
{
    static const cylray_cylinder cyl[] = {
        {{0, 0, 0}, {0, 0, 1}, 1, 2, CYLRAY_CAPPED},
        {{0, 0, 0}, {0, 0, 1}, 1, 2, 0},
        {{0, 0, 0}, {0, 0, 1}, 1, INFINITY, 0},
        {{1, -2, 3}, {1, 0, 0}, 0.5f, 3, CYLRAY_CAPPED},
        {{1, -2, 3}, {0, -1, 0}, 0.5f, 3, 0},
        {{0.5f, 1.5f, -2}, {0.3f, -0.7f, 0.4f}, 1.25f, 0.75f, CYLRAY_CAPPED},
        {{0.5f, 1.5f, -2}, {0.3f, -0.7f, 0.4f}, 1.25f, 0.75f, 0},
        {{-3, 7, 2}, {2, 1, -2}, 0.8f, INFINITY, CYLRAY_CAPPED},
        {{100, 200, -50}, {1, 1, 1}, 20, 60, CYLRAY_CAPPED},
        {{1e3f, -1e3f, 5e2f}, {-0.2f, 0.9f, 0.1f}, 1e-2f, 0.5f, CYLRAY_CAPPED},
    };
    const int n = (int)(sizeof cyl / sizeof cyl[0]);
    for (int i = 0; i < n; i++)
        out[i] = cyl[i];
    return n;
}
