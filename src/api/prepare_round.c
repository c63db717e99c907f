/* SPDX-License-Identifier: MIT */
/* api/prepare_round.c - a round cone prepared: the cone tangent to its two spheres
 * through the spheres' centers (a cone prepared on p0 and p1, or a capsule's
 * cylinder), cut at the planes of the circles where it touches them, and the spheres
 * as numbers beside it. */
#include "cylray_internal.h"

#include <math.h>

_Static_assert(sizeof(cylray_prepared) == 192, "cylray_prepared keeps its size");

/* One sphere within the other (|p1 - p0| <= |r1 - r0|, or the same sphere twice): the
 * hull is the larger sphere, on the surface with its end's flag (the same sphere twice:
 * with either flag, as CAP_LO when CYLRAY_CAPPED_LO is set), else nothing. Prepared as
 * that sphere, whose h_v of 0 tells the kernels so; rc_caps holds the end it is. */
static cylray_status nested(cylray_prepared *out, const cylray_round_cone *in)
{
    const int hi = in->r1 > in->r0 || (in->r1 == in->r0 && !(in->flags & CYLRAY_CAPPED_LO));
    const cylray_sphere s = {
        {hi ? in->p1[0] : in->p0[0], hi ? in->p1[1] : in->p0[1], hi ? in->p1[2] : in->p0[2]},
        hi ? in->r1 : in->r0};
    cylray_prepared p;
    if (cylray_prepare_sphere(&p, &s) != CYLRAY_OK)
        return CYLRAY_EINVAL;
    p.rc_caps = in->flags & (hi ? CYLRAY_CAPPED_HI : CYLRAY_CAPPED_LO);
    p.kind = CYLRAY_KIND_ROUND;
    p.variant = (uint8_t)cylray_variant_of_(p.kind, 0u, 0, 0u, 0, 0);
    *out = p;
    return CYLRAY_OK;
}

/* With a = p1 - p0, L = |a| and dr = r1 - r0 (L > |dr|), the cone tangent to both
 * spheres makes the angle alpha with the axis, sin alpha = -dr / L: its radius at the
 * level of p_i is r_i / cos alpha, and it touches sphere i along the circle of radius
 * r_i cos alpha in the plane -r_i dr / L from p_i along the axis (the sphere's radius to
 * a tangent point is r_i (cos alpha u - (dr / L) a / L), u the unit radial direction).
 * cos^2 alpha = (L - |dr|) (L + |dr|) / L^2 is formed from the two factors, each rounded
 * once in double, not as 1 - dr^2 / L^2, which cancels where one sphere nearly holds
 * the other. The cone is prepared on p0 and p1 themselves, so that everything the
 * kernels place (its axis, its center, the spheres) is where a cone on p0 and p1 would
 * be, within the roundings of the axis and the center: an end placed at the tangent
 * circle's center would be rounded in world coordinates, ulps of the coordinates
 * rather than of the shape's size. A capsule (dr = 0) has cos alpha = 1, its planes at
 * p0 and p1. */
cylray_status cylray_prepare_round_cone(cylray_prepared *out, const cylray_round_cone *in)
{
    if (!out || !in || !cylray_round_cone_ok_(in))
        return CYLRAY_EINVAL;
    double a[3], aa = 0;
    for (int k = 0; k < 3; k++) {
        a[k] = (double)in->p1[k] - in->p0[k]; /* exact */
        aa += a[k] * a[k];
    }
    const double r[2] = {in->r0, in->r1}, dr = r[1] - r[0], L = sqrt(aa), adr = fabs(dr);
    if (!(L > adr))
        return nested(out, in);
    const double ca = sqrt((L - adr) * (L + adr)) / L;
    cylray_cone cone = {.r0 = (float)(r[0] / ca), .r1 = (float)(r[1] / ca), .flags = 0u};
    for (int k = 0; k < 3; k++)
        cone.p0[k] = in->p0[k], cone.p1[k] = in->p1[k];
    cylray_prepared p;
    if (cylray_prepare_cone(&p, &cone) != CYLRAY_OK)
        return CYLRAY_EINVAL;
    if (p.kind != CYLRAY_KIND_CONE) { /* a capsule's cylinder: the general kernel */
        p.axis_id = 0;
        for (unsigned k = 0; k < 3; k++)
            p.order[k] = (uint8_t)k;
    }
    /* p1 - c along v (p0 - c is its negative to the center's rounding), the planes at
     * the spheres' levels less the tangent circles' offsets (axial coordinates are x.v,
     * |v| times a length), the hull's bounding sphere: the spheres' farthest points
     * from c, which the frustum lies within. */
    double vv = 0, av = 0, sv = 0, bound = 0;
    for (int k = 0; k < 3; k++) {
        vv += (double)p.v[k] * p.v[k], av += a[k] * p.v[k];
        sv += ((double)in->p1[k] - p.c[k]) * p.v[k];
    }
    p.rc_s = (float)(sv / vv);
    /* the radius's slope per axial unit, dr / (L cos alpha |v|), and the normal's
     * length, cos alpha, from the inputs rather than the rounded radii at p0 and p1,
     * whose difference cancels for a slight taper */
    if (p.kind == CYLRAY_KIND_CONE) {
        p.kap = (float)(dr / (ca * L * sqrt(vv)));
        p.cnrm = (float)ca;
    }
    const float *pc[2] = {in->p0, in->p1};
    for (int i = 0; i < 2; i++) {
        double ww = 0;
        for (int k = 0; k < 3; k++) {
            const double w = (double)pc[i][k] - p.c[k];
            ww += w * w;
        }
        const double zc = (i ? 1.0 : -1.0) * (double)p.rc_s * vv;
        p.rc_z[i] = (float)(zc - r[i] * dr / aa * av);
        p.rc_rim[i] = (float)(r[i] * ca);
        p.rc_rr[i] = (float)(r[i] * r[i]);
        bound = fmax(bound, sqrt(ww) + r[i]);
    }
    p.bound2 = (float)(bound * bound * (1.0 + 0x1p-12));
    p.rc_caps = in->flags & (r[0] > 0 ? CYLRAY_CAPPED : CYLRAY_CAPPED_HI) &
                (r[1] > 0 ? CYLRAY_CAPPED : CYLRAY_CAPPED_LO);
    p.kind = CYLRAY_KIND_ROUND;
    p.caps = 0u;
    p.variant = (uint8_t)cylray_variant_of_(p.kind, 0u, 0, 0u, 0, 0);
    *out = p;
    return CYLRAY_OK;
}
