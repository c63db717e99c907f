/* SPDX-License-Identifier: MIT */
/* test_common.c - the reference tests' shared harness: the counts, the shape table, the
 * hand-case runner and the generator checks (test_ref.h). */
#include "congen.h"
#include "gen.h"
#include "rcgen.h"
#include "sphgen.h"
#include "test_ref.h"

#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

long ref_checks, ref_failures;

/* A reference's calls behind ref_kind's signatures, on the union's member `m`. */
#define REF_CALLS(ref, m)                                                                      \
    static int ref##_x(const ref_shape *s, const float o[3], const float d[3], float tmin,     \
                       float tmax, unsigned flags, cylref_hit *out)                            \
    {                                                                                          \
        return ref##_intersect(&s->m, o, d, tmin, tmax, flags, out);                           \
    }                                                                                          \
    static void ref##_b(const ref_shape *s, const float o[3], const float d[3], float tmin,    \
                        float tmax, unsigned flags, cylref_band *out)                          \
    {                                                                                          \
        ref##_band_eval(&s->m, o, d, tmin, tmax, flags, out);                                  \
    }
#define REF_VALID(ref, m)                                                                      \
    static int ref##_v(const ref_shape *s)                                                     \
    {                                                                                          \
        return ref##_valid(&s->m);                                                             \
    }

REF_CALLS(cylref, cyl)
REF_CALLS(sphref, sph)
REF_VALID(sphref, sph)
REF_CALLS(conref, cone)
REF_VALID(conref, cone)
REF_CALLS(rcref, rc)
REF_VALID(rcref, rc)

const ref_kind ref_cylinder = {
    "cylinder", sizeof(cylray_cylinder), cylref_x, cylref_b, cylref_judge, NULL};
const ref_kind ref_sphere = {"sphere", sizeof(cylray_sphere), sphref_x,
                             sphref_b, sphref_judge,          sphref_v};
const ref_kind ref_cone = {"cone",   sizeof(cylray_cone), conref_x,
                           conref_b, conref_judge,        conref_v};
const ref_kind ref_round_cone = {
    "round cone", sizeof(rcref_round_cone), rcref_x, rcref_b, rcref_judge, rcref_v};

/* A generator's cases (`gen`_case: the shape, then o, d, tmin, tmax) behind ref_gen. */
#define REF_GEN(gen, P, kind)                                                                  \
    static void gen##_any(int cat, uint64_t seed, size_t n, void *out, int shared)             \
    {                                                                                          \
        (shared ? gen##_make_shared : gen##_make)(cat, seed, n, out);                          \
    }                                                                                          \
    const ref_gen kind##_gen = {&kind,                                                         \
                                P##_COUNT,                                                     \
                                P##_FAR,                                                       \
                                P##_BAD,                                                       \
                                sizeof(gen##_case),                                            \
                                {offsetof(gen##_case, o), offsetof(gen##_case, d),             \
                                 offsetof(gen##_case, tmin), offsetof(gen##_case, tmax)},      \
                                gen##_category_name,                                           \
                                gen##_category_description,                                    \
                                gen##_category_find,                                           \
                                gen##_any};

REF_GEN(sphgen, SPHGEN, ref_sphere)
REF_GEN(congen, CONGEN, ref_cone)
REF_GEN(rcgen, RCGEN, ref_round_cone)

/* The shape is each case's first member. */
static void unpack(const ref_gen *g, const unsigned char *c, ref_shape *s, float o[3],
                   float d[3], float *tmin, float *tmax)
{
    memset(s, 0, sizeof *s);
    memcpy(s, c, g->kind->size);
    memcpy(o, c + g->at[0], 3 * sizeof(float));
    memcpy(d, c + g->at[1], 3 * sizeof(float));
    memcpy(tmin, c + g->at[2], sizeof(float));
    memcpy(tmax, c + g->at[3], sizeof(float));
}

void ref_run_hand(const ref_kind *k, const ref_hand *cases, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        const ref_hand *h = &cases[i];
        cylref_hit r;
        int ret = k->intersect(&h->s, h->o, h->d, h->tmin, h->tmax, h->flags, &r);
        CHECK(ret == h->hit && r.hit == h->hit, "%s: hit %d (ret %d), want %d", h->what, r.hit,
              ret, h->hit);
        if (!h->hit || !r.hit)
            continue;
        CHECK(fabs(r.t - h->t) <= 1e-15 * fabs(h->t), "%s: t %.17g want %.17g", h->what, r.t,
              h->t);
        CHECK(r.part == h->part, "%s: part %#x want %#x", h->what, r.part, h->part);
        if (h->n[0] != 0 || h->n[1] != 0 || h->n[2] != 0)
            for (int j = 0; j < 3; j++)
                CHECK(fabs(r.n[j] - h->n[j]) <= 1e-15, "%s: n[%d] %.17g want %.17g", h->what, j,
                      r.n[j], h->n[j]);
        cylref_band b;
        double beyond;
        k->band_eval(&h->s, h->o, h->d, h->tmin, h->tmax, h->flags, &b);
        CHECK(k->judge(&b, 1, r.part, (float)r.t, &beyond) == 0 && beyond == 0,
              "%s: the exact answer fails its band", h->what);
    }
}

void ref_run_refused(const ref_kind *k, const ref_shape *bad, size_t n, const float o[3],
                     const float d[3])
{
    for (size_t i = 0; i < n; i++) {
        cylref_hit r;
        CHECK(k->intersect(&bad[i], o, d, 0, INFINITY, 0, &r) == -1 && !r.hit,
              "bad %s %zu accepted", k->name, i);
        if (k->valid)
            CHECK(!k->valid(&bad[i]), "bad %s %zu called valid", k->name, i);
    }
}

void ref_run_valid(const ref_kind *k, const ref_shape *edge, size_t n)
{
    for (size_t i = 0; i < n; i++)
        CHECK(k->valid(&edge[i]), "edge %s %zu refused", k->name, i);
}

void ref_run_generators(const ref_gen *g)
{
    enum { N = 64 };
    const ref_kind *k = g->kind;
    unsigned char *a = malloc(N * g->size), *b = malloc(N * g->size);
    if (!a || !b)
        exit(2);
    CHECK(g->name(g->count) == NULL, "count");
    for (int cat = 0; cat < g->count; cat++) {
        const char *name = g->name(cat);
        CHECK(name && g->find(name) == cat, "name %d", cat);
        CHECK(g->description(cat) != NULL, "description %d", cat);
        g->make(cat, 5, N, a, 0);
        g->make(cat, 5, N / 2, b, 0);
        CHECK(memcmp(a, b, g->size * (N / 2)) == 0, "%s: not prefix-stable", name);
        int hits = 0;
        ref_shape s, prev;
        for (int i = 0; i < N; i++) {
            float o[3], d[3], tmin, tmax;
            unpack(g, a + (size_t)i * g->size, &s, o, d, &tmin, &tmax);
            CHECK(k->valid(&s), "%s #%d: invalid %s", name, i, k->name);
            if (i % CYLGEN_BATCH)
                CHECK(memcmp(&s, &prev, k->size) == 0, "%s: batch", name);
            prev = s;
            cylref_band bd;
            double beyond;
            k->band_eval(&s, o, d, tmin, tmax, 0, &bd);
            hits += bd.exact.hit;
            CHECK(k->judge(&bd, bd.exact.hit, bd.exact.part, (float)bd.exact.t, &beyond) == 0 &&
                      (!bd.exact.hit || beyond <= 0.5),
                  "%s #%d: the exact answer fails its band", name, i);
        }
        CHECK(cat == g->bad || hits >= N / 8, "%s: only %d hits of %d", name, hits, N);
    }
    g->make(g->far, 5, N, a, 1);
    ref_shape s0, s;
    float o[3], d[3], tmin, tmax;
    unpack(g, a, &s0, o, d, &tmin, &tmax);
    for (int i = 1; i < N; i++) {
        unpack(g, a + (size_t)i * g->size, &s, o, d, &tmin, &tmax);
        CHECK(memcmp(&s, &s0, k->size) == 0, "shared");
    }
    free(a);
    free(b);
}

void ref_each_case(const ref_gen *g, const int *cats, size_t ncats, uint64_t seed, size_t n,
                   ref_case_fn *each, void *ctx)
{
    unsigned char *a = malloc(n * g->size);
    if (!a)
        exit(2);
    for (size_t ci = 0; ci < ncats; ci++) {
        g->make(cats[ci], seed, n, a, 0);
        for (size_t i = 0; i < n; i++)
            for (unsigned fl = 0; fl <= CYLRAY_CULL_BACK; fl += CYLRAY_CULL_BACK)
                each(ctx, a + i * g->size, g->name(cats[ci]), (int)i, fl);
    }
    free(a);
}

int ref_catch_defects(ref_judge_fn *judge, const cylref_band *b, int *of)
{
    if (!b->exact.hit || b->decision_unstable)
        return 0;
    const float late = (float)(b->t_hi + 16 * cylref_float_ulp(b->t_hi));
    double u;
    int caught = 0;
    (*of)++;
    caught += judge(b, 1, b->exact.part, late, &u) == 0 && u > 8;
    caught += judge(b, 0, 0, 0, &u) == 1;
    caught += judge(b, 1, b->exact.part ^ CYLRAY_BACKFACE, (float)b->exact.t, &u) == 2;
    return caught;
}
