/* SPDX-License-Identifier: MIT */
/* test_conref.c - tests of the exact cone reference: an independent computation in another
 * precision and algebraic form, and the generators (its hand-computed answers, of tips,
 * rims, the apex, the discs and open ends: test_hand.c). */
#include "congen.h"
#include "conref.h"
#include "test_ref.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* The same question in long double and another form: world coordinates from p0, the
 * textbook quadratic F(t) = |q + t d|^2 - (zq + t zd)^2 - (r0 + k (zq + t zd))^2 with no
 * frame and no stable root formula, then each disc by its plane. */
static int ld_solve(const congen_case *c, unsigned flags, long double *t, int *part)
{
    long double a[3], q[3], u[3], L = 0;
    for (int k = 0; k < 3; k++) {
        a[k] = (long double)c->cone.p1[k] - c->cone.p0[k];
        q[k] = (long double)c->o[k] - c->cone.p0[k];
        L += a[k] * a[k];
    }
    L = sqrtl(L);
    for (int k = 0; k < 3; k++)
        u[k] = a[k] / L;
    long double zq = 0, zd = 0, qq = 0, qd = 0, dd = 0;
    for (int k = 0; k < 3; k++) {
        zq += q[k] * u[k];
        zd += c->d[k] * u[k];
        qq += q[k] * q[k];
        qd += q[k] * c->d[k];
        dd += (long double)c->d[k] * c->d[k];
    }
    const long double r0 = c->cone.r0, kk = ((long double)c->cone.r1 - r0) / L;
    const long double a2 = dd - zd * zd - kk * kk * zd * zd;
    const long double a1 = 2 * (qd - zq * zd - kk * zd * (r0 + kk * zq));
    const long double a0 = qq - zq * zq - (r0 + kk * zq) * (r0 + kk * zq);
    long double cand[4];
    int cpart[4], n = 0;
    const long double disc = a1 * a1 - 4 * a2 * a0;
    if (disc >= 0 && a2 != 0) {
        const long double s = sqrtl(disc);
        const long double ts[2] = {(-a1 - s) / (2 * a2), (-a1 + s) / (2 * a2)};
        for (int i = 0; i < 2; i++) {
            const long double z = zq + ts[i] * zd;
            if (z < 0 || z > L)
                continue;
            /* the facing: the sign of F'(t) */
            cand[n] = ts[i];
            cpart[n++] = CYLRAY_SIDE | (2 * a2 * ts[i] + a1 > 0 ? CYLRAY_BACKFACE : 0);
        }
    }
    for (int e = 0; e < 2; e++) {
        const long double rad = e ? c->cone.r1 : c->cone.r0;
        if (!(c->cone.flags & (e ? CYLRAY_CAPPED_HI : CYLRAY_CAPPED_LO)) || zd == 0 || rad == 0)
            continue;
        const long double tt = ((e ? L : 0) - zq) / zd;
        long double x2 = 0;
        for (int k = 0; k < 3; k++) {
            long double x = q[k] + tt * c->d[k];
            x2 += x * x;
        }
        const long double z = zq + tt * zd;
        if (x2 - z * z > rad * rad)
            continue;
        cand[n] = tt;
        cpart[n++] =
            (e ? CYLRAY_CAP_HI : CYLRAY_CAP_LO) | ((e ? zd > 0 : zd < 0) ? CYLRAY_BACKFACE : 0);
    }
    int best = -1;
    for (int i = 0; i < n; i++) {
        if (cand[i] < c->tmin || cand[i] > c->tmax)
            continue;
        if ((flags & CYLRAY_CULL_BACK) && (cpart[i] & CYLRAY_BACKFACE))
            continue;
        if (best < 0 || cand[i] < cand[best])
            best = i;
    }
    if (best < 0)
        return 0;
    *t = cand[best];
    *part = cpart[best];
    return 1;
}

static void compare(void *ctx, const void *cv, const char *cat, int i, unsigned fl)
{
    const congen_case *c = cv;
    cylref_band b;
    conref_band_eval(&c->cone, c->o, c->d, c->tmin, c->tmax, fl, &b);
    if (b.decision_unstable)
        return;
    long double t = 0;
    int part = 0;
    int hit = ld_solve(c, fl, &t, &part);
    ++*(long *)ctx;
    CHECK(hit == b.exact.hit, "%s #%d flags %u: ld hit %d, ref %d", cat, i, fl, hit,
          b.exact.hit);
    if (!hit || !b.exact.hit)
        return;
    CHECK(part == b.exact.part, "%s #%d: ld part %#x, ref %#x", cat, i, (unsigned)part,
          (unsigned)b.exact.part);
    CHECK(fabsl(t - (long double)b.exact.t) <= 1e-12L * (fabsl(t) + 1e-30L) ||
              fabsl(t - (long double)b.exact.t) <= 1e-9L * (b.t_hi - b.t_lo),
          "%s #%d: ld t %.17Lg, ref %.17g", cat, i, t, b.exact.t);
}

static void test_independent(void)
{
    const int cats[] = {CONGEN_ORDINARY, CONGEN_INSIDE, CONGEN_CAMERA, CONGEN_FLAT,
                        CONGEN_APEX};
    long compared = 0;
    ref_each_case(&ref_cone_gen, cats, sizeof cats / sizeof *cats, 77, 160, compare, &compared);
    CHECK(compared > 1000, "only %ld stable cases compared", compared);
}

void test_conref(void)
{
    ref_run_generators(&ref_cone_gen);
    test_independent();
}
