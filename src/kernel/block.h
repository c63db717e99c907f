/* SPDX-License-Identifier: MIT */
/* kernel/block.h - the stages in order, for one vector and for two in flight. */

/* The stages after the rejection, for one vector. Returns the hit lanes. */
CYLRAY_INLINE uint32_t KFN(finish)(KFN(lanes) *st, const cylray_kat_ *k, const cylray_kflags_ F)
{
    KFN(shift)(st, k, F);
    if (!KFN(side)(st, k, F))
        return 0;
    KFN(roots)(st, k, F);
    KFN(ends)(st, k, F);
    uint32_t hit = KFN(decide)(st, k, F);
    if (!F.occ && hit)
        KFN(store)(st, k, F);
    return hit;
}

/* One vector of rays: lanes [i, i + VW) of R, active where `bits` is set. Returns the
 * hit lanes; writes H and R->tmax only there. FL is a compile-time constant. Where the
 * cheap rejections end the work, *rejected (if given) is set.
 *
 * With CYLRAY_KF_ALIGNED the axis is a coordinate axis (P->axis_id) and exactly a unit
 * vector: the coordinates are renamed so that it is the third one, and the side is a
 * 2D quadratic without cross products. */
CYLRAY_INLINE uint32_t KFN(block_r)(const cylray_prepared *P, const cylray_rays *R,
                                    const cylray_hits *H, size_t i, uint32_t bits,
                                    unsigned rt, const unsigned FL, const float *L, size_t lm,
                                    int *rejected)
{
    const cylray_kflags_ F = cylray_kflags_of_(FL, rt);
    const cylray_kat_ at = {P, R, H, L, lm, i, bits, cylray_kcenter_(P, F)};
    KFN(lanes) st;
    if (KFN(load_ray)(&st, &at, F))
        return CYLRAY_RARE_;
    if (!KFN(reject)(&st, &at, F)) {
        if (rejected)
            *rejected = 1;
        return 0;
    }
    CYLRAY_REREAD();
    return KFN(finish)(&st, &at, F);
}

CYLRAY_INLINE uint32_t KFN(block)(const cylray_prepared *P, const cylray_rays *R,
                                  const cylray_hits *H, size_t i, uint32_t bits,
                                  unsigned rt, const unsigned FL, const float *L, size_t lm)
{
    return KFN(block_r)(P, R, H, i, bits, rt, FL, L, lm, NULL);
}

/* Two vectors in flight: lanes [i0, i0 + VW) active where bits0 is set and
 * [i1, i1 + VW) where bits1 is. One vector's work is a chain of dependent operations
 * longer than the out-of-order window; with the stages of two vectors alternating, the
 * core has independent work while one waits on a division or a square root. A vector
 * that the rejection drops takes its partner's place as a twin. Returns how many of
 * the two the rejection dropped, with the hit lanes in m[0] and m[1]; or CYLRAY_RARE_,
 * having written nothing, when either vector needs the rare instance (the driver then
 * takes them one at a time). */
CYLRAY_INLINE uint32_t KFN(block2)(const cylray_prepared *P, const cylray_rays *R,
                                   const cylray_hits *H, size_t i0, size_t i1, uint32_t bits0,
                                   uint32_t bits1, unsigned rt, const unsigned FL,
                                   uint32_t m[2])
{
    const cylray_kflags_ F = cylray_kflags_of_(FL, rt);
    cylray_kat_ k0 = {P, R, H, NULL, 0, i0, bits0, cylray_kcenter_(P, F)};
    cylray_kat_ k1 = {P, R, H, NULL, 0, i1, bits1, cylray_kcenter_(P, F)};
    KFN(lanes) a, b;
    m[0] = m[1] = 0;
    if (KFN(load_ray)(&a, &k0, F) | KFN(load_ray)(&b, &k1, F))
        return CYLRAY_RARE_;
    const int la = KFN(reject)(&a, &k0, F), lb = KFN(reject)(&b, &k1, F);
    const uint32_t dropped = (uint32_t)(!la + !lb);
    if (dropped == 2)
        return dropped;
    CYLRAY_REREAD();
    /* A vector that the rejection drops takes the other's place: the pair then runs
     * one vector twice, at the latency of one, and the kernel stays one copy. */
    if (!la)
        a = b, k0 = k1;
    else if (!lb)
        b = a, k1 = k0;
    KFN(shift)(&a, &k0, F), KFN(shift)(&b, &k1, F);
    /* A vector that the side drops runs on with no lane in play: a branch here would
     * cost more than the work it saves, on rays that hit. */
    if (!(KFN(side)(&a, &k0, F) | KFN(side)(&b, &k1, F)))
        return dropped;
    KFN(roots)(&a, &k0, F), KFN(roots)(&b, &k1, F);
    KFN(ends)(&a, &k0, F), KFN(ends)(&b, &k1, F);
    m[0] = KFN(decide)(&a, &k0, F), m[1] = KFN(decide)(&b, &k1, F);
    if (!F.occ) {
        if (m[0])
            KFN(store)(&a, &k0, F);
        if (m[1] && la && lb) /* a twin stores nothing new */
            KFN(store)(&b, &k1, F);
    }
    m[0] = la ? m[0] : 0u, m[1] = lb ? m[1] : 0u;
    return dropped;
}
#undef KR_
#undef KL_
#undef KC_
#undef KCEN_
#undef KSANE_
#undef KPARTIAL_
#undef KLOAD_O_
