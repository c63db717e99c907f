/* SPDX-License-Identifier: MIT */
/* simd/f64_scalar.h - the secondary-ray code's vocabulary of double vectors, one lane:
 * plain C. It is also the definition of every operation the SIMD headers implement:
 *   vd: DW doubles; vdm: a lane mask (dlt, dle, dgt, deq: ordered compares);
 *   dsel(m, a, b) = m ? a : b; dmax(a, b) = a > b ? a : b, dmin(a, b) = a < b ? a : b
 *     (NaN gives b, as maxpd/minpd do);
 *   dround_f(x) = (double)(float)x, the rounding to float done for certain;
 *   dexpo(x) = x with its significand cleared (2^e for a normal x, inf for inf and NaN);
 *   dloadu_f / dstoreu_f: DW floats to and from doubles (the store rounds to nearest);
 *   dload_bits(p, m) = (double)(p[i] & m), for an int32_t array p;
 *   dmbits(m): bit i set where lane i of m is. */
#include <stdint.h>
#include <string.h>

#define DW 1
#define DFULL 1u
#define vd double
#define vdm int

#define dset1(x) ((double)(x))
#define dadd(a, b) ((a) + (b))
#define dsub(a, b) ((a) - (b))
#define dmul(a, b) ((a) * (b))
#define ddiv(a, b) ((a) / (b))
#define dsqrt(a) sqrt(a)
#define dabs(a) fabs(a)
#define dmax(a, b) ((a) > (b) ? (a) : (b))
#define dmin(a, b) ((a) < (b) ? (a) : (b))
#define dlt(a, b) ((a) < (b))
#define dle(a, b) ((a) <= (b))
#define dgt(a, b) ((a) > (b))
#define deq(a, b) ((a) == (b))
#define dmand(a, b) ((a) & (b))
#define dmor(a, b) ((a) | (b))
#define dmandn(a, b) ((a) & !(b))
#define dmnot(a) (!(a))
#define dmbits(m) ((uint32_t)(m))
#define dsel(m, a, b) ((m) ? (a) : (b))

/* gcc -O3 may pack scalar statements into vectors and lose a conversion to float on
 * the way (double -> float -> double came back unrounded in some lanes), so the float
 * is passed through an empty asm statement, which the compiler must treat as changing
 * it: the rounding happens, whatever the optimiser does around it. */
static inline double DFN(round_f)(double x)
{
    float f = (float)x;
#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__)) && defined(__SSE2__)
    __asm__("" : "+x"(f));
#elif defined(__GNUC__) && defined(__aarch64__)
    __asm__("" : "+w"(f));
#else
    volatile float vf_ = f;
    f = vf_;
#endif
    return (double)f;
}
#define dround_f(x) DFN(round_f)(x)

static inline double DFN(expo)(double x)
{
    uint64_t b;
    memcpy(&b, &x, sizeof b);
    b &= 0x7ff0000000000000ull;
    memcpy(&x, &b, sizeof x);
    return x;
}
#define dexpo(x) DFN(expo)(x)
#define dloadu_f(p) ((double)*(p))
#define dstoreu_f(p, x) (*(p) = (float)(x))
#define dload_bits(p, m) ((double)(*(p) & (m)))
