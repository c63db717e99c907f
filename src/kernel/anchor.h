/* SPDX-License-Identifier: MIT */
/* kernel/anchor.h - stage 3b: where a slender shape's lanes take their frame. */

/* The lanes of a slender shape (cylray_slender_): a prepared one's all, a leaf's as its
 * meta marks. */
CYLRAY_INLINE vm KFN(slender)(const cylray_kat_ *k, const cylray_kflags_ F)
{
    if (!F.slender)
        return mfrom_bits(0u);
    if (F.leaf) {
        const uint32_t *meta = KFN(leaf_meta)(k);
        return mfrom_bits(cylray_leaf_slender_(meta) >> k->i);
    }
    return mfrom_bits(cylray_slender_(k->P) ? VFULL : 0u);
}

/* The center of a shape 16 radii long or more can lie thousands of radii from where a
 * ray meets it: p, f = v x p and C rounded at |p| there lose the local radius (a tip
 * cone 1e4 radii long kept 10 bits of t). Its lanes take their frame at a point
 * a = c + m v of the axis segment instead, the origin moved to its closest approach to
 * a. Two candidates: the segment's point nearest the line (the clamped common
 * perpendicular: |p| is then the line's distance from the segment, the least any point
 * of it gives), and the origin's own level (clamped), which serves an origin next to
 * the surface whose hit lies far along a shallow ray; the origin's level where the
 * origin lies at least twice as near it as the other. The center stays where the line
 * passes it within twice the larger of the origin's distance from that point and R (a
 * cone's narrower end's): there its frame, with o - c exact, is as local, and an origin
 * far from the shape keeps it (its own perturbation exceeds the shape's size).
 * The choice is made from |w - m v| before p is formed, so that p is formed once, and
 * nothing branches on it (which lanes take a frame is the rays' toss). A leaf's lane
 * chooses from the same bits as a packet, and answers as it does.
 *
 * Any m is exact as long as everything measures from that same a: h = w - m v is
 * rounded once (the product exact), an error of eps |h| that moves the origin within
 * its own perturbation; p = s d + h + wl as the center's shift forms it, and m = 0 is
 * the center's frame bit for bit. Axial coordinates are then measured from a: the
 * slab's planes lie at -+H|v| - m v.v, with v.v as an exact two-term sum, so that a
 * plane near a is placed to the ulps of its own distance from it (KFN(axial): the slab
 * in KFN(ends), the cone's narrower end in KFN(cone_side)). rr is the shape's R^2 (a
 * cone's narrower end's: KFN(shape_anchor_rr)). Sets st->am and st->s, and returns h in
 * hx, hy, hz (w's rounded part where the center stays). */
CYLRAY_INLINE void KFN(anchor)(KFN(lanes) *st, const cylray_kat_ *k, const cylray_kflags_ F,
                               vf rr, vf *hx, vf *hy, vf *hz)
{
    const vf zero = vzero(), four = vset1(4.0f);
    const vf vx = st->vx, vy = st->vy, vz = st->vz, dx = st->dx, dy = st->dy, dz = st->dz;
    const vf whx = st->whx, why = st->why, whz = st->whz;
    const vf hv = KFN(both_in)(k, F, offsetof(cylray_prepared, h_v), CYLRAY_LF_HV);
    *hx = whx, *hy = why, *hz = whz;
    st->am = zero;
    const vm sl = mand(KFN(slender)(k, F), st->act);
    if (!many(sl)) /* (a packet's lanes are all slender or none) */
        return;
    const vf vv = KDOT(vx, vy, vz, vx, vy, vz);
    const vf wv = KDOT(whx, why, whz, vx, vy, vz), dv = KDOT(dx, dy, dz, vx, vy, vz);
    const vf wd = KDOT(whx, why, whz, dx, dy, dz);
    const vf ivv = KRCP(F, vv); /* (a leaf's and a packet's the same bits) */
    const vf lim = vmul(hv, ivv);
    /* the common perpendicular, (d.d w.v - d.v w.d) / |d x v|^2 (st->A is e.e here), and
     * the origin's level; a NaN (d along v) takes the center */
    vf ml = vdiv(vfms(st->dd, wv, vmul(dv, wd)), st->A);
    vf mo = vmul(wv, ivv);
    ml = vsel(veq(ml, ml), ml, zero);
    ml = vmax(vneg(lim), vmin(lim, ml)), mo = vmax(vneg(lim), vmin(lim, mo));
    /* |w - m v| for each, from h = w - m v itself (w.w - m (2 w.v - m v.v) would cancel
     * to eps |w|^2) */
    const vf lx = vfma_x(vneg(ml), vx, whx), ly = vfma_x(vneg(ml), vy, why),
             lz = vfma_x(vneg(ml), vz, whz);
    const vf ox = vfma_x(vneg(mo), vx, whx), oy = vfma_x(vneg(mo), vy, why),
             oz = vfma_x(vneg(mo), vz, whz);
    const vf nl = KDOT(lx, ly, lz, lx, ly, lz), no = KDOT(ox, oy, oz, ox, oy, oz);
    const vm at_o = vle(vmul(four, no), nl);
    const vf mc = vsel(at_o, mo, ml), nc = vsel(at_o, no, nl);
    /* the center's closest approach, squared: |w x d|^2 / d.d (w.w - (w.d)^2 / d.d would
     * cancel to eps |w|^2 from an origin far from the center) */
    const vf cx = vfms(why, dz, vmul(whz, dy)), cy = vfms(whz, dx, vmul(whx, dz)),
             cz = vfms(whx, dy, vmul(why, dx));
    const vf pc = vmul(KDOT(cx, cy, cz, cx, cy, cz), st->rdd);
    const vm anc = mandn(sl, vle(pc, vmul(four, vmax(nc, rr))));
    st->am = vkeep(anc, mc);
    *hx = vsel(anc, vsel(at_o, ox, lx), whx), *hy = vsel(anc, vsel(at_o, oy, ly), why);
    *hz = vsel(anc, vsel(at_o, oz, lz), whz);
    /* the shift to the closest approach to a, skipped as the center's is */
    const vf hd = KDOT(*hx, *hy, *hz, dx, dy, dz), hh = KDOT(*hx, *hy, *hz, *hx, *hy, *hz);
    const vf hd2 = vmul(vmul(hd, hd), st->rdd);
    st->s = vsel(anc, vkeep(vgt(vadd(hd2, hd2), hh), vmul(vneg(hd), st->rdd)), st->s);
}

/* The axial coordinate z (from the center) measured from the lane's frame point c + m v:
 * z - m v.v, with v.v as an exact two-term sum; z itself where m = 0. An aligned axis
 * measures along its third coordinate, whose m v is m vz, exact. */
CYLRAY_INLINE vf KFN(axial)(const KFN(lanes) *st, const cylray_kflags_ F, vf z)
{
    const vf m = st->am;
    if (F.aligned)
        return vsub(z, vmul(m, st->vz));
    const vf vx = st->vx, vy = st->vy, vz = st->vz;
    const vf vv = KDOT(vx, vy, vz, vx, vy, vz);
    const vf vvl = vdot3_x(vx, vy, vz, vx, vy, vz, vneg(vv));
    return vsub(vfma_x(vneg(m), vv, z), vmul(m, vvl));
}
