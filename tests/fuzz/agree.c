/* SPDX-License-Identifier: MIT */
/* agree.c - the disagreement criterion of agree.h.
 *
 * Two answers agree when both miss, or both hit the same part at t within the
 * position tolerance of hitcheck.h (2^-18 of the scale |o - c| + |t d| + R, 16 times
 * that under CYLRAY_FAST). Otherwise the difference is excused when the ray lies near
 * a decision boundary, measured generously in double from the float inputs with a band
 * of 2^-12 of the same scale (2^-8 under CYLRAY_FAST): about 2^11 float ulps of the
 * numbers involved, far more than any rounding difference between two correct paths
 * can move a decision, yet small enough that a wrong formula or a lane mix-up, which
 * goes wrong away from the boundaries too, is still caught. The boundaries:
 *   - t at tmin or tmax (inside or outside the interval);
 *   - a ray grazing the side (its line passes at R from the axis);
 *   - a ray nearly parallel to the axis (the kernel's parallel test);
 *   - a hit near the rim, or a side hit near the end of an open tube (the clip);
 *   - an origin on the surface (which root is the first one).
 * When none applies, the exact reference decides (tests/ref, cylref_band_eval): the
 * difference stands only if both answers are outcomes it allows. */
#include "agree.h"

#include <math.h>
#include <stdio.h>

#include "hitcheck.h"
#ifdef HAVE_CYLREF
#include "cylref.h"
#endif

unsigned long fz_excused_geometric, fz_excused_exact;

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* Is the hit at t near a boundary? (hc_cyl geometry, w = o - c, d in double) */
static int near_hit_boundary(const hc_cyl *g, const double w[3], const double d[3], double dl,
                             float t, const float ray[G_NFIELD], double band)
{
    if (fabs((double)t - ray[G_TMIN]) * dl <= band ||
        fabs((double)t - ray[G_TMAX]) * dl <= band)
        return 1;
    double x[3], p[3];
    for (int k = 0; k < 3; k++)
        x[k] = w[k] + (double)t * d[k];
    const double z = dot3(x, g->u);
    for (int k = 0; k < 3; k++)
        p[k] = x[k] - z * g->u[k];
    const double r = sqrt(dot3(p, p));
    if (isfinite(g->H) && fabs(fabs(z) - g->H) <= band && r <= g->R + band)
        return 1; /* at the rim, or at the end of an open tube */
    return 0;
}

int fz_agree(const cylray_cylinder *c, const float ray[G_NFIELD], unsigned flags,
             const fz_answer *a, const fz_answer *b, char *why, size_t whylen)
{
    if (!a->hit && !b->hit)
        return 0;
    hc_cyl g;
    hc_from(&g, c);
    const float o[3] = {ray[G_OX], ray[G_OY], ray[G_OZ]};
    const float df[3] = {ray[G_DX], ray[G_DY], ray[G_DZ]};
    const float tt = a->hit && b->hit ? fmaxf(fabsf(a->t), fabsf(b->t)) : a->hit ? a->t : b->t;
    const double slack = (flags & CYLRAY_FAST) ? 16 : 1;
    const double tol = hc_tolerance(&g, o, df, tt, slack);
    double w[3], d[3];
    for (int k = 0; k < 3; k++) {
        w[k] = (double)o[k] - g.c[k];
        d[k] = df[k];
    }
    const double dl = sqrt(dot3(d, d));
    if (a->hit && b->hit && a->part == b->part && fabs((double)a->t - b->t) * dl <= 2 * tol)
        return 0;
    /* Beyond the range cylray.h promises answers for (an origin 2^62 from the center),
     * a path may miss where another hits; a hit is still held to hitcheck.h. */
    if (a->hit != b->hit && !(sqrt(dot3(w, w)) <= 0x1p62)) {
        fz_excused_geometric++;
        return 0;
    }

    /* The generous band: 2^6 times the tolerance, i.e. 2^-12 of the scale. */
    const double band = 64 * tol;
    int near = 0;
    if (a->hit)
        near |= near_hit_boundary(&g, w, d, dl, a->t, ray, band);
    if (b->hit)
        near |= near_hit_boundary(&g, w, d, dl, b->t, ray, band);
    /* parallel: the sine of the angle between d and the axis */
    double n[3] = {d[1] * g.u[2] - d[2] * g.u[1], d[2] * g.u[0] - d[0] * g.u[2],
                   d[0] * g.u[1] - d[1] * g.u[0]};
    const double nl = sqrt(dot3(n, n));
    if (nl <= 0x1p-10 * dl)
        near = 1;
    /* grazing: the ray's line passes at distance |w . n| / |n| from the axis */
    else if (fabs(fabs(dot3(w, n)) / nl - g.R) <= band)
        near = 1;
    /* origin on the surface */
    {
        const double z = dot3(w, g.u);
        double p[3];
        for (int k = 0; k < 3; k++)
            p[k] = w[k] - z * g.u[k];
        const double r = sqrt(dot3(p, p));
        if (fabs(r - g.R) <= band && (!isfinite(g.H) || fabs(z) <= g.H + band))
            near = 1;
        if (g.capped && fabs(fabs(z) - g.H) <= band && r <= g.R + band)
            near = 1;
    }
    if (near) {
        fz_excused_geometric++;
        return 0;
    }
#ifdef HAVE_CYLREF
    cylref_band bd;
    cylref_band_eval(c, o, df, ray[G_TMIN], ray[G_TMAX], flags, &bd);
    double ua = 0, ub = 0;
    const int va = cylref_judge(&bd, a->hit, a->part, a->t, &ua);
    const int vb = cylref_judge(&bd, b->hit, b->part, b->t, &ub);
    /* t beyond the band: a few ulps for rounding order, more for FAST's estimates */
    const double ulp_tol = (flags & CYLRAY_FAST) ? 256 : 16;
    if (va == 0 && vb == 0 && ua <= ulp_tol && ub <= ulp_tol) {
        fz_excused_exact++;
        return 0;
    }
    snprintf(why, whylen,
             "answers (%s t=%a part=%#x) and (%s t=%a part=%#x); exact: %s t=%.17g part=%#x, "
             "verdicts %d/%d, ulps beyond the band %.3g/%.3g",
             a->hit ? "hit" : "miss", a->t, (unsigned)a->part, b->hit ? "hit" : "miss", b->t,
             (unsigned)b->part, bd.exact.hit ? "hit" : "miss", bd.exact.t,
             (unsigned)bd.exact.part, va, vb, ua, ub);
#else
    snprintf(why, whylen,
             "answers (%s t=%a part=%#x) and (%s t=%a part=%#x) away from any "
             "decision boundary",
             a->hit ? "hit" : "miss", a->t, (unsigned)a->part, b->hit ? "hit" : "miss", b->t,
             (unsigned)b->part);
#endif
    return 1;
}
