/* SPDX-License-Identifier: MIT */
/* api/endpoints.c - a cylinder from its end points and radius. */
#include "cylray_internal.h"
#include "internal/dd.h"

#include <string.h>

/* The sign of the exact sum of x[0..n) (n <= 24), by growing a nonoverlapping
 * expansion (Shewchuk): the sign of a nonoverlapping expansion is its largest term's. */
static int sum_sign(const double *x, int n)
{
    double h[24];
    int m = 0;
    for (int i = 0; i < n; i++) {
        double q = x[i];
        int k = 0;
        for (int j = 0; j < m; j++) {
            const cylray_dd t = dd_two_sum(q, h[j]); /* exact: any order of magnitudes */
            if (t.lo != 0)
                h[k++] = t.lo;
            q = t.hi;
        }
        if (q != 0)
            h[k++] = q;
        m = k;
    }
    return m == 0 ? 0 : h[m - 1] > 0 ? 1 : -1;
}

/* The sign of S - (2 mid)^2, S = sum of a[k]^2 with a[k] = ah[k] + al[k] exact: every
 * square and product split exactly by an FMA (no double product of floats' differences
 * underflows or overflows). */
static int cmp_sq(const double ah[3], const double al[3], double mid)
{
    double x[20];
    int n = 0;
    for (int k = 0; k < 3; k++) {
        const double t[3][2] = {{ah[k], ah[k]}, {2 * ah[k], al[k]}, {al[k], al[k]}};
        for (int j = 0; j < 3; j++) {
            const double pr = t[j][0] * t[j][1];
            x[n++] = pr;
            x[n++] = fma(t[j][0], t[j][1], -pr);
        }
    }
    const double m2 = 2 * mid, pr = m2 * m2;
    x[n++] = -pr;
    x[n++] = -fma(m2, m2, -pr);
    return sum_sign(x, n);
}

cylray_status cylray_cylinder_from_endpoints(cylray_cylinder *out, const float p0[3],
                                             const float p1[3], float radius, unsigned flags)
{
    if (!out || !p0 || !p1)
        return CYLRAY_EINVAL;
    cylray_cylinder c;
    double ah[3], al[3], len2 = 0;
    for (int k = 0; k < 3; k++) {
        if (!isfinite(p0[k]) || !isfinite(p1[k]))
            return CYLRAY_EINVAL;
        /* The difference and the sum of two floats are exact as two-term sums in
         * double; each is rounded once, to float (halving is exact). */
        const cylray_dd d = dd_two_sum((double)p1[k], -(double)p0[k]);
        const cylray_dd m = dd_two_sum((double)p0[k], (double)p1[k]);
        ah[k] = d.hi, al[k] = d.lo;
        c.axis[k] = cylray_round_float_(ah[k], al[k]);
        c.center[k] = cylray_round_float_(0.5 * m.hi, 0.5 * m.lo);
        len2 += ah[k] * ah[k];
    }
    /* The half height |a| / 2 rounded once: a first guess from double, then moved to
     * the float whose rounding interval holds it, each midpoint m judged exactly by the
     * sign of |a|^2 - (2m)^2 (a tie goes to the even float). */
    float h = cylray_round_float_(0.5 * sqrt(len2), 0);
    /* The guess is the rounding of |a| / 2 wherever the bound on its error decides it:
     * len2 is within 5 units of 2^-53 of |a|^2 (each al at most half an ulp of its ah,
     * the squares and sums rounded once each), 0.5 sqrt(len2) within 4 of |a| / 2, and
     * the bound used is 8. */
    const double hd = 0.5 * sqrt(len2);
    if (len2 > 0 && h > 0 && isfinite(h) && !cylray_float_decided_(hd, 0x1p-50 * hd)) {
        for (int iter = 0; iter < 4; iter++) {
            const float up = cylray_float_step_(h, 1), dn = cylray_float_step_(h, 0);
            uint32_t hb;
            memcpy(&hb, &h, sizeof hb);
            const int even = (hb & 1u) == 0;
            const int su = isfinite(up) ? cmp_sq(ah, al, 0.5 * ((double)h + up)) : -1;
            const int sd = dn > 0 ? cmp_sq(ah, al, 0.5 * ((double)h + dn)) : 1;
            if (su > 0 || (su == 0 && !even))
                h = up;
            else if (sd < 0 || (sd == 0 && !even))
                h = dn;
            else
                break;
        }
    }
    c.radius = radius;
    c.half_height = h;
    c.flags = flags;
    if (!(len2 > 0) || !cylray_cylinder_ok_(&c))
        return CYLRAY_EINVAL;
    *out = c;
    return CYLRAY_OK;
}
