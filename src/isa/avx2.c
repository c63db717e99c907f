/* SPDX-License-Identifier: MIT */
/* isa/avx2.c - the kernel on AVX2+FMA: 8 lanes in ymm, and 4 in xmm for 4-ray packets
 * (compiled with -mavx2 -mfma, never -march=native, which would add AVX-512). */
#include "cylray_internal.h"

#if !defined(__AVX2__) || !defined(__FMA__)
#error "isa/avx2.c needs -mavx2 -mfma"
#endif
#ifdef __AVX512F__
#error "isa/avx2.c must not be compiled with AVX-512 enabled"
#endif

#define X86_FMA 1
#define X86_KMASK 0

#define VW 8
#define KFN(n) CYLRAY_CAT(n, _avx2_8)
#define KPAIRS(F) 1 /* streams keep two vectors in flight (docs/performance.md) */
#include "simd/x86.h"
#include "simd/x86_stores.h"
#include "kernel/kernel.h"
#include "simd/undef.h"
#undef KFN
#undef KPAIRS

#define VW 4
#define KFN(n) CYLRAY_CAT(n, _avx2_4)
#include "simd/x86.h"
#include "simd/x86_stores.h"
#include "kernel/kernel.h"
#include "simd/undef.h"
#undef KFN

#define DFN(n) CYLRAY_CAT(n, _avx2_d4)
#define DW 4
#include "simd/f64_x86.h"
#include "spawn/spawn.h"
#include "simd/f64_undef.h"
#undef DFN

#define KISA avx2
#define KISA_ENUM CYLRAY_ISA_AVX2
#define KISA_NAME "avx2"
#define KW4 avx2_4
#define KW8 avx2_8
#define KW16 avx2_8
#define KWSTREAM avx2_8
#define KL4 avx2_4
#define KL8 avx2_8
#define KL16 avx2_8
#define SPW4 avx2_d4
#define SPW8 avx2_d4
#define SPW16 avx2_d4
#define SPWS avx2_d4
#include "spawn/spawn_slots.h"
/* a table per store policy (internal/variants.h; api/dispatch.c picks one) */
#define KSTORES(X)                                                                             \
    X(, CYLRAY_STORE_MASKED) X(_blend, CYLRAY_STORE_BLEND) X(_lanes, CYLRAY_STORE_LANES)
#define KFAST_BY_CPU 1 /* CYLRAY_FAST by the CPU (kernel/query_slots.h) */
#include "kernel/query_slots.h"
#include "isa/table.h"
