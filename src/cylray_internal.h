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

/* Each ISA's table; SSE4.1 and AVX2 have one per store policy (CYLRAY_STORE_*,
 * internal/variants.h): the plain name is MASKED's (on SSE, which has no masked store,
 * that stores as LANES). */
extern const cylray_kernels cylray_kernels_scalar_;
extern const cylray_kernels cylray_kernels_sse41_;
extern const cylray_kernels cylray_kernels_sse41_blend_;
extern const cylray_kernels cylray_kernels_avx2_;
extern const cylray_kernels cylray_kernels_avx2_blend_;
extern const cylray_kernels cylray_kernels_avx2_lanes_;
extern const cylray_kernels cylray_kernels_avx512_;
extern const cylray_kernels cylray_kernels_neon_;

/* CPU support, from api/cpu.c: nonzero when the CPU and the OS can run that ISA. */
int cylray_cpu_has_(cylray_isa isa);

/* The store policy AVX's masked stores call for on this CPU (api/cpu.c): BLEND where they
 * are microcode (AMD, Hygon), else MASKED. */
unsigned cylray_cpu_store_policy_(void);

/* The x86 tables that serve CYLRAY_FAST with the exact kernels, each filled into t
 * (isa/table.h), named as the table it copies. */
void cylray_divided_sse41_(cylray_kernels *t);
void cylray_divided_sse41_blend_(cylray_kernels *t);
void cylray_divided_avx2_(cylray_kernels *t);
void cylray_divided_avx2_blend_(cylray_kernels *t);
void cylray_divided_avx2_lanes_(cylray_kernels *t);
void cylray_divided_avx512_(cylray_kernels *t);

/* Whether this CPU's divisions beat the estimates with their Newton steps (api/cpu.c),
 * and so whether the x86 paths take those tables (api/dispatch.c). */
int cylray_cpu_divides_fast_(void);

/* Whether the toolkit's surface coordinates take their FMA instance, as the path
 * chosen does (api/dispatch.c). */
int cylray_surface_fma_(void);

/* Whether cylray_prepare takes the cylinder (api/shape_ok.c): what it checks before it
 * derives anything, for cylray_cylinder_from_endpoints, which refuses what it refuses. */
int cylray_cylinder_ok_(const cylray_cylinder *in);
int cylray_sphere_ok_(const cylray_sphere *in);
int cylray_cone_ok_(const cylray_cone *in);
int cylray_round_cone_ok_(const cylray_round_cone *in);

/* An axis's largest magnitude: its scale, and whether it has a direction at all. */
static inline double cylray_axis_max_(const float a[3])
{
    return fmax(fabs((double)a[0]), fmax(fabs((double)a[1]), fabs((double)a[2])));
}

#endif
