/* SPDX-License-Identifier: MIT */
/* api/shape_ok.c - which shapes the library takes: the checks cylray_prepare,
 * cylray_prepare_sphere and cylray_prepare_cone make before they derive anything. A file
 * of its own, below both: cylray_cylinder_from_endpoints (api/endpoints.c) checks the
 * cylinder it forms as cylray_prepare would, and cylray_prepare_cone forms its cylinder
 * through it. */
#include "cylray_internal.h"

#include <float.h>

/* Magnitudes beyond 2^62 would overflow R^2 v.v and the products of the kernel, and
 * a radius below 2^-60 would leave R^2 subnormal; such a cylinder is refused rather
 * than answered wrongly. */
#define CYLRAY_MAX_COORD 0x1p62
#define CYLRAY_MIN_RADIUS 0x1p-60

static int coord_ok(float x)
{
    return isfinite(x) && fabs((double)x) <= CYLRAY_MAX_COORD;
}

int cylray_cylinder_ok_(const cylray_cylinder *in)
{
    const float *c = in->center, *a = in->axis;
    const double R = in->radius, H = in->half_height;
    for (int k = 0; k < 3; k++)
        if (!coord_ok(c[k]) || !coord_ok(a[k]))
            return 0;
    if (!(R >= CYLRAY_MIN_RADIUS) || !(R <= CYLRAY_MAX_COORD))
        return 0;
    if (!(H > 0) || (isfinite(H) && H > CYLRAY_MAX_COORD))
        return 0;
    if (in->flags & ~CYLRAY_CAPPED)
        return 0;
    return cylray_axis_max_(a) >=
           FLT_MIN; /* not zero, nor so small that its direction is lost */
}

int cylray_sphere_ok_(const cylray_sphere *in)
{
    const double R = in->radius;
    for (int k = 0; k < 3; k++)
        if (!coord_ok(in->center[k]))
            return 0;
    return R >= CYLRAY_MIN_RADIUS && R <= CYLRAY_MAX_COORD;
}

static int cone_radius_ok(double r)
{
    return r == 0 || (r >= CYLRAY_MIN_RADIUS && r <= CYLRAY_MAX_COORD);
}

/* A cone's radius at a point the kernels keep (within 1.42 bounding radii of the
 * center) is at most 1.42 (rmax (1 + slope) + |r1 - r0| / 2), and the kernels square it
 * (times v.v < 12) and multiply it by the slope times d.v: that bound is kept to 2^61,
 * the slope to 2^40 (cylray.h; docs/design.md, "The range"). r0 == r1 prepares a
 * cylinder, whose limits are its own. */
static int cone_steep_ok(float r0, float r1, const float p0[3], const float p1[3])
{
    double len2 = 0;
    for (int k = 0; k < 3; k++) {
        const double a = (double)p1[k] - p0[k]; /* exact */
        len2 += a * a;
    }
    const double slope = fabs((double)r1 - r0) / sqrt(len2);
    return r0 == r1 || (slope <= 0x1p40 &&
                        fmax(r0, r1) * (1.0 + slope) + 0.5 * fabs((double)r1 - r0) <= 0x1p61);
}

int cylray_cone_ok_(const cylray_cone *in)
{
    for (int k = 0; k < 3; k++)
        if (!coord_ok(in->p0[k]) || !coord_ok(in->p1[k]))
            return 0;
    return cone_radius_ok(in->r0) && cone_radius_ok(in->r1) && (in->r0 > 0 || in->r1 > 0) &&
           !(in->flags & ~CYLRAY_CAPPED) && cone_steep_ok(in->r0, in->r1, in->p0, in->p1);
}

int cylray_round_cone_ok_(const cylray_round_cone *in)
{
    for (int k = 0; k < 3; k++)
        if (!coord_ok(in->p0[k]) || !coord_ok(in->p1[k]))
            return 0;
    return cone_radius_ok(in->r0) && cone_radius_ok(in->r1) && (in->r0 > 0 || in->r1 > 0) &&
           !(in->flags & ~CYLRAY_CAPPED);
}
