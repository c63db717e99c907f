/* SPDX-License-Identifier: MIT */
/* rays.c - drawing the scenarios' rays: camera tiles, incoherent rays, shadow rays,
 * hit/miss mixes, far origins and clusters, all in double and rounded once to float. */
#include "rays.h"

#include "gen.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846

void *bench_alloc(size_t bytes)
{
    size_t b = (bytes + 63) & ~(size_t)63; /* aligned_alloc wants a multiple */
    void *p = aligned_alloc(64, b ? b : 64);
    if (p)
        memset(p, 0, b ? b : 64);
    return p;
}

void bench_free(void *p)
{
    free(p);
}

int raysoa_alloc(raysoa *r, size_t n)
{
    memset(r, 0, sizeof *r);
    float **f[8] = {&r->ox, &r->oy, &r->oz, &r->dx, &r->dy, &r->dz, &r->tmin, &r->tmax};
    for (int k = 0; k < 8; k++) {
        *f[k] = bench_alloc(n * sizeof(float));
        if (!*f[k]) {
            raysoa_free(r);
            return -1;
        }
    }
    r->n = n;
    return 0;
}

void raysoa_free(raysoa *r)
{
    float *f[8] = {r->ox, r->oy, r->oz, r->dx, r->dy, r->dz, r->tmin, r->tmax};
    for (int k = 0; k < 8; k++)
        bench_free(f[k]);
    memset(r, 0, sizeof *r);
}

void raysoa_get(const raysoa *r, size_t i, float o[3], float d[3])
{
    o[0] = r->ox[i], o[1] = r->oy[i], o[2] = r->oz[i];
    d[0] = r->dx[i], d[1] = r->dy[i], d[2] = r->dz[i];
}

/* splitmix64 from the exact reference's generators: small, fast, the same sequence on
 * every platform, and the one the Embree scenes draw from too. */
static uint64_t rng_next(rng *g)
{
    return cylgen_splitmix64(&g->s);
}

double rng_unit(rng *g)
{
    return (double)(rng_next(g) >> 11) * 0x1p-53;
}

double rng_range(rng *g, double a, double b)
{
    return a + (b - a) * rng_unit(g);
}

/* ---- geometry in double --------------------------------------------------- */

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void cross3(const double a[3], const double b[3], double r[3])
{
    r[0] = a[1] * b[2] - a[2] * b[1];
    r[1] = a[2] * b[0] - a[0] * b[2];
    r[2] = a[0] * b[1] - a[1] * b[0];
}

static void norm3(double a[3])
{
    double l = sqrt(dot3(a, a));
    a[0] /= l, a[1] /= l, a[2] /= l;
}

/* An orthonormal frame on a cylinder: a along the axis, u and w across it. */
typedef struct frame {
    double c[3], a[3], u[3], w[3];
    double R, H, S; /* radius, half height (3R when infinite), bounding radius */
} frame;

static void frame_of(frame *f, const cylray_cylinder *cy)
{
    for (int k = 0; k < 3; k++)
        f->c[k] = cy->center[k], f->a[k] = cy->axis[k];
    norm3(f->a);
    double e[3] = {0, 0, 0};
    int m = fabs(f->a[0]) < fabs(f->a[1]) ? (fabs(f->a[0]) < fabs(f->a[2]) ? 0 : 2)
                                          : (fabs(f->a[1]) < fabs(f->a[2]) ? 1 : 2);
    e[m] = 1;
    cross3(f->a, e, f->u);
    norm3(f->u);
    cross3(f->a, f->u, f->w);
    f->R = cy->radius;
    f->H = isfinite(cy->half_height) ? cy->half_height : 3 * cy->radius;
    f->S = sqrt(f->R * f->R + f->H * f->H);
}

static void to_world(const frame *f, const double l[3], double out[3], int point)
{
    for (int k = 0; k < 3; k++)
        out[k] = (point ? f->c[k] : 0) + l[0] * f->u[k] + l[1] * f->w[k] + l[2] * f->a[k];
}

static void random_unit(rng *g, double v[3])
{
    double z = rng_range(g, -1, 1), p = rng_range(g, 0, 2 * PI), s = sqrt(1 - z * z);
    v[0] = s * cos(p), v[1] = s * sin(p), v[2] = z;
}

static void put(raysoa *r, size_t i, const double o[3], const double d[3], double tmin,
                double tmax)
{
    r->ox[i] = (float)o[0], r->oy[i] = (float)o[1], r->oz[i] = (float)o[2];
    r->dx[i] = (float)d[0], r->dy[i] = (float)d[1], r->dz[i] = (float)d[2];
    r->tmin[i] = (float)tmin;
    r->tmax[i] = (float)tmax;
}

/* A random point of the box 1.3 times the solid's, in local coordinates. */
static void box_point(const frame *f, rng *g, double l[3])
{
    l[0] = rng_range(g, -1.3, 1.3) * f->R;
    l[1] = rng_range(g, -1.3, 1.3) * f->R;
    l[2] = rng_range(g, -1.3, 1.3) * f->H;
}

/* Origin at distance dist (local), aimed at a random point of the box; unit d. */
static void aimed_ray(const frame *f, rng *g, double dist, double o[3], double d[3])
{
    double dir[3], ol[3], tl[3];
    random_unit(g, dir);
    for (int k = 0; k < 3; k++)
        ol[k] = dir[k] * dist;
    box_point(f, g, tl);
    double dl[3] = {tl[0] - ol[0], tl[1] - ol[1], tl[2] - ol[2]};
    norm3(dl);
    to_world(f, ol, o, 1);
    to_world(f, dl, d, 0);
}

int rays_classify(const cylray_cylinder *cy, const double o[3], const double d[3], double tmin,
                  double tmax)
{
    frame f;
    frame_of(&f, cy);
    double w[3] = {o[0] - f.c[0], o[1] - f.c[1], o[2] - f.c[2]};
    double dv = dot3(d, f.a), z0 = dot3(w, f.a);
    double dp[3], wp[3];
    for (int k = 0; k < 3; k++)
        dp[k] = d[k] - dv * f.a[k], wp[k] = w[k] - z0 * f.a[k];
    double A = dot3(dp, dp), B = dot3(dp, wp), C = dot3(wp, wp) - f.R * f.R;
    int inf = !isfinite(cy->half_height), capped = !inf && (cy->flags & CYLRAY_CAPPED);
    double H = cy->half_height, t1, t2;
    if (A < 1e-24 * dot3(d, d)) {
        if (C > 0)
            return 0;
        if (!capped)
            return 1;
        t1 = -INFINITY, t2 = INFINITY; /* inside the tube along its whole length */
    } else {
        double disc = B * B - A * C;
        if (disc < 0)
            return 0;
        double s = sqrt(disc);
        t1 = (-B - s) / A, t2 = (-B + s) / A;
    }
    if (inf)
        return (t1 >= tmin && t1 <= tmax) || (t2 >= tmin && t2 <= tmax) ? 2 : 1;
    if (!capped) {
        int h1 = t1 >= tmin && t1 <= tmax && fabs(z0 + t1 * dv) <= H;
        int h2 = t2 >= tmin && t2 <= tmax && fabs(z0 + t2 * dv) <= H;
        return h1 || h2 ? 2 : 1;
    }
    double lo = t1, hi = t2;
    if (dv == 0) {
        if (fabs(z0) > H)
            return 1;
    } else {
        double ta = (-H - z0) / dv, tb = (H - z0) / dv;
        lo = fmax(lo, fmin(ta, tb));
        hi = fmin(hi, fmax(ta, tb));
    }
    if (lo > hi)
        return 1;
    return (lo >= tmin && lo <= tmax) || (hi >= tmin && hi <= tmax) ? 2 : 1;
}

/* Rays drawn like RK_INCOHERENT until one of the wanted class (bit c of `want`) comes. */
static void class_ray(const cylray_cylinder *cy, const frame *f, rng *g, unsigned want,
                      double o[3], double d[3])
{
    for (int tries = 0; tries < 100000; tries++) {
        aimed_ray(f, g, rng_range(g, 3, 6) * f->S, o, d);
        if (want >> rays_classify(cy, o, d, 0, INFINITY) & 1u)
            return;
    }
}

void rays_generate(raysoa *r, ray_kind kind, const cylray_cylinder *cy, double extent, rng *g)
{
    frame f;
    frame_of(&f, cy);
    double o[3], d[3];
    switch (kind) {
    case RK_INCOHERENT:
        for (size_t i = 0; i < r->n; i++) {
            aimed_ray(&f, g, rng_range(g, 3, 6) * f.S, o, d);
            put(r, i, o, d, 0, INFINITY);
        }
        break;
    case RK_FAR:
        /* The far-origin category: the quadratic's cancellation grows with |w|/R. */
        for (size_t i = 0; i < r->n; i++) {
            aimed_ray(&f, g, f.R * pow(10, rng_range(g, 2, 5)), o, d);
            put(r, i, o, d, 0, INFINITY);
        }
        break;
    case RK_VERY_FAR:
        /* Where the textbook's b^2 - (d.d) c loses everything: c = |w|^2 - R^2 keeps
         * no bit of R^2 once |w| passes 2^12 R. */
        for (size_t i = 0; i < r->n; i++) {
            aimed_ray(&f, g, f.R * pow(10, rng_range(g, 4, 6)), o, d);
            put(r, i, o, d, 0, INFINITY);
        }
        break;
    case RK_CAMERA: {
        /* 64 pixels wide; pixels ordered in 4x4 tiles so that any 4, 8 or 16
         * consecutive rays form a compact 4x1, 4x2 or 4x4 block of the image. */
        size_t W = 64, H = r->n / W;
        double view[3] = {0.8, 0.45, 0.4}, up[3] = {0, 0, 1}, right[3], camup[3];
        norm3(view);
        cross3(view, up, right);
        norm3(right);
        cross3(right, view, camup);
        double dist = 4 * f.S, half = 1.25 * f.S / dist; /* view spans +-1.25 S */
        double eye[3] = {-view[0] * dist, -view[1] * dist, -view[2] * dist};
        to_world(&f, eye, o, 1);
        size_t i = 0;
        for (size_t ty = 0; ty < H / 4; ty++)
            for (size_t tx = 0; tx < W / 4; tx++)
                for (size_t y = ty * 4; y < ty * 4 + 4; y++)
                    for (size_t x = tx * 4; x < tx * 4 + 4; x++, i++) {
                        double sx = ((x + 0.5) / W * 2 - 1) * half;
                        double sy = (1 - (y + 0.5) / H * 2) * half * H / W;
                        double dl[3];
                        for (int k = 0; k < 3; k++)
                            dl[k] = view[k] + sx * right[k] + sy * camup[k];
                        norm3(dl);
                        to_world(&f, dl, d, 0);
                        put(r, i, o, d, 0, INFINITY);
                    }
        break;
    }
    case RK_SHADOW: {
        /* A floor plane behind the cylinder (local u = -1.2 S) lit by a point light in
         * front of it: the cylinder casts a shadow on about a quarter of the floor. */
        double light_l[3] = {5 * f.S, 0.5 * f.S, 1.5 * f.S}, L[3];
        to_world(&f, light_l, L, 1);
        for (size_t i = 0; i < r->n; i++) {
            double pl[3] = {-1.2 * f.S, rng_range(g, -1.5, 1.5) * f.S,
                            rng_range(g, -1.5, 1.5) * f.S};
            to_world(&f, pl, o, 1);
            double v[3] = {L[0] - o[0], L[1] - o[1], L[2] - o[2]};
            double len = sqrt(dot3(v, v));
            for (int k = 0; k < 3; k++)
                d[k] = v[k] / len;
            put(r, i, o, d, 1e-3, len);
        }
        break;
    }
    case RK_MISS_MIX:
    case RK_HIT_MIX:
    case RK_ALL_MISS:
    case RK_ALL_HIT: {
        double p_hit = kind == RK_MISS_MIX  ? 0.1
                       : kind == RK_HIT_MIX ? 0.9
                       : kind == RK_ALL_HIT ? 1.0
                                            : 0.0;
        for (size_t i = 0; i < r->n; i++) {
            unsigned want = rng_unit(g) < p_hit ? 4u : kind == RK_ALL_MISS ? 1u : 3u;
            class_ray(cy, &f, g, want, o, d);
            put(r, i, o, d, 0, INFINITY);
        }
        break;
    }
    case RK_CLUSTER:
        for (size_t i = 0; i < r->n; i++) {
            double dir[3], t[3];
            random_unit(g, dir);
            for (int k = 0; k < 3; k++) {
                o[k] = cy->center[k] + 3 * extent * dir[k];
                t[k] = cy->center[k] + rng_range(g, -extent, extent);
                d[k] = t[k] - o[k];
            }
            norm3(d);
            put(r, i, o, d, 0, INFINITY);
        }
        break;
    }
}

cylray_cylinder cyl_general(int kind)
{
    cylray_cylinder c = {{0.3f, -1.7f, 2.2f},
                         {0.31f, 0.87f, -0.42f},
                         0.75f,
                         kind == 0 ? INFINITY : 1.5f,
                         kind == 2 ? CYLRAY_CAPPED : 0u};
    return c;
}

cylray_sphere sph_general(void)
{
    const cylray_cylinder c = cyl_general(2);
    cylray_sphere s = {{c.center[0], c.center[1], c.center[2]}, c.radius};
    return s;
}

cylray_cylinder sph_box(const cylray_sphere *s)
{
    cylray_cylinder c = cyl_general(2);
    for (int k = 0; k < 3; k++)
        c.center[k] = s->center[k];
    c.radius = c.half_height = s->radius;
    return c;
}

cylray_cone con_general(int kind)
{
    const cylray_cylinder c = cyl_general(2);
    const double al = sqrt((double)c.axis[0] * c.axis[0] + (double)c.axis[1] * c.axis[1] +
                           (double)c.axis[2] * c.axis[2]);
    cylray_cone k = {{0}, {0}, 1.0f, kind == 0 ? 0.4f : 0.0f, CYLRAY_CAPPED};
    for (int i = 0; i < 3; i++) {
        k.p0[i] = (float)(c.center[i] - c.half_height * c.axis[i] / al);
        k.p1[i] = (float)(c.center[i] + c.half_height * c.axis[i] / al);
    }
    if (kind == 2) {
        k.r0 = c.radius;
        k.r1 = nextafterf(nextafterf(nextafterf(c.radius, 1.0f), 1.0f), 1.0f);
    }
    if (kind == 3) { /* slender: 1000 of its wider radius long */
        k.r0 = (float)(c.half_height / 500.0);
        k.r1 = (float)(c.half_height / 1250.0);
    }
    return k;
}

cylray_cylinder con_box(const cylray_cone *k)
{
    cylray_cylinder c = cyl_general(2);
    c.radius = k->r0 > k->r1 ? k->r0 : k->r1;
    return c;
}

cylray_cylinder cyl_aligned(int kind)
{
    cylray_cylinder c = cyl_general(kind);
    c.axis[0] = 0, c.axis[1] = 0, c.axis[2] = 1;
    return c;
}

void rays_to_general(raysoa *dst, const raysoa *src)
{
    cylray_cylinder a = cyl_aligned(2), b = cyl_general(2);
    frame fa, fb;
    frame_of(&fa, &a);
    frame_of(&fb, &b);
    for (size_t i = 0; i < src->n; i++) {
        double o[3] = {src->ox[i] - fa.c[0], src->oy[i] - fa.c[1], src->oz[i] - fa.c[2]};
        double d[3] = {src->dx[i], src->dy[i], src->dz[i]};
        /* local coordinates in the aligned frame, then out into the general one */
        double ol[3] = {dot3(o, fa.u), dot3(o, fa.w), dot3(o, fa.a)};
        double dl[3] = {dot3(d, fa.u), dot3(d, fa.w), dot3(d, fa.a)};
        double ow[3], dw[3];
        to_world(&fb, ol, ow, 1);
        to_world(&fb, dl, dw, 0);
        put(dst, i, ow, dw, src->tmin[i], src->tmax[i]);
    }
}

void cyl_cluster(cylray_cylinder *out, int n, double e, rng *g)
{
    for (int i = 0; i < n; i++) {
        double a[3];
        random_unit(g, a);
        cylray_cylinder c = {{(float)rng_range(g, -0.8 * e, 0.8 * e),
                              (float)rng_range(g, -0.8 * e, 0.8 * e),
                              (float)rng_range(g, -0.8 * e, 0.8 * e)},
                             {(float)a[0], (float)a[1], (float)a[2]},
                             (float)rng_range(g, 0.05 * e, 0.15 * e),
                             (float)rng_range(g, 0.1 * e, 0.4 * e),
                             CYLRAY_CAPPED};
        out[i] = c;
    }
}
