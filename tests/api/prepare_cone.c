/* SPDX-License-Identifier: MIT */
/* prepare_cone.c - cylray_prepare_cone and cylray_leaf_prepare_conesM refuse what
 * describes no cone within the limits and leave *out untouched when they do; accepted
 * edge cones answer as the exact reference does on every path; a cone with r0 == r1
 * answers exactly as the cylinder cylray_cylinder_from_endpoints makes of it. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "conref.h"
#include "cylray.h"
#include "guarded.h"
#include "judged.h"
#include "tcheck.h"

static const cylray_cone good = {
    {1.0f, -2.0f, 3.0f}, {2.0f, -1.0f, 5.0f}, 0.5f, 0.25f, CYLRAY_CAPPED};

static void expect(const cylray_cone *c, cylray_status want, const char *what)
{
    cylray_cone *in = malloc(sizeof *in);
    cylray_prepared *out = aligned_alloc(64, sizeof *out);
    unsigned char pattern[sizeof *out];
    if (!in || !out)
        exit(2);
    *in = *c;
    memset(pattern, 0xa5, sizeof pattern);
    memcpy(out, pattern, sizeof *out);
    cylray_status st = cylray_prepare_cone(out, in);
    CHECK(st == want,
          "%s: prepare_cone returned %d, expected %d (p0 %a %a %a p1 %a %a %a r %a %a f %#x)",
          what, (int)st, (int)want, (double)c->p0[0], (double)c->p0[1], (double)c->p0[2],
          (double)c->p1[0], (double)c->p1[1], (double)c->p1[2], (double)c->r0, (double)c->r1,
          c->flags);
    if (want != CYLRAY_OK)
        CHECK(memcmp(out, pattern, sizeof *out) == 0, "%s: refused, but *out was written",
              what);
    CHECK(memcmp(in, c, sizeof *c) == 0, "%s: prepare_cone wrote its input", what);
    CHECK((want == CYLRAY_OK) == conref_valid(c), "%s: the reference disagrees on validity",
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
    for (int e = 0; e < 2; e++)
        for (int k = 0; k < 3; k++)
            for (size_t b = 0; b < sizeof bad_coord / sizeof bad_coord[0]; b++) {
                cylray_cone c = good;
                (e ? c.p1 : c.p0)[k] = bad_coord[b];
                snprintf(what, sizeof what, "p%d[%d] = %a", e, k, (double)bad_coord[b]);
                expect(&c, CYLRAY_EINVAL, what);
            }
    const float bad_r[] = {-0.0f,
                           -1.0f,
                           -FLT_TRUE_MIN,
                           FLT_TRUE_MIN,
                           FLT_MIN,
                           0x1p-61f,
                           nextafterf(0x1p-60f, 0),
                           NAN,
                           -NAN,
                           INFINITY,
                           -INFINITY,
                           0x1p63f,
                           nextafterf(0x1p62f, INFINITY)};
    for (int e = 0; e < 2; e++)
        for (size_t i = 0; i < sizeof bad_r / sizeof bad_r[0]; i++) {
            cylray_cone c = good;
            *(e ? &c.r1 : &c.r0) = bad_r[i];
            snprintf(what, sizeof what, "r%d %a", e, (double)bad_r[i]);
            /* -0.0 compares equal to 0: a tip, which the other radius allows. */
            expect(&c, bad_r[i] == 0 ? CYLRAY_OK : CYLRAY_EINVAL, what);
        }
    {
        cylray_cone c = good;
        c.r0 = c.r1 = 0;
        expect(&c, CYLRAY_EINVAL, "both radii 0");
        c = good;
        memcpy(c.p1, c.p0, sizeof c.p1);
        expect(&c, CYLRAY_EINVAL, "p0 == p1");
        c = good;
        c.p0[0] = c.p0[1] = c.p0[2] = 0;
        c.p1[0] = c.p1[1] = c.p1[2] = 0x1p-140f;
        expect(&c, CYLRAY_EINVAL, "p1 - p0 subnormal");
        /* too steep, or too wide for its slope (each just past its limit) */
        const cylray_cone steep[] = {
            {{0, 0, 0}, {0, 0, 1}, 0, 0x1p62f, CYLRAY_CAPPED_LO},
            {{0, 0, 0}, {0, 0, 0x1p-126f}, 1, 0, CYLRAY_CAPPED_HI},
            {{0, 0, 0}, {0, 0, 0x1p40f}, 0x1p62f, 0x1p-60f, CYLRAY_CAPPED},
            {{0, 0, 0}, {0, 0, 1}, 0, 0x1.000002p40f, 0},
            {{0, 0, 0}, {0, 0, 1}, 0x1.000002p31f, 0, 0},
            {{0, 0, 0}, {0, 0, 0x1p-20f}, 0x1.000002p20f, 0, 0},
            {{0, 0, 0}, {0, 0, 0x1p20f}, 0x1p62f, 0x1p61f, 0}};
        for (size_t i = 0; i < sizeof steep / sizeof steep[0]; i++) {
            snprintf(what, sizeof what, "steep cone %zu", i);
            expect(&steep[i], CYLRAY_EINVAL, what);
        }
        for (unsigned bit = 4; bit; bit <<= 1) {
            c = good;
            c.flags |= bit;
            snprintf(what, sizeof what, "flag bit %#x", bit);
            expect(&c, CYLRAY_EINVAL, what);
        }
    }
    cylray_prepared out;
    unsigned char pattern[sizeof out];
    memset(pattern, 0x5a, sizeof pattern);
    memcpy(&out, pattern, sizeof out);
    CHECK(cylray_prepare_cone(&out, NULL) == CYLRAY_EINVAL, "prepare_cone(out, NULL)");
    CHECK(memcmp(&out, pattern, sizeof out) == 0, "prepare_cone(out, NULL) wrote *out");
    CHECK(cylray_prepare_cone(NULL, &good) == CYLRAY_EINVAL, "prepare_cone(NULL, in)");
    CHECK(cylray_prepare_cone(NULL, NULL) == CYLRAY_EINVAL, "prepare_cone(NULL, NULL)");

    const cylray_cone edges[] = {
        {{0x1p62f, 0, 0}, {0, 0, -0x1p62f}, 0x1p-60f, 0, CYLRAY_CAPPED},
        {{0, 0, 0}, {0, 0, 1}, 0, 0x1p30f, CYLRAY_CAPPED_LO},
        {{0, 0, 0}, {0, 0, 0x1p-100f}, 0x1p-60f, 0, CYLRAY_CAPPED_HI},
        {{-0.0f, 0, 0}, {0, 1, 0}, 1, 1, 0},
        {{4e18f, 0, 0}, {4e18f, 1e12f, 0}, 1e-10f, 2e-10f, CYLRAY_CAPPED},
        {{0, 0, 0}, {0, 0, 1}, 0x1p30f, 0x1p-60f, 0},
        {{0, 0, 0}, {0, 0, 0x1p22f}, 0x1p62f, 0x1p62f, CYLRAY_CAPPED},
        {{0, 0, 0}, {0, 0, 0x1p-20f}, 0x1p20f, 0, CYLRAY_CAPPED}};
    for (size_t i = 0; i < sizeof edges / sizeof edges[0]; i++) {
        snprintf(what, sizeof what, "edge cone %zu", i);
        expect(&edges[i], CYLRAY_OK, what);
    }
}

#define LEAF_REFUSALS(M)                                                                       \
    static void leaf_refusals##M(void)                                                         \
    {                                                                                          \
        cylray_leaf##M *leaf = aligned_alloc(64, sizeof *leaf);                                \
        cylray_leaf##M *copy = aligned_alloc(64, sizeof *copy);                                \
        cylray_cone c[M + 1];                                                                  \
        uint32_t ids[M + 1];                                                                   \
        if (!leaf || !copy)                                                                    \
            exit(2);                                                                           \
        for (int j = 0; j <= M; j++) {                                                         \
            c[j] = good;                                                                       \
            c[j].p0[0] += (float)j;                                                            \
            c[j].p1[0] += (float)j;                                                            \
            if (j % 3 == 1)                                                                    \
                c[j].r1 = c[j].r0; /* a cylinder among the cones */                            \
            ids[j] = 100u + (uint32_t)j;                                                       \
        }                                                                                      \
        memset(leaf, 0xa5, sizeof *leaf);                                                      \
        *copy = *leaf;                                                                         \
        CHECK(cylray_leaf_prepare_cones##M(leaf, c, ids, M + 1) == CYLRAY_EINVAL,              \
              "leaf%d: %d cones accepted", M, M + 1);                                          \
        CHECK(cylray_leaf_prepare_cones##M(leaf, c, ids, (size_t)-1) == CYLRAY_EINVAL,         \
              "leaf%d: SIZE_MAX cones accepted", M);                                           \
        CHECK(cylray_leaf_prepare_cones##M(leaf, NULL, ids, 1) == CYLRAY_EINVAL,               \
              "leaf%d: NULL cones accepted", M);                                               \
        CHECK(cylray_leaf_prepare_cones##M(NULL, c, ids, 1) == CYLRAY_EINVAL,                  \
              "leaf%d: NULL leaf accepted", M);                                                \
        for (int bad = 0; bad < 4; bad++) {                                                    \
            cylray_cone keep = c[M - 1];                                                       \
            if (bad == 0)                                                                      \
                c[M - 1].r0 = c[M - 1].r1 = 0;                                                 \
            else if (bad == 1)                                                                 \
                c[M - 1].p1[2] = NAN;                                                          \
            else if (bad == 2)                                                                 \
                memcpy(c[M - 1].p1, c[M - 1].p0, sizeof c[M - 1].p1);                          \
            else                                                                               \
                c[M - 1].flags = 8;                                                            \
            CHECK(cylray_leaf_prepare_cones##M(leaf, c, ids, M) == CYLRAY_EINVAL,              \
                  "leaf%d: bad cone %d in the last lane accepted", M, bad);                    \
            c[M - 1] = keep;                                                                   \
        }                                                                                      \
        CHECK(memcmp(leaf, copy, sizeof *leaf) == 0, "leaf%d: a refusal wrote the leaf", M);   \
        CHECK(cylray_leaf_prepare_cones##M(leaf, c, ids, M) == CYLRAY_OK,                      \
              "leaf%d: a good leaf refused", M);                                               \
        CHECK(cylray_leaf_prepare_cones##M(leaf, c, NULL, M) == CYLRAY_OK,                     \
              "leaf%d: NULL ids refused", M);                                                  \
        CHECK(cylray_leaf_prepare_cones##M(leaf, c, ids, 0) == CYLRAY_OK,                      \
              "leaf%d: an empty leaf refused", M);                                             \
        cylray_ray1 ray = {{good.p0[0], good.p0[1], good.p0[2] - 10}, {0, 0, 1}, 0, INFINITY}; \
        cylray_hit1 hit;                                                                       \
        CHECK(!cylray_leaf_intersect##M(leaf, &ray, &hit, 0) &&                                \
                  !cylray_leaf_occluded##M(leaf, &ray, 0),                                     \
              "leaf%d: an empty leaf of cones hits", M);                                       \
        free(leaf);                                                                            \
        free(copy);                                                                            \
    }
LEAF_REFUSALS(4)
LEAF_REFUSALS(8)
LEAF_REFUSALS(16)

static void band_of(const void *shape, const float o[3], const float d[3], float tmin,
                    float tmax, unsigned flags, cylref_band *out)
{
    conref_band_eval((const cylray_cone *)shape, o, d, tmin, tmax, flags, out);
}

/* A cone with r0 == r1 is the cylinder cylray_cylinder_from_endpoints makes: the same
 * bits on every path, width and flag set. */
static void as_cylinder(void)
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

static void edge_answers(void)
{
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
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        cylray_prepared P;
        CHECK(cylray_prepare_cone(&P, &cases[i].c) == CYLRAY_OK, "edge cone %zu refused", i);
        gbatch b;
        judged_fill(&b, cases[i].rays, 4, 16);
        char what[64];
        snprintf(what, sizeof what, "edge cone %zu", i);
        judged_rays(&P, band_of, &cases[i].c, &b, 13, 4, what);
    }
}

int main(void)
{
    refusals();
    leaf_refusals4();
    leaf_refusals8();
    leaf_refusals16();
    as_cylinder();
    edge_answers();
    return tc_report("api-prepare-cone");
}
