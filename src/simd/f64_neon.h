/* SPDX-License-Identifier: MIT */
/* simd/f64_neon.h - the secondary-ray code's vocabulary of double vectors on AArch64 NEON,
 * two lanes (meanings in simd/f64_scalar.h; max and min from a compare, so that NaN gives
 * the second operand as on x86). */
#include <arm_neon.h>
#include <stdint.h>

#define DW 2
#define DFULL 3u
#define vd float64x2_t
#define vdm uint64x2_t

#define dset1(x) vdupq_n_f64(x)
#define dadd(a, b) vaddq_f64(a, b)
#define dsub(a, b) vsubq_f64(a, b)
#define dmul(a, b) vmulq_f64(a, b)
#define ddiv(a, b) vdivq_f64(a, b)
#define dsqrt(a) vsqrtq_f64(a)
#define dabs(a) vabsq_f64(a)
#define dmax(a, b) vbslq_f64(vcgtq_f64(a, b), a, b)
#define dmin(a, b) vbslq_f64(vcltq_f64(a, b), a, b)
#define dlt(a, b) vcltq_f64(a, b)
#define dle(a, b) vcleq_f64(a, b)
#define dgt(a, b) vcgtq_f64(a, b)
#define deq(a, b) vceqq_f64(a, b)
#define dmand(a, b) vandq_u64(a, b)
#define dmor(a, b) vorrq_u64(a, b)
#define dmandn(a, b) vbicq_u64(a, b)
#define dmnot(a) veorq_u64(a, vdupq_n_u64(~0ull))
#define dmbits(m)                                                                              \
    ((uint32_t)(vgetq_lane_u64(m, 0) & 1u) | (uint32_t)(vgetq_lane_u64(m, 1) & 2u))
#define dsel(m, a, b) vbslq_f64(m, a, b)
#define dround_f(x) vcvt_f64_f32(vcvt_f32_f64(x))
#define dexpo(x)                                                                               \
    vreinterpretq_f64_u64(                                                                     \
        vandq_u64(vreinterpretq_u64_f64(x), vdupq_n_u64(0x7ff0000000000000ull)))
#define dloadu_f(p) vcvt_f64_f32(vld1_f32(p))
#define dstoreu_f(p, x) vst1_f32(p, vcvt_f32_f64(x))
#define dload_bits(p, m) vcvtq_f64_s64(vmovl_s32(vand_s32(vld1_s32(p), vdup_n_s32(m))))
