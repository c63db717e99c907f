/* SPDX-License-Identifier: MIT */
/* kernel/stream.h - the stream driver and its tail. */

/* The last lanes of a stream (fewer than a vector: all of a short stream) as one packet
 * of VW lanes, copied in and out: nothing beyond the caller's arrays is read or
 * written. `one` is the stream's own table slot's one-vector packet function, whose
 * kernel is specialised as the stream's is; the streams with flags read at run time
 * pass NULL and get the packet driver with those flags. The views are the stream's,
 * renamed for an aligned cylinder; the packet function renames its packet itself, so
 * the lanes go in and out in the caller's order. A short stream runs here only, so it
 * is compiled for speed, not as a cold path (docs/performance.md). */
CYLRAY_OUTLINE size_t KFN(stream_tail)(const cylray_prepared *P, const cylray_rays *R,
                                       const cylray_hits *H, uint8_t *occluded, size_t n,
                                       size_t i, unsigned rt, unsigned FL, KFN(packet_fn) one)
{
    const int occ = (FL & CYLRAY_KF_OCCLUDED) != 0;
    const int normal = (FL & CYLRAY_NORMAL) && !occ;
    const size_t rest = n - i;
    size_t k[3]; /* the views' component j is the packet's k[j] (cylray_packet_rays_) */
    cylray_axis_order_(P, (FL & CYLRAY_KF_ALIGNED) != 0, k);
    CYLRAY_ALIGN(64) float ray[8 * VW] = {0};
    CYLRAY_ALIGN(64) float hit[5 * VW];
    const float *src[8] = {R->ox, R->oy, R->oz, R->dx, R->dy, R->dz, R->tmin, R->tmax};
    const size_t field[8] = {k[0], k[1], k[2], 3 + k[0], 3 + k[1], 3 + k[2], 6, 7};
    for (size_t f = 0; f < 8; f++)
        for (size_t j = 0; j < rest; j++)
            ray[field[f] * VW + j] = src[f][i + j];
    const uint32_t bits = (uint32_t)((1u << rest) - 1u);
    float *h = occ ? NULL : hit;
    uint32_t m = one ? one(P, ray, h, VW, bits, rt) : KFN(packet1)(P, ray, h, bits, rt, FL);
    const size_t count = CYLRAY_POPCOUNT(m);
    for (; m; m &= m - 1) {
        const size_t j = CYLRAY_CTZ(m);
        if (occ) {
            occluded[i + j] = 1;
            continue;
        }
        H->t[i + j] = hit[j];
        R->tmax[i + j] = ray[7 * VW + j];
        memcpy(&H->part[i + j], &hit[4 * VW + j], sizeof H->part[0]);
        if (normal) {
            H->nx[i + j] = hit[(1 + k[0]) * VW + j];
            H->ny[i + j] = hit[(1 + k[1]) * VW + j];
            H->nz[i + j] = hit[(1 + k[2]) * VW + j];
        }
    }
    return count;
}

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
