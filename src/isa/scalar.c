/* SPDX-License-Identifier: MIT */
/* isa/scalar.c - the portable path: the kernel at one lane, plain C. */
#include "cylray_internal.h"

#define KFN(n) CYLRAY_CAT(n, _scalar_1)
#include "simd/scalar.h"
#include "kernel/kernel.h"
#include "simd/undef.h"
#undef KFN

#define DFN(n) CYLRAY_CAT(n, _scalar_d1)
#include "simd/f64_scalar.h"
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
#define SPW4 scalar_d1
#define SPW8 scalar_d1
#define SPW16 scalar_d1
#define SPWS scalar_d1
#include "spawn/entry.h"
#include "isa/entry.h"
