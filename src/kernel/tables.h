/* SPDX-License-Identifier: MIT */
/* kernel/tables.h - the specialisations stamped into the tables the entry points
 * index. */

/* The specialisations, where a tracer spends its time: for each kind of cylinder
 * (infinite, open, capped; the same three along a coordinate axis), the sphere, the
 * capped cone (and the one with a tiny end), and a leaf of cylinders, spheres or cones
 * (and of cones, one with a tiny end), the
 * intersect kernels with and without normals, each plain, with CYLRAY_FAST or with
 * CYLRAY_REFINE, and the occluded ones likewise. FAST and REFINE together (an odd
 * pair: one trades accuracy away, the other buys it) take the drivers that read their
 * flags at run time, as the rare cylinders do; so do face-forward and culling in every
 * kernel (a select each). kind is the variant, b cylray_spec_'s encoding (both decoded
 * in internal/variants.h); the tables are indexed by cylray_isect_index_ /
 * cylray_occ_index_. Half the specialisations of
 * every combination, in build time and size, for the same speed where it counts. */
#define KFL_(kind, spec) (CYLRAY_VARIANT_KF_(kind) | (spec))
#define KLFL_(spec) (CYLRAY_KIND_LEAF << CYLRAY_KF_KIND_SHIFT | (spec))
/* The three drivers of one table slot; the calls are given, as they differ between the
 * specialised drivers and the run-time ones. */
#define KSLOT_(kind, b, pk1_call, pk_body, st_call)                                            \
    static uint32_t KFN(pk1_##kind##_##b)(const cylray_prepared *P, float *R, float *H,        \
                                          size_t n, uint32_t a, unsigned rt)                   \
    {                                                                                          \
        (void)n;                                                                               \
        return pk1_call;                                                                       \
    }                                                                                          \
    static size_t KFN(st_##kind##_##b)(const cylray_prepared *P, const cylray_rays *R,         \
                                       const cylray_hits *H, uint8_t *o, size_t n,             \
                                       unsigned rt)                                            \
    {                                                                                          \
        return st_call;                                                                        \
    }                                                                                          \
    static uint32_t KFN(pk_##kind##_##b)(const cylray_prepared *P, float *R, float *H,         \
                                         size_t n, uint32_t a, unsigned rt)                    \
    {                                                                                          \
        pk_body;                                                                               \
    }
#if VW == 1
#define KPACKET_SEVERAL_(kind, b, fl, drv)                                                     \
    return KFN(packet_by_stream)(P, R, H, n, a, rt, KFN(st_##kind##_##b))
#else
/* A packet of several vectors, one vector at a time (KFN(packet)). */
#define KPACKET_SEVERAL_(kind, b, fl, drv) return KFN(drv)(P, R, H, n, a, rt, fl)
#endif
#define KSPEC_(kind, b, fl)                                                                    \
    KSLOT_(kind, b, KFN(packet1)(P, R, H, a, rt, fl), KPACKET_SEVERAL_(kind, b, fl, packet),   \
           KFN(stream)(P, R, H, o, n, rt, fl, KFN(pk1_##kind##_##b)))
#define KANY_(kind, b, fl)                                                                     \
    KSLOT_(kind, b, KFN(packet_any)(P, R, H, n, a, rt, fl),                                    \
           KPACKET_SEVERAL_(kind, b, fl, packet_any), KFN(stream_any)(P, R, H, o, n, rt, fl))
#define KISECT_(kind, b) KSPEC_(kind, b, KFL_(kind, CYLRAY_SPEC_KF_(b)))
#define KOCC_(kind, b) KSPEC_(kind, o##b, KFL_(kind, CYLRAY_OCC_SPEC_KF_(b)))
#define KISECTANY_(kind, b) KANY_(kind, b, KFL_(kind, CYLRAY_SPEC_KF_(b)))
#define KOCCANY_(kind, b) KANY_(kind, o##b, KFL_(kind, CYLRAY_OCC_SPEC_KF_(b)))
#define KLEAFDRV_(name, drv, fl)                                                               \
    static int KFN(name)(const float *L, size_t lm, cylray_ray1 *r, cylray_hit1 *h,            \
                         unsigned rt)                                                          \
    {                                                                                          \
        return KFN(drv)(L, lm, r, h, rt, fl);                                                  \
    }
#define KLEAF_(b)                                                                              \
    KLEAFDRV_(lf_##b, leaf, KLFL_(CYLRAY_SPEC_KF_(b)))                                         \
    KLEAFDRV_(sf_##b, leaf, KLFL_(CYLRAY_SPEC_KF_(b)) | CYLRAY_KF_SPHERE)
#define KLEAFOCC_(b)                                                                           \
    KLEAFDRV_(lo_##b, leaf, KLFL_(CYLRAY_OCC_SPEC_KF_(b)))                                     \
    KLEAFDRV_(so_##b, leaf, KLFL_(CYLRAY_OCC_SPEC_KF_(b)) | CYLRAY_KF_SPHERE)
#define KLEAFANY_(b)                                                                           \
    KLEAFDRV_(lf_##b, leaf_any, KLFL_(CYLRAY_SPEC_KF_(b)))                                     \
    KLEAFDRV_(sf_##b, leaf_any, KLFL_(CYLRAY_SPEC_KF_(b)) | CYLRAY_KF_SPHERE)
#define KLEAFOCCANY_(b)                                                                        \
    KLEAFDRV_(lo_##b, leaf_any, KLFL_(CYLRAY_OCC_SPEC_KF_(b)))                                 \
    KLEAFDRV_(so_##b, leaf_any, KLFL_(CYLRAY_OCC_SPEC_KF_(b)) | CYLRAY_KF_SPHERE)
/* A slot served by another's drivers. */
#define KALIAS_(kind, b, b0)                                                                   \
    KSLOT_(kind, b, KFN(pk1_##kind##_##b0)(P, R, H, n, a, rt),                                 \
           return KFN(pk_##kind##_##b0)(P, R, H, n, a, rt),                                    \
           KFN(st_##kind##_##b0)(P, R, H, o, n, rt))
#define KLEAFALIAS_(name, target)                                                              \
    static int KFN(name)(const float *L, size_t lm, cylray_ray1 *r, cylray_hit1 *h,            \
                         unsigned rt)                                                          \
    {                                                                                          \
        return KFN(target)(L, lm, r, h, rt);                                                   \
    }
/* The cone specialises only its plain kernels, with and without normals: CYLRAY_FAST
 * takes them as they are (the estimates buy a cone nothing: its divisions are few, and
 * the accurate kernel is within FAST's promise), and CYLRAY_REFINE, the rarer flag,
 * takes the drivers that read their flags at run time. A third of the cone's kernels,
 * which keeps the library within its size. */
/* clang-format off */
#define KCONE_(k)                                                                              \
    KISECT_(k, 0) KISECT_(k, 1) KALIAS_(k, 2, 0) KALIAS_(k, 3, 1)                              \
    KISECTANY_(k, 4) KISECTANY_(k, 5) KISECTANY_(k, 6) KISECTANY_(k, 7)                        \
    KOCC_(k, 0) KALIAS_(k, o1, o0) KOCCANY_(k, 2) KOCCANY_(k, 3)
#define KLEAFCONE_(c, x)                                                                       \
    KLEAFDRV_(c##f_0, leaf, KLFL_(CYLRAY_SPEC_KF_(0)) | CYLRAY_KF_CONE | (x))                  \
    KLEAFDRV_(c##f_1, leaf, KLFL_(CYLRAY_SPEC_KF_(1)) | CYLRAY_KF_CONE | (x))                  \
    KLEAFALIAS_(c##f_2, c##f_0)                                                                \
    KLEAFALIAS_(c##f_3, c##f_1)                                                                \
    KLEAFDRV_(c##f_4, leaf_any, KLFL_(CYLRAY_SPEC_KF_(4)) | CYLRAY_KF_CONE | (x))              \
    KLEAFDRV_(c##f_5, leaf_any, KLFL_(CYLRAY_SPEC_KF_(5)) | CYLRAY_KF_CONE | (x))              \
    KLEAFDRV_(c##f_6, leaf_any, KLFL_(CYLRAY_SPEC_KF_(6)) | CYLRAY_KF_CONE | (x))              \
    KLEAFDRV_(c##f_7, leaf_any, KLFL_(CYLRAY_SPEC_KF_(7)) | CYLRAY_KF_CONE | (x))              \
    KLEAFDRV_(c##o_0, leaf, KLFL_(CYLRAY_OCC_SPEC_KF_(0)) | CYLRAY_KF_CONE | (x))              \
    KLEAFALIAS_(c##o_1, c##o_0)                                                                \
    KLEAFDRV_(c##o_2, leaf_any, KLFL_(CYLRAY_OCC_SPEC_KF_(2)) | CYLRAY_KF_CONE | (x))          \
    KLEAFDRV_(c##o_3, leaf_any, KLFL_(CYLRAY_OCC_SPEC_KF_(3)) | CYLRAY_KF_CONE | (x))
/* clang-format on */
_Static_assert(CYLRAY_VARIANT_CONE == 7 && CYLRAY_VARIANT_CONE_TINY == 8,
               "the cone is kind 7 of the tables, a tiny-ended (or slender) one 8");
#define K8_(X, k) X(k, 0) X(k, 1) X(k, 2) X(k, 3) X(k, 4) X(k, 5) X(k, 6) X(k, 7)
#define K4_(X, k) X(k, 0) X(k, 1) X(k, 2) X(k, 3)
#define KALL8_(X)                                                                              \
    K8_(X, 0) K8_(X, 1) K8_(X, 2) K8_(X, 3) K8_(X, 4) K8_(X, 5) K8_(X, 6) K8_(X, 7) K8_(X, 8)
#define KALL4_(X)                                                                              \
    K4_(X, 0) K4_(X, 1) K4_(X, 2) K4_(X, 3) K4_(X, 4) K4_(X, 5) K4_(X, 6) K4_(X, 7) K4_(X, 8)

/* b = 6, 7 (occluded: 3) are FAST with REFINE. Lists of definitions: clang-format reads
 * them as one long expression and breaks them differently from version to version. */
/* clang-format off */
#define KKIND_(k)                                                                              \
    KISECT_(k, 0)                                                                              \
    KISECT_(k, 1) KISECT_(k, 2) KISECT_(k, 3) KISECT_(k, 4) KISECT_(k, 5) KISECTANY_(k, 6)     \
        KISECTANY_(k, 7) KOCC_(k, 0) KOCC_(k, 1) KOCC_(k, 2) KOCCANY_(k, 3)
KKIND_(0)
KKIND_(1) KKIND_(2) KKIND_(3) KKIND_(4) KKIND_(5) KKIND_(6) KCONE_(7) KCONE_(8) KLEAF_(0) KLEAF_(1) KLEAF_(2) KLEAF_(3)
    KLEAF_(4) KLEAF_(5) KLEAFANY_(6) KLEAFANY_(7) KLEAFOCC_(0) KLEAFOCC_(1) KLEAFOCC_(2)
        KLEAFOCCANY_(3) KLEAFCONE_(c, 0u) KLEAFCONE_(t, CYLRAY_KF_TINY)
/* A leaf that holds a slender shape: the driver with the flags read at run time. */
#define KLEAFSL_(c, x)                                                                         \
    KLEAFDRV_(c##f_0, leaf_any, KLFL_(CYLRAY_SPEC_KF_(0)) | CYLRAY_KF_SLENDER | (x))           \
    KLEAFDRV_(c##f_1, leaf_any, KLFL_(CYLRAY_SPEC_KF_(1)) | CYLRAY_KF_SLENDER | (x))           \
    KLEAFDRV_(c##f_2, leaf_any, KLFL_(CYLRAY_SPEC_KF_(2)) | CYLRAY_KF_SLENDER | (x))           \
    KLEAFDRV_(c##f_3, leaf_any, KLFL_(CYLRAY_SPEC_KF_(3)) | CYLRAY_KF_SLENDER | (x))           \
    KLEAFDRV_(c##f_4, leaf_any, KLFL_(CYLRAY_SPEC_KF_(4)) | CYLRAY_KF_SLENDER | (x))           \
    KLEAFDRV_(c##f_5, leaf_any, KLFL_(CYLRAY_SPEC_KF_(5)) | CYLRAY_KF_SLENDER | (x))           \
    KLEAFDRV_(c##f_6, leaf_any, KLFL_(CYLRAY_SPEC_KF_(6)) | CYLRAY_KF_SLENDER | (x))           \
    KLEAFDRV_(c##f_7, leaf_any, KLFL_(CYLRAY_SPEC_KF_(7)) | CYLRAY_KF_SLENDER | (x))           \
    KLEAFDRV_(c##o_0, leaf_any, KLFL_(CYLRAY_OCC_SPEC_KF_(0)) | CYLRAY_KF_SLENDER | (x))       \
    KLEAFDRV_(c##o_1, leaf_any, KLFL_(CYLRAY_OCC_SPEC_KF_(1)) | CYLRAY_KF_SLENDER | (x))       \
    KLEAFDRV_(c##o_2, leaf_any, KLFL_(CYLRAY_OCC_SPEC_KF_(2)) | CYLRAY_KF_SLENDER | (x))       \
    KLEAFDRV_(c##o_3, leaf_any, KLFL_(CYLRAY_OCC_SPEC_KF_(3)) | CYLRAY_KF_SLENDER | (x))
KLEAFSL_(y, 0u) KLEAFSL_(k, CYLRAY_KF_CONE | CYLRAY_KF_TINY)
/* clang-format on */

#define KREF_PK1_(k, b) KFN(pk1_##k##_##b),
#define KREF_PK_(k, b) KFN(pk_##k##_##b),
#define KREF_ST_(k, b) KFN(st_##k##_##b),
#define KREF_PO1_(k, b) KFN(pk1_##k##_o##b),
#define KREF_PO_(k, b) KFN(pk_##k##_o##b),
#define KREF_SO_(k, b) KFN(st_##k##_o##b),
    /* The packet tables for one vector (isect1, occ1) and for several (isect, occ); an
 * ISA's entry points take the ones their widths need, the compiler drops the rest. */
    enum {
        KFN(vw) = VW
    };
CYLRAY_MAYBE_UNUSED static const KFN(packet_fn) KFN(isect1_table)[] = {KALL8_(KREF_PK1_)};
CYLRAY_MAYBE_UNUSED static const KFN(packet_fn) KFN(isect_table)[] = {KALL8_(KREF_PK_)};
CYLRAY_MAYBE_UNUSED static const KFN(stream_fn) KFN(isect_stream_table)[] = {KALL8_(KREF_ST_)};
CYLRAY_MAYBE_UNUSED static const KFN(packet_fn) KFN(occ1_table)[] = {KALL4_(KREF_PO1_)};
CYLRAY_MAYBE_UNUSED static const KFN(packet_fn) KFN(occ_table)[] = {KALL4_(KREF_PO_)};
CYLRAY_MAYBE_UNUSED static const KFN(stream_fn) KFN(occ_stream_table)[] = {KALL4_(KREF_SO_)};
CYLRAY_MAYBE_UNUSED static const KFN(leaf_fn) KFN(leaf_table)[] = {
    KFN(lf_0), KFN(lf_1), KFN(lf_2), KFN(lf_3), KFN(lf_4), KFN(lf_5), KFN(lf_6), KFN(lf_7)};
CYLRAY_MAYBE_UNUSED static const KFN(leaf_fn)
    KFN(leaf_occ_table)[] = {KFN(lo_0), KFN(lo_1), KFN(lo_2), KFN(lo_3)};
/* The same for a leaf of spheres. */
CYLRAY_MAYBE_UNUSED static const KFN(leaf_fn) KFN(leaf_sphere_table)[] = {
    KFN(sf_0), KFN(sf_1), KFN(sf_2), KFN(sf_3), KFN(sf_4), KFN(sf_5), KFN(sf_6), KFN(sf_7)};
CYLRAY_MAYBE_UNUSED static const KFN(leaf_fn)
    KFN(leaf_sphere_occ_table)[] = {KFN(so_0), KFN(so_1), KFN(so_2), KFN(so_3)};
/* And for a leaf of cones. */
CYLRAY_MAYBE_UNUSED static const KFN(leaf_fn) KFN(leaf_cone_table)[] = {
    KFN(cf_0), KFN(cf_1), KFN(cf_2), KFN(cf_3), KFN(cf_4), KFN(cf_5), KFN(cf_6), KFN(cf_7)};
CYLRAY_MAYBE_UNUSED static const KFN(leaf_fn)
    KFN(leaf_cone_occ_table)[] = {KFN(co_0), KFN(co_1), KFN(co_2), KFN(co_3)};
/* And for a leaf that holds a tiny-ended cone. */
CYLRAY_MAYBE_UNUSED static const KFN(leaf_fn) KFN(leaf_tiny_table)[] = {
    KFN(tf_0), KFN(tf_1), KFN(tf_2), KFN(tf_3), KFN(tf_4), KFN(tf_5), KFN(tf_6), KFN(tf_7)};
CYLRAY_MAYBE_UNUSED static const KFN(leaf_fn)
    KFN(leaf_tiny_occ_table)[] = {KFN(to_0), KFN(to_1), KFN(to_2), KFN(to_3)};
/* And for a leaf that holds a slender shape: of cylinders, and of cones. */
CYLRAY_MAYBE_UNUSED static const KFN(leaf_fn) KFN(leaf_slender_table)[] = {
    KFN(yf_0), KFN(yf_1), KFN(yf_2), KFN(yf_3), KFN(yf_4), KFN(yf_5), KFN(yf_6), KFN(yf_7)};
CYLRAY_MAYBE_UNUSED static const KFN(leaf_fn)
    KFN(leaf_slender_occ_table)[] = {KFN(yo_0), KFN(yo_1), KFN(yo_2), KFN(yo_3)};
CYLRAY_MAYBE_UNUSED static const KFN(leaf_fn) KFN(leaf_cone_slender_table)[] = {
    KFN(kf_0), KFN(kf_1), KFN(kf_2), KFN(kf_3), KFN(kf_4), KFN(kf_5), KFN(kf_6), KFN(kf_7)};
CYLRAY_MAYBE_UNUSED static const KFN(leaf_fn)
    KFN(leaf_cone_slender_occ_table)[] = {KFN(ko_0), KFN(ko_1), KFN(ko_2), KFN(ko_3)};
/* Every table holds exactly what its index reaches (cylray_isect_index_,
 * cylray_occ_index_, cylray_spec_, cylray_occ_spec_): one entry per specialised variant
 * and flag encoding. */
#define KTABLE_SIZE_(t, n) _Static_assert(sizeof KFN(t) / sizeof KFN(t)[0] == (n), #t " size")
KTABLE_SIZE_(isect1_table, CYLRAY_VARIANT_GENERIC *CYLRAY_SPECS);
KTABLE_SIZE_(isect_table, CYLRAY_VARIANT_GENERIC *CYLRAY_SPECS);
KTABLE_SIZE_(isect_stream_table, CYLRAY_VARIANT_GENERIC *CYLRAY_SPECS);
KTABLE_SIZE_(occ1_table, CYLRAY_VARIANT_GENERIC *CYLRAY_OCC_SPECS);
KTABLE_SIZE_(occ_table, CYLRAY_VARIANT_GENERIC *CYLRAY_OCC_SPECS);
KTABLE_SIZE_(occ_stream_table, CYLRAY_VARIANT_GENERIC *CYLRAY_OCC_SPECS);
KTABLE_SIZE_(leaf_table, CYLRAY_SPECS);
KTABLE_SIZE_(leaf_occ_table, CYLRAY_OCC_SPECS);
KTABLE_SIZE_(leaf_sphere_table, CYLRAY_SPECS);
KTABLE_SIZE_(leaf_sphere_occ_table, CYLRAY_OCC_SPECS);
KTABLE_SIZE_(leaf_cone_table, CYLRAY_SPECS);
KTABLE_SIZE_(leaf_cone_occ_table, CYLRAY_OCC_SPECS);
KTABLE_SIZE_(leaf_tiny_table, CYLRAY_SPECS);
KTABLE_SIZE_(leaf_tiny_occ_table, CYLRAY_OCC_SPECS);
KTABLE_SIZE_(leaf_slender_table, CYLRAY_SPECS);
KTABLE_SIZE_(leaf_slender_occ_table, CYLRAY_OCC_SPECS);
KTABLE_SIZE_(leaf_cone_slender_table, CYLRAY_SPECS);
KTABLE_SIZE_(leaf_cone_slender_occ_table, CYLRAY_OCC_SPECS);

#undef KDOT
#undef KRCP
#undef KSUMSQ_CHAINED
#undef KFL_
#undef KLFL_
#undef KSPEC_
#undef KPACKET_SEVERAL_
#undef KSLOT_
#undef KISECT_
#undef KOCC_
#undef KLEAF_
#undef KLEAFOCC_
#undef KLEAFANY_
#undef KLEAFOCCANY_
#undef KLEAFDRV_
#undef KANY_
#undef KISECTANY_
#undef KOCCANY_
#undef KKIND_
#undef KCONE_
#undef KLEAFCONE_
#undef KALIAS_
#undef KLEAFALIAS_
#undef K8_
#undef K4_
#undef KALL8_
#undef KALL4_
#undef KREF_PK1_
#undef KREF_PK_
#undef KREF_ST_
#undef KREF_PO1_
#undef KREF_PO_
#undef KREF_SO_
#undef KTABLE_SIZE_
