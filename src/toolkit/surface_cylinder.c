/* SPDX-License-Identifier: MIT */
/* toolkit/surface_cylinder.c - a cylinder's surface coordinates, apart from the other
 * shapes' because this file alone is compiled a second time with AVX2 and FMA. */
#include "internal/dd.h"
#include "surface.h"

/* surface_at is compiled twice on x86 (src/meson.build): here, and with AVX2 and FMA
 * as cylray_surface_at_fma_, where each fma() of the double-double products is one
 * instruction instead of a call into libm (32 a call, with the live floating-point
 * registers saved around each). The products are exact either way: the answers are
 * the same. */
#ifdef CYLRAY_SURFACE_FMA
#define SURFACE_AT_ cylray_surface_at_fma_
#else
#define SURFACE_AT_ cylray_surface_at_plain_
#endif

/* The double-double path, every quantity good to about 2^-100 of its size: u and v,
 * and the derivatives that turn with the azimuth (dpdr: a disc's dpdu; NULL on the
 * side, whose dpdu SURFACE_AT_ writes). */
static void surface_dd(const surf_cyl *s, const float p[3], int32_t part, float uv[2],
                       float dpdr[3], float dpdv[3])
{
    /* The unit axis as a double-double; exact along a coordinate axis. */
    cylray_dd n[3];
    int zeros = (s->v[0] == 0) + (s->v[1] == 0) + (s->v[2] == 0);
    if (zeros == 2) {
        for (int k = 0; k < 3; k++)
            n[k] = dd_make(s->v[k] == 0 ? 0.0 : s->v[k] > 0 ? 1.0 : -1.0, 0.0);
    } else {
        cylray_dd vv = dd_make(0.0, 0.0);
        for (int k = 0; k < 3; k++)
            vv = dd_add(vv, dd_two_prod(s->v[k], s->v[k]));
        cylray_dd sv = dd_sqrt(vv);
        for (int k = 0; k < 3; k++)
            n[k] = dd_div(dd_make(s->v[k], 0.0), sv);
    }
    const int side = part == CYLRAY_SIDE, finite = isfinite(s->H);
    /* p - c is exact as a double-double. */
    cylray_dd r[3];
    for (int k = 0; k < 3; k++)
        r[k] = dd_two_sum(p[k], -(double)s->c[k]);
    if (uv && side) {
        cylray_dd z = dd_make(0.0, 0.0);
        for (int k = 0; k < 3; k++)
            z = dd_add(z, dd_mul(r[k], n[k]));
        if (finite)
            z = dd_div(dd_add(z, dd_make(s->H, 0.0)), dd_make(2.0 * s->H, 0.0));
        uv[0] = (float)(z.hi + z.lo);
    }
    /* The frame of Duff et al. (JCGT 2017) with s = +1 where n_z >= 0, a zero of either
     * sign included: s + n_z never cancels, and every user builds the same frame. */
    double sg = n[2].hi >= 0 ? 1.0 : -1.0;
    cylray_dd a = dd_div(dd_make(-1.0, 0.0), dd_add(dd_make(sg, 0.0), n[2]));
    cylray_dd b = dd_mul(dd_mul(n[0], n[1]), a);
    cylray_dd b1[3] = {dd_add(dd_make(1.0, 0.0), dd_mul_d(dd_mul(dd_mul(n[0], n[0]), a), sg)),
                       dd_mul_d(b, sg), dd_mul_d(n[0], -sg)};
    cylray_dd b2[3] = {b, dd_add(dd_make(sg, 0.0), dd_mul(dd_mul(n[1], n[1]), a)),
                       dd_neg(n[1])};
    /* The coordinates of p - c in the frame, good to 2^-100 |p - c|. */
    cylray_dd X = dd_make(0.0, 0.0), Y = X;
    for (int k = 0; k < 3; k++) {
        X = dd_add(X, dd_mul(r[k], b1[k]));
        Y = dd_add(Y, dd_mul(r[k], b2[k]));
    }
    const double x = X.hi + X.lo, y = Y.hi + Y.lo, rho = hypot(x, y);
    /* cos and sin of the azimuth; on the axis the azimuth is 0 */
    double co = rho > 0 ? x / rho : 1.0, si = rho > 0 ? y / rho : 0.0;
    if (uv) {
        double t = rho > 0 ? atan2(y, x) / TWO_PI : 0.0;
        if (t < 0)
            t += 1.0;
        float f = (float)t + 0.0f; /* + 0: no -0 */
        uv[1] = f < 1.0f ? f : BELOW_ONE;
    }
    if (side) {
        if (dpdv)
            for (int k = 0; k < 3; k++)
                dpdv[k] = (float)(TWO_PI * s->R * (co * b2[k].hi - si * b1[k].hi));
        return;
    }
    /* A disc: the radial coordinate w = rho / R in [0, 1] with v the azimuth. */
    if (dpdr)
        for (int k = 0; k < 3; k++)
            dpdr[k] = (float)(s->R * (co * b1[k].hi + si * b2[k].hi));
    if (dpdv)
        for (int k = 0; k < 3; k++)
            dpdv[k] = (float)(TWO_PI * rho * (co * b2[k].hi - si * b1[k].hi));
}

/* The unit axis in double, good to 4U |n_k| (U = 2^-53: two sums of exact squares, a
 * square root, a division); exact along a coordinate axis. */
static void axis_d(const surf_cyl *s, double n[3])
{
    int zeros = (s->v[0] == 0) + (s->v[1] == 0) + (s->v[2] == 0);
    if (zeros == 2) {
        for (int k = 0; k < 3; k++)
            n[k] = s->v[k] == 0 ? 0.0 : s->v[k] > 0 ? 1.0 : -1.0;
        return;
    }
    const double sv =
        sqrt((double)s->v[0] * s->v[0] + (double)s->v[1] * s->v[1] + (double)s->v[2] * s->v[2]);
    for (int k = 0; k < 3; k++)
        n[k] = s->v[k] / sv + 0.0; /* + 0: a zero is +0, as on the double-double path */
}

/* u and v in plain double, where the error bound e of the coordinates (z = r.n, x, y in
 * the frame, rho = |(x, y)|) decides their floats: each then rounds to the float of its
 * exact value, as on the double-double path (good to 2^-100). Returns 0 where it does
 * not decide: u or v within the bound of a midpoint between two floats (about one
 * point in 2^20 of ordinary ones), or v at its seam (y of either sign where x > 0). */
static int uv_quick(const surf_cyl *s, int side, double z, double x, double y, double rho,
                    double e, float uv[2])
{
    float u = 0.0f;
    if (side) {
        double ud = z, eu = e;
        if (isfinite(s->H)) {
            ud = (z + s->H) / (2.0 * s->H);
            eu = e / (2.0 * s->H) + 0x1p-51 * fabs(ud);
        }
        /* twice the bound: the double-double path's value lies within it as well */
        if (!cylray_float_decided_(ud, 2.0 * eu))
            return 0;
        u = (float)ud;
    }
    /* The azimuth moves by at most 1.5 e / rho; atan2 (charged two ulps), 2 pi and the
     * division add 6U |t|, the wrap U. */
    if (!(y > e || y < -e || x < 0))
        return 0;
    double t = atan2(y, x) / TWO_PI, et = 2.0 * (0.25 * e / rho + 0x1p-50 * fabs(t));
    if (t < 0)
        t += 1.0, et += 0x1p-51;
    if (!cylray_float_decided_(t, et))
        return 0;
    const float f = (float)t + 0.0f; /* + 0: no -0 */
    if (side)
        uv[0] = u; /* a disc's u is written already */
    uv[1] = f < 1.0f ? f : BELOW_ONE;
    return 1;
}

/* The frame and the coordinates in plain double first, with a bound on their error,
 * and the double-double path only for what that bound leaves undecided. The bound: the
 * axis is good to 4U |n_k|; a = -1 / (s + n_z), whose denominator is at least 1, to
 * 7U |a|; every frame component, each at most 1 in size, to 19U; r = p - c to U |r_k|;
 * so each of z, x and y to 23U R1, with R1 = |r_0| + |r_1| + |r_2|; E = 2^-47 R1 is
 * 64U R1. Where rho > 2^26 E the azimuth's cosine and sine are good to 2^-25, and the
 * derivatives with them (the header promises 2^-20); short of that, and for NaN or
 * infinite coordinates, the double-double path computes everything that turns with
 * the azimuth. Each choice depends on p alone, never on which outputs are asked for,
 * so an output does not change with the others. */
void SURFACE_AT_(const surf_cyl *s, const float p[3], int32_t part, float uv[2], float dpdu[3],
                 float dpdv[3])
{
    part &= CYLRAY_PART_MASK;
    if (part != CYLRAY_SIDE && part != CYLRAY_CAP_LO && part != CYLRAY_CAP_HI)
        return;
    const int side = part == CYLRAY_SIDE;
    double n[3];
    axis_d(s, n);
    if (dpdu && side)
        for (int k = 0; k < 3; k++)
            dpdu[k] = (float)((isfinite(s->H) ? 2.0 * s->H : 1.0) * n[k]);
    if (uv && !side)
        uv[0] = part == CYLRAY_CAP_HI ? 1.0f : 0.0f;
    float *const dpdr = side ? NULL : dpdu; /* a disc's dpdu turns with the azimuth */
    if (!uv && !dpdv && !dpdr)
        return;
    double r[3], R1 = 0;
    for (int k = 0; k < 3; k++) {
        r[k] = (double)p[k] - (double)s->c[k];
        R1 += fabs(r[k]);
    }
    const double E = 0x1p-47 * R1;
    /* The frame of Duff et al., as on the double-double path, whose zeros are +0 where
     * they come from a product (hence the + 0) and -0 in -n_y. */
    const double sg = n[2] >= 0 ? 1.0 : -1.0, a = -1.0 / (sg + n[2]), b = n[0] * n[1] * a + 0.0;
    const double b1[3] = {1.0 + sg * (n[0] * n[0] * a), sg * b + 0.0, -sg * n[0] + 0.0};
    const double b2[3] = {b, sg + n[1] * n[1] * a, -n[1]};
    const double x = r[0] * b1[0] + r[1] * b1[1] + r[2] * b1[2];
    const double y = r[0] * b2[0] + r[1] * b2[1] + r[2] * b2[2];
    const double rho = sqrt(x * x + y * y);
    if (!(E < INFINITY) || !(rho > 0x1p26 * E)) {
        surface_dd(s, p, part, uv, dpdr, dpdv);
        return;
    }
    const double co = x / rho, si = y / rho;
    for (int k = 0; k < 3 && dpdv; k++)
        dpdv[k] = (float)(TWO_PI * (side ? s->R : rho) * (co * b2[k] - si * b1[k]));
    for (int k = 0; k < 3 && dpdr; k++)
        dpdr[k] = (float)(s->R * (co * b1[k] + si * b2[k]));
    if (uv) {
        const double z = side ? r[0] * n[0] + r[1] * n[1] + r[2] * n[2] : 0.0;
        if (!uv_quick(s, side, z, x, y, rho, E, uv))
            surface_dd(s, p, part, uv, NULL, NULL);
    }
}
