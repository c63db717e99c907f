/* SPDX-License-Identifier: MIT */
/* agree.h - may two paths answer the same ray differently? The SIMD paths are judged
 * against the scalar one: they compute the same formulas in a different order (FMA or
 * not, approximate reciprocals under CYLRAY_FAST), so their answers may differ only
 * where the decision itself is fragile. */
#ifndef AGREE_H
#define AGREE_H

#include <stddef.h>
#include <stdint.h>

#include "cylray.h"
#include "guarded.h"

typedef struct fz_answer {
    int hit;
    float t;
    int32_t part;
} fz_answer;

/* 0: the two answers may both be right. 1: they may not; `why` says how. ray: the
 * eight fields in gbatch order. */
int fz_agree(const cylray_cylinder *c, const float ray[G_NFIELD], unsigned flags,
             const fz_answer *a, const fz_answer *b, char *why, size_t whylen);

/* How many disagreements were excused by the geometric band, and how many only by
 * the exact reference (for the run's summary). */
extern unsigned long fz_excused_geometric, fz_excused_exact;

#endif
