/* SPDX-License-Identifier: MIT */
/* scenegen.c - the harness's cylinder sets, built from a seed (scenegen.h). */
#include "scenegen.h"

#include "morton.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

cylray_cylinder sg_segment(const double p0[3], const double p1[3], double r, unsigned caps)
{
    cylray_cylinder c;
    double len2 = 0;
    for (int k = 0; k < 3; k++) {
        c.center[k] = (float)(0.5 * (p0[k] + p1[k]));
        c.axis[k] = (float)(p1[k] - p0[k]);
        len2 += (p1[k] - p0[k]) * (p1[k] - p0[k]);
    }
    c.radius = (float)r;
    c.half_height = (float)(0.5 * sqrt(len2));
    c.flags = caps;
    return c;
}

int sg_molecule(cylray_cylinder *out, int n, const double base[3], rng *g)
{
    const double a = 1.4;
    const int side = (int)ceil(cbrt(n / 1.5)) + 1;
    int k = 0;
    for (int i = 0; i < side && k < n; i++)
        for (int j = 0; j < side && k < n; j++)
            for (int l = 0; l < side && k < n; l++) {
                double p[3] = {base[0] + a * i, base[1] + a * j, base[2] + a * l};
                for (int q = 0; q < 3; q++)
                    p[q] += rng_range(g, -0.15, 0.15) * a;
                for (int dir = 0; dir < 3 && k < n; dir++) {
                    if (rng_unit(g) < 0.5)
                        continue;
                    double e[3] = {p[0], p[1], p[2]};
                    e[dir] += a;
                    for (int q = 0; q < 3; q++)
                        e[q] += rng_range(g, -0.15, 0.15) * a;
                    double len =
                        sqrt((e[0] - p[0]) * (e[0] - p[0]) + (e[1] - p[1]) * (e[1] - p[1]) +
                             (e[2] - p[2]) * (e[2] - p[2]));
                    out[k++] = sg_segment(p, e, rng_range(g, 0.1, 0.2) * len, CYLRAY_CAPPED);
                }
            }
    return k;
}

void sg_atoms(cylray_sphere *out, int n, const double base[3], rng *g)
{
    const double a = 1.4;
    const int side = (int)ceil(cbrt((double)n));
    int k = 0;
    for (int i = 0; i < side && k < n; i++)
        for (int j = 0; j < side && k < n; j++)
            for (int l = 0; l < side && k < n; l++, k++) {
                const int idx[3] = {i, j, l};
                for (int q = 0; q < 3; q++)
                    out[k].center[q] =
                        (float)(base[q] + a * (idx[q] + rng_range(g, -0.15, 0.15)));
                out[k].radius = (float)rng_range(g, 0.3, 0.5);
            }
}

int sg_pipes(cylray_cylinder *out, int n, const double base[3], double size, rng *g)
{
    int k = 0;
    while (k < n) {
        double p[3] = {base[0] + rng_range(g, 0, size), base[1] + rng_range(g, 0, size),
                       base[2] + rng_range(g, 0, size)};
        const double r = rng_range(g, 0.15, 0.3);
        const int segs = 4 + (int)(rng_unit(g) * 6);
        int axis = (int)(rng_unit(g) * 3);
        for (int s = 0; s < segs && k < n; s++) {
            double e[3] = {p[0], p[1], p[2]};
            double len = rng_range(g, 1.0, 3.0) * (rng_unit(g) < 0.5 ? -1 : 1);
            e[axis] += len;
            unsigned caps = (s == 0 ? CYLRAY_CAPPED_LO : 0u) |
                            (s == segs - 1 || k == n - 1 ? CYLRAY_CAPPED_HI : 0u);
            out[k++] = sg_segment(p, e, r, caps);
            memcpy(p, e, sizeof p);
            axis = (axis + 1 + (int)(rng_unit(g) * 2)) % 3;
        }
    }
    return k;
}

typedef struct sg_keyed {
    uint32_t key;
    int idx;
} sg_keyed;

static int by_key(const void *a, const void *b)
{
    const sg_keyed *x = a, *y = b;
    return x->key < y->key ? -1 : x->key > y->key;
}

/* Sorted by the Morton code of the center, quantised to 10 bits a coordinate in the
 * centers' box. */
void sg_taper(cylray_cylinder *cyl, cylray_cone *out, int n, rng *g)
{
    for (int i = 0; i < n; i++) {
        cylray_cylinder *c = &cyl[i];
        const double al =
            sqrt((double)c->axis[0] * c->axis[0] + (double)c->axis[1] * c->axis[1] +
                 (double)c->axis[2] * c->axis[2]);
        cylray_cone k;
        for (int q = 0; q < 3; q++) {
            k.p0[q] = (float)(c->center[q] - c->half_height * c->axis[q] / al);
            k.p1[q] = (float)(c->center[q] + c->half_height * c->axis[q] / al);
        }
        const double u = rng_range(g, 0.1, 0.5), R = c->radius;
        const int tip = rng_unit(g) < 0.25, wide_lo = rng_unit(g) < 0.5;
        const float big = (float)(tip ? 1.3 * R : (1 + u) * R);
        const float small = tip ? 0.0f : (float)((1 - u) * R);
        k.r0 = wide_lo ? big : small;
        k.r1 = wide_lo ? small : big;
        k.flags = c->flags;
        out[i] = k;
        c->radius = big;
    }
}

int sg_morton_sort(cylray_cylinder *c, int n)
{
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) {
            lo[k] = fminf(lo[k], c[i].center[k]);
            hi[k] = fmaxf(hi[k], c[i].center[k]);
        }
    sg_keyed *kv = malloc((size_t)n * sizeof *kv);
    cylray_cylinder *tmp = malloc((size_t)n * sizeof *tmp);
    if (!kv || !tmp) {
        free(kv), free(tmp);
        return -1;
    }
    for (int i = 0; i < n; i++) {
        uint32_t q[3];
        for (int k = 0; k < 3; k++)
            q[k] = (uint32_t)(1023.0f * (c[i].center[k] - lo[k]) / fmaxf(hi[k] - lo[k], 1e-6f));
        kv[i].key =
            morton_spread3(q[0]) | morton_spread3(q[1]) << 1 | morton_spread3(q[2]) << 2;
        kv[i].idx = i;
    }
    qsort(kv, (size_t)n, sizeof *kv, by_key);
    for (int i = 0; i < n; i++)
        tmp[i] = c[kv[i].idx];
    memcpy(c, tmp, (size_t)n * sizeof *c);
    free(kv), free(tmp);
    return 0;
}

/* ---- the rendered scene --------------------------------------------------------- */

static void add_cyl(sg_painted *s, const double c[3], const double a[3], double R, double H,
                    const float rgb[3], int mat)
{
    if (s->n >= s->max)
        return;
    cylray_cylinder *cy = &s->cyl[s->n];
    for (int k = 0; k < 3; k++) {
        cy->center[k] = (float)c[k];
        cy->axis[k] = (float)a[k];
        s->albedo[s->n][k] = rgb[k];
    }
    cy->radius = (float)R;
    cy->half_height = (float)H;
    cy->flags = CYLRAY_CAPPED;
    s->mat[s->n] = mat;
    s->n++;
}

/* A capped cylinder from p to q. */
static void add_seg(sg_painted *s, const double p[3], const double q[3], double R,
                    const float rgb[3], int mat)
{
    if (s->n >= s->max)
        return;
    s->cyl[s->n] = sg_segment(p, q, R, CYLRAY_CAPPED);
    memcpy(s->albedo[s->n], rgb, sizeof s->albedo[0]);
    s->mat[s->n] = mat;
    s->n++;
}

void sg_fence_scene(sg_painted *s)
{
    static const float floor_c[3] = {0.7f, 0.7f, 0.7f}, wood[3] = {0.55f, 0.36f, 0.2f},
                       pipe[3] = {0.45f, 0.55f, 0.65f}, flange[3] = {0.7f, 0.45f, 0.15f},
                       carbon[3] = {0.2f, 0.2f, 0.22f}, hydrogen[3] = {0.92f, 0.92f, 0.92f},
                       bond[3] = {0.6f, 0.6f, 0.6f}, red[3] = {0.8f, 0.15f, 0.12f},
                       blue[3] = {0.15f, 0.3f, 0.8f}, yellow[3] = {0.9f, 0.75f, 0.15f};
    s->n = 0;
    /* The floor: a wide, thin disc whose top face is y = 0. */
    add_cyl(s, (double[]){0, -0.05, 0}, (double[]){0, 1, 0}, 30, 0.05, floor_c, SG_FLOOR);

    /* A fence at the back: 11 posts (axis-aligned) and two rails between each pair. */
    for (int k = 0; k <= 10; k++) {
        double x = -6 + 1.2 * k;
        add_cyl(s, (double[]){x, 0.6, -3}, (double[]){0, 1, 0}, 0.08, 0.6, wood, SG_MATTE);
        if (k < 10)
            for (int r = 0; r < 2; r++) {
                double y = r ? 0.95 : 0.4;
                add_seg(s, (double[]){x, y, -3}, (double[]){x + 1.2, y, -3}, 0.045, wood,
                        SG_MATTE);
            }
    }

    /* A pipe run on the right: straight pieces with flanges at every joint. */
    const double run[][3] = {{1.2, 0.35, 2.2}, {3.2, 0.35, 2.2}, {4.6, 0.35, 2.2},
                             {4.6, 1.6, 2.2},  {4.6, 1.6, 0.0},  {4.6, 1.6, -2.0}};
    for (int p = 0; p < 2; p++) {
        double dz = p ? -0.55 : 0, dx = p ? 0.55 : 0;
        for (size_t i = 0; i + 1 < sizeof run / sizeof run[0]; i++) {
            double a[3] = {run[i][0] + dx, run[i][1], run[i][2] + dz};
            double b[3] = {run[i + 1][0] + dx, run[i + 1][1], run[i + 1][2] + dz};
            add_seg(s, a, b, 0.14, pipe, SG_SHINY);
            double ax[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
            add_cyl(s, b, ax, 0.2, 0.05, flange, SG_SHINY);
        }
    }
    /* Supports under the lower pipes. */
    for (int k = 0; k < 3; k++)
        add_cyl(s, (double[]){1.6 + 1.3 * k, 0.1, 1.95}, (double[]){0, 1, 0}, 0.06, 0.1, flange,
                SG_MATTE);

    /* Benzene, ball-and-stick with drums for atoms, tilted, hovering at the front left. */
    double cen[3] = {-1.2, 1.75, 1.7}, u[3] = {1, 0.2, 0}, v[3] = {0, 0.85, 0.5};
    double lu = sqrt(u[0] * u[0] + u[1] * u[1]), lv = sqrt(v[1] * v[1] + v[2] * v[2]);
    for (int k = 0; k < 3; k++)
        u[k] /= lu, v[k] /= lv;
    double nrm[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                     u[0] * v[1] - u[1] * v[0]};
    double C[6][3], Hh[6][3];
    for (int i = 0; i < 6; i++) {
        double ang = i * 3.14159265358979 / 3, ca = cos(ang), sa = sin(ang);
        for (int k = 0; k < 3; k++) {
            C[i][k] = cen[k] + 0.85 * (ca * u[k] + sa * v[k]);
            Hh[i][k] = cen[k] + 1.45 * (ca * u[k] + sa * v[k]);
        }
    }
    for (int i = 0; i < 6; i++) {
        add_seg(s, C[i], C[(i + 1) % 6], 0.05, bond, SG_SHINY);
        add_seg(s, C[i], Hh[i], 0.035, bond, SG_SHINY);
        add_cyl(s, C[i], nrm, 0.16, 0.09, carbon, SG_SHINY);
        add_cyl(s, Hh[i], nrm, 0.11, 0.06, hydrogen, SG_SHINY);
    }

    /* A double helix on the left: two backbones of bonds, and rungs between them. */
    double hx = -4.2, hz = 0.4;
    double prev[2][3];
    for (int k = 0; k <= 16; k++) {
        double y = 0.25 + 0.19 * k, ang = 0.55 * k;
        double pts[2][3];
        for (int st = 0; st < 2; st++) {
            double a = ang + st * 3.14159265358979;
            pts[st][0] = hx + 0.75 * cos(a);
            pts[st][1] = y;
            pts[st][2] = hz + 0.75 * sin(a);
            if (k > 0)
                add_seg(s, prev[st], pts[st], 0.06, st ? blue : red, SG_SHINY);
        }
        if (k % 2 == 0)
            add_seg(s, pts[0], pts[1], 0.035, yellow, SG_MATTE);
        memcpy(prev, pts, sizeof prev);
    }
}
