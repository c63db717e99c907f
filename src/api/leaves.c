/* SPDX-License-Identifier: MIT */
/* api/leaves.c - building leaves of cylinders, of spheres or of cones: each lane a
 * prepared shape's fields. */
#include "cylray_internal.h"

#include <string.h>

/* Prepares shape k of n (cylinders, spheres or cones, as the leaf holds). */
typedef cylray_status (*prepare_fn)(cylray_prepared *, const void *shapes, size_t k);
static cylray_status prepare_cylinder(cylray_prepared *p, const void *shapes, size_t k)
{
    return cylray_prepare(p, (const cylray_cylinder *)shapes + k);
}
static cylray_status prepare_sphere(cylray_prepared *p, const void *shapes, size_t k)
{
    return cylray_prepare_sphere(p, (const cylray_sphere *)shapes + k);
}
/* A leaf of cones takes every lane as a cone: r0 == r1 too (a cylinder, slope 0). */
static cylray_status prepare_cone(cylray_prepared *p, const void *shapes, size_t k)
{
    const cylray_cone *c = (const cylray_cone *)shapes + k;
    cylray_status st = cylray_prepare_cone(p, c);
    if (st == CYLRAY_OK && p->kind != CYLRAY_KIND_CONE) {
        p->kind = CYLRAY_KIND_CONE;
        p->r0 = c->r0, p->r1 = c->r1, p->rm = c->r0, p->kap = 0.0f, p->cnrm = 1.0f;
    }
    return st;
}

/* Fills a leaf of m lanes (the geom_, meta_ and id_ arrays of cylray_leafM, given as
 * one array of (CYLRAY_LF_COUNT + 2) m words) from shapes[0..n), all or nothing. A
 * sphere's lane has no axis and a zero half height (a finite lane); its bit is set in
 * meta_[CYLRAY_LM_SPHERE]. */
static cylray_status leaf_prepare(void *out, size_t m, size_t bytes, const void *shapes,
                                  prepare_fn prep, const uint32_t *ids, size_t n)
{
    if (!out || n > m || (n && !shapes))
        return CYLRAY_EINVAL;
    float geom[CYLRAY_LF_COUNT][16];
    uint32_t meta[16] = {0}, id[16] = {0};
    memset(geom, 0, sizeof geom);
    for (size_t k = 0; k < m; k++)
        geom[CYLRAY_LF_BOUND2][k] = -1.0f; /* padding: no ray passes the sphere test */
    for (size_t k = 0; k < n; k++) {
        cylray_prepared p;
        if (prep(&p, shapes, k) != CYLRAY_OK)
            return CYLRAY_EINVAL;
        const int cone = p.kind == CYLRAY_KIND_CONE;
        float f[CYLRAY_LF_COUNT] = {
            [CYLRAY_LF_CX] = p.c[0],
            [CYLRAY_LF_CY] = p.c[1],
            [CYLRAY_LF_CZ] = p.c[2],
            [CYLRAY_LF_VX] = p.v[0],
            [CYLRAY_LF_VY] = p.v[1],
            [CYLRAY_LF_VZ] = p.v[2],
            [CYLRAY_LF_R] = p.radius,
            [CYLRAY_LF_H] = p.half_height,
            [CYLRAY_LF_RRVV] = p.rr_vv,
            [CYLRAY_LF_HV] = p.h_v,
            [CYLRAY_LF_SQS] = p.sqrt_vv / p.g_s, /* an exact power-of-two scaling */
            [CYLRAY_LF_GS] = p.g_s,
            [CYLRAY_LF_NSCALE] = p.nscale,
            [CYLRAY_LF_BOUND2] = p.bound2,
        };
        if (cone)
            f[CYLRAY_LF_RA] = cylray_cone_ra_(&p), f[CYLRAY_LF_KAP] = p.kap,
            f[CYLRAY_LF_CNRM] = p.cnrm;
        for (int j = 0; j < CYLRAY_LF_COUNT; j++)
            geom[j][k] = f[j];
        meta[CYLRAY_LM_USED] |= 1u << k;
        if (p.caps & CYLRAY_CAPPED_LO)
            meta[CYLRAY_LM_LO] |= 1u << k;
        if (p.caps & CYLRAY_CAPPED_HI)
            meta[CYLRAY_LM_HI] |= 1u << k;
        if (p.kind == CYLRAY_KIND_SPHERE)
            meta[CYLRAY_LM_SPHERE] |= 1u << k;
        if (cone)
            meta[CYLRAY_LM_SPHERE] |= 1u << (CYLRAY_LM_CONE_SHIFT + k);
        if (cone && cylray_cone_tiny_(&p))
            meta[CYLRAY_LM_USED] |= 1u << (CYLRAY_LM_CONE_SHIFT + k);
        if (cylray_slender_(&p))
            meta[CYLRAY_LM_LO] |= 1u << (CYLRAY_LM_CONE_SHIFT + k);
        id[k] = ids ? ids[k] : (uint32_t)k;
    }
    unsigned char *o = out;
    for (int j = 0; j < CYLRAY_LF_COUNT; j++)
        memcpy(o + (size_t)j * m * 4, geom[j], m * 4);
    memcpy(o + CYLRAY_LF_COUNT * m * 4, meta, m * 4);
    memcpy(o + (CYLRAY_LF_COUNT + 1) * m * 4, id, m * 4);
    (void)bytes;
    return CYLRAY_OK;
}

#define LEAF_PREPARE_(m)                                                                       \
    _Static_assert(sizeof(cylray_leaf##m) == (CYLRAY_LF_COUNT + 2) * m * 4,                    \
                   "a leaf is its field arrays, 64 bytes a lane");                             \
    cylray_status cylray_leaf_prepare##m(cylray_leaf##m *out, const cylray_cylinder *cyl,      \
                                         const uint32_t *ids, size_t n)                        \
    {                                                                                          \
        return leaf_prepare(out, m, sizeof *out, cyl, prepare_cylinder, ids, n);               \
    }                                                                                          \
    cylray_status cylray_leaf_prepare_spheres##m(cylray_leaf##m *out, const cylray_sphere *s,  \
                                                 const uint32_t *ids, size_t n)                \
    {                                                                                          \
        return leaf_prepare(out, m, sizeof *out, s, prepare_sphere, ids, n);                   \
    }                                                                                          \
    cylray_status cylray_leaf_prepare_cones##m(cylray_leaf##m *out, const cylray_cone *c,      \
                                               const uint32_t *ids, size_t n)                  \
    {                                                                                          \
        return leaf_prepare(out, m, sizeof *out, c, prepare_cone, ids, n);                     \
    }
LEAF_PREPARE_(4)
LEAF_PREPARE_(8)
LEAF_PREPARE_(16)
