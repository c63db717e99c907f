/* SPDX-License-Identifier: MIT */
/* isa/sse41.c - the kernel on SSE4.1, 4 lanes (compiled with -msse4.1). */
#include "cylray_internal.h"

#ifndef __SSE4_1__
#error "isa/sse41.c needs -msse4.1"
#endif

#define VW 4
#define X86_FMA 0
#define X86_KMASK 0
#define KFN(n) CYLRAY_CAT(n, _sse41_4)
#define KPAIRS(F) 1 /* streams keep two vectors in flight (docs/performance.md) */
#include "simd/x86.h"
#include "simd/x86_stores.h"
#include "kernel/kernel.h"
#include "simd/undef.h"
#undef KFN
#undef KPAIRS

#define DFN(n) CYLRAY_CAT(n, _sse41_d2)
#define DW 2
#include "simd/f64_x86.h"
#include "spawn/spawn.h"
#include "simd/f64_undef.h"
#undef DFN

#define KISA sse41
#define KISA_ENUM CYLRAY_ISA_SSE41
#define KISA_NAME "sse41"
#define KW4 sse41_4
#define KW8 sse41_4
#define KW16 sse41_4
#define KWSTREAM sse41_4
#define KL4 sse41_4
#define KL8 sse41_4
#define KL16 sse41_4
#define SPW4 sse41_d2
#define SPW8 sse41_d2
#define SPW16 sse41_d2
#define SPWS sse41_d2
#include "spawn/spawn_slots.h"
/* a table per store policy (internal/variants.h; api/dispatch.c picks one) */
#define KSTORES(X) X(, CYLRAY_STORE_MASKED) X(_blend, CYLRAY_STORE_BLEND)
#define KFAST_BY_CPU 1 /* CYLRAY_FAST by the CPU (kernel/query_slots.h) */
#include "kernel/query_slots.h"
#include "isa/table.h"
