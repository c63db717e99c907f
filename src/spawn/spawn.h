/* SPDX-License-Identifier: MIT */
/* spawn/spawn.h - secondary rays, written once against the double-vector vocabulary
 * (simd/f64_*.h) and compiled per ISA and width: the hit point with its bound, and the
 * spawned origin. spawn/one_ray.c holds the derivation of every step; this is its one
 * implementation, the scalar entry points being its one-lane instance.
 *
 * Every operation is an IEEE double operation in a fixed order, with no fused
 * multiply-add (the vocabulary has none, and the build turns contraction off), so the
 * answers are the same bit for bit on every ISA and width. Where a branch of the
 * derivation depends on a lane, both sides are computed and a select keeps one; a
 * surface that does not take part contributes through a select, never through a
 * product with zero (its margin may be infinite). The roundings to float the analysis
 * relies on are explicit conversions (dround_f), which no optimiser may drop.
 *
 * Parameters: the vocabulary (DW lanes) and DFN(name), the instance's name. */

#ifndef CYLRAY_SPAWN_TMPL_ONCE_
#define CYLRAY_SPAWN_TMPL_ONCE_
#define CYLRAY_SPAWN_SAFETY 2.0 /* spawn/one_ray.c says why */
#define CYLRAY_SQRT3 1.7320508075688774
#endif
#include "internal/shape.h"

/* The files below, in the order a lane flows through them. */
#include "spawn/geo.h"
#include "spawn/point.h"
#include "spawn/origin.h"
#include "spawn/batch.h"
#include "spawn/forms.h"
