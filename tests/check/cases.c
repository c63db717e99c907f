/* SPDX-License-Identifier: MIT */
/* cases.c - the cases of one category, generated and evaluated exactly once, before
 * any path runs over them. */
#include "check.h"

#include <stdio.h>
#include <stdlib.h>

/* The cases of one category with their exact bands: n packet cases (one cylinder per
 * batch of 16), then the stream segments (one cylinder each). */
ref_case *make_cases(int cat, uint64_t seed, size_t n_packet, const size_t *lengths,
                     size_t n_lengths, size_t *total)
{
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
