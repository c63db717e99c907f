/* SPDX-License-Identifier: MIT */
/* isa/scalar.c - the portable path: the kernel at one lane, plain C (the secondary
 * rays: below). */
#include "cylray_internal.h"

#define KFN(n) CYLRAY_CAT(n, _scalar_1)
#include "simd/scalar.h"
#include "kernel/kernel.h"
#include "simd/undef.h"
#undef KFN

/* The secondary rays: on x86-64, whose baseline has SSE2, two lanes of doubles (two
 * rays an operation: a vector's time hardly grows with its width, docs/performance.md),
 * the same answers bit for bit as one lane; elsewhere one lane, plain C. */
#define DFN(n) CYLRAY_CAT(n, CYLRAY_CAT(_, SPWD))
#if defined(__x86_64__) && defined(__SSE2__)
#define SPWD scalar_d2
#define DW 2
#include "simd/f64_x86.h"
#else
#define SPWD scalar_d1
#include "simd/f64_scalar.h" /* its helpers are named with DFN */
#endif
#include "spawn/spawn.h"
#include "simd/f64_undef.h"
#undef DFN

#define KISA scalar
#define KISA_ENUM CYLRAY_ISA_SCALAR
#define KISA_NAME "scalar"
#define KW4 scalar_1
#define KW8 scalar_1
#define KW16 scalar_1
#define KWSTREAM scalar_1
#define KL4 scalar_1
#define KL8 scalar_1
#define KL16 scalar_1
#define SPW4 SPWD
#define SPW8 SPWD
#define SPW16 SPWD
#define SPWS SPWD
#include "spawn/spawn_slots.h"
#include "kernel/query_slots.h"
#include "isa/table.h"
