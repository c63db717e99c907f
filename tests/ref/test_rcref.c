/* SPDX-License-Identifier: MIT */
/* test_rcref.c - tests of the exact round-cone reference: an independent computation of the
 * hull's entry and exit (a convex function minimised and bisected, no quadratic, no tangent
 * slab), the band's verdicts on answers from inside its box and a double solver's, seams,
 * and the defects the band must catch (its hand-computed answers: test_rchand.c; its random
 * cases and the double solver: test_rcgen.c). */
#include "bandutil.h"
#include "quad.h"
#include "rcref_eval.h"
#include "test_rc.h"
#include "test_ref.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* ---- the independent computation ------------------------------------------------------ *
 * The hull is {x : g(x) <= 0} with g(x) = min over sigma in [0, L] of
 * |x - p0 - sigma u| - (r0 + k sigma), k = dr / L: a function jointly convex in (x, sigma)
 * minimised over sigma, so convex in x and along the ray in t. The inner minimum is where
 * the derivative in sigma vanishes, -(zeta - sigma) / dist = k with zeta the axial
 * coordinate and rho the distance from the axis: sigma* = zeta + k rho / sqrt(1 - k^2),
 * clamped to [0, L] (|k| >= 1: the end of the larger radius). Along the ray a golden-section
 * search finds g's least value, bisection each of its zeros, all in binary128; the part is
 * where the clamped sigma* lies (0: sphere 0, L: sphere 1, between: the side). */
typedef struct {
    cylq W[3], d[3], a[3], L, r0, r1, dr;
} ind_geo;

static cylq ind_g(const ind_geo *g, cylq t, cylq *sigma)
{
    cylq X[3];
    for (int k = 0; k < 3; k++)
        X[k] = g->W[k] + t * g->d[k];
    if (g->L == 0 || q_abs(g->dr) >= g->L) {
        const int one = g->r1 > g->r0;
        cylq Y[3];
        for (int k = 0; k < 3; k++)
            Y[k] = one ? X[k] - g->a[k] : X[k];
        *sigma = one ? g->L : 0;
        return q_sqrt(Y[0] * Y[0] + Y[1] * Y[1] + Y[2] * Y[2]) - (one ? g->r1 : g->r0);
    }
    const cylq c[3] = {X[1] * g->a[2] - X[2] * g->a[1], X[2] * g->a[0] - X[0] * g->a[2],
                       X[0] * g->a[1] - X[1] * g->a[0]};
    const cylq rho = q_sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]) / g->L;
    const cylq zeta = (X[0] * g->a[0] + X[1] * g->a[1] + X[2] * g->a[2]) / g->L;
    const cylq k = g->dr / g->L, adr = q_abs(g->dr);
    const cylq cosa = q_sqrt((g->L - adr) * (g->L + adr)) / g->L;
    cylq s = zeta + k * rho / cosa;
    *sigma = s;
    s = s < 0 ? 0 : s > g->L ? g->L : s;
    const cylq dz = zeta - s;
    return q_sqrt(dz * dz + rho * rho) - (g->r0 + k * s);
}

/* g's gradient at t: the unit vector from the centre c(sigma*) of the nearest sphere, the
 * outward normal wherever the surface is smooth (all 0 at a point end's apex). */
static void ind_normal(const ind_geo *g, cylq t, double n[3])
{
    cylq s, Y[3];
    ind_g(g, t, &s);
    s = s < 0 ? 0 : s > g->L ? g->L : s;
    for (int k = 0; k < 3; k++)
        Y[k] = g->W[k] + t * g->d[k] - (g->L > 0 ? s / g->L * g->a[k] : 0);
    const cylq len = q_sqrt(Y[0] * Y[0] + Y[1] * Y[1] + Y[2] * Y[2]);
    for (int k = 0; k < 3; k++)
        n[k] = len > 0 ? (double)(Y[k] / len) : 0;
}

typedef struct {
    ind_geo g;
    int hit;
    cylq te, tx;    /* entry and exit */
    cylq se, sx;    /* sigma* there, unclamped */
    cylq gmin, tol; /* g's least value; the scale of t */
    double size;    /* |p1 - p0| / 2 + the larger radius */
    double slope;   /* |g'| / |d| at the worse of the two zeros: the cosine of incidence */
} ind_out;

static void ind_solve(const rc_case *c, ind_out *out)
{
    ind_geo g;
    memset(&g, 0, sizeof g);
    cylq aa = 0, dd = 0, wd = 0;
    for (int k = 0; k < 3; k++) {
        g.W[k] = (cylq)c->o[k] - c->rc.p0[k];
        g.d[k] = c->d[k];
        g.a[k] = (cylq)c->rc.p1[k] - c->rc.p0[k];
        aa += g.a[k] * g.a[k];
        dd += g.d[k] * g.d[k];
    }
    for (int k = 0; k < 3; k++)
        wd += (g.W[k] - g.a[k] / 2) * g.d[k];
    g.L = q_sqrt(aa);
    g.r0 = c->rc.r0;
    g.r1 = c->rc.r1;
    g.dr = g.r1 - g.r0;
    const cylq size = g.L / 2 + q_max(g.r0, g.r1), dl = q_sqrt(dd);
    const cylq mid = -wd / dd, reach = size / dl * (cylq)1.25;
    out->tol = q_abs(mid) + reach;
    out->size = (double)size;
    cylq a = mid - reach, b = mid + reach, sg;
    const cylq phi = (cylq)0.6180339887498948482045868343656381L;
    cylq x1 = b - phi * (b - a), x2 = a + phi * (b - a);
    cylq g1 = ind_g(&g, x1, &sg), g2 = ind_g(&g, x2, &sg);
    for (int it = 0; it < 120; it++) {
        if (g1 < g2) {
            b = x2, x2 = x1, g2 = g1;
            x1 = b - phi * (b - a);
            g1 = ind_g(&g, x1, &sg);
        } else {
            a = x1, x1 = x2, g1 = g2;
            x2 = a + phi * (b - a);
            g2 = ind_g(&g, x2, &sg);
        }
    }
    const cylq tm = g1 < g2 ? x1 : x2;
    out->gmin = q_min(g1, g2);
    out->hit = out->gmin <= 0;
    if (!out->hit)
        return;
    cylq ends[2];
    for (int e = 0; e < 2; e++) {
        cylq lo = e ? tm : mid - reach, hi = e ? mid + reach : tm; /* g changes sign */
        for (int it = 0; it < 400; it++) {
            const cylq m = (lo + hi) / 2;
            if (m == lo || m == hi)
                break;
            const int in = ind_g(&g, m, &sg) <= 0;
            if (in == (e == 0))
                hi = m;
            else
                lo = m;
        }
        ends[e] = (lo + hi) / 2;
    }
    out->te = ends[0];
    out->tx = ends[1];
    ind_g(&g, out->te, &out->se);
    ind_g(&g, out->tx, &out->sx);
    const cylq h = reach * (cylq)1e-7;
    const cylq se = (ind_g(&g, out->te - h, &sg) - ind_g(&g, out->te, &sg)) / h;
    const cylq sx = (ind_g(&g, out->tx + h, &sg) - ind_g(&g, out->tx, &sg)) / h;
    out->slope = (double)(q_min(se, sx) / dl);
    out->g = g;
}

/* The part at sigma*: -1 where it is within 1e-9 of a seam (or the hull is one sphere of
 * two equal ones), where either part is right to the precision of the search. */
static int ind_part(const rc_case *c, cylq sigma)
{
    double aa = 0;
    for (int k = 0; k < 3; k++) {
        const double a = (double)c->rc.p1[k] - c->rc.p0[k];
        aa += a * a;
    }
    const double L = sqrt(aa), dr = (double)c->rc.r1 - c->rc.r0, s = (double)sigma;
    if (L == 0 || fabs(dr) >= L) {
        if (c->rc.r0 == c->rc.r1 || fabs(fabs(dr) - L) <= 1e-9 * L)
            return -1;
        return c->rc.r1 > c->rc.r0 ? CYLRAY_CAP_HI : CYLRAY_CAP_LO;
    }
    if (fabs(s) <= 1e-9 * L || fabs(s - L) <= 1e-9 * L)
        return -1;
    if (s < 0)
        return c->rc.r0 > 0 ? CYLRAY_CAP_LO : -1;
    if (s > L)
        return c->rc.r1 > 0 ? CYLRAY_CAP_HI : -1;
    return CYLRAY_SIDE;
}

static int present(unsigned flags, int part)
{
    return part == CYLRAY_SIDE ||
           (flags & (part == CYLRAY_CAP_LO ? CYLRAY_CAPPED_LO : CYLRAY_CAPPED_HI));
}

typedef struct {
    long cases, compared, hits, backs, open, skipped_grazing, skipped_seam, parts;
    double worst, worst_n;
    int worst_cat, worst_i;
} ind_counts;

static void compare_one(ind_counts *n, const rc_case *c, int cat, int i, unsigned fl)
{
    ind_out x;
    ind_solve(c, &x);
    n->cases++;
    if (fabs((double)x.gmin) < 1e-9 * x.size || (x.hit && x.slope < 1e-4)) {
        n->skipped_grazing++;
        return;
    }
    const cylq tmin = c->tmin, tmax = c->tmax;
    const int pe = x.hit ? ind_part(c, x.se) : 0, px = x.hit ? ind_part(c, x.sx) : 0;
    int hit = 0, part = 0;
    cylq t = 0;
    if (x.hit) {
        const cylq eps = (cylq)1e-15 * x.tol;
        if (q_abs(x.te - tmin) < eps || q_abs(x.te - tmax) < eps || q_abs(x.tx - tmin) < eps ||
            q_abs(x.tx - tmax) < eps || pe < 0 || px < 0) {
            n->skipped_seam++;
            return;
        }
        if (x.te > tmax) {
        } else if (x.te >= tmin && present(c->rc.flags, pe)) {
            hit = 1, t = x.te, part = pe;
        } else if (x.tx >= tmin && x.tx <= tmax && present(c->rc.flags, px) &&
                   !(fl & CYLRAY_CULL_BACK)) {
            hit = 1, t = x.tx, part = px | CYLRAY_BACKFACE;
        }
    }
    rin_q q;
    rrec r;
    rcref_in_(&c->rc, c->o, c->d, &q);
    rcref_eval_(&q, -1, tmin, tmax, &r);
    const int xr = rcref_decide_(&r, c->rc.flags | (fl & CYLRAY_CULL_BACK));
    cylref_hit h;
    rcref_intersect(&c->rc, c->o, c->d, c->tmin, c->tmax, fl, &h);
    n->compared++;
    CHECK(h.hit == (xr >= 0), "%s #%d: intersect %d, eval %d", rc_names[cat], i, h.hit, xr);
    CHECK(hit == h.hit, "%s #%d flags %u/%u: independent %d (gmin %.3g), reference %d",
          rc_names[cat], i, c->rc.flags, fl, hit, (double)x.gmin, h.hit);
    if (!hit || !h.hit || xr < 0)
        return;
    n->hits++;
    n->backs += (part & CYLRAY_BACKFACE) != 0;
    n->open += c->rc.flags != CYLRAY_CAPPED;
    const cylq tr = rcref_t_(&r, xr);
    const double rel = (double)(q_abs(tr - t) / x.tol);
    if (rel > n->worst) {
        n->worst = rel;
        n->worst_cat = cat;
        n->worst_i = i;
    }
    CHECK(rel <= 1e-20, "%s #%d: t %.25g vs independent %.25g (%.3g relative)", rc_names[cat],
          i, (double)tr, (double)t, rel);
    CHECK(h.t == (double)tr, "%s #%d: intersect's t %.17g, eval's %.17g", rc_names[cat], i, h.t,
          (double)tr);
    n->parts++;
    CHECK(h.part == part, "%s #%d: part %#x, independent %#x", rc_names[cat], i,
          (unsigned)h.part, (unsigned)part);
    const double len = sqrt(h.n[0] * h.n[0] + h.n[1] * h.n[1] + h.n[2] * h.n[2]);
    double ni[3];
    ind_normal(&x.g, t, ni);
    if (len == 0 && ni[0] == 0 && ni[1] == 0 && ni[2] == 0)
        return; /* a point end's apex */
    CHECK(fabs(len - 1) < 1e-14, "%s #%d: |n| %.17g", rc_names[cat], i, len);
    const double ang = ref_angle3(h.n, ni);
    n->worst_n = fmax(n->worst_n, ang);
    CHECK(ang < 1e-14, "%s #%d: normal %.3g rad from the independent one", rc_names[cat], i,
          ang);
    /* facing the ray: the same normal, turned where the ray leaves */
    cylref_hit hf;
    rcref_intersect(&c->rc, c->o, c->d, c->tmin, c->tmax, fl | CYLRAY_FACE_FORWARD, &hf);
    const double sg = part & CYLRAY_BACKFACE ? -1 : 1;
    CHECK(hf.hit && hf.part == h.part && hf.n[0] == sg * h.n[0] && hf.n[1] == sg * h.n[1] &&
              hf.n[2] == sg * h.n[2],
          "%s #%d: face forward", rc_names[cat], i);
}

static void test_independent(void)
{
    enum { N = 240 };
    const int n_cases = rc_quick() ? N / 4 : N;
    static rc_case cs[N];
    ind_counts n;
    memset(&n, 0, sizeof n);
    for (int cat = 0; cat < RC_COUNT; cat++) {
        rc_make(cat, 2026, n_cases, cs);
        for (int i = 0; i < n_cases; i++)
            compare_one(&n, &cs[i], cat, i, i % 3 == 2 ? CYLRAY_CULL_BACK : 0);
    }
    printf("rcref vs minimised convex distance: %ld cases, %ld compared (%ld hits, %ld back, "
           "%ld open ends, %ld parts), %ld grazing and %ld at seams or range ends skipped; "
           "worst t %.3g relative (%s #%d), worst normal %.3g rad\n",
           n.cases, n.compared, n.hits, n.backs, n.open, n.parts, n.skipped_grazing,
           n.skipped_seam, n.worst, rc_names[n.worst_cat], n.worst_i, n.worst_n);
    CHECK(n.compared > RC_COUNT * n_cases * 3 / 4 && n.hits > RC_COUNT * n_cases / 4,
          "too few compared: %ld, %ld hits", n.compared, n.hits);
}

/* ---- symmetries ----------------------------------------------------------------------- */

/* The exact answer in binary128: 1 and *t, *part for a hit. */
static int answer(const rc_case *c, unsigned fl, cylq *t, int *part)
{
    rin_q q;
    rrec r;
    rcref_in_(&c->rc, c->o, c->d, &q);
    rcref_eval_(&q, -1, c->tmin, c->tmax, &r);
    const int x = rcref_decide_(&r, c->rc.flags | (fl & CYLRAY_CULL_BACK));
    if (x < 0)
        return 0;
    *t = rcref_t_(&r, x);
    *part = rcref_part_(&r, x);
    return 1;
}

static unsigned swap_caps(unsigned f)
{
    return (f & CYLRAY_CAPPED_LO ? CYLRAY_CAPPED_HI : 0) |
           (f & CYLRAY_CAPPED_HI ? CYLRAY_CAPPED_LO : 0);
}

static int swap_part(int p)
{
    const int q = p & CYLRAY_PART_MASK;
    return (p & ~CYLRAY_PART_MASK) | (q == CYLRAY_CAP_LO   ? CYLRAY_CAP_HI
                                      : q == CYLRAY_CAP_HI ? CYLRAY_CAP_LO
                                                           : q);
}

/* The ends swapped (p0, r0 with p1, r1 and their flags) is the same hull with the caps'
 * names swapped; a rotation of the coordinates with mirrors moves nothing but the frame;
 * every length times a power of two multiplies t by it exactly, and d times one divides
 * it. A part may change only where the band allows both. */
static void test_symmetry(void)
{
    enum { N = 64 };
    const int n = rc_quick() ? N / 4 : N;
    static rc_case cs[N];
    int checked = 0, excused = 0;
    for (int cat = 0; cat < RC_COUNT; cat++) {
        rc_make(cat, 31, n, cs);
        for (int i = 0; i < n; i++) {
            const rc_case *c = &cs[i];
            const unsigned fl = i % 3 == 2 ? CYLRAY_CULL_BACK : 0;
            cylq t0 = 0, t1 = 0;
            int p0 = 0, p1 = 0;
            const int h0 = answer(c, fl, &t0, &p0);
            double dd = 0, size = 0;
            for (int k = 0; k < 3; k++) {
                const double a = (double)c->rc.p1[k] - c->rc.p0[k];
                dd += (double)c->d[k] * c->d[k];
                size += a * a;
            }
            size = sqrt(size) / 2 + fmax(c->rc.r0, c->rc.r1);
            const cylq tol = (cylq)1e-28 * (q_abs(t0) + (cylq)(size / sqrt(dd)));
            rc_case v = *c;
            for (int k = 0; k < 3; k++) {
                v.rc.p0[k] = c->rc.p1[k];
                v.rc.p1[k] = c->rc.p0[k];
            }
            v.rc.r0 = c->rc.r1;
            v.rc.r1 = c->rc.r0;
            v.rc.flags = swap_caps(c->rc.flags);
            int h1 = answer(&v, fl, &t1, &p1);
            int same = h0 == h1 && (!h0 || q_abs(t1 - t0) <= tol);
            if (same && h0 && swap_part(p1) != p0) {
                cylref_band b;
                rcref_band_eval(&c->rc, c->o, c->d, c->tmin, c->tmax, fl, &b);
                same = b.part_unstable;
                excused += same;
            }
            CHECK(same, "%s #%d ends swapped: hit %d/%d t %.21g/%.21g part %#x/%#x",
                  rc_names[cat], i, h0, h1, (double)t0, (double)t1, (unsigned)p0, (unsigned)p1);

            static const int perm[3] = {2, 0, 1};
            static const float sgn[3] = {-1, 1, -1};
            for (int k = 0; k < 3; k++) {
                v.rc.p0[k] = c->rc.p0[perm[k]] * sgn[k];
                v.rc.p1[k] = c->rc.p1[perm[k]] * sgn[k];
                v.o[k] = c->o[perm[k]] * sgn[k];
                v.d[k] = c->d[perm[k]] * sgn[k];
            }
            v.rc.r0 = c->rc.r0;
            v.rc.r1 = c->rc.r1;
            v.rc.flags = c->rc.flags;
            h1 = answer(&v, fl, &t1, &p1);
            CHECK(h0 == h1 && (!h0 || (q_abs(t1 - t0) <= tol && p0 == p1)),
                  "%s #%d rotated: hit %d/%d t %.21g/%.21g part %#x/%#x", rc_names[cat], i, h0,
                  h1, (double)t0, (double)t1, (unsigned)p0, (unsigned)p1);

            /* every length by 2, 2^40 or 2^-40: t by the same, exactly; d by 2^30: t
             * by 2^-30, exactly; and the exact answer inside its band at those scales */
            static const float lens[3] = {2, 0x1p40f, 0x1p-40f};
            for (int j = 0; j < 4; j++) {
                const float f = j < 3 ? lens[j] : 1, g = j < 3 ? 1 : 0x1p30f;
                v = *c;
                for (int k = 0; k < 3; k++) {
                    v.rc.p0[k] *= f;
                    v.rc.p1[k] *= f;
                    v.o[k] *= f;
                    v.d[k] *= g;
                }
                v.rc.r0 *= f;
                v.rc.r1 *= f;
                v.tmin *= f / g;
                v.tmax *= f / g;
                h1 = answer(&v, fl, &t1, &p1);
                CHECK(h0 == h1 && (!h0 || (t1 == t0 * f / g && p0 == p1)),
                      "%s #%d scaled by %g, d by %g: hit %d/%d t %.21g/%.21g part %#x/%#x",
                      rc_names[cat], i, (double)f, (double)g, h0, h1, (double)t0, (double)t1,
                      (unsigned)p0, (unsigned)p1);
                if (j == 0)
                    continue;
                cylref_band b;
                double ub;
                rcref_band_eval(&v.rc, v.o, v.d, v.tmin, v.tmax, fl, &b);
                CHECK(rcref_judge(&b, b.exact.hit, b.exact.part, (float)b.exact.t, &ub) == 0 &&
                          (!b.exact.hit || ub == 0),
                      "%s #%d scaled by %g, d by %g: the exact answer fails its band",
                      rc_names[cat], i, (double)f, (double)g);
            }
            checked++;
        }
    }
    printf(
        "rc symmetry: %d cases x 6 transforms, %d parts swapped where the band allows both\n",
        checked, excused);
}

/* ---- the band ------------------------------------------------------------------------- */

static void test_band(void)
{
    enum { N = 96, INNER = 4 };
    static rc_case cs[N];
    const int n = rc_quick() ? N / 4 : N;
    uint64_t s = 0x626e64;
    for (int cat = 0; cat < RC_COUNT; cat++) {
        rc_make(cat, 7, n, cs);
        int dbad = 0, nbad = 0;
        double dworst = 0;
        int hits = 0, unstable = 0, hit_unstable = 0, bad = 0, caught = 0, caught_of = 0,
            wn = 0;
        double wsum = 0, worst = 0;
        for (int i = 0; i < n; i++) {
            const rc_case *c = &cs[i];
            for (unsigned fl = 0; fl <= CYLRAY_CULL_BACK; fl += CYLRAY_CULL_BACK) {
                cylref_band b;
                double ub;
                rcref_band_eval(&c->rc, c->o, c->d, c->tmin, c->tmax, fl, &b);
                hits += b.exact.hit;
                unstable += b.decision_unstable;
                hit_unstable += b.hit_unstable;
                CHECK(rcref_judge(&b, b.exact.hit, b.exact.part, (float)b.exact.t, &ub) == 0 &&
                          (!b.exact.hit || ub == 0),
                      "%s #%d: the exact answer fails its band", rc_names[cat], i);
                if (b.exact.hit) {
                    wsum += 0.5 * (b.t_hi - b.t_lo) / cylref_float_ulp(b.exact.t);
                    wn++;
                }
                for (int j = 0; j < INNER; j++) {
                    int part = 0;
                    float t = 0;
                    double n[3];
                    const int hit = rc_inside_box(c, fl, &s, &part, &t, n);
                    /* the normal where the part is the exact one: within n_spread (an
                     * apex has none) */
                    if (hit && b.exact.hit && part == b.exact.part &&
                        (n[0] != 0 || n[1] != 0 || n[2] != 0) &&
                        !(ref_angle3(n, b.exact.n) <= b.n_spread + 1e-12))
                        nbad++;
                    const int v = rc_judge_answer(&b, "inside the box", rc_names[cat], i, fl,
                                                  hit, t, part, 0.5, &bad, &ub);
                    if (!v && hit)
                        worst = fmax(worst, ub);
                }
                {
                    int part = 0;
                    float t = 0;
                    const int hit = rc_dbl_solve(c, fl, &t, &part);
                    const int v = rc_judge_answer(&b, "double solver", rc_names[cat], i, fl,
                                                  hit, t, part, 1, &dbad, &ub);
                    if (!v && hit)
                        dworst = fmax(dworst, ub);
                }
                caught += ref_catch_defects(rcref_judge, &b, &caught_of);
            }
        }
        printf("rc band %-13s %3d/%d hits, %3d unstable (%d hit or miss), %d of %d answers "
               "from inside the box "
               "judged bad (worst %.3g ulps beyond), %d/%d defects caught, band +-%.3g ulps on "
               "average\n",
               rc_names[cat], hits, 2 * n, unstable, hit_unstable, bad, 2 * n * INNER, worst,
               caught, 3 * caught_of, wn ? wsum / wn : 0.0);
        printf("rc band %-13s double solver: %d judged bad, worst %.3g ulps beyond\n",
               rc_names[cat], dbad, dworst);
        CHECK(bad == 0, "%s: answers from inside the box fail the band %d times", rc_names[cat],
              bad);
        CHECK(dbad == 0, "%s: the double solver fails its bands %d times", rc_names[cat], dbad);
        CHECK(nbad == 0, "%s: normals from inside the box beyond n_spread %d times",
              rc_names[cat], nbad);
        CHECK(caught == 3 * caught_of, "%s: defects missed", rc_names[cat]);
        CHECK(hits > n / 4, "%s: too few hits %d", rc_names[cat], hits);
        /* far: the box moves the ray by 2 ulps of 1e3..1e6 hull sizes (a quarter of the
         * hull's size at 1e6), so a ray aimed within 1.3 radii of the axis often may hit or
         * miss, and a side or a cap near a seam is often either */
        if (cat == RC_ORDINARY || cat == RC_CAPSULE)
            CHECK(unstable < 2 * n / 10 + 1, "%s: too many unstable %d", rc_names[cat],
                  unstable);
        if (cat == RC_FAR)
            CHECK(hit_unstable < n, "%s: too many unstable %d", rc_names[cat], hit_unstable);
    }
}

/* ---- seams and grazing rays ------------------------------------------------------------ */

/* A point of the seam of end `end` at azimuth phi, in double: the point, the outward normal
 * there (the cone's and the sphere's), the seam's tangent and the generator line's
 * direction (from p0's end to p1's); size = |p1 - p0| / 2 + the larger radius. 0 where the
 * hull has no such seam (nested, or a point end). */
typedef struct {
    double x[3], n[3], tang[3], gen[3], size;
} rc_seam;

static int seam_at(const rcref_round_cone *rc, int end, double phi, rc_seam *f)
{
    double a[3], u[3], e1[3], e2[3], aa = 0;
    for (int k = 0; k < 3; k++) {
        a[k] = (double)rc->p1[k] - rc->p0[k];
        aa += a[k] * a[k];
    }
    const double L = sqrt(aa), dr = (double)rc->r1 - rc->r0;
    const double rad = end ? rc->r1 : rc->r0;
    if (!(L > fabs(dr) * (1 + 1e-6)) || !(rad > 0))
        return 0;
    for (int k = 0; k < 3; k++)
        u[k] = a[k] / L;
    /* e1, e2: a frame across the axis */
    const double pick[3] = {fabs(u[0]) < 0.6 ? 1 : 0, fabs(u[0]) < 0.6 ? 0 : 1, 0};
    const double pu = pick[0] * u[0] + pick[1] * u[1] + pick[2] * u[2];
    double l1 = 0;
    for (int k = 0; k < 3; k++) {
        e1[k] = pick[k] - pu * u[k];
        l1 += e1[k] * e1[k];
    }
    for (int k = 0; k < 3; k++)
        e1[k] /= sqrt(l1);
    ref_cross3(u, e1, e2);
    const double k = dr / L, nr = sqrt((L - fabs(dr)) * (L + fabs(dr))) / L;
    for (int j = 0; j < 3; j++) {
        const double radial = cos(phi) * e1[j] + sin(phi) * e2[j];
        const double at = (end ? rc->p1[j] : rc->p0[j]) - rad * k * u[j];
        f->x[j] = at + rad * nr * radial;
        f->n[j] = nr * radial - k * u[j];
        f->tang[j] = -sin(phi) * e1[j] + cos(phi) * e2[j];
        f->gen[j] = k * radial + nr * u[j];
    }
    f->size = L / 2 + fmax(rc->r0, rc->r1);
    return 1;
}

/* Rays through a point of a seam (a tangent circle), rounded to floats, entering the hull:
 * a closed hull is hit there, never missed, and the band allows both the side and the cap;
 * with that end open the band allows the side at the seam. */
static void test_seams(void)
{
    enum { N = 400 };
    const int n = rc_quick() ? N / 4 : N;
    static rc_case cs[N];
    const int cats[] = {RC_ORDINARY, RC_STRONG, RC_CAPSULE, RC_POINT, RC_THIN, RC_SLIGHT};
    uint64_t s = 0x7365616d;
    int rays = 0, leaks = 0, both = 0, side_open = 0, open = 0;
    for (size_t ci = 0; ci < sizeof cats / sizeof *cats; ci++) {
        rc_make(cats[ci], 99, n, cs);
        for (int i = 0; i < n; i++) {
            rc_case *c = &cs[i];
            const int end = i & 1;
            const double phi = rc_unif(&s, 0, 6.283185307179586);
            const double tw = rc_unif(&s, -0.6, 0.6), tz = rc_unif(&s, -0.6, 0.6);
            rc_seam f;
            if (!seam_at(&c->rc, end, phi, &f))
                continue;
            double x[3], d[3];
            for (int j = 0; j < 3; j++) {
                x[j] = f.x[j];
                /* in across the seam, along it and along the generator line */
                d[j] = -f.n[j] + tw * f.tang[j] + tz * f.gen[j];
            }
            const double size = f.size;
            for (int j = 0; j < 3; j++) {
                c->o[j] = (float)(x[j] - 3 * size * d[j]);
                c->d[j] = (float)d[j];
            }
            c->tmin = 0;
            c->tmax = INFINITY;
            c->rc.flags = i % 4 < 2 ? CYLRAY_CAPPED : end ? CYLRAY_CAPPED_LO : CYLRAY_CAPPED_HI;
            const int cap = end ? CYLRAY_CAP_HI : CYLRAY_CAP_LO;
            cylref_band b;
            double ub1, ub2;
            rcref_band_eval(&c->rc, c->o, c->d, 0, INFINITY, 0, &b);
            const float t = (float)(3 * size);
            if (c->rc.flags == CYLRAY_CAPPED) {
                rays++;
                const int leak = !b.exact.hit || fabs(b.exact.t - 3 * size) > 1e-4 * size ||
                                 rcref_judge(&b, 0, 0, 0, &ub1) != 1;
                leaks += leak;
                if (leak && leaks < 4)
                    printf("  seam %s #%d: exact %d t %.9g (seam at %.9g) part %#x, "
                           "hit_unstable %d\n",
                           rc_names[cats[ci]], i, b.exact.hit, b.exact.t, 3 * size,
                           b.exact.part, b.hit_unstable);
                both += rcref_judge(&b, 1, CYLRAY_SIDE, t, &ub1) == 0 && ub1 < 1 &&
                        rcref_judge(&b, 1, cap, t, &ub2) == 0 && ub2 < 1;
            } else {
                open++;
                side_open += rcref_judge(&b, 1, CYLRAY_SIDE, t, &ub1) == 0 && ub1 < 1;
            }
        }
    }
    printf(
        "rc seams: %d rays at closed seams, %d missed or judged missable, %d with both parts "
        "allowed; %d at open seams, %d with the side allowed\n",
        rays, leaks, both, open, side_open);
    CHECK(rays > n * 3 / 4 && leaks == 0, "seams: %d leaks of %d", leaks, rays);
    CHECK(both >= rays * 9 / 10, "seams: both parts allowed at %d of %d", both, rays);
    CHECK(side_open >= open * 9 / 10, "open seams: the side allowed at %d of %d", side_open,
          open);
}

/* Rays that graze the hull: along a generator line of the side (from a point of seam 0
 * towards seam 1, and moved off it by 1e-7 or 1e-5 of the size either way), and tangent to
 * the side or a cap. The band's box takes such a ray on and off the hull, and along the
 * line its t moves far: answers from inside the box and the double solver's must all be
 * allowed. */
static void test_grazing(void)
{
    enum { N = 160, INNER = 12 };
    const int n = rc_quick() ? N / 4 : N;
    static rc_case cs[N];
    const int cats[] = {RC_ORDINARY, RC_STRONG, RC_CAPSULE, RC_THIN, RC_EDGE};
    uint64_t s = 0x67727a;
    int rays = 0, bad = 0, dbad = 0, unstable = 0;
    for (size_t ci = 0; ci < sizeof cats / sizeof *cats; ci++) {
        rc_make(cats[ci], 5, n, cs);
        for (int i = 0; i < n; i++) {
            rc_case *c = &cs[i];
            const int kind = i % 4;
            const double phi = rc_unif(&s, 0, 6.283185307179586);
            const double off = kind == 0 ? 0 : (i & 4 ? 1e-7 : 1e-5) * (i & 8 ? 1 : -1);
            const double along = rc_unif(&s, 0.2, 0.8);
            rc_seam f, g;
            if (!seam_at(&c->rc, 0, phi, &f) || !seam_at(&c->rc, 1, phi, &g))
                continue;
            double x[3], d[3];
            for (int j = 0; j < 3; j++) {
                if (kind < 2) { /* along the generator line */
                    x[j] = f.x[j] + off * f.size * f.n[j];
                    d[j] = f.gen[j];
                } else if (kind == 2) { /* tangent to the side, across the generator */
                    x[j] = f.x[j] + along * (g.x[j] - f.x[j]);
                    d[j] = f.tang[j];
                } else { /* tangent to cap 1, past its seam */
                    const double p1 = c->rc.p1[j], r1 = c->rc.r1;
                    const double cn = (g.n[j] + (p1 - c->rc.p0[j]) / (2 * f.size)) / 2;
                    x[j] = p1 + r1 * cn;
                    d[j] = f.tang[j];
                }
            }
            if (kind == 3) {
                double len = 0, dn = 0, nn[3];
                for (int j = 0; j < 3; j++) {
                    nn[j] = x[j] - c->rc.p1[j];
                    len += nn[j] * nn[j];
                }
                for (int j = 0; j < 3; j++) {
                    nn[j] /= sqrt(len);
                    x[j] = c->rc.p1[j] + c->rc.r1 * nn[j];
                    dn += d[j] * nn[j];
                }
                for (int j = 0; j < 3; j++)
                    d[j] -= dn * nn[j];
            }
            for (int j = 0; j < 3; j++) {
                c->o[j] = (float)(x[j] - 3 * f.size * d[j]);
                c->d[j] = (float)d[j];
            }
            c->tmin = 0;
            c->tmax = INFINITY;
            for (unsigned fl = 0; fl <= CYLRAY_CULL_BACK; fl += CYLRAY_CULL_BACK) {
                cylref_band b;
                double ub;
                rcref_band_eval(&c->rc, c->o, c->d, 0, INFINITY, fl, &b);
                rays++;
                unstable += b.hit_unstable;
                for (int j = 0; j < INNER; j++) {
                    int part = 0;
                    float t = 0;
                    double n[3];
                    const int hit = rc_inside_box(c, fl, &s, &part, &t, n);
                    const int v = rcref_judge(&b, hit, part, t, &ub);
                    if ((v || ub > 0.5) && bad++ < 4)
                        printf("  grazing %s #%d kind %d flags %u: inside the box %d t %.9g "
                               "part %#x judged %d, %.3g ulps beyond (exact %d t %.9g part "
                               "%#x)\n",
                               rc_names[cats[ci]], i, kind, fl, hit, (double)t, part, v, ub,
                               b.exact.hit, b.exact.t, b.exact.part);
                }
                int part = 0;
                float t = 0;
                const int hit = rc_dbl_solve(c, fl, &t, &part);
                const int v = rcref_judge(&b, hit, part, t, &ub);
                if ((v || ub > 1) && dbad++ < 4)
                    printf(
                        "  grazing %s #%d kind %d flags %u: double solver %d t %.9g part %#x "
                        "judged %d, %.3g ulps beyond (exact %d t %.9g part %#x)\n",
                        rc_names[cats[ci]], i, kind, fl, hit, (double)t, part, v, ub,
                        b.exact.hit, b.exact.t, b.exact.part);
            }
        }
    }
    printf("rc grazing: %d rays (%d may hit or miss), %d answers from inside the box judged "
           "bad, %d of the double solver\n",
           rays, unstable, bad, dbad);
    CHECK(rays > 6 * n && bad == 0 && dbad == 0, "grazing: %d and %d judged bad of %d", bad,
          dbad, rays);
}

void test_rcref(void)
{
    ref_run_generators(&ref_round_cone_gen);
    test_rcgen_bands();
    test_independent();
    test_symmetry();
    test_band();
    test_seams();
    test_grazing();
}
