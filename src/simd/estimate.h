/* SPDX-License-Identifier: MIT */
/* simd/estimate.h - test builds only: other valid reciprocal and reciprocal-square-root
 * estimates in place of the hardware's, for CYLRAY_FAST (the only kernels that take
 * one). The tables behind rcpps and rsqrtps differ between vendors; a test build
 * (meson -Destimate=...) puts in what another CPU may give, so that a run on one CPU
 * checks FAST's error bound for all:
 *   1 exact: the correctly rounded value;
 *   2 high, 3 low: that value moved by the documented error (VEST_ERR) up or down;
 *   4 table: that value with its significand cut to the estimate's bits (VEST_MASK),
 *     an error of one sign, as a table indexed by the leading bits gives;
 *   5 run time: the hardware's or one of 1-4, as the environment says
 *     (CYLRAY_TEST_ESTIMATE, api/estimate_mode.c), so that one build checks them all.
 * Included by a vocabulary after its vrcp_est_ and vrsqrt_est_, with VEST_ERR and
 * vest_cut_(x) defined. */
#if defined(CYLRAY_ESTIMATE) && CYLRAY_ESTIMATE
#if CYLRAY_ESTIMATE == 5
unsigned cylray_estimate_mode_(void);
static inline vf KFN(est_rcp_hw)(vf x)
{
    return vrcp_est_(x);
}
static inline vf KFN(est_rsqrt_hw)(vf x)
{
    return vrsqrt_est_(x);
}
#endif
#undef vrcp_est_
#undef vrsqrt_est_
static inline vf KFN(est_move)(vf r, unsigned mode)
{
    (void)mode;
#if CYLRAY_ESTIMATE == 5
    if (mode == 2)
        return vmul(r, vset1(1.0f + VEST_ERR));
    if (mode == 3)
        return vmul(r, vset1(1.0f - VEST_ERR));
    if (mode == 4)
        return vest_cut_(r);
    return r;
#elif CYLRAY_ESTIMATE == 1
    return r;
#elif CYLRAY_ESTIMATE == 2
    return vmul(r, vset1(1.0f + VEST_ERR));
#elif CYLRAY_ESTIMATE == 3
    return vmul(r, vset1(1.0f - VEST_ERR));
#elif CYLRAY_ESTIMATE == 4
    return vest_cut_(r);
#else
#error "CYLRAY_ESTIMATE: 1 exact, 2 high, 3 low, 4 table, 5 chosen at run time"
#endif
}
#if CYLRAY_ESTIMATE == 5
static inline vf KFN(est_rcp)(vf x)
{
    const unsigned mode = cylray_estimate_mode_();
    return mode ? KFN(est_move)(vdiv(vset1(1.0f), x), mode) : KFN(est_rcp_hw)(x);
}
static inline vf KFN(est_rsqrt)(vf x)
{
    const unsigned mode = cylray_estimate_mode_();
    return mode ? KFN(est_move)(vdiv(vset1(1.0f), vsqrt(x)), mode) : KFN(est_rsqrt_hw)(x);
}
#define vrcp_est_(x) KFN(est_rcp)(x)
#define vrsqrt_est_(x) KFN(est_rsqrt)(x)
#else
#define vrcp_est_(x) KFN(est_move)(vdiv(vset1(1.0f), (x)), 0u)
#define vrsqrt_est_(x) KFN(est_move)(vdiv(vset1(1.0f), vsqrt(x)), 0u)
#endif
#endif
