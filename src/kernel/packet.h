/* SPDX-License-Identifier: MIT */
/* kernel/packet.h - the rare instance, the one place the drivers fall back to it,
 * and the packet drivers. */

static const cylray_hits KFN(no_hits) = {NULL, NULL, NULL, NULL, NULL}; /* occlusion */

/* The rare instance, one per ISA and width for every kind and flag set: a vector with
 * an active lane whose direction is far from unit length is rare, and the branches on
 * FL here cost less than more specialised copies would. The drivers call it (through
 * KFN(vector)) when KFN(block) asks for it, rather than KFN(block) itself: a call there
 * would make the views escape, and every vector would pay for storing them. */
CYLRAY_NOINLINE uint32_t KFN(block_rare)(const cylray_prepared *P, const cylray_rays *R,
                                         const cylray_hits *H, size_t i, uint32_t bits,
                                         unsigned rt, unsigned FL, const float *L, size_t lm)
{
    return KFN(block)(P, R, H, i, bits, rt, FL | CYLRAY_KF_SCALED, L, lm).hit[0];
}

/* The same for lanes [b, b + VW) of a packet of n, given as the packet structs: the
 * views built here, out of the packet drivers, and the rare instance above called (one
 * copy of it per ISA and width serves both). */
CYLRAY_NOINLINE uint32_t KFN(packet_rare)(const cylray_prepared *P, float *ray, float *hit,
                                          size_t n, size_t b, uint32_t bits, unsigned rt,
                                          unsigned FL)
{
    const int aligned = (FL & CYLRAY_KF_ALIGNED) != 0, occ = (FL & CYLRAY_KF_OCCLUDED) != 0;
    const cylray_rays R = cylray_packet_rays_(P, ray, n, aligned);
    const cylray_hits H = occ ? KFN(no_hits) : cylray_packet_hits_(P, hit, n, aligned);
    return KFN(block_rare)(P, &R, &H, b, bits, rt, FL, NULL, 0);
}

/* One vector through KFN(block), or through the rare instance where the block asks for
 * it: the one place the drivers fall back. A packet (pk = 1: ray and hit are its
 * structs, of n lanes) has the rare instance build its views again, so that its own
 * stay in registers; a stream or a leaf passes its views. */
CYLRAY_INLINE cylray_kres_ KFN(vector)(const cylray_prepared *P, const cylray_rays *R,
                                       const cylray_hits *H, size_t i, uint32_t bits,
                                       unsigned rt, const unsigned FL, const float *L,
                                       size_t lm, const int pk, float *ray, float *hit,
                                       size_t n)
{
    cylray_kres_ r = KFN(block)(P, R, H, i, bits, rt, FL, L, lm);
    if (r.rare)
        r.hit[0] = pk ? KFN(packet_rare)(P, ray, hit, n, i, bits, rt, FL)
                      : KFN(block_rare)(P, R, H, i, bits, rt, FL, L, lm);
    return r;
}

/* Two whole vectors of a stream through KFN(block2); where either needs the rare
 * instance, both take it, one at a time. */
CYLRAY_INLINE cylray_kres_ KFN(vector2)(const cylray_prepared *P, const cylray_rays *R,
                                        const cylray_hits *H, size_t i, unsigned rt,
                                        const unsigned FL)
{
    cylray_kres_ r = KFN(block2)(P, R, H, i, i + VW, VFULL, VFULL, rt, FL);
    if (r.rare) {
        r.hit[0] = KFN(block_rare)(P, R, H, i, VFULL, rt, FL, NULL, 0);
        r.hit[1] = KFN(block_rare)(P, R, H, i + VW, VFULL, rt, FL, NULL, 0);
        r.rejected = 0;
    }
    return r;
}

/* A packet given as the packet structs themselves: field f of the rays at ray + f n,
 * of the hits at hit + f n. The views are built here, where they stay in registers,
 * rather than by the caller (a struct of pointers passed through memory costs a store
 * and a reload on every call). packet1 is one vector (n = VW), with constant offsets
 * and nothing else to keep in registers; packet any multiple of VW up to 32. (packet
 * with n = VW folds to nearly the same code, but a rejected AVX2 packet then takes 12
 * instructions and 6 % more time.) */

CYLRAY_INLINE uint32_t KFN(packet1)(const cylray_prepared *P, float *ray, float *hit,
                                    uint32_t active, unsigned rt, const unsigned FL)
{
    const int aligned = (FL & CYLRAY_KF_ALIGNED) != 0, occ = (FL & CYLRAY_KF_OCCLUDED) != 0;
    const cylray_rays R = cylray_packet_rays_(P, ray, VW, aligned);
    const cylray_hits H = occ ? KFN(no_hits) : cylray_packet_hits_(P, hit, VW, aligned);
    return KFN(vector)(P, &R, &H, 0, active, rt, FL, NULL, 0, 1, ray, hit, VW).hit[0];
}

/* A packet of several vectors, one vector at a time. Two in flight, as the streams
 * run them, did not pay here (docs/performance.md): a packet has no further vectors
 * to pair a survivor with, and a pair that the rejection drops costs more than two
 * single vectors do. */
CYLRAY_INLINE uint32_t KFN(packet)(const cylray_prepared *P, float *ray, float *hit, size_t n,
                                   uint32_t active, unsigned rt, const unsigned FL)
{
    const int aligned = (FL & CYLRAY_KF_ALIGNED) != 0, occ = (FL & CYLRAY_KF_OCCLUDED) != 0;
    const cylray_rays R = cylray_packet_rays_(P, ray, n, aligned);
    const cylray_hits H = occ ? KFN(no_hits) : cylray_packet_hits_(P, hit, n, aligned);
    uint32_t hits = 0;
    for (size_t b = 0; b < n; b += VW) {
        uint32_t a = (active >> b) & VFULL;
        if (a) {
            hits |= KFN(vector)(P, &R, &H, b, a, rt, FL, NULL, 0, 1, ray, hit, n).hit[0] << b;
        }
    }
    return hits;
}
