/* SPDX-License-Identifier: MIT */
/* test_conref.c - tests of the exact cone reference: hand-computed answers (tips, rims,
 * the apex, the discs and open ends), an independent computation in another precision
 * and algebraic form, the band's consistency, and the generators. */
#include "congen.h"
#include "conref.h"
#include "test_ref.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define R2 0.70710678118654752440

static void test_cone_hand(void)
{
    const float I = INFINITY;
    const int S = CYLRAY_SIDE, SB = CYLRAY_SIDE | CYLRAY_BACKFACE, LO = CYLRAY_CAP_LO,
              HI = CYLRAY_CAP_HI, B = CYLRAY_BACKFACE;
    const unsigned FF = CYLRAY_FACE_FORWARD, CB = CYLRAY_CULL_BACK;
    /* A tip cone: radius 2 at z = 0, the apex at z = 2, slope -1. */
    const cylray_cone tip = {{0, 0, 0}, {0, 0, 2}, 2, 0, CYLRAY_CAPPED_LO};
    const cylray_cone tip_open = {{0, 0, 0}, {0, 0, 2}, 2, 0, 0};
    /* A frustum: radius 1 at z = 0, 2 at z = 2. */
    const cylray_cone fr = {{0, 0, 0}, {0, 0, 2}, 1, 2, CYLRAY_CAPPED};
    const cylray_cone fr_lo = {{0, 0, 0}, {0, 0, 2}, 1, 2, CYLRAY_CAPPED_LO};
    const cylray_cone cyl = {{0, 0, -1}, {0, 0, 1}, 1, 1, CYLRAY_CAPPED};
    const ref_hand cases[] = {
        {"side at r(1)", {.cone = tip}, {5, 0, 1}, {-1, 0, 0}, 0, I, 0, 1, 4, S, {R2, 0, R2}},
        {"side exit", {.cone = tip}, {0, 0, 1}, {-1, 0, 0}, 0, I, 0, 1, 1, SB, {-R2, 0, R2}},
        {"side exit, ff",
         {.cone = tip},
         {0, 0, 1},
         {-1, 0, 0},
         0,
         I,
         FF,
         1,
         1,
         SB,
         {R2, 0, -R2}},
        {"side exit, culled", {.cone = tip}, {0, 0, 1}, {-1, 0, 0}, 0, I, CB, 0, 0, 0, {0}},
        {"disc at p0", {.cone = tip}, {0.5f, 0, -5}, {0, 0, 1}, 0, I, 0, 1, 5, LO, {0, 0, -1}},
        {"open end: in through the hole, out the side",
         {.cone = tip_open},
         {0.5f, 0, -5},
         {0, 0, 1},
         0,
         I,
         0,
         1,
         6.5,
         SB,
         {R2, 0, R2}},
        {"disc at p1", {.cone = fr}, {0, 0, 5}, {0, 0, -1}, 0, I, 0, 1, 3, HI, {0, 0, 1}},
        {"disc at p1 from inside",
         {.cone = fr},
         {0, 0, 1},
         {0, 0, 1},
         0,
         I,
         0,
         1,
         1,
         HI | B,
         {0, 0, 1}},
        {"disc at p1 from inside, culled",
         {.cone = fr},
         {0, 0, 1},
         {0, 0, 1},
         0,
         I,
         CB,
         0,
         0,
         0,
         {0}},
        {"open p1: out through the hole",
         {.cone = fr_lo},
         {0, 0, 1},
         {0, 0, 1},
         0,
         I,
         0,
         0,
         0,
         0,
         {0}},
        {"open p1: in through the hole, out the disc",
         {.cone = fr_lo},
         {0, 0, 5},
         {0, 0, -1},
         0,
         I,
         0,
         1,
         5,
         LO | B,
         {0, 0, -1}},
        /* Widening side: n = (e - k u)/|..| with k = 1/2. */
        {"frustum side",
         {.cone = fr},
         {5, 0, 1},
         {-1, 0, 0},
         0,
         I,
         0,
         1,
         3.5,
         S,
         {2 / 2.2360679774997897, 0, -1 / 2.2360679774997897}},
        {"mirror nappe left out", {.cone = tip}, {5, 0, 3}, {-1, 0, 0}, 0, I, 0, 0, 0, 0, {0}},
        {"beyond the slab", {.cone = fr}, {5, 0, 2.5f}, {-1, 0, 0}, 0, I, 0, 0, 0, 0, {0}},
        {"through the apex", {.cone = tip}, {-1, 0, 4}, {1, 0, -2}, 0, I, 0, 1, 1, S, {0}},
        {"tmax short", {.cone = tip}, {5, 0, 1}, {-1, 0, 0}, 0, 3.5f, 0, 0, 0, 0, {0}},
        {"tmin past the entry",
         {.cone = tip},
         {5, 0, 1},
         {-1, 0, 0},
         4.5f,
         I,
         0,
         1,
         6,
         SB,
         {-R2, 0, R2}},
        {"r0 == r1 is the cylinder",
         {.cone = cyl},
         {5, 0, 0},
         {-1, 0, 0},
         0,
         I,
         0,
         1,
         4,
         S,
         {1, 0, 0}},
        {"unnormalized d", {.cone = tip}, {5, 0, 1}, {-4, 0, 0}, 0, I, 0, 1, 1, S, {R2, 0, R2}},
        {"NaN origin", {.cone = tip}, {NAN, 0, 1}, {-1, 0, 0}, 0, I, 0, 0, 0, 0, {0}},
        {"zero direction", {.cone = tip}, {5, 0, 1}, {0, 0, 0}, 0, I, 0, 0, 0, 0, {0}},
    };
    ref_run_hand(&ref_cone, cases, sizeof cases / sizeof cases[0]);

    /* A ray down x = 2 touches the rim of the frustum's disc at p1 from outside the
     * side: the side (a back face there, the side leaning outward) and the disc are
     * both at t = 3, and the band must allow either, and a miss (2 ulps further out). */
    {
        const float o[3] = {2, 0, 5}, d[3] = {0, 0, -1};
        cylref_band b;
        double beyond;
        conref_band_eval(&fr, o, d, 0, INFINITY, 0, &b);
        CHECK(b.exact.hit && fabs(b.exact.t - 3) < 1e-15, "rim: t %.17g", b.exact.t);
        CHECK(conref_judge(&b, 1, CYLRAY_CAP_HI, 3, &beyond) == 0, "rim: the disc refused");
        CHECK(conref_judge(&b, 1, CYLRAY_SIDE | CYLRAY_BACKFACE, 3, &beyond) == 0,
              "rim: the side refused");
        CHECK(b.hit_unstable && conref_judge(&b, 0, 0, 0, &beyond) == 0, "rim: a miss refused");
        CHECK(conref_judge(&b, 1, CYLRAY_CAP_LO, 3, &beyond) != 0, "rim: the wrong disc");
    }

    const ref_shape bad[] = {
        {.cone = {{NAN, 0, 0}, {0, 0, 1}, 1, 1, 0}},
        {.cone = {{0, 0, 0}, {0, INFINITY, 1}, 1, 1, 0}},
        {.cone = {{0, 0, 0x1p63f}, {0, 0, 1}, 1, 1, 0}},
        {.cone = {{0, 0, 1}, {0, 0, 1}, 1, 2, 0}},
        {.cone = {{0, 0, 0}, {0, 0, 1}, 0, 0, 0}},
        {.cone = {{0, 0, 0}, {0, 0, 1}, -1, 1, 0}},
        {.cone = {{0, 0, 0}, {0, 0, 1}, NAN, 1, 0}},
        {.cone = {{0, 0, 0}, {0, 0, 1}, 1, 0x1p-61f, 0}},
        {.cone = {{0, 0, 0}, {0, 0, 1}, 0x1p63f, 1, 0}},
        {.cone = {{0, 0, 0}, {0, 0, 1}, 1, 1, 4}},
        {.cone = {{0, 0, 0}, {0, 0, 0x1p-140f}, 1, 1, 0}},
        {.cone = {{0, 0, 0}, {0, 0, 0x1p-126f}, 0, 0x1p62f, 1}}, /* too steep */
        {.cone = {{0, 0, 0}, {0, 0, 1}, 0, 0x1.000002p31f, 0}},  /* too wide for its slope */
    };
    const float o[3] = {0, 0, -5}, d[3] = {0, 0, 1};
    ref_run_refused(&ref_cone, bad, sizeof bad / sizeof bad[0], o, d);
    const ref_shape edge[] = {{.cone = {{0x1p62f, 0, 0}, {0, 0, -0x1p62f}, 0x1p-60f, 0, 3}},
                              {.cone = {{0, 0, 0}, {0, 0, 0x1p-100f}, 0, 0x1p-60f, 1}},
                              {.cone = {{0, 0, 0}, {0, 0, 1}, 0, 0x1p30f, 1}},
                              {.cone = {{0, 0, 0}, {0, 0, 0x1p22f}, 0x1p62f, 0x1p62f, 3}}};
    ref_run_valid(&ref_cone, edge, sizeof edge / sizeof edge[0]);
}

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

static void test_independent(void)
{
    enum { N = 160 };
    static congen_case cs[N];
    const int cats[] = {CONGEN_ORDINARY, CONGEN_INSIDE, CONGEN_CAMERA, CONGEN_FLAT,
                        CONGEN_APEX};
    long compared = 0;
    for (size_t ci = 0; ci < sizeof cats / sizeof *cats; ci++) {
        congen_make(cats[ci], 77, N, cs);
        for (int i = 0; i < N; i++) {
            const congen_case *c = &cs[i];
            for (unsigned fl = 0; fl <= CYLRAY_CULL_BACK; fl += CYLRAY_CULL_BACK) {
                cylref_band b;
                conref_band_eval(&c->cone, c->o, c->d, c->tmin, c->tmax, fl, &b);
                if (b.decision_unstable)
                    continue;
                long double t = 0;
                int part = 0;
                int hit = ld_solve(c, fl, &t, &part);
                compared++;
                CHECK(hit == b.exact.hit, "%s #%d flags %u: ld hit %d, ref %d",
                      congen_category_name(cats[ci]), i, fl, hit, b.exact.hit);
                if (!hit || !b.exact.hit)
                    continue;
                CHECK(part == b.exact.part, "%s #%d: ld part %#x, ref %#x",
                      congen_category_name(cats[ci]), i, (unsigned)part,
                      (unsigned)b.exact.part);
                CHECK(fabsl(t - (long double)b.exact.t) <= 1e-12L * (fabsl(t) + 1e-30L) ||
                          fabsl(t - (long double)b.exact.t) <= 1e-9L * (b.t_hi - b.t_lo),
                      "%s #%d: ld t %.17Lg, ref %.17g", congen_category_name(cats[ci]), i, t,
                      b.exact.t);
            }
        }
    }
    CHECK(compared > 1000, "only %ld stable cases compared", compared);
}

void test_conref(void)
{
    test_cone_hand();
    ref_run_generators(&ref_cone_gen);
    test_independent();
}
