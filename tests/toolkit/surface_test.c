/* SPDX-License-Identifier: MIT */
/* surface_test.c - cylray_surface and cylray_leaf_surface4/8/16 against exact arithmetic.
 *
 *   surface_test exact   points of every part of every kind of cylinder (and of infinite
 *                        ones), rounded to float: u and v within the header's bound of
 *                        their exact values at that float point (binary128 frame, long
 *                        double atan2), dpdu and dpdv within 2^-20 of theirs, v in [0, 1)
 *   surface_test frame   the frame is that of Duff et al. with s = +1 at a zero n_z of
 *                        either sign: the direction b1 is v = 0, b2 is v = 1/4; points
 *                        on the axis get v = 0 (and a zero dpdv on a disc); in the
 *                        endpoint form u = 0 at p0 and 1 at p1, dpdu = p1 - p0
 *   surface_test null    every subset of NULL outputs gives the same values in the rest;
 *                        the leaf forms equal the prepared form; bad parts write nothing
 *   surface_test mutant  the checks of "exact" applied to a float implementation with
 *                        the rounded unit axis must fail (the test can fail)
 *
 * CYLRAY_TEST_QUICK=1 shrinks the counts tenfold. */
#include "cylray.h"
#include "tcheck.h"
#include "tkgen.h"

#include <float.h>
#include <stdlib.h>

static long failures, checks;

static void fail(const cylray_cylinder *c, const float p[3], int part, const char *what,
                 double got, double want)
{
    if (failures++ < 20)
        fprintf(stderr,
                "FAIL %s: got %.9g want %.9g; part %d p=(%a %a %a) c=(%a %a %a) "
                "v=(%a %a %a) R=%a H=%a\n",
                what, got, want, part, p[0], p[1], p[2], c->center[0], c->center[1],
                c->center[2], c->axis[0], c->axis[1], c->axis[2], c->radius, c->half_height);
}

/* A float implementation a user might write from the rounded unit axis. */
static void naive_surface(const cylray_cylinder *c, const float p[3], int part, float uv[2],
                          float dpdu[3], float dpdv[3])
{
    float l =
        sqrtf(c->axis[0] * c->axis[0] + c->axis[1] * c->axis[1] + c->axis[2] * c->axis[2]);
    float n[3] = {c->axis[0] / l, c->axis[1] / l, c->axis[2] / l}, r[3];
    for (int k = 0; k < 3; k++)
        r[k] = p[k] - c->center[k];
    float s = n[2] >= 0 ? 1.0f : -1.0f, a = -1 / (s + n[2]), b = n[0] * n[1] * a;
    float b1[3] = {1 + s * n[0] * n[0] * a, s * b, -s * n[0]};
    float b2[3] = {b, s + n[1] * n[1] * a, -n[1]};
    float z = r[0] * n[0] + r[1] * n[1] + r[2] * n[2];
    float x = r[0] * b1[0] + r[1] * b1[1] + r[2] * b1[2];
    float y = r[0] * b2[0] + r[1] * b2[1] + r[2] * b2[2];
    float H = c->half_height;
    uv[0] = part == CYLRAY_SIDE ? (isfinite(H) ? (z + H) / (2 * H) : z)
                                : (part == CYLRAY_CAP_HI ? 1.0f : 0.0f);
    float t = atan2f(y, x) / 6.2831853f;
    uv[1] = t < 0 ? t + 1 : t;
    for (int k = 0; k < 3; k++) {
        dpdu[k] = (isfinite(H) ? 2 * H : 1) * n[k];
        dpdv[k] = 6.2831853f * c->radius * (x * b2[k] - y * b1[k]) / hypotf(x, y);
    }
}

/* The exact values at the float point p. */
typedef struct sref {
    long double u, v;
    cylq dpdu[3], dpdv[3];
    cylq rho, r; /* distance from the axis, |p - c| */
} sref;

static void exact_surface(const cylray_cylinder *c, const tkq *q, const float p[3], int part,
                          sref *s)
{
    cylq r[3], z = 0, x = 0, y = 0, rr = 0;
    for (int k = 0; k < 3; k++) {
        r[k] = (cylq)p[k] - q->c[k];
        z += r[k] * q->n[k];
        x += r[k] * q->b1[k];
        y += r[k] * q->b2[k];
        rr += r[k] * r[k];
    }
    s->r = q_sqrt(rr);
    s->rho = q_sqrt(x * x + y * y);
    int finite = isfinite(c->half_height);
    cylq H = q->H;
    if (part == CYLRAY_SIDE)
        s->u = (long double)(finite ? (z + H) / (2 * H) : z);
    else
        s->u = part == CYLRAY_CAP_HI ? 1 : 0;
    long double t = s->rho > 0 ? atan2l((long double)y, (long double)x) /
                                     (2 * 3.14159265358979323846264338327950288L)
                               : 0;
    s->v = t < 0 ? t + 1 : t;
    cylq co = s->rho > 0 ? x / s->rho : 1, si = s->rho > 0 ? y / s->rho : 0;
    cylq twopi = (cylq)2 * (cylq)3.14159265358979323846264338327950288L;
    for (int k = 0; k < 3; k++) {
        if (part == CYLRAY_SIDE) {
            s->dpdu[k] = (finite ? 2 * H : 1) * q->n[k];
            s->dpdv[k] = twopi * q->R * (co * q->b2[k] - si * q->b1[k]);
        } else {
            s->dpdu[k] = q->R * (co * q->b1[k] + si * q->b2[k]);
            s->dpdv[k] = twopi * s->rho * (co * q->b2[k] - si * q->b1[k]);
        }
    }
}

static double ulpf(double x)
{
    float f = (float)fabs(x);
    return (double)nextafterf(f, INFINITY) - (double)f;
}

/* The header's bound: one float ulp plus 2^-90 |p - c| / 2H (u) or / rho (v). */
static long check(const cylray_cylinder *c, const float p[3], int part, const float uv[2],
                  const float dpdu[3], const float dpdv[3], const sref *s)
{
    long bad = 0;
    double r = (double)s->r, rho = (double)s->rho;
    double H = c->half_height;
    double tol_u = ulpf((double)s->u) + ldexp(r / (isfinite(H) ? 2 * H : 1), -90);
    checks += 4;
    if (!(fabs(uv[0] - (double)s->u) <= tol_u)) {
        fail(c, p, part, "u", uv[0], (double)s->u), bad++;
    }
    if (!(uv[1] >= 0 && uv[1] < 1)) {
        fail(c, p, part, "v outside [0, 1)", uv[1], (double)s->v), bad++;
    } else if (rho > ldexp(r, -60)) {
        double dv = fabs(uv[1] - (double)s->v);
        dv = fmin(dv, 1 - dv); /* 0 and 1 are the same azimuth */
        if (!(dv <= ulpf((double)s->v) + ldexp(r / rho, -90)))
            fail(c, p, part, "v", uv[1], (double)s->v), bad++;
    }
    double nu = 0, nv = 0, eu = 0, ev = 0;
    for (int k = 0; k < 3; k++) {
        nu = fmax(nu, fabs((double)s->dpdu[k]));
        nv = fmax(nv, fabs((double)s->dpdv[k]));
        eu = fmax(eu, fabs(dpdu[k] - (double)s->dpdu[k]));
        ev = fmax(ev, fabs(dpdv[k] - (double)s->dpdv[k]));
    }
    /* a disc's dpdu turns with v as well; the side's does not */
    if ((part == CYLRAY_SIDE || rho > ldexp(r, -60)) && !(eu <= ldexp(nu, -20)))
        fail(c, p, part, "dpdu (largest error, largest component)", eu, nu), bad++;
    /* dpdv turns with v: its error is v's, 2 pi |dpdv| times the azimuth error */
    if (rho > ldexp(r, -60) && !(ev <= ldexp(nv, -20)))
        fail(c, p, part, "dpdv (largest error, largest component)", ev, nv), bad++;
    return bad;
}

/* Points of part `part`, exact then rounded to float. */
static void make_point(cylgen_rng *g, const tkq *q, int part, int finite, float p[3])
{
    cylq pt[3];
    double th = 2 * 3.14159265358979323846 * tk_u(g);
    /* now and then an azimuth next to 0 from either side: the seam of v */
    if (tk_u(g) < 0.1)
        th = (tk_u(g) - 0.5) * 1e-6;
    cylq z, r = q->R;
    if (part == CYLRAY_SIDE)
        z = finite ? q->H * (cylq)(2 * tk_u(g) - 1) : q->R * (cylq)tk_sym(g, 1e3);
    else {
        z = part == CYLRAY_CAP_HI ? q->H : -q->H;
        r = q->R * (cylq)tk_u(g);
        /* now and then next to the axis, where the azimuth says less and less: the
         * plain-double evaluation hands over to the double-double one there */
        if (tk_u(g) < 0.1)
            r = q->R * (cylq)tk_log(g, 1e-12, 1e-3);
    }
    tk_point(q, z, cos(th), sin(th), r, pt);
    for (int k = 0; k < 3; k++)
        p[k] = (float)pt[k];
}

static int run_exact(long n, int mutant)
{
    cylgen_rng g;
    cylgen_seed(&g, 2317);
    long bad_cases = 0, cases = 0;
    for (long i = 0; i < n; i++) {
        cylray_cylinder c;
        tk_cylinder(&g, (int)(i % 10), &c);
        if (i % 13 == 0)
            c.half_height = INFINITY;
        cylray_prepared P;
        if (cylray_prepare(&P, &c) != CYLRAY_OK)
            continue;
        tkq q;
        tk_exact(&c, &q);
        int finite = isfinite(c.half_height);
        for (int part = CYLRAY_SIDE; part <= (finite ? CYLRAY_CAP_HI : CYLRAY_SIDE); part++) {
            float p[3], uv[2], du[3], dv[3];
            make_point(&g, &q, part, finite, p);
            if (mutant)
                naive_surface(&c, p, part, uv, du, dv);
            else
                cylray_surface(&P, p, part | ((i & 1) ? CYLRAY_BACKFACE : 0), uv, du, dv);
            sref s;
            exact_surface(&c, &q, p, part, &s);
            cases++;
            bad_cases += check(&c, p, part, uv, du, dv, &s) != 0;
        }
    }
    if (mutant) {
        printf("mutant: %ld of %ld points caught\n", bad_cases, cases);
        return bad_cases > cases / 20 ? 0 : 1;
    }
    printf("exact: %ld points, %ld checks, %ld failures\n", cases, checks, failures);
    return failures != 0;
}

static int run_frame(void)
{
    /* axes with n_z of both signs and both zeros, coordinate axes, tilted ones */
    const float axes[][3] = {
        {0, 0, 1},  {0, 0, -1},   {1, 0, 0},     {-1, 0, 0},          {0, 1, 0},
        {0, -1, 0}, {1, 0, 0.0f}, {1, 0, -0.0f}, {0.3f, -0.4f, 0.0f}, {0.3f, -0.4f, -0.0f},
        {1, 2, 3},  {-1, 2, -3},  {1e-7f, 0, -1}};
    for (size_t a = 0; a < sizeof axes / sizeof axes[0]; a++) {
        cylray_cylinder c = {
            {1, 2, 3}, {axes[a][0], axes[a][1], axes[a][2]}, 2, 5, CYLRAY_CAPPED};
        cylray_prepared P;
        cylray_prepare(&P, &c);
        tkq q;
        tk_exact(&c, &q);
        /* s = +1 at n_z = -0: b1 = (1 - n_x^2/(1 + n_z), ...) as for +0 */
        if (c.axis[2] == 0 && q.b2[1] < 0)
            fail(&c, c.center, 1, "Duff frame sign at n_z = 0", (double)q.b2[1], 1);
        for (int quarter = 0; quarter < 4; quarter++) {
            double co = quarter == 0 ? 1 : quarter == 2 ? -1 : 0;
            double si = quarter == 1 ? 1 : quarter == 3 ? -1 : 0;
            cylq pt[3];
            tk_point(&q, 1, co, si, q.R, pt);
            float p[3] = {(float)pt[0], (float)pt[1], (float)pt[2]}, uv[2];
            cylray_surface(&P, p, CYLRAY_SIDE, uv, NULL, NULL);
            double want = quarter / 4.0, d = fabs(uv[1] - want);
            d = fmin(d, 1 - d);
            checks++;
            if (!(d < 1e-6))
                fail(&c, p, 1, "v of b1 (0), b2 (1/4), -b1 (1/2), -b2 (3/4)", uv[1], want);
        }
        /* on the axis: v = 0, and on a disc dpdv = 0, dpdu = R b1 */
        for (int part = CYLRAY_CAP_LO; part <= CYLRAY_CAP_HI; part++) {
            if ((c.axis[0] == 0) + (c.axis[1] == 0) + (c.axis[2] == 0) != 2)
                continue;
            float p[3], uv[2] = {7, 7}, du[3], dv[3];
            for (int k = 0; k < 3; k++)
                p[k] = c.center[k] + (part == CYLRAY_CAP_HI ? 5 : -5) * c.axis[k];
            cylray_surface(&P, p, part, uv, du, dv);
            checks++;
            if (uv[1] != 0 || uv[0] != (part == CYLRAY_CAP_HI) || dv[0] != 0 || dv[1] != 0 ||
                dv[2] != 0 || fabs(du[0] - 2 * (double)q.b1[0]) > 1e-6 ||
                fabs(du[1] - 2 * (double)q.b1[1]) > 1e-6)
                fail(&c, p, part, "disc center: u 0/1, v 0, dpdv 0, dpdu R b1", uv[1], 0);
        }
    }
    /* the endpoint form: u = 0 at p0 and 1 at p1, the caps there CAP_LO and CAP_HI */
    const float p0[3] = {10, -3, 7}, p1[3] = {4, 5, 7.5f};
    cylray_cylinder e;
    cylray_prepared P;
    cylray_cylinder_from_endpoints(&e, p0, p1, 0.5f, CYLRAY_CAPPED);
    cylray_prepare(&P, &e);
    for (int end = 0; end < 2; end++) {
        const float *q = end ? p1 : p0;
        float uv[2], side_uv[2], du[3];
        cylray_surface(&P, q, end ? CYLRAY_CAP_HI : CYLRAY_CAP_LO, uv, NULL, NULL);
        cylray_surface(&P, q, CYLRAY_SIDE, side_uv, du, NULL);
        checks++;
        if (uv[0] != end || fabs(side_uv[0] - end) > 1e-6 ||
            fabs(du[0] - (p1[0] - p0[0])) > 1e-5 || fabs(du[1] - (p1[1] - p0[1])) > 1e-5)
            fail(&e, q, end, "endpoint form: u 0 at p0, 1 at p1, dpdu = p1 - p0", side_uv[0],
                 end);
    }
    printf("frame: %ld checks, %ld failures\n", checks, failures);
    return failures != 0;
}

#define SAME3(a, b) (memcmp((a), (b), 3 * sizeof(float)) == 0)

static int run_null(long n)
{
    cylgen_rng g;
    cylgen_seed(&g, 17);
    static cylray_leaf4 l4;
    static cylray_leaf8 l8;
    static cylray_leaf16 l16;
    for (long i = 0; i < n; i++) {
        cylray_cylinder cs[16];
        for (int j = 0; j < 16; j++)
            do
                tk_cylinder(&g, (int)(cylgen_next(&g) % 10), &cs[j]);
            while (cylray_prepare(&(cylray_prepared){0}, &cs[j]) != CYLRAY_OK);
        if (i % 5 == 0)
            cs[3].half_height = INFINITY;
        cylray_leaf_prepare4(&l4, cs, NULL, 4);
        cylray_leaf_prepare8(&l8, cs, NULL, 8);
        cylray_leaf_prepare16(&l16, cs, NULL, 16);
        unsigned lane = (unsigned)(cylgen_next(&g) % 4);
        cylray_prepared P;
        cylray_prepare(&P, &cs[lane]);
        tkq q;
        tk_exact(&cs[lane], &q);
        int finite = isfinite(cs[lane].half_height);
        int part = finite ? 1 + (int)(cylgen_next(&g) % 3) : CYLRAY_SIDE;
        float p[3], uv[2], du[3], dv[3];
        make_point(&g, &q, part, finite, p);
        cylray_surface(&P, p, part, uv, du, dv);
        for (int mask = 0; mask < 8; mask++) {
            float a[2] = {7, 7}, b[3] = {7, 7, 7}, d[3] = {7, 7, 7};
            cylray_surface(&P, p, part, mask & 1 ? a : NULL, mask & 2 ? b : NULL,
                           mask & 4 ? d : NULL);
            checks++;
            if (((mask & 1) && memcmp(a, uv, sizeof a)) || ((mask & 2) && !SAME3(b, du)) ||
                ((mask & 4) && !SAME3(d, dv)) || (!(mask & 1) && a[0] != 7) ||
                (!(mask & 2) && b[0] != 7) || (!(mask & 4) && d[0] != 7))
                fail(&cs[lane], p, part, "NULL outputs change the others", mask, 0);
        }
        cylray_hit1 h = {0, {0, 0, 0}, part | CYLRAY_BACKFACE, 99, lane};
        float a[3][2], b[3][3], d[3][3];
        cylray_leaf_surface4(&l4, &h, p, a[0], b[0], d[0]);
        cylray_leaf_surface8(&l8, &h, p, a[1], b[1], d[1]);
        cylray_leaf_surface16(&l16, &h, p, a[2], b[2], d[2]);
        for (int w = 0; w < 3; w++) {
            checks++;
            if (memcmp(a[w], uv, sizeof uv) || !SAME3(b[w], du) || !SAME3(d[w], dv))
                fail(&cs[lane], p, part, "leaf form differs (width 4, 8, 16)", w, 0);
        }
        /* bad parts and unused lanes write nothing */
        float z[2] = {7, 7};
        cylray_surface(&P, p, CYLRAY_MISS, z, NULL, NULL);
        cylray_surface(&P, p, 5, z, NULL, NULL);
        cylray_leaf_prepare4(&l4, cs, NULL, 2);
        h.lane = 3;
        cylray_leaf_surface4(&l4, &h, p, z, NULL, NULL);
        h.lane = 40;
        cylray_leaf_surface16(&l16, &h, p, z, NULL, NULL);
        checks++;
        if (z[0] != 7 || z[1] != 7)
            fail(&cs[lane], p, part, "a bad part or lane wrote", z[0], 7);
    }
    printf("null: %ld checks, %ld failures\n", checks, failures);
    return failures != 0;
}

int main(int argc, char **argv)
{
    long scale = tc_quick() ? 10 : 1;
    const char *what = argc > 1 ? argv[1] : "exact";
    if (!strcmp(what, "exact"))
        return run_exact(100000 / scale, 0);
    if (!strcmp(what, "mutant"))
        return run_exact(20000 / scale, 1);
    if (!strcmp(what, "frame"))
        return run_frame();
    if (!strcmp(what, "null"))
        return run_null(3000 / scale);
    fprintf(stderr, "usage: surface_test exact|frame|null|mutant\n");
    return 2;
}
