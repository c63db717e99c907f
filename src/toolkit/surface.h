/* SPDX-License-Identifier: MIT */
/* toolkit/surface.h - what the cylinder's path (surface_cylinder.c, compiled twice) and
 * the other shapes and entry points (surface.c) share. */
#ifndef CYLRAY_TOOLKIT_SURFACE_H
#define CYLRAY_TOOLKIT_SURFACE_H
#include "cylray_internal.h"

#define TWO_PI 6.283185307179586476925

/* The geometry surface_at needs, from a prepared cylinder or a leaf lane. */
typedef struct surf_cyl {
    float c[3], v[3];
    double R, H; /* H: INFINITY when infinite */
} surf_cyl;

/* The largest float below 1: where v rounds up to 1, it stays in [0, 1). */
#define BELOW_ONE 0x1.fffffep-1f

/* The cylinder's path (surface_cylinder.c): plain, and with AVX2 and FMA. */
void cylray_surface_at_plain_(const surf_cyl *s, const float p[3], int32_t part, float uv[2],
                              float dpdu[3], float dpdv[3]);
void cylray_surface_at_fma_(const surf_cyl *s, const float p[3], int32_t part, float uv[2],
                            float dpdu[3], float dpdv[3]);

#endif
