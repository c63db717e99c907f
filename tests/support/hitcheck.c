/* SPDX-License-Identifier: MIT */
/* hitcheck.c - the geometric verifier of one reported hit (hitcheck.h). */
#include "hitcheck.h"

#include <math.h>
#include <stdio.h>

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

void hc_from(hc_cyl *g, const cylray_cylinder *cyl)
{
    /* An axis of FLT_MIN size would square to nearly nothing; scale it to 1 first. */
    double m = fmax(fabs((double)cyl->axis[0]),
                    fmax(fabs((double)cyl->axis[1]), fabs((double)cyl->axis[2])));
    double s = m > 0 ? 1.0 / m : 1.0;
    double vv = 0;
    for (int k = 0; k < 3; k++)
        vv += ((double)cyl->axis[k] * s) * ((double)cyl->axis[k] * s);
    double l = sqrt(vv);
    for (int k = 0; k < 3; k++) {
        g->c[k] = cyl->center[k];
        g->u[k] = (double)cyl->axis[k] * s / l;
    }
    g->R = cyl->radius;
    g->H = cyl->half_height;
    g->capped = (cyl->flags & CYLRAY_CAPPED) && isfinite(g->H);
}

void hc_locate(const hc_cyl *g, const double x[3], double *z, double *r, double p[3])
{
    double w[3] = {x[0] - g->c[0], x[1] - g->c[1], x[2] - g->c[2]};
    *z = dot3(w, g->u);
    for (int k = 0; k < 3; k++)
        p[k] = w[k] - *z * g->u[k];
    *r = sqrt(dot3(p, p));
}

double hc_tolerance(const hc_cyl *g, const float o[3], const float d[3], float t, double slack)
{
    double w = 0, dd = 0;
    for (int k = 0; k < 3; k++) {
        w += ((double)o[k] - g->c[k]) * ((double)o[k] - g->c[k]);
        dd += (double)d[k] * d[k];
    }
    /* The last term: t is a float, and below 2^-126 its spacing is 2^-149, which a
     * direction of 2^100 turns into a step of 2^-49 along the ray. */
    return slack * 0x1p-18 * (sqrt(w) + fabs((double)t) * sqrt(dd) + g->R) +
           sqrt(dd) * 0x1p-149;
}

#define WHY_(...) (snprintf(why, whylen, __VA_ARGS__), 1)

int hc_verify(const cylray_cylinder *cyl, const float o[3], const float d[3], float tmin,
              float tmax, float t, int32_t part, const float *n, unsigned flags, double slack,
              char *why, size_t whylen)
{
    hc_cyl g;
    hc_from(&g, cyl);
    if (!isfinite(t) || !(t >= tmin && t <= tmax))
        return WHY_("t %a not a finite value in [%a, %a]", t, tmin, tmax);
    /* The hit point relative to the center: o - c is exact in double unless the two
     * differ by more than 2^29 in scale, and t d is exact; adding c back first would
     * lose everything below 2^-53 of a far center. */
    double w[3], p[3], z, r;
    for (int k = 0; k < 3; k++)
        w[k] = ((double)o[k] - g.c[k]) + (double)t * d[k];
    z = dot3(w, g.u);
    for (int k = 0; k < 3; k++)
        p[k] = w[k] - z * g.u[k];
    r = sqrt(dot3(p, p));
    const double tol = hc_tolerance(&g, o, d, t, slack);
    const int base = part & ~CYLRAY_BACKFACE;
    const int back = (part & CYLRAY_BACKFACE) != 0;

    double nout[3];
    switch (base) {
    case CYLRAY_SIDE:
        if (fabs(r - g.R) > tol)
            return WHY_("side hit %g from the axis, radius %g (tolerance %g)", r, g.R, tol);
        if (isfinite(g.H) && fabs(z) > g.H + tol)
            return WHY_("side hit at axial %g beyond half height %g (tolerance %g)", z, g.H,
                        tol);
        for (int k = 0; k < 3; k++)
            nout[k] = r > 0 ? p[k] / r : 0;
        break;
    case CYLRAY_CAP_LO:
    case CYLRAY_CAP_HI: {
        const double s = base == CYLRAY_CAP_HI ? 1.0 : -1.0;
        if (!g.capped)
            return WHY_("cap hit on a cylinder without caps");
        if (fabs(z - s * g.H) > tol)
            return WHY_("cap hit at axial %g, cap at %g (tolerance %g)", z, s * g.H, tol);
        if (r > g.R + tol)
            return WHY_("cap hit %g from the axis, outside radius %g (tolerance %g)", r, g.R,
                        tol);
        for (int k = 0; k < 3; k++)
            nout[k] = s * g.u[k];
        break;
    }
    default:
        return WHY_("part %#x is no part", (unsigned)part);
    }

    /* Front or back: the sign of d . n_out. The side normal's direction is known to
     * about tol / R from the point's position. Near a tangency the entry and the exit
     * merge: d . n_out / |d| there is the square root of the discriminant's relative
     * size, so an error of tol / R in the discriminant allows sqrt(tol / R) either way
     * (the kernel may report the exit as the entry of a grazing ray). */
    const double dl = sqrt((double)d[0] * d[0] + (double)d[1] * d[1] + (double)d[2] * d[2]);
    const double dn[3] = {d[0] / dl, d[1] / dl, d[2] / dl};
    const double cosang = dot3(dn, nout);
    const double dir_err = base == CYLRAY_SIDE ? 2 * tol / g.R + 1e-6 : 1e-6;
    const double face_err = base == CYLRAY_SIDE ? dir_err + sqrt(tol / g.R) : dir_err;
    if (back && cosang < -face_err)
        return WHY_("BACKFACE set but the ray enters (d.n_out/|d| = %g)", cosang);
    if (!back && cosang > face_err)
        return WHY_("BACKFACE clear but the ray leaves (d.n_out/|d| = %g)", cosang);

    if (n && (flags & CYLRAY_NORMAL)) {
        const double nd[3] = {n[0], n[1], n[2]};
        const double len = sqrt(dot3(nd, nd));
        const double len_tol = (flags & CYLRAY_FAST) ? 1e-4 : 1e-5;
        if (!(fabs(len - 1) <= len_tol))
            return WHY_("normal (%a, %a, %a) has length %.9g", n[0], n[1], n[2], len);
        double want[3];
        const double flip = ((flags & CYLRAY_FACE_FORWARD) && back) ? -1.0 : 1.0;
        for (int k = 0; k < 3; k++)
            want[k] = flip * nout[k];
        /* Only meaningful when the point's position pins the normal down. */
        if (dir_err < 0.1) {
            const double c = dot3(nd, want) / len;
            const double ang = acos(fmin(1.0, fmax(-1.0, c)));
            if (ang > dir_err + ((flags & CYLRAY_FAST) ? 1e-3 : 1e-4))
                return WHY_("normal (%a, %a, %a) is %.3g rad off the %s normal", n[0], n[1],
                            n[2], ang, flip < 0 ? "flipped outward" : "outward");
        }
        if ((flags & CYLRAY_FACE_FORWARD) && dot3(nd, dn) / len > face_err)
            return WHY_("FACE_FORWARD normal faces away from the ray (n.d/|d| = %g)",
                        dot3(nd, dn) / len);
    }
    return 0;
}
