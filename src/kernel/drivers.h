/* SPDX-License-Identifier: MIT */
/* kernel/drivers.h - the rare instance and the packet drivers. */

static const cylray_hits KFN(no_hits) = {NULL, NULL, NULL, NULL, NULL}; /* occlusion */

/* The rare instance, one per ISA and width for every kind and flag set: a vector with
 * an active lane whose direction is far from unit length is rare, and the branches on
 * FL here cost less than more specialised copies would. The drivers call it when
 * KFN(block) returns CYLRAY_RARE_, rather than KFN(block) itself: a call there would
 * make the views escape, and every vector would pay for storing them. */
CYLRAY_NOINLINE uint32_t KFN(block_rare)(const cylray_prepared *P, const cylray_rays *R,
                                         const cylray_hits *H, size_t i, uint32_t bits,
                                         unsigned rt, unsigned FL, const float *L, size_t lm)
{
    return KFN(block)(P, R, H, i, bits, rt, FL | CYLRAY_KF_SCALED, L, lm);
}

/* The same for lanes [b, b + VW) of a packet of n, given as the packet structs. */
CYLRAY_NOINLINE uint32_t KFN(packet_rare)(const cylray_prepared *P, float *ray, float *hit,
                                          size_t n, size_t b, uint32_t bits, unsigned rt,
                                          unsigned FL)
{
    const int aligned = (FL & CYLRAY_KF_ALIGNED) != 0, occ = (FL & CYLRAY_KF_OCCLUDED) != 0;
    const cylray_rays R = cylray_packet_rays_(P, ray, n, aligned);
    const cylray_hits H = occ ? KFN(no_hits) : cylray_packet_hits_(P, hit, n, aligned);
    return KFN(block)(P, &R, &H, b, bits, rt, FL | CYLRAY_KF_SCALED, NULL, 0);
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
    uint32_t m = KFN(block)(P, &R, &H, 0, active, rt, FL, NULL, 0);
    return m == CYLRAY_RARE_ ? KFN(packet_rare)(P, ray, hit, VW, 0, active, rt, FL) : m;
}

/* The last lanes of a stream, fewer than two vectors, through a local copy: nothing
 * beyond the caller's arrays is read or written. One instance per ISA and width, with
 * the flags read at run time: it runs once per stream call. */
CYLRAY_NOINLINE size_t KFN(stream_tail)(const cylray_prepared *P, const cylray_rays *R,
                                        const cylray_hits *H, uint8_t *occluded, size_t n,
                                        size_t i, unsigned rt, unsigned FL)
{
    const int occ = (FL & CYLRAY_KF_OCCLUDED) != 0;
    const int normal = (FL & CYLRAY_NORMAL) && !occ;
    const size_t rest = n - i;
    float in[8][2 * VW] = {{0}}, out[4][2 * VW] = {{0}};
    int32_t part[2 * VW] = {0};
    const float *src[8] = {R->ox, R->oy, R->oz, R->dx, R->dy, R->dz, R->tmin, R->tmax};
    for (int f = 0; f < 8; f++)
        for (size_t j = 0; j < rest; j++)
            in[f][j] = src[f][i + j];
    const cylray_rays lr = {in[0], in[1], in[2], in[3], in[4], in[5], in[6], in[7]};
    const cylray_hits lh = {out[0], out[1], out[2], out[3], part};
    size_t count = 0;
    for (size_t b = 0; b < rest; b += VW) {
        const uint32_t bits = rest - b >= VW ? VFULL : (uint32_t)((1u << (rest - b)) - 1u);
        uint32_t m = KFN(block)(P, &lr, &lh, b, bits, rt, FL, NULL, 0);
        if (m == CYLRAY_RARE_)
            m = KFN(block_rare)(P, &lr, &lh, b, bits, rt, FL, NULL, 0);
        count += CYLRAY_POPCOUNT(m);
        for (; m; m &= m - 1) {
            const size_t j = b + CYLRAY_CTZ(m);
            if (occ) {
                occluded[i + j] = 1;
                continue;
            }
            H->t[i + j] = out[0][j];
            R->tmax[i + j] = in[7][j];
            H->part[i + j] = part[j];
            if (normal) {
                H->nx[i + j] = out[1][j];
                H->ny[i + j] = out[2][j];
                H->nz[i + j] = out[3][j];
            }
        }
    }
    return count;
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
            uint32_t m = KFN(block)(P, &R, &H, b, a, rt, FL, NULL, 0);
            if (m == CYLRAY_RARE_)
                m = KFN(packet_rare)(P, ray, hit, n, b, a, rt, FL);
            hits |= m << b;
        }
    }
    return hits;
}
