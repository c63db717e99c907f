/* SPDX-License-Identifier: MIT */
/* test_ref.c - tests of the exact references themselves: the cylinder's generators,
 * symmetries, an independent membership check along the ray and the band's verdicts; every
 * shape's hand-computed answers (test_hand.c), the sphere's, the cone's and the round
 * cone's own tests (test_sphref.c, test_conref.c, test_rcref.c). */
#include "gen.h"
#include "test_ref.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- symmetries ------------------------------------------------------------------ */

static int close_t(double a, double b)
{
    return a == b || fabs(a - b) <= 4 * 0x1p-52 * fabs(a);
}

typedef struct {
    cylray_cylinder cyl;
    float o[3], d[3];
} geo;

static geo geo_of(const cylgen_case *c)
{
    geo g;
    g.cyl = c->cyl;
    memcpy(g.o, c->o, sizeof g.o);
    memcpy(g.d, c->d, sizeof g.d);
    return g;
}

static void map3(float v[3], const int perm[3], const float sgn[3])
{
    float t[3] = {v[perm[0]] * sgn[0], v[perm[1]] * sgn[1], v[perm[2]] * sgn[2]};
    memcpy(v, t, sizeof t);
}

/* A coordinate permutation with mirror signs moves nothing but the frame. */
static geo rigid(geo g, const int perm[3], const float sgn[3])
{
    map3(g.cyl.center, perm, sgn);
    map3(g.cyl.axis, perm, sgn);
    map3(g.o, perm, sgn);
    map3(g.d, perm, sgn);
    return g;
}

static void test_symmetry(void)
{
    enum { N = 160 };
    static cylgen_case cs[N];
    int checked = 0;
    for (int cat = 0; cat < cylgen_category_count(); cat++) {
        cylgen_make(cat, 12345, N, cs);
        for (int i = 0; i < N; i++) {
            const cylgen_case *c = &cs[i];
            cylref_hit h0, h1;
            cylref_intersect(&c->cyl, c->o, c->d, c->tmin, c->tmax, 0, &h0);
            geo g0 = geo_of(c);

            const int perm[3] = {2, 0, 1};
            const float sgn[3] = {-1, 1, -1};
            geo g = rigid(g0, perm, sgn);
            cylref_intersect(&g.cyl, g.o, g.d, c->tmin, c->tmax, 0, &h1);
            CHECK(h0.hit == h1.hit && (!h0.hit || (close_t(h0.t, h1.t) && h0.part == h1.part)),
                  "%s #%d rotated: hit %d/%d t %.17g/%.17g part %d/%d",
                  cylgen_category_name(cat), i, h0.hit, h1.hit, h0.t, h1.t, h0.part, h1.part);

            /* The axis reversed: the same solid, the caps swap names (and so do the
             * flags of a cylinder with one cap). */
            g = g0;
            for (int k = 0; k < 3; k++)
                g.cyl.axis[k] = -g.cyl.axis[k];
            if ((g.cyl.flags & CYLRAY_CAPPED) != CYLRAY_CAPPED)
                g.cyl.flags ^= g.cyl.flags & CYLRAY_CAPPED ? CYLRAY_CAPPED : 0u;
            cylref_intersect(&g.cyl, g.o, g.d, c->tmin, c->tmax, 0, &h1);
            int p0 = h0.part & CYLRAY_PART_MASK, p1 = h1.part & CYLRAY_PART_MASK;
            int swapped = p0 == CYLRAY_SIDE ? p1 == CYLRAY_SIDE : p0 + p1 == 5;
            CHECK(h0.hit == h1.hit &&
                      (!h0.hit || (close_t(h0.t, h1.t) && swapped &&
                                   (h0.part & CYLRAY_BACKFACE) == (h1.part & CYLRAY_BACKFACE))),
                  "%s #%d axis reversed: t %.17g/%.17g part %d/%d", cylgen_category_name(cat),
                  i, h0.t, h1.t, h0.part, h1.part);

            /* Every length doubled and d kept: t doubles, exactly. */
            g = g0;
            for (int k = 0; k < 3; k++) {
                g.cyl.center[k] *= 2;
                g.o[k] *= 2;
            }
            g.cyl.radius *= 2;
            g.cyl.half_height *= 2;
            cylref_intersect(&g.cyl, g.o, g.d, 2 * c->tmin, 2 * c->tmax, 0, &h1);
            CHECK(h0.hit == h1.hit &&
                      (!h0.hit || (close_t(2 * h0.t, h1.t) && h0.part == h1.part)),
                  "%s #%d scaled: t %.17g/%.17g", cylgen_category_name(cat), i, h0.t, h1.t);

            /* Scaling the axis by 2 changes nothing. */
            g = g0;
            for (int k = 0; k < 3; k++)
                g.cyl.axis[k] *= 2;
            cylref_intersect(&g.cyl, g.o, g.d, c->tmin, c->tmax, 0, &h1);
            CHECK(h0.hit == h1.hit && (!h0.hit || (close_t(h0.t, h1.t) && h0.part == h1.part)),
                  "%s #%d axis x2: t %.17g/%.17g", cylgen_category_name(cat), i, h0.t, h1.t);
            checked++;
        }
    }
    printf("symmetry: %d cases x 4 transforms\n", checked);
}

/* ---- membership along the ray ------------------------------------------------------ *
 * An independent check in long double (at least as precise as double): sample the
 * segment before the hit and check that the solid is not entered (front hit) or not
 * left (back hit) there; after a miss, that membership never changes. Capped and
 * infinite solids only (an open tube has no inside). Coarse, so it allows a margin of
 * 1e-6 of the t range around the ends: it catches a wrong root or a wrong part, not
 * the last digits. */
static int member(const cylray_cylinder *c, const float o[3], const float d[3], long double t)
{
    long double v[3], w[3], vv = 0, wv = 0, ww = 0;
    for (int k = 0; k < 3; k++) {
        v[k] = c->axis[k];
        w[k] = o[k] + t * d[k] - (long double)c->center[k];
        vv += v[k] * v[k];
        wv += w[k] * v[k];
        ww += w[k] * w[k];
    }
    long double perp2 = ww - wv * wv / vv, z = wv / sqrtl(vv);
    int in = perp2 <= (long double)c->radius * c->radius;
    if (isfinite(c->half_height))
        in = in && fabsl(z) <= c->half_height;
    return in;
}

static void test_membership(void)
{
    enum { N = 320, S = 200 };
    static cylgen_case cs[N];
    int checked = 0;
    const int cats[] = {CYLGEN_ORDINARY, CYLGEN_INSIDE,       CYLGEN_INFINITE,
                        CYLGEN_RIM,      CYLGEN_UNNORMALIZED, CYLGEN_HUGE};
    for (size_t ci = 0; ci < sizeof cats / sizeof cats[0]; ci++) {
        cylgen_make(cats[ci], 777, N, cs);
        for (int i = 0; i < N; i++) {
            const cylgen_case *c = &cs[i];
            int solid = (c->cyl.flags & CYLRAY_CAPPED) || !isfinite(c->cyl.half_height);
            if (!solid)
                continue;
            cylref_hit h;
            cylref_intersect(&c->cyl, c->o, c->d, c->tmin, c->tmax, 0, &h);
            long double t0 = c->tmin;
            long double t1 = h.hit ? h.t : (isfinite(c->tmax) ? c->tmax : 1e7L * c->cyl.radius);
            if (!(t1 > t0))
                continue;
            long double span = t1 - t0, eps = span * 1e-6L;
            int first = member(&c->cyl, c->o, c->d, t0 + eps);
            int bad = 0;
            for (int s = 0; s <= S && !bad; s++) {
                long double t = t0 + eps + (span - 2 * eps) * s / S;
                bad = member(&c->cyl, c->o, c->d, t) != first;
            }
            int want_first = h.hit ? (h.part & CYLRAY_BACKFACE) != 0 : first;
            CHECK(
                !bad && first == want_first,
                "%s #%d: membership on [tmin, t) %s (starts %s), reference %s part %#x t %.9g",
                cylgen_category_name(cats[ci]), i, bad ? "changes" : "constant",
                first ? "inside" : "outside", h.hit ? "hit" : "miss", h.part, h.t);
            if (h.hit) {
                int after = member(&c->cyl, c->o, c->d, h.t + eps);
                CHECK(after != first || (h.part & CYLRAY_BACKFACE) == 0 ? 1 : 0,
                      "%s #%d: still inside after the exit", cylgen_category_name(cats[ci]), i);
            }
            checked++;
        }
    }
    printf("membership: %d rays\n", checked);
}

/* ---- the band ------------------------------------------------------------------- */

static void test_band(void)
{
    cylref_band b;
    cylray_cylinder c = cyl_z(1, 2, CYLRAY_CAPPED);
    const float o[3] = {-5, 0.25f, 0.5f}, d[3] = {1, 0, 0};
    cylref_band_eval(&c, o, d, 0, INFINITY, 0, &b);
    CHECK(b.exact.hit && !b.decision_unstable, "ordinary: unstable");
    CHECK(b.t_lo <= b.exact.t && b.exact.t <= b.t_hi, "ordinary: exact outside its band");
    CHECK(cylref_ulps(b.t_hi, b.exact.t) < 40 && cylref_ulps(b.t_lo, b.exact.t) < 40,
          "ordinary: band [%a, %a] too wide around %a", b.t_lo, b.t_hi, b.exact.t);
    CHECK(b.evals >= 16 && b.evals <= 32, "evals %d", b.evals);
    double ub;
    CHECK(cylref_judge(&b, 1, CYLRAY_SIDE, (float)b.exact.t, &ub) == 0 && ub == 0,
          "judge exact");
    CHECK(cylref_judge(&b, 0, 0, 0, &ub) == 1, "judge miss");
    CHECK(cylref_judge(&b, 1, CYLRAY_CAP_LO, (float)b.exact.t, &ub) == 2, "judge part");
    float far = nextafterf(nextafterf((float)b.t_hi, INFINITY), INFINITY);
    for (int k = 0; k < 8; k++)
        far = nextafterf(far, INFINITY);
    CHECK(cylref_ulps_beyond(far, &b) >= 9, "beyond %g", cylref_ulps_beyond(far, &b));

    /* Tangent: hit or miss may both be right. */
    const float ot[3] = {-5, 1, 0};
    cylref_band_eval(&c, ot, d, 0, INFINITY, 0, &b);
    CHECK(b.exact.hit && b.hit_unstable, "tangent: stable?");
    CHECK(cylref_judge(&b, 0, 0, 0, &ub) == 0, "tangent: miss not excused");

    /* Exactly through the rim: a hit for sure, side or cap. */
    const float orim[3] = {-2, 0, 3}, drim[3] = {1, 0, -1};
    cylref_band_eval(&c, orim, drim, 0, INFINITY, 0, &b);
    CHECK(b.exact.hit && !b.hit_unstable && b.part_unstable,
          "rim: hit %d hit_unst %d part_unst %d", b.exact.hit, b.hit_unstable, b.part_unstable);
    CHECK(cylref_judge(&b, 1, CYLRAY_CAP_HI, 1.0f, &ub) == 0 && ub == 0,
          "rim: cap not allowed");
    CHECK(cylref_judge(&b, 0, 0, 0, &ub) == 1, "rim: miss excused");

    /* t within an ulp of tmax (or tmin): hit or miss. */
    cylref_band_eval(&c, o, d, 0, INFINITY, 0, &b);
    float t_up = nextafterf((float)b.exact.t, INFINITY), t_dn = nextafterf((float)b.exact.t, 0);
    cylref_band_eval(&c, o, d, 0, t_up, 0, &b);
    CHECK(b.exact.hit && b.hit_unstable, "t just below tmax: stable?");
    cylref_band_eval(&c, o, d, 0, t_dn, 0, &b);
    CHECK(!b.exact.hit && b.hit_unstable, "t just above tmax: stable?");
    cylref_band_eval(&c, o, d, t_dn, INFINITY, CYLRAY_CULL_BACK, &b);
    CHECK(b.exact.hit && b.hit_unstable, "t just above tmin: stable?");

    /* A secondary ray from the surface point, outward: self-hit or not, undecidable. */
    const float os[3] = {1, 0, 0.5f}, ds[3] = {0.6f, 0.8f, 0};
    cylref_band_eval(&c, os, ds, 0, INFINITY, 0, &b);
    CHECK(b.hit_unstable, "surface: stable?");

    /* Ordinary categories: mostly stable, bands narrow. */
    enum { N = 400 };
    static cylgen_case cs[N];
    cylgen_make(CYLGEN_ORDINARY, 99, N, cs);
    int unstable = 0, hits = 0, wide = 0, outside = 0;
    for (int i = 0; i < N; i++) {
        const cylgen_case *k = &cs[i];
        cylref_band_eval(&k->cyl, k->o, k->d, k->tmin, k->tmax, 0, &b);
        unstable += b.decision_unstable;
        if (b.exact.hit && !b.decision_unstable) {
            hits++;
            outside += !(b.t_lo <= b.exact.t && b.exact.t <= b.t_hi);
            /* Moving the inputs by 2 ulps of their size moves t by about that much
             * over |d|, whatever the size of t: bound the band by it. */
            double s = 0;
            for (int j = 0; j < 3; j++)
                s = fmax(s, fmax(fabs(k->o[j]), fabs(k->cyl.center[j])));
            s = fmax(s, k->cyl.radius) /
                sqrt(k->d[0] * k->d[0] + k->d[1] * k->d[1] + k->d[2] * k->d[2]);
            double half = 0.5 * (b.t_hi - b.t_lo) / cylref_float_ulp(s);
            wide += half > 2 * 14 * 8; /* 14 inputs x 2 ulps, x 8 for leverage */
        }
    }
    printf("band, ordinary: %d of %d unstable, %d stable hits, %d with a band beyond bound\n",
           unstable, N, hits, wide);
    CHECK(unstable < N / 20, "too many unstable: %d", unstable);
    CHECK(hits > N / 4, "too few hits: %d", hits);
    CHECK(outside == 0, "exact outside its band: %d", outside);
    CHECK(wide < hits / 20, "too many wide bands: %d", wide);
}

static void test_generators(void)
{
    enum { N = 64 };
    static cylgen_case a[N], b[N];
    CHECK(cylgen_category_count() == CYLGEN_COUNT, "count");
    for (int cat = 0; cat < CYLGEN_COUNT; cat++) {
        const char *name = cylgen_category_name(cat);
        CHECK(name && cylgen_category_find(name) == cat, "name %d", cat);
        cylgen_make(cat, 5, N, a);
        cylgen_make(cat, 5, N / 2, b);
        CHECK(memcmp(a, b, sizeof a[0] * (N / 2)) == 0, "%s: not prefix-stable", name);
        int hits = 0, capped = 0, aligned = 0;
        for (int i = 0; i < N; i++) {
            cylref_hit h;
            CHECK(cylref_intersect(&a[i].cyl, a[i].o, a[i].d, a[i].tmin, a[i].tmax, 0, &h) >= 0,
                  "%s #%d: invalid cylinder", name, i);
            hits += h.hit;
            capped += (a[i].cyl.flags & CYLRAY_CAPPED) != 0;
            aligned +=
                (a[i].cyl.axis[0] == 0) + (a[i].cyl.axis[1] == 0) + (a[i].cyl.axis[2] == 0) ==
                2;
            if (i % CYLGEN_BATCH)
                CHECK(memcmp(&a[i].cyl, &a[i - 1].cyl, sizeof a[i].cyl) == 0, "%s: batch",
                      name);
        }
        printf("gen %-13s %2d/%d hit, %2d capped, %2d axis-aligned\n", name, hits, N, capped,
               aligned);
        CHECK(hits > 0, "%s: no hits at all", name);
    }
    cylgen_make_shared(CYLGEN_FAR, 5, N, a);
    for (int i = 1; i < N; i++)
        CHECK(memcmp(&a[i].cyl, &a[0].cyl, sizeof a[0].cyl) == 0, "shared");
}

/* Each part with its count of checks, so that a change to the tests shows what it took or
 * added. */
static void part(const char *name, void (*run)(void))
{
    long c0 = ref_checks, f0 = ref_failures;
    run();
    printf("ref-selftest %-18s %6ld checks, %ld failures\n", name, ref_checks - c0,
           ref_failures - f0);
}

int main(void)
{
    part("cylinder hand", test_hand_cylinder);
    part("cylinder generators", test_generators);
    part("cylinder symmetry", test_symmetry);
    part("cylinder membership", test_membership);
    part("cylinder band", test_band);
    part("sphere hand", test_hand_sphere);
    part("sphere", test_sphref);
    part("cone hand", test_hand_cone);
    part("cone", test_conref);
    part("round cone hand", test_hand_round_cone);
    part("round cone hand band", test_band_round_cone);
    part("round cone", test_rcref);
    printf("ref-selftest: %ld checks, %ld failures\n", ref_checks, ref_failures);
    return ref_failures != 0;
}
