/* SPDX-License-Identifier: MIT */
/* The lane-mask bit counts of internal/compiler.h as a compiler without GNU C's
 * builtins gets them (tests/api/bits.c compares them with a plain count). */
#include <stddef.h>
#include <stdint.h>
#undef __GNUC__
#undef __clang__
#include "internal/compiler.h"

unsigned bits_portable_popcount(unsigned x);
size_t bits_portable_ctz(unsigned x);

unsigned bits_portable_popcount(unsigned x)
{
    return CYLRAY_POPCOUNT(x);
}

size_t bits_portable_ctz(unsigned x)
{
    return CYLRAY_CTZ(x);
}
