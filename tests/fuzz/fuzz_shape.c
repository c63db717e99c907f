/* SPDX-License-Identifier: MIT */
/* fuzz_shape.c - the checks of fuzz_shape.h. */
#include "fuzz_shape.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "tcheck.h"
#ifdef HAVE_CYLREF
#include "conref.h"
#include "sphref.h"
#endif

unsigned long fz_sphere_cases, fz_sphere_lanes, fz_cone_cases, fz_cone_lanes;

/* The shape's center, for the working range: a sphere's, a cone's midpoint. */
static void center_of(const fz_case *c, double ctr[3])
{
    for (int k = 0; k < 3; k++)
        ctr[k] = c->cone ? 0.5 * ((double)c->con.p0[k] + c->con.p1[k]) : c->sph.center[k];
}

#ifdef HAVE_CYLREF
/* cylray.h's working range: the origin within 2^62 of the center in each coordinate;
 * beyond it a lane may miss, and is not judged against the reference. The exact t
 * beyond FLT_MAX is left to the band's own judgement (an exact hit there cannot be
 * reported, and the band then says so only through t). */
static int in_range(const fz_case *c, const float *ray)
{
    double ctr[3];
    center_of(c, ctr);
    for (int k = 0; k < 3; k++)
        if (!(fabs((double)ray[G_OX + k] - ctr[k]) <= 0x1p62))
            return 0;
    return 1;
}
#endif

int fz_shape(const fz_case *c, const cylray_kernels *const *isas, int nisa, char *why,
             size_t whylen)
{
    const char *shape = c->cone ? "cone" : "sphere";
    unsigned long *lanes = c->cone ? &fz_cone_lanes : &fz_sphere_lanes;
    ++*(c->cone ? &fz_cone_cases : &fz_sphere_cases);
    cylray_prepared P;
    const int valid = (c->cone ? cylray_prepare_cone(&P, &c->con)
                               : cylray_prepare_sphere(&P, &c->sph)) == CYLRAY_OK;
    if (!valid)
        memset(&P, 0, sizeof P); /* what a careless caller passes on: must give nothing */
#ifdef HAVE_CYLREF
    if (valid != (c->cone ? conref_valid(&c->con) : sphref_valid(&c->sph))) {
        snprintf(why, whylen, "prepare %s a %s the reference calls %s",
                 valid ? "accepted" : "refused", shape, valid ? "invalid" : "valid");
        return 1;
    }
    static cylref_band band[2][G_MAX];
    int judged[G_MAX] = {0};
    for (size_t i = 0; valid && i < c->n; i++) {
        float r[G_NFIELD];
        for (int f = 0; f < G_NFIELD; f++)
            r[f] = c->rays.f[f][i];
        if (!in_range(c, r))
            continue;
        judged[i] = 1;
        for (int cull = 0; cull < 2; cull++) {
            const unsigned fl = cull ? CYLRAY_CULL_BACK : 0u;
            if (c->cone)
                conref_band_eval(&c->con, r + G_OX, r + G_DX, r[G_TMIN], r[G_TMAX], fl,
                                 &band[cull][i]);
            else
                sphref_band_eval(&c->sph, r + G_OX, r + G_DX, r[G_TMIN], r[G_TMAX], fl,
                                 &band[cull][i]);
        }
    }
#endif
    static gresult res, occ;
    for (int ii = 0; ii < nisa; ii++) {
        const cylray_kernels *k = isas[ii];
        const long before = tc_failures_;
        g_intersect(k, c->width, &P, &c->rays, c->n, c->active, c->flags, c->misalign, &res);
        g_occluded(k, c->width, &P, &c->rays, c->n, c->active, c->flags, c->misalign, &occ);
        if (tc_failures_ != before) {
            snprintf(why, whylen, "%s broke the memory contract (see above)", k->name);
            return 1;
        }
        if (occ.hit != res.hit) {
            snprintf(why, whylen, "%s: occluded %#llx, intersect %#llx", k->name,
                     (unsigned long long)occ.hit, (unsigned long long)res.hit);
            return 1;
        }
        if (!valid && res.hit) {
            snprintf(why, whylen, "%s: hits with a %s prepare refused", k->name, shape);
            return 1;
        }
#ifdef HAVE_CYLREF
        const int cull = (c->flags & CYLRAY_CULL_BACK) != 0;
        const double tol = (c->flags & CYLRAY_FAST) ? 8 : 4;
        for (size_t i = 0; i < c->n; i++) {
            if (!judged[i] || (c->width != G_STREAM && !((c->active >> i) & 1u)))
                continue;
            const cylref_band *b = &band[cull][i];
            ++*lanes;
            const int hit = (int)((res.hit >> i) & 1u);
            double ub = 0;
            const int v = cylref_judge(b, hit, hit ? res.part[i] : 0, hit ? res.t[i] : 0, &ub);
            if (v || ub > tol) {
                snprintf(why, whylen,
                         "%s ray %zu: %s t %a part %#x; exact %s t %a part %#x, band [%a, %a] "
                         "hit_unstable %d part_unstable %d (verdict %d, %.3g ulps beyond)",
                         k->name, i, hit ? "hit" : "miss", hit ? (double)res.t[i] : 0.0,
                         hit ? (unsigned)res.part[i] : 0u, b->exact.hit ? "hit" : "miss",
                         b->exact.t, (unsigned)b->exact.part, b->t_lo, b->t_hi, b->hit_unstable,
                         b->part_unstable, v, ub);
                return 1;
            }
            if (!hit || !(c->flags & CYLRAY_NORMAL) || res.part[i] != b->exact.part)
                continue;
            const float n[3] = {res.nx[i], res.ny[i], res.nz[i]};
            const double len =
                sqrt((double)n[0] * n[0] + (double)n[1] * n[1] + (double)n[2] * n[2]);
            const double sg =
                (c->flags & CYLRAY_FACE_FORWARD) && (res.part[i] & CYLRAY_BACKFACE) ? -1 : 1;
            const double en[3] = {sg * b->exact.n[0], sg * b->exact.n[1], sg * b->exact.n[2]};
            const double ang = cylref_angle(n, en);
            if (!(fabs(len - 1) <= 1e-5) || !(ang <= 1e-6 + b->n_spread)) {
                snprintf(why, whylen,
                         "%s ray %zu: normal (%a, %a, %a), |n| %.9g, %.3g rad "
                         "from the exact one (spread %.3g)",
                         k->name, i, (double)n[0], (double)n[1], (double)n[2], len, ang,
                         b->n_spread);
                return 1;
            }
        }
#endif
    }
    return 0;
}
