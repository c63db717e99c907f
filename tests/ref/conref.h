/* SPDX-License-Identifier: MIT */
/* conref.h - the exact ray/cone reference (binary128), written apart from the kernels.
 *
 * A cone is the double cone through the two rims cut by the slab between the end
 * planes (the slab leaves out the mirror nappe), with the discs its flags ask for.
 * Everything is evaluated in binary128 (quad.h) in an orthonormal frame about the exact
 * axis p1 - p0, measured from the exact center (p0 + p1) / 2: z along the axis, the
 * radius r(z) linear between r0 and r1, the side |x_perp|^2 = r(z)^2. The answer is the
 * smallest t in the closed [tmin, tmax] among the side roots inside the slab and the
 * hits of the discs present; a disc that is absent is no surface (an open end). It
 * shares cylref's answer, band and judge types. */
#ifndef CONREF_H
#define CONREF_H

#include "cylref.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The cone's row (cylref.h):
 *   conref_valid       1 when cylray_prepare_cone must accept c (cylray.h's refusals,
 *                      without NULL)
 *   conref_intersect   part CYLRAY_SIDE / CAP_LO / CAP_HI, | CYLRAY_BACKFACE when
 *                      dot(d, n_out) > 0 (a tangency counts as a front face); n outward,
 *                      or facing the ray with CYLRAY_FACE_FORWARD; CYLRAY_CULL_BACK
 *                      drops back-face hits
 *   conref_band_eval   the band (below)
 *   conref_judge       as cylref_judge
 *
 * The band's perturbed inputs: the origin relative to the center by 2 ulps of
 * |o - c|, plus 2 ulps of the center's largest coordinate when the center (p0 + p1) / 2
 * is not a float (the prepared cone rounds it once); d by 2 ulps of its
 * largest component; the axis p1 - p0 by 2 ulps of its largest component; each radius
 * by 2 ulps. Re-evaluated once per input, at the two vertices where t is extreme, at
 * 8 random ones, and for each input alone at a quarter and a half of its reach either
 * way (t need not be monotonic in an input on a cone). Where the box takes d.v through
 * 0, also at the level ray (d.v = 0), and a disc outcome seen extends to tmin or tmax
 * or to where the ray leaves the disc's reach. And at the rays of the box (d's and the
 * origin's moves along the axis) that meet each end's plane along the line's chord
 * across the disc, clipped to the range: the ends and inside of the stretch of that
 * chord where those moves can reach the plane.
 * A candidate (each side root, each disc) whose validity margins (the
 * discriminant, the slab, the disc, tmin and tmax) can change sign in the box, or lie
 * within 4 float ulps of the values compared, may be taken or dropped; candidates whose
 * t ranges overlap may come in either order; every outcome this allows is kept. A
 * cone in a leaf has the same band. */
CYLREF_SHAPE_DECLARE(conref, cylray_cone);

/* The cylinder a cone with r0 == r1 prepares as (cylray_cylinder_from_endpoints's). */
void conref_as_cylinder(const cylray_cone *c, cylray_cylinder *out);

#ifdef __cplusplus
}
#endif

#endif /* CONREF_H */
