/* SPDX-License-Identifier: MIT */
/* gen.c - the stress-ray generators: one function per category of numerical difficulty.
 *
 * Geometry is built in double from the float cylinder (the values the kernel will see),
 * then rounded to float, so "aimed at the rim" means aimed at the rim of the float
 * cylinder, off only by the final rounding of o and d. */
#include "gen.h"

#include "genutil.h"

#include "../support/rng.h"

#include <float.h>
#include <math.h>
#include <string.h>

/* ---- PRNG --------------------------------------------------------------------- */

uint64_t cylgen_splitmix64(uint64_t *state)
{
    return rng_splitmix64(state);
}

void cylgen_seed(cylgen_rng *r, uint64_t seed)
{
    for (int k = 0; k < 4; k++)
        r->s[k] = cylgen_splitmix64(&seed);
}

static uint64_t rotl(uint64_t x, int k)
{
    return (x << k) | (x >> (64 - k));
}

uint64_t cylgen_next(cylgen_rng *r)
{
    uint64_t *s = r->s;
    uint64_t out = rotl(s[1] * 5, 7) * 9, t = s[1] << 17;
    s[2] ^= s[0];
    s[3] ^= s[1];
    s[1] ^= s[2];
    s[0] ^= s[3];
    s[2] ^= t;
    s[3] = rotl(s[3], 45);
    return out;
}

double cylgen_uniform(cylgen_rng *r)
{
    return rng_unit(cylgen_next(r));
}

static double sign(cylgen_rng *r)
{
    return (cylgen_next(r) >> 63) ? -1.0 : 1.0;
}

/* 2^x and log2(x) from series, so that draws are identical on every libm. */
static double exp2_(double x)
{
    double n = floor(x), f = (x - n) * 0.69314718055994530942, term = 1, sum = 1;
    for (int k = 1; k < 24; k++) {
        term *= f / k;
        sum += term;
    }
    return ldexp(sum, (int)n);
}

static double log2_(double x)
{
    int e;
    double m = frexp(x, &e); /* [0.5, 1) */
    double y = (m - 1) / (m + 1), y2 = y * y, term = y, sum = 0;
    for (int k = 1; k < 60; k += 2) {
        sum += term / k;
        term *= y2;
    }
    return e + 2 * sum / 0.69314718055994530942;
}

/* Log-uniform in [a, b], a > 0. */
static double logu(cylgen_rng *r, double a, double b)
{
    return exp2_(gen_uni(r, log2_(a), log2_(b)));
}

/* Uniform on the unit sphere, by rejection from the cube. */
static v3 rand_dir(cylgen_rng *r)
{
    for (;;) {
        /* One draw per statement: the order of function arguments is unspecified,
         * and gcc and clang do differ. */
        double x = gen_uni(r, -1, 1), y = gen_uni(r, -1, 1), z = gen_uni(r, -1, 1);
        v3 p = mk(x, y, z);
        double l = dot(p, p);
        if (l > 1e-4 && l <= 1)
            return scl(p, 1 / sqrt(l));
    }
}

/* The float cylinder seen in double: unit axis a, two unit perpendiculars p, q. */
typedef struct {
    v3 c, a, p, q;
    double R, H; /* H = INFINITY for infinite */
    int capped;
} frame;

static frame frame_of(const cylray_cylinder *cyl)
{
    frame f;
    f.c = from_f(cyl->center);
    f.a = unit(from_f(cyl->axis));
    int k = fabs(f.a.x[0]) < fabs(f.a.x[1]) ? (fabs(f.a.x[0]) < fabs(f.a.x[2]) ? 0 : 2)
                                            : (fabs(f.a.x[1]) < fabs(f.a.x[2]) ? 1 : 2);
    v3 e = mk(0, 0, 0);
    e.x[k] = 1;
    f.p = unit(cross(f.a, e));
    f.q = cross(f.a, f.p);
    f.R = cyl->radius;
    f.H = cyl->half_height;
    f.capped = (cyl->flags & CYLRAY_CAPPED) != 0;
    return f;
}

/* A unit vector perpendicular to the axis at a random angle. */
static v3 rand_perp(cylgen_rng *r, const frame *f)
{
    for (;;) {
        double a = gen_uni(r, -1, 1), b = gen_uni(r, -1, 1), l = a * a + b * b;
        if (l > 1e-4 && l <= 1)
            return scl(add(scl(f->p, a), scl(f->q, b)), 1 / sqrt(l));
    }
}

/* Axial extent to aim within: the height, or a few radii for an infinite cylinder. */
static double zspan(const frame *f)
{
    return isfinite(f->H) ? f->H : 4 * f->R;
}

/* ---- cylinders ------------------------------------------------------------------ */

enum { KIND_ANY, KIND_CAPPED, KIND_OPEN, KIND_INFINITE };

typedef struct {
    double c_lo, c_hi; /* |center component| range (random sign) */
    double r_lo, r_hi; /* radius, log-uniform */
    int kind;
} cyl_spec;

static void make_cylinder(cylgen_rng *r, const cyl_spec *s, cylray_cylinder *out)
{
    memset(out, 0, sizeof *out);
    for (int k = 0; k < 3; k++) {
        double sg = sign(r); /* one draw per statement: argument order is unspecified */
        out->center[k] = (float)(sg * gen_uni(r, s->c_lo, s->c_hi));
    }
    /* Any nonzero length (unit, 0.25..8, sometimes 1e-4..1e4): the axis is taken as
     * exact, never normalised. A third lie along a coordinate axis exactly (either
     * sign), where kernels may take shortcuts. */
    double u = cylgen_uniform(r);
    double len = u < 0.45 ? 1.0 : u < 0.85 ? logu(r, 0.25, 8) : logu(r, 1e-4, 1e4);
    if (gen_chance(r, 0.35)) {
        int k = (int)(cylgen_next(r) % 3);
        out->axis[k] = (float)(sign(r) * len);
    } else {
        to_f(out->axis, scl(rand_dir(r), len));
    }
    double R = logu(r, s->r_lo, s->r_hi);
    out->radius = (float)R;
    int kind = s->kind;
    if (kind == KIND_ANY) {
        u = cylgen_uniform(r);
        kind = u < 0.45 ? KIND_CAPPED : u < 0.75 ? KIND_OPEN : KIND_INFINITE;
    }
    if (kind == KIND_INFINITE) {
        out->half_height = INFINITY;
        /* The capped flag means nothing without ends; a kernel must not invent them. */
        out->flags = gen_chance(r, 0.25) ? CYLRAY_CAPPED : 0u;
    } else {
        out->half_height = (float)(R * logu(r, 0.2, 5));
        out->flags = kind == KIND_CAPPED ? CYLRAY_CAPPED : 0u;
    }
}

static const cyl_spec spec_ordinary = {0, 10, 0.2, 5, KIND_ANY};

static void category_cylinder(int cat, cylgen_rng *r, cylray_cylinder *out)
{
    cyl_spec s = spec_ordinary;
    switch (cat) {
    case CYLGEN_RIM:
        s.kind = KIND_CAPPED;
        break;
    case CYLGEN_ONE_END:
        s.kind = KIND_CAPPED;
        make_cylinder(r, &s, out);
        out->flags = (cylgen_next(r) >> 63) ? CYLRAY_CAPPED_LO : CYLRAY_CAPPED_HI;
        return;
    case CYLGEN_TINY:
        s.c_lo = 0.5e4;
        s.c_hi = 2e4;
        s.r_lo = 1e-4;
        s.r_hi = 1e-3;
        break;
    case CYLGEN_HUGE:
        s.c_lo = 1e4;
        s.c_hi = 1e5;
        s.r_lo = 1e3;
        s.r_hi = 1e5;
        break;
    case CYLGEN_INFINITE:
        s.kind = KIND_INFINITE;
        break;
    default:
        break;
    }
    make_cylinder(r, &s, out);
}

/* ---- rays ------------------------------------------------------------------------- */

/* A point inside the solid, or a little beyond it when `slack` > 1. */
static v3 point_in(cylgen_rng *r, const frame *f, double slack)
{
    v3 u = rand_perp(r, f);
    double rho = f->R * slack * sqrt(cylgen_uniform(r));
    double z = zspan(f) * slack * gen_uni(r, -1, 1);
    return axpy(axpy(f->c, rho, u), z, f->a);
}

static void set_ray(cylgen_case *c, v3 o, v3 d)
{
    to_f(c->o, o);
    to_f(c->d, d);
}

/* From `dist` away along a random direction towards a point near the solid. */
static void ray_towards(cylgen_rng *r, const frame *f, double dist, double slack,
                        cylgen_case *c)
{
    v3 target = point_in(r, f, slack);
    v3 d = rand_dir(r);
    set_ray(c, axpy(target, -dist, d), d);
    gen_interval(r, dist, &c->tmin, &c->tmax);
}

static void ray_inside(cylgen_rng *r, const frame *f, cylgen_case *c)
{
    v3 o = point_in(r, f, 0.99);
    set_ray(c, o, rand_dir(r));
    gen_interval(r, f->R, &c->tmin, &c->tmax);
}

static void gen_parallel(cylgen_rng *r, const frame *f, cylgen_case *c)
{
    double th = logu(r, 1e-7, 1e-2);
    /* cos and sin of a small angle from their series: exact enough, libm-free. */
    double co = 1 - th * th / 2 + th * th * th * th / 24, si = th - th * th * th / 6;
    double sg = sign(r);
    v3 d = add(scl(f->a, sg * co), scl(rand_perp(r, f), si));
    double rho = gen_chance(r, 0.6) ? f->R * sqrt(cylgen_uniform(r)) : f->R * gen_uni(r, 1, 3);
    double z = zspan(f) * gen_uni(r, -3, 3);
    v3 o = axpy(axpy(f->c, rho, rand_perp(r, f)), z, f->a);
    set_ray(c, o, d);
    gen_interval(r, 2 * f->R / th, &c->tmin, &c->tmax);
}

static void gen_grazing(cylgen_rng *r, const frame *f, cylgen_case *c)
{
    double sg = sign(r);
    double delta = sg * logu(r, 1e-6, 1e-2);
    v3 u = rand_perp(r, f), w = cross(f->a, u);
    double z = zspan(f) * gen_uni(r, -0.9, 0.9);
    /* The closest approach to the axis is at q, distance R (1 + delta), whatever the
     * tilt of d along the axis. */
    v3 q = axpy(axpy(f->c, f->R * (1 + delta), u), z, f->a);
    double tilt = gen_uni(r, -0.7, 0.7);
    v3 d = unit(add(w, scl(f->a, tilt)));
    if (gen_chance(r, 0.5))
        d = scl(d, -1);
    /* Mostly from nearby; a quarter from far away, where the packet rejections of
     * the kernels must keep their margins against a large |o - c|. */
    double dist = f->R * (gen_chance(r, 0.25) ? logu(r, 1e3, 1e6) : gen_uni(r, 2, 20));
    set_ray(c, axpy(q, -dist, d), d);
    gen_interval(r, dist, &c->tmin, &c->tmax);
}

/* A secondary ray: the origin is a surface point (rounded to float), tmin = 0. */
static void gen_surface(cylgen_rng *r, const frame *f, cylgen_case *c)
{
    v3 u = rand_perp(r, f), p, n;
    if (f->capped && gen_chance(r, 0.3)) {
        double s = sign(r);
        p = axpy(axpy(f->c, f->R * 0.95 * sqrt(cylgen_uniform(r)), u), s * f->H, f->a);
        n = scl(f->a, s);
    } else {
        p = axpy(axpy(f->c, f->R, u), zspan(f) * gen_uni(r, -0.95, 0.95), f->a);
        n = u;
    }
    v3 d = rand_dir(r);
    int outward = gen_chance(r, 0.5);
    if ((dot(d, n) > 0) != outward)
        d = scl(d, -1);
    set_ray(c, p, d);
    c->tmin = 0.0f;
    c->tmax = INFINITY;
}

/* Aimed at a rim point through the solid's edge, so that the exact ray enters (or,
 * from inside, leaves) the solid there: a robust hit that a kernel testing side and
 * cap separately can lose to rounding. */
static void gen_rim(cylgen_rng *r, const frame *f, cylgen_case *c)
{
    v3 u = rand_perp(r, f), t = cross(f->a, u);
    double s = sign(r);
    v3 rim = axpy(axpy(f->c, f->R, u), s * f->H, f->a);
    v3 nc = scl(f->a, s); /* the cap's outward normal */
    /* Inward along both outward normals, with a tangential part. */
    double a = gen_uni(r, 0.1, 1), b = gen_uni(r, 0.1, 1), tg = gen_uni(r, -0.5, 0.5) * a;
    v3 d = unit(add(add(scl(u, -a), scl(nc, -b)), scl(t, tg)));
    if (gen_chance(r, 0.25)) {
        /* From inside, leaving at the rim: start a short way back inside. */
        double back = gen_uni(r, 0.05, 0.45) * fmin(f->R * a, 2 * f->H * b);
        set_ray(c, axpy(rim, back, d), scl(d, -1));
        c->tmin = 0.0f;
        c->tmax = INFINITY;
        return;
    }
    double dist = f->R * gen_uni(r, 1, 10);
    set_ray(c, axpy(rim, -dist, d), d);
    c->tmin = 0.0f;
    c->tmax = gen_chance(r, 0.1) ? (float)(dist * gen_uni(r, 1.01, 3)) : INFINITY;
}

static void gen_case(int cat, cylgen_rng *r, cylgen_case *c)
{
    frame f = frame_of(&c->cyl);
    switch (cat) {
    case CYLGEN_FAR:
        ray_towards(r, &f, f.R * logu(r, 1e3, 1e6), 0.9, c);
        break;
    case CYLGEN_PARALLEL:
        gen_parallel(r, &f, c);
        break;
    case CYLGEN_GRAZING:
        gen_grazing(r, &f, c);
        break;
    case CYLGEN_SURFACE:
        gen_surface(r, &f, c);
        break;
    case CYLGEN_INSIDE:
        ray_inside(r, &f, c);
        break;
    case CYLGEN_RIM:
        gen_rim(r, &f, c);
        break;
    case CYLGEN_TINY:
        if (gen_chance(r, 0.2))
            ray_towards(r, &f, f.R * logu(r, 1e3, 1e6), 0.9, c);
        else
            ray_towards(r, &f, f.R * logu(r, 2, 1e3), 1.3, c);
        break;
    case CYLGEN_HUGE:
        /* From outside, as "tiny": the scale is the difficulty here; rays from inside
         * are the "inside" category's. */
        ray_towards(r, &f, f.R * gen_uni(r, 2, 20), 1.3, c);
        break;
    case CYLGEN_UNNORMALIZED: {
        ray_towards(r, &f, f.R * gen_uni(r, 2, 20), 1.3, c);
        double k = logu(r, 1e-3, 1e3);
        for (int j = 0; j < 3; j++)
            c->d[j] = (float)(c->d[j] * k);
        if (isfinite(c->tmax) && c->tmax != FLT_MAX)
            c->tmax = (float)(c->tmax / k);
        c->tmin = (float)(c->tmin / k);
        break;
    }
    case CYLGEN_INFINITE:
        if (gen_chance(r, 0.4))
            ray_inside(r, &f, c);
        else
            ray_towards(r, &f, f.R * gen_uni(r, 2, 20), 1.3, c);
        break;
    case CYLGEN_SCALED: {
        /* The direction times 2^k, |k| <= 100, and the interval over it: the same
         * line and the same hits, at t 2^-k times as large. */
        const double u = cylgen_uniform(r);
        if (u < 0.25)
            gen_parallel(r, &f, c);
        else if (u < 0.5)
            gen_grazing(r, &f, c);
        else
            ray_towards(r, &f, f.R * gen_uni(r, 2, 20), 1.3, c);
        const int k = (int)floor(gen_uni(r, -100, 101));
        for (int j = 0; j < 3; j++)
            c->d[j] = (float)ldexp(c->d[j], k);
        c->tmin = (float)ldexp(c->tmin, -k);
        c->tmax = (float)ldexp(c->tmax, -k);
        break;
    }
    case CYLGEN_ONE_END: {
        /* Both rims (the capped one must stay watertight, the open one lets rays
         * through), from inside, down the axis through the open end, and ordinary. */
        const double u = cylgen_uniform(r);
        if (u < 0.35)
            gen_rim(r, &f, c);
        else if (u < 0.55)
            ray_inside(r, &f, c);
        else if (u < 0.7)
            gen_parallel(r, &f, c);
        else
            ray_towards(r, &f, f.R * gen_uni(r, 2, 20), 1.3, c);
        break;
    }
    case CYLGEN_ORDINARY:
    default:
        ray_towards(r, &f, f.R * gen_uni(r, 2, 20), 1.3, c);
        break;
    }
}

/* ---- the catalogue -------------------------------------------------------------- */

static const char *const names[CYLGEN_COUNT] = {
    "ordinary", "far",  "parallel",     "grazing",  "surface", "inside", "rim",
    "tiny",     "huge", "unnormalized", "infinite", "scaled",  "onecap",
};
static const char *const descriptions[CYLGEN_COUNT] = {
    "random cylinder, origin 2-20 R away, aimed near the solid",
    "origin 1e3-1e6 R away, aimed inside",
    "direction 1e-7-1e-2 rad from the axis, inside and outside the tube",
    "closest approach to the axis R (1 +- 1e-6..1e-2)",
    "origin on the surface (side or cap), tmin = 0, inward and outward",
    "origin inside the solid",
    "capped, aimed exactly at a rim point, entering (or leaving) through the edge",
    "radius 1e-4..1e-3, center at 0.5e4..2e4, origin 2-1e6 R away",
    "radius 1e3..1e5, center at 1e4..1e5, origin 2-20 R away",
    "|d| 1e-3..1e3",
    "infinite cylinders, outside and inside origins",
    "ordinary, parallel or grazing, d times 2^k (|k| <= 100), the interval over it",
    "one disc only: aimed at either rim, from inside, down the axis, ordinary",
};

/* The cylinders' rays need no camera. */
static void cylinder_ray(int cat, cylgen_rng *r, cylgen_rng *cam, size_t index,
                         const cylray_cylinder *cyl, cylgen_case *c)
{
    (void)cam;
    (void)index;
    memset(c, 0, sizeof *c);
    c->cyl = *cyl;
    gen_case(cat, r, c);
}

GEN_SHAPE_DEFINE(cylgen, cylray_cylinder, names, descriptions, CYLGEN_COUNT, 0,
                 category_cylinder, cylinder_ray)

int cylgen_category_count(void)
{
    return CYLGEN_COUNT;
}

/* Spoils one input of a ray by the draw u (the sphere's and the cone's NaN lanes): NaN
 * or Inf in o, d, tmin or tmax, a zero direction, an empty interval; 2 draws in 12
 * leave the ray good, a lane beside the bad ones. */
void cylgen_spoil(uint64_t u, float o[3], float d[3], float *tmin, float *tmax)
{
    const float nan = NAN, inf = INFINITY;
    int k = (int)((u >> 8) % 3);
    switch (u % 12) {
    case 0:
        o[k] = nan;
        break;
    case 1:
        d[k] = nan;
        break;
    case 2:
        o[k] = (u >> 16) & 1 ? inf : -inf;
        break;
    case 3:
        d[k] = (u >> 16) & 1 ? inf : -inf;
        break;
    case 4:
        d[0] = d[1] = d[2] = 0;
        break;
    case 5:
        *tmin = nan;
        break;
    case 6:
        *tmax = nan;
        break;
    case 7:
        *tmin = inf;
        break;
    case 8:
        *tmax = -inf;
        break;
    case 9: /* an empty interval */
        *tmin = 2 * *tmax;
        *tmax = 1;
        *tmin = *tmin > 2 ? *tmin : 2;
        break;
    default: /* a good lane beside the bad ones */
        break;
    }
}
