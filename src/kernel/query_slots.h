/* SPDX-License-Identifier: MIT */
/* kernel/query_slots.h - one ISA's intersect, occluded and leaf entry points, the query
 * slots of its cylray_kernels table, from the kernel instantiations its translation unit
 * made; isa/table.h puts them in the table.
 *
 * Parameters: KISA (suffix, e.g. avx2), and KW4, KW8, KW16 (the instantiation suffix
 * that serves each packet width), KWSTREAM (the one that serves streams: the widest
 * vector), and KL4, KL8, KL16 (the one that serves each leaf size); optionally
 * KSTORES(X), which calls X(suffix, policy) for each store policy (CYLRAY_STORE_*) the
 * ISA offers a table for, whose intersect entry points pass that policy down with the
 * run-time flags (the occluded, leaf and spawn ones store no hit vector and are
 * shared). Without it, CYLRAY_STORE_MASKED alone. */

#define KI_(name) CYLRAY_CAT(name, CYLRAY_CAT(_, KISA))

/* Out of line: the entry points of every table (a store policy's, one that divides)
 * go on into these, and a copy inlined in each would only grow the library. */
#define KENTRY_ CYLRAY_OUTLINE
#define KW_(name, w) CYLRAY_CAT(name, CYLRAY_CAT(_, w))

/* The intersect entry points' bodies, one for every store policy: flags holds the
 * public flags and the policy (CYLRAY_KF_STORE_MASK), as the entry points below set
 * them. */
#define KISECT_BODY_(n)                                                                        \
    KENTRY_ uint32_t KI_(intersect##n##_body)(const cylray_prepared *P, cylray_ray##n *ray,    \
                                              cylray_hit##n *hit, uint32_t active,             \
                                              unsigned flags)                                  \
    {                                                                                          \
        active &= (uint32_t)((1ull << n) - 1u);                                                \
        if (!active || !ray || !hit || !cylray_prepared_ok_(P))                                \
            return 0;                                                                          \
        if (cylray_generic_(P))                                                                \
            return KW_(packet_generic, KW##n)(P, ray->ox, hit->t, n, active, flags);           \
        const KW_(packet_fn, KW##n) *t =                                                       \
            n == KW_(vw, KW##n) ? KW_(isect1_table, KW##n) : KW_(isect_table, KW##n);          \
        return t[cylray_isect_index_(P->variant, flags)](P, ray->ox, hit->t, n, active,        \
                                                         flags & CYLRAY_KF_RUNTIME);           \
    }
KISECT_BODY_(4)
KISECT_BODY_(8)
KISECT_BODY_(16)
KENTRY_ size_t KI_(intersect_stream_body)(const cylray_prepared *P, const cylray_rays *rays,
                                          const cylray_hits *hits, size_t n, unsigned flags)
{
    if (!n || !rays || !hits || !cylray_prepared_ok_(P))
        return 0;
    if (cylray_generic_(P))
        return KW_(stream_generic, KWSTREAM)(P, rays, hits, NULL, n, flags);
    return KW_(isect_stream_table, KWSTREAM)[cylray_isect_index_(P->variant, flags)](
        P, rays, hits, NULL, n, flags & CYLRAY_KF_RUNTIME);
}

/* The intersect entry points of one store policy st, named with suffix sfx: of the
 * user's flags they keep the public ones but drop (CYLRAY_FAST in the tables that
 * divide, below), so that none can pose as a policy, and they add the policy. */
#define KISECT_FLAGS_(st, drop)                                                                \
    ((flags & CYLRAY_FLAGS_ALL & ~(drop)) | (st) << CYLRAY_KF_STORE_SHIFT)
#define KISECT_ENTRY_(n, sfx, st, drop)                                                        \
    static uint32_t KI_(intersect##n##sfx)(const cylray_prepared *P, cylray_ray##n *ray,       \
                                           cylray_hit##n *hit, uint32_t active,                \
                                           unsigned flags)                                     \
    {                                                                                          \
        return KI_(intersect##n##_body)(P, ray, hit, active, KISECT_FLAGS_(st, drop));         \
    }
#define KISECT_ALL_(sfx, st, drop)                                                             \
    KISECT_ENTRY_(4, sfx, st, drop)                                                            \
    KISECT_ENTRY_(8, sfx, st, drop)                                                            \
    KISECT_ENTRY_(16, sfx, st, drop)                                                           \
    static size_t KI_(intersect_stream##sfx)(const cylray_prepared *P,                         \
                                             const cylray_rays *rays, const cylray_hits *hits, \
                                             size_t n, unsigned flags)                         \
    {                                                                                          \
        return KI_(intersect_stream_body)(P, rays, hits, n, KISECT_FLAGS_(st, drop));          \
    }
#define KISECT_KEEP_(sfx, st) KISECT_ALL_(sfx, st, 0u)
#ifndef KSTORES
#define KSTORES(X) X(, CYLRAY_STORE_MASKED)
#endif
KSTORES(KISECT_KEEP_)

/* The packet structs are read as arrays of n-lane fields (cylray_packet_rays_). */
#define KPACKET_(n)                                                                            \
    _Static_assert(offsetof(cylray_ray##n, tmax) == 7 * n * sizeof(float) &&                   \
                       offsetof(cylray_hit##n, part) == 4 * n * sizeof(float),                 \
                   "packet fields are n-lane arrays, back to back");                           \
    KENTRY_ uint32_t KI_(occluded##n)(const cylray_prepared *P, const cylray_ray##n *ray,      \
                                      uint32_t active, unsigned flags)                         \
    {                                                                                          \
        active &= (uint32_t)((1ull << n) - 1u);                                                \
        if (!active || !ray || !cylray_prepared_ok_(P))                                        \
            return 0;                                                                          \
        flags &= CYLRAY_FLAGS_ALL;                                                             \
        /* the occluded kernels read tmax and never write through this pointer */              \
        if (cylray_generic_(P))                                                                \
            return KW_(packet_generic, KW##n)(P, (float *)(uintptr_t)ray->ox, NULL, n, active, \
                                              flags);                                          \
        const KW_(packet_fn, KW##n) *t =                                                       \
            n == KW_(vw, KW##n) ? KW_(occ1_table, KW##n) : KW_(occ_table, KW##n);              \
        return t[cylray_occ_index_(P->variant, flags)](P, (float *)(uintptr_t)ray->ox, NULL,   \
                                                       n, active, flags & CYLRAY_CULL_BACK);   \
    }
KPACKET_(4)
KPACKET_(8)
KPACKET_(16)

KENTRY_ size_t KI_(occluded_stream)(const cylray_prepared *P, const cylray_rays *rays,
                                    uint8_t *occluded, size_t n, unsigned flags)
{
    if (!n || !rays || !occluded || !cylray_prepared_ok_(P))
        return 0;
    flags &= CYLRAY_FLAGS_ALL;
    if (cylray_generic_(P))
        return KW_(stream_generic, KWSTREAM)(P, rays, NULL, occluded, n, flags);
    return KW_(occ_stream_table, KWSTREAM)[cylray_occ_index_(P->variant, flags)](
        P, rays, NULL, occluded, n, flags & CYLRAY_CULL_BACK);
}

/* Leaves: a leaf of M runs on the instantiation KLm (VW lanes at a time, M / VW times).
 * A leaf is read as its field array: geom_, then meta_ and id_ (internal/leaf.h). */
#define KLEAF_ENTRY_(m)                                                                        \
    _Static_assert(offsetof(cylray_leaf##m, meta_) == CYLRAY_LF_COUNT * m * sizeof(float) &&   \
                       offsetof(cylray_leaf##m, id_) == (CYLRAY_LF_COUNT + 1) * m * 4,         \
                   "leaf fields are m-lane arrays, back to back");                             \
    KENTRY_ int KI_(leaf_intersect##m)(const cylray_leaf##m *leaf, cylray_ray1 *ray,           \
                                       cylray_hit1 *hit, unsigned flags)                       \
    {                                                                                          \
        if (!leaf || !ray || !hit)                                                             \
            return 0;                                                                          \
        const KW_(leaf_fn, KL##m) *t = KW_(leaf_table, KL##m)[cylray_leaf_row_(leaf->meta_)];  \
        return t[cylray_spec_(flags)](leaf->geom_[0], m, ray, hit,                             \
                                      flags & CYLRAY_FLAGS_ALL & CYLRAY_KF_RUNTIME);           \
    }                                                                                          \
    KENTRY_ int KI_(leaf_occluded##m)(const cylray_leaf##m *leaf, const cylray_ray1 *ray,      \
                                      unsigned flags)                                          \
    {                                                                                          \
        if (!leaf || !ray)                                                                     \
            return 0;                                                                          \
        /* the occluded kernels read the ray and never write through this pointer */           \
        cylray_ray1 *r = (cylray_ray1 *)(uintptr_t)ray;                                        \
        const KW_(leaf_fn, KL##m) *t =                                                         \
            KW_(leaf_occ_table, KL##m)[cylray_leaf_row_(leaf->meta_)];                         \
        return t[cylray_occ_spec_(flags)](leaf->geom_[0], m, r, NULL,                          \
                                          flags & CYLRAY_CULL_BACK);                           \
    }
KLEAF_ENTRY_(4)
KLEAF_ENTRY_(8)
KLEAF_ENTRY_(16)

/* Where the CPU divides quickly, CYLRAY_FAST is served by the exact kernels: they are
 * within its rule and faster there than the estimates with their Newton steps. The x86
 * ISAs (KFAST_BY_CPU) have a second table per store policy that does so (isa/table.h),
 * whose FAST-reading slots are these: each drops the flag and goes on. api/dispatch.c
 * chooses the table once, as it chooses the store policy, so no call asks. */
#ifdef KFAST_BY_CPU
#define KISECT_DIVIDE_(sfx, st) KISECT_ALL_(sfx##_divide, st, CYLRAY_FAST)
KSTORES(KISECT_DIVIDE_)
#define KDIV_OCC_(n)                                                                           \
    static uint32_t KI_(occluded##n##_divide)(                                                 \
        const cylray_prepared *P, const cylray_ray##n *ray, uint32_t active, unsigned flags)   \
    {                                                                                          \
        return KI_(occluded##n)(P, ray, active, flags & ~CYLRAY_FAST);                         \
    }
KDIV_OCC_(4)
KDIV_OCC_(8)
KDIV_OCC_(16)
static size_t KI_(occluded_stream_divide)(const cylray_prepared *P, const cylray_rays *rays,
                                          uint8_t *occluded, size_t n, unsigned flags)
{
    return KI_(occluded_stream)(P, rays, occluded, n, flags & ~CYLRAY_FAST);
}
#define KDIV_LEAF_(m)                                                                          \
    static int KI_(leaf_intersect##m##_divide)(const cylray_leaf##m *leaf, cylray_ray1 *ray,   \
                                               cylray_hit1 *hit, unsigned flags)               \
    {                                                                                          \
        return KI_(leaf_intersect##m)(leaf, ray, hit, flags & ~CYLRAY_FAST);                   \
    }                                                                                          \
    static int KI_(leaf_occluded##m##_divide)(const cylray_leaf##m *leaf,                      \
                                              const cylray_ray1 *ray, unsigned flags)          \
    {                                                                                          \
        return KI_(leaf_occluded##m)(leaf, ray, flags & ~CYLRAY_FAST);                         \
    }
KDIV_LEAF_(4)
KDIV_LEAF_(8)
KDIV_LEAF_(16)
#undef KISECT_DIVIDE_
#undef KDIV_OCC_
#undef KDIV_LEAF_
#endif

#undef KI_
#undef KW_
#undef KENTRY_
#undef KPACKET_
#undef KLEAF_ENTRY_
#undef KISECT_BODY_
#undef KISECT_FLAGS_
#undef KISECT_ENTRY_
#undef KISECT_ALL_
#undef KISECT_KEEP_
