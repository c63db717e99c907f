/* SPDX-License-Identifier: MIT */
/* kernel/tables.h - the specialisations stamped into the tables the entry points
 * index. */

/* The specialisations, where a tracer spends its time: the rows of CYLRAY_VARIANT_ROWS
 * (each specialised variant of a prepared shape) and of CYLRAY_LEAF_ROWS (each kind of
 * leaf), each with its intersect kernels (with and without normals, each plain, with
 * CYLRAY_FAST or with CYLRAY_REFINE) and its occluded ones likewise. Face-forward and
 * culling are read at run time in every kernel (a select each). The tables are indexed by
 * cylray_isect_index_ / cylray_occ_index_ (variants) and cylray_leaf_row_ with
 * cylray_spec_ / cylray_occ_spec_ (leaves), all decoded in internal/. */
#define KLFL_(kf) (CYLRAY_KF_KIND_(CYLRAY_KIND_LEAF) | (kf))
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

/* Which of a row's slots are specialised (S), served by the drivers that read their
 * flags at run time (A), or served by another slot's kernels (L): X(row, slot, the
 * slot's kernel flags, S/A/L, the slot it is served by). Slots 0-7 are the intersect
 * ones (cylray_spec_), o0-o3 the occluded ones (cylray_occ_spec_).
 *   FULL   every flag set but FAST with REFINE (6, 7; occluded 3), an odd pair (one
 *          trades accuracy away, the other buys it) that takes the run-time drivers:
 *          half the specialisations of every combination, in build time and size, for
 *          the same speed where it counts;
 *   THIRD  plain and normals; FAST takes those, REFINE the run-time drivers;
 *   ANY    the run-time drivers for all. */
#define KSI_(b, fl) ((fl) | CYLRAY_SPEC_KF_(b))
#define KSO_(b, fl) ((fl) | CYLRAY_OCC_SPEC_KF_(b))
/* clang-format off */
#define KSET_FULL_I_(X, k, fl) \
    X(k, 0, KSI_(0, fl), S, 0) X(k, 1, KSI_(1, fl), S, 1) \
    X(k, 2, KSI_(2, fl), S, 2) X(k, 3, KSI_(3, fl), S, 3) \
    X(k, 4, KSI_(4, fl), S, 4) X(k, 5, KSI_(5, fl), S, 5) \
    X(k, 6, KSI_(6, fl), A, 6) X(k, 7, KSI_(7, fl), A, 7)
#define KSET_FULL_O_(X, k, fl) \
    X(k, o0, KSO_(0, fl), S, o0) X(k, o1, KSO_(1, fl), S, o1) \
    X(k, o2, KSO_(2, fl), S, o2) X(k, o3, KSO_(3, fl), A, o3)
#define KSET_THIRD_I_(X, k, fl) \
    X(k, 0, KSI_(0, fl), S, 0) X(k, 1, KSI_(1, fl), S, 1) \
    X(k, 2, KSI_(2, fl), L, 0) X(k, 3, KSI_(3, fl), L, 1) \
    X(k, 4, KSI_(4, fl), A, 4) X(k, 5, KSI_(5, fl), A, 5) \
    X(k, 6, KSI_(6, fl), A, 6) X(k, 7, KSI_(7, fl), A, 7)
#define KSET_THIRD_O_(X, k, fl) \
    X(k, o0, KSO_(0, fl), S, o0) X(k, o1, KSO_(1, fl), L, o0) \
    X(k, o2, KSO_(2, fl), A, o2) X(k, o3, KSO_(3, fl), A, o3)
#define KSET_ANY_I_(X, k, fl) \
    X(k, 0, KSI_(0, fl), A, 0) X(k, 1, KSI_(1, fl), A, 1) \
    X(k, 2, KSI_(2, fl), A, 2) X(k, 3, KSI_(3, fl), A, 3) \
    X(k, 4, KSI_(4, fl), A, 4) X(k, 5, KSI_(5, fl), A, 5) \
    X(k, 6, KSI_(6, fl), A, 6) X(k, 7, KSI_(7, fl), A, 7)
#define KSET_ANY_O_(X, k, fl) \
    X(k, o0, KSO_(0, fl), A, o0) X(k, o1, KSO_(1, fl), A, o1) \
    X(k, o2, KSO_(2, fl), A, o2) X(k, o3, KSO_(3, fl), A, o3)
/* clang-format on */
#define KSET_(X, k, fl, set) KSET_##set##_I_(X, k, fl) KSET_##set##_O_(X, k, fl)

/* A variant's slot: its three drivers. */
#define KPK_(k, s, fl, how, t) KPK_##how(k, s, fl, t)
#define KPK_S(k, s, fl, t)                                                                     \
    KSLOT_(k, s, KFN(packet1)(P, R, H, a, rt, fl), KPACKET_SEVERAL_(k, s, fl, packet),         \
           KFN(stream)(P, R, H, o, n, rt, fl, KFN(pk1_##k##_##s)))
#define KPK_A(k, s, fl, t)                                                                     \
    KSLOT_(k, s, KFN(packet_any)(P, R, H, n, a, rt, fl),                                       \
           KPACKET_SEVERAL_(k, s, fl, packet_any), KFN(stream_any)(P, R, H, o, n, rt, fl))
#define KPK_L(k, s, fl, t)                                                                     \
    KSLOT_(k, s, KFN(pk1_##k##_##t)(P, R, H, n, a, rt),                                        \
           return KFN(pk_##k##_##t)(P, R, H, n, a, rt), KFN(st_##k##_##t)(P, R, H, o, n, rt))
/* A leaf row's slot: its driver. */
#define KLF_(k, s, fl, how, t) KLF_##how(k, s, fl, t)
#define KLFDRV_(k, s, body)                                                                    \
    static int KFN(lf_##k##_##s)(const float *L, size_t lm, cylray_ray1 *r, cylray_hit1 *h,    \
                                 unsigned rt)                                                  \
    {                                                                                          \
        return body;                                                                           \
    }
#define KLF_S(k, s, fl, t) KLFDRV_(k, s, KFN(leaf)(L, lm, r, h, rt, KLFL_(fl)))
#define KLF_A(k, s, fl, t) KLFDRV_(k, s, KFN(leaf_any)(L, lm, r, h, rt, KLFL_(fl)))
#define KLF_L(k, s, fl, t) KLFDRV_(k, s, KFN(lf_##k##_##t)(L, lm, r, h, rt))

#define KVARIANT_(k, kf, set) KSET_(KPK_, k, kf, set)
#define KLEAFROW_(k, kf, set) KSET_(KLF_, k, kf, set)
/* clang-format off */
CYLRAY_VARIANT_ROWS(KVARIANT_)
CYLRAY_LEAF_ROWS(KLEAFROW_)
/* clang-format on */

/* The tables: a variant's slots in a row of the packet tables for one vector (isect1,
 * occ1) and for several (isect, occ) and of the stream tables; a leaf row's in a row of
 * the leaf tables. An ISA's entry points take the ones their widths need, the compiler
 * drops the rest. */
enum { KFN(vw) = VW };
#define KREF_(p, k, s) KFN(p##_##k##_##s),
#define KREF_PK1_(k, s, fl, how, t) KREF_(pk1, k, s)
#define KREF_PK_(k, s, fl, how, t) KREF_(pk, k, s)
#define KREF_ST_(k, s, fl, how, t) KREF_(st, k, s)
#define KREF_LF_(k, s, fl, how, t) KREF_(lf, k, s)
#define KROW_PK1_I_(k, kf, set) KSET_##set##_I_(KREF_PK1_, k, kf)
#define KROW_PK_I_(k, kf, set) KSET_##set##_I_(KREF_PK_, k, kf)
#define KROW_ST_I_(k, kf, set) KSET_##set##_I_(KREF_ST_, k, kf)
#define KROW_PK1_O_(k, kf, set) KSET_##set##_O_(KREF_PK1_, k, kf)
#define KROW_PK_O_(k, kf, set) KSET_##set##_O_(KREF_PK_, k, kf)
#define KROW_ST_O_(k, kf, set) KSET_##set##_O_(KREF_ST_, k, kf)
#define KROW_LF_I_(k, kf, set) {KSET_##set##_I_(KREF_LF_, k, kf)},
#define KROW_LF_O_(k, kf, set) {KSET_##set##_O_(KREF_LF_, k, kf)},
/* clang-format off */
CYLRAY_MAYBE_UNUSED static const KFN(packet_fn) KFN(isect1_table)[] = {
    CYLRAY_VARIANT_ROWS(KROW_PK1_I_)};
CYLRAY_MAYBE_UNUSED static const KFN(packet_fn) KFN(isect_table)[] = {
    CYLRAY_VARIANT_ROWS(KROW_PK_I_)};
CYLRAY_MAYBE_UNUSED static const KFN(stream_fn) KFN(isect_stream_table)[] = {
    CYLRAY_VARIANT_ROWS(KROW_ST_I_)};
CYLRAY_MAYBE_UNUSED static const KFN(packet_fn) KFN(occ1_table)[] = {
    CYLRAY_VARIANT_ROWS(KROW_PK1_O_)};
CYLRAY_MAYBE_UNUSED static const KFN(packet_fn) KFN(occ_table)[] = {
    CYLRAY_VARIANT_ROWS(KROW_PK_O_)};
CYLRAY_MAYBE_UNUSED static const KFN(stream_fn) KFN(occ_stream_table)[] = {
    CYLRAY_VARIANT_ROWS(KROW_ST_O_)};
CYLRAY_MAYBE_UNUSED static const KFN(leaf_fn) KFN(leaf_table)[][CYLRAY_SPECS] = {
    CYLRAY_LEAF_ROWS(KROW_LF_I_)};
CYLRAY_MAYBE_UNUSED static const KFN(leaf_fn) KFN(leaf_occ_table)[][CYLRAY_OCC_SPECS] = {
    CYLRAY_LEAF_ROWS(KROW_LF_O_)};
/* clang-format on */
/* Every table holds exactly what its index reaches (cylray_isect_index_,
 * cylray_occ_index_, cylray_leaf_row_, cylray_spec_, cylray_occ_spec_): one entry per
 * specialised variant or leaf row and flag encoding. */
#define KTABLE_SIZE_(t, n) _Static_assert(sizeof KFN(t) / sizeof KFN(t)[0] == (n), #t " size")
KTABLE_SIZE_(isect1_table, CYLRAY_VARIANT_GENERIC *CYLRAY_SPECS);
KTABLE_SIZE_(isect_table, CYLRAY_VARIANT_GENERIC *CYLRAY_SPECS);
KTABLE_SIZE_(isect_stream_table, CYLRAY_VARIANT_GENERIC *CYLRAY_SPECS);
KTABLE_SIZE_(occ1_table, CYLRAY_VARIANT_GENERIC *CYLRAY_OCC_SPECS);
KTABLE_SIZE_(occ_table, CYLRAY_VARIANT_GENERIC *CYLRAY_OCC_SPECS);
KTABLE_SIZE_(occ_stream_table, CYLRAY_VARIANT_GENERIC *CYLRAY_OCC_SPECS);
KTABLE_SIZE_(leaf_table, CYLRAY_LEAF_ROW_COUNT);
KTABLE_SIZE_(leaf_occ_table, CYLRAY_LEAF_ROW_COUNT);

#undef KDOT
#undef KRCP
#undef KSUMSQ_CHAINED
#undef KLFL_
#undef KSLOT_
#undef KPACKET_SEVERAL_
#undef KSI_
#undef KSO_
#undef KSET_FULL_I_
#undef KSET_FULL_O_
#undef KSET_THIRD_I_
#undef KSET_THIRD_O_
#undef KSET_ANY_I_
#undef KSET_ANY_O_
#undef KSET_
#undef KPK_
#undef KPK_S
#undef KPK_A
#undef KPK_L
#undef KLF_
#undef KLFDRV_
#undef KLF_S
#undef KLF_A
#undef KLF_L
#undef KVARIANT_
#undef KLEAFROW_
#undef KREF_
#undef KREF_PK1_
#undef KREF_PK_
#undef KREF_ST_
#undef KREF_LF_
#undef KROW_PK1_I_
#undef KROW_PK_I_
#undef KROW_ST_I_
#undef KROW_PK1_O_
#undef KROW_PK_O_
#undef KROW_ST_O_
#undef KROW_LF_I_
#undef KROW_LF_O_
#undef KTABLE_SIZE_
