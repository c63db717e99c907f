/* SPDX-License-Identifier: MIT */
/* simd/f64_x86.h - the secondary-ray code's vocabulary of double vectors on x86 (meanings
 * in simd/f64_scalar.h). DW = 2 (SSE4.1, or SSE2 alone: the scalar path on x86-64; xmm),
 * 4 (AVX2, ymm; also under AVX-512 with vector masks) or 8 (AVX-512 zmm, mask
 * registers). */
#include <immintrin.h>
#include <stdint.h>

#if DW == 2
#define vd __m128d
#define vdm __m128d
#define DX(n) _mm_##n
#define dloadu_f(p)                                                                            \
    _mm_cvtps_pd(_mm_castsi128_ps(_mm_loadl_epi64((const __m128i *)(const void *)(p))))
#define dstoreu_f(p, x)                                                                        \
    _mm_storel_epi64((__m128i *)(void *)(p), _mm_castps_si128(_mm_cvtpd_ps(x)))
#define dround_f(x) _mm_cvtps_pd(_mm_cvtpd_ps(x))
#define dload_bits(p, m)                                                                       \
    _mm_cvtepi32_pd(                                                                           \
        _mm_and_si128(_mm_loadl_epi64((const __m128i *)(const void *)(p)), _mm_set1_epi32(m)))
#define dlt(a, b) _mm_cmplt_pd(a, b)
#define dle(a, b) _mm_cmple_pd(a, b)
#define dgt(a, b) _mm_cmpgt_pd(a, b)
#define deq(a, b) _mm_cmpeq_pd(a, b)
#define dones_() _mm_castsi128_pd(_mm_set1_epi32(-1))
#elif DW == 4
#define vd __m256d
#define vdm __m256d
#define DX(n) _mm256_##n
#define dloadu_f(p) _mm256_cvtps_pd(_mm_loadu_ps(p))
#define dstoreu_f(p, x) _mm_storeu_ps(p, _mm256_cvtpd_ps(x))
#define dround_f(x) _mm256_cvtps_pd(_mm256_cvtpd_ps(x))
#define dload_bits(p, m)                                                                       \
    _mm256_cvtepi32_pd(                                                                        \
        _mm_and_si128(_mm_loadu_si128((const __m128i *)(const void *)(p)), _mm_set1_epi32(m)))
#define dlt(a, b) _mm256_cmp_pd(a, b, _CMP_LT_OQ)
#define dle(a, b) _mm256_cmp_pd(a, b, _CMP_LE_OQ)
#define dgt(a, b) _mm256_cmp_pd(a, b, _CMP_GT_OQ)
#define deq(a, b) _mm256_cmp_pd(a, b, _CMP_EQ_OQ)
#define dones_() _mm256_castsi256_pd(_mm256_set1_epi32(-1))
#elif DW == 8
#define vd __m512d
#define vdm __mmask8
#define DX(n) _mm512_##n
#define dloadu_f(p) _mm512_cvtps_pd(_mm256_loadu_ps(p))
#define dstoreu_f(p, x) _mm256_storeu_ps(p, _mm512_cvtpd_ps(x))
#define dround_f(x) _mm512_cvtps_pd(_mm512_cvtpd_ps(x))
#define dload_bits(p, m)                                                                       \
    _mm512_cvtepi32_pd(_mm256_and_si256(                                                       \
        _mm256_loadu_si256((const __m256i *)(const void *)(p)), _mm256_set1_epi32(m)))
#define dlt(a, b) _mm512_cmp_pd_mask(a, b, _CMP_LT_OQ)
#define dle(a, b) _mm512_cmp_pd_mask(a, b, _CMP_LE_OQ)
#define dgt(a, b) _mm512_cmp_pd_mask(a, b, _CMP_GT_OQ)
#define deq(a, b) _mm512_cmp_pd_mask(a, b, _CMP_EQ_OQ)
#else
#error "simd/f64_x86.h: DW must be 2, 4 or 8"
#endif

#define DFULL ((uint32_t)((1u << DW) - 1u))
#define dset1(x) DX(set1_pd)(x)
#define dadd(a, b) DX(add_pd)(a, b)
#define dsub(a, b) DX(sub_pd)(a, b)
#define dmul(a, b) DX(mul_pd)(a, b)
#define ddiv(a, b) DX(div_pd)(a, b)
#define dsqrt(a) DX(sqrt_pd)(a)
#define dabs(a) DX(andnot_pd)(DX(set1_pd)(-0.0), a)
#define dmax(a, b) DX(max_pd)(a, b)
#define dmin(a, b) DX(min_pd)(a, b)
/* INFINITY's bits are the exponent field's */
#define dexpo(x) DX(and_pd)(x, DX(set1_pd)(INFINITY))
#if DW == 8
#define dmand(a, b) ((vdm)((a) & (b)))
#define dmor(a, b) ((vdm)((a) | (b)))
#define dmandn(a, b) ((vdm)((a) & ~(b)))
#define dmnot(a) ((vdm)(~(a)))
#define dmbits(m) ((uint32_t)(m))
#define dsel(m, a, b) _mm512_mask_blend_pd(m, b, a)
#else
#define dmand(a, b) DX(and_pd)(a, b)
#define dmor(a, b) DX(or_pd)(a, b)
#define dmandn(a, b) DX(andnot_pd)(b, a)
#define dmnot(a) DX(xor_pd)(a, dones_())
#define dmbits(m) ((uint32_t)DX(movemask_pd)(m))
#if DW == 2 && !defined(__SSE4_1__)
/* SSE2 alone (the scalar path's two lanes on x86-64): no blendv */
#define dsel(m, a, b) _mm_or_pd(_mm_and_pd(m, a), _mm_andnot_pd(m, b))
#else
#define dsel(m, a, b) DX(blendv_pd)(b, a, m)
#endif
#endif
