/* SPDX-License-Identifier: MIT */
/* internal/round.h - rounding to float on the bits, where the rounding error is used. */
#ifndef CYLRAY_INTERNAL_ROUND_H
#define CYLRAY_INTERNAL_ROUND_H

#include <stdint.h>
#include <string.h>

/* hi + lo rounded to the nearest float, ties to even, for |lo| at most half an ulp of
 * hi in double (lo then only breaks a tie; 0 for a plain double), computed on the bits.
 * Wherever the library takes e = fl(x) - x as exact, fl(x) comes from here and not
 * from a conversion: gcc 12 at -O3 vectorises (float)x, (double)(float)x - x over two
 * lanes and folds the narrowing and widening away, giving e = 0. An integer rounding
 * leaves the optimiser nothing to fold, with any compiler and flags. */
static inline float cylray_round_float_(double hi, double lo)
{
    uint64_t b;
    memcpy(&b, &hi, sizeof b);
    const uint32_t sign = (uint32_t)(b >> 32) & 0x80000000u;
    const int e = (int)(b >> 52 & 0x7ff), fe = e - 1023 + 127; /* fe: float's exponent */
    const uint64_t frac = b & 0xfffffffffffffull;
    uint32_t bits;
    if (e == 0x7ff) {
        bits = 0x7f800000u | (frac ? 0x400000u : 0u);
    } else if (e == 0 || fe >= 255) {
        bits = e == 0 ? 0u : 0x7f800000u; /* below 2^-1022: zero; beyond float: inf */
    } else {
        const uint64_t m = frac | 1ull << 52;
        const int shift = fe >= 1 ? 29 : 30 - fe; /* below 2^-126, float's subnormals */
        if (shift >= 64) {
            bits = 0;
        } else {
            uint64_t q = m >> shift;
            const uint64_t rem = m & ((1ull << shift) - 1), half = 1ull << (shift - 1);
            if (rem > half || (rem == half && (lo != 0 ? (lo > 0) == !sign : (q & 1u) != 0)))
                q++;
            /* the carry of q into the exponent field is the rounding into the next
             * binade, and into inf above FLT_MAX */
            bits = (fe >= 1 ? (uint32_t)(fe - 1) << 23 : 0u) + (uint32_t)q;
        }
    }
    bits |= sign;
    float f;
    memcpy(&f, &bits, sizeof f);
    return f;
}

/* (float)x as the hardware rounds it, opaque to the optimiser: for code that compares
 * the float with x, where a compiler must not fold (double)(float)x back into x (see
 * above). Elsewhere the rounding on the bits. */
static inline float cylray_to_float_(double x)
{
#if (defined(__GNUC__) || defined(__clang__)) && defined(__x86_64__)
    float f = (float)x;
    __asm__("" : "+x"(f));
    return f;
#elif (defined(__GNUC__) || defined(__clang__)) && defined(__aarch64__)
    float f = (float)x;
    __asm__("" : "+w"(f));
    return f;
#else
    return cylray_round_float_(x, 0.0);
#endif
}

/* The float next to f toward +inf (up) or -inf: nextafterf inline, for f not NaN. */
static inline float cylray_float_step_(float f, int up)
{
    if (f == 0)
        return up ? 0x1p-149f : -0x1p-149f;
    uint32_t b;
    memcpy(&b, &f, sizeof b);
    b = (f > 0) == (up != 0) ? b + 1u : b - 1u;
    memcpy(&f, &b, sizeof f);
    return f;
}

/* Would every double within e of x round to the float x rounds to? The midpoints
 * between floats are doubles and rounding is monotonic, so the two comparisons are
 * exact statements about x - e and x + e. */
static inline int cylray_float_decided_(double x, double e)
{
    if (x != x)
        return 0;
    const float f = cylray_to_float_(x);
    const double below = ((double)f + (double)cylray_float_step_(f, 0)) * 0.5;
    const double above = ((double)f + (double)cylray_float_step_(f, 1)) * 0.5;
    return x - e > below && x + e < above;
}

#endif
