/* SPDX-License-Identifier: MIT */
/* gen.h - deterministic stress-ray generators shared by the checker, the bench and the fuzzer.
 *
 * Each category returns cylinders and rays of one numerical difficulty. Output is a
 * pure function of (category, seed, index): case i is the same whatever n is, on every
 * platform (the draw uses only +, -, *, /, sqrt and exact scalings in double, all fixed
 * by IEEE 754; no libm transcendental), so a seed printed by one tool reproduces in
 * another. */
#ifndef CYLGEN_H
#define CYLGEN_H

#include <stddef.h>
#include <stdint.h>

#include "cylray.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The categories, in a fixed order (names are stable; the order may only grow). */
enum {
    CYLGEN_ORDINARY,     /* "ordinary": a ray from a few radii away at a random cylinder */
    CYLGEN_FAR,          /* "far": origin 1e3-1e6 R from the cylinder */
    CYLGEN_PARALLEL,     /* "parallel": 1e-7-1e-2 rad from the axis */
    CYLGEN_GRAZING,      /* "grazing": closest approach within 1e-6-1e-2 R of the surface */
    CYLGEN_SURFACE,      /* "surface": origin on the surface, tmin = 0, in- and outward */
    CYLGEN_INSIDE,       /* "inside": origin inside the solid */
    CYLGEN_RIM,          /* "rim": capped, aimed exactly at a point of the cap rim */
    CYLGEN_TINY,         /* "tiny": radius 1e-4..1e-3, center around 1e4 */
    CYLGEN_HUGE,         /* "huge": radius 1e3..1e5, center around 1e4..1e5, from outside */
    CYLGEN_UNNORMALIZED, /* "unnormalized": |d| 1e-3..1e3 */
    CYLGEN_INFINITE,     /* "infinite": half_height = INFINITY, outside and inside rays */
    CYLGEN_SCALED,       /* "scaled": ordinary, parallel or grazing, |d| 2^-100..2^100 */
    CYLGEN_ONE_END,      /* "onecap": a disc at one end only; rims, inside, down the axis */
    CYLGEN_COUNT
};

/* The cylinder changes every CYLGEN_BATCH cases (cases [k*16, k*16+16) share one), so
 * a packet of 4, 8 or 16 taken at a multiple of its width has one cylinder. */
#define CYLGEN_BATCH 16

/* A shape's generator, declared from its row (prefix, shape type, the case's member):
 *   prefix_case                      the shape, then the ray o, d, tmin, tmax
 *   prefix_category_name(cat)        NULL when out of range
 *   prefix_category_description(cat) one line, for reports; NULL when out of range
 *   prefix_category_find(name)       -1 when unknown
 *   prefix_make(cat, seed, n, out)   n cases; the shape changes every CYLGEN_BATCH cases
 *   prefix_make_shared(...)          n cases that all share batch 0's shape: for streams
 * Each shape's generator defines them with GEN_SHAPE_DEFINE (genutil.h). */
#define CYLGEN_SHAPE_DECLARE(prefix, shape_t, member)                                          \
    typedef struct prefix##_case {                                                             \
        shape_t member;                                                                        \
        float o[3], d[3];                                                                      \
        float tmin, tmax;                                                                      \
    } prefix##_case;                                                                           \
    const char *prefix##_category_name(int category);                                          \
    const char *prefix##_category_description(int category);                                   \
    int prefix##_category_find(const char *name);                                              \
    void prefix##_make(int category, uint64_t seed, size_t n, prefix##_case *out);             \
    void prefix##_make_shared(int category, uint64_t seed, size_t n, prefix##_case *out)

CYLGEN_SHAPE_DECLARE(cylgen, cylray_cylinder, cyl);
int cylgen_category_count(void);

/* The PRNG underneath (xoshiro256**, seeded through splitmix64), for anyone who
 * needs more deterministic draws. */
typedef struct cylgen_rng {
    uint64_t s[4];
} cylgen_rng;
void cylgen_seed(cylgen_rng *r, uint64_t seed);
uint64_t cylgen_next(cylgen_rng *r);
double cylgen_uniform(cylgen_rng *r); /* [0, 1), 53 bits */
uint64_t cylgen_splitmix64(uint64_t *state);
/* Spoils one input of the ray by the draw u: NaN or Inf in o, d, tmin or tmax, a zero
 * direction, or an empty interval (u % 12 below 10; otherwise the ray stays good). */
void cylgen_spoil(uint64_t u, float o[3], float d[3], float *tmin, float *tmax);

#ifdef __cplusplus
}
#endif

#endif /* CYLGEN_H */
