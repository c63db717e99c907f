/* SPDX-License-Identifier: MIT */
/* test_sphref.c - tests of the exact sphere reference: an independent computation in
 * another precision and algebraic form, the band's verdicts on a double-precision solver,
 * and the generators (its hand-computed answers: test_hand.c). */
#include "sphgen.h"
#include "sphref.h"
#include "test_ref.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* The same question in long double (64 bits on x86, binary128 on AArch64) in another
 * form: the closest approach s = -(w.d)/(d.d), then t = s -+ sqrt((R^2 - |p|^2)/(d.d))
 * with p = w + s d. Returns 0 (miss), 1 near, 2 far; *t, *h2 (R^2 - |p|^2). */
static int ld_solve(const sphgen_case *c, unsigned flags, long double *t, long double *h2)
{
    long double w[3], d[3], A = 0, B = 0, pp = 0, R = c->sph.radius;
    for (int k = 0; k < 3; k++) {
        w[k] = (long double)c->o[k] - c->sph.center[k];
        d[k] = c->d[k];
        A += d[k] * d[k];
        B += w[k] * d[k];
    }
    long double s = -B / A;
    for (int k = 0; k < 3; k++) {
        long double p = w[k] + s * d[k];
        pp += p * p;
    }
    *h2 = R * R - pp;
    if (*h2 < 0)
        return 0;
    long double dt = sqrtl(*h2 / A), tn = s - dt, tf = s + dt;
    if (tn >= c->tmin && tn <= c->tmax) {
        *t = tn;
        return 1;
    }
    if (!(flags & CYLRAY_CULL_BACK) && tf >= c->tmin && tf <= c->tmax) {
        *t = tf;
        return 2;
    }
    return 0;
}

typedef struct {
    int compared, hits;
} ld_counts;

static void compare(void *ctx, const void *cv, const char *cat, int i, unsigned flags)
{
    const sphgen_case *c = cv;
    ld_counts *n = ctx;
    long double t = 0, h2;
    int x = ld_solve(c, flags, &t, &h2);
    cylref_hit r;
    sphref_intersect(&c->sph, c->o, c->d, c->tmin, c->tmax, flags, &r);
    /* Skip what long double cannot decide: near tangency or near an end of the
     * interval. */
    long double R2 = (long double)c->sph.radius * c->sph.radius;
    if (fabsl(h2) < 1e-9L * R2)
        return;
    long double dn = sqrtl(fabsl(h2)) / c->sph.radius;
    (void)dn;
    if (r.hit &&
        (fabs(r.t - c->tmin) <= 1e-9 * fabs(r.t) || fabs(r.t - c->tmax) <= 1e-9 * fabs(r.t)))
        return;
    n->compared++;
    n->hits += r.hit;
    CHECK(r.hit == (x != 0), "%s #%d flags %u: ref %d, long double %d", cat, i, flags, r.hit,
          x);
    if (!r.hit || !x)
        return;
    CHECK(((r.part & CYLRAY_BACKFACE) != 0) == (x == 2), "%s #%d: part %#x vs %d", cat, i,
          r.part, x);
    /* The long double form's error grows with |w|/|d| (the shift) and with the condition
     * of the root; 1e-3 float ulps of that is far above it. */
    double scale = 0, dd = 0;
    for (int k = 0; k < 3; k++) {
        double wk = (double)c->o[k] - c->sph.center[k];
        scale += wk * wk;
        dd += (double)c->d[k] * c->d[k];
    }
    scale = fmax(sqrt(scale / dd), fabs(r.t));
    CHECK(fabs(r.t - (double)t) <= 1e-3 * cylref_float_ulp(scale) + 1e-30,
          "%s #%d: t %.17g vs %.17Lg", cat, i, r.t, t);
    double len = sqrt(r.n[0] * r.n[0] + r.n[1] * r.n[1] + r.n[2] * r.n[2]);
    CHECK(fabs(len - 1) < 1e-14, "%s #%d: |n| %.17g", cat, i, len);
}

static void test_independent(void)
{
    const int cats[] = {SPHGEN_ORDINARY, SPHGEN_FAR,          SPHGEN_INSIDE, SPHGEN_TINY,
                        SPHGEN_HUGE,     SPHGEN_UNNORMALIZED, SPHGEN_CAMERA};
    ld_counts n = {0, 0};
    ref_each_case(&ref_sphere_gen, cats, sizeof cats / sizeof cats[0], 11, 600, compare, &n);
    printf("sphref vs long double: %d compared, %d hits\n", n.compared, n.hits);
    CHECK(n.compared > 3000 && n.hits > 1000, "too few compared: %d, %d hits", n.compared,
          n.hits);
}

/* A float kernel that solves in double with the stable formulas and rounds once: it
 * must be inside every band (the band is not too tight), and one off by 16 ulps
 * outside it (the band is not too loose). */
static int dbl_solve(const sphgen_case *c, unsigned flags, float *t, int *part)
{
    double w[3], d[3], x[3], A = 0, B = 0, C = 0, R = c->sph.radius;
    if (c->tmin != c->tmin || c->tmax != c->tmax)
        return 0;
    for (int k = 0; k < 3; k++) {
        if (!isfinite(c->o[k]) || !isfinite(c->d[k]))
            return 0;
        w[k] = (double)c->o[k] - c->sph.center[k];
        d[k] = c->d[k];
    }
    for (int k = 0; k < 3; k++)
        x[k] = w[(k + 1) % 3] * d[(k + 2) % 3] - w[(k + 2) % 3] * d[(k + 1) % 3];
    for (int k = 0; k < 3; k++) {
        A += d[k] * d[k];
        B += w[k] * d[k];
        C += w[k] * w[k];
    }
    double D = A * R * R - (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
    if (!(D >= 0) || !(A > 0))
        return 0;
    double sq = sqrt(D), q = -(B + copysign(sq, B));
    double r1 = q / A, r2 = q != 0 ? (C - R * R) / q : r1;
    double tn = fmin(r1, r2), tf = fmax(r1, r2);
    if (tn >= c->tmin && tn <= c->tmax) {
        *t = (float)tn;
        *part = CYLRAY_SIDE;
        return 1;
    }
    if (!(flags & CYLRAY_CULL_BACK) && tf >= c->tmin && tf <= c->tmax) {
        *t = (float)tf;
        *part = CYLRAY_SIDE | CYLRAY_BACKFACE;
        return 1;
    }
    return 0;
}

static void test_band(void)
{
    enum { N = 192 };
    static sphgen_case cs[N];
    for (int cat = 0; cat < SPHGEN_COUNT; cat++) {
        sphgen_make(cat, 3, N, cs);
        int hits = 0, unstable = 0, bad = 0, caught = 0, caught_of = 0;
        double worst = 0, wsum = 0;
        int wn = 0;
        for (int i = 0; i < N; i++) {
            const sphgen_case *c = &cs[i];
            for (unsigned flags = 0; flags <= CYLRAY_CULL_BACK; flags += CYLRAY_CULL_BACK) {
                cylref_band b;
                sphref_band_eval(&c->sph, c->o, c->d, c->tmin, c->tmax, flags, &b);
                hits += b.exact.hit;
                if (b.exact.hit) {
                    wsum += 0.5 * (b.t_hi - b.t_lo) / cylref_float_ulp(b.exact.t);
                    wn++;
                }
                unstable += b.decision_unstable;
                if (b.exact.hit)
                    CHECK(b.t_lo <= b.exact.t && b.exact.t <= b.t_hi,
                          "%s #%d: exact outside its band", sphgen_category_name(cat), i);
                float t = 0;
                int part = 0, hit = dbl_solve(c, flags, &t, &part);
                double ub;
                int v = sphref_judge(&b, hit, part, t, &ub);
                if (v || ub > 1) {
                    bad++;
                    if (bad < 4)
                        printf("  %s #%d flags %u: double solver judged %d, %.3g ulps beyond "
                               "(exact %d t %.9g part %#x, got %d t %.9g part %#x)\n",
                               sphgen_category_name(cat), i, flags, v, ub, b.exact.hit,
                               b.exact.t, b.exact.part, hit, (double)t, part);
                }
                if (!v && hit)
                    worst = fmax(worst, ub);
                caught += ref_catch_defects(sphref_judge, &b, &caught_of);
            }
        }
        printf("sph band %-16s %4d/%d hits, %4d unstable, double solver: %d judged bad, worst "
               "%.3g ulps beyond; %d/%d defects caught; band +-%.3g ulps on average\n",
               sphgen_category_name(cat), hits, 2 * N, unstable, bad, worst, caught,
               3 * caught_of, wn ? wsum / wn : 0.0);
        CHECK(bad == 0, "%s: the double solver fails its bands %d times",
              sphgen_category_name(cat), bad);
        CHECK(caught == 3 * caught_of, "%s: defects missed", sphgen_category_name(cat));
        if (cat != SPHGEN_BAD && cat != SPHGEN_GRAZING && cat != SPHGEN_SURFACE)
            CHECK(caught_of > N / 4, "%s: too few stable hits %d", sphgen_category_name(cat),
                  caught_of);
        if (cat != SPHGEN_BAD)
            CHECK(hits > N / 4, "%s: too few hits %d", sphgen_category_name(cat), hits);
        if (cat == SPHGEN_ORDINARY || cat == SPHGEN_INSIDE || cat == SPHGEN_CAMERA)
            CHECK(unstable < N / 10, "%s: too many unstable %d", sphgen_category_name(cat),
                  unstable);
    }
}

void test_sphref(void)
{
    ref_run_generators(&ref_sphere_gen);
    test_independent();
    test_band();
}
