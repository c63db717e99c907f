/* SPDX-License-Identifier: MIT */
/* kernel/shape.h - where the stages meet a shape: the one switch on the kernel's shape
 * flags (CYLRAY_KF_SPHERE, CYLRAY_KF_CONE), each hook taking its shape's branch from
 * kernel/shape/ (the flags are compile-time constants: every other branch folds away).
 * The stages call these hooks and name no shape; a shape that adds its own stage work
 * adds its branch here and its file there.
 *
 * The hooks, in the order a vector meets them:
 *   shape_axis, shape_reject   stage 2: the axis, and the test after the bounding sphere
 *   shape_anchor_rr            stage 3: the squared radius a slender frame is sized by
 *   shape_start, shape_side    stage 4: the quadratic and its discriminant
 *   shape_unit_v, shape_near_root, shape_far_root, shape_tangent, shape_polish_roots,
 *   shape_polish_bounds        stage 5: the roots
 *   shape_axial, shape_interval, shape_planes, shape_slab, shape_rims
 *                              stage 6: the slab of the ends and the side's interval
 *   shape_ends                 stage 6: a shape's own solid joined to the slab's
 *   shape_part, shape_normal, shape_facing, shape_cap_scale
 *                              stage 8: the part and the normal */

#include "shape/cylinder.h"
#include "shape/sphere.h"
#include "shape/round_cone.h"
#include "shape/cone_frame.h"
#include "shape/cone.h"
#include "shape/cone_rims.h"

CYLRAY_INLINE void KFN(shape_axis)(KFN(lanes) *st, const cylray_kat_ *k, const cylray_kflags_ F)
{
    if (F.sphere)
        st->vx = st->vy = st->vz = vzero();
    else
        KFN(axis_in)(st, k, F);
}

/* After the bounding sphere (act, with w.w = ww): whether any lane is left. */
CYLRAY_INLINE int KFN(shape_reject)(KFN(lanes) *st, const cylray_kat_ *k,
                                    const cylray_kflags_ F, vm act, vf ww)
{
    if (F.sphere && F.round) /* a round cone's larger sphere: on the surface or not */
        act = mand(act, mfrom_bits(k->P->rc_caps ? VFULL : 0u));
    if (F.sphere)
        return KFN(sphere_reject)(st, act);
    const vf g0 = KFN(axis_cross)(st, F);
    if (F.cone)
        return KFN(cone_reject)(st, act);
    return KFN(cyl_reject)(st, act, g0, ww);
}

/* R^2, R a cone's narrower end's, which a leaf holds as a packet does. */
CYLRAY_INLINE vf KFN(shape_anchor_rr)(const KFN(lanes) *st, const cylray_kat_ *k,
                                      const cylray_kflags_ F)
{
    if (!F.cone)
        return st->rr;
    const vf ra = F.leaf    ? KFN(leaf_in)(k, F, CYLRAY_LF_RA)
                  : F.round ? vset1(k->P->kap > 0 ? k->P->rc_rim[0] : k->P->rc_rim[1])
                            : vset1(cylray_cone_ra_(k->P));
    return vmul(ra, ra);
}

/* The shapes' own lane fields, empty before stage 4 (a vector copied whole, as a pair's
 * twin is, copies no undefined values). */
CYLRAY_INLINE void KFN(shape_start)(KFN(lanes) *st)
{
    const vf zero = vzero();
    st->cone.cr = st->cone.ca = st->cone.zn = zero;
    st->cone.near = mfrom_bits(0u);
    st->cone.pol = vlt(vset1(1.0f), zero);
    st->round.pin = st->round.pout = zero;
}

CYLRAY_INLINE int KFN(shape_side)(KFN(lanes) *st, const cylray_kat_ *k, const cylray_kflags_ F)
{
    if (F.sphere)
        return KFN(sphere_side)(st, k, F);
    const int live = F.cone ? KFN(cone_side)(st, k, F) : KFN(cyl_side)(st, k, F);
    /* a round cone's balls may be met by a line that misses its side */
    return F.round ? many(st->act) : live;
}

/* |v| = 1: along a coordinate axis, and on a sphere whose j = 0. */
CYLRAY_INLINE int KFN(shape_unit_v)(const cylray_kflags_ F)
{
    return F.aligned || (F.sphere && !F.scaled && !F.leaf);
}

/* q / A, the root that takes the sign of nB. */
CYLRAY_INLINE vf KFN(shape_near_root)(const KFN(lanes) *st, const cylray_kflags_ F, vm side,
                                      vf q, vf A)
{
    if (F.sphere)
        return KFN(sphere_near_root)(st, q);
    vf r1 = F.fast ? vmul(q, vrcp_fast(A)) : vdiv(q, A);
    if (F.cone)
        r1 = KFN(cone_near_root)(F, side, q, A, r1);
    return r1;
}

/* C / q, the other. By construction q^2 >= A C. Where rounding of C (a point on the
 * surface, or a tangent ray) breaks that, C / q is no root: the two coincide at q / A. */
CYLRAY_INLINE vf KFN(shape_far_root)(const KFN(lanes) *st, const cylray_kflags_ F, vm side,
                                     vf q, vf sq, vf r1)
{
    if (F.sphere)
        return KFN(sphere_far_root)(st, F, side, q, sq, r1);
    const vf C = st->C;
    vf r2;
    if (F.fast) {
        r2 = vmul(C, vrcp_fast(q));
        vm small = mand(side, vlt(vabs(q), vset1(KM_TINY)));
        if (many(small))
            r2 = vsel(small, vdiv(C, q), r2);
    } else {
        r2 = vdiv(C, q);
    }
    return vsel(mor(veq(q, vzero()), vlt(vmul(q, q), vmul(C, st->A))), r1, r2);
}

/* The lanes near a tangency whose far root takes the direct form. */
CYLRAY_INLINE vm KFN(shape_tangent)(const KFN(lanes) *st, const cylray_kflags_ F, vm tangent,
                                    vf A)
{
    return F.cone ? KFN(cone_tangent)(st, tangent, A) : tangent;
}

/* The roots polished before they are ordered (a cone's), */
CYLRAY_INLINE void KFN(shape_polish_roots)(const KFN(lanes) *st, const cylray_kflags_ F,
                                           vm side, vf *r1, vf *r2)
{
    if (F.cone)
        KFN(cone_polish_roots)(st, F, side, r1, r2);
}

/* or after, with CYLRAY_REFINE (a cylinder's and a sphere's): both before anything is
 * decided from them, so that the entry test, the clip and the range test all see the t
 * that is reported: a call with tmax set to a reported t then reports it again. */
CYLRAY_INLINE void KFN(shape_polish_bounds)(KFN(lanes) *st, const cylray_kflags_ F, vm side,
                                            vf A)
{
    if (!F.refine || F.cone || !many(side))
        return;
    st->tn = KFN(polish)(st->rr_vv, st->rr, F.aligned, F.sphere, side, st->tn, A, st->dx,
                         st->dy, st->dz, st->ex, st->ey, st->ez, st->vx, st->vy, st->vz, st->px,
                         st->py, st->pz);
    st->tf = KFN(polish)(st->rr_vv, st->rr, F.aligned, F.sphere, side, st->tf, A, st->dx,
                         st->dy, st->dz, st->ex, st->ey, st->ez, st->vx, st->vy, st->vz, st->px,
                         st->py, st->pz);
}

/* The axial coordinate z0 + t dv, over |v|, of a finite shape with an axis. An aligned
 * axis is measured along the third coordinate itself, whatever its sign: the slab is
 * symmetric, and the sign only names the caps. */
CYLRAY_INLINE void KFN(shape_axial)(const KFN(lanes) *st, const cylray_kflags_ F, vf *z0,
                                    vf *dv)
{
    *z0 = *dv = vzero();
    if (!F.finite || F.sphere)
        return;
    *z0 = F.aligned ? st->pz
          : F.cone  ? KFN(cone_z0)(st)
                    : KDOT(st->px, st->py, st->pz, st->vx, st->vy, st->vz);
    *dv = F.aligned ? st->dz
          : F.cone  ? KFN(cone_dv)(st)
                    : KDOT(st->dx, st->dy, st->dz, st->vx, st->vy, st->vz);
}

/* The side's inside on the ray, [lo, hi]: [tn, tf] but for a cone's nappes. */
CYLRAY_INLINE void KFN(shape_interval)(KFN(lanes) *st, const cylray_kflags_ F, vf *lo, vf *hi)
{
    if (F.cone)
        KFN(cone_interval)(st, lo, hi);
}

/* Where a shape's ends lie, if not at -+H|v| (a round cone's tangent circles): before
 * a slender lane's frame moves them. */
CYLRAY_INLINE void KFN(shape_end_planes)(const cylray_kat_ *k, const cylray_kflags_ F, vf *zlo,
                                         vf *zhi)
{
    if (F.round)
        KFN(round_planes)(k, zlo, zhi);
}

/* The ends' planes, on a tiny-ended cone's lanes measured from that end. */
CYLRAY_INLINE void KFN(shape_planes)(const KFN(lanes) *st, const cylray_kat_ *k,
                                     const cylray_kflags_ F, vf *zlo, vf *zhi)
{
    if (F.cone)
        KFN(cone_planes)(st, k, F, zlo, zhi);
}

/* The slab's bounds, at a cone's tips. */
CYLRAY_INLINE void KFN(shape_slab)(KFN(lanes) *st, const cylray_kat_ *k, const cylray_kflags_ F,
                                   vf slab_in, vf slab_out)
{
    if (F.cone)
        KFN(cone_tips)(st, k, F, slab_in, slab_out);
}

/* Entry and exit where a side meets its ends' discs at their rims (a cone's). */
CYLRAY_INLINE void KFN(shape_rims)(KFN(lanes) *st, const cylray_kat_ *k, const cylray_kflags_ F,
                                   vf slab_in, vf slab_out)
{
    if (F.cone)
        KFN(cone_rims)(st, k, F, slab_in, slab_out);
}

/* The joins of the ends' solid with a shape's own (a round cone's balls), after the
 * slab: na, nb the planes' offsets from the origin's level, ta, tb their crossings. */
CYLRAY_INLINE void KFN(shape_ends)(KFN(lanes) *st, const cylray_kat_ *k, const cylray_kflags_ F,
                                   vf na, vf nb, vf ta, vf tb, vf slab_in, vf slab_out)
{
    if (F.round)
        KFN(round_hull)(st, k, F, na, nb, ta, tb, slab_in, slab_out);
}

/* The part of the hit lanes, where a shape records its own (a round cone); 0 elsewhere. */
CYLRAY_INLINE int KFN(shape_part)(const KFN(lanes) *st, const cylray_kat_ *k,
                                  const cylray_kflags_ F, vf *part)
{
    if (!F.round)
        return 0;
    if (F.sphere) /* one sphere within the other: the larger, its end's cap */
        *part = vset1(k->P->rc_caps & CYLRAY_CAPPED_LO ? CYLRAY_CAP_LO : CYLRAY_CAP_HI);
    else
        *part = KFN(round_part)(st);
    return 1;
}

/* The side's normal at the hit lanes, before its length is corrected. */
CYLRAY_INLINE void KFN(shape_normal)(const KFN(lanes) *st, const cylray_kat_ *k,
                                     const cylray_kflags_ F, vf *nx, vf *ny, vf *nz)
{
    if (F.sphere)
        KFN(sphere_normal)(st, k, F, nx, ny, nz);
    else if (F.cone)
        KFN(cone_normal)(st, k, F, nx, ny, nz);
    else
        KFN(cyl_normal)(st, k, F, nx, ny, nz);
    if (F.round && !F.sphere)
        KFN(round_normal)(st, k, F, nx, ny, nz);
}

/* The direction facing the ray, for a hit point with none of its own. */
CYLRAY_INLINE void KFN(shape_facing)(const KFN(lanes) *st, const cylray_kflags_ F, vf *ux,
                                     vf *uy, vf *uz)
{
    if (F.sphere)
        *ux = st->dx, *uy = st->dy, *uz = st->dz;
    else
        KFN(cyl_facing)(st, F, ux, uy, uz);
}

/* +-1 (sgn) over |v|, for a leaf's cap normal +-v / |v|. */
CYLRAY_INLINE vf KFN(shape_cap_scale)(const KFN(lanes) *st, const cylray_kat_ *k,
                                      const cylray_kflags_ F, vf sgn)
{
    return F.cone ? KFN(cone_cap_scale)(k, F, sgn) : KFN(cyl_cap_scale)(st, k, F, sgn);
}
