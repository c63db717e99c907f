/* SPDX-License-Identifier: MIT */
/* simd/scalar.h - the kernel's vector vocabulary for one lane: plain C.
 *
 * This is also the definition of every operation the SIMD headers implement:
 *   vfma(a,b,c) = a*b + c, vfms = a*b - c, vfnma = c - a*b; fused where the ISA can,
 *     used where one more rounding does not matter;
 *   vfma_x(a,b,c) = a*b + c with the product exact, vfma_x2(a,b,ch,cl) = a*b + ch + cl
 *     with the product exact (for c given as a two-term sum, |cl| <= ulp(ch)),
 *     vfma_xw(a,b,o,c,ch,cl) = vfma_x2(a,b,ch,cl) where ch + cl = o - c exactly (a
 *     two-sum): an ISA may form it from o and c instead,
 *   vsumsq_x(a,b,c,k) = a*a + b*b + c*c - k, with the sum of squares as an FMA chain
 *     forms it (in double, rounded once, where the ISA has no FMA), and
 *   vdop_x(a,b,c,d) = a*b - c*d within about one ulp: used where it matters;
 *   vdot3_x(ax,ay,az,bx,by,bz,c) = ax*bx + ay*by + az*bz + c within about an ulp of
 *     the result and 2^-45 of the terms, where they cancel far below themselves
 *     (kernel/kmath.h forms it from vfms wherever vfms is an exact a*b - c);
 *   vexpsign(x) = x with its significand cleared: its sign times the power of two at or
 *     below |x| (x normal, or 0);
 *   vmin(a,b) = a < b ? a : b and vmax(a,b) = a > b ? a : b (NaN gives b);
 *   comparisons are ordered (false when either side is NaN);
 *   vxorsign(a,b) = a with its sign flipped where b's sign bit is set (copysign for a >= 0);
 *   vsel(m,a,b) = m ? a : b, vkeep(m,a) = m ? a : 0; vstore_m writes lane i only where m is set. */
#include <math.h>
#include <stdint.h>

#define VW 1
#define VFULL 1u
#define vf float
#define vm int

#define vset1(x) ((float)(x))
#define vzero() 0.0f
#define vloadu(p) (*(p))
#define vadd(a, b) ((a) + (b))
#define vsub(a, b) ((a) - (b))
#define vmul(a, b) ((a) * (b))
#define vdiv(a, b) ((a) / (b))
#define vsqrt(a) sqrtf(a)
#define vmin(a, b) ((a) < (b) ? (a) : (b))
#define vmax(a, b) ((a) > (b) ? (a) : (b))
#define vabs(a) fabsf(a)
#define vneg(a) (-(a))
#define vcopysign(mag, sgn) copysignf(mag, sgn)
#define vxorsign(a, b) (signbit(b) ? -(a) : (a))
static inline float KFN(expsign)(float x)
{
    union {
        float f;
        uint32_t u;
    } b = {x};
    b.u &= 0xff800000u;
    return b.f;
}
#define vexpsign(x) KFN(expsign)(x)

#if defined(__FMA__) || defined(__aarch64__) || defined(__ARM_FEATURE_FMA)
#define vfma(a, b, c) fmaf(a, b, c)
#define vfms(a, b, c) fmaf(a, b, -(c))
#define vfnma(a, b, c) fmaf(-(a), b, c)
#define vfma_x(a, b, c) fmaf(a, b, c)
#define vfma_x2(a, b, ch, cl) (fmaf(a, b, ch) + (cl))
#define vsumsq_x(a, b, c, k) (fmaf(a, a, fmaf(b, b, (c) * (c))) - (k))
static inline float KFN(dop_x)(float a, float b, float c, float d)
{
    float cd = c * d;
    float err = fmaf(c, d, -cd);
    return fmaf(a, b, -cd) - err;
}
#else
/* Without a hardware FMA, fmaf is a slow library call; a product of two floats is
 * exact in double, so double does the same job in two instructions. */
#define vfma(a, b, c) ((float)((double)(a) * (double)(b) + (double)(c)))
#define vfms(a, b, c) ((float)((double)(a) * (double)(b) - (double)(c)))
#define vfnma(a, b, c) ((float)((double)(c) - (double)(a) * (double)(b)))
#define vfma_x(a, b, c) vfma(a, b, c)
#define vfma_x2(a, b, ch, cl)                                                                  \
    ((float)((double)(a) * (double)(b) + ((double)(ch) + (double)(cl))))
#define vsumsq_x(a, b, c, k)                                                                   \
    ((float)((double)(a) * (double)(a) + (double)(b) * (double)(b) +                           \
             (double)(c) * (double)(c) - (double)(k)))
#define vdot3_x(ax, ay, az, bx, by, bz, c)                                                     \
    ((float)((double)(ax) * (double)(bx) + (double)(ay) * (double)(by) +                       \
             (double)(az) * (double)(bz) + (double)(c)))
static inline float KFN(dop_x)(float a, float b, float c, float d)
{
    return (float)((double)a * (double)b - (double)c * (double)d);
}
#endif
#define vdop_x(a, b, c, d) KFN(dop_x)(a, b, c, d)
#define vfma_xw(a, b, o, c, ch, cl) vfma_x2(a, b, ch, cl)
#define vrcp_fast(x) (1.0f / (x))
#define vrsqrt_fast(x) (1.0f / sqrtf(x))

#define vlt(a, b) ((a) < (b))
#define vle(a, b) ((a) <= (b))
#define vgt(a, b) ((a) > (b))
#define vge(a, b) ((a) >= (b))
#define veq(a, b) ((a) == (b))
#define mand(a, b) ((a) & (b))
#define mor(a, b) ((a) | (b))
#define mandn(a, b) ((a) & !(b))
#define many(m) (m)
#define mbits(m) ((uint32_t)(m))
#define mfrom_bits(b) ((int)((b)&1u))
#define vsel(m, a, b) ((m) ? (a) : (b))
#define vkeep(m, a) ((m) ? (a) : 0.0f)
#define mxor(a, b) ((a) ^ (b))
#define vstore_m(p, m, x)                                                                      \
    do {                                                                                       \
        if (m)                                                                                 \
            *(p) = (x);                                                                        \
    } while (0)
#define vstoreu(p, x) (*(p) = (x))
#define vstoreu_part(p, x) (*(p) = (int32_t)(x))
#define vstore_part_m(p, m, x)                                                                 \
    do {                                                                                       \
        if (m)                                                                                 \
            *(p) = (int32_t)(x);                                                               \
    } while (0)
