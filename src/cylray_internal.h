/* SPDX-License-Identifier: MIT */
/* cylray_internal.h - what the library's translation units share and users never see. */
#ifndef CYLRAY_INTERNAL_H
#define CYLRAY_INTERNAL_H

#include "cylray.h"

#include <float.h>
#include <math.h>
#include <stdatomic.h>

#include "internal/compiler.h"
#include "internal/variants.h"
#include "internal/views.h"
#include "internal/leaf.h"
#include "internal/round.h"

extern const cylray_kernels cylray_kernels_scalar_;
extern const cylray_kernels cylray_kernels_sse41_;
extern const cylray_kernels cylray_kernels_avx2_;
extern const cylray_kernels cylray_kernels_avx512_;
extern const cylray_kernels cylray_kernels_neon_;

/* CPU support, from cpu.c: nonzero when the CPU and the OS can run that ISA. */
int cylray_cpu_has_(cylray_isa isa);

/* Whether the AVX kernels store a hit vector's lanes one by one (with a plain store
 * when every lane hit) instead of with AVX's masked stores, which AMD Zen 1 to 3 run
 * as microcode (docs/performance.md, "Stores by vendor"). Set by cylray_kernels_for
 * from the CPU, or CYLRAY_STORES=lanes|masked; read by every kernel call. Atomic, as
 * the first calls of several threads may set it (to the same value) while others run. */
extern atomic_int cylray_stores_by_lane_v_;
static inline int cylray_stores_by_lane_(void)
{
    return atomic_load_explicit(&cylray_stores_by_lane_v_, memory_order_relaxed);
}
int cylray_cpu_stores_by_lane_(void);

/* Whether cylray_prepare takes the cylinder (prepare.c): what it checks before it
 * derives anything, for cylray_cylinder_from_endpoints, which refuses what it refuses. */
int cylray_cylinder_ok_(const cylray_cylinder *in);

#endif
