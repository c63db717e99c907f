/* SPDX-License-Identifier: MIT */
/* toolkit/faces.h - a box's faces rounded outward to float, in double first and in
 * double-double where that leaves the float undecided: shared by bounds.c and split.c,
 * whose boxes must both hold the exact shape. */
#ifndef CYLRAY_TOOLKIT_FACES_H
#define CYLRAY_TOOLKIT_FACES_H
#include "cylray_internal.h"
#include "internal/dd.h"

/* The unit axis n = v / |v| and the rim's half extent s = sqrt(1 - n_k^2) along
 * coordinate k, as double-doubles. Both are exact when the axis lies along k (n_k =
 * +-1, s = 0) or across it (n_k = 0, s = 1); otherwise each is within 2^-100 of its
 * value relative to itself, and *exact is cleared. */
typedef struct axis_k {
    cylray_dd n, s;
    int exact;
} axis_k;

static axis_k axis_coord(const float v[3], int k)
{
    axis_k a;
    const double vk = v[k], vi = v[(k + 1) % 3], vj = v[(k + 2) % 3];
    if (vi == 0 && vj == 0) {
        a.n = dd_make(vk > 0 ? 1.0 : -1.0, 0.0);
        a.s = dd_make(0.0, 0.0);
        a.exact = 1;
        return a;
    }
    if (vk == 0) {
        a.n = dd_make(0.0, 0.0);
        a.s = dd_make(1.0, 0.0);
        a.exact = 1;
        return a;
    }
    /* The squares of floats are exact as double-doubles, so S and V are good to a few
     * 2^-104, and so are their roots and the quotients. */
    cylray_dd S = dd_add(dd_two_prod(vi, vi), dd_two_prod(vj, vj));
    cylray_dd V = dd_add(S, dd_two_prod(vk, vk));
    cylray_dd sv = dd_sqrt(V);
    a.n = dd_div(dd_make(vk, 0.0), sv);
    a.s = dd_div(dd_sqrt(S), sv);
    a.exact = 0;
    return a;
}

/* c + a + b rounded down (dir < 0) or up (dir > 0) to float, where a and b carry a
 * relative error of at most 2^-100 unless exact. The sum in double-double adds a few
 * 2^-104 of the magnitudes; 2^-96 of them covers everything, so the float is on the
 * outer side of the exact value and, unless the sum cancels to below about 2^-70 of
 * its terms, at most one float step beyond the closest float there. */
static float face(double c, cylray_dd a, cylray_dd b, int exact, int dir)
{
    cylray_dd x = dd_add(dd_add(dd_make(c, 0.0), a), b);
    if (!exact) {
        double mag = fabs(c) + fabs(a.hi) + fabs(b.hi);
        x = dd_add(x, dd_make(dir * ldexp(mag, -96), 0.0));
    }
    return dir < 0 ? dd_floor_float(x) : dd_ceil_float(x);
}

/* ---- the same faces in plain double first ------------------------------------------
 * The double-double path above costs about 300 ns a coordinate (square roots and
 * divisions in a chain). Each face is first formed in double with a bound on its
 * error, and taken where every value within the bound rounds outward to the same
 * float: that float is then the double-double path's too, which rounds the exact
 * value, pushed outward by 2^-96 of the magnitudes, the same way. */

/* n_k and s_k in double, within 3 and 4.5 units of 2^-53 of themselves (sums of exact
 * squares, square roots, divisions); exact along k and across it, as axis_coord. */
static int axis_coord_d(const float v[3], int k, double *n, double *s)
{
    const double vk = v[k], vi = v[(k + 1) % 3], vj = v[(k + 2) % 3];
    if (vi == 0 && vj == 0) {
        *n = vk > 0 ? 1.0 : -1.0, *s = 0.0;
        return 1;
    }
    if (vk == 0) {
        *n = 0.0, *s = 1.0;
        return 1;
    }
    const double S = vi * vi + vj * vj, sv = sqrt(S + vk * vk);
    *n = vk / sv, *s = sqrt(S) / sv;
    return 0;
}

/* x rounded down or up to float (x not NaN) */
static float outward_f(double x, int dir)
{
    return dir < 0 ? dd_floor_float(dd_make(x, 0.0)) : dd_ceil_float(dd_make(x, 0.0));
}

/* c + a + b rounded outward to float, where a and b are within 6 units of 2^-53 of
 * themselves (exact where `exact`): 1 and *out where decided. The sum's two roundings
 * add 2 units of the magnitudes; 2^-48 of them (32 units) bounds every error, the
 * roundings of x -+ e included. */
static inline int face_quick(double c, double a, double b, int exact, int dir, float *out)
{
    const cylray_dd s1 = dd_two_sum(c, a), s2 = dd_two_sum(s1.hi, b);
    const double x = s2.hi;
    if (exact && s1.lo == 0 && s2.lo == 0) {
        *out = outward_f(x, dir); /* the sum is exact */
        return 1;
    }
    const double e = (fabs(c) + fabs(a) + fabs(b)) * 0x1p-48;
    const float f = outward_f(x + dir * e, dir);
    if (f != outward_f(x - dir * e, dir))
        return 0;
    *out = f;
    return 1;
}

#endif
