/* SPDX-License-Identifier: MIT */
/* sphere_test.c - the toolkit for spheres: bounds, leaf bounds, boxes across z, surface
 * coordinates, against exact arithmetic (binary128; long double for the angles).
 *
 *   sphere_test box      each face of cylray_bounds on the outer side of c_k -+ R (exact)
 *                        and the float next to it (the smallest box); points of the
 *                        exact sphere inside; leaves of 4, 8 and 16 spheres: the union
 *   sphere_test split    cylray_split_boxes: k = 0 gives 1 box, the sphere's; k slices
 *                        across z each on the outer side of its slice's exact box and at
 *                        most one float beyond the nearest; points of the sphere inside
 *                        the box of their slice
 *   sphere_test surface  u, v, dpdu and dpdv against the same formulas in long double
 *                        at the exact point p - c: u and v within a float ulp, the
 *                        derivatives within 2^-20 of their length; the leaf forms equal
 *                        the prepared one; parts other than the side write nothing
 *
 * CYLRAY_TEST_QUICK=1 shrinks the counts tenfold. */
#include "cylray.h"
#include "cylref.h"
#include "gen.h"
#include "quad.h"
#include "spawnref.h"
#include "tcheck.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static long scale = 1;

static double uni(cylgen_rng *r, double a, double b)
{
    return a + (b - a) * cylgen_uniform(r);
}

/* A mantissa in [1, 2) times 2^e, e uniform in [lo, hi): the exponent drawn first. */
static double binade(cylgen_rng *r, double lo, double hi)
{
    const int e = (int)uni(r, lo, hi);
    return ldexp(1 + cylgen_uniform(r), e);
}

static void make_sphere(cylgen_rng *r, int kind, cylray_sphere *s)
{
    double R;
    switch (kind % 4) {
    case 0:
        R = pow(10, uni(r, -3, 3));
        break;
    case 1:
        R = pow(10, uni(r, -4, 4));
        break;
    case 2:
        R = binade(r, -60, -40);
        break;
    default:
        R = binade(r, 40, 58);
        break;
    }
    const double spread = kind % 4 == 1 ? pow(10, uni(r, 3, 6)) * (1 + R) : R * uni(r, 0, 8);
    for (int k = 0; k < 3; k++)
        s->center[k] = (float)(spread * uni(r, -1, 1));
    if (cylgen_uniform(r) < 0.1) /* exactly at the origin, or on a coordinate plane */
        s->center[(int)(cylgen_next(r) % 3)] = 0.0f;
    s->radius = (float)R;
}

/* 1 where the float face f lies on the outer side of the exact value x (dir -1: below,
 * +1: above) and the float next to f toward x does not. */
static int face_ok(float f, cylq x, int dir, int tight_only_one)
{
    const cylq F = (cylq)f;
    if (dir < 0 ? !(F <= x) : !(F >= x))
        return 0;
    /* one step in: then inside (the nearest), or at most one more step */
    float g = nextafterf(f, dir < 0 ? INFINITY : -INFINITY);
    if (dir < 0 ? (cylq)g <= x : (cylq)g >= x) {
        if (!tight_only_one)
            return 0;
        g = nextafterf(g, dir < 0 ? INFINITY : -INFINITY);
        return dir < 0 ? !((cylq)g <= x) : !((cylq)g >= x);
    }
    return 1;
}

/* A point of the exact sphere near c + R u: inside [lo, hi] in binary128 terms where
 * the point is exact; floats of the directions are exact, the point c + R u in
 * binary128 (off the sphere by 2^-100 R: checked with that slack). */
static int inside(const float lo[3], const float hi[3], const cylray_sphere *s,
                  const double u[3])
{
    for (int k = 0; k < 3; k++) {
        const cylq x = (cylq)s->center[k] + (cylq)s->radius * (cylq)u[k];
        const cylq slack = (cylq)s->radius * (cylq)0x1p-90;
        if (x < (cylq)lo[k] - slack || x > (cylq)hi[k] + slack)
            return 0;
    }
    return 1;
}

static int run_box(void)
{
    const long N = 40000 / scale;
    cylgen_rng rng;
    cylgen_seed(&rng, 601);
    for (long i = 0; i < N; i++) {
        cylray_sphere s[16];
        for (int j = 0; j < 16; j++)
            make_sphere(&rng, (int)(i + j), &s[j]);
        cylray_prepared P;
        CHECK(cylray_prepare_sphere(&P, &s[0]) == CYLRAY_OK, "prepare");
        float lo[3], hi[3];
        CHECK(cylray_bounds(&P, lo, hi) == CYLRAY_OK, "bounds of a sphere");
        for (int k = 0; k < 3; k++) {
            const cylq c = s[0].center[k], R = s[0].radius;
            CHECK(face_ok(lo[k], c - R, -1, 0) && face_ok(hi[k], c + R, 1, 0),
                  "box face %d: c=%a R=%a lo=%a hi=%a (not the nearest float outside)", k,
                  (double)s[0].center[k], (double)s[0].radius, (double)lo[k], (double)hi[k]);
        }
        for (int j = 0; j < 8; j++) {
            double u[3];
            sref_unit(&rng, u);
            if (j < 6) /* the extreme points */
                u[0] = u[1] = u[2] = 0, u[j / 2] = j & 1 ? 1 : -1;
            CHECK(inside(lo, hi, &s[0], u), "a point of the sphere outside its box");
        }
        if (i % 8)
            continue;
        /* leaves: the union of the used lanes' boxes */
        const size_t n = 1 + (size_t)(cylgen_next(&rng) % 16);
        cylray_leaf16 l16;
        cylray_leaf8 l8;
        cylray_leaf4 l4;
        float L[3][3], H[3][3], u[3] = {INFINITY, INFINITY, INFINITY},
                                v[3] = {-INFINITY, -INFINITY, -INFINITY};
        for (size_t j = 0; j < n; j++) {
            float a[3], b[3];
            cylray_prepare_sphere(&P, &s[j]);
            cylray_bounds(&P, a, b);
            for (int k = 0; k < 3; k++)
                u[k] = fminf(u[k], a[k]), v[k] = fmaxf(v[k], b[k]);
        }
        CHECK(cylray_leaf_prepare_spheres16(&l16, s, NULL, n) == CYLRAY_OK, "leaf16");
        CHECK(cylray_leaf_bounds16(&l16, L[0], H[0]) == CYLRAY_OK, "leaf16 bounds");
        int same = 1;
        for (int k = 0; k < 3; k++)
            same &= tc_same(L[0][k], u[k]) && tc_same(H[0][k], v[k]);
        CHECK(same, "leaf16 bounds: not the union of the lanes' boxes");
        if (n <= 8) {
            CHECK(cylray_leaf_prepare_spheres8(&l8, s, NULL, n) == CYLRAY_OK, "leaf8");
            CHECK(cylray_leaf_bounds8(&l8, L[1], H[1]) == CYLRAY_OK, "leaf8 bounds");
            for (int k = 0; k < 3; k++)
                CHECK(tc_same(L[1][k], u[k]) && tc_same(H[1][k], v[k]), "leaf8 bounds");
        }
        if (n <= 4) {
            CHECK(cylray_leaf_prepare_spheres4(&l4, s, NULL, n) == CYLRAY_OK, "leaf4");
            CHECK(cylray_leaf_bounds4(&l4, L[2], H[2]) == CYLRAY_OK, "leaf4 bounds");
            for (int k = 0; k < 3; k++)
                CHECK(tc_same(L[2][k], u[k]) && tc_same(H[2][k], v[k]), "leaf4 bounds");
        }
    }
    return tc_report("sphere box");
}

static int run_split(void)
{
    const long N = 10000 / scale;
    cylgen_rng rng;
    cylgen_seed(&rng, 602);
    for (long i = 0; i < N; i++) {
        cylray_sphere s;
        make_sphere(&rng, (int)i, &s);
        cylray_prepared P;
        cylray_prepare_sphere(&P, &s);
        float lo[CYLRAY_SPLIT_MAX][3], hi[CYLRAY_SPLIT_MAX][3], bl[3], bh[3];
        cylray_bounds(&P, bl, bh);
        CHECK(cylray_split_boxes(&P, 0, NULL, NULL) == 1, "k = 0: one box");
        CHECK(cylray_split_boxes(&P, 0, lo, hi) == 1, "k = 0: one box");
        for (int k = 0; k < 3; k++)
            CHECK(tc_same(lo[0][k], bl[k]) && tc_same(hi[0][k], bh[k]),
                  "k = 0: the box of cylray_bounds");
        const size_t n = 1 + (size_t)(cylgen_next(&rng) % CYLRAY_SPLIT_MAX);
        CHECK(cylray_split_boxes(&P, n, lo, hi) == n, "k slices: k boxes");
        const cylq c[3] = {s.center[0], s.center[1], s.center[2]}, R = s.radius;
        for (size_t j = 0; j < n; j++) {
            const double qa = ((double)j * 2.0 - (double)n) / (double)n;
            const double qb = ((double)(j + 1) * 2.0 - (double)n) / (double)n;
            const double m = qa <= 0 && qb >= 0 ? 0.0 : fmin(fabs(qa), fabs(qb));
            const cylq mq = m, w = R * q_sqrt(1 - mq * mq);
            CHECK(face_ok(lo[j][2], c[2] + R * (cylq)qa, -1, 1) &&
                      face_ok(hi[j][2], c[2] + R * (cylq)qb, 1, 1),
                  "slice %zu of %zu: z faces %a %a", j, n, (double)lo[j][2], (double)hi[j][2]);
            for (int k = 0; k < 2; k++)
                CHECK(face_ok(lo[j][k], c[k] - w, -1, 1) && face_ok(hi[j][k], c[k] + w, 1, 1),
                      "slice %zu of %zu: face %d %a %a (R=%a, c=%a)", j, n, k, (double)lo[j][k],
                      (double)hi[j][k], (double)s.radius, (double)s.center[k]);
        }
        /* points of the sphere: each in the box of its slice */
        for (int t = 0; t < 16; t++) {
            double u[3];
            sref_unit(&rng, u);
            size_t j = (size_t)floor((u[2] + 1) * 0.5 * (double)n);
            if (j >= n)
                j = n - 1;
            const double qa = ((double)j * 2.0 - (double)n) / (double)n;
            const double qb = ((double)(j + 1) * 2.0 - (double)n) / (double)n;
            if (u[2] < qa || u[2] > qb)
                continue; /* at a boundary, rounded across it */
            CHECK(inside(lo[j], hi[j], &s, u), "a point of the sphere outside its slice's box");
        }
    }
    return tc_report("sphere split");
}

#define PI_L 3.141592653589793238462643383279502884L

/* The float ulps between a and the exact x (long double), in units of a's spacing. */
static double ulps_off(float a, long double x)
{
    int e;
    frexpl(x == 0 ? 1e-30L : x, &e);
    long double sp = ldexpl(1, e - 24 > -149 ? e - 24 : -149);
    return (double)(fabsl((long double)a - x) / sp);
}

static int run_surface(void)
{
    const long N = 200000 / scale;
    cylgen_rng rng;
    cylgen_seed(&rng, 603);
    double worst_u = 0, worst_v = 0, worst_d = 0;
    for (long i = 0; i < N; i++) {
        cylray_sphere s[4];
        for (int j = 0; j < 4; j++)
            make_sphere(&rng, (int)(i + j), &s[j]);
        const uint32_t lane = (uint32_t)(cylgen_next(&rng) % 4);
        cylray_prepared P;
        cylray_prepare_sphere(&P, &s[lane]);
        /* a float point on (or next to) the sphere; some at the poles and on the seam */
        double u[3];
        sref_unit(&rng, u);
        const int special = (int)(cylgen_next(&rng) % 16);
        if (special == 0)
            u[0] = u[1] = 0, u[2] = u[2] < 0 ? -1 : 1;
        if (special == 1)
            u[1] = 0;
        if (special == 2)
            u[0] = 0;
        const double l = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
        float p[3];
        for (int k = 0; k < 3; k++)
            p[k] = (float)(s[lane].center[k] + s[lane].radius * u[k] / l);
        float uv[2] = {-1, -1}, du[3] = {-1, -1, -1}, dv[3] = {-1, -1, -1};
        cylray_surface(&P, p, CYLRAY_SIDE | (special == 3 ? CYLRAY_BACKFACE : 0), uv, du, dv);
        /* the reference, at the exact p - c */
        long double r[3];
        for (int k = 0; k < 3; k++)
            r[k] = (long double)p[k] - (long double)s[lane].center[k];
        const long double h = sqrtl(r[0] * r[0] + r[1] * r[1]);
        if (h == 0 && r[2] == 0)
            continue; /* the center: not a point of the sphere */
        const long double L = sqrtl(h * h + r[2] * r[2]), R = s[lane].radius;
        long double U = h > 0 ? atan2l(r[1], r[0]) / (2 * PI_L) : 0;
        if (U < 0)
            U += 1;
        const long double V = atan2l(h, -r[2]) / PI_L;
        const long double co = h > 0 ? r[0] / h : 1, si = h > 0 ? r[1] / h : 0;
        const long double DU[3] = {-2 * PI_L * R * r[1] / L, 2 * PI_L * R * r[0] / L, 0};
        const long double DV[3] = {-PI_L * R * r[2] / L * co, -PI_L * R * r[2] / L * si,
                                   PI_L * R * h / L};
        /* u: within a float ulp, around the seam too (1 - ulp and 0 are neighbours) */
        double eu = ulps_off(uv[0], U);
        if (U > 0.5L && uv[0] == 0x1.fffffep-1f)
            eu = fmin(eu, ulps_off(uv[0], 1.0L));
        if (U < 0x1p-20L)
            eu = fmin(eu, fabs((double)((long double)uv[0] - U)) / 0x1p-24);
        const double ev = ulps_off(uv[1], V);
        CHECK(eu <= 1 && uv[0] >= 0 && uv[0] < 1, "u=%a off the exact %La by %.3g ulps", uv[0],
              U, eu);
        CHECK(ev <= 1 && uv[1] >= 0 && uv[1] <= 1, "v=%a off the exact %La by %.3g ulps", uv[1],
              V, ev);
        worst_u = fmax(worst_u, eu), worst_v = fmax(worst_v, ev);
        long double lu = 0, lv = 0, xu = 0, xv = 0;
        for (int k = 0; k < 3; k++) {
            lu += DU[k] * DU[k], lv += DV[k] * DV[k];
            xu = fmaxl(xu, fabsl((long double)du[k] - DU[k]));
            xv = fmaxl(xv, fabsl((long double)dv[k] - DV[k]));
        }
        lu = sqrtl(lu), lv = sqrtl(lv);
        CHECK(xu <= 0x1p-20L * lu, "dpdu off by %La of its length %La", xu, lu);
        CHECK(xv <= 0x1p-20L * lv, "dpdv off by %La of its length %La", xv, lv);
        if (lu > 0)
            worst_d = fmax(worst_d, (double)(xu / lu));
        worst_d = fmax(worst_d, (double)(xv / lv));
        /* the leaf form, the lane named; NULL outputs; a cap part writes nothing */
        cylray_leaf4 leaf;
        cylray_leaf_prepare_spheres4(&leaf, s, NULL, 4);
        cylray_hit1 hit = {1, {0, 0, 0}, CYLRAY_SIDE, 0, lane};
        float uv2[2], du2[3], dv2[3];
        cylray_leaf_surface4(&leaf, &hit, p, uv2, du2, dv2);
        int same = tc_same(uv2[0], uv[0]) && tc_same(uv2[1], uv[1]);
        for (int k = 0; k < 3; k++)
            same &= tc_same(du2[k], du[k]) && tc_same(dv2[k], dv[k]);
        CHECK(same, "the leaf form differs from cylray_surface");
        float uv3[2] = {7, 7};
        cylray_surface(&P, p, CYLRAY_SIDE, uv3, NULL, NULL);
        CHECK(tc_same(uv3[0], uv[0]) && tc_same(uv3[1], uv[1]), "uv alone differs");
        float d3[3] = {7, 7, 7};
        cylray_surface(&P, p, CYLRAY_CAP_LO, uv3, d3, NULL);
        CHECK(uv3[0] == uv[0] && d3[0] == 7, "a cap part of a sphere wrote something");
    }
    printf("sphere surface: worst u %.3g ulps, v %.3g ulps, derivatives %.3g of their length\n",
           worst_u, worst_v, worst_d);
    return tc_report("sphere surface");
}

int main(int argc, char **argv)
{
    scale = tc_quick() ? 10 : 1;
    const char *what = argc > 1 ? argv[1] : "box";
    if (!strcmp(what, "box"))
        return run_box();
    if (!strcmp(what, "split"))
        return run_split();
    if (!strcmp(what, "surface"))
        return run_surface();
    fprintf(stderr, "usage: sphere_test box|split|surface\n");
    return 2;
}
