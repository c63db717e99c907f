/* SPDX-License-Identifier: MIT */
/* quad.h - the binary128 type of the reference and the few functions it needs on it.
 *
 * __float128 on x86-64 (gcc and clang), long double on AArch64 where it is binary128.
 * Arithmetic and comparisons go to libgcc's soft-float routines; the square root is our
 * own (Newton from a double seed), so nothing depends on libquadmath. */
#ifndef CYLREF_QUAD_H
#define CYLREF_QUAD_H

#include <float.h>
#include <math.h>

#if defined(__aarch64__) && LDBL_MANT_DIG == 113
typedef long double cylq;
#elif defined(__SIZEOF_FLOAT128__)
__extension__ typedef __float128 cylq; /* __extension__: -Wpedantic knows no __float128 */
#else
#error "cylref needs an IEEE binary128 type (__float128, or a 113-bit long double)"
#endif

static inline cylq q_abs(cylq x)
{
    return x < 0 ? -x : x;
}

static inline cylq q_max(cylq a, cylq b)
{
    return a > b ? a : b;
}

static inline cylq q_min(cylq a, cylq b)
{
    return a < b ? a : b;
}

/* |x| with the sign of s (s == 0 counts as positive, as copysign(x, +0) does). */
static inline cylq q_copysign(cylq x, cylq s)
{
    cylq a = q_abs(x);
    return s < 0 ? -a : a;
}

static inline int q_isfinite(cylq x)
{
    return x - x == 0; /* NaN and Inf give NaN */
}

/* sqrt(a) to about 2^-112 relative. The double seed has 53 bits; each Newton step
 * x' = (x + a/x) / 2 doubles them, so two reach 106 and three the full 113. a is first
 * scaled by an even power of two into double's comfortable range, so the seed exists
 * for every finite binary128. */
static inline cylq q_sqrt(cylq a)
{
    if (!(a > 0))
        return a == 0 ? a : (cylq)NAN;
    if (!q_isfinite(a))
        return a;
    cylq s = a, back = 1;
    const cylq big = (cylq)0x1p600, small = (cylq)0x1p-600;
    while (s > (cylq)0x1p900) {
        s *= small * small; /* 2^-1200 */
        back *= big;        /* sqrt(2^1200) */
    }
    while (s < (cylq)0x1p-900) {
        s *= big * big;
        back *= small;
    }
    cylq x = (cylq)sqrt((double)s);
    for (int k = 0; k < 3; k++)
        x = (x + s / x) * (cylq)0.5;
    return x * back;
}

#endif
