/* SPDX-License-Identifier: MIT */
/* prepare_sphere.c - cylray_prepare_sphere and cylray_leaf_prepare_spheresM refuse what
 * describes no sphere within the limits, leave *out untouched when they do, and accept
 * the edge cases, whose spheres then answer as the exact reference does on every path;
 * a zeroed cylray_prepared never hits. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cylray.h"
#include "guarded.h"
#include "judged.h"
#include "sphref.h"
#include "tcheck.h"

static const cylray_sphere good = {{1.0f, -2.0f, 3.0f}, 0.5f};

/* As api-prepare's: a heap copy of the input, a patterned *out that a refusal must
 * leave as it was. */
static void expect(const cylray_sphere *s, cylray_status want, const char *what)
{
    cylray_sphere *in = malloc(sizeof *in);
    cylray_prepared *out = aligned_alloc(64, sizeof *out);
    unsigned char pattern[sizeof *out];
    if (!in || !out)
        exit(2);
    *in = *s;
    memset(pattern, 0xa5, sizeof pattern);
    memcpy(out, pattern, sizeof *out);
    cylray_status st = cylray_prepare_sphere(out, in);
    CHECK(st == want, "%s: prepare_sphere returned %d, expected %d (c %a %a %a R %a)", what,
          (int)st, (int)want, (double)s->center[0], (double)s->center[1], (double)s->center[2],
          (double)s->radius);
    if (want != CYLRAY_OK)
        CHECK(memcmp(out, pattern, sizeof *out) == 0, "%s: refused, but *out was written",
              what);
    CHECK(memcmp(in, s, sizeof *s) == 0, "%s: prepare_sphere wrote its input", what);
    CHECK((want == CYLRAY_OK) == sphref_valid(s), "%s: the reference disagrees on validity",
          what);
    free(in);
    free(out);
}

static void refusals(void)
{
    char what[128];
    const float bad_coord[] = {
        NAN,      -NAN, INFINITY, -INFINITY, 0x1p63f, -0x1p63f, nextafterf(0x1p62f, INFINITY),
        -FLT_MAX, 1e30f};
    for (int k = 0; k < 3; k++)
        for (size_t b = 0; b < sizeof bad_coord / sizeof bad_coord[0]; b++) {
            cylray_sphere s = good;
            s.center[k] = bad_coord[b];
            snprintf(what, sizeof what, "center[%d] = %a", k, (double)bad_coord[b]);
            expect(&s, CYLRAY_EINVAL, what);
        }
    const float bad_r[] = {0.0f,         -0.0f,
                           -1.0f,        -FLT_TRUE_MIN,
                           FLT_TRUE_MIN, FLT_MIN,
                           0x1p-61f,     nextafterf(0x1p-60f, 0),
                           NAN,          -NAN,
                           INFINITY,     -INFINITY,
                           0x1p63f,      nextafterf(0x1p62f, INFINITY)};
    for (size_t i = 0; i < sizeof bad_r / sizeof bad_r[0]; i++) {
        cylray_sphere s = good;
        s.radius = bad_r[i];
        snprintf(what, sizeof what, "radius %a", (double)s.radius);
        expect(&s, CYLRAY_EINVAL, what);
    }
    cylray_prepared out;
    unsigned char pattern[sizeof out];
    memset(pattern, 0x5a, sizeof pattern);
    memcpy(&out, pattern, sizeof out);
    CHECK(cylray_prepare_sphere(&out, NULL) == CYLRAY_EINVAL, "prepare_sphere(out, NULL)");
    CHECK(memcmp(&out, pattern, sizeof out) == 0, "prepare_sphere(out, NULL) wrote *out");
    CHECK(cylray_prepare_sphere(NULL, &good) == CYLRAY_EINVAL, "prepare_sphere(NULL, in)");
    CHECK(cylray_prepare_sphere(NULL, NULL) == CYLRAY_EINVAL, "prepare_sphere(NULL, NULL)");

    const cylray_sphere edges[] = {
        {{0x1p62f, -0x1p62f, 0}, 0x1p-60f}, {{0, 0, 0}, 0x1p62f},    {{-0.0f, 0, 0}, 1},
        {{FLT_TRUE_MIN, 0, -FLT_MIN}, 2},   {{4e18f, 0, 0}, 1e-10f}, {{0, 0, 0}, 0x1p-60f}};
    for (size_t i = 0; i < sizeof edges / sizeof edges[0]; i++) {
        snprintf(what, sizeof what, "edge sphere %zu", i);
        expect(&edges[i], CYLRAY_OK, what);
    }
}

#define LEAF_REFUSALS(M)                                                                       \
    static void leaf_refusals##M(void)                                                         \
    {                                                                                          \
        cylray_leaf##M *leaf = aligned_alloc(64, sizeof *leaf);                                \
        cylray_leaf##M *copy = aligned_alloc(64, sizeof *copy);                                \
        cylray_sphere s[M + 1];                                                                \
        uint32_t ids[M + 1];                                                                   \
        if (!leaf || !copy)                                                                    \
            exit(2);                                                                           \
        for (int j = 0; j <= M; j++) {                                                         \
            s[j] = good;                                                                       \
            s[j].center[0] += (float)j;                                                        \
            ids[j] = 100u + (uint32_t)j;                                                       \
        }                                                                                      \
        memset(leaf, 0xa5, sizeof *leaf);                                                      \
        *copy = *leaf;                                                                         \
        CHECK(cylray_leaf_prepare_spheres##M(leaf, s, ids, M + 1) == CYLRAY_EINVAL,            \
              "leaf%d: %d spheres accepted", M, M + 1);                                        \
        CHECK(cylray_leaf_prepare_spheres##M(leaf, s, ids, (size_t)-1) == CYLRAY_EINVAL,       \
              "leaf%d: SIZE_MAX spheres accepted", M);                                         \
        CHECK(cylray_leaf_prepare_spheres##M(leaf, NULL, ids, 1) == CYLRAY_EINVAL,             \
              "leaf%d: NULL spheres accepted", M);                                             \
        CHECK(cylray_leaf_prepare_spheres##M(NULL, s, ids, 1) == CYLRAY_EINVAL,                \
              "leaf%d: NULL leaf accepted", M);                                                \
        for (int bad = 0; bad < 3; bad++) {                                                    \
            cylray_sphere keep = s[M - 1];                                                     \
            if (bad == 0)                                                                      \
                s[M - 1].radius = 0;                                                           \
            else if (bad == 1)                                                                 \
                s[M - 1].center[2] = NAN;                                                      \
            else                                                                               \
                s[M - 1].radius = 0x1p63f;                                                     \
            CHECK(cylray_leaf_prepare_spheres##M(leaf, s, ids, M) == CYLRAY_EINVAL,            \
                  "leaf%d: bad sphere %d in the last lane accepted", M, bad);                  \
            s[M - 1] = keep;                                                                   \
        }                                                                                      \
        CHECK(memcmp(leaf, copy, sizeof *leaf) == 0, "leaf%d: a refusal wrote the leaf", M);   \
        CHECK(cylray_leaf_prepare_spheres##M(leaf, s, ids, M) == CYLRAY_OK,                    \
              "leaf%d: a good leaf refused", M);                                               \
        CHECK(cylray_leaf_prepare_spheres##M(leaf, s, NULL, M) == CYLRAY_OK,                   \
              "leaf%d: NULL ids refused", M);                                                  \
        CHECK(cylray_leaf_prepare_spheres##M(leaf, s, ids, 0) == CYLRAY_OK,                    \
              "leaf%d: an empty leaf refused", M);                                             \
        cylray_ray1 ray = {                                                                    \
            {good.center[0], good.center[1], good.center[2] - 10}, {0, 0, 1}, 0, INFINITY};    \
        cylray_hit1 hit;                                                                       \
        CHECK(!cylray_leaf_intersect##M(leaf, &ray, &hit, 0) &&                                \
                  !cylray_leaf_occluded##M(leaf, &ray, 0),                                     \
              "leaf%d: an empty leaf of spheres hits", M);                                     \
        free(leaf);                                                                            \
        free(copy);                                                                            \
    }
LEAF_REFUSALS(4)
LEAF_REFUSALS(8)
LEAF_REFUSALS(16)

static void band_of(const void *shape, const float o[3], const float d[3], float tmin,
                    float tmax, unsigned flags, cylref_band *out)
{
    sphref_band_eval((const cylray_sphere *)shape, o, d, tmin, tmax, flags, out);
}

static void edge_answers(void)
{
    const float I = INFINITY;
    static const struct {
        cylray_sphere s;
        float rays[4][8]; /* ox oy oz dx dy dz tmin tmax */
    } cases[] = {
        /* Origins within 2^62 of the center in each coordinate (the working range). */
        {{{0, 0, 0}, 0x1p62f},
         {{-0x1p62f, -0x1p62f, 0, 1, 1, 0, 0, I},
          {0, 0, 0, 0, 1, 0, 0, I},
          {-0x1p62f, 0x1p61f, -0x1p62f, 1, 0, 1, 0, I},
          {-0x1p62f, 0, -0x1p62f, 0x1p-30f, 0, 0x1p30f, 0, I}}},
        {{{0, 0, 0}, 0x1p-60f},
         {{-1, 0, 0, 1, 0, 0, 0, I},
          {-1, 0x1p-61f, 0, 1, 0, 0, 0, I},
          {-1, 0x1p-59f, 0, 1, 0, 0, 0, I},
          {0, 0, 0, 0x1p-20f, 1, -1, 0, I}}},
        {{{0x1p62f, 0, 0}, 0x1p-60f},
         {{0x1p62f - 0x1p40f, 0, 0, 1, 0, 0, 0, I},
          {0x1p62f, 0, -1, 0, 0, 1, 0, I},
          {0x1p62f, 0, 0, 0, 0, 1, 0, I},
          {0x1p62f, 0x1p-61f, -1, 0, 0, 1, 0, I}}},
        {{{1e4f, -1e4f, 1e4f}, 1e-3f},
         {{1e4f - 1, -1e4f, 1e4f, 1, 0, 0, 0, I},
          {1e4f, -1e4f, 1e4f, 0, 0, 1, 0, I},
          {1e4f, -1e4f - 0.5f, 1e4f + 9.5e-4f, 0, 1, 0, 0, I},
          {1e4f, -1e4f - 0.5f, 1e4f + 1.05e-3f, 0, 1, 0, 0, I}}},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        cylray_prepared P;
        CHECK(cylray_prepare_sphere(&P, &cases[i].s) == CYLRAY_OK, "edge sphere %zu refused",
              i);
        gbatch b;
        judged_fill(&b, cases[i].rays, 4, 16);
        char what[64];
        snprintf(what, sizeof what, "edge sphere %zu", i);
        judged_rays(&P, band_of, &cases[i].s, &b, 13, 4, what);
    }

    /* A zeroed prepared struct: never a hit, nothing written (guarded.h checks that). */
    cylray_prepared Z;
    memset(&Z, 0, sizeof Z);
    gbatch b;
    judged_fill(&b, cases[0].rays, 4, 16);
    judged_rays(&Z, band_of, NULL, &b, 13, 4, "zeroed");
    judged_fill(&b, cases[1].rays, 4, 16);
    judged_rays(&Z, band_of, NULL, &b, 13, 4, "zeroed");
}

int main(void)
{
    refusals();
    leaf_refusals4();
    leaf_refusals8();
    leaf_refusals16();
    edge_answers();
    return tc_report("api-prepare-sphere");
}
