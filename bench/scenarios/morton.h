/* SPDX-License-Identifier: MIT */
/* morton.h - Morton codes, for grouping cylinders along a space-filling curve (the leaf
 * scenario and the Embree comparison). */
#ifndef BENCH_MORTON_H
#define BENCH_MORTON_H

#include <stdint.h>

/* The low 10 bits of x spread to every third bit of 30. */
static inline uint32_t morton_spread3(uint32_t x)
{
    x &= 0x3ff;
    x = (x | x << 16) & 0x030000ff;
    x = (x | x << 8) & 0x0300f00f;
    x = (x | x << 4) & 0x030c30c3;
    x = (x | x << 2) & 0x09249249;
    return x;
}

#endif
