/* SPDX-License-Identifier: MIT */
/* internal/compiler.h - the compiler's attributes and builtins, with plain C
 * where they are missing. */
#ifndef CYLRAY_INTERNAL_COMPILER_H
#define CYLRAY_INTERNAL_COMPILER_H

#if defined(__GNUC__) || defined(__clang__)
#define CYLRAY_INLINE static inline __attribute__((always_inline))
/* The rare paths (lanes that need the scaled instance): out of the hot code and
 * compiled for size. */
#define CYLRAY_NOINLINE static __attribute__((noinline, cold))
/* Out of line but compiled for speed: the drivers that read their flags at run time,
 * which whole scenes run (cylinders with one end disc), and a stream's last lanes.
 * Compiled as cold, their helpers (the SSE4.1 exact products in double) would be
 * calls, with every live vector register spilled around each. */
#define CYLRAY_OUTLINE static __attribute__((noinline))
/* Out of line and one copy: gcc would clone a function for each constant it is called
 * with (a leaf's width), which buys nothing where the work is per lane. */
#if defined(__clang__)
#define CYLRAY_ONE_COPY CYLRAY_OUTLINE
#else
#define CYLRAY_ONE_COPY static __attribute__((noinline, noclone))
#endif
/* Makes the compiler read memory again after this point instead of keeping what it
 * read before in registers (or in spill slots). */
#define CYLRAY_REREAD() __asm__ volatile("" ::: "memory")
#define CYLRAY_MAYBE_UNUSED __attribute__((unused))
#if defined(__POPCNT__) || !(defined(__x86_64__) || defined(__i386__))
#define CYLRAY_POPCOUNT(x) ((unsigned)__builtin_popcount(x))
#else
/* On x86 without the popcnt instruction (the SSE4.1 and scalar paths may not assume
 * it) the builtin is a call into libgcc, and a call inside a kernel's loop spills
 * every vector register live across it. */
#define CYLRAY_POPCOUNT(x) cylray_popcount_((unsigned)(x))
#endif
#define CYLRAY_CTZ(x) ((size_t)__builtin_ctz(x))
#else
#define CYLRAY_INLINE static inline
#define CYLRAY_NOINLINE static
#define CYLRAY_OUTLINE static
#define CYLRAY_ONE_COPY static
#define CYLRAY_REREAD() ((void)0)
#define CYLRAY_MAYBE_UNUSED
#define CYLRAY_POPCOUNT(x) cylray_popcount_((unsigned)(x))
static inline size_t CYLRAY_CTZ(unsigned x)
{
    size_t n = 0;
    for (; !(x & 1u); x >>= 1)
        n++;
    return n;
}
#endif

/* The bits of a lane mask (at most 32), where the compiler has no instruction for
 * it: a dozen integer operations, no branch, no call. */
CYLRAY_INLINE unsigned cylray_popcount_(unsigned x)
{
    x = x - ((x >> 1) & 0x55555555u);
    x = (x & 0x33333333u) + ((x >> 2) & 0x33333333u);
    x = (x + (x >> 4)) & 0x0f0f0f0fu;
    return (x * 0x01010101u) >> 24;
}

#define CYLRAY_CAT_(a, b) a##b
#define CYLRAY_CAT(a, b) CYLRAY_CAT_(a, b)

#endif
