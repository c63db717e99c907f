/* SPDX-License-Identifier: MIT */
/* kernel/shape/cone_frame.h - where a cone's lanes measure from: the axial coordinate
 * and its rate along the ray, the narrower end from which the radius is formed, and a
 * tiny-ended cone's lanes near that end, measured from it (CYLRAY_KF_TINY). */

/* A cone's axial coordinate z0 = p.v, one rounding (KDOTX): its radius at z0 and the
 * ends' slab (kernel/ends.h) both take this one, so that an error in it moves
 * the planes and the side together along the axis and keeps their order where a flat
 * side runs along a plane (rounded product by product, SSE4.1 once put the slab past
 * the side there). The compiler forms it once. */
CYLRAY_INLINE vf KFN(cone_z0)(const KFN(lanes) *st)
{
    return KDOTX(st->px, st->py, st->pz, st->vx, st->vy, st->vz);
}
/* Its rate along the ray dv = d.v, one rounding too: the radius's rate a = kap dv and
 * the slab both take it. A = e.e - v.v a^2 cancels where the ray runs near a generator
 * line, and there an error in d.v that e = d x v does not share moves the root: rounded
 * product by product (SSE4.1), it put t 0.6 % outside the band on a flat tip cone
 * 1.4e-10 long and 0.47 wide. */
CYLRAY_INLINE vf KFN(cone_dv)(const KFN(lanes) *st)
{
    return KDOTX(st->dx, st->dy, st->dz, st->vx, st->vy, st->vz);
}

/* A cone's narrower end, from which its radius is formed: r = ra + kap (z - za), with ra
 * that end's radius as given and za its axial coordinate (-H|v| where kap > 0, +H|v|
 * where kap < 0). At the narrow end's plane z - za is exact (z0 is computed from the
 * same p.v as the slab's), so the disc meets the side at the radius given, however
 * small beside the other; rm + kap z would cancel there to an ulp of the wide end (a
 * 1e-10 tip beside a radius of 0.5 came out 7e-9 wide). Away from it kap (z - za) is
 * the radius's growth from ra, rounded relative to itself: the radius is good to a few
 * ulps of its own value at every level. A leaf holds ra as its radius row; a cylinder's
 * lane in a leaf of cones (kap = 0) takes za = 0, whose half height may be infinite. */
CYLRAY_INLINE void KFN(cone_anchor)(const cylray_kat_ *k, const cylray_kflags_ F, vf kap,
                                    vf *ra, vf *za)
{
    if (F.leaf) {
        const vf hv = KFN(leaf_in)(k, F, CYLRAY_LF_HV);
        *ra = KFN(leaf_in)(k, F, CYLRAY_LF_RA);
        *za = vsel(veq(kap, vzero()), vzero(), vneg(vxorsign(hv, kap)));
    } else if (F.round) { /* at its narrower tangent circle, where its frustum lies */
        const cylray_prepared *P = k->P;
        *ra = vset1(P->kap > 0 ? P->rc_rim[0] : P->rc_rim[1]);
        *za = vset1(P->kap > 0 ? P->rc_z[0] : P->rc_z[1]);
    } else {
        const cylray_prepared *P = k->P;
        *ra = vset1(cylray_cone_ra_(P));
        *za = vset1(P->kap > 0 ? -P->h_v : P->h_v);
    }
}

/* A cone is far smaller near its narrower end than its distance from the center, which
 * sets the rounding of p (and of s + t', and of f = v x p where p runs along the axis):
 * a ray from next to a tip 1e-9 wide and 10 from the center would see it to 1e-6. A
 * lane whose origin lies at least twice as near that end as the center therefore takes
 * its origin there: p = o - a unshifted (s = 0), with a = c + m v, m the power of two
 * nearest za / v.v, so that m v is exact and p = (wh - m v) + wl is o - a rounded at
 * its own size. Axial coordinates are then measured from a: the narrower end's plane
 * lies at zn = za - m v.v (vdot3_x: a residue of the rounding of H|v|, formed to far
 * below it), the other 2 H|v| beyond (KFN(cone_planes), for the slab). Everything after
 * is the same quadratic in that frame, whose C = f.f - v.v r0^2, which cancels to the
 * tiny radius, is formed to the last bits.
 *
 * Only where the cone comes to a point or nearly (its narrower end under 1/64 of the
 * other, cylray_cone_tiny_) is that end's size below what the center's frame resolves:
 * those cones, and leaves that hold one, run kernels of their own (CYLRAY_KF_TINY), and
 * every other cone's kernel has none of this work. */

/* The lanes of a tiny-ended cone: a prepared one's all, a leaf's as its meta marks. */
CYLRAY_INLINE vm KFN(cone_tiny)(const cylray_kat_ *k, const cylray_kflags_ F)
{
    if (!F.tiny)
        return mfrom_bits(0u);
    if (F.leaf) {
        const uint32_t *meta = KFN(leaf_meta)(k);
        return mfrom_bits(cylray_leaf_tiny_(meta) >> k->i);
    }
    /* (a slender cone's kernel serves tiny-ended ones and others) */
    return mfrom_bits(cylray_cone_tiny_(k->P) ? VFULL : 0u);
}

/* The lanes of `tiny` whose origin is near the narrower end, from w = o - c rounded:
 * |o - a|^2 v.v = w.w v.v - 2 (w.v) za + za^2, against w.w v.v / 4. */
CYLRAY_INLINE vm KFN(cone_near)(vm tiny, vf wx, vf wy, vf wz, vf vx, vf vy, vf vz, vf vv, vf za)
{
    const vf ww = KDOT(wx, wy, wz, wx, wy, wz), zw = KDOT(wx, wy, wz, vx, vy, vz);
    const vf oa = vfma(za, za, vfms(ww, vv, vmul(vadd(zw, zw), za)));
    return mand(tiny, vlt(vmul(oa, vset1(4.0f)), vmul(ww, vv)));
}

/* Takes the narrower end's frame on the lanes near it (st->cone.near): p, s, and za, the
 * narrower end's axial coordinate, which becomes zn (kept in st->cone.zn for the slab). */
CYLRAY_INLINE void KFN(cone_frame)(KFN(lanes) *st, vm tiny, vf vv, vf *za)
{
    const vf vx = st->vx, vy = st->vy, vz = st->vz;
    const vm near = KFN(cone_near)(tiny, st->whx, st->why, st->whz, vx, vy, vz, vv, *za);
    st->cone.near = near;
    if (!many(near))
        return;
    const vf m = vexpsign(vmul(vdiv(*za, vv), vset1(1.25f)));
    const vf mx = vmul(m, vx), my = vmul(m, vy), mz = vmul(m, vz);
    st->px = vsel(near, vadd(vsub(st->whx, mx), st->wlx), st->px);
    st->py = vsel(near, vadd(vsub(st->why, my), st->wly), st->py);
    st->pz = vsel(near, vadd(vsub(st->whz, mz), st->wlz), st->pz);
    st->s = vsel(near, vzero(), st->s);
    st->cone.zn = vdot3_x(vneg(mx), vneg(my), vneg(mz), vx, vy, vz, *za);
    *za = vsel(near, st->cone.zn, *za);
}

/* The slab's planes, the axial coordinates of -H and +H (kernel/ends.h), on the lanes
 * that took the narrower end's frame: that end's at zn, the other 2 H|v| beyond. */
CYLRAY_INLINE void KFN(cone_planes)(const KFN(lanes) *st, const cylray_kat_ *k,
                                    const cylray_kflags_ F, vf *zlo, vf *zhi)
{
    if (!F.tiny || !many(st->cone.near))
        return;
    const vf kap = KFN(both_in)(k, F, offsetof(cylray_prepared, kap), CYLRAY_LF_KAP);
    vf ra, za;
    KFN(cone_anchor)(k, F, kap, &ra, &za);
    const vf zn = st->cone.zn, zf = vsub(zn, vadd(za, za));
    const vm lo = vlt(za, vzero()); /* the narrower end is the low one */
    *zlo = vsel(st->cone.near, vsel(lo, zn, zf), *zlo);
    *zhi = vsel(st->cone.near, vsel(lo, zf, zn), *zhi);
}
