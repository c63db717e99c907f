/* SPDX-License-Identifier: MIT */
/* internal/dd.h - double-double arithmetic (about 104 bits) for the toolkit's exact-enough sums.
 *
 * A value is hi + lo with |lo| <= ulp(hi) / 2. The products use fma(), which C99
 * rounds once wherever the hardware lacks it, so each operation is good to a few units
 * of 2^-104 of its result on every platform; toolkit/bounds.c, split.c and surface_cylinder.c
 * state their error bounds from that. Built with -ffp-contract=off, so nothing here is
 * fused behind our back. */
#ifndef CYLRAY_DD_H
#define CYLRAY_DD_H

#include <math.h>

#include "round.h"

typedef struct cylray_dd {
    double hi, lo;
} cylray_dd;

static inline cylray_dd dd_make(double hi, double lo)
{
    cylray_dd r = {hi, lo};
    return r;
}

/* a + b exactly, for |a| >= |b| or a == 0 */
static inline cylray_dd dd_fast_two_sum(double a, double b)
{
    double s = a + b;
    return dd_make(s, b - (s - a));
}

/* a + b exactly */
static inline cylray_dd dd_two_sum(double a, double b)
{
    double s = a + b, bb = s - a;
    return dd_make(s, (a - (s - bb)) + (b - bb));
}

/* a b exactly (barring underflow) */
static inline cylray_dd dd_two_prod(double a, double b)
{
    double p = a * b;
    return dd_make(p, fma(a, b, -p));
}

static inline cylray_dd dd_add(cylray_dd a, cylray_dd b)
{
    cylray_dd s = dd_two_sum(a.hi, b.hi), t = dd_two_sum(a.lo, b.lo);
    s.lo += t.hi;
    s = dd_fast_two_sum(s.hi, s.lo);
    s.lo += t.lo;
    return dd_fast_two_sum(s.hi, s.lo);
}

static inline cylray_dd dd_neg(cylray_dd a)
{
    return dd_make(-a.hi, -a.lo);
}

static inline cylray_dd dd_sub(cylray_dd a, cylray_dd b)
{
    return dd_add(a, dd_neg(b));
}

static inline cylray_dd dd_mul(cylray_dd a, cylray_dd b)
{
    cylray_dd p = dd_two_prod(a.hi, b.hi);
    p.lo += a.hi * b.lo + a.lo * b.hi;
    return dd_fast_two_sum(p.hi, p.lo);
}

static inline cylray_dd dd_mul_d(cylray_dd a, double b)
{
    cylray_dd p = dd_two_prod(a.hi, b);
    p.lo += a.lo * b;
    return dd_fast_two_sum(p.hi, p.lo);
}

static inline cylray_dd dd_div(cylray_dd a, cylray_dd b)
{
    double q1 = a.hi / b.hi;
    cylray_dd r = dd_sub(a, dd_mul_d(b, q1));
    double q2 = r.hi / b.hi;
    r = dd_sub(r, dd_mul_d(b, q2));
    double q3 = r.hi / b.hi;
    cylray_dd q = dd_fast_two_sum(q1, q2);
    return dd_add(q, dd_make(q3, 0.0));
}

/* sqrt(a) for a >= 0 (0 for a <= 0): one Newton step from the double root. */
static inline cylray_dd dd_sqrt(cylray_dd a)
{
    if (!(a.hi > 0))
        return dd_make(0.0, 0.0);
    double s = sqrt(a.hi);
    cylray_dd r = dd_sub(a, dd_two_prod(s, s));
    return dd_fast_two_sum(s, r.hi / (2.0 * s));
}

/* The largest float <= a.hi + a.lo, and the smallest float >= it. */
static inline float dd_floor_float(cylray_dd a)
{
    float f = cylray_to_float_(a.hi); /* opaque: (double)f is not folded into a.hi */
    if ((double)f > a.hi || ((double)f == a.hi && a.lo < 0))
        f = cylray_float_step_(f, 0);
    return f;
}

static inline float dd_ceil_float(cylray_dd a)
{
    float f = cylray_to_float_(a.hi);
    if ((double)f < a.hi || ((double)f == a.hi && a.lo > 0))
        f = cylray_float_step_(f, 1);
    return f;
}

#endif
