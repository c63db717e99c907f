/* SPDX-License-Identifier: MIT */
/* api/forward.c - the plain entry points of what the tables hold, the kernels and the
 * batched secondary-ray forms, each forwarded to the path api/dispatch.c chose. */
#include "cylray_internal.h"

/* ---- the kernels ------------------------------------------------------------ */

uint32_t cylray_intersect4(const cylray_prepared *cyl, cylray_ray4 *ray, cylray_hit4 *hit,
                           uint32_t active, unsigned flags)
{
    return cylray_kernels_best()->intersect4(cyl, ray, hit, active, flags);
}
uint32_t cylray_intersect8(const cylray_prepared *cyl, cylray_ray8 *ray, cylray_hit8 *hit,
                           uint32_t active, unsigned flags)
{
    return cylray_kernels_best()->intersect8(cyl, ray, hit, active, flags);
}
uint32_t cylray_intersect16(const cylray_prepared *cyl, cylray_ray16 *ray, cylray_hit16 *hit,
                            uint32_t active, unsigned flags)
{
    return cylray_kernels_best()->intersect16(cyl, ray, hit, active, flags);
}
uint32_t cylray_occluded4(const cylray_prepared *cyl, const cylray_ray4 *ray, uint32_t active,
                          unsigned flags)
{
    return cylray_kernels_best()->occluded4(cyl, ray, active, flags);
}
uint32_t cylray_occluded8(const cylray_prepared *cyl, const cylray_ray8 *ray, uint32_t active,
                          unsigned flags)
{
    return cylray_kernels_best()->occluded8(cyl, ray, active, flags);
}
uint32_t cylray_occluded16(const cylray_prepared *cyl, const cylray_ray16 *ray, uint32_t active,
                           unsigned flags)
{
    return cylray_kernels_best()->occluded16(cyl, ray, active, flags);
}
size_t cylray_intersect_stream(const cylray_prepared *cyl, const cylray_rays *rays,
                               const cylray_hits *hits, size_t n, unsigned flags)
{
    return cylray_kernels_best()->intersect_stream(cyl, rays, hits, n, flags);
}
size_t cylray_occluded_stream(const cylray_prepared *cyl, const cylray_rays *rays,
                              uint8_t *occluded, size_t n, unsigned flags)
{
    return cylray_kernels_best()->occluded_stream(cyl, rays, occluded, n, flags);
}

#define LEAF_ENTRY_(m)                                                                         \
    int cylray_leaf_intersect##m(const cylray_leaf##m *leaf, cylray_ray1 *ray,                 \
                                 cylray_hit1 *hit, unsigned flags)                             \
    {                                                                                          \
        return cylray_kernels_best()->leaf_intersect##m(leaf, ray, hit, flags);                \
    }                                                                                          \
    int cylray_leaf_occluded##m(const cylray_leaf##m *leaf, const cylray_ray1 *ray,            \
                                unsigned flags)                                                \
    {                                                                                          \
        return cylray_kernels_best()->leaf_occluded##m(leaf, ray, flags);                      \
    }
LEAF_ENTRY_(4)
LEAF_ENTRY_(8)
LEAF_ENTRY_(16)

/* ---- secondary rays --------------------------------------------------------- */

#define CYLRAY_SPAWN_PACKET_(n)                                                                \
    void cylray_hit_points##n(const cylray_prepared *cyl, const cylray_ray##n *ray,            \
                              const cylray_hit##n *hit, uint32_t mask, cylray_points##n *pts)  \
    {                                                                                          \
        cylray_kernels_best()->hit_points##n(cyl, ray, hit, mask, pts);                        \
    }                                                                                          \
    void cylray_hit_points_normal##n(const cylray_prepared *cyl, const cylray_ray##n *ray,     \
                                     const cylray_hit##n *hit, uint32_t mask,                  \
                                     cylray_points##n *pts)                                    \
    {                                                                                          \
        cylray_kernels_best()->hit_points_normal##n(cyl, ray, hit, mask, pts);                 \
    }                                                                                          \
    void cylray_spawn_rays##n(const cylray_prepared *cyl, const cylray_points##n *pts,         \
                              const cylray_hit##n *hit, uint32_t mask, cylray_ray##n *out)     \
    {                                                                                          \
        cylray_kernels_best()->spawn_rays##n(cyl, pts, hit, mask, out);                        \
    }                                                                                          \
    void cylray_spawn_rays_side##n(const cylray_prepared *cyl, const cylray_points##n *pts,    \
                                   const cylray_hit##n *hit, uint32_t mask, uint32_t outward,  \
                                   cylray_ray##n *out)                                         \
    {                                                                                          \
        cylray_kernels_best()->spawn_rays_side##n(cyl, pts, hit, mask, outward, out);          \
    }
CYLRAY_SPAWN_PACKET_(4)
CYLRAY_SPAWN_PACKET_(8)
CYLRAY_SPAWN_PACKET_(16)
#undef CYLRAY_SPAWN_PACKET_

size_t cylray_hit_points_stream(const cylray_prepared *cyl, const cylray_rays *rays,
                                const cylray_hits *hits, const cylray_points *pts, size_t n)
{
    return cylray_kernels_best()->hit_points_stream(cyl, rays, hits, pts, n);
}

size_t cylray_hit_points_normal_stream(const cylray_prepared *cyl, const cylray_rays *rays,
                                       const cylray_hits *hits, const cylray_points *pts,
                                       size_t n)
{
    return cylray_kernels_best()->hit_points_normal_stream(cyl, rays, hits, pts, n);
}

void cylray_spawn_stream(const cylray_prepared *cyl, const cylray_points *pts,
                         const int32_t *part, const cylray_points *dirs,
                         const cylray_points *origins, size_t n)
{
    cylray_kernels_best()->spawn_stream(cyl, pts, part, dirs, origins, n);
}

void cylray_spawn_stream_side(const cylray_prepared *cyl, const cylray_points *pts,
                              const int32_t *part, const uint8_t *outward,
                              const cylray_points *dirs, const cylray_points *origins, size_t n)
{
    cylray_kernels_best()->spawn_stream_side(cyl, pts, part, outward, dirs, origins, n);
}

#define CYLRAY_SPAWN_LEAF_(m)                                                                  \
    void cylray_leaf_hit_points##m(const cylray_leaf##m *const *leaf, const cylray_ray1 *ray,  \
                                   const cylray_hit1 *hit, const cylray_points *pts, size_t n) \
    {                                                                                          \
        cylray_kernels_best()->leaf_hit_points##m(leaf, ray, hit, pts, n);                     \
    }                                                                                          \
    void cylray_leaf_hit_points_normal##m(const cylray_leaf##m *const *leaf,                   \
                                          const cylray_ray1 *ray, const cylray_hit1 *hit,      \
                                          const cylray_points *pts, size_t n)                  \
    {                                                                                          \
        cylray_kernels_best()->leaf_hit_points_normal##m(leaf, ray, hit, pts, n);              \
    }                                                                                          \
    void cylray_leaf_spawn_origins##m(                                                         \
        const cylray_leaf##m *const *leaf, const cylray_hit1 *hit, const cylray_points *pts,   \
        const cylray_points *dirs, const cylray_points *origins, size_t n)                     \
    {                                                                                          \
        cylray_kernels_best()->leaf_spawn_origins##m(leaf, hit, pts, dirs, origins, n);        \
    }                                                                                          \
    void cylray_leaf_spawn_origins_side##m(const cylray_leaf##m *const *leaf,                  \
                                           const cylray_hit1 *hit, const cylray_points *pts,   \
                                           const uint8_t *outward, const cylray_points *dirs,  \
                                           const cylray_points *origins, size_t n)             \
    {                                                                                          \
        cylray_kernels_best()->leaf_spawn_origins_side##m(leaf, hit, pts, outward, dirs,       \
                                                          origins, n);                         \
    }
CYLRAY_SPAWN_LEAF_(4)
CYLRAY_SPAWN_LEAF_(8)
CYLRAY_SPAWN_LEAF_(16)
#undef CYLRAY_SPAWN_LEAF_
