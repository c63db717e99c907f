/* SPDX-License-Identifier: MIT */
/* isa/table.h - one ISA's cylray_kernels table (one per store policy where KSTORES
 * names several: cylray_kernels_<KISA><suffix>_), from the entry points of
 * kernel/query_slots.h and spawn/spawn_slots.h, which the ISA's unit includes first.
 *
 * Parameters: KISA, KISA_ENUM, KISA_NAME, and KSTORES as kernel/query_slots.h reads it. */

#define KT_(name) CYLRAY_CAT(name, CYLRAY_CAT(_, KISA))
/* Each slot filled by name: a type check alone would let two slots of one signature
 * (hit_points4 and hit_points_normal4, say) trade places. */
#define KS_(slot) .slot = KT_(slot)

#ifndef KSTORES
#define KSTORES(X) X(, CYLRAY_STORE_MASKED)
#endif

#define KTABLE_(sfx, st)                                                                       \
    const cylray_kernels CYLRAY_CAT(CYLRAY_CAT(CYLRAY_CAT(cylray_kernels_, KISA), sfx), _) = { \
        .isa = KISA_ENUM,                                                                      \
        .name = KISA_NAME,                                                                     \
        .intersect4 = KT_(intersect4##sfx),                                                    \
        .intersect8 = KT_(intersect8##sfx),                                                    \
        .intersect16 = KT_(intersect16##sfx),                                                  \
        KS_(occluded4),                                                                        \
        KS_(occluded8),                                                                        \
        KS_(occluded16),                                                                       \
        .intersect_stream = KT_(intersect_stream##sfx),                                        \
        KS_(occluded_stream),                                                                  \
        KS_(leaf_intersect4),                                                                  \
        KS_(leaf_intersect8),                                                                  \
        KS_(leaf_intersect16),                                                                 \
        KS_(leaf_occluded4),                                                                   \
        KS_(leaf_occluded8),                                                                   \
        KS_(leaf_occluded16),                                                                  \
        KSPAWN_SLOTS, /* spawn/spawn_slots.h */                                                \
    };
KSTORES(KTABLE_)

/* The tables that serve CYLRAY_FAST with the exact kernels (kernel/query_slots.h): each
 * fills t with its store policy's table and the slots that drop the flag, on the first
 * call that chooses it (api/dispatch.c). Filled by code, not stamped as data: six more
 * tables of pointers would each cost the library a relocation per slot. */
#ifdef KFAST_BY_CPU
#define KDIVIDED_(sfx, st)                                                                     \
    void CYLRAY_CAT(CYLRAY_CAT(CYLRAY_CAT(cylray_divided_, KISA), sfx), _)(cylray_kernels * t) \
    {                                                                                          \
        *t = CYLRAY_CAT(CYLRAY_CAT(CYLRAY_CAT(cylray_kernels_, KISA), sfx), _);                \
        t->intersect4 = KT_(intersect4##sfx##_divide);                                         \
        t->intersect8 = KT_(intersect8##sfx##_divide);                                         \
        t->intersect16 = KT_(intersect16##sfx##_divide);                                       \
        t->occluded4 = KT_(occluded4_divide);                                                  \
        t->occluded8 = KT_(occluded8_divide);                                                  \
        t->occluded16 = KT_(occluded16_divide);                                                \
        t->intersect_stream = KT_(intersect_stream##sfx##_divide);                             \
        t->occluded_stream = KT_(occluded_stream_divide);                                      \
        t->leaf_intersect4 = KT_(leaf_intersect4_divide);                                      \
        t->leaf_intersect8 = KT_(leaf_intersect8_divide);                                      \
        t->leaf_intersect16 = KT_(leaf_intersect16_divide);                                    \
        t->leaf_occluded4 = KT_(leaf_occluded4_divide);                                        \
        t->leaf_occluded8 = KT_(leaf_occluded8_divide);                                        \
        t->leaf_occluded16 = KT_(leaf_occluded16_divide);                                      \
    }
KSTORES(KDIVIDED_)
#undef KDIVIDED_
#endif

#undef KT_
#undef KS_
#undef KTABLE_
#undef KSTORES
