/* SPDX-License-Identifier: MIT */
/* genutil.h - what the shapes' stress-ray generators share: the double vectors, the
 * draws, the ray interval and scalings, the camera block, the category tables and the
 * batch filling, so that a shape brings only its own shapes and rays.
 *
 * Every draw uses only +, -, *, /, sqrt and exact scalings in double, so a seed gives
 * the same cases on every platform. */
#ifndef GENUTIL_H
#define GENUTIL_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>

#include "gen.h"

typedef struct {
    double x[3];
} v3;

static inline v3 mk(double a, double b, double c)
{
    v3 v = {{a, b, c}};
    return v;
}
static inline v3 add(v3 a, v3 b)
{
    return mk(a.x[0] + b.x[0], a.x[1] + b.x[1], a.x[2] + b.x[2]);
}
static inline v3 scl(v3 a, double s)
{
    return mk(a.x[0] * s, a.x[1] * s, a.x[2] * s);
}
static inline v3 axpy(v3 y, double s, v3 a) /* y + s a */
{
    return add(y, scl(a, s));
}
static inline double dot(v3 a, v3 b)
{
    return a.x[0] * b.x[0] + a.x[1] * b.x[1] + a.x[2] * b.x[2];
}
static inline v3 cross(v3 a, v3 b)
{
    return mk(a.x[1] * b.x[2] - a.x[2] * b.x[1], a.x[2] * b.x[0] - a.x[0] * b.x[2],
              a.x[0] * b.x[1] - a.x[1] * b.x[0]);
}
static inline v3 unit(v3 a)
{
    return scl(a, 1.0 / sqrt(dot(a, a)));
}
static inline v3 neg(v3 a)
{
    return mk(-a.x[0], -a.x[1], -a.x[2]);
}
static inline v3 from_f(const float f[3])
{
    return mk(f[0], f[1], f[2]);
}
static inline void to_f(float f[3], v3 a)
{
    for (int k = 0; k < 3; k++)
        f[k] = (float)a.x[k];
}

double gen_uni(cylgen_rng *r, double a, double b); /* uniform in [a, b) */
int gen_chance(cylgen_rng *r, double p);
/* About log-uniform in [2^ea, 2^eb): a uniform exponent and a uniform mantissa, for
 * want of a libm transcendental that is the same everywhere. */
double gen_logu(cylgen_rng *r, int ea, int eb);
v3 gen_dir(cylgen_rng *r);        /* a unit vector, by rejection from the cube */
v3 gen_perp(cylgen_rng *r, v3 a); /* a unit vector perpendicular to the unit a */

/* Mostly [0, inf); sometimes a tmax or tmin near the expected hit distance, so that the
 * clip to the interval is exercised. */
void gen_interval(cylgen_rng *r, double dist, float *tmin, float *tmax);
/* d times 2^-span..2^span (a uniform mantissa), the interval over it, so that the same
 * hits come at other |d|. */
void gen_scale_d(cylgen_rng *r, int span, float d[3], float *tmin, float *tmax);
/* A pixel of a 4 x 4 block of a pinhole camera looking at ctr, the block spread times
 * R wide at ctr: coherent rays sharing an origin, as a primary-ray packet. The camera is
 * the block's (cam); the pixel is index % 16. */
void gen_camera(cylgen_rng *cam, size_t index, v3 ctr, double R, double spread, float o[3],
                float d[3]);

/* The ray categories the sphere's, the cone's and the round cone's generators share, each
 * drawn from the shape's own few draws (gen_ray_row), so that a category means the same
 * on all. A shape numbers its categories its own way and maps them to these. */
typedef enum {
    GEN_RAY_ORDINARY, /* from near-10 R at a point within 1.2 of the solid */
    GEN_RAY_FAR,      /* from 2^10-2^20 R */
    GEN_RAY_GRAZING,
    GEN_RAY_SURFACE,
    GEN_RAY_INSIDE,
    GEN_RAY_TINY, /* ordinary, from 1.05-100 R */
    GEN_RAY_HUGE, /* ordinary, from 1.05-3 R */
    GEN_RAY_UNNORM,
    GEN_RAY_CAMERA,
    GEN_RAY_BAD,
    GEN_RAY_SCALED, /* grazing, at a rim or ordinary, |d| 2^-20..2^20 */
    GEN_RAY_COUNT
} gen_ray_kind;

/* A shape's draws under those categories, on its geometry in double (geo) and its case
 * (c): towards from dist away at a point of the solid grown by slack; point_in a point
 * of it grown by slack; rim NULL where the shape has none. */
typedef struct gen_ray_row {
    void (*towards)(cylgen_rng *r, const void *geo, double dist, double slack, void *c);
    void (*grazing)(cylgen_rng *r, const void *geo, void *c);
    void (*surface)(cylgen_rng *r, const void *geo, void *c);
    v3 (*point_in)(cylgen_rng *r, const void *geo, double slack);
    void (*rim)(cylgen_rng *r, const void *geo, void *c);
} gen_ray_row;

/* The row of towards, grazing, surface and point_in, typed on the shape's geometry and
 * case, and rim (a gen_ray_row hook, or NULL). */
#define GEN_RAY_ROW_DEFINE(name, towards, grazing, surface, point_in, rim)                     \
    static void name##_towards(cylgen_rng *r, const void *g, double dist, double slack,        \
                               void *c)                                                        \
    {                                                                                          \
        towards(r, g, dist, slack, c);                                                         \
    }                                                                                          \
    static void name##_grazing(cylgen_rng *r, const void *g, void *c)                          \
    {                                                                                          \
        grazing(r, g, c);                                                                      \
    }                                                                                          \
    static void name##_surface(cylgen_rng *r, const void *g, void *c)                          \
    {                                                                                          \
        surface(r, g, c);                                                                      \
    }                                                                                          \
    static v3 name##_point_in(cylgen_rng *r, const void *g, double slack)                      \
    {                                                                                          \
        return point_in(r, g, slack);                                                          \
    }                                                                                          \
    static const gen_ray_row name = {name##_towards, name##_grazing, name##_surface,           \
                                     name##_point_in, rim}

/* One case under a shared category: the shape's row and geometry, its size R (the unit
 * of every distance), the camera's aim and its block's spread (in R), the ordinary rays'
 * nearest origin (in R: 1.5 for the sphere and the cone, 2 hull sizes for the round cone),
 * and the case with its ray. */
typedef struct gen_ray_at {
    const gen_ray_row *row;
    const void *geo;
    double R;
    v3 aim;
    double spread, near;
    void *c;
    float *o, *d, *tmin, *tmax;
} gen_ray_at;
/* gen_ray_at's last fields, from a case (a shape, then o, d, tmin, tmax: gen.h). */
#define GEN_RAY_CASE(c) (c), (c)->o, (c)->d, &(c)->tmin, &(c)->tmax

/* Draws the ray of a case of category kind (out of range: ordinary); cam and index as
 * gen_camera's. */
void gen_shared_ray(int kind, cylgen_rng *r, cylgen_rng *cam, size_t index,
                    const gen_ray_at *at);

/* A shape's generator as a row: its categories, its draws kept apart from the other
 * shapes' by salt, and its two hooks. The shape changes every CYLGEN_BATCH cases. */
#define GEN_SHAPE_MAX 64
typedef struct gen_shape {
    const char *const *names;
    const char *const *descriptions;
    int count;
    uint64_t salt;
    size_t case_size;
    void (*shape)(int cat, cylgen_rng *r, void *shape);
    /* Fills the case c whole; cam is the generator of the 16-case camera block. */
    void (*ray)(int cat, cylgen_rng *r, cylgen_rng *cam, size_t index, const void *shape,
                void *c);
} gen_shape;

const char *gen_name(const gen_shape *g, int cat);        /* NULL when out of range */
const char *gen_description(const gen_shape *g, int cat); /* NULL when out of range */
int gen_find(const gen_shape *g, const char *name);       /* -1 when unknown */
/* n cases of a category (out of range: the first); shared: all of batch 0's shape. */
void gen_fill(const gen_shape *g, int cat, uint64_t seed, size_t n, void *out, int shared);

/* A shape's generator from its row: its categories' names and descriptions (count of
 * each), its salt, and its two draws, typed: shape_fn(cat, r, shape_t *) and
 * ray_fn(cat, r, cam, index, const shape_t *, prefix_case *), which fills the case whole.
 * Defines the row prefix_row and the five functions CYLGEN_SHAPE_DECLARE declares. */
#define GEN_SHAPE_DEFINE(prefix, shape_t, names, descriptions, count, salt, shape_fn, ray_fn)  \
    static void prefix##_shape_hook(int cat, cylgen_rng *r, void *shape)                       \
    {                                                                                          \
        shape_fn(cat, r, (shape_t *)shape);                                                    \
    }                                                                                          \
    static void prefix##_ray_hook(int cat, cylgen_rng *r, cylgen_rng *cam, size_t index,       \
                                  const void *shape, void *c)                                  \
    {                                                                                          \
        ray_fn(cat, r, cam, index, (const shape_t *)shape, (prefix##_case *)c);                \
    }                                                                                          \
    _Static_assert(sizeof(shape_t) <= GEN_SHAPE_MAX, #shape_t " fits gen_fill's shape");       \
    static const gen_shape prefix##_row = {names,                                              \
                                           descriptions,                                       \
                                           count,                                              \
                                           salt,                                               \
                                           sizeof(prefix##_case),                              \
                                           prefix##_shape_hook,                                \
                                           prefix##_ray_hook};                                 \
    const char *prefix##_category_name(int category)                                           \
    {                                                                                          \
        return gen_name(&prefix##_row, category);                                              \
    }                                                                                          \
    const char *prefix##_category_description(int category)                                    \
    {                                                                                          \
        return gen_description(&prefix##_row, category);                                       \
    }                                                                                          \
    int prefix##_category_find(const char *name)                                               \
    {                                                                                          \
        return gen_find(&prefix##_row, name);                                                  \
    }                                                                                          \
    void prefix##_make(int category, uint64_t seed, size_t n, prefix##_case *out)              \
    {                                                                                          \
        gen_fill(&prefix##_row, category, seed, n, out, 0);                                    \
    }                                                                                          \
    void prefix##_make_shared(int category, uint64_t seed, size_t n, prefix##_case *out)       \
    {                                                                                          \
        gen_fill(&prefix##_row, category, seed, n, out, 1);                                    \
    }

#endif /* GENUTIL_H */
