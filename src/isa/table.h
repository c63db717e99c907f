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

#undef KT_
#undef KS_
#undef KTABLE_
#undef KSTORES
