/* SPDX-License-Identifier: MIT */
/* spawn/one_ray.c - secondary rays: the hit point moved onto the surface with a bound on its
 * distance to it, and the origin from which a new ray leaves that surface; the scalar
 * entry points (the batched ones are dispatched: api/forward.c).
 *
 * Everything is evaluated in double from float inputs, in spawn/spawn.h: one source,
 * compiled per ISA and width against a vocabulary of double vectors (simd/f64_*.h), whose
 * one-lane instance serves the scalar entry points here. docs/secondary-rays.md holds
 * the derivations in full, this comment their steps. Norms written |x|_1 are 1-norms,
 * which bound the 2-norms from above: where one enters a bound, the bound holds.
 *
 * THE HIT POINT. Write u = 2^-53 (double) and q = (o + t d) - c, rounded; the rounding
 * of q only changes which point is projected, never how far the result is from the
 * surface, so the analysis starts at q.
 *   Side. s = (q.v)(1/(v.v)) is off by at most 8u|q|/|v| (a 3-term dot product, the
 *   rounded v.v, its reciprocal, the product), so r = q - s v keeps an axial part
 *   |alpha| <= 12.1u|q| (4.1u|q| more from the subtraction and the product). L = |r|
 *   and g = R (1/L) carry relative errors 2.6u and 4.7u. P' = c + (s v + g r), rounded
 *   three times. The distance of P' from the axis is |g perp(r) + perp(e)| with
 *   |g perp(r)| = g sqrt(L^2 - alpha^2), hence within 4.7u R + R (alpha/L)^2 +
 *   2u(|s v| + R) + u|P'| of R. Clamping s to [-H, H]/|v| (a finite side) adds at most
 *   4.6u H to the axial position.
 *   Cap. P' = c + (+-H/|v|) v + r, with r scaled down to length R when longer: the axial
 *   position is off by at most 4.6u H + 12.1u|q| + 2u(H + R) + u|P'|, the radius by 4.7u R.
 *   Every term is below env = 2^-47 (R + H + |q|_1 + |P'|_1)(1 + R/L) + R (2^-49 |q|_1/L)^2
 *   (2^-47 = 64u; the factor R/L from g alpha; H counts only when finite).
 * Then P = fl(P'), and e = P - P' is exact in double (Sterbenz). fl is a conversion
 * the vocabulary makes certain (dround_f): a vector conversion instruction, or in one
 * lane a conversion through an empty asm statement, so that no optimiser can drop it
 * (gcc 12 at -O3 folded (double)(float)x back into x in vectorised scalar code, giving
 * e = 0). Against the surface
 * point next to P', with the normal n there, the distance from P is at most
 *   |e.n| + |e|^2 / R   (side, |e| <= R/2: the tangential part of e moves the radius
 *                        by |e_t|^2 / (2(R - |e|)) at most),
 *   |e.n|               (cap, the disc's edge more than |e| away),
 *   |e|                 (otherwise, the triangle inequality),
 * plus 3 env (P' itself, and the normal's direction error times |e| <= R). err is that
 * sum rounded up to float.
 *
 * THE SPAWNED ORIGIN. The kernels are held (tests/check) to answer as the exact
 * geometry does for some inputs within 2 ulps of the given ones: the origin relative to
 * the center w = o - c by 2 ulps of its largest component in each component, the axis
 * likewise, the radius and the half height by 2 ulps. A decision the kernel can get
 * wrong is therefore one whose exact answer those perturbations can flip: an origin
 * closer to a surface than
 *   m_side = 2 ulp(X) |n|_1 + |z| tilt + 2 ulp(R),
 *   m_cap  = 2 ulp(X) |n|_1 + rho tilt + 2 ulp(H),   tilt = 2 sqrt(3) ulp(max|v_k|)/|v|,
 * with X = max|w_k| (z, rho: the origin's axial and radial coordinates) may be taken for
 * lying on its other side. The kernels' t is held to 4 ulps, and below 2^-126 an ulp of
 * t is 2^-149: a surface within tau = 4 2^-149 |w|_1 of the origin along the new
 * direction w may be met at t = 0, so tau joins both margins (1e-44 for |w| = 1). The margins m_i used are twice these, with X the larger of
 * max|w_k| and the origin's own max|x_k| (the note below says why). So the
 * origin is moved along each surface's outward normal n_i, to w's side (sign of
 * dot(w, n_i), inward when 0), by
 *   a_i = max(0, -sign_i sigma_i) + e_d + m_i,
 * sigma_i being p's signed distance from surface i computed in double (off by at most
 * e_d = 2^-47 (|q|_1 + R + H)), for the part hit and for any other surface whose
 * distance from p is within err + m_i (a rim). Each float coordinate of the result is
 * then rounded away from p in the direction of the move (the next-float push of
 * pbrt-v4), so that its move along a single normal is never shortened; with two normals
 * (a rim) the rounding may cost sqrt(3) ulp(max|x_k|) against either, which is added to
 * both. Moving inward from the side, the rounding's tangential part shrinks the radius
 * by |e|^2 / rho at most, which is added as well. The margins grow with the origin's
 * own coordinates, so they are evaluated twice, the second time at the first pass's
 * origin enlarged by 2^-19 of itself, which bounds the second pass's. */
#include "cylray_internal.h"

/* The kernels' tolerance box is what the tests hold them to, not a proven bound: one
 * spawned ray in 10^7 (a reflection 0.0015 rad off the tangent plane, its line within
 * 1e-8 R of tangency) was still taken for a hit with the origin at the box's edge. The
 * margins (CYLRAY_SPAWN_SAFETY, in spawn/spawn.h) are therefore twice the box, with the
 * origin's rounding counted in ulps of its world coordinates as well as of those
 * relative to the center (the FMA kernels took an origin 2.4e-6 outside a radius-2.2
 * tube, 2.5 ulps of its coordinate 8, for inside). */
#define DFN(n) CYLRAY_CAT(n, _one_)
#include "simd/f64_scalar.h"
#include "spawn/spawn.h"
#include "simd/f64_undef.h"

/* ---- the scalar entry points ------------------------------------------------ */

void cylray_hit_point(const cylray_prepared *cyl, const float o[3], const float d[3], float t,
                      int32_t part, float p[3], float *err)
{
    DFN(geo) g;
    DFN(geo_prepared)(&g, cyl);
    DFN(hit_point1)(&g, o, d, t, part, NULL, p, err);
}

void cylray_hit_point_normal(const cylray_prepared *cyl, const float o[3], const float d[3],
                             float t, int32_t part, const float n[3], float p[3], float *err)
{
    DFN(geo) g;
    DFN(geo_prepared)(&g, cyl);
    DFN(hit_point1)(&g, o, d, t, part, n, p, err);
}

void cylray_spawn_origin(const cylray_prepared *cyl, const float p[3], float err, int32_t part,
                         const float w[3], float out[3])
{
    DFN(geo) g;
    DFN(geo_prepared)(&g, cyl);
    DFN(spawn1)(&g, p, err, part, 0, w, out);
}

void cylray_spawn_origin_side(const cylray_prepared *cyl, const float p[3], float err,
                              int32_t part, int outward, const float w[3], float out[3])
{
    DFN(geo) g;
    DFN(geo_prepared)(&g, cyl);
    DFN(spawn1)(&g, p, err, part, outward ? 1 : -1, w, out);
}

/* Leaves: the lane the hit names. */
#define CYLRAY_SPAWN_LEAF_(m)                                                                  \
    void cylray_leaf_hit_point##m(const cylray_leaf##m *leaf, const cylray_ray1 *ray,          \
                                  const cylray_hit1 *hit, float p[3], float *err)              \
    {                                                                                          \
        const float *geom = leaf->geom_[0];                                                    \
        DFN(geo) g;                                                                            \
        DFN(leaf_geo)(&g, &geom, hit, m, 1);                                                   \
        DFN(hit_point1)(&g, ray->o, ray->d, hit->t, hit->part, NULL, p, err);                  \
    }                                                                                          \
    void cylray_leaf_hit_point_normal##m(const cylray_leaf##m *leaf, const cylray_ray1 *ray,   \
                                         const cylray_hit1 *hit, float p[3], float *err)       \
    {                                                                                          \
        const float *geom = leaf->geom_[0];                                                    \
        DFN(geo) g;                                                                            \
        DFN(leaf_geo)(&g, &geom, hit, m, 1);                                                   \
        DFN(hit_point1)(&g, ray->o, ray->d, hit->t, hit->part, hit->n, p, err);                \
    }                                                                                          \
    void cylray_leaf_spawn_origin##m(const cylray_leaf##m *leaf, const cylray_hit1 *hit,       \
                                     const float p[3], float err, const float w[3],            \
                                     float out[3])                                             \
    {                                                                                          \
        const float *geom = leaf->geom_[0];                                                    \
        DFN(geo) g;                                                                            \
        DFN(leaf_geo)(&g, &geom, hit, m, 1);                                                   \
        DFN(spawn1)(&g, p, err, hit->part, 0, w, out);                                         \
    }                                                                                          \
    void cylray_leaf_spawn_origin_side##m(const cylray_leaf##m *leaf, const cylray_hit1 *hit,  \
                                          const float p[3], float err, int outward,            \
                                          const float w[3], float out[3])                      \
    {                                                                                          \
        const float *geom = leaf->geom_[0];                                                    \
        DFN(geo) g;                                                                            \
        DFN(leaf_geo)(&g, &geom, hit, m, 1);                                                   \
        DFN(spawn1)(&g, p, err, hit->part, outward ? 1 : -1, w, out);                          \
    }
CYLRAY_SPAWN_LEAF_(4)
CYLRAY_SPAWN_LEAF_(8)
CYLRAY_SPAWN_LEAF_(16)
#undef CYLRAY_SPAWN_LEAF_
