/* SPDX-License-Identifier: MIT */
/* isa/table.h - one ISA's cylray_kernels table (one per store policy where KSTORES
 * names several: cylray_kernels_<KISA><suffix>_), from the entry points of
 * kernel/query_slots.h and spawn/spawn_slots.h, which the ISA's unit includes first.
 *
 * Parameters: KISA, KISA_ENUM, KISA_NAME, and KSTORES as kernel/query_slots.h reads it. */

#define KT_(name) CYLRAY_CAT(name, CYLRAY_CAT(_, KISA))

#ifndef KSTORES
#define KSTORES(X) X(, CYLRAY_STORE_MASKED)
#endif

#define KTABLE_(sfx, st)                                                                       \
    const cylray_kernels CYLRAY_CAT(CYLRAY_CAT(CYLRAY_CAT(cylray_kernels_, KISA), sfx), _) = { \
        KISA_ENUM,                                                                             \
        KISA_NAME,                                                                             \
        KT_(intersect4##sfx),                                                                  \
        KT_(intersect8##sfx),                                                                  \
        KT_(intersect16##sfx),                                                                 \
        KT_(occluded4),                                                                        \
        KT_(occluded8),                                                                        \
        KT_(occluded16),                                                                       \
        KT_(intersect_stream##sfx),                                                            \
        KT_(occluded_stream),                                                                  \
        KT_(leaf_intersect4),                                                                  \
        KT_(leaf_intersect8),                                                                  \
        KT_(leaf_intersect16),                                                                 \
        KT_(leaf_occluded4),                                                                   \
        KT_(leaf_occluded8),                                                                   \
        KT_(leaf_occluded16),                                                                  \
        KSPAWN_SLOTS, /* spawn/spawn_slots.h */                                                \
    };
KSTORES(KTABLE_)

#undef KT_
#undef KTABLE_
#undef KSTORES
