/* SPDX-License-Identifier: MIT */
/* kernel/runtime.h - the drivers with the flags read at run time: the generic
 * variants' way in, and the specialisations that take them. */

/* One instance each of the drivers with the flags read at run time. */
CYLRAY_MAYBE_UNUSED CYLRAY_OUTLINE size_t KFN(stream_any)(const cylray_prepared *P,
                                                          const cylray_rays *R,
                                                          const cylray_hits *H,
                                                          uint8_t *occluded, size_t n,
                                                          unsigned rt, unsigned FL)
{
    return KFN(stream)(P, R, H, occluded, n, rt, FL, NULL);
}

CYLRAY_MAYBE_UNUSED CYLRAY_OUTLINE uint32_t KFN(packet_any)(const cylray_prepared *P,
                                                            float *ray, float *hit, size_t n,
                                                            uint32_t active, unsigned rt,
                                                            unsigned FL)
{
    return n == VW ? KFN(packet1)(P, ray, hit, active, rt, FL)
                   : KFN(packet)(P, ray, hit, n, active, rt, FL);
}

CYLRAY_MAYBE_UNUSED CYLRAY_OUTLINE int KFN(leaf_any)(const float *L, size_t lm,
                                                     cylray_ray1 *ray, cylray_hit1 *hit,
                                                     unsigned rt, unsigned FL)
{
    return KFN(leaf)(L, lm, ray, hit, rt, FL);
}

#if VW == 1
/* One lane a vector: a packet of several is a stream of its lanes, and runs through a
 * stream driver (its slot's, or the one with the flags read at run time), a run of
 * consecutive active lanes a call (a whole packet is one call). The lanes see the same
 * kernel with the same inputs, so the answers are the same; a second copy of every
 * kernel (about a third of this path's code) is not. The hit lanes are read back from
 * the parts, which the stream writes to a local copy (a hit's part is never 0), or
 * from the occluded bytes. */
CYLRAY_INLINE uint32_t KFN(by_stream_)(const cylray_prepared *P, float *ray, float *hit,
                                       size_t n, uint32_t active, unsigned rt,
                                       KFN(stream_fn) st, unsigned FL)
{
    int32_t part[32] = {0};
    uint8_t occ[32] = {0};
    for (size_t b = 0; b < n;) {
        if (!((active >> b) & 1u)) {
            b++;
            continue;
        }
        size_t e = b + 1;
        while (e < n && ((active >> e) & 1u))
            e++;
        const cylray_rays R = {ray + b,         ray + n + b,     ray + 2 * n + b,
                               ray + 3 * n + b, ray + 4 * n + b, ray + 5 * n + b,
                               ray + 6 * n + b, ray + 7 * n + b};
        const cylray_hits H = {hit ? hit + b : NULL, hit ? hit + n + b : NULL,
                               hit ? hit + 2 * n + b : NULL, hit ? hit + 3 * n + b : NULL,
                               part + b};
        if (st)
            st(P, &R, hit ? &H : NULL, hit ? NULL : occ + b, e - b, rt);
        else
            KFN(stream_any)(P, &R, hit ? &H : NULL, hit ? NULL : occ + b, e - b, rt, FL);
        b = e;
    }
    int32_t *out = hit ? (int32_t *)(void *)(hit + 4 * n) : NULL;
    uint32_t hits = 0;
    for (size_t j = 0; j < n; j++) {
        if (hit ? part[j] != 0 : occ[j] != 0) {
            hits |= 1u << j;
            if (hit)
                out[j] = part[j];
        }
    }
    return hits;
}
static uint32_t KFN(packet_by_stream)(const cylray_prepared *P, float *ray, float *hit,
                                      size_t n, uint32_t active, unsigned rt, KFN(stream_fn) st)
{
    return KFN(by_stream_)(P, ray, hit, n, active, rt, st, 0u);
}
#endif

/* The entry points' way to the generic drivers, for what the specialisations
 * (kernel/tables.h) leave out: a cylinder whose radius is far from 1 or that has one
 * disc only (variant >= CYLRAY_VARIANT_GENERIC). Cold, so that the entry points' hot
 * path to the specialised kernels stays free of the call's register saves. */
CYLRAY_MAYBE_UNUSED CYLRAY_NOINLINE uint32_t KFN(packet_generic)(const cylray_prepared *P,
                                                                 float *ray, float *hit,
                                                                 size_t n, uint32_t active,
                                                                 unsigned flags)
{
#if VW == 1 /* KFN(by_stream_) above */
    return KFN(by_stream_)(P, ray, hit, n, active, flags & CYLRAY_KF_RUNTIME, NULL,
                           cylray_generic_kf_(P, flags, hit == NULL));
#else
    return KFN(packet_any)(P, ray, hit, n, active, flags & CYLRAY_KF_RUNTIME,
                           cylray_generic_kf_(P, flags, hit == NULL));
#endif
}

CYLRAY_MAYBE_UNUSED CYLRAY_NOINLINE size_t KFN(stream_generic)(const cylray_prepared *P,
                                                               const cylray_rays *R,
                                                               const cylray_hits *H,
                                                               uint8_t *occluded, size_t n,
                                                               unsigned flags)
{
    return KFN(stream_any)(P, R, H, occluded, n, flags & CYLRAY_KF_RUNTIME,
                           cylray_generic_kf_(P, flags, occluded != NULL));
}
