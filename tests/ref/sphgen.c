/* SPDX-License-Identifier: MIT */
/* sphgen.c - the sphere stress-ray generators: one function per category.
 *
 * Geometry is built in double from the float sphere (the values the kernel will see),
 * then rounded to float, so "a surface point" is a point of the float sphere rounded
 * once, and "grazing" is grazing for the float sphere, off only by the rounding of o
 * and d. */
#include "sphgen.h"

#include <float.h>
#include <math.h>
#include <string.h>

typedef struct {
    double x[3];
} v3;

static v3 mk(double a, double b, double c)
{
    v3 v = {{a, b, c}};
    return v;
}
static v3 axpy(v3 y, double s, v3 a) /* y + s a */
{
    return mk(y.x[0] + s * a.x[0], y.x[1] + s * a.x[1], y.x[2] + s * a.x[2]);
}
static double dot(v3 a, v3 b)
{
    return a.x[0] * b.x[0] + a.x[1] * b.x[1] + a.x[2] * b.x[2];
}
static v3 unit(v3 a)
{
    double s = 1.0 / sqrt(dot(a, a));
    return mk(a.x[0] * s, a.x[1] * s, a.x[2] * s);
}

static double uni(cylgen_rng *r, double a, double b)
{
    return a + (b - a) * cylgen_uniform(r);
}

static int chance(cylgen_rng *r, double p)
{
    return cylgen_uniform(r) < p;
}

/* About log-uniform in [2^ea, 2^eb): a uniform exponent and a uniform mantissa; no
 * libm transcendental, so the draw is the same everywhere. */
static double logu(cylgen_rng *r, int ea, int eb)
{
    int e = ea + (int)(cylgen_next(r) % (uint64_t)(eb - ea));
    double m = uni(r, 1, 2);
    return ldexp(m, e);
}

static v3 rand_dir(cylgen_rng *r)
{
    for (;;) {
        /* One draw per statement: the order of function arguments is unspecified. */
        double x = uni(r, -1, 1), y = uni(r, -1, 1), z = uni(r, -1, 1);
        v3 p = mk(x, y, z);
        double l = dot(p, p);
        if (l > 1e-4 && l <= 1)
            return mk(x / sqrt(l), y / sqrt(l), z / sqrt(l));
    }
}

/* A unit vector perpendicular to the unit vector a. */
static v3 rand_perp(cylgen_rng *r, v3 a)
{
    for (;;) {
        v3 u = rand_dir(r);
        v3 p = axpy(u, -dot(u, a), a);
        if (dot(p, p) > 1e-4)
            return unit(p);
    }
}

static void to_f(float f[3], v3 a)
{
    for (int k = 0; k < 3; k++)
        f[k] = (float)a.x[k];
}

/* ---- spheres ------------------------------------------------------------------- */

static void make_sphere(int cat, cylgen_rng *r, cylray_sphere *s)
{
    double R, span;
    switch (cat) {
    case SPHGEN_TINY:
        R = uni(r, 1e-4, 1e-3);
        span = 1e4;
        break;
    case SPHGEN_HUGE:
        R = uni(r, 1e4, 1e6);
        span = uni(r, 1e5, 1e6);
        break;
    case SPHGEN_SCALED: {
        /* Beyond 2^+-20 the kernel scales its discriminant: both sides of that. */
        int e = 21 + (int)(cylgen_next(r) % 30);
        double k = ldexp(1.0, chance(r, 0.5) ? e : -e);
        R = uni(r, 0.1, 10) * k;
        span = 10 * k;
        break;
    }
    default:
        R = uni(r, 0.1, 10);
        span = 10;
        break;
    }
    for (int k = 0; k < 3; k++) {
        double x = uni(r, -span, span);
        /* Tiny spheres sit far out on every axis: o - c then loses everything to
         * rounding unless it is formed exactly. */
        if (cat == SPHGEN_TINY)
            x = (chance(r, 0.5) ? -1 : 1) * uni(r, 0.5 * span, span);
        s->center[k] = (float)x;
    }
    s->radius = (float)R;
}

typedef struct {
    v3 c;
    double R;
} ball;

static ball ball_of(const cylray_sphere *s)
{
    ball b = {mk(s->center[0], s->center[1], s->center[2]), s->radius};
    return b;
}

/* A point within slack R of the center, uniform in the ball. */
static v3 point_in(cylgen_rng *r, const ball *b, double slack)
{
    double u = cylgen_uniform(r);
    return axpy(b->c, b->R * slack * cbrt(u), rand_dir(r));
}

/* Mostly [0, inf); sometimes a tmax or tmin near the expected hit distance. */
static void pick_interval(cylgen_rng *r, double dist, sphgen_case *c)
{
    double u = cylgen_uniform(r);
    c->tmin = 0.0f;
    c->tmax = INFINITY;
    if (u < 0.12)
        c->tmax = (float)(dist * uni(r, 0.5, 1.5));
    else if (u < 0.22)
        c->tmin = (float)(dist * uni(r, 0.3, 1.2));
    else if (u < 0.27)
        c->tmax = FLT_MAX;
}

static void towards(cylgen_rng *r, const ball *b, double dist, double slack, sphgen_case *c)
{
    v3 target = point_in(r, b, slack), d = rand_dir(r);
    to_f(c->o, axpy(target, -dist, d));
    to_f(c->d, d);
    pick_interval(r, dist, c);
}

static void gen_grazing(cylgen_rng *r, const ball *b, sphgen_case *c)
{
    v3 d = rand_dir(r), u = rand_perp(r, d);
    double eps = logu(r, -23, -7) * (chance(r, 0.5) ? 1 : -1);
    double dist = b->R * uni(r, 2, 10);
    v3 closest = axpy(b->c, b->R * (1 + eps), u);
    to_f(c->o, axpy(closest, -dist, d));
    to_f(c->d, d);
    pick_interval(r, dist, c);
}

/* A secondary ray: a point of the sphere rounded to float, leaving outward or going
 * in (a reflection or a refraction), tmin = 0. */
static void gen_surface(cylgen_rng *r, const ball *b, sphgen_case *c)
{
    v3 n = rand_dir(r), d = rand_dir(r);
    int outward = chance(r, 0.5);
    if ((dot(d, n) > 0) != outward)
        d = mk(-d.x[0], -d.x[1], -d.x[2]);
    to_f(c->o, axpy(b->c, b->R, n));
    to_f(c->d, d);
    c->tmin = 0.0f;
    c->tmax = INFINITY;
}

/* A 4 x 4 block of a pinhole camera's pixels looking at the sphere: coherent rays
 * sharing an origin, as a primary-ray packet. The camera is that of the batch; the
 * pixel is the case's index. */
static void gen_camera(const ball *b, cylgen_rng *cam, size_t index, sphgen_case *c)
{
    v3 fwd = rand_dir(cam);
    double dist = b->R * uni(cam, 3, 50);
    v3 eye = axpy(b->c, -dist, fwd);
    v3 right = rand_perp(cam, fwd);
    v3 up = mk(fwd.x[1] * right.x[2] - fwd.x[2] * right.x[1],
               fwd.x[2] * right.x[0] - fwd.x[0] * right.x[2],
               fwd.x[0] * right.x[1] - fwd.x[1] * right.x[0]);
    /* The block spans a bit more than the sphere's silhouette, so its edge pixels
     * miss or graze. */
    double half = 1.3 * b->R / dist, px = uni(cam, -0.5, 0.5), py = uni(cam, -0.5, 0.5);
    double sx = ((double)(index % 4) - 1.5 + px) / 1.5 * half,
           sy = ((double)(index / 4 % 4) - 1.5 + py) / 1.5 * half;
    v3 d = axpy(axpy(fwd, sx, right), sy, up);
    to_f(c->o, eye);
    to_f(c->d, d);
    c->tmin = 0.0f;
    c->tmax = INFINITY;
}

/* Ordinary rays with one input made unusable in most lanes: NaN or Inf in o, d, tmin
 * or tmax, a zero direction, an empty interval. None of them may hit. */
static void gen_bad(cylgen_rng *r, const ball *b, sphgen_case *c)
{
    towards(r, b, b->R * uni(r, 1.5, 10), 1.2, c);
    cylgen_spoil(cylgen_next(r), c->o, c->d, &c->tmin, &c->tmax);
}

static void gen_case(int cat, cylgen_rng *r, const ball *b, cylgen_rng *cam, size_t index,
                     sphgen_case *c)
{
    switch (cat) {
    case SPHGEN_FAR:
        towards(r, b, b->R * logu(r, 10, 20), 1.1, c);
        break;
    case SPHGEN_GRAZING:
        gen_grazing(r, b, c);
        break;
    case SPHGEN_SURFACE:
        gen_surface(r, b, c);
        break;
    case SPHGEN_INSIDE: {
        v3 o = point_in(r, b, 0.99);
        to_f(c->o, o);
        to_f(c->d, rand_dir(r));
        pick_interval(r, b->R, c);
        break;
    }
    case SPHGEN_TINY:
    case SPHGEN_HUGE:
        towards(r, b, b->R * uni(r, 1.05, cat == SPHGEN_TINY ? 100 : 3), 1.2, c);
        break;
    case SPHGEN_UNNORMALIZED: {
        double dist = b->R * uni(r, 1.5, 10);
        towards(r, b, dist, 1.2, c);
        double s = ldexp(uni(r, 1, 2), (int)(cylgen_next(r) % 61) - 30);
        for (int k = 0; k < 3; k++)
            c->d[k] = (float)((double)c->d[k] * s);
        if (c->tmin != 0)
            c->tmin = (float)((double)c->tmin / s);
        if (c->tmax != INFINITY && c->tmax != FLT_MAX)
            c->tmax = (float)((double)c->tmax / s);
        break;
    }
    case SPHGEN_CAMERA:
        gen_camera(b, cam, index, c);
        break;
    case SPHGEN_BAD:
        gen_bad(r, b, c);
        break;
    case SPHGEN_SCALED: {
        if (chance(r, 0.3))
            gen_grazing(r, b, c);
        else
            towards(r, b, b->R * uni(r, 1.5, 10), 1.2, c);
        double s = ldexp(uni(r, 1, 2), (int)(cylgen_next(r) % 41) - 20);
        for (int k = 0; k < 3; k++)
            c->d[k] = (float)((double)c->d[k] * s);
        if (c->tmin != 0)
            c->tmin = (float)((double)c->tmin / s);
        if (c->tmax != INFINITY && c->tmax != FLT_MAX)
            c->tmax = (float)((double)c->tmax / s);
        break;
    }
    case SPHGEN_ORDINARY:
    default:
        towards(r, b, b->R * uni(r, 1.5, 10), 1.2, c);
        break;
    }
}

static const char *const names[SPHGEN_COUNT] = {
    "sph-ordinary", "sph-far",    "sph-grazing", "sph-surface", "sph-inside", "sph-tiny",
    "sph-huge",     "sph-unnorm", "sph-camera",  "sph-bad",     "sph-scaled"};

static const char *const descriptions[SPHGEN_COUNT] = {
    "sphere: from 1.5-10 R at a point within 1.2 R",
    "sphere: origin 1e3-1e6 R from the center",
    "sphere: closest approach within 1e-7-1e-2 R of the surface",
    "sphere: origin a float-rounded surface point, in- and outward, tmin 0",
    "sphere: origin inside",
    "sphere: R 1e-4..1e-3, center around 1e4",
    "sphere: R 1e4..1e6, center around 1e5..1e6",
    "sphere: |d| 2^-30..2^30",
    "sphere: 4 x 4 pixel blocks of a pinhole camera",
    "sphere: NaN, Inf, zero-direction and empty-interval lanes among good ones",
    "sphere: ordinary and grazing scenes scaled by 2^+-(21..50), |d| 2^-20..2^20"};

const char *sphgen_category_name(int category)
{
    return category >= 0 && category < SPHGEN_COUNT ? names[category] : NULL;
}

const char *sphgen_category_description(int category)
{
    return category >= 0 && category < SPHGEN_COUNT ? descriptions[category] : NULL;
}

int sphgen_category_find(const char *name)
{
    for (int c = 0; name && c < SPHGEN_COUNT; c++)
        if (strcmp(name, sphgen_category_name(c)) == 0)
            return c;
    return -1;
}

static void rng_for(cylgen_rng *r, uint64_t seed, int cat, uint64_t index, uint64_t role)
{
    uint64_t h = seed ^ 0x737068657265ull; /* apart from the cylinders' draws */
    h ^= cylgen_splitmix64(&h) + (uint64_t)(cat + 1) * 0xd1b54a32d192ed03u;
    h ^= cylgen_splitmix64(&h) + index * 0x9e3779b97f4a7c15u;
    h ^= cylgen_splitmix64(&h) + role;
    cylgen_seed(r, h);
}

static void make_range(int cat, uint64_t seed, size_t n, sphgen_case *out, int shared)
{
    if (cat < 0 || cat >= SPHGEN_COUNT)
        cat = SPHGEN_ORDINARY;
    cylray_sphere s = {{0, 0, 0}, 1};
    size_t batch = (size_t)-1;
    for (size_t i = 0; i < n; i++) {
        size_t b = shared ? 0 : i / CYLGEN_BATCH;
        if (b != batch) {
            cylgen_rng sr;
            rng_for(&sr, seed, cat, b, 1);
            make_sphere(cat, &sr, &s);
            batch = b;
        }
        /* The camera of the pixel's block: shared by the 16 pixels of a block. */
        cylgen_rng r, cam;
        rng_for(&r, seed, cat, i, 2);
        rng_for(&cam, seed, cat, i / 16, 3);
        memset(&out[i], 0, sizeof out[i]);
        out[i].sph = s;
        ball bl = ball_of(&s);
        gen_case(cat, &r, &bl, &cam, i, &out[i]);
    }
}

void sphgen_make(int category, uint64_t seed, size_t n, sphgen_case *out)
{
    make_range(category, seed, n, out, 0);
}

void sphgen_make_shared(int category, uint64_t seed, size_t n, sphgen_case *out)
{
    make_range(category, seed, n, out, 1);
}
