/* SPDX-License-Identifier: MIT */
/* kernel/stream.h - the stream driver and the leaf driver. */

/* A stream of any length: whole vectors in place, then the last lanes through
 * KFN(stream_tail) as a packet (`one`: see there). Where the ISA file sets KPAIRS (the
 * widths and kernels on which it was measured to pay), a stream keeps two vectors in
 * flight (KFN(block2)) while the rejection drops none; once a pair sees a vector
 * rejected, the vectors go one at a time until KGROUP_ in a row pass it (a rejected
 * vector would otherwise run beside one that hits, as its twin, and cost what the pair
 * saves). Occlusion streams run the same way. */
#define KGROUP_ KGROUP(cylray_kflags_of_(FL, rt))
CYLRAY_INLINE size_t KFN(stream)(const cylray_prepared *P, const cylray_rays *R0,
                                 const cylray_hits *H0, uint8_t *occluded, size_t n,
                                 unsigned rt, const unsigned FL, KFN(packet_fn) one)
{
    const int occ = (FL & CYLRAY_KF_OCCLUDED) != 0;
    const int aligned = (FL & CYLRAY_KF_ALIGNED) != 0;
    const cylray_rays Rv = aligned ? cylray_rays_renamed_(P, R0) : *R0;
    const cylray_hits Hv = occ ? KFN(no_hits) : aligned ? cylray_hits_renamed_(P, H0) : *H0;
    const cylray_rays *R = &Rv;
    const cylray_hits *H = &Hv;
    const size_t whole = n - n % VW;
    size_t count = 0;
    const int pairs = KPAIRS(cylray_kflags_of_(FL, rt));
    /* The occluded bytes without a branch per hit lane: a loop over the set bits
     * mispredicts on a mix of hits and misses. A lane that missed keeps its byte. */
#define KOCC_MARK_(i, m)                                                                       \
    do {                                                                                       \
        if (occ && (m))                                                                        \
            for (size_t j_ = 0; j_ < VW; j_++)                                                 \
                occluded[(i) + j_] = ((m) >> j_) & 1u ? (uint8_t)1 : occluded[(i) + j_];       \
    } while (0)
    for (size_t i = 0; i < whole;) {
        /* Each phase is a loop of its own: in one loop body with a branch between
         * them, the single vectors of streams that the rejection mostly ends ran 5-10 %
         * slower than in a driver without pairs. Two vectors at a time until a pair
         * sees one rejected... */
        for (uint32_t r = 0; pairs && !r && i + 2 * VW <= whole; i += 2 * VW) {
            const cylray_kres_ v = KFN(vector2)(P, R, H, i, rt, FL);
            r = v.rejected;
            count += (size_t)CYLRAY_POPCOUNT(v.hit[0]) + (size_t)CYLRAY_POPCOUNT(v.hit[1]);
            KOCC_MARK_(i, v.hit[0]);
            KOCC_MARK_(i + VW, v.hit[1]);
        }
        /* ...then one at a time until KGROUP_ in a row pass the rejection (or one is
         * left over); without pairs, to the end. */
        for (int passed = 0; i < whole && (!pairs || passed < KGROUP_ || i + 2 * VW > whole);
             i += VW) {
            const cylray_kres_ v =
                KFN(vector)(P, R, H, i, VFULL, rt, FL, NULL, 0, 0, NULL, NULL, 0);
            count += CYLRAY_POPCOUNT(v.hit[0]);
            KOCC_MARK_(i, v.hit[0]);
            passed = v.rejected ? 0 : passed + 1;
        }
    }
#undef KOCC_MARK_
    if (whole < n)
        count += KFN(stream_tail)(P, R, H, occluded, n, whole, rt, FL, one);
    return count;
}
#undef KGROUP_

/* One ray against a leaf of lm cylinders (lm a multiple of VW, at most 16): a vector of
 * lanes at a time, each with tmax lowered to the closest hit so far, so that a farther
 * vector is rejected cheaply; the closest lane wins, the lowest of equal ones. */
CYLRAY_INLINE int KFN(leaf)(const float *L, size_t lm, cylray_ray1 *ray, cylray_hit1 *hit,
                            unsigned rt, const unsigned FL)
{
    const int occ = (FL & CYLRAY_KF_OCCLUDED) != 0;
    const int normal = (FL & CYLRAY_NORMAL) && !occ;
    const uint32_t *meta = (const uint32_t *)(const void *)(L + CYLRAY_LF_COUNT * lm);
    const uint32_t used = meta[CYLRAY_LM_USED];
    float tmax = ray->tmax;
    const cylray_rays R = {&ray->o[0], &ray->o[1], &ray->o[2], &ray->d[0],
                           &ray->d[1], &ray->d[2], &ray->tmin, &tmax};
    float out[4][16];
    int32_t part[16];
    const cylray_hits H = {out[0], out[1], out[2], out[3], part};
    int best = -1;
    for (size_t b = 0; b < lm; b += VW) {
        uint32_t a = (used >> b) & VFULL;
        if (!a)
            continue;
        uint32_t m = KFN(vector)(NULL, &R, &H, b, a, rt, FL, L, lm, 0, NULL, NULL, 0).hit[0];
        if (occ) {
            if (m)
                return 1;
            continue;
        }
        for (; m; m &= m - 1) {
            int j = (int)(b + CYLRAY_CTZ(m));
            if (best < 0 || out[0][j] < out[0][best])
                best = j;
        }
        if (best >= 0)
            tmax = out[0][best];
    }
    if (best < 0)
        return 0;
    hit->t = out[0][best];
    if (normal) {
        hit->n[0] = out[1][best];
        hit->n[1] = out[2][best];
        hit->n[2] = out[3][best];
    }
    hit->part = part[best];
    hit->id = meta[lm + best]; /* id_ follows meta_ */
    hit->lane = (uint32_t)best;
    ray->tmax = out[0][best];
    return 1;
}
