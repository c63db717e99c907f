/* SPDX-License-Identifier: MIT */
/* cases.c - the cases of one category, generated and evaluated exactly once, before
 * any path runs over them. */
#include "check.h"

#include <stdio.h>
#include <stdlib.h>

cylray_status prepare_case(cylray_prepared *p, const ref_case *rc)
{
    return rc->sphere ? cylray_prepare_sphere(p, &rc->sph) : cylray_prepare(p, &rc->c.cyl);
}

static void sphere_case(ref_case *rc, const sphgen_case *g)
{
    rc->sphere = 1;
    rc->sph = g->sph;
    for (int k = 0; k < 3; k++) {
        rc->c.o[k] = g->o[k];
        rc->c.d[k] = g->d[k];
    }
    rc->c.tmin = g->tmin;
    rc->c.tmax = g->tmax;
}

static ref_case *make_sphere_cases(int cat, uint64_t seed, size_t n_packet,
                                   const size_t *lengths, size_t n_lengths, size_t *total)
{
    size_t ns = 0, longest = n_packet;
    for (size_t i = 0; i < n_lengths; i++) {
        ns += lengths[i];
        longest = lengths[i] > longest ? lengths[i] : longest;
    }
    size_t n = n_packet + ns;
    ref_case *rc = calloc(n, sizeof *rc);
    sphgen_case *gc = malloc((longest ? longest : 1) * sizeof *gc);
    if (!rc || !gc) {
        fprintf(stderr, "cylcheck: out of memory\n");
        exit(2);
    }
    sphgen_make(cat - CAT_SPHERE, seed, n_packet, gc);
    for (size_t i = 0; i < n_packet; i++)
        sphere_case(&rc[i], &gc[i]);
    size_t at = n_packet;
    for (size_t li = 0; li < n_lengths; li++) {
        sphgen_make_shared(cat - CAT_SPHERE,
                           seed ^ (0x5354524541ull + li) * 0x9e3779b97f4a7c15ull, lengths[li],
                           gc);
        for (size_t i = 0; i < lengths[li]; i++)
            sphere_case(&rc[at++], &gc[i]);
    }
    for (size_t i = 0; i < n; i++) {
        const cylgen_case *c = &rc[i].c;
        rc[i].index = (int)i;
        if (opt.only_case >= 0 && (int)i != opt.only_case)
            continue;
        sphref_band_eval(&rc[i].sph, c->o, c->d, c->tmin, c->tmax, 0, &rc[i].band[0]);
        sphref_band_eval(&rc[i].sph, c->o, c->d, c->tmin, c->tmax, CYLRAY_CULL_BACK,
                         &rc[i].band[1]);
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
        return make_sphere_cases(cat, seed, n_packet, lengths, n_lengths, total);
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
