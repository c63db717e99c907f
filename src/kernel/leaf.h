/* SPDX-License-Identifier: MIT */
/* kernel/leaf.h - the leaf driver: one ray against a leaf's lanes. */

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
