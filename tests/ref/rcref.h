/* SPDX-License-Identifier: MIT */
/* rcref.h - the exact ray/round-cone reference (binary128), written apart from the kernels
 * (kernel/shape/round_cone.h and the tangent frustum are judged against it).
 *
 * A round cone is the convex hull of the spheres (p0, r0) and (p1, r1) (docs/design.md
 * section 9; the derivation of its parts: rcref.c and docs/design.md section 11). Its
 * surface is the cone tangent to both spheres between the two tangent circles (part
 * CYLRAY_SIDE) and the part of each sphere beyond its tangent circle (CYLRAY_CAP_LO for
 * sphere 0, CYLRAY_CAP_HI for sphere 1); a cap whose flag (CYLRAY_CAPPED_LO / _HI) is not
 * set is a hole the side ends at. One sphere inside the other (|p1 - p0| <= |r1 - r0|,
 * a zero-length segment too): the hull is the larger sphere alone, reported as its end's
 * cap and present only with its end's flag. Everything is evaluated in binary128
 * (quad.h) from the float inputs taken as exact binary values. It shares cylref's answer,
 * band and judge types. */
#ifndef RCREF_H
#define RCREF_H

#include "cylref.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The reference's name for cylray.h's round cone. */
typedef cylray_round_cone rcref_round_cone;

/* The round cone's row (cylref.h):
 *   rcref_valid       coordinates of p0 and p1 finite with |x| <= 2^62; each radius 0
 *                     or in [2^-60, 2^62] (2^-60: the sphere's smallest radius; a
 *                     radius of 0 is a point end, not a sphere), not both 0; no flag
 *                     bits but CYLRAY_CAPPED_LO and CYLRAY_CAPPED_HI. Any p0 == p1 is
 *                     taken (one sphere, or two concentric ones: the larger).
 *   rcref_intersect   a ray with NaN/Inf origin or direction, a zero direction or a NaN
 *                     tmin/tmax misses. The hit is the smallest t in the closed
 *                     [tmin, tmax] at which the ray meets a part present; part
 *                     CYLRAY_SIDE / CAP_LO / CAP_HI, | CYLRAY_BACKFACE when
 *                     dot(d, n_out) > 0 (a tangency counts as a front face); n the
 *                     outward unit normal, or facing the ray with CYLRAY_FACE_FORWARD
 *                     (all 0 at a point end's apex, which has none); CYLRAY_CULL_BACK
 *                     drops back-face hits. A point on a tangent circle (a seam) is on
 *                     the side, so a ray through the rim of an open end hits the side.
 *                     Two identical spheres (p0 == p1, r0 == r1): there when either
 *                     end's flag is set, as CAP_LO when CYLRAY_CAPPED_LO is, else as
 *                     CAP_HI.
 *   rcref_band_eval   the band (below)
 *   rcref_judge       as cylref_judge
 *
 * The band's perturbed inputs: the origin relative to the center (p0 + p1) / 2 by 2 ulps
 * of |o - c| (plus 2 ulps of the center's largest coordinate when the center is not a
 * float), d by 2 ulps of its largest component, the axis p1 - p0 by 2 ulps of its
 * largest component (the center kept), each nonzero radius by 2 ulps (a point end stays
 * a point). Re-evaluated once per input either way (a quantity's first-order reach is
 * the sum over the inputs of the larger of its two moves: t has kinks, at a point end's
 * apex), at the two vertices of that box where t is extreme, at 8 random vertices and
 * for each input alone at a quarter and a half of its reach either way. The hull is the union of three convex pieces along the ray:
 * sphere 0, sphere 1 and the frustum of the tangent cone between the tangent planes;
 * its entry is the least of their entries, its exit the greatest of their exits. Each
 * piece may be met or missed when its margins (a discriminant, the frustum's clipped
 * length) can change sign in the box or lie within 4 float ulps; each piece whose entry
 * (exit) can be the least (greatest) within the t ranges the box and 4 float ulps give
 * may be the hull's, and each comparison with tmin and tmax within them may go either
 * way; at a tangency (or within reach of one) the exit may face either way. The frustum
 * is met where the least of its quadratic along the tangent slab's stretch of the ray is
 * <= 0 (a margin continuous in the inputs). Near a tangency a piece's entry and exit
 * reach -B/A -+ sqrt(its margin + the margin's spread)/A (t moves with a square root
 * there, which no first order sees); a ray beside a generator line of the side may meet
 * it wherever the box can put a root of the quadratic along the stretch (conref_band.c's
 * reach). Where |p1 - p0| - |r1 - r0| can change sign in the box, both readings (nested
 * or not) are kept; where the box moves |p1 - p0|^2 - (r1 - r0)^2 by more than 1e-3 of
 * itself (almost nested: the cone's angle turns fast) every first-order spread is
 * widened by 1 + 8 times that part. Every outcome this allows is kept. So a ray through
 * a seam may report the side or the cap, but not a miss, unless the box can take it off
 * the hull. */
CYLREF_SHAPE_DECLARE(rcref, rcref_round_cone);

#ifdef __cplusplus
}
#endif

#endif /* RCREF_H */
