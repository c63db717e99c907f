/* SPDX-License-Identifier: MIT */
/* The kernels count a vector's hit lanes with CYLRAY_POPCOUNT and find the next one
 * with CYLRAY_CTZ (internal/compiler.h): the builtins with GNU C (the count inline
 * instead on x86 without popcnt), plain C for other compilers. The form this build
 * takes and the plain C one (bits_portable.c) are checked against a count bit by
 * bit. */
#include "internal/compiler.h"

#include <stdint.h>
#include <stdio.h>

unsigned bits_portable_popcount(unsigned x);
size_t bits_portable_ctz(unsigned x);

static unsigned ref_popcount(uint32_t x)
{
    unsigned n = 0;
    for (int i = 0; i < 32; i++)
        n += (x >> i) & 1u;
    return n;
}

static size_t ref_ctz(uint32_t x)
{
    size_t n = 0;
    while (!((x >> n) & 1u))
        n++;
    return n;
}

static int bad;

static void check(uint32_t x)
{
    const unsigned p = ref_popcount(x);
    if (CYLRAY_POPCOUNT(x) != p || bits_portable_popcount(x) != p) {
        if (bad++ < 10)
            fprintf(stderr, "popcount(0x%08x): %u, portable %u, expected %u\n", (unsigned)x,
                    CYLRAY_POPCOUNT(x), bits_portable_popcount(x), p);
    }
    if (x) {
        const size_t z = ref_ctz(x);
        if (CYLRAY_CTZ(x) != z || bits_portable_ctz(x) != z) {
            if (bad++ < 10)
                fprintf(stderr, "ctz(0x%08x): %zu, portable %zu, expected %zu\n", (unsigned)x,
                        (size_t)CYLRAY_CTZ(x), bits_portable_ctz(x), z);
        }
    }
}

int main(void)
{
    /* Every mask a packet of 16 lanes can have, at every shift; then random words. */
    for (uint32_t m = 0; m <= 0xffffu; m++)
        for (int s = 0; s <= 16; s++)
            check(m << s);
    uint64_t r = 0x9e3779b97f4a7c15u;
    for (int i = 0; i < 1000000; i++) {
        r ^= r << 13, r ^= r >> 7, r ^= r << 17;
        check((uint32_t)(r >> 16));
    }
    check(0xffffffffu);
    printf("bits: %s\n", bad ? "FAILED" : "ok");
    return bad != 0;
}
