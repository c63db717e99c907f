/* SPDX-License-Identifier: MIT */
/* kernel/block.h - the stages in order, for one vector and for two in flight. */

/* The stages after the rejection, the one list that both KFN(block) and KFN(block2)
 * run: for one vector (two = 0: b and kb are not read), or for two in flight (two = 1),
 * their stages alternating. The hit lanes go to hit[0] (and hit[1]); store_b = 0 leaves
 * out b's store, for a twin that has nothing new to store. */
CYLRAY_INLINE void KFN(stages)(KFN(lanes) *a, const cylray_kat_ *ka, KFN(lanes) *b,
                               const cylray_kat_ *kb, const cylray_kflags_ F, const int two,
                               const int store_b, uint32_t hit[2])
{
    KFN(shift)(a, ka, F);
    if (two)
        KFN(shift)(b, kb, F);
    /* A vector of a pair that the side drops runs on with no lane in play: a branch
     * there would cost more than the work it saves, on rays that hit. */
    int live = KFN(side)(a, ka, F);
    if (two)
        live |= KFN(side)(b, kb, F);
    if (!live)
        return;
    KFN(roots)(a, ka, F);
    if (two)
        KFN(roots)(b, kb, F);
    KFN(ends)(a, ka, F);
    if (two)
        KFN(ends)(b, kb, F);
    hit[0] = KFN(decide)(a, ka, F);
    if (two)
        hit[1] = KFN(decide)(b, kb, F);
    if (!F.occ) {
        if (hit[0])
            KFN(store)(a, ka, F);
        if (two && store_b && hit[1])
            KFN(store)(b, kb, F);
    }
}

/* One vector of rays: lanes [i, i + VW) of R, active where `bits` is set. Returns the
 * hit lanes in hit[0], having written H and R->tmax only there; rejected = 1 where the
 * cheap rejections end the work; rare = 1, having written nothing, where the rare
 * instance must take the vector (KFN(vector) does). FL is a compile-time constant.
 *
 * With CYLRAY_KF_ALIGNED the axis is a coordinate axis (P->axis_id) and exactly a unit
 * vector: the coordinates are renamed so that it is the third one, and the side is a
 * 2D quadratic without cross products. */
CYLRAY_INLINE cylray_kres_ KFN(block)(const cylray_prepared *P, const cylray_rays *R,
                                      const cylray_hits *H, size_t i, uint32_t bits,
                                      unsigned rt, const unsigned FL, const float *L, size_t lm)
{
    const cylray_kflags_ F = cylray_kflags_of_(FL, rt);
    const cylray_kat_ at = {P, R, H, L, lm, i, bits, cylray_kcenter_(P, F)};
    cylray_kres_ r = {{0u, 0u}, 0u, 0};
    KFN(lanes) st;
    if (KFN(load_ray)(&st, &at, F)) {
        r.rare = 1;
        return r;
    }
    if (!KFN(reject)(&st, &at, F)) {
        r.rejected = 1;
        return r;
    }
    CYLRAY_REREAD();
    KFN(stages)(&st, &at, &st, &at, F, 0, 0, r.hit);
    return r;
}

/* Two vectors in flight: lanes [i0, i0 + VW) active where bits0 is set and
 * [i1, i1 + VW) where bits1 is. One vector's work is a chain of dependent operations
 * longer than the out-of-order window; with the stages of two vectors alternating, the
 * core has independent work while one waits on a division or a square root. Returns
 * the hit lanes of each in hit[0] and hit[1], and how many of the two the rejection
 * dropped; or rare = 1, having written nothing, when either vector needs the rare
 * instance (KFN(vector2) then takes them one at a time). */
CYLRAY_INLINE cylray_kres_ KFN(block2)(const cylray_prepared *P, const cylray_rays *R,
                                       const cylray_hits *H, size_t i0, size_t i1,
                                       uint32_t bits0, uint32_t bits1, unsigned rt,
                                       const unsigned FL)
{
    const cylray_kflags_ F = cylray_kflags_of_(FL, rt);
    cylray_kat_ k0 = {P, R, H, NULL, 0, i0, bits0, cylray_kcenter_(P, F)};
    cylray_kat_ k1 = {P, R, H, NULL, 0, i1, bits1, cylray_kcenter_(P, F)};
    cylray_kres_ r = {{0u, 0u}, 0u, 0};
    KFN(lanes) a, b;
    if (KFN(load_ray)(&a, &k0, F) | KFN(load_ray)(&b, &k1, F)) {
        r.rare = 1;
        return r;
    }
    const int la = KFN(reject)(&a, &k0, F), lb = KFN(reject)(&b, &k1, F);
    r.rejected = (uint32_t)(!la + !lb);
    if (r.rejected == 2)
        return r;
    CYLRAY_REREAD();
    /* A vector that the rejection drops takes the other's place: the pair then runs
     * one vector twice, at the latency of one, and the kernel stays one copy. */
    if (!la)
        a = b, k0 = k1;
    else if (!lb)
        b = a, k1 = k0;
    KFN(stages)(&a, &k0, &b, &k1, F, 1, la && lb, r.hit);
    r.hit[0] = la ? r.hit[0] : 0u, r.hit[1] = lb ? r.hit[1] : 0u;
    return r;
}
