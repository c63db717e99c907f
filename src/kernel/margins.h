/* SPDX-License-Identifier: MIT */
/* kernel/margins.h - shared by every instantiation, defined once. */

#ifndef CYLRAY_KERNEL_MARGINS_H
#define CYLRAY_KERNEL_MARGINS_H

/* The margins the kernel decides with, each with why it is safe.
 *
 * KM_DD_LO, KM_DD_HI: an active lane whose |d|^2 lies outside [2^-40, 2^40] goes to the
 *   rare instance (2^-40 keeps A R^2 clear of underflow for the smallest radius prepare
 *   takes with j = 0, 2^-20 squared twice over; 2^40 keeps d.d times coordinates of
 *   2^62 below the float range after the shift).
 * KM_SPHERE: the slack of the sphere rejection, relative to |w|^2. The rounding of
 *   w, w.w, w.d and the refined reciprocal moves the closest approach's squared
 *   distance by less than 2^-19 |w|^2; 2^-17 leaves a factor 4.
 * KM_TUBE_A, KM_TUBE_WW: the tube rejection. g0 = e.w from the rounded w is off from
 *   g by d <= 2^-21 sqrt(A ww); the line misses when |g| > R sqrt(A), and
 *   (R sqrt(A) + d)^2 <= A R^2 (1 + 2^-9) + 2^9 d^2 + d^2 < A R^2 (1 + 2^-9) + 2^-30 A ww
 *   (2ab <= 2^-9 a^2 + 2^9 b^2), which leaves room for the products' own rounding.
 * KM_TINY: the hardware estimates treat subnormals as zero; below 2^-100 the exact
 *   operation serves (CYLRAY_FAST).
 * KM_TANGENT: D below 2^-18 A R^2, some 32 ulps of its larger term, is near a tangency,
 *   where only the direct form of the second root is safe (see there).
 * KM_GENERATOR: a cone's A below 2^-8 e.e is the cancellation of a ray nearly along a
 *   generator line, not a tangency (kernel/solve.h, the roots).
 * KM_ROOTLESS: a cone's A = e.e - v.v a^2 below 2^-18 e.e, some 32 ulps of the terms it
 *   is rounded from, may be 0 exactly (a line along the side's lines), where a line can
 *   have no roots; above it the sign of A is sure, and a line steeper than the side
 *   (A < 0) always has roots (kernel/shape/cone.h).
 * KM_CANCEL: a cone's A below 2^-5 e.e: the ray runs within a few degrees of the
 *   side's lines, where nB and C cancel too, and the roots are polished (kernel/shape/cone.h).
 * KM_RIM: a cone's entry by a disc and exit by the side (or the reverse) within 2^-16 of
 *   their size, some 256 ulps, pass a rim; the disc there decides (kernel/ends.h).
 * KM_ROOT: a cone's side root and an end's plane t within 2^-4 of their size may be in
 *   the wrong order where the root is ill-conditioned (0.06 % off, near a flat cone's
 *   tiny end); there a sure disc verdict decides (kernel/ends.h). Beyond, the roots'
 *   own bands are narrower than the gap.
 * KM_NORMAL_OFF: a normal whose squared length is off 1 by more than 2^-10 (a hit point
 *   that rounding moved well off a tiny radius) is normalised exactly; below that one
 *   Newton step of 1/sqrt takes the error to rounding level. */
#define KM_DD_LO 0x1p-40f
#define KM_DD_HI 0x1p40f
#define KM_SPHERE 0x1p-17f
#define KM_TUBE_A (1.0f + 0x1p-9f)
#define KM_TUBE_WW 0x1p-30f
#define KM_TINY 0x1p-100f
#define KM_NORMAL_OFF 0x1p-10f
#define KM_TANGENT 0x1p-18f
#define KM_GENERATOR 0x1p-8f
#define KM_CANCEL 0x1p-5f
#define KM_ROOTLESS 0x1p-18f
#define KM_RIM 0x1p-16f
#define KM_ROOT 0x1p-4f
#endif
