/* SPDX-License-Identifier: MIT */
/* spawn/spawn_slots.h - one ISA's batched secondary-ray forms, from the spawn/spawn.h
 * instances its translation unit made, as the slots of its cylray_kernels table
 * (KSPAWN_SLOTS, which isa/table.h appends).
 *
 * Parameters: KISA, and SPW4, SPW8, SPW16 (the instance serving each packet width: DW
 * at most the width), SPWS (the one serving streams and leaves in bulk). */

#define SKI_(name) CYLRAY_CAT(name, CYLRAY_CAT(_sp_, KISA))
#define SPW_(name, w) CYLRAY_CAT(name, CYLRAY_CAT(_, w))

#define KSPAWN_PACKET_(n)                                                                      \
    static void SKI_(hit_points##n)(const cylray_prepared *P, const cylray_ray##n *ray,        \
                                    const cylray_hit##n *hit, uint32_t mask,                   \
                                    cylray_points##n *pts)                                     \
    {                                                                                          \
        mask &= (uint32_t)((1ull << n) - 1u);                                                  \
        if (mask)                                                                              \
            SPW_(hit_points_packet, SPW##n)(P, ray->ox, hit->t, n, mask, 0, pts->x);           \
    }                                                                                          \
    static void SKI_(hit_points_normal##n)(const cylray_prepared *P, const cylray_ray##n *ray, \
                                           const cylray_hit##n *hit, uint32_t mask,            \
                                           cylray_points##n *pts)                              \
    {                                                                                          \
        mask &= (uint32_t)((1ull << n) - 1u);                                                  \
        if (mask)                                                                              \
            SPW_(hit_points_packet, SPW##n)(P, ray->ox, hit->t, n, mask, 1, pts->x);           \
    }                                                                                          \
    static void SKI_(spawn_rays##n)(const cylray_prepared *P, const cylray_points##n *pts,     \
                                    const cylray_hit##n *hit, uint32_t mask,                   \
                                    cylray_ray##n *out)                                        \
    {                                                                                          \
        mask &= (uint32_t)((1ull << n) - 1u);                                                  \
        if (mask)                                                                              \
            SPW_(spawn_rays_packet, SPW##n)(P, pts->x, hit->t, n, mask, NULL, out->ox);        \
    }                                                                                          \
    static void SKI_(spawn_rays_side##n)(                                                      \
        const cylray_prepared *P, const cylray_points##n *pts, const cylray_hit##n *hit,       \
        uint32_t mask, uint32_t outward, cylray_ray##n *out)                                   \
    {                                                                                          \
        mask &= (uint32_t)((1ull << n) - 1u);                                                  \
        if (mask)                                                                              \
            SPW_(spawn_rays_packet, SPW##n)(P, pts->x, hit->t, n, mask, &outward, out->ox);    \
    }
KSPAWN_PACKET_(4)
KSPAWN_PACKET_(8)
KSPAWN_PACKET_(16)

static size_t SKI_(hit_points_stream)(const cylray_prepared *P, const cylray_rays *rays,
                                      const cylray_hits *hits, const cylray_points *pts,
                                      size_t n)
{
    return SPW_(hit_points_stream, SPWS)(P, rays, hits, pts, n, 0);
}

static size_t SKI_(hit_points_normal_stream)(const cylray_prepared *P, const cylray_rays *rays,
                                             const cylray_hits *hits, const cylray_points *pts,
                                             size_t n)
{
    return SPW_(hit_points_stream, SPWS)(P, rays, hits, pts, n, 1);
}

static void SKI_(spawn_stream)(const cylray_prepared *P, const cylray_points *pts,
                               const int32_t *part, const cylray_points *dirs,
                               const cylray_points *origins, size_t n)
{
    SPW_(spawn_stream, SPWS)(P, pts, part, NULL, dirs, origins, n);
}

static void SKI_(spawn_stream_side)(const cylray_prepared *P, const cylray_points *pts,
                                    const int32_t *part, const uint8_t *outward,
                                    const cylray_points *dirs, const cylray_points *origins,
                                    size_t n)
{
    SPW_(spawn_stream, SPWS)(P, pts, part, outward, dirs, origins, n);
}

/* Leaves in bulk: the leaves' field arrays, a block of pointers at a time. normals:
 * the hits' n are the kernel's normals; outward: NULL, or the sides asked for. */
#define KSPAWN_LEAF_(m)                                                                        \
    static void SKI_(leaf_points##m)(const cylray_leaf##m *const *leaf,                        \
                                     const cylray_ray1 *ray, const cylray_hit1 *hit,           \
                                     const cylray_points *pts, size_t n, int normals)          \
    {                                                                                          \
        const float *geom[64];                                                                 \
        for (size_t b = 0; b < n; b += 64) {                                                   \
            const size_t c = n - b < 64 ? n - b : 64;                                          \
            for (size_t i = 0; i < c; i++)                                                     \
                geom[i] = leaf[b + i]->geom_[0];                                               \
            cylray_points p = {pts->x + b, pts->y + b, pts->z + b,                             \
                               pts->err ? pts->err + b : NULL};                                \
            SPW_(leaf_hit_points, SPWS)(geom, m, ray + b, hit + b, &p, c, normals);            \
        }                                                                                      \
    }                                                                                          \
    static void SKI_(leaf_origins##m)(const cylray_leaf##m *const *leaf,                       \
                                      const cylray_hit1 *hit, const cylray_points *pts,        \
                                      const uint8_t *outward, const cylray_points *dirs,       \
                                      const cylray_points *origins, size_t n)                  \
    {                                                                                          \
        const float *geom[64];                                                                 \
        for (size_t b = 0; b < n; b += 64) {                                                   \
            const size_t c = n - b < 64 ? n - b : 64;                                          \
            for (size_t i = 0; i < c; i++)                                                     \
                geom[i] = leaf[b + i]->geom_[0];                                               \
            cylray_points p = {pts->x + b, pts->y + b, pts->z + b,                             \
                               pts->err ? pts->err + b : NULL};                                \
            cylray_points d = {dirs->x + b, dirs->y + b, dirs->z + b, NULL};                   \
            cylray_points o = {origins->x + b, origins->y + b, origins->z + b, NULL};          \
            SPW_(leaf_spawn_origins, SPWS)                                                     \
            (geom, m, hit + b, &p, outward ? outward + b : NULL, &d, &o, c);                   \
        }                                                                                      \
    }                                                                                          \
    static void SKI_(leaf_hit_points##m)(const cylray_leaf##m *const *leaf,                    \
                                         const cylray_ray1 *ray, const cylray_hit1 *hit,       \
                                         const cylray_points *pts, size_t n)                   \
    {                                                                                          \
        SKI_(leaf_points##m)(leaf, ray, hit, pts, n, 0);                                       \
    }                                                                                          \
    static void SKI_(leaf_hit_points_normal##m)(                                               \
        const cylray_leaf##m *const *leaf, const cylray_ray1 *ray, const cylray_hit1 *hit,     \
        const cylray_points *pts, size_t n)                                                    \
    {                                                                                          \
        SKI_(leaf_points##m)(leaf, ray, hit, pts, n, 1);                                       \
    }                                                                                          \
    static void SKI_(leaf_spawn_origins##m)(                                                   \
        const cylray_leaf##m *const *leaf, const cylray_hit1 *hit, const cylray_points *pts,   \
        const cylray_points *dirs, const cylray_points *origins, size_t n)                     \
    {                                                                                          \
        SKI_(leaf_origins##m)(leaf, hit, pts, NULL, dirs, origins, n);                         \
    }                                                                                          \
    static void SKI_(leaf_spawn_origins_side##m)(                                              \
        const cylray_leaf##m *const *leaf, const cylray_hit1 *hit, const cylray_points *pts,   \
        const uint8_t *outward, const cylray_points *dirs, const cylray_points *origins,       \
        size_t n)                                                                              \
    {                                                                                          \
        SKI_(leaf_origins##m)(leaf, hit, pts, outward, dirs, origins, n);                      \
    }
KSPAWN_LEAF_(4)
KSPAWN_LEAF_(8)
KSPAWN_LEAF_(16)

/* Each slot filled by name (isa/table.h's designated initializers): a type check alone
 * would let two slots of one signature, such as hit_points4 and hit_points_normal4,
 * trade places. */
#define KSPAWN_SLOT_(slot) .slot = SKI_(slot)
#define KSPAWN_SLOTS                                                                           \
    KSPAWN_SLOT_(hit_points4), KSPAWN_SLOT_(hit_points8), KSPAWN_SLOT_(hit_points16),          \
        KSPAWN_SLOT_(spawn_rays4), KSPAWN_SLOT_(spawn_rays8), KSPAWN_SLOT_(spawn_rays16),      \
        KSPAWN_SLOT_(hit_points_stream), KSPAWN_SLOT_(spawn_stream),                           \
        KSPAWN_SLOT_(leaf_hit_points4), KSPAWN_SLOT_(leaf_hit_points8),                        \
        KSPAWN_SLOT_(leaf_hit_points16), KSPAWN_SLOT_(leaf_spawn_origins4),                    \
        KSPAWN_SLOT_(leaf_spawn_origins8), KSPAWN_SLOT_(leaf_spawn_origins16),                 \
        KSPAWN_SLOT_(hit_points_normal4), KSPAWN_SLOT_(hit_points_normal8),                    \
        KSPAWN_SLOT_(hit_points_normal16), KSPAWN_SLOT_(spawn_rays_side4),                     \
        KSPAWN_SLOT_(spawn_rays_side8), KSPAWN_SLOT_(spawn_rays_side16),                       \
        KSPAWN_SLOT_(hit_points_normal_stream), KSPAWN_SLOT_(spawn_stream_side),               \
        KSPAWN_SLOT_(leaf_hit_points_normal4), KSPAWN_SLOT_(leaf_hit_points_normal8),          \
        KSPAWN_SLOT_(leaf_hit_points_normal16), KSPAWN_SLOT_(leaf_spawn_origins_side4),        \
        KSPAWN_SLOT_(leaf_spawn_origins_side8), KSPAWN_SLOT_(leaf_spawn_origins_side16)

#undef KSPAWN_PACKET_
#undef KSPAWN_LEAF_
