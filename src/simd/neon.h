/* SPDX-License-Identifier: MIT */
/* simd/neon.h - the kernel's vector vocabulary on AArch64 NEON (4 lanes).
 * Semantics as stated in simd/scalar.h; min/max are built from a compare so that NaN
 * lanes give the second operand, as on x86. */
#include <arm_neon.h>
#include <stdint.h>

#define VW 4
#define VFULL 0xfu
#define vf float32x4_t
#define vm uint32x4_t

#define vset1(x) vdupq_n_f32(x)
#define vzero() vdupq_n_f32(0.0f)
#define vloadu(p) vld1q_f32(p)
#define vadd(a, b) vaddq_f32(a, b)
#define vsub(a, b) vsubq_f32(a, b)
#define vmul(a, b) vmulq_f32(a, b)
#define vdiv(a, b) vdivq_f32(a, b)
#define vsqrt(a) vsqrtq_f32(a)
#define vmin(a, b) vbslq_f32(vcltq_f32(a, b), a, b)
#define vmax(a, b) vbslq_f32(vcgtq_f32(a, b), a, b)
#define vabs(a) vabsq_f32(a)
#define vneg(a) vnegq_f32(a)
#define vcopysign(mag, sgn) vbslq_f32(vdupq_n_u32(0x80000000u), sgn, mag)
#define vxorsign(a, b)                                                                         \
    vreinterpretq_f32_u32(                                                                     \
        veorq_u32(vreinterpretq_u32_f32(a),                                                    \
                  vandq_u32(vreinterpretq_u32_f32(b), vdupq_n_u32(0x80000000u))))

#define vexpsign(x)                                                                            \
    vreinterpretq_f32_u32(vandq_u32(vreinterpretq_u32_f32(x), vdupq_n_u32(0xff800000u)))

#define vfma(a, b, c) vfmaq_f32(c, a, b)
#define vfms(a, b, c) vnegq_f32(vfmsq_f32(c, a, b))
#define vfnma(a, b, c) vfmsq_f32(c, a, b)
#define vfma_x(a, b, c) vfmaq_f32(c, a, b)
#define vfma_x2(a, b, ch, cl) vaddq_f32(vfmaq_f32(ch, a, b), cl)
#define vfma_xw(a, b, o, c, ch, cl) vfma_x2(a, b, ch, cl)
#define vsumsq_x(a, b, c, k) vsubq_f32(vfmaq_f32(vfmaq_f32(vmulq_f32(c, c), b, b), a, a), k)
static inline vf KFN(dop_x)(vf a, vf b, vf c, vf d)
{
    vf cd = vmulq_f32(c, d);
    vf err = vfms(c, d, cd);
    return vsubq_f32(vfms(a, b, cd), err);
}
#define vdop_x(a, b, c, d) KFN(dop_x)(a, b, c, d)
/* The estimates give 8 bits; two Newton steps give about 23. */
#define vrcp_est_(x) vrecpeq_f32(x)
#define vrsqrt_est_(x) vrsqrteq_f32(x)
/* The test builds' stand-ins for the estimates (simd/estimate.h): 8 bits. */
#define VEST_ERR 0x1p-8f
#define vest_cut_(x)                                                                           \
    vreinterpretq_f32_u32(vandq_u32(vreinterpretq_u32_f32(x), vdupq_n_u32(0xffff8000u)))
#include "estimate.h"
static inline vf KFN(rcp_fast)(vf x)
{
    vf r = vrcp_est_(x);
    r = vmulq_f32(r, vrecpsq_f32(x, r));
    return vmulq_f32(r, vrecpsq_f32(x, r));
}
static inline vf KFN(rsqrt_fast)(vf x)
{
    vf r = vrsqrt_est_(x);
    r = vmulq_f32(r, vrsqrtsq_f32(vmulq_f32(x, r), r));
    return vmulq_f32(r, vrsqrtsq_f32(vmulq_f32(x, r), r));
}
#define vrcp_fast(x) KFN(rcp_fast)(x)
#define vrsqrt_fast(x) KFN(rsqrt_fast)(x)

#define vlt(a, b) vcltq_f32(a, b)
#define vle(a, b) vcleq_f32(a, b)
#define vgt(a, b) vcgtq_f32(a, b)
#define vge(a, b) vcgeq_f32(a, b)
#define veq(a, b) vceqq_f32(a, b)
#define mand(a, b) vandq_u32(a, b)
#define mor(a, b) vorrq_u32(a, b)
#define mandn(a, b) vbicq_u32(a, b)
#define many(m) (vmaxvq_u32(m) != 0)
static inline uint32_t KFN(mbits)(vm m)
{
    static const uint32_t bits[4] = {1, 2, 4, 8};
    return vaddvq_u32(vandq_u32(m, vld1q_u32(bits)));
}
static inline vm KFN(mfrom_bits)(uint32_t b)
{
    static const uint32_t bits[4] = {1, 2, 4, 8};
    return vtstq_u32(vdupq_n_u32(b), vld1q_u32(bits));
}
#define mbits(m) KFN(mbits)(m)
#define mfrom_bits(b) KFN(mfrom_bits)(b)
#define vsel(m, a, b) vbslq_f32(m, a, b)
#define vkeep(m, a) vreinterpretq_f32_u32(vandq_u32(m, vreinterpretq_u32_f32(a)))
#define mxor(a, b) veorq_u32(a, b)
static inline void KFN(store_m)(float *p, vm m, vf x)
{
    uint32_t b = mbits(m);
    if (b == 0xfu) {
        vst1q_f32(p, x);
    } else {
        if (b & 1u)
            vst1q_lane_f32(p + 0, x, 0);
        if (b & 2u)
            vst1q_lane_f32(p + 1, x, 1);
        if (b & 4u)
            vst1q_lane_f32(p + 2, x, 2);
        if (b & 8u)
            vst1q_lane_f32(p + 3, x, 3);
    }
}
static inline void KFN(store_part_m)(int32_t *p, vm m, vf x)
{
    uint32_t b = mbits(m);
    int32x4_t xi = vcvtq_s32_f32(x);
    if (b == 0xfu) {
        vst1q_s32(p, xi);
    } else {
        if (b & 1u)
            vst1q_lane_s32(p + 0, xi, 0);
        if (b & 2u)
            vst1q_lane_s32(p + 1, xi, 1);
        if (b & 4u)
            vst1q_lane_s32(p + 2, xi, 2);
        if (b & 8u)
            vst1q_lane_s32(p + 3, xi, 3);
    }
}
#define vstore_m(p, m, x) KFN(store_m)(p, m, x)
#define vstoreu(p, x) vst1q_f32(p, x)
#define vstoreu_part(p, x) vst1q_s32(p, vcvtq_s32_f32(x))
#define vstore_part_m(p, m, x) KFN(store_part_m)(p, m, x)
