/* SPDX-License-Identifier: MIT */
/* genutil.c - the generators' shared draws and batch filling (see genutil.h). */
#include "genutil.h"

#include <float.h>
#include <string.h>

double gen_uni(cylgen_rng *r, double a, double b)
{
    return a + (b - a) * cylgen_uniform(r);
}

int gen_chance(cylgen_rng *r, double p)
{
    return cylgen_uniform(r) < p;
}

double gen_logu(cylgen_rng *r, int ea, int eb)
{
    int e = ea + (int)(cylgen_next(r) % (uint64_t)(eb - ea));
    double m = gen_uni(r, 1, 2);
    return ldexp(m, e);
}

v3 gen_dir(cylgen_rng *r)
{
    for (;;) {
        /* One draw per statement: the order of function arguments is unspecified. */
        double x = gen_uni(r, -1, 1), y = gen_uni(r, -1, 1), z = gen_uni(r, -1, 1);
        double l = x * x + y * y + z * z;
        if (l > 1e-4 && l <= 1)
            return mk(x / sqrt(l), y / sqrt(l), z / sqrt(l));
    }
}

v3 gen_perp(cylgen_rng *r, v3 a)
{
    for (;;) {
        v3 u = gen_dir(r);
        v3 p = axpy(u, -dot(u, a), a);
        if (dot(p, p) > 1e-4)
            return unit(p);
    }
}

void gen_interval(cylgen_rng *r, double dist, float *tmin, float *tmax)
{
    double u = cylgen_uniform(r);
    *tmin = 0.0f;
    *tmax = INFINITY;
    if (u < 0.12)
        *tmax = (float)(dist * gen_uni(r, 0.5, 1.5));
    else if (u < 0.22)
        *tmin = (float)(dist * gen_uni(r, 0.3, 1.2));
    else if (u < 0.27)
        *tmax = FLT_MAX;
}

void gen_scale_d(cylgen_rng *r, int span, float d[3], float *tmin, float *tmax)
{
    const int e = (int)(cylgen_next(r) % (uint64_t)(2 * span + 1)) - span;
    const double s = ldexp(gen_uni(r, 1, 2), e);
    for (int k = 0; k < 3; k++)
        d[k] = (float)((double)d[k] * s);
    if (*tmin != 0)
        *tmin = (float)((double)*tmin / s);
    if (*tmax != INFINITY && *tmax != FLT_MAX)
        *tmax = (float)((double)*tmax / s);
}

void gen_camera(cylgen_rng *cam, size_t index, v3 ctr, double R, double spread, float o[3],
                float d[3])
{
    v3 fwd = gen_dir(cam);
    double dist = R * gen_uni(cam, 3, 50);
    v3 eye = axpy(ctr, -dist, fwd);
    v3 right = gen_perp(cam, fwd), up = cross(fwd, right);
    double half = spread * R / dist, px = gen_uni(cam, -0.5, 0.5), py = gen_uni(cam, -0.5, 0.5);
    double sx = ((double)(index % 4) - 1.5 + px) / 1.5 * half,
           sy = ((double)(index / 4 % 4) - 1.5 + py) / 1.5 * half;
    to_f(o, eye);
    to_f(d, axpy(axpy(fwd, sx, right), sy, up));
}

static void ordinary(cylgen_rng *r, const gen_ray_at *a)
{
    a->row->towards(r, a->geo, a->R * gen_uni(r, a->near, 10), 1.2, a->c);
}

void gen_shared_ray(int kind, cylgen_rng *r, cylgen_rng *cam, size_t index, const gen_ray_at *a)
{
    const gen_ray_row *h = a->row;
    switch (kind) {
    case GEN_RAY_FAR:
        h->towards(r, a->geo, a->R * gen_logu(r, 10, 20), 1.1, a->c);
        break;
    case GEN_RAY_GRAZING:
        h->grazing(r, a->geo, a->c);
        break;
    case GEN_RAY_SURFACE:
        h->surface(r, a->geo, a->c);
        break;
    case GEN_RAY_INSIDE:
        to_f(a->o, h->point_in(r, a->geo, 0.99));
        to_f(a->d, gen_dir(r));
        gen_interval(r, a->R, a->tmin, a->tmax);
        break;
    case GEN_RAY_TINY:
    case GEN_RAY_HUGE:
        h->towards(r, a->geo, a->R * gen_uni(r, 1.05, kind == GEN_RAY_TINY ? 100 : 3), 1.2,
                   a->c);
        break;
    case GEN_RAY_UNNORM:
        ordinary(r, a);
        gen_scale_d(r, 30, a->d, a->tmin, a->tmax);
        break;
    case GEN_RAY_CAMERA:
        gen_camera(cam, index, a->aim, a->R, a->spread, a->o, a->d);
        *a->tmin = 0.0f;
        *a->tmax = INFINITY;
        break;
    case GEN_RAY_BAD:
        /* one input made unusable in most lanes (cylgen_spoil): none of them may hit */
        ordinary(r, a);
        cylgen_spoil(cylgen_next(r), a->o, a->d, a->tmin, a->tmax);
        break;
    case GEN_RAY_SCALED:
        /* the rim's draw only where there is one, so that a shape without keeps its cases */
        if (gen_chance(r, 0.3))
            h->grazing(r, a->geo, a->c);
        else if (h->rim && gen_chance(r, 0.2))
            h->rim(r, a->geo, a->c);
        else
            ordinary(r, a);
        gen_scale_d(r, 20, a->d, a->tmin, a->tmax);
        break;
    case GEN_RAY_ORDINARY:
    default:
        ordinary(r, a);
        break;
    }
}

const char *gen_name(const gen_shape *g, int cat)
{
    return cat >= 0 && cat < g->count ? g->names[cat] : NULL;
}

const char *gen_description(const gen_shape *g, int cat)
{
    return cat >= 0 && cat < g->count ? g->descriptions[cat] : NULL;
}

int gen_find(const gen_shape *g, const char *name)
{
    for (int c = 0; name && c < g->count; c++)
        if (strcmp(name, g->names[c]) == 0)
            return c;
    return -1;
}

/* One generator per (seed, shape, category, index, role): a case is independent of n
 * and of the order it is made in. */
static void rng_for(cylgen_rng *r, uint64_t seed, int cat, uint64_t index, uint64_t role)
{
    uint64_t h = seed;
    h ^= cylgen_splitmix64(&h) + (uint64_t)(cat + 1) * 0xd1b54a32d192ed03u;
    h ^= cylgen_splitmix64(&h) + index * 0x9e3779b97f4a7c15u;
    h ^= cylgen_splitmix64(&h) + role;
    cylgen_seed(r, h);
}

void gen_fill(const gen_shape *g, int cat, uint64_t seed, size_t n, void *out, int shared)
{
    if (cat < 0 || cat >= g->count)
        cat = 0;
    seed ^= g->salt;
    _Alignas(max_align_t) unsigned char shape[GEN_SHAPE_MAX];
    memset(shape, 0, sizeof shape);
    size_t batch = (size_t)-1;
    for (size_t i = 0; i < n; i++) {
        size_t b = shared ? 0 : i / CYLGEN_BATCH;
        if (b != batch) {
            cylgen_rng sr;
            rng_for(&sr, seed, cat, b, 1);
            g->shape(cat, &sr, shape);
            batch = b;
        }
        cylgen_rng r, cam;
        rng_for(&r, seed, cat, i, 2);
        rng_for(&cam, seed, cat, i / 16, 3);
        g->ray(cat, &r, &cam, i, shape, (unsigned char *)out + i * g->case_size);
    }
}
