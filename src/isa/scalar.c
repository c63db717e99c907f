/* SPDX-License-Identifier: MIT */
/* isa/scalar.c - the portable path: the kernel at one lane, plain C. */
#include "cylray_internal.h"

#define KFN(n) CYLRAY_CAT(n, _scalar_1)
#include "simd/scalar.h"
#include "kernel/kernel.h"
#include "simd/undef.h"
#undef KFN

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
#include "isa/entry.h"
