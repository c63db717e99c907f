/* SPDX-License-Identifier: MIT */
/* rng.h - the tests' one deterministic generator: splitmix64 (Steele, Lea and Flood,
 * OOPSLA 2014), and a double in [0, 1) from 64 random bits. Header-only, so that
 * programs that link none of tests/support (the reference's generators in tests/ref,
 * which the bench links too) draw from the same code: a seed gives the same sequence
 * on every platform and compiler, which is what lets a failure replay. */
#ifndef RNG_H
#define RNG_H

#include <stdint.h>

/* The next number of the sequence that *state seeds; any state is a valid seed. */
static inline uint64_t rng_splitmix64(uint64_t *state)
{
    uint64_t z = (*state += 0x9e3779b97f4a7c15u);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9u;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebu;
    return z ^ (z >> 31);
}

/* Uniform in [0, 1): the top 53 bits of x, every double there a multiple of 2^-53. */
static inline double rng_unit(uint64_t x)
{
    return (double)(x >> 11) * 0x1p-53;
}

#endif
