/* SPDX-License-Identifier: MIT */
/* prepare.c - cylray_prepare, cylray_prepare_sphere, cylray_prepare_cone and their leaves,
 * one row of `shapes` each: every refusal leaves *out (or the leaf) untouched and the
 * input as it was, the exact reference agrees on validity where the shape has one, and
 * accepted edge shapes answer as that reference does on every path. A new shape is a new
 * row; what only one shape has (a cylinder's axis, a cone's slope) stays in its row's
 * own functions.
 *
 * Usage: api_prepare [cylinder|sphere|cone]   (no argument: every row) */
#include <float.h>
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "conref.h"
#include "cylray.h"
#include "guarded.h"
#include "judged.h"
#include "sphref.h"
#include "tcheck.h"

typedef struct field {
    const char *name;
    size_t at; /* offsetof in the shape's struct */
} field;

typedef struct shape shape;
struct shape {
    const char *name, *plural, *report;
    const char *call; /* the prepare call's name, as failures print it */
    size_t size;
    const void *good;
    cylray_status (*prepare)(cylray_prepared *out, const void *in);
    int (*ref_valid)(const void *in); /* NULL: no exact reference to agree with */
    void (*show)(const void *in, char *buf, size_t len);
    /* Each coordinate of each point, set to each bad value, is refused. */
    field points[2];
    const float *bad_coords;
    size_t n_bad_coords;
    /* Each radius, set to each bad value, is refused; 0 is a tip where zero_is_tip. */
    field radii[2];
    const float *bad_radii;
    size_t n_bad_radii;
    int zero_is_tip;
    int has_flags; /* a flags field, at `flags_at`, whose unknown bits are refused */
    size_t flags_at;
    void (*own_refusals)(const shape *S);
    const void *edges; /* n_edges shapes prepare must accept */
    size_t n_edges;
    /* Leaves of widths 4, 8 and 16 built from member(j) for j = 0..M, and a member
     * spoilt by defect `bad` (returns 0 past the last defect). */
    cylray_status (*leaf_prepare[3])(void *leaf, const void *in, const uint32_t *ids, size_t n);
    void (*member)(void *in, int j);
    int (*spoil)(void *in, int bad);
    void (*answers)(void);
};

/* Runs prepare on a heap copy (so AddressSanitizer sees any read past the struct) into a
 * prepared struct filled with a byte pattern, and checks the verdict; a refusal must
 * leave every byte of the pattern. */
static void expect(const shape *S, const void *in, cylray_status want, const char *what)
{
    void *copy = malloc(S->size);
    cylray_prepared *out = aligned_alloc(64, sizeof *out);
    unsigned char pattern[sizeof *out];
    if (!copy || !out)
        exit(2);
    memcpy(copy, in, S->size);
    memset(pattern, 0xa5, sizeof pattern);
    memcpy(out, pattern, sizeof *out);
    cylray_status st = S->prepare(out, copy);
    char shown[256];
    S->show(in, shown, sizeof shown);
    CHECK(st == want, "%s: %s returned %d, expected %d (%s)", what, S->call, (int)st, (int)want,
          shown);
    if (want != CYLRAY_OK)
        CHECK(memcmp(out, pattern, sizeof *out) == 0, "%s: refused, but *out was written",
              what);
    CHECK(memcmp(copy, in, S->size) == 0, "%s: %s wrote its input", what, S->call);
    if (S->ref_valid)
        CHECK((want == CYLRAY_OK) == S->ref_valid(in),
              "%s: the reference disagrees on validity", what);
    free(copy);
    free(out);
}

static void refusals(const shape *S)
{
    char what[128];
    unsigned char *in = malloc(S->size);
    if (!in)
        exit(2);
    for (int p = 0; p < 2 && S->points[p].name; p++)
        for (int k = 0; k < 3; k++)
            for (size_t b = 0; b < S->n_bad_coords; b++) {
                memcpy(in, S->good, S->size);
                memcpy(in + S->points[p].at + (size_t)k * sizeof(float), &S->bad_coords[b],
                       sizeof(float));
                snprintf(what, sizeof what, "%s[%d] = %a", S->points[p].name, k,
                         (double)S->bad_coords[b]);
                expect(S, in, CYLRAY_EINVAL, what);
            }
    for (int r = 0; r < 2 && S->radii[r].name; r++)
        for (size_t i = 0; i < S->n_bad_radii; i++) {
            memcpy(in, S->good, S->size);
            memcpy(in + S->radii[r].at, &S->bad_radii[i], sizeof(float));
            snprintf(what, sizeof what, "%s %a", S->radii[r].name, (double)S->bad_radii[i]);
            /* -0.0 compares equal to 0: a tip, where the other radius allows one. */
            int tip = S->zero_is_tip && S->bad_radii[i] == 0;
            expect(S, in, tip ? CYLRAY_OK : CYLRAY_EINVAL, what);
        }
    if (S->has_flags) {
        /* Whole words with unknown bits, then each unknown bit beside the known ones. */
        const unsigned words[] = {0x4u, 0x7u, 0x80u, 0x80000000u, ~0u, CYLRAY_NORMAL << 4};
        unsigned good_flags;
        memcpy(&good_flags, (const char *)S->good + S->flags_at, sizeof good_flags);
        for (size_t i = 0; i < sizeof words / sizeof words[0] + 30; i++) {
            unsigned f = i < sizeof words / sizeof words[0]
                             ? words[i]
                             : good_flags | 4u << (i - sizeof words / sizeof words[0]);
            memcpy(in, S->good, S->size);
            memcpy(in + S->flags_at, &f, sizeof f);
            snprintf(what, sizeof what, "flags %#x", f);
            expect(S, in, CYLRAY_EINVAL, what);
        }
    }
    free(in);
    if (S->own_refusals)
        S->own_refusals(S);

    cylray_prepared out;
    unsigned char pattern[sizeof out];
    memset(pattern, 0x5a, sizeof pattern);
    memcpy(&out, pattern, sizeof out);
    CHECK(S->prepare(&out, NULL) == CYLRAY_EINVAL, "%s(out, NULL) accepted", S->call);
    CHECK(memcmp(&out, pattern, sizeof out) == 0, "%s(out, NULL) wrote *out", S->call);
    CHECK(S->prepare(NULL, S->good) == CYLRAY_EINVAL, "%s(NULL, in) accepted", S->call);
    CHECK(S->prepare(NULL, NULL) == CYLRAY_EINVAL, "%s(NULL, NULL) accepted", S->call);

    expect(S, S->good, CYLRAY_OK, "the good shape");
    for (size_t i = 0; i < S->n_edges; i++) {
        snprintf(what, sizeof what, "edge %s %zu", S->name, i);
        expect(S, (const char *)S->edges + i * S->size, CYLRAY_OK, what);
    }
}

/* The leaf calls of one width, behind one signature for every shape. */
static const size_t leaf_size[3] = {sizeof(cylray_leaf4), sizeof(cylray_leaf8),
                                    sizeof(cylray_leaf16)};
static int leaf_hits(int w, const void *leaf, const cylray_ray1 *ray)
{
    cylray_ray1 r = *ray;
    cylray_hit1 hit;
    switch (w) {
    case 0:
        return cylray_leaf_intersect4(leaf, &r, &hit, 0) || cylray_leaf_occluded4(leaf, ray, 0);
    case 1:
        return cylray_leaf_intersect8(leaf, &r, &hit, 0) || cylray_leaf_occluded8(leaf, ray, 0);
    default:
        return cylray_leaf_intersect16(leaf, &r, &hit, 0) ||
               cylray_leaf_occluded16(leaf, ray, 0);
    }
}

static void leaf_refusals(const shape *S, int w)
{
    const int M = 4 << w;
    cylray_status (*const prep)(void *, const void *, const uint32_t *, size_t) =
        S->leaf_prepare[w];
    unsigned char *leaf = aligned_alloc(64, leaf_size[w]);
    unsigned char *copy = aligned_alloc(64, leaf_size[w]);
    unsigned char *in = malloc((size_t)(M + 1) * S->size), *keep = malloc(S->size);
    uint32_t ids[17];
    if (!leaf || !copy || !in || !keep)
        exit(2);
    for (int j = 0; j <= M; j++) {
        S->member(in + (size_t)j * S->size, j);
        ids[j] = 100u + (uint32_t)j;
    }
    memset(leaf, 0xa5, leaf_size[w]);
    memcpy(copy, leaf, leaf_size[w]);
    CHECK(prep(leaf, in, ids, (size_t)M + 1) == CYLRAY_EINVAL, "leaf%d: %d %s accepted", M,
          M + 1, S->plural);
    CHECK(prep(leaf, in, ids, (size_t)-1) == CYLRAY_EINVAL, "leaf%d: SIZE_MAX %s accepted", M,
          S->plural);
    CHECK(prep(leaf, NULL, ids, 1) == CYLRAY_EINVAL, "leaf%d: NULL %s accepted", M, S->plural);
    CHECK(prep(NULL, in, ids, 1) == CYLRAY_EINVAL, "leaf%d: NULL leaf accepted", M);
    unsigned char *last = in + (size_t)(M - 1) * S->size;
    for (int bad = 0;; bad++) {
        memcpy(keep, last, S->size);
        if (!S->spoil(last, bad))
            break;
        CHECK(prep(leaf, in, ids, (size_t)M) == CYLRAY_EINVAL,
              "leaf%d: bad %s %d in the last lane accepted", M, S->name, bad);
        memcpy(last, keep, S->size);
    }
    CHECK(memcmp(leaf, copy, leaf_size[w]) == 0, "leaf%d: a refusal wrote the leaf", M);
    CHECK(prep(leaf, in, ids, (size_t)M) == CYLRAY_OK, "leaf%d: a good leaf refused", M);
    CHECK(prep(leaf, in, NULL, (size_t)M) == CYLRAY_OK, "leaf%d: NULL ids refused", M);
    CHECK(prep(leaf, in, ids, 0) == CYLRAY_OK, "leaf%d: an empty leaf refused", M);
    /* Every shape's struct begins with a point of it (a center, or p0). */
    const float *at = S->good;
    cylray_ray1 ray = {{at[0], at[1], at[2] - 10}, {0, 0, 1}, 0, INFINITY};
    CHECK(!leaf_hits(w, leaf, &ray), "leaf%d: an empty leaf of %s hits", M, S->plural);
    free(leaf);
    free(copy);
    free(in);
    free(keep);
}

/* Prepares `in`, then judges a batch of 16 rays repeating the 4 given against the
 * shape's exact band on every width and path. */
static void judge_edge(const void *in,
                       cylray_status (*prepare)(cylray_prepared *, const void *),
                       judged_band_fn band_of, const float rays[4][8], const char *what)
{
    cylray_prepared P;
    CHECK(prepare(&P, in) == CYLRAY_OK, "%s refused", what);
    gbatch b;
    judged_fill(&b, rays, 4, 16);
    judged_rays(&P, band_of, in, &b, 13, 4, what);
}

#define LEAF_CALLS(prefix, T)                                                                  \
    static cylray_status prefix##4(void *l, const void *in, const uint32_t *ids, size_t n)     \
    {                                                                                          \
        return prefix##4_(l, (const T *)in, ids, n);                                           \
    }                                                                                          \
    static cylray_status prefix##8(void *l, const void *in, const uint32_t *ids, size_t n)     \
    {                                                                                          \
        return prefix##8_(l, (const T *)in, ids, n);                                           \
    }                                                                                          \
    static cylray_status prefix##16(void *l, const void *in, const uint32_t *ids, size_t n)    \
    {                                                                                          \
        return prefix##16_(l, (const T *)in, ids, n);                                          \
    }

/* ---- the cylinder --------------------------------------------------------------- */

static const cylray_cylinder good_cyl = {
    {1.0f, -2.0f, 3.0f}, {0.0f, 1.0f, 1.0f}, 0.5f, 2.0f, CYLRAY_CAPPED};

static cylray_status cyl_prepare(cylray_prepared *out, const void *in)
{
    return cylray_prepare(out, in);
}
static void cyl_show(const void *in, char *buf, size_t len)
{
    g_cyl_str(in, buf, len);
}
#define cyl_leaf4_ cylray_leaf_prepare4
#define cyl_leaf8_ cylray_leaf_prepare8
#define cyl_leaf16_ cylray_leaf_prepare16
LEAF_CALLS(cyl_leaf, cylray_cylinder)

static void cyl_member(void *in, int j)
{
    cylray_cylinder *c = in;
    *c = good_cyl;
    c->center[0] += (float)j;
}
static int cyl_spoil(void *in, int bad)
{
    cylray_cylinder *c = in;
    if (bad == 0)
        c->radius = 0;
    else if (bad == 1)
        c->center[2] = NAN;
    else if (bad == 2)
        c->axis[0] = c->axis[1] = c->axis[2] = 0;
    else if (bad == 3)
        c->flags = 8;
    return bad < 4;
}

static void cyl_refusals(const shape *S)
{
    char what[128];
    /* Zero and subnormal axes: no direction, or one whose bits are mostly gone. */
    const float zero_axes[][3] = {
        {0, 0, 0},
        {-0.0f, 0, -0.0f},
        {FLT_TRUE_MIN, 0, 0},
        {0, -FLT_TRUE_MIN, 0},
        {1e-40f, 1e-40f, 1e-40f},
        {0, 0, FLT_MIN / 2},
        {-1e-39f, 0, 1e-42f},
    };
    for (size_t i = 0; i < sizeof zero_axes / sizeof zero_axes[0]; i++) {
        cylray_cylinder c = good_cyl;
        memcpy(c.axis, zero_axes[i], sizeof c.axis);
        snprintf(what, sizeof what, "axis (%a, %a, %a)", c.axis[0], c.axis[1], c.axis[2]);
        expect(S, &c, CYLRAY_EINVAL, what);
    }
    /* Half height: not positive, or NaN (INFINITY is legal: an infinite cylinder). */
    const float bad_h[] = {0.0f, -0.0f, -2.0f, -FLT_TRUE_MIN, NAN, -NAN, -INFINITY};
    for (size_t i = 0; i < sizeof bad_h / sizeof bad_h[0]; i++)
        for (unsigned f = 0; f <= CYLRAY_CAPPED; f++) {
            cylray_cylinder c = good_cyl;
            c.half_height = bad_h[i];
            c.flags = f;
            snprintf(what, sizeof what, "half height %a, flags %u", c.half_height, f);
            expect(S, &c, CYLRAY_EINVAL, what);
        }
}

static const cylray_cylinder cyl_edges[] = {
    {{1, -2, 3}, {0, 1, 1}, 0.5f, INFINITY, 0},
    {{1, -2, 3}, {0, 1, 1}, 0.5f, INFINITY, CYLRAY_CAPPED_LO},
    {{1, -2, 3}, {0, 1, 1}, 0.5f, INFINITY, CYLRAY_CAPPED_HI},
    {{1, -2, 3}, {0, 1, 1}, 0.5f, INFINITY, CYLRAY_CAPPED},
    {{1, -2, 3}, {0, FLT_MIN, 0}, 0.5f, 2, CYLRAY_CAPPED}, /* the smallest normal axis */
    {{1, -2, 3}, {0, -3, 1e-30f}, 0.5f, 2, CYLRAY_CAPPED}, /* magnitudes wildly apart */
    {{1, -2, 3}, {0, 1, 1}, 1e-3f, 1e-3f, CYLRAY_CAPPED},
    {{-0.0f, -2, 3}, {0, 1, 1}, 0.5f, 2, CYLRAY_CAPPED}};

/* The statuses' messages, which no shape owns: run with the cylinder's row. */
static void cyl_answers(void)
{
    const char *ok = cylray_strerror(CYLRAY_OK), *inv = cylray_strerror(CYLRAY_EINVAL);
    CHECK(ok && *ok, "strerror(CYLRAY_OK) gives no message");
    CHECK(inv && *inv, "strerror(CYLRAY_EINVAL) gives no message");
    CHECK(ok && inv && strcmp(ok, inv) != 0, "CYLRAY_OK and CYLRAY_EINVAL read the same");
    const char *nomem = cylray_strerror(CYLRAY_ENOMEM);
    CHECK(nomem && *nomem, "strerror(CYLRAY_ENOMEM) gives no message");
    CHECK(nomem && ok && inv && strcmp(nomem, ok) != 0 && strcmp(nomem, inv) != 0,
          "CYLRAY_ENOMEM reads as another status");
    const char *unk = cylray_strerror((cylray_status)12345);
    CHECK(unk && *unk, "strerror of an unknown status gives no message");
}

/* ---- the sphere and the cone: limits of their kernels' range ---------------------- */

/* Past the range on either side: 0x1.000002p62f is the float after 2^62, 0x1.fffffep-61f
 * the one before 2^-60. */
static const float far_coords[] = {NAN,      -NAN,           INFINITY, -INFINITY, 0x1p63f,
                                   -0x1p63f, 0x1.000002p62f, -FLT_MAX, 1e30f};
/* +0 first: a cone takes the list from its second entry, 0 being its tip. */
static const float far_radii[] = {0.0f,         -0.0f,         -1.0f,    -FLT_TRUE_MIN,
                                  FLT_TRUE_MIN, FLT_MIN,       0x1p-61f, 0x1.fffffep-61f,
                                  NAN,          -NAN,          INFINITY, -INFINITY,
                                  0x1p63f,      0x1.000002p62f};

/* ---- the sphere ----------------------------------------------------------------- */

static const cylray_sphere good_sph = {{1.0f, -2.0f, 3.0f}, 0.5f};

static cylray_status sph_prepare(cylray_prepared *out, const void *in)
{
    return cylray_prepare_sphere(out, in);
}
static int sph_valid(const void *in)
{
    return sphref_valid(in);
}
static void sph_show(const void *in, char *buf, size_t len)
{
    const cylray_sphere *s = in;
    snprintf(buf, len, "c %a %a %a R %a", (double)s->center[0], (double)s->center[1],
             (double)s->center[2], (double)s->radius);
}
static void sph_band(const void *in, const float o[3], const float d[3], float tmin, float tmax,
                     unsigned flags, cylref_band *out)
{
    sphref_band_eval(in, o, d, tmin, tmax, flags, out);
}
#define sph_leaf4_ cylray_leaf_prepare_spheres4
#define sph_leaf8_ cylray_leaf_prepare_spheres8
#define sph_leaf16_ cylray_leaf_prepare_spheres16
LEAF_CALLS(sph_leaf, cylray_sphere)

static void sph_member(void *in, int j)
{
    cylray_sphere *s = in;
    *s = good_sph;
    s->center[0] += (float)j;
}
static int sph_spoil(void *in, int bad)
{
    cylray_sphere *s = in;
    if (bad == 0)
        s->radius = 0;
    else if (bad == 1)
        s->center[2] = NAN;
    else if (bad == 2)
        s->radius = 0x1p63f;
    return bad < 3;
}

static const cylray_sphere sph_edges[] = {
    {{0x1p62f, -0x1p62f, 0}, 0x1p-60f}, {{0, 0, 0}, 0x1p62f},    {{-0.0f, 0, 0}, 1},
    {{FLT_TRUE_MIN, 0, -FLT_MIN}, 2},   {{4e18f, 0, 0}, 1e-10f}, {{0, 0, 0}, 0x1p-60f}};

static void sph_answers(void)
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
    char what[64];
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        snprintf(what, sizeof what, "edge sphere %zu", i);
        judge_edge(&cases[i].s, sph_prepare, sph_band, cases[i].rays, what);
    }

    /* A zeroed prepared struct: never a hit, nothing written (guarded.h checks that). */
    cylray_prepared Z;
    memset(&Z, 0, sizeof Z);
    gbatch b;
    for (size_t i = 0; i < 2; i++) {
        judged_fill(&b, cases[i].rays, 4, 16);
        judged_rays(&Z, sph_band, NULL, &b, 13, 4, "zeroed");
    }
}

/* ---- the cone ------------------------------------------------------------------- */

static const cylray_cone good_cone = {
    {1.0f, -2.0f, 3.0f}, {2.0f, -1.0f, 5.0f}, 0.5f, 0.25f, CYLRAY_CAPPED};

static cylray_status cone_prepare(cylray_prepared *out, const void *in)
{
    return cylray_prepare_cone(out, in);
}
static int cone_valid(const void *in)
{
    return conref_valid(in);
}
static void cone_show(const void *in, char *buf, size_t len)
{
    const cylray_cone *c = in;
    snprintf(buf, len, "p0 %a %a %a p1 %a %a %a r %a %a f %#x", (double)c->p0[0],
             (double)c->p0[1], (double)c->p0[2], (double)c->p1[0], (double)c->p1[1],
             (double)c->p1[2], (double)c->r0, (double)c->r1, c->flags);
}
static void cone_band(const void *in, const float o[3], const float d[3], float tmin,
                      float tmax, unsigned flags, cylref_band *out)
{
    conref_band_eval(in, o, d, tmin, tmax, flags, out);
}
#define cone_leaf4_ cylray_leaf_prepare_cones4
#define cone_leaf8_ cylray_leaf_prepare_cones8
#define cone_leaf16_ cylray_leaf_prepare_cones16
LEAF_CALLS(cone_leaf, cylray_cone)

static void cone_member(void *in, int j)
{
    cylray_cone *c = in;
    *c = good_cone;
    c->p0[0] += (float)j;
    c->p1[0] += (float)j;
    if (j % 3 == 1)
        c->r1 = c->r0; /* a cylinder among the cones */
}
static int cone_spoil(void *in, int bad)
{
    cylray_cone *c = in;
    if (bad == 0)
        c->r0 = c->r1 = 0;
    else if (bad == 1)
        c->p1[2] = NAN;
    else if (bad == 2)
        memcpy(c->p1, c->p0, sizeof c->p1);
    else if (bad == 3)
        c->flags = 8;
    return bad < 4;
}

static void cone_refusals(const shape *S)
{
    char what[128];
    cylray_cone c = good_cone;
    c.r0 = c.r1 = 0;
    expect(S, &c, CYLRAY_EINVAL, "both radii 0");
    c = good_cone;
    memcpy(c.p1, c.p0, sizeof c.p1);
    expect(S, &c, CYLRAY_EINVAL, "p0 == p1");
    c = good_cone;
    c.p0[0] = c.p0[1] = c.p0[2] = 0;
    c.p1[0] = c.p1[1] = c.p1[2] = 0x1p-140f;
    expect(S, &c, CYLRAY_EINVAL, "p1 - p0 subnormal");
    /* too steep, or too wide for its slope (each just past its limit) */
    const cylray_cone steep[] = {{{0, 0, 0}, {0, 0, 1}, 0, 0x1p62f, CYLRAY_CAPPED_LO},
                                 {{0, 0, 0}, {0, 0, 0x1p-126f}, 1, 0, CYLRAY_CAPPED_HI},
                                 {{0, 0, 0}, {0, 0, 0x1p40f}, 0x1p62f, 0x1p-60f, CYLRAY_CAPPED},
                                 {{0, 0, 0}, {0, 0, 1}, 0, 0x1.000002p40f, 0},
                                 {{0, 0, 0}, {0, 0, 1}, 0x1.000002p31f, 0, 0},
                                 {{0, 0, 0}, {0, 0, 0x1p-20f}, 0x1.000002p20f, 0, 0},
                                 {{0, 0, 0}, {0, 0, 0x1p20f}, 0x1p62f, 0x1p61f, 0}};
    for (size_t i = 0; i < sizeof steep / sizeof steep[0]; i++) {
        snprintf(what, sizeof what, "steep cone %zu", i);
        expect(S, &steep[i], CYLRAY_EINVAL, what);
    }
}

static const cylray_cone cone_edges[] = {
    {{0x1p62f, 0, 0}, {0, 0, -0x1p62f}, 0x1p-60f, 0, CYLRAY_CAPPED},
    {{0, 0, 0}, {0, 0, 1}, 0, 0x1p30f, CYLRAY_CAPPED_LO},
    {{0, 0, 0}, {0, 0, 0x1p-100f}, 0x1p-60f, 0, CYLRAY_CAPPED_HI},
    {{-0.0f, 0, 0}, {0, 1, 0}, 1, 1, 0},
    {{4e18f, 0, 0}, {4e18f, 1e12f, 0}, 1e-10f, 2e-10f, CYLRAY_CAPPED},
    {{0, 0, 0}, {0, 0, 1}, 0x1p30f, 0x1p-60f, 0},
    {{0, 0, 0}, {0, 0, 0x1p22f}, 0x1p62f, 0x1p62f, CYLRAY_CAPPED},
    {{0, 0, 0}, {0, 0, 0x1p-20f}, 0x1p20f, 0, CYLRAY_CAPPED}};

/* A cone with r0 == r1 is the cylinder cylray_cylinder_from_endpoints makes: the same
 * bits on every path, width and flag set. */
static void cone_as_cylinder(void)
{
    const float I = INFINITY;
    static const cylray_cone cones[] = {
        {{1, -2, 3}, {2, -1, 5}, 0.5f, 0.5f, CYLRAY_CAPPED},
        {{1e4f, 3, -7}, {1e4f + 0.75f, 3.5f, -7}, 0.125f, 0.125f, CYLRAY_CAPPED_LO},
        {{0, 0, 0}, {0, 0, 3}, 2, 2, CYLRAY_CAPPED_HI},
        {{-5, 1, 0.3f}, {4, 1.7f, 0.1f}, 1e-3f, 1e-3f, 0}};
    static const float rays[4][8] = {{0, 0, -10, 0.1f, 0.05f, 1, 0, I},
                                     {10, 3, 2, -1, -0.3f, 0.1f, 0, I},
                                     {1.3f, -1.6f, 4, 0, 0, -1, 0, I},
                                     {0.2f, 0.1f, 1.5f, 1, 0.5f, 0.25f, 0, I}};
    const cylray_kernels *isas[CYLRAY_ISA_COUNT];
    const int nisa = g_isas(isas);
    for (size_t i = 0; i < sizeof cones / sizeof cones[0]; i++) {
        const cylray_cone *c = &cones[i];
        cylray_prepared Pc, Py;
        cylray_cylinder y;
        CHECK(cylray_prepare_cone(&Pc, c) == CYLRAY_OK, "cylinder cone %zu refused", i);
        CHECK(cylray_cylinder_from_endpoints(&y, c->p0, c->p1, c->r0, c->flags) == CYLRAY_OK &&
                  cylray_prepare(&Py, &y) == CYLRAY_OK,
              "cylinder %zu refused", i);
        gbatch b;
        float aimed[4][8];
        for (int j = 0; j < 4; j++) {
            memcpy(aimed[j], rays[j], sizeof aimed[j]);
            for (int k = 0; k < 3; k++) /* about the cone, so that some rays hit */
                aimed[j][k] += (c->p0[k] + c->p1[k]) / 2;
        }
        judged_fill(&b, (const float(*)[8])aimed, 4, 16);
        for (int s = 0; s < nisa; s++)
            for (unsigned flags = 0; flags <= CYLRAY_FLAGS_ALL; flags++) {
                gresult rc, ry;
                g_intersect(isas[s], 16, &Pc, &b, 16, 0xffffu, flags, 1, &rc);
                g_intersect(isas[s], 16, &Py, &b, 16, 0xffffu, flags, 1, &ry);
                for (size_t j = 0; j < 16; j++)
                    CHECK(g_same_lane(&rc, j, &ry, j, 1),
                          "cylinder cone %zu %s flags %#x lane %zu: not the cylinder's answer",
                          i, isas[s]->name, flags, j);
            }
    }
}

static void cone_answers(void)
{
    cone_as_cylinder();
    const float I = INFINITY;
    static const struct {
        cylray_cone c;
        float rays[4][8];
    } cases[] = {
        {{{0, 0, -1}, {0, 0, 1}, 1, 0, CYLRAY_CAPPED},
         {{0, 0, -5, 0, 0, 1, 0, I},
          {0.5f, 0, -5, 0, 0, 1, 0, I},
          {5, 0, 0, -1, 0, 0, 0, I},
          {0, 0, 5, 0, 0, -1, 0, I}}},
        {{{1e4f, -1e4f, 1e4f}, {1e4f, -1e4f, 1e4f + 1}, 1e-3f, 2e-3f, 0},
         {{1e4f - 1, -1e4f, 1e4f + 0.5f, 1, 0, 0, 0, I},
          {1e4f, -1e4f - 0.5f, 1e4f + 0.5f, 0, 1, 0, 0, I},
          {1e4f + 1e-3f, -1e4f, 1e4f - 1, 0, 0, 1, 0, I},
          {1e4f, -1e4f, 1e4f + 5, 0, 0, -1, 0, I}}},
        {{{0, 0, 0}, {0, 0, 0x1p18f}, 0x1p38f, 0x1p-60f, CYLRAY_CAPPED},
         {{-0x1p38f, 0, 0x1p17f, 1, 0, 0, 0, I},
          {0, 0, -1, 0, 0, 1, 0, I},
          {0x1p36f, 0x1p36f, -0x1p28f, 0, 0, 1, 0, I},
          {0, 0, 0x1p28f, 0, 0, -1, 0, I}}},
        {{{0, 0, 0}, {0, 0, 0x1p-20f}, 0x1p20f, 0, CYLRAY_CAPPED},
         {{-0x1p21f, 0, 0x1p-21f, 1, 0, 0, 0, I},
          {0, 0, -1, 0, 0, 1, 0, I},
          {0x1p19f, 0x1p18f, -5, 0, 0, 1, 0, I},
          {0x1p19f, 0, 0x1p-22f, -1, 0, 0.5f, 0, I}}},
    };
    char what[64];
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        snprintf(what, sizeof what, "edge cone %zu", i);
        judge_edge(&cases[i].c, cone_prepare, cone_band, cases[i].rays, what);
    }
}

/* ---- the table ------------------------------------------------------------------ */

#define N(a) (sizeof(a) / sizeof((a)[0]))

static const float cyl_coords[] = {NAN, -NAN, INFINITY, -INFINITY};
static const float cyl_radii[] = {0.0f, -0.0f, -1.0f,    -FLT_TRUE_MIN,
                                  NAN,  -NAN,  INFINITY, -INFINITY};

static const shape shapes[] = {
    {.name = "cylinder",
     .plural = "cylinders",
     .report = "api-prepare",
     .call = "prepare",
     .size = sizeof(cylray_cylinder),
     .good = &good_cyl,
     .prepare = cyl_prepare,
     .show = cyl_show,
     .points = {{"center", offsetof(cylray_cylinder, center)},
                {"axis", offsetof(cylray_cylinder, axis)}},
     .bad_coords = cyl_coords,
     .n_bad_coords = N(cyl_coords),
     .radii = {{"radius", offsetof(cylray_cylinder, radius)}},
     .bad_radii = cyl_radii,
     .n_bad_radii = N(cyl_radii),
     .has_flags = 1,
     .flags_at = offsetof(cylray_cylinder, flags),
     .own_refusals = cyl_refusals,
     .edges = cyl_edges,
     .n_edges = N(cyl_edges),
     .leaf_prepare = {cyl_leaf4, cyl_leaf8, cyl_leaf16},
     .member = cyl_member,
     .spoil = cyl_spoil,
     .answers = cyl_answers},
    {.name = "sphere",
     .plural = "spheres",
     .report = "api-prepare-sphere",
     .call = "prepare_sphere",
     .size = sizeof(cylray_sphere),
     .good = &good_sph,
     .prepare = sph_prepare,
     .ref_valid = sph_valid,
     .show = sph_show,
     .points = {{"center", offsetof(cylray_sphere, center)}},
     .bad_coords = far_coords,
     .n_bad_coords = N(far_coords),
     .radii = {{"radius", offsetof(cylray_sphere, radius)}},
     .bad_radii = far_radii,
     .n_bad_radii = N(far_radii),
     .edges = sph_edges,
     .n_edges = N(sph_edges),
     .leaf_prepare = {sph_leaf4, sph_leaf8, sph_leaf16},
     .member = sph_member,
     .spoil = sph_spoil,
     .answers = sph_answers},
    {.name = "cone",
     .plural = "cones",
     .report = "api-prepare-cone",
     .call = "prepare_cone",
     .size = sizeof(cylray_cone),
     .good = &good_cone,
     .prepare = cone_prepare,
     .ref_valid = cone_valid,
     .show = cone_show,
     .points = {{"p0", offsetof(cylray_cone, p0)}, {"p1", offsetof(cylray_cone, p1)}},
     .bad_coords = far_coords,
     .n_bad_coords = N(far_coords),
     .radii = {{"r0", offsetof(cylray_cone, r0)}, {"r1", offsetof(cylray_cone, r1)}},
     .bad_radii = far_radii + 1,
     .n_bad_radii = N(far_radii) - 1,
     .zero_is_tip = 1,
     .has_flags = 1,
     .flags_at = offsetof(cylray_cone, flags),
     .own_refusals = cone_refusals,
     .edges = cone_edges,
     .n_edges = N(cone_edges),
     .leaf_prepare = {cone_leaf4, cone_leaf8, cone_leaf16},
     .member = cone_member,
     .spoil = cone_spoil,
     .answers = cone_answers},
};

int main(int argc, char **argv)
{
    const shape *ran = NULL;
    int n = 0;
    for (size_t i = 0; i < N(shapes); i++) {
        const shape *S = &shapes[i];
        if (argc > 1 && strcmp(argv[1], S->name) != 0)
            continue;
        refusals(S);
        for (int w = 0; w < 3; w++)
            leaf_refusals(S, w);
        S->answers();
        ran = S;
        n++;
    }
    if (!n) {
        fprintf(stderr, "api_prepare: no shape '%s'\n", argv[1]);
        return 2;
    }
    return tc_report(n == 1 ? ran->report : "api-prepare (every shape)");
}
