/* SPDX-License-Identifier: MIT */
/* cases.c - the cases of one category, generated and evaluated exactly once, before
 * any path runs over them. */
#include "check.h"

#include <stdio.h>
#include <stdlib.h>

cylray_status prepare_case(cylray_prepared *p, const ref_case *rc)
{
    return rc->sphere  ? cylray_prepare_sphere(p, &rc->sph)
           : rc->cone  ? cylray_prepare_cone(p, &rc->con)
           : rc->round ? cylray_prepare_round_cone(p, &rc->rnd)
                       : cylray_prepare(p, &rc->c.cyl);
}

/* What the cases of a sphere, cone or round cone category need of their shape's generator and
 * reference: the generator cases are of `size` bytes each. */
typedef struct {
    size_t size;
    void (*make)(int cat, uint64_t seed, size_t n, void *out, int shared);
    void (*to_case)(ref_case *rc, const void *g);
    void (*band)(const ref_case *rc, unsigned flags, cylref_band *out);
} shape_gen;

static void ray_of(ref_case *rc, const float o[3], const float d[3], float tmin, float tmax)
{
    for (int k = 0; k < 3; k++) {
        rc->c.o[k] = o[k];
        rc->c.d[k] = d[k];
    }
    rc->c.tmin = tmin;
    rc->c.tmax = tmax;
}

/* A shape's row, name##s: its generator gen (gen##_make, gen##_make_shared, its cases
 * gen##_case with the shape as member) from the category base on, its reference ref
 * (ref##_band_eval), and the ref_case's flag that marks the shape and field that holds it. */
#define SHAPE_GEN_DEFINE(name, gen, ref, member, flag, field, base)                            \
    static void name##_make(int cat, uint64_t seed, size_t n, void *out, int shared)           \
    {                                                                                          \
        (shared ? gen##_make_shared : gen##_make)(cat - (base), seed, n, out);                 \
    }                                                                                          \
    static void name##_case(ref_case *rc, const void *gv)                                      \
    {                                                                                          \
        const gen##_case *g = gv;                                                              \
        rc->flag = 1;                                                                          \
        rc->field = g->member;                                                                 \
        ray_of(rc, g->o, g->d, g->tmin, g->tmax);                                              \
    }                                                                                          \
    static void name##_band(const ref_case *rc, unsigned flags, cylref_band *out)              \
    {                                                                                          \
        ref##_band_eval(&rc->field, rc->c.o, rc->c.d, rc->c.tmin, rc->c.tmax, flags, out);     \
    }                                                                                          \
    static const shape_gen name##s = {sizeof(gen##_case), name##_make, name##_case, name##_band}

SHAPE_GEN_DEFINE(sphere, sphgen, sphref, sph, sphere, sph, CAT_SPHERE);
SHAPE_GEN_DEFINE(cone, congen, conref, cone, cone, con, CAT_CONE);
SHAPE_GEN_DEFINE(round, rcgen, rcref, rc, round, rnd, CAT_ROUND);

/* A sphere or cone category's cases: n_packet of their own, then one shared shape per
 * stream length, each with its two bands (plain and culling). */
static ref_case *make_shape_cases(const shape_gen *sg, int cat, uint64_t seed, size_t n_packet,
                                  const size_t *lengths, size_t n_lengths, size_t *total)
{
    size_t ns = 0, longest = n_packet;
    for (size_t i = 0; i < n_lengths; i++) {
        ns += lengths[i];
        longest = lengths[i] > longest ? lengths[i] : longest;
    }
    size_t n = n_packet + ns;
    ref_case *rc = calloc(n, sizeof *rc);
    unsigned char *gc = malloc((longest ? longest : 1) * sg->size);
    if (!rc || !gc) {
        fprintf(stderr, "cylcheck: out of memory\n");
        exit(2);
    }
    sg->make(cat, seed, n_packet, gc, 0);
    for (size_t i = 0; i < n_packet; i++)
        sg->to_case(&rc[i], gc + i * sg->size);
    size_t at = n_packet;
    for (size_t li = 0; li < n_lengths; li++) {
        sg->make(cat, seed ^ (0x5354524541ull + li) * 0x9e3779b97f4a7c15ull, lengths[li], gc,
                 1);
        for (size_t i = 0; i < lengths[li]; i++)
            sg->to_case(&rc[at++], gc + i * sg->size);
    }
    for (size_t i = 0; i < n; i++) {
        rc[i].index = (int)i;
        if (opt.only_case >= 0 && (int)i != opt.only_case)
            continue;
        sg->band(&rc[i], 0, &rc[i].band[0]);
        sg->band(&rc[i], CYLRAY_CULL_BACK, &rc[i].band[1]);
    }
    free(gc);
    *total = n;
    return rc;
}

/* The cases of one category with their exact bands: n packet cases (one cylinder per
 * batch of 16), then the stream segments (one cylinder each). */
ref_case *make_cases(int cat, uint64_t seed, size_t n_packet, const size_t *lengths,
                     size_t n_lengths, size_t *total)
{
    if (cat_is_sphere(cat))
        return make_shape_cases(&spheres, cat, seed, n_packet, lengths, n_lengths, total);
    if (cat_is_cone(cat))
        return make_shape_cases(&cones, cat, seed, n_packet, lengths, n_lengths, total);
    if (cat_is_round(cat))
        return make_shape_cases(&rounds, cat, seed, n_packet, lengths, n_lengths, total);
    size_t ns = 0, longest = n_packet;
    for (size_t i = 0; i < n_lengths; i++) {
        ns += lengths[i];
        longest = lengths[i] > longest ? lengths[i] : longest;
    }
    size_t n = n_packet + ns;
    ref_case *rc = calloc(n, sizeof *rc);
    cylgen_case *gc = malloc((longest ? longest : 1) * sizeof *gc);
    if (!rc || !gc) {
        fprintf(stderr, "cylcheck: out of memory\n");
        exit(2);
    }
    cylgen_make(cat, seed, n_packet, gc);
    for (size_t i = 0; i < n_packet; i++)
        rc[i].c = gc[i];
    size_t at = n_packet;
    for (size_t li = 0; li < n_lengths; li++) {
        cylgen_make_shared(cat, seed ^ (0x5354524541ull + li) * 0x9e3779b97f4a7c15ull,
                           lengths[li], gc);
        for (size_t i = 0; i < lengths[li]; i++)
            rc[at++].c = gc[i];
    }
    for (size_t i = 0; i < n; i++) {
        const cylgen_case *c = &rc[i].c;
        rc[i].index = (int)i;
        if (opt.only_case >= 0 && (int)i != opt.only_case)
            continue;
        cylref_band_eval(&c->cyl, c->o, c->d, c->tmin, c->tmax, 0, &rc[i].band[0]);
        cylref_band_eval(&c->cyl, c->o, c->d, c->tmin, c->tmax, CYLRAY_CULL_BACK,
                         &rc[i].band[1]);
    }
    free(gc);
    *total = n;
    return rc;
}
