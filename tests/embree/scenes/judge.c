/* SPDX-License-Identifier: MIT */
/* judge.c - classifies a variant's answers against the exact reference. */
#include "judge.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int eb_err_init(eb_err *e, size_t cap)
{
    memset(e, 0, sizeof *e);
    e->t_ulps = malloc((cap ? cap : 1) * sizeof *e->t_ulps);
    e->t_beyond = malloc((cap ? cap : 1) * sizeof *e->t_beyond);
    e->n_rad = malloc((cap ? cap : 1) * sizeof *e->n_rad);
    return e->t_ulps && e->t_beyond && e->n_rad ? 0 : -1;
}

void eb_err_free(eb_err *e)
{
    free(e->t_ulps);
    free(e->t_beyond);
    free(e->n_rad);
    memset(e, 0, sizeof *e);
}

void eb_sample_solve(eb_sample *s, const eb_ref *ref)
{
    s->xhit = eb_ref_closest(ref, s->o, s->d, s->tmin, s->tmax, &s->xid, &s->xh);
}

/* Would a float kernel be excused for answering `hit` (at t) on cylinder id? */
static int excused(const eb_ref *ref, const eb_sample *s, uint32_t id, int hit, float t)
{
    cylref_band b;
    eb_shape_band(ref->s, id, s->o, s->d, s->tmin, s->tmax, &b);
    if (b.hit_unstable)
        return 1;
    if (!hit)
        return 0;
    double beyond = 0;
    int j = cylref_judge(&b, 1, b.exact.part, t, &beyond);
    return j != 1 && beyond <= 4;
}

static double angle_unsigned(const float n[3], const double x[3])
{
    float m[3] = {-n[0], -n[1], -n[2]};
    return fmin(cylref_angle(n, x), cylref_angle(m, x));
}

void eb_judge(eb_err *e, const eb_ref *ref, const eb_sample *s, uint32_t vprim, float vt,
              const float vng[3])
{
    int vhit = vprim != RTC_INVALID_GEOMETRY_ID;
    e->rays++;
    if (!vhit && !s->xhit)
        return;
    if (vhit && s->xhit && vprim == s->xid) {
        double u = cylref_ulps(vt, s->xh.t);
        if (u > 64 && !excused(ref, s, vprim, 1, vt)) {
            /* the right cylinder, the wrong surface of it (e.g. its far side) */
            e->wrong++;
            if (vt > s->xh.t)
                e->leak++;
            else
                e->phantom++;
            return;
        }
        /* past a few ulps, part of the error is what the float inputs leave open (a
         * near-parallel ray's side hit, a graze): the band says how much is not */
        double beyond = 0;
        if (u > 2) {
            cylref_band b;
            eb_shape_band(ref->s, vprim, s->o, s->d, s->tmin, s->tmax, &b);
            cylref_judge(&b, 1, s->xh.part, vt, &beyond);
        }
        e->t_beyond[e->nt] = beyond;
        e->t_ulps[e->nt++] = u;
        e->n_rad[e->nn++] = angle_unsigned(vng, s->xh.n);
        return;
    }
    if (vhit && s->xhit) {
        /* another cylinder at the same place (a joint, a crossing, a shared stretch):
         * a tie, not an error. Where t is small against the coordinates, their
         * rounding decides which is first. */
        float m = fmaxf(fabsf(s->o[0]), fmaxf(fabsf(s->o[1]), fabsf(s->o[2])));
        double dl = sqrt((double)s->d[0] * s->d[0] + (double)s->d[1] * s->d[1] +
                         (double)s->d[2] * s->d[2]);
        double tol = 8 * fmax(cylref_float_ulp(s->xh.t), cylref_float_ulp(m) / dl);
        if (fabs(vt - s->xh.t) <= tol)
            return;
    }
    int leak = s->xhit && (!vhit || vt > s->xh.t);
    int ok = leak ? excused(ref, s, s->xid, 0, 0) : excused(ref, s, vprim, 1, vt);
    if (ok) {
        e->excused++;
        return;
    }
    e->wrong++;
    if (leak)
        e->leak++;
    else
        e->phantom++;
}

void eb_judge_secondary(eb_err *e, const eb_sample *s, const float w[3], uint32_t vprim)
{
    if (!s->xhit || (s->xh.part & CYLRAY_BACKFACE))
        return;
    double c = w[0] * s->xh.n[0] + w[1] * s->xh.n[1] + w[2] * s->xh.n[2];
    if (c <= 0)
        return;
    e->sec++;
    if (vprim == s->xid)
        e->self++;
}

/* NaN (a NaN t or normal from a variant) sorts last, so that it shows as the maximum. */
static int cmp_d(const void *pa, const void *pb)
{
    double a = *(const double *)pa, b = *(const double *)pb;
    if (isnan(a) || isnan(b))
        return isnan(a) - isnan(b);
    return a < b ? -1 : a > b;
}

void eb_quantiles(double *v, size_t n, double *med, double *p99, double *max)
{
    if (!n) {
        *med = *p99 = *max = NAN;
        return;
    }
    qsort(v, n, sizeof *v, cmp_d);
    *med = v[(n - 1) / 2];
    *p99 = v[(size_t)(0.99 * (double)(n - 1))];
    *max = v[n - 1];
}
