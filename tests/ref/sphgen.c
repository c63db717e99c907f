/* SPDX-License-Identifier: MIT */
/* sphgen.c - the sphere stress-ray generators: one function per category.
 *
 * Geometry is built in double from the float sphere (the values the kernel will see),
 * then rounded to float, so "a surface point" is a point of the float sphere rounded
 * once, and "grazing" is grazing for the float sphere, off only by the rounding of o
 * and d. */
#include "sphgen.h"

#include "genutil.h"

#include <float.h>
#include <math.h>
#include <string.h>

/* ---- spheres ------------------------------------------------------------------- */

static void make_sphere(int cat, cylgen_rng *r, cylray_sphere *s)
{
    double R, span;
    switch (cat) {
    case SPHGEN_TINY:
        R = gen_uni(r, 1e-4, 1e-3);
        span = 1e4;
        break;
    case SPHGEN_HUGE:
        R = gen_uni(r, 1e4, 1e6);
        span = gen_uni(r, 1e5, 1e6);
        break;
    case SPHGEN_SCALED: {
        /* Beyond 2^+-20 the kernel scales its discriminant: both sides of that. */
        int e = 21 + (int)(cylgen_next(r) % 30);
        double k = ldexp(1.0, gen_chance(r, 0.5) ? e : -e);
        R = gen_uni(r, 0.1, 10) * k;
        span = 10 * k;
        break;
    }
    default:
        R = gen_uni(r, 0.1, 10);
        span = 10;
        break;
    }
    for (int k = 0; k < 3; k++) {
        double x = gen_uni(r, -span, span);
        /* Tiny spheres sit far out on every axis: o - c then loses everything to
         * rounding unless it is formed exactly. */
        if (cat == SPHGEN_TINY) {
            const double sign = gen_chance(r, 0.5) ? -1 : 1;
            x = sign * gen_uni(r, 0.5 * span, span);
        }
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
    return axpy(b->c, b->R * slack * cbrt(u), gen_dir(r));
}

static void towards(cylgen_rng *r, const ball *b, double dist, double slack, sphgen_case *c)
{
    v3 target = point_in(r, b, slack), d = gen_dir(r);
    to_f(c->o, axpy(target, -dist, d));
    to_f(c->d, d);
    gen_interval(r, dist, &c->tmin, &c->tmax);
}

static void gen_grazing(cylgen_rng *r, const ball *b, sphgen_case *c)
{
    v3 d = gen_dir(r), u = gen_perp(r, d);
    double eps = gen_logu(r, -23, -7);
    eps *= gen_chance(r, 0.5) ? 1 : -1;
    double dist = b->R * gen_uni(r, 2, 10);
    v3 closest = axpy(b->c, b->R * (1 + eps), u);
    to_f(c->o, axpy(closest, -dist, d));
    to_f(c->d, d);
    gen_interval(r, dist, &c->tmin, &c->tmax);
}

/* A secondary ray: a point of the sphere rounded to float, leaving outward or going
 * in (a reflection or a refraction), tmin = 0. */
static void gen_surface(cylgen_rng *r, const ball *b, sphgen_case *c)
{
    v3 n = gen_dir(r), d = gen_dir(r);
    int outward = gen_chance(r, 0.5);
    if ((dot(d, n) > 0) != outward)
        d = mk(-d.x[0], -d.x[1], -d.x[2]);
    to_f(c->o, axpy(b->c, b->R, n));
    to_f(c->d, d);
    c->tmin = 0.0f;
    c->tmax = INFINITY;
}

GEN_RAY_ROW_DEFINE(ball_rays, towards, gen_grazing, gen_surface, point_in, NULL);

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

/* The sphere's categories are the shared ones, in their order. */
_Static_assert((int)SPHGEN_ORDINARY == GEN_RAY_ORDINARY && (int)SPHGEN_FAR == GEN_RAY_FAR &&
                   (int)SPHGEN_GRAZING == GEN_RAY_GRAZING &&
                   (int)SPHGEN_SURFACE == GEN_RAY_SURFACE &&
                   (int)SPHGEN_INSIDE == GEN_RAY_INSIDE && (int)SPHGEN_TINY == GEN_RAY_TINY &&
                   (int)SPHGEN_HUGE == GEN_RAY_HUGE &&
                   (int)SPHGEN_UNNORMALIZED == GEN_RAY_UNNORM &&
                   (int)SPHGEN_CAMERA == GEN_RAY_CAMERA && (int)SPHGEN_BAD == GEN_RAY_BAD &&
                   (int)SPHGEN_SCALED == GEN_RAY_SCALED && (int)SPHGEN_COUNT == GEN_RAY_COUNT,
               "sphgen's categories are gen_ray_kind's");

static void sphere_ray(int cat, cylgen_rng *r, cylgen_rng *cam, size_t index,
                       const cylray_sphere *sph, sphgen_case *c)
{
    memset(c, 0, sizeof *c);
    c->sph = *sph;
    ball bl = ball_of(&c->sph);
    /* The camera's block spans a bit more than the sphere's silhouette, so that its edge
     * pixels miss or graze. */
    const gen_ray_at at = {&ball_rays, &bl, bl.R, bl.c, 1.3, 1.5, GEN_RAY_CASE(c)};
    gen_shared_ray(cat, r, cam, index, &at);
}

GEN_SHAPE_DEFINE(sphgen, cylray_sphere, names, descriptions, SPHGEN_COUNT, 0x737068657265ull,
                 make_sphere, sphere_ray)
