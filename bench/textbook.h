/* textbook.h - the seed's textbook intersection, the baseline of the error comparison. */
#ifndef CYLBENCH_TEXTBOOK_H
#define CYLBENCH_TEXTBOOK_H

#include "cylray.h"

#include <stddef.h>

/* What the seed would precompute: the axis normalised in float, R^2, and the squared
 * radius R^2 + H^2 of its sphere-style finite clip. */
typedef struct tb_cylinder {
    float c[3], v[3];
    float rr, clip;
} tb_cylinder;

void tb_prepare(tb_cylinder *out, const cylray_cylinder *in);

/* The cylray stream contract (writes t, part, tmax and, with CYLRAY_NORMAL, the outward
 * normal on a hit), computed the textbook way in plain float, one ray at a time. The
 * seed has no end caps: every cylinder is an open tube here (infinite when H is). */
size_t tb_intersect_stream(const tb_cylinder *cyl, const cylray_rays *rays,
                           const cylray_hits *hits, size_t n, unsigned flags);

#endif
