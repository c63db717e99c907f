/* SPDX-License-Identifier: MIT */
/* test_rcgen.c - the round cone tests' random cases, their solver in double and answers from
 * inside a band's box (test_rc.h), and the band over rcgen.h's categories. */
#include "test_rc.h"

#include "bandutil.h"
#include "quad.h"
#include "rcgen.h"
#include "rcref_eval.h"
#include "test_ref.h"

#include "../support/rng.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const char *const rc_names[RC_COUNT] = {
    "ordinary", "far",    "strong taper", "slight taper", "capsule",
    "point",    "nested", "zero length",  "long thin",    "almost nested"};

int rc_quick(void)
{
    const char *q = getenv("CYLRAY_TEST_QUICK");
    return q && *q && strcmp(q, "0") != 0;
}

double rc_unif(uint64_t *s, double lo, double hi)
{
    const double u = rng_unit(rng_splitmix64(s));
    return lo + (hi - lo) * u;
}

static void unit3(uint64_t *s, double v[3])
{
    double len;
    do {
        v[0] = rc_unif(s, -1, 1);
        v[1] = rc_unif(s, -1, 1);
        v[2] = rc_unif(s, -1, 1);
        len = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    } while (len < 0.1 || len > 1);
    for (int k = 0; k < 3; k++)
        v[k] /= len;
}

void rc_make(int cat, uint64_t seed, int n, rc_case *out)
{
    /* the stream's start hashed from the seed and the kind: splitmix64's state only adds a
     * constant per draw, so seeds taken as states would give shifted copies of one stream */
    uint64_t h = seed ^ (uint64_t)cat << 40;
    uint64_t s = rng_splitmix64(&h);
    for (int i = 0; i < n; i++) {
        rc_case *c = &out[i];
        double p0[3], u[3], L, r0, r1;
        for (int k = 0; k < 3; k++)
            p0[k] = rc_unif(&s, -4, 4);
        unit3(&s, u);
        r0 = rc_unif(&s, 0.2, 1.5);
        r1 = rc_unif(&s, 0.2, 1.5);
        L = rc_unif(&s, 0.5, 4);
        const double f = rc_unif(&s, 0, 1), g = rc_unif(&s, 0, 1);
        switch (cat) {
        case RC_STRONG:
            r0 = rc_unif(&s, 0.05, 1);
            r1 = r0 * pow(10, (f < 0.5 ? -1 : 1) * (1 + 2 * g));
            L = fabs(r1 - r0) * (1 + pow(10, rc_unif(&s, -2, 0.5)));
            break;
        case RC_SLIGHT:
            r1 = r0;
            for (int j = 0; j < 1 + (int)(4 * f); j++)
                r1 = nextafterf((float)r1, g < 0.5 ? 0.0f : 2.0f);
            break;
        case RC_CAPSULE:
            r1 = r0;
            break;
        case RC_POINT:
            rcgen_point_end(f < 0.5, &r0, &r1, &L);
            break;
        case RC_NESTED:
            L = fabs(r1 - r0) * g * 0.99;
            break;
        case RC_ZERO:
            L = 0;
            break;
        case RC_THIN:
            r0 = rc_unif(&s, 1e-3, 1e-2);
            r1 = r0 * (0.8 + 0.45 * g);
            L = r0 * 1e4 * (0.5 + 0.5 * f);
            break;
        case RC_EDGE:
            L = fabs(r1 - r0) * (1 + pow(2, -8 - 12 * g));
            break;
        }
        for (int k = 0; k < 3; k++) {
            c->rc.p0[k] = (float)p0[k];
            c->rc.p1[k] = (float)(p0[k] + L * u[k]);
        }
        c->rc.r0 = (float)r0;
        c->rc.r1 = (float)r1;
        c->rc.flags = i % 4 == 3 ? (unsigned)(i / 4 % 4) : CYLRAY_CAPPED;
        /* the ray: aimed at a point about the segment, from 2..8 hull sizes away (far:
         * 1e3..1e6), or from that point itself; d unnormalized */
        const double rmax = fmax(c->rc.r0, c->rc.r1), size = L / 2 + rmax;
        double x[3], v[3], dir[3];
        const double at = rc_unif(&s, -0.2, 1.2), off = rc_unif(&s, 0, 1.3) * rmax;
        unit3(&s, v);
        unit3(&s, dir);
        double dist = size * rc_unif(&s, 2, 8);
        if (cat == RC_FAR)
            dist *= pow(10, rc_unif(&s, 3, 6));
        if (i % 7 == 6)
            dist = 0;
        const double sc = pow(10, rc_unif(&s, -1, 1));
        for (int k = 0; k < 3; k++) {
            x[k] = (double)c->rc.p0[k] + at * ((double)c->rc.p1[k] - c->rc.p0[k]) + off * v[k];
            c->o[k] = (float)(x[k] - dist * dir[k]);
            c->d[k] = (float)(dir[k] * sc);
        }
        const double tt = dist / sc, h = rc_unif(&s, 0, 1);
        c->tmin = i % 5 == 4 ? (float)(tt * (0.9 + 0.2 * h)) : 0;
        c->tmax = i % 6 == 5 ? (float)(tt * (0.95 + 0.4 * h)) : INFINITY;
    }
}

/* ---- a solver in double ---------------------------------------------------------------- *
 * What a kernel in double might write, in the textbook frame: the unit axis u, z in
 * lengths, the frustum's quadratic |x_perp|^2 n_rho^2 - (r0 + k z)^2 from subtracted
 * perpendicular parts; the hull's entry and exit as the least and greatest of the pieces',
 * rounded once to float. It must be inside every band, as the double solvers of the
 * sphere and the cone are. */
typedef struct {
    int ex;
    double lo, hi, face;
} dbl_piece;

static void dbl_sphere(const double W[3], const double d[3], double rad, dbl_piece *p)
{
    const double x[3] = {W[1] * d[2] - W[2] * d[1], W[2] * d[0] - W[0] * d[2],
                         W[0] * d[1] - W[1] * d[0]};
    const double A = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    const double B = W[0] * d[0] + W[1] * d[1] + W[2] * d[2];
    const double C = W[0] * W[0] + W[1] * W[1] + W[2] * W[2] - rad * rad;
    const double D = A * rad * rad - (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
    p->ex = rad > 0 && D >= 0;
    if (!p->ex)
        return;
    const double sq = sqrt(D), q = -(B + copysign(sq, B));
    const double t1 = q / A, t2 = q != 0 ? C / q : t1;
    p->lo = fmin(t1, t2);
    p->hi = fmax(t1, t2);
    p->face = sq;
}

static void dbl_frustum(const double W[3], const double d[3], const double a[3], double r0,
                        double r1, dbl_piece *p)
{
    double aa = 0, zw = 0, zd = 0, wp[3], dp[3];
    for (int k = 0; k < 3; k++)
        aa += a[k] * a[k];
    const double L = sqrt(aa), dr = r1 - r0, k = dr / L;
    const double nr2 = fmax(0, (L - fabs(dr)) * (L + fabs(dr))) / aa;
    for (int j = 0; j < 3; j++) {
        zw += W[j] * a[j] / L;
        zd += d[j] * a[j] / L;
    }
    for (int j = 0; j < 3; j++) {
        wp[j] = W[j] - zw * a[j] / L;
        dp[j] = d[j] - zd * a[j] / L;
    }
    const double rw = r0 + k * zw;
    const double A = nr2 * (dp[0] * dp[0] + dp[1] * dp[1] + dp[2] * dp[2]) - k * k * zd * zd;
    const double B = nr2 * (wp[0] * dp[0] + wp[1] * dp[1] + wp[2] * dp[2]) - k * zd * rw;
    const double C = nr2 * (wp[0] * wp[0] + wp[1] * wp[1] + wp[2] * wp[2]) - rw * rw;
    const double D = B * B - A * C;
    double cl = -INFINITY, ch = INFINITY, sl = -INFINITY, sh = INFINITY;
    p->ex = 0;
    const double sq = sqrt(fmax(D, 0)), q = -(B + copysign(sq, B));
    const double ra = q / A, rc = q != 0 ? C / q : ra;
    const double tm = B >= 0 ? ra : rc, tp = B >= 0 ? rc : ra;
    if (A > 0) {
        if (D < 0)
            return;
        cl = tm, ch = tp;
    } else if (A < 0 && D >= 0) {
        if (k * zd > 0)
            cl = tm;
        else
            ch = tp;
    } else if (A == 0) {
        if (B != 0) {
            if (B < 0)
                cl = -C / (2 * B);
            else
                ch = -C / (2 * B);
        } else if (C > 0) {
            return;
        }
    }
    const double z0 = -r0 * k, z1 = L - r1 * k;
    if (zd != 0) {
        sl = fmin((z0 - zw) / zd, (z1 - zw) / zd);
        sh = fmax((z0 - zw) / zd, (z1 - zw) / zd);
    } else if (zw < z0 || zw > z1) {
        return;
    }
    p->lo = fmax(cl, sl);
    p->hi = fmin(ch, sh);
    p->face = ch <= sh ? sq : A * p->hi + B;
    p->ex = p->lo <= p->hi && isfinite(p->lo) && isfinite(p->hi);
}

int rc_dbl_solve(const rc_case *c, unsigned fl, float *t, int *part)
{
    if (!ref_ray_ok(c->o, c->d, c->tmin, c->tmax))
        return 0;
    double w[3], d[3], a[3], W0[3], W1[3], wd = 0, dd = 0, aa = 0;
    for (int k = 0; k < 3; k++) {
        w[k] = (double)c->o[k] - ((double)c->rc.p0[k] + c->rc.p1[k]) / 2;
        d[k] = c->d[k];
        a[k] = (double)c->rc.p1[k] - c->rc.p0[k];
        wd += w[k] * d[k];
        dd += d[k] * d[k];
        aa += a[k] * a[k];
    }
    const double s0 = -wd / dd, r0 = c->rc.r0, r1 = c->rc.r1, dr = r1 - r0;
    for (int k = 0; k < 3; k++) {
        W0[k] = w[k] + s0 * d[k] + a[k] / 2;
        W1[k] = w[k] + s0 * d[k] - a[k] / 2;
    }
    dbl_piece pc[3] = {{0, 0, 0, 0}, {0, 0, 0, 0}, {0, 0, 0, 0}}; /* F, S0, S1 */
    const int nested = !(aa - dr * dr > 0), big = r1 > r0;
    if (!nested || !big)
        dbl_sphere(W0, d, r0, &pc[1]);
    if (!nested || big)
        dbl_sphere(W1, d, r1, &pc[2]);
    if (!nested)
        dbl_frustum(W0, d, a, r0, r1, &pc[0]);
    int e = -1, x = -1;
    for (int p = 0; p < 3; p++) {
        if (!pc[p].ex)
            continue;
        if (e < 0 || pc[p].lo < pc[e].lo)
            e = p;
        if (x < 0 || pc[p].hi > pc[x].hi)
            x = p;
    }
    if (e < 0)
        return 0;
    static const int parts[3] = {CYLRAY_SIDE, CYLRAY_CAP_LO, CYLRAY_CAP_HI};
    const unsigned caps[3] = {0, CYLRAY_CAPPED_LO, CYLRAY_CAPPED_HI};
    const double te = s0 + pc[e].lo, tx = s0 + pc[x].hi;
    const int back = pc[x].face > 0;
    if (te > c->tmax)
        return 0;
    if (te >= c->tmin && (e == 0 || (c->rc.flags & caps[e]))) {
        *t = (float)te;
        *part = parts[e];
        return 1;
    }
    if (tx >= c->tmin && tx <= c->tmax && (x == 0 || (c->rc.flags & caps[x])) &&
        !((fl & CYLRAY_CULL_BACK) && back)) {
        *t = (float)tx;
        *part = parts[x] | (back ? CYLRAY_BACKFACE : 0);
        return 1;
    }
    return 0;
}

/* The answer for inputs moved to a random point inside the band's box (up to 1.9 of its 2
 * ulps in each input): the band must allow it. */
int rc_inside_box(const rc_case *c, unsigned flags, uint64_t *s, int *part, float *t,
                  double n[3])
{
    if (!ref_ray_ok(c->o, c->d, c->tmin, c->tmax))
        return 0; /* a spoilt ray misses, wherever the box moves it */
    rin_q q;
    rcref_in_(&c->rc, c->o, c->d, &q);
    const cylq sw = ref_vec_step(q.w), sd = ref_vec_step(q.d), sa = ref_vec_step(q.a);
    for (int k = 0; k < 3; k++) {
        const double u1 = rc_unif(s, -1.9, 1.9);
        const double u2 = rc_unif(s, -1.9, 1.9);
        const double u3 = rc_unif(s, -1.9, 1.9);
        q.w[k] += sw * (cylq)u1;
        q.d[k] += sd * (cylq)u2;
        q.a[k] += sa * (cylq)u3;
    }
    const double u4 = rc_unif(s, -1.9, 1.9);
    const double u5 = rc_unif(s, -1.9, 1.9);
    if (q.r0 > 0)
        q.r0 += (cylq)(u4 * ref_float_ulp(c->rc.r0));
    if (q.r1 > 0)
        q.r1 += (cylq)(u5 * ref_float_ulp(c->rc.r1));
    rrec r;
    rcref_eval_(&q, -1, c->tmin, c->tmax, &r);
    const int x = rcref_decide_(&r, c->rc.flags | (flags & CYLRAY_CULL_BACK));
    if (x < 0)
        return 0;
    *part = rcref_part_(&r, x);
    *t = (float)rcref_t_(&r, x);
    rcref_normal_(&r, x, 0, n);
    return 1;
}

int rc_judge_answer(const cylref_band *b, const char *what, const char *cat, int i,
                    unsigned flags, int hit, float t, int part, double allow, int *bad,
                    double *ub)
{
    const int v = rcref_judge(b, hit, part, t, ub);
    if ((v || *ub > allow) && (*bad)++ < 4)
        printf("  %s #%d flags %u: %s %d t %.9g part %#x judged %d, %.3g ulps beyond (exact %d "
               "t %.9g part %#x)\n",
               cat, i, flags, what, hit, (double)t, part, v, *ub, b->exact.hit, b->exact.t,
               b->exact.part);
    return v;
}

/* rcgen.h's categories (the cases a checker of round-cone kernels draws): the exact
 * answer inside its band, answers from inside the box and the double solver's allowed. */
void test_rcgen_bands(void)
{
    enum { N = 96, INNER = 4 };
    static rcgen_case g[N];
    const int n = rc_quick() ? N / 4 : N;
    uint64_t s = 0x7263676e;
    for (int cat = 0; cat < RCGEN_COUNT; cat++) {
        rcgen_make(cat, 3, (size_t)n, g);
        int hits = 0, unstable = 0, bad = 0, dbad = 0;
        for (int i = 0; i < n; i++) {
            rc_case c;
            c.rc = g[i].rc;
            memcpy(c.o, g[i].o, sizeof c.o);
            memcpy(c.d, g[i].d, sizeof c.d);
            c.tmin = g[i].tmin;
            c.tmax = g[i].tmax;
            for (unsigned fl = 0; fl <= CYLRAY_CULL_BACK; fl += CYLRAY_CULL_BACK) {
                cylref_band b;
                double ub;
                rcref_band_eval(&c.rc, c.o, c.d, c.tmin, c.tmax, fl, &b);
                hits += b.exact.hit;
                unstable += b.hit_unstable;
                CHECK(rcref_judge(&b, b.exact.hit, b.exact.part, (float)b.exact.t, &ub) == 0 &&
                          (!b.exact.hit || ub == 0),
                      "%s #%d: the exact answer fails its band", rcgen_category_name(cat), i);
                for (int j = 0; j < INNER; j++) {
                    int part = 0;
                    float t = 0;
                    double n[3];
                    const int hit = rc_inside_box(&c, fl, &s, &part, &t, n);
                    rc_judge_answer(&b, "inside the box", rcgen_category_name(cat), i, fl, hit,
                                    t, part, 0.5, &bad, &ub);
                }
                int part = 0;
                float t = 0;
                const int hit = rc_dbl_solve(&c, fl, &t, &part);
                rc_judge_answer(&b, "double solver", rcgen_category_name(cat), i, fl, hit, t,
                                part, 1, &dbad, &ub);
            }
        }
        printf("rcgen %-12s %3d/%d hits, %3d may hit or miss; %d answers from inside the box "
               "and %d of the double solver judged bad\n",
               rcgen_category_name(cat), hits, 2 * n, unstable, bad, dbad);
        CHECK(bad == 0 && dbad == 0, "%s: %d and %d judged bad", rcgen_category_name(cat), bad,
              dbad);
    }
}
