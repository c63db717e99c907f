/* SPDX-License-Identifier: MIT */
/* tkgen.h - what the toolkit tests share: cylinders of every awkward kind, and the exact
 * (binary128) axis, frame and points of a cylinder. Header-only, static functions. */
#ifndef TKGEN_H
#define TKGEN_H

#include "cylray.h"
#include "gen.h"
#include "quad.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static inline double tk_u(cylgen_rng *g)
{
    return cylgen_uniform(g);
}

static inline double tk_log(cylgen_rng *g, double lo, double hi) /* log-uniform in [lo, hi] */
{
    return exp(log(lo) + (log(hi) - log(lo)) * tk_u(g));
}

static inline float tk_sym(cylgen_rng *g, double m) /* uniform in [-m, m] */
{
    return (float)((2 * tk_u(g) - 1) * m);
}

static const unsigned tk_flags[4] = {0, CYLRAY_CAPPED_LO, CYLRAY_CAPPED_HI, CYLRAY_CAPPED};

#define TK_KINDS 11
static const char *const tk_kind_names[TK_KINDS] = {
    "general",    "coordinate-axis", "one-zero",     "near-axis-1e-7",
    "far-center", "tiny-radius",     "huge-radius",  "endpoints",
    "generators", "extreme",         "touching-zero"};

/* Cylinder i of kind `kind` (finite; the generators' infinite ones become finite). */
static inline void tk_cylinder(cylgen_rng *g, int kind, cylray_cylinder *c)
{
    memset(c, 0, sizeof *c);
    c->flags = tk_flags[cylgen_next(g) & 3];
    for (int k = 0; k < 3; k++) {
        c->center[k] = tk_sym(g, 1e3);
        c->axis[k] = tk_sym(g, 2.0);
    }
    c->radius = (float)tk_log(g, 1e-3, 1e3);
    c->half_height = (float)tk_log(g, 1e-3, 1e3);
    int j = (int)(cylgen_next(g) % 3);
    switch (kind) {
    case 1: { /* along a coordinate axis, any length and sign; faces through 0 */
        float s = (float)tk_log(g, 1e-30, 1e30);
        s *= tk_u(g) < 0.5f ? -1.0f : 1.0f;
        c->axis[0] = c->axis[1] = c->axis[2] = 0;
        c->axis[j] = s;
        if (tk_u(g) < 0.5)
            c->center[(j + 1) % 3] = c->radius;
        if (tk_u(g) < 0.5)
            c->center[j] = -c->half_height;
        break;
    }
    case 2:
        c->axis[j] = 0;
        break;
    case 3: { /* within 1e-7 rad of a coordinate axis */
        c->axis[j] = tk_u(g) < 0.5 ? 1.0f : -3.0f;
        c->axis[(j + 1) % 3] = (float)(c->axis[j] * 1e-7 * (2 * tk_u(g) - 1));
        c->axis[(j + 2) % 3] = (float)(c->axis[j] * 1e-7 * (2 * tk_u(g) - 1));
        break;
    }
    case 4:
        for (int k = 0; k < 3; k++)
            c->center[k] = tk_sym(g, 4e7);
        c->radius = (float)tk_log(g, 1e-3, 1.0);
        c->half_height = (float)tk_log(g, 1.0, 2e3);
        break;
    case 5:
        c->radius = (float)tk_log(g, 1e-12, 1e-6);
        c->half_height = (float)tk_log(g, 1e-9, 1.0);
        break;
    case 6:
        c->radius = (float)tk_log(g, 1e5, 1e15);
        c->half_height = (float)tk_log(g, 1e-2, 1e15);
        break;
    case 7: {
        float p0[3], p1[3];
        for (int k = 0; k < 3; k++) {
            p0[k] = tk_sym(g, 1e4);
            p1[k] = p0[k] + tk_sym(g, 1e2);
        }
        cylray_cylinder e;
        if (cylray_cylinder_from_endpoints(&e, p0, p1, c->radius, c->flags) == CYLRAY_OK)
            *c = e;
        break;
    }
    case 8: {
        cylgen_case cs;
        int cat = (int)(cylgen_next(g) % (uint64_t)cylgen_category_count());
        cylgen_make(cat, cylgen_next(g), 1, &cs);
        *c = cs.cyl;
        if (!isfinite(c->half_height))
            c->half_height = (float)tk_log(g, 1e-2, 1e4);
        break;
    }
    case 9: /* the edges of the working range */
        for (int k = 0; k < 3; k++)
            c->center[k] = tk_sym(g, 0x1p62);
        c->radius = (float)tk_log(g, 0x1p-60, 0x1p62);
        c->half_height = (float)tk_log(g, 0x1p-60, 0x1p62);
        if (tk_u(g) < 0.3)
            c->axis[j] = (float)(0x1p-126 * (1 + tk_u(g)));
        break;
    case 10:   /* a tilted cylinder whose face lies within rounding of 0 */
        break; /* the caller moves the center, it needs the exact extent */
    default:
        break;
    }
}

/* ---- the exact side: binary128 ------------------------------------------------- */

typedef struct tkq {
    cylq c[3], n[3], b1[3], b2[3], R, H;
} tkq;

/* The exact unit axis and the frame of Duff et al. (JCGT 2017) with s = +1 where
 * n_z >= 0 (either zero), in binary128, of the prepared geometry (center, axis, radius
 * and half height as given). */
static inline void tk_exact(const cylray_cylinder *cy, tkq *q)
{
    cylq vv = 0;
    for (int k = 0; k < 3; k++)
        vv += (cylq)cy->axis[k] * cy->axis[k];
    cylq sv = q_sqrt(vv);
    for (int k = 0; k < 3; k++) {
        q->c[k] = cy->center[k];
        q->n[k] = (cylq)cy->axis[k] / sv;
    }
    q->R = cy->radius;
    q->H = cy->half_height;
    cylq s = q->n[2] >= 0 ? 1 : -1;
    cylq a = -1 / (s + q->n[2]), b = q->n[0] * q->n[1] * a;
    q->b1[0] = 1 + s * q->n[0] * q->n[0] * a;
    q->b1[1] = s * b;
    q->b1[2] = -s * q->n[0];
    q->b2[0] = b;
    q->b2[1] = s + q->n[1] * q->n[1] * a;
    q->b2[2] = -q->n[1];
}

/* The exact half extent of the box along k: H |n_k| + R sqrt(1 - n_k^2). */
static inline cylq tk_extent(const cylray_cylinder *cy, int k)
{
    cylq vk = cy->axis[k], vi = cy->axis[(k + 1) % 3], vj = cy->axis[(k + 2) % 3];
    cylq S = vi * vi + vj * vj, V = S + vk * vk, sv = q_sqrt(V);
    return ((cylq)cy->half_height * q_abs(vk) + (cylq)cy->radius * q_sqrt(S)) / sv;
}

/* The point at axial z (world units) and angle (cs, sn) (any length: normalised
 * here) at distance r from the axis, exactly. */
static inline void tk_point(const tkq *q, cylq z, double cs, double sn, cylq r, cylq p[3])
{
    cylq l = q_sqrt((cylq)cs * cs + (cylq)sn * sn);
    cylq a = (cylq)cs / l, b = (cylq)sn / l;
    for (int k = 0; k < 3; k++)
        p[k] = q->c[k] + z * q->n[k] + r * (a * q->b1[k] + b * q->b2[k]);
}

/* Floats strictly between f and the exact x (0 when f is the nearest on its side). */
static inline double tk_steps(float f, cylq x)
{
    double n = 0;
    if ((cylq)f <= x) {
        for (float g = nextafterf(f, INFINITY); (cylq)g <= x && n < 100;
             g = nextafterf(g, INFINITY))
            n++;
    } else {
        for (float g = nextafterf(f, -INFINITY); (cylq)g >= x && n < 100;
             g = nextafterf(g, -INFINITY))
            n++;
    }
    return n;
}

#endif
