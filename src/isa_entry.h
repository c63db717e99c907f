/* isa_entry.h - one ISA's public entry points and its cylray_kernels table, from the
 * kernel instantiations its translation unit made.
 *
 * Parameters: KISA (suffix, e.g. avx2), KISA_ENUM, KISA_NAME, and KW4, KW8, KW16 (the
 * instantiation suffix that serves each packet width; streams use KW16's). */

#define KI_(name) CYLRAY_CAT(name, CYLRAY_CAT(_, KISA))
#define KW_(name, w) CYLRAY_CAT(name, CYLRAY_CAT(_, w))

#define KPACKET_(n, al)                                                                \
    static uint32_t KI_(intersect##n)(const cylray_prepared *P, cylray_ray##n *ray,    \
                                      cylray_hit##n *hit, uint32_t active, unsigned flags) \
    {                                                                                  \
        active &= (uint32_t)((1ull << n) - 1u);                                        \
        if (!active || !ray || !hit || !cylray_prepared_ok_(P))                        \
            return 0;                                                                  \
        const cylray_rays R0 = {ray->ox, ray->oy, ray->oz, ray->dx, ray->dy, ray->dz, ray->tmin, ray->tmax}; \
        const cylray_hits H0 = {hit->t, hit->nx, hit->ny, hit->nz, hit->part};        \
        const cylray_rays R = cylray_rays_renamed_(P, &R0);                            \
        const cylray_hits H = cylray_hits_renamed_(P, &H0);                            \
        return KW_(isect_table, KW##n)[cylray_isect_index_(cylray_variant_(P), flags)](           \
            P, &R, &H, n, active, flags & CYLRAY_FACE_FORWARD);                        \
    }                                                                                  \
    static uint32_t KI_(occluded##n)(const cylray_prepared *P, const cylray_ray##n *ray, \
                                     uint32_t active, unsigned flags)                  \
    {                                                                                  \
        active &= (uint32_t)((1ull << n) - 1u);                                        \
        if (!active || !ray || !cylray_prepared_ok_(P))                                \
            return 0;                                                                  \
        /* the occluded kernels read tmax and never write through these pointers */    \
        const cylray_rays R0 = {ray->ox, ray->oy, ray->oz, ray->dx, ray->dy, ray->dz,    \
                                ray->tmin, (float *)(uintptr_t)ray->tmax};             \
        const cylray_rays R = cylray_rays_renamed_(P, &R0);                            \
        return KW_(occ_table, KW##n)[cylray_occ_index_(cylray_variant_(P), flags)](               \
            P, &R, NULL, n, active, 0);                                                \
    }
KPACKET_(4, 16)
KPACKET_(8, 32)
KPACKET_(16, 64)

static size_t KI_(intersect_stream)(const cylray_prepared *P, const cylray_rays *rays,
                                    const cylray_hits *hits, size_t n, unsigned flags)
{
    if (!n || !rays || !hits || !cylray_prepared_ok_(P))
        return 0;
    const cylray_rays R = cylray_rays_renamed_(P, rays);
    const cylray_hits H = cylray_hits_renamed_(P, hits);
    return KW_(isect_stream_table, KW16)[cylray_isect_index_(cylray_variant_(P), flags)](
        P, &R, &H, NULL, n, flags & CYLRAY_FACE_FORWARD);
}

static size_t KI_(occluded_stream)(const cylray_prepared *P, const cylray_rays *rays,
                                   uint8_t *occluded, size_t n, unsigned flags)
{
    if (!n || !rays || !occluded || !cylray_prepared_ok_(P))
        return 0;
    const cylray_rays R = cylray_rays_renamed_(P, rays);
    return KW_(occ_stream_table, KW16)[cylray_occ_index_(cylray_variant_(P), flags)](
        P, &R, NULL, occluded, n, 0);
}

const cylray_kernels CYLRAY_CAT(CYLRAY_CAT(cylray_kernels_, KISA), _) = {
    KISA_ENUM,          KISA_NAME,
    KI_(intersect4),    KI_(intersect8),       KI_(intersect16),
    KI_(occluded4),     KI_(occluded8),        KI_(occluded16),
    KI_(intersect_stream), KI_(occluded_stream),
};

#undef KI_
#undef KW_
#undef KPACKET_
