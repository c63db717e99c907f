/* SPDX-License-Identifier: MIT */
/* test_ref.h - what the reference's test files share: the check and its counts, the
 * shapes as rows of one table (ref_kind: a shape's exact reference behind one
 * signature), the hand-case runner and the generator checks (test_common.c). A new
 * shape is a member of ref_shape, a ref_kind, and its own rows. */
#ifndef TEST_REF_H
#define TEST_REF_H

#include "conref.h"
#include "cylref.h"
#include "rcref.h"
#include "sphref.h"

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

extern long ref_checks, ref_failures;

#define CHECK(cond, ...)                                                                       \
    do {                                                                                       \
        ref_checks++;                                                                          \
        if (!(cond)) {                                                                         \
            ref_failures++;                                                                    \
            printf("FAIL %s:%d: %s: ", __FILE__, __LINE__, #cond);                             \
            printf(__VA_ARGS__);                                                               \
            printf("\n");                                                                      \
        }                                                                                      \
    } while (0)

static inline cylray_cylinder cyl_z(float R, float H, unsigned flags)
{
    cylray_cylinder c = {{0, 0, 0}, {0, 0, 1}, R, H, flags};
    return c;
}

typedef union ref_shape {
    cylray_cylinder cyl;
    cylray_sphere sph;
    cylray_cone cone;
    rcref_round_cone rc;
} ref_shape;

typedef struct ref_kind {
    const char *name;
    size_t size; /* of the member of ref_shape this kind reads */
    int (*intersect)(const ref_shape *s, const float o[3], const float d[3], float tmin,
                     float tmax, unsigned flags, cylref_hit *out);
    void (*band_eval)(const ref_shape *s, const float o[3], const float d[3], float tmin,
                      float tmax, unsigned flags, cylref_band *out);
    int (*judge)(const cylref_band *b, int hit, int part, float t, double *ulps_beyond);
    int (*valid)(const ref_shape *s); /* NULL: the reference has no verdict of its own */
} ref_kind;

extern const ref_kind ref_cylinder, ref_sphere, ref_cone, ref_round_cone;

/* A ray at a shape with the answer worked out by hand. */
typedef struct ref_hand {
    const char *what;
    ref_shape s;
    float o[3], d[3], tmin, tmax;
    unsigned flags;
    int hit;
    double t;
    int part;
    double n[3]; /* all 0: no normal to check (the apex of a cone has none) */
} ref_hand;

/* Each case: the hit, t to 1e-15 relative, the part, the normal to 1e-15, and the exact
 * answer inside its own band. */
void ref_run_hand(const ref_kind *k, const ref_hand *cases, size_t n);
/* Shapes the reference must refuse (-1 and a miss for a ray o, d) and say so, and shapes
 * at the limits it must take. */
void ref_run_refused(const ref_kind *k, const ref_shape *bad, size_t n, const float o[3],
                     const float d[3]);
void ref_run_valid(const ref_kind *k, const ref_shape *edge, size_t n);

/* A shape's generator: categories by name; cases of `size` bytes, each the shape, then o,
 * d, tmin and tmax at the offsets `at`. */
typedef struct ref_gen {
    const ref_kind *kind;
    int count, far, bad; /* the category count, one category of shared shapes, the bad one */
    size_t size, at[4];
    const char *(*name)(int cat);
    const char *(*description)(int cat);
    int (*find)(const char *name);
    void (*make)(int cat, uint64_t seed, size_t n, void *out, int shared);
} ref_gen;

extern const ref_gen ref_sphere_gen, ref_cone_gen, ref_round_cone_gen;

/* Every category: named both ways, prefix-stable, valid shapes in batches, the exact
 * answer inside its own band, and enough hits; shared shapes all the same. */
void ref_run_generators(const ref_gen *g);

/* Each of n cases (from seed) of each category cats[0..ncats) under the flags 0 and
 * CYLRAY_CULL_BACK, to each(ctx, the case, its category's name, its index, flags): the
 * loop of a shape's check against an independent solver, whose verdicts are its own. */
typedef void ref_case_fn(void *ctx, const void *c, const char *cat, int i, unsigned flags);
void ref_each_case(const ref_gen *g, const int *cats, size_t ncats, uint64_t seed, size_t n,
                   ref_case_fn *each, void *ctx);

/* The defects a band must catch on a stable hit (b->exact.hit, not decision_unstable): 16
 * ulps past the band, a miss and the other face; counts the stable hit in *of and returns
 * how many of the 3 judge caught (0 and nothing counted for any other band). */
typedef int ref_judge_fn(const cylref_band *b, int hit, int part, float t, double *ulps_beyond);
int ref_catch_defects(ref_judge_fn *judge, const cylref_band *b, int *of);

void test_hand_cylinder(void); /* test_hand.c */
void test_hand_sphere(void);
void test_hand_cone(void);
void test_sphref(void);          /* test_sphref.c */
void test_conref(void);          /* test_conref.c */
void test_hand_round_cone(void); /* test_rchand.c */
void test_band_round_cone(void);
void test_rcref(void); /* test_rcref.c */

#endif
