/* SPDX-License-Identifier: MIT */
/* simd/x86.h - the kernel's vector vocabulary on x86: SSE4.1, AVX2+FMA and AVX-512.
 *
 * Included once per vector width by an ISA's translation unit, with:
 *   VW         lanes per vector: 4 (xmm), 8 (ymm) or 16 (zmm)
 *   X86_FMA    1 when the FMA3 instructions may be used
 *   X86_KMASK  1 for AVX-512: lane masks live in mask registers (needs VL below 16)
 * simd/undef.h takes every name back, so the next width can define them again.
 * X86_AVX, whether the unit is compiled for AVX (its compares with a predicate and its
 * masked stores), follows the compiler's flags: FMA3 and AVX are separate extensions.
 * The stores of the hit lanes are simd/x86_stores.h, included after this one.
 *
 * Every operation has one meaning on every ISA (see simd/scalar.h for the plain
 * statement of each); in particular vmin/vmax return the second operand when either
 * is NaN, as minps/maxps do, so that NaN lanes behave the same everywhere. */
#include <immintrin.h>
#include <stdint.h>

#ifndef X86_AVX
#ifdef __AVX__
#define X86_AVX 1
#else
#define X86_AVX 0
#endif
#endif

#if VW == 4
#define vf __m128
#define VX(n) _mm_##n
#define VXI(n) _mm_##n##_si128
#define vi_ __m128i
#define VCASTI(x) _mm_castps_si128(x)
#define VCASTF(x) _mm_castsi128_ps(x)
#elif VW == 8
#define vf __m256
#define VX(n) _mm256_##n
#define VXI(n) _mm256_##n##_si256
#define vi_ __m256i
#define VCASTI(x) _mm256_castps_si256(x)
#define VCASTF(x) _mm256_castsi256_ps(x)
#elif VW == 16
#define vf __m512
#define VX(n) _mm512_##n
#define VXI(n) _mm512_##n##_si512
#define vi_ __m512i
#define VCASTI(x) _mm512_castps_si512(x)
#define VCASTF(x) _mm512_castsi512_ps(x)
#else
#error "simd/x86.h: VW must be 4, 8 or 16"
#endif

#define VFULL ((uint32_t)((1u << VW) - 1u))

#define vset1(x) VX(set1_ps)(x)
#define vzero() VX(setzero_ps)()
#define vloadu(p) VX(loadu_ps)(p)
#define vadd(a, b) VX(add_ps)(a, b)
#define vsub(a, b) VX(sub_ps)(a, b)
#define vmul(a, b) VX(mul_ps)(a, b)
#define vdiv(a, b) VX(div_ps)(a, b)
#define vsqrt(a) VX(sqrt_ps)(a)
#define vmin(a, b) VX(min_ps)(a, b)
#define vmax(a, b) VX(max_ps)(a, b)
#define vsignbit_() VX(set1_ps)(-0.0f)
#define vabs(a) VX(andnot_ps)(vsignbit_(), a)
#define vneg(a) VX(xor_ps)(a, vsignbit_())
#define vcopysign(mag, sgn)                                                                    \
    VX(or_ps)(VX(andnot_ps)(vsignbit_(), mag), VX(and_ps)(vsignbit_(), sgn))
#define vxorsign(a, b) VX(xor_ps)(a, VX(and_ps)(b, vsignbit_()))
#define vexpsign(x) VX(and_ps)(x, VCASTF(VX(set1_epi32)((int)0xff800000u)))

#if X86_FMA
#define vfma(a, b, c) VX(fmadd_ps)(a, b, c)
#define vfms(a, b, c) VX(fmsub_ps)(a, b, c)
#define vfnma(a, b, c) VX(fnmadd_ps)(a, b, c)
#define vfma_x(a, b, c) VX(fmadd_ps)(a, b, c)
#define vfma_x2(a, b, ch, cl) vadd(VX(fmadd_ps)(a, b, ch), cl)
#define vfma_xw(a, b, o, c, ch, cl) vfma_x2(a, b, ch, cl)
#define vsumsq_x(a, b, c, k) vsub(VX(fmadd_ps)(a, a, VX(fmadd_ps)(b, b, vmul(c, c))), k)
/* Kahan's a*b - c*d: the rounding error of c*d is recovered exactly by an FMA. */
static inline vf KFN(dop_x)(vf a, vf b, vf c, vf d)
{
    vf cd = vmul(c, d);
    vf err = VX(fmsub_ps)(c, d, cd);
    return vsub(VX(fmsub_ps)(a, b, cd), err);
}
#define vdop_x(a, b, c, d) KFN(dop_x)(a, b, c, d)
#else
/* No FMA: the products whose rounding matters (the origin shift, the cross products,
 * the discriminant, C) are formed in double, where a product of two floats is exact. */
#define vfma(a, b, c) vadd(vmul(a, b), c)
#define vfms(a, b, c) vsub(vmul(a, b), c)
#define vfnma(a, b, c) vsub(c, vmul(a, b))
/* Each is one expression E(H) in the double lanes H(x) of its operands, evaluated for
 * lanes 0-1 and 2-3 and rounded to float once. */
#define VLO_(x) _mm_cvtps_pd(x)
/* The high lanes by a generic shuffle rather than movhlps's builtin: the compiler then
 * sees that those of a broadcast (the axis, R^2) are its low lanes, converts it once
 * and keeps one double vector of it instead of two. */
#define VHI_(x) _mm_cvtps_pd(__builtin_shufflevector(x, x, 2, 3, 2, 3))
#define VIN_DOUBLE_(E) _mm_movelh_ps(_mm_cvtpd_ps(E(VLO_)), _mm_cvtpd_ps(E(VHI_)))
static inline __m128 KFN(fma_x)(__m128 a, __m128 b, __m128 c)
{
#define E_(H) _mm_add_pd(_mm_mul_pd(H(a), H(b)), H(c))
    return VIN_DOUBLE_(E_);
#undef E_
}
/* a*b + (ch + cl): the two-term sum and the product are exact in double. */
static inline __m128 KFN(fma_x2)(__m128 a, __m128 b, __m128 ch, __m128 cl)
{
#define E_(H) _mm_add_pd(_mm_mul_pd(H(a), H(b)), _mm_add_pd(H(ch), H(cl)))
    return VIN_DOUBLE_(E_);
#undef E_
}
/* a*b + (o - c), where ch + cl = o - c exactly (a two-sum of floats that did not
 * overflow): fma_x2's value, since ch + cl and o - c round to the same double. From o
 * and c the two-sum's low part need not be formed, and a broadcast c converts once. */
static inline __m128 KFN(fma_xw)(__m128 a, __m128 b, __m128 o, __m128 c)
{
#define E_(H) _mm_add_pd(_mm_mul_pd(H(a), H(b)), _mm_sub_pd(H(o), H(c)))
    return VIN_DOUBLE_(E_);
#undef E_
}
/* |(a, b, c)|^2 - k: C, where the shifted origin lies near the surface, is a
 * difference of two near numbers that only an exact sum of squares keeps. */
static inline __m128 KFN(sumsq_x)(__m128 a, __m128 b, __m128 c, __m128 k)
{
#define E_(H)                                                                                  \
    _mm_sub_pd(_mm_add_pd(_mm_add_pd(_mm_mul_pd(H(a), H(a)), _mm_mul_pd(H(b), H(b))),          \
                          _mm_mul_pd(H(c), H(c))),                                             \
               H(k))
    return VIN_DOUBLE_(E_);
#undef E_
}
static inline __m128 KFN(dop_x)(__m128 a, __m128 b, __m128 c, __m128 d)
{
#define E_(H) _mm_sub_pd(_mm_mul_pd(H(a), H(b)), _mm_mul_pd(H(c), H(d)))
    return VIN_DOUBLE_(E_);
#undef E_
}
/* in double, whose rounding of the sum (2^-52 of the terms) is far below what the
 * callers need */
static inline __m128 KFN(dot3_x)(__m128 ax, __m128 ay, __m128 az, __m128 bx, __m128 by,
                                 __m128 bz, __m128 c)
{
#define E_(H)                                                                                  \
    _mm_add_pd(_mm_add_pd(_mm_add_pd(_mm_mul_pd(H(ax), H(bx)), _mm_mul_pd(H(ay), H(by))),      \
                          _mm_mul_pd(H(az), H(bz))),                                           \
               H(c))
    return VIN_DOUBLE_(E_);
#undef E_
}
#undef VLO_
#undef VHI_
#undef VIN_DOUBLE_
#define vfma_x(a, b, c) KFN(fma_x)(a, b, c)
#define vfma_x2(a, b, ch, cl) KFN(fma_x2)(a, b, ch, cl)
#define vfma_xw(a, b, o, c, ch, cl) KFN(fma_xw)(a, b, o, c)
#define vsumsq_x(a, b, c, k) KFN(sumsq_x)(a, b, c, k)
#define vdop_x(a, b, c, d) KFN(dop_x)(a, b, c, d)
#define vdot3_x(ax, ay, az, bx, by, bz, c) KFN(dot3_x)(ax, ay, az, bx, by, bz, c)
#endif

/* Reciprocal and reciprocal square root for CYLRAY_FAST: the hardware estimate and
 * one Newton step (rcp14 gives 14 bits, rcpps 12; one step brings either to ~23). */
#if X86_KMASK
#define vrcp_est_(x) VX(rcp14_ps)(x)
#define vrsqrt_est_(x) VX(rsqrt14_ps)(x)
#else
#define vrcp_est_(x) VX(rcp_ps)(x)
#define vrsqrt_est_(x) VX(rsqrt_ps)(x)
#endif
/* The documented error of the estimates (rcp14: 2^-14; rcpps: 1.5 x 2^-12), and their
 * bits, for the test builds' stand-ins (simd/estimate.h). */
#if X86_KMASK
#define VEST_ERR 0x1p-14f
#define VEST_BITS_ 0xffffffe0u
#else
#define VEST_ERR 0x1.8p-12f
#define VEST_BITS_ 0xfffff800u
#endif
#define vest_cut_(x) VX(and_ps)(x, VCASTF(VX(set1_epi32)((int)VEST_BITS_)))
#include "estimate.h"
static inline vf KFN(rcp_fast)(vf x)
{
    vf r = vrcp_est_(x);
#if !X86_KMASK
    r = vfma(r, vfnma(x, r, vset1(1.0f)), r);
#endif
    return vfma(r, vfnma(x, r, vset1(1.0f)), r);
}
static inline vf KFN(rsqrt_fast)(vf x)
{
    vf r = vrsqrt_est_(x);
    vf hx = vmul(x, vset1(0.5f));
#if !X86_KMASK
    r = vmul(r, vfnma(hx, vmul(r, r), vset1(1.5f)));
#endif
    return vmul(r, vfnma(hx, vmul(r, r), vset1(1.5f)));
}
#define vrcp_fast(x) KFN(rcp_fast)(x)
#define vrsqrt_fast(x) KFN(rsqrt_fast)(x)

/* ---- lane masks ---- */
#if X86_KMASK
#if VW == 16
#define vm __mmask16
#define vcmp_(a, b, p) _mm512_cmp_ps_mask(a, b, p)
#else
#define vm __mmask8
#define vcmp_(a, b, p) VX(cmp_ps_mask)(a, b, p)
#endif
#define vlt(a, b) vcmp_(a, b, _CMP_LT_OQ)
#define vle(a, b) vcmp_(a, b, _CMP_LE_OQ)
#define vgt(a, b) vcmp_(a, b, _CMP_GT_OQ)
#define vge(a, b) vcmp_(a, b, _CMP_GE_OQ)
#define veq(a, b) vcmp_(a, b, _CMP_EQ_OQ)
#define mand(a, b) ((vm)((a) & (b)))
#define mor(a, b) ((vm)((a) | (b)))
#define mandn(a, b) ((vm)((a) & ~(b)))
#define many(m) ((m) != 0)
#define mbits(m) ((uint32_t)(m))
#define mfrom_bits(b) ((vm)((b)&VFULL))
#define vsel(m, a, b) VX(mask_blend_ps)(m, b, a)
#define vkeep(m, a) VX(maskz_mov_ps)(m, a)
#define mxor(a, b) ((vm)((a) ^ (b)))
#else /* vector masks */
#define vm vf
#if X86_AVX /* one compare with a predicate */
#define vlt(a, b) VX(cmp_ps)(a, b, _CMP_LT_OQ)
#define vle(a, b) VX(cmp_ps)(a, b, _CMP_LE_OQ)
#define vgt(a, b) VX(cmp_ps)(a, b, _CMP_GT_OQ)
#define vge(a, b) VX(cmp_ps)(a, b, _CMP_GE_OQ)
#define veq(a, b) VX(cmp_ps)(a, b, _CMP_EQ_OQ)
#else
#define vlt(a, b) _mm_cmplt_ps(a, b)
#define vle(a, b) _mm_cmple_ps(a, b)
#define vgt(a, b) _mm_cmpgt_ps(a, b)
#define vge(a, b) _mm_cmpge_ps(a, b)
#define veq(a, b) _mm_cmpeq_ps(a, b)
#endif
#define mand(a, b) VX(and_ps)(a, b)
#define mor(a, b) VX(or_ps)(a, b)
#define mandn(a, b) VX(andnot_ps)(b, a)
#define mbits(m) ((uint32_t)VX(movemask_ps)(m))
#define many(m) (mbits(m) != 0)
#define vsel(m, a, b) VX(blendv_ps)(b, a, m)
#define vkeep(m, a) VX(and_ps)(m, a)
#define mxor(a, b) VX(xor_ps)(a, b)
#if VW == 4
#define vlanebits_() _mm_setr_epi32(1, 2, 4, 8)
#define vcmpeq_i_(a, b) _mm_cmpeq_epi32(a, b)
#else
#define vlanebits_() _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128)
#define vcmpeq_i_(a, b) _mm256_cmpeq_epi32(a, b)
#endif
#define mfrom_bits(b)                                                                          \
    VCASTF(vcmpeq_i_(VXI (and)(VX(set1_epi32)((int)(b)), vlanebits_()), vlanebits_()))
#endif
