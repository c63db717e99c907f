/* SPDX-License-Identifier: MIT */
/* cylray_internal.h - what the library's translation units share and users never see. */
#ifndef CYLRAY_INTERNAL_H
#define CYLRAY_INTERNAL_H

#include "cylray.h"

#include <float.h>
#include <math.h>

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

#endif
