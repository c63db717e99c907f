/* SPDX-License-Identifier: MIT */
/* isa/neon.c - the kernel on AArch64 NEON, 4 lanes. */
#include "cylray_internal.h"

#ifndef __aarch64__
#error "isa/neon.c is for AArch64"
#endif

#define KFN(n) CYLRAY_CAT(n, _neon_4)
#include "simd/neon.h"
#include "kernel/kernel.h"
#include "simd/undef.h"
#undef KFN

#define DFN(n) CYLRAY_CAT(n, _neon_d2)
#include "simd/f64_neon.h"
#include "spawn/spawn.h"
#include "simd/f64_undef.h"
#undef DFN

#define KISA neon
#define KISA_ENUM CYLRAY_ISA_NEON
#define KISA_NAME "neon"
#define KW4 neon_4
#define KW8 neon_4
#define KW16 neon_4
#define KWSTREAM neon_4
#define KL4 neon_4
#define KL8 neon_4
#define KL16 neon_4
#define SPW4 neon_d2
#define SPW8 neon_d2
#define SPW16 neon_d2
#define SPWS neon_d2
#include "spawn/spawn_slots.h"
#include "kernel/query_slots.h"
#include "isa/table.h"
