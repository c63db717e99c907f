/* SPDX-License-Identifier: MIT */
/* api/cpu.c - which ISAs this CPU and OS can run: cpuid for the instructions, xgetbv for
 * the OS's promise to save the wide registers across context switches. */
#include "cylray_internal.h"

#if defined(__x86_64__) || defined(__i386__)
#include <cpuid.h>

static uint64_t xgetbv0(void)
{
    uint32_t lo, hi;
    __asm__ volatile("xgetbv" : "=a"(lo), "=d"(hi) : "c"(0));
    return ((uint64_t)hi << 32) | lo;
}

int cylray_cpu_has_(cylray_isa isa)
{
    unsigned a, b, c, d;
    if (!__get_cpuid(1, &a, &b, &c, &d))
        return isa == CYLRAY_ISA_SCALAR;
    const int sse41 = (c >> 19) & 1, fma = (c >> 12) & 1, osxsave = (c >> 27) & 1,
              avx = (c >> 28) & 1;
    uint64_t xcr0 = osxsave ? xgetbv0() : 0;
    const int os_ymm = (xcr0 & 0x6) == 0x6;   /* XMM and YMM state */
    const int os_zmm = (xcr0 & 0xe6) == 0xe6; /* and opmask, ZMM_Hi256, Hi16_ZMM */
    unsigned b7 = 0;
    if (__get_cpuid_count(7, 0, &a, &b, &c, &d))
        b7 = b;
    const int avx2 = (b7 >> 5) & 1, avx512f = (b7 >> 16) & 1, avx512dq = (b7 >> 17) & 1,
              avx512vl = (b7 >> 31) & 1;
    switch (isa) {
    case CYLRAY_ISA_SCALAR:
        return 1;
    case CYLRAY_ISA_SSE41:
        return sse41;
    case CYLRAY_ISA_AVX2:
        return avx && avx2 && fma && os_ymm;
    case CYLRAY_ISA_AVX512:
        return avx && avx2 && fma && avx512f && avx512dq && avx512vl && os_zmm;
    default:
        return 0;
    }
}

static int amd_or_hygon(void)
{
    unsigned a, b, c, d;
    if (!__get_cpuid(0, &a, &b, &c, &d))
        return 0;
    const int amd = b == 0x68747541u && d == 0x69746e65u && c == 0x444d4163u; /* AuthenticAMD */
    const int hygon =
        b == 0x6f677948u && d == 0x6e65476eu && c == 0x656e6975u; /* HygonGenuine */
    return amd || hygon;
}
/* AMD's cores from Zen 1 to Zen 4, and Hygon's Zen, run AVX's masked stores to memory
 * as microcode (11-17 cycles each for 256 bits on Zen 3 and Zen 4, measured), while
 * their blends cost half a cycle; so every AMD and Hygon CPU takes the blends. Intel
 * cores run the masked store as two uops (docs/performance.md, "Stores by vendor"). */
unsigned cylray_cpu_store_policy_(void)
{
    return amd_or_hygon() ? CYLRAY_STORE_BLEND : CYLRAY_STORE_MASKED;
}
/* The same cores divide quickly (a 256-bit division every 3.3 cycles on Zen 4): there
 * an estimate with its Newton steps is a longer chain of more operations than the
 * division it replaces, and CYLRAY_FAST ran 13-30 % slower on SSE4.1 and AVX2 and up
 * to 7 % on AVX-512 (docs/measurements/2026-12-06-fast-zen4.md). */
int cylray_cpu_divides_fast_(void)
{
    return amd_or_hygon();
}
#elif defined(__aarch64__)
int cylray_cpu_has_(cylray_isa isa)
{
    /* Advanced SIMD is mandatory on AArch64. */
    return isa == CYLRAY_ISA_SCALAR || isa == CYLRAY_ISA_NEON;
}
#else
int cylray_cpu_has_(cylray_isa isa)
{
    return isa == CYLRAY_ISA_SCALAR;
}
#endif
#if !defined(__x86_64__) && !defined(__i386__)
unsigned cylray_cpu_store_policy_(void)
{
    return CYLRAY_STORE_MASKED;
}
int cylray_cpu_divides_fast_(void)
{
    return 0;
}
#endif
