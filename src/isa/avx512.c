/* SPDX-License-Identifier: MIT */
/* isa/avx512.c - the kernel on AVX-512 F+VL+DQ: 16 lanes in zmm, 8 and 4 in ymm and
 * xmm with mask registers (compiled with -mavx512f -mavx512vl -mavx512dq). */
#include "cylray_internal.h"

#if !defined(__AVX512F__) || !defined(__AVX512VL__) || !defined(__AVX512DQ__)
#error "isa/avx512.c needs -mavx512f -mavx512vl -mavx512dq"
#endif

#define X86_FMA 1
#define X86_KMASK 1

#define VW 16
#define KFN(n) CYLRAY_CAT(n, _avx512_16)
/* Streams keep two vectors in flight for the cylinders of a general axis, where that
 * pays on this width (docs/performance.md); a coordinate axis's kernels, shorter, run
 * one vector at a time. The plain capped kernels resume pairs only after eight vectors
 * in a row pass the rejection: with two, streams that the rejection mostly ends (a BVH
 * leaf's) lost what rays that hit gained. */
#define KPAIRS(F) (!(F).aligned)
#define KGROUP(F) ((F).capped && !(F).fast && !(F).refine ? 8 : 2)
#include "simd/x86.h"
#include "simd/x86_stores.h"
#include "kernel/kernel.h"
#include "simd/undef.h"
#undef KFN
#undef KPAIRS

#define VW 8
#define KFN(n) CYLRAY_CAT(n, _avx512_8)
#include "simd/x86.h"
#include "simd/x86_stores.h"
#include "kernel/kernel.h"
#include "simd/undef.h"
#undef KFN

#define VW 4
#define KFN(n) CYLRAY_CAT(n, _avx512_4)
#include "simd/x86.h"
#include "simd/x86_stores.h"
#include "kernel/kernel.h"
#include "simd/undef.h"
#undef KFN

/* Secondary rays in double: 8 lanes in zmm, and 4 in ymm for 4-ray packets. */
#define DFN(n) CYLRAY_CAT(n, _avx512_d8)
#define DW 8
#include "simd/f64_x86.h"
#include "spawn/spawn.h"
#include "simd/f64_undef.h"
#undef DFN
#define DFN(n) CYLRAY_CAT(n, _avx512_d4)
#define DW 4
#include "simd/f64_x86.h"
#include "spawn/spawn.h"
#include "simd/f64_undef.h"
#undef DFN

#define KISA avx512
#define KISA_ENUM CYLRAY_ISA_AVX512
#define KISA_NAME "avx512"
#define KW4 avx512_4
#define KW8 avx512_8
#define KW16 avx512_16
#define KWSTREAM avx512_16
#define KL4 avx512_4
#define KL8 avx512_8
#define KL16 avx512_16
#define SPW4 avx512_d4
#define SPW8 avx512_d8
#define SPW16 avx512_d8
#define SPWS avx512_d8
#include "spawn/spawn_slots.h"
#define KFAST_BY_CPU 1 /* CYLRAY_FAST by the CPU (kernel/query_slots.h) */
#include "kernel/query_slots.h"
#include "isa/table.h"
