/* SPDX-License-Identifier: MIT */
/* api/prepare.c - deriving what every kernel call needs from a shape that api/shape_ok.c
 * takes. */
#include "cylray_internal.h"

#include <stdlib.h>
#include <string.h>

const char *cylray_strerror(cylray_status s)
{
    switch (s) {
    case CYLRAY_OK:
        return "success";
    case CYLRAY_EINVAL:
        return "invalid argument: a NULL pointer, more shapes than the leaf holds, "
               "equal endpoints, or a shape with a center, axis or end coordinate that is "
               "NaN, infinite or beyond 2^62 (or ends 2^62 or more apart), a zero or "
               "subnormal axis, a radius outside [2^-60, 2^62] (a cone's: 0 or in it, "
               "not both 0), a half height <= 0, NaN or finite beyond 2^62, or flag bits "
               "other than CYLRAY_CAPPED_LO and CYLRAY_CAPPED_HI";
    case CYLRAY_ENOMEM:
        return "out of memory";
    }
    return "unknown cylray status";
}

cylray_status cylray_prepare(cylray_prepared *out, const cylray_cylinder *in)
{
    if (!out || !in || !cylray_cylinder_ok_(in))
        return CYLRAY_EINVAL;
    const float *c = in->center, *a = in->axis;
    const double R = in->radius, H = in->half_height;
    const double amax = cylray_axis_max_(a);

    cylray_prepared p;
    memset(&p, 0, sizeof p);
    /* Scaling by a power of two keeps the direction exact and v.v near 1; an axis
     * along a coordinate axis becomes exactly a unit vector. */
    int zeros = (a[0] == 0) + (a[1] == 0) + (a[2] == 0);
    int e = ilogb(amax);
    double v[3];
    for (int k = 0; k < 3; k++) {
        v[k] = zeros == 2 ? (a[k] == 0 ? 0.0 : copysign(1.0, (double)a[k]))
                          : ldexp((double)a[k], -e);
        p.v[k] = (float)v[k];
        p.c[k] = c[k];
    }
    /* The squares of 24-bit values are exact in double, their sum nearly so. */
    double vv = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    double sv = sqrt(vv);
    for (int k = 0; k < 3; k++)
        p.n[k] = (float)(v[k] / sv);
    p.inv_vv = (float)(1.0 / vv);
    p.rr = (float)(R * R);
    p.rr_vv = (float)(R * R * vv);
    /* The discriminant A R^2 - g^2 is formed as (A R^2 - g^2) 2^-2j, with R 2^-j near 1
     * when R is far from it, so that A R^2 neither underflows (a radius of 1e-16 and a
     * near-parallel ray) nor overflows (a radius of 2^62 and |d| = 8). */
    const int j = abs(ilogb(R)) > 20 ? ilogb(R) : 0;
    p.rr_d = (float)ldexp(R * R, -2 * j);
    p.g_s = (float)ldexp(1.0, -j);
    p.sqrt_vv = (float)sv;
    p.h_v = isfinite(H) ? (float)(H * sv) : INFINITY;
    p.nscale = (float)(1.0 / (R * vv));
    for (int k = 0; k < 3; k++)
        p.vk[k] = (float)(v[k] / (R * vv));
    p.par_eps = (float)(vv * CYLRAY_PAR_EPS);
    /* The margin covers the rounding of the shifted origin many times over. */
    p.bound2 = isfinite(H) ? (float)((R * R + H * H) * (1.0 + 0x1p-12)) : INFINITY;
    p.radius = in->radius;
    p.half_height = in->half_height;
    p.caps = isfinite(H) ? in->flags & CYLRAY_CAPPED : 0u;
    p.kind = !isfinite(H) ? CYLRAY_KIND_INFINITE
             : p.caps     ? CYLRAY_KIND_CAPPED
                          : CYLRAY_KIND_OPEN;
    /* Only the rare instance of the general kernel (variant >= 6) takes the scaled
     * form; the others, and the coordinate-axis kernels, take R^2 as it is. */
    p.axis_id = zeros == 2 && j == 0 ? (a[0] != 0 ? 1u : a[1] != 0 ? 2u : 3u) : 0u;
    /* The renaming of internal/views.h: along x, (x, y, z) is read as (y, z, x); along
     * y, as (z, x, y); so that the axis is the third coordinate. */
    for (unsigned j = 0; j < 3; j++)
        p.order[j] = (uint8_t)(p.axis_id ? (p.axis_id + j) % 3u : j);
    if (p.axis_id) {
        for (unsigned j = 0; j < 3; j++)
            p.cr[j] = p.c[p.order[j]];
        p.vr = p.v[p.order[2]];
        p.cap_up = p.vr > 0 ? CYLRAY_CAP_HI : CYLRAY_CAP_LO;
        p.cap_down = p.vr > 0 ? CYLRAY_CAP_LO : CYLRAY_CAP_HI;
    }
    p.variant =
        (uint8_t)cylray_variant_of_(p.kind, p.axis_id, j != 0, p.caps, 0, cylray_slender_(&p));
    p.magic = CYLRAY_MAGIC;
    *out = p;
    return CYLRAY_OK;
}

/* A sphere is prepared as the kernels' sphere branches read it (kernel/kmath.h): the
 * center, R^2 (also in rr_vv, v.v being 1 there), 1 / R for the normal, a bounding
 * sphere with the cylinder's margin, and the same 2^-j scaling of the discriminant for
 * a radius far from 1; no axis. */
cylray_status cylray_prepare_sphere(cylray_prepared *out, const cylray_sphere *in)
{
    if (!out || !in || !cylray_sphere_ok_(in))
        return CYLRAY_EINVAL;
    const double R = in->radius;
    cylray_prepared p;
    memset(&p, 0, sizeof p);
    for (int k = 0; k < 3; k++)
        p.c[k] = in->center[k];
    p.rr = (float)(R * R);
    p.rr_vv = p.rr;
    p.inv_vv = 1.0f;
    const int j = abs(ilogb(R)) > 20 ? ilogb(R) : 0;
    p.rr_d = (float)ldexp(R * R, -2 * j);
    p.g_s = (float)ldexp(1.0, -j);
    p.sqrt_vv = 1.0f;
    p.h_v = 0.0f;
    p.nscale = (float)(1.0 / R);
    p.bound2 = (float)(R * R * (1.0 + 0x1p-12));
    p.radius = in->radius;
    p.half_height = 0.0f;
    p.kind = CYLRAY_KIND_SPHERE;
    for (unsigned k = 0; k < 3; k++)
        p.order[k] = (uint8_t)k;
    p.variant = (uint8_t)cylray_variant_of_(p.kind, 0u, j != 0, 0u, 0, 0);
    p.magic = CYLRAY_MAGIC;
    *out = p;
    return CYLRAY_OK;
}

/* A cone is prepared as the capped cylinder of its larger radius around the same axis
 * (the endpoint form's center, axis and half height, whose bounding sphere and scaling
 * serve the cone as they are), and then the radius as a function of the axial
 * coordinate z = p.v, with kap = (r1 - r0) / (2 H |v|): r is r0 at z = -H |v| and r1 at
 * +H |v|, and the kernels form it from the narrower end, as given (internal/leaf.h), so
 * that a tiny end keeps its radius beside a wide one. rm, the radius at the center, is
 * kept for the caller. The normal's length, 1 / sqrt(1 + slope^2), and v / v.v
 * for its radial part (kernel/store.h). */
cylray_status cylray_prepare_cone(cylray_prepared *out, const cylray_cone *in)
{
    if (!out || !in || !cylray_cone_ok_(in))
        return CYLRAY_EINVAL;
    const double rmax = fmax(in->r0, in->r1);
    /* the disc of a radius-0 end is a point, no surface: that end is open */
    const unsigned caps = in->flags & (in->r0 > 0 ? CYLRAY_CAPPED : CYLRAY_CAPPED_HI) &
                          (in->r1 > 0 ? CYLRAY_CAPPED : CYLRAY_CAPPED_LO);
    cylray_cylinder cyl;
    if (cylray_cylinder_from_endpoints(&cyl, in->p0, in->p1, (float)rmax, caps) != CYLRAY_OK)
        return CYLRAY_EINVAL;
    cylray_prepared p;
    if (cylray_prepare(&p, &cyl) != CYLRAY_OK)
        return CYLRAY_EINVAL;
    if (in->r0 == in->r1) { /* a cylinder, and its own kernels */
        *out = p;
        return CYLRAY_OK;
    }
    /* the general kernels: a cone has no coordinate-axis variant */
    if (p.axis_id) { /* v is a unit step already, and serves the general kernel */
        p.axis_id = 0;
        for (unsigned k = 0; k < 3; k++)
            p.order[k] = (uint8_t)k;
    }
    const double vv =
        (double)p.v[0] * p.v[0] + (double)p.v[1] * p.v[1] + (double)p.v[2] * p.v[2];
    const double H = cyl.half_height, sv = sqrt(vv),
                 slope = ((double)in->r1 - in->r0) / (2 * H);
    p.kind = CYLRAY_KIND_CONE;
    p.r0 = in->r0, p.r1 = in->r1;
    p.rm = (float)(0.5 * ((double)in->r0 + in->r1));
    p.kap = (float)(slope / sv);
    p.cnrm = (float)(1.0 / sqrt(1.0 + slope * slope));
    /* The discriminant's u = r e + a f grows with the radius and the slope times the
     * distance: its scaling 2^-j (as the cylinder's, cylray_prepare) is chosen for
     * rmax max(1, slope) rather than for rmax alone. */
    const double rs = rmax * fmax(1.0, fabs(slope));
    const int j = abs(ilogb(rs)) > 20 ? ilogb(rs) : 0;
    p.rr_d = (float)ldexp(rmax * rmax, -2 * j);
    p.g_s = (float)ldexp(1.0, -j);
    for (int k = 0; k < 3; k++)
        p.vk[k] = (float)(p.v[k] / vv);
    p.variant = (uint8_t)cylray_variant_of_(p.kind, 0u, p.g_s != 1.0f, p.caps,
                                            cylray_cone_tiny_(&p), cylray_slender_(&p));
    *out = p;
    return CYLRAY_OK;
}
