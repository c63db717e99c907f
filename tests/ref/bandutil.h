/* SPDX-License-Identifier: MIT */
/* bandutil.h - what the three shapes' bands (band.c, sphref.c, conref_band.c) measure
 * their outcomes with. */
#ifndef CYLREF_BANDUTIL_H
#define CYLREF_BANDUTIL_H

#include "quad.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

/* |x - y| of two margins or t values, INFINITY when not comparable. */
static inline double ref_qdiff(cylq x, cylq y)
{
    if (x == y)
        return 0;
    cylq d = x - y;
    return q_isfinite(d) ? (double)q_abs(d) : INFINITY;
}

static inline uint32_t ref_fbits(float f)
{
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    return u;
}

/* The angle between two directions, accurate near 0 and near pi. */
static inline double ref_angle3(const double a[3], const double b[3])
{
    double c[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                   a[0] * b[1] - a[1] * b[0]};
    return atan2(sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]),
                 a[0] * b[0] + a[1] * b[1] + a[2] * b[2]);
}

#endif
