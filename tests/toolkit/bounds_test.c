/* SPDX-License-Identifier: MIT */
/* bounds_test.c - cylray_bounds and cylray_leaf_bounds4/8/16 against exact arithmetic.
 *
 *   bounds_test box      every kind of cylinder: each face on the outer side of the
 *                        exact face (binary128) and at most one float beyond the nearest
 *                        float there (exactly the nearest along a coordinate axis); dense
 *                        points of the exact surface (rims, side, discs, and each face's
 *                        extreme rim point) inside the box
 *   bounds_test leaf     leaf boxes are the union of their lanes' boxes; infinite lanes,
 *                        empty leaves, infinite and unprepared cylinders: EINVAL, nothing
 *                        written
 *   bounds_test split    cylray_split_boxes: each box on the outer side of its slice's
 *                        exact box and at most one float beyond; points of the exact
 *                        surface (every slice disc's extreme rim points among them) in a
 *                        box; the count of k = 0 is the header's rule
 *   bounds_test mutant   the checks of "box" applied to a box computed in float from the
 *                        rounded unit axis must fail (the test can fail)
 *
 * CYLRAY_TEST_QUICK=1 shrinks the counts tenfold. */
#include "cylray.h"
#include "tcheck.h"
#include "tkgen.h"

#include <stdlib.h>

static long failures, checks;

static void fail(const cylray_cylinder *c, const char *what, int k)
{
    if (failures++ < 20)
        fprintf(stderr, "FAIL %s (k=%d): c=(%a %a %a) v=(%a %a %a) R=%a H=%a flags=%u\n", what,
                k, c->center[0], c->center[1], c->center[2], c->axis[0], c->axis[1], c->axis[2],
                c->radius, c->half_height, c->flags);
}

/* The naive box a user might write: float arithmetic on the rounded unit axis. */
static void naive_box(const cylray_cylinder *c, float lo[3], float hi[3])
{
    float l =
        sqrtf(c->axis[0] * c->axis[0] + c->axis[1] * c->axis[1] + c->axis[2] * c->axis[2]);
    for (int k = 0; k < 3; k++) {
        float n = c->axis[k] / l;
        float e = c->half_height * fabsf(n) + c->radius * sqrtf(fmaxf(0.0f, 1.0f - n * n));
        lo[k] = c->center[k] - e;
        hi[k] = c->center[k] + e;
    }
}

/* Checks one box against the exact cylinder; returns the number of violations. */
static long check_box(const cylray_cylinder *c, const float lo[3], const float hi[3])
{
    long bad = 0;
    tkq q;
    tk_exact(c, &q);
    int aligned = (c->axis[0] == 0) + (c->axis[1] == 0) + (c->axis[2] == 0) == 2;
    cylq mag[3];
    for (int k = 0; k < 3; k++) {
        cylq e = tk_extent(c, k);
        cylq F[2] = {q.c[k] - e, q.c[k] + e};
        mag[k] = q_abs(q.c[k]) + e;
        /* the reference is good to about 2^-110 of the magnitudes */
        cylq eps = mag[k] * (cylq)0x1p-105;
        cylq cancel = mag[k] * (cylq)0x1p-70;
        const float f[2] = {lo[k], hi[k]};
        for (int s = 0; s < 2; s++) {
            checks++;
            int outer = s == 0 ? (cylq)f[s] <= F[s] + eps : (cylq)f[s] >= F[s] - eps;
            if (!outer) {
                fail(c, s ? "hi face inside the exact box" : "lo face inside the exact box", k);
                bad++;
                continue;
            }
            double n = tk_steps(f[s], s == 0 ? F[s] - eps : F[s] + eps);
            double allowed = aligned ? 0 : 1;
            if (q_abs(F[s]) < cancel)
                allowed = 1e9; /* the cancellation regime: checked by distance */
            if (n > allowed) {
                fail(c,
                     aligned ? "face not the nearest float (coordinate axis)"
                             : "face more than one float beyond the nearest",
                     k);
                bad++;
            }
            if (q_abs(F[s]) < cancel && q_abs((cylq)f[s] - F[s]) > mag[k] * (cylq)0x1p-95) {
                fail(c, "face beyond 2^-95 of its magnitude (cancellation)", k);
                bad++;
            }
        }
    }
    /* points of the exact surface: both rims (and each face's extreme point on them),
     * the side between, and the discs */
    for (int end = -1; end <= 1; end += 2) {
        for (int k = 0; k < 3; k++) {
            /* the rim point furthest along +-e_k: direction e_k - n_k n, in the frame */
            cylq u1 = q.b1[k], u2 = q.b2[k];
            if (u1 == 0 && u2 == 0)
                continue;
            for (int sgn = -1; sgn <= 1; sgn += 2) {
                cylq z = q.n[k] * sgn >= 0 ? q.H : -q.H;
                cylq p[3];
                tk_point(&q, z, (double)(sgn * u1), (double)(sgn * u2), q.R, p);
                (void)end;
                for (int j = 0; j < 3; j++) {
                    cylq eps = mag[j] * (cylq)0x1p-100;
                    checks++;
                    if (!((cylq)lo[j] <= p[j] + eps && (cylq)hi[j] >= p[j] - eps)) {
                        fail(c, "extreme rim point outside", j);
                        bad++;
                    }
                }
            }
        }
    }
    for (int i = 0; i < 96; i++) {
        double th = 2 * 3.14159265358979323846 * i / 96.0;
        int which = i % 4; /* rim lo, rim hi, side, disc */
        cylq z = which == 0 ? -q.H : which == 1 ? q.H : q.H * (cylq)((i % 7) / 3.0 - 1.0);
        cylq r = which == 3 ? q.R * (cylq)((i % 5) / 5.0) : q.R;
        if (which == 3)
            z = (i & 8) ? q.H : -q.H;
        cylq p[3];
        tk_point(&q, z, cos(th), sin(th), r, p);
        for (int j = 0; j < 3; j++) {
            cylq eps = mag[j] * (cylq)0x1p-100;
            checks++;
            if (!((cylq)lo[j] <= p[j] + eps && (cylq)hi[j] >= p[j] - eps)) {
                fail(c, "surface point outside", j);
                bad++;
            }
        }
    }
    return bad;
}

/* Kind 10 puts the center at the float nearest the exact extent along k, so that the
 * low face lies within rounding of 0. */
static void touch_zero(cylray_cylinder *c)
{
    int k = 0;
    c->center[k] = (float)tk_extent(c, k);
}

static int run_box(long n, int mutant)
{
    cylgen_rng g;
    cylgen_seed(&g, 23);
    long mutant_bad = 0;
    long per_kind[TK_KINDS] = {0};
    for (long i = 0; i < n; i++) {
        int kind = (int)(i % TK_KINDS);
        cylray_cylinder c;
        tk_cylinder(&g, kind, &c);
        if (kind == 10)
            touch_zero(&c);
        cylray_prepared p;
        if (cylray_prepare(&p, &c) != CYLRAY_OK)
            continue;
        per_kind[kind]++;
        float lo[3] = {NAN, NAN, NAN}, hi[3] = {NAN, NAN, NAN};
        if (mutant) {
            naive_box(&c, lo, hi);
            mutant_bad += check_box(&c, lo, hi) != 0;
            continue;
        }
        if (cylray_bounds(&p, lo, hi) != CYLRAY_OK) {
            fail(&c, "cylray_bounds refused a finite cylinder", -1);
            continue;
        }
        check_box(&c, lo, hi);
    }
    for (int k = 0; k < TK_KINDS; k++)
        printf("  %-16s %ld cylinders\n", tk_kind_names[k], per_kind[k]);
    if (mutant) {
        printf("mutant: %ld of %ld cylinders caught (%ld checks)\n", mutant_bad, n, checks);
        return mutant_bad > n / 4 ? 0 : 1;
    }
    printf("box: %ld checks, %ld failures\n", checks, failures);
    return failures != 0;
}

#define LEAF_CASE_(m)                                                                          \
    static void leaf_case##m(cylgen_rng *g)                                                    \
    {                                                                                          \
        static cylray_leaf##m leaf;                                                            \
        cylray_cylinder cs[m];                                                                 \
        size_t n = 1 + (size_t)(cylgen_next(g) % m);                                           \
        for (size_t i = 0; i < n; i++)                                                         \
            do                                                                                 \
                tk_cylinder(g, (int)(cylgen_next(g) % 10), &cs[i]);                            \
            while (cylray_prepare(&(cylray_prepared){0}, &cs[i]) != CYLRAY_OK);                \
        if (cylray_leaf_prepare##m(&leaf, cs, NULL, n) != CYLRAY_OK) {                         \
            fail(&cs[0], "leaf_prepare", (int)n);                                              \
            return;                                                                            \
        }                                                                                      \
        float lo[3], hi[3], el[3] = {INFINITY, INFINITY, INFINITY},                            \
                            eh[3] = {-INFINITY, -INFINITY, -INFINITY};                         \
        for (size_t i = 0; i < n; i++) {                                                       \
            cylray_prepared p;                                                                 \
            float l[3], h[3];                                                                  \
            cylray_prepare(&p, &cs[i]);                                                        \
            cylray_bounds(&p, l, h);                                                           \
            for (int k = 0; k < 3; k++)                                                        \
                el[k] = fminf(el[k], l[k]), eh[k] = fmaxf(eh[k], h[k]);                        \
        }                                                                                      \
        checks++;                                                                              \
        if (cylray_leaf_bounds##m(&leaf, lo, hi) != CYLRAY_OK || memcmp(lo, el, sizeof lo) ||  \
            memcmp(hi, eh, sizeof hi))                                                         \
            fail(&cs[0], "leaf box is not the union of its lanes' boxes", (int)n);             \
        /* an infinite lane: no box, nothing written */                                        \
        cs[n - 1].half_height = INFINITY;                                                      \
        float sl[3] = {7, 7, 7}, sh[3] = {7, 7, 7};                                            \
        checks++;                                                                              \
        if (cylray_leaf_prepare##m(&leaf, cs, NULL, n) != CYLRAY_OK ||                         \
            cylray_leaf_bounds##m(&leaf, sl, sh) != CYLRAY_EINVAL || sl[0] != 7 || sh[2] != 7) \
            fail(&cs[0], "leaf with an infinite lane", (int)n);                                \
        checks++;                                                                              \
        if (cylray_leaf_prepare##m(&leaf, cs, NULL, 0) != CYLRAY_OK ||                         \
            cylray_leaf_bounds##m(&leaf, sl, sh) != CYLRAY_EINVAL || sl[1] != 7 ||             \
            cylray_leaf_bounds##m(NULL, sl, sh) != CYLRAY_EINVAL)                              \
            fail(&cs[0], "empty leaf or NULL", (int)n);                                        \
    }
LEAF_CASE_(4)
LEAF_CASE_(8)
LEAF_CASE_(16)

static int run_leaf(long n)
{
    cylgen_rng g;
    cylgen_seed(&g, 2323);
    for (long i = 0; i < n; i++) {
        leaf_case4(&g);
        leaf_case8(&g);
        leaf_case16(&g);
    }
    cylray_cylinder c = {{1, 2, 3}, {0, 1, 1}, 1, INFINITY, 0};
    cylray_prepared p, z;
    memset(&z, 0, sizeof z);
    float lo[3] = {7, 7, 7}, hi[3] = {7, 7, 7};
    checks += 3;
    if (cylray_prepare(&p, &c) != CYLRAY_OK || cylray_bounds(&p, lo, hi) != CYLRAY_EINVAL ||
        lo[0] != 7 || hi[1] != 7)
        fail(&c, "infinite cylinder: EINVAL, nothing written", -1);
    if (cylray_bounds(&z, lo, hi) != CYLRAY_EINVAL || lo[2] != 7)
        fail(&c, "unprepared cylinder: EINVAL", -1);
    c.half_height = 1;
    cylray_prepare(&p, &c);
    if (cylray_bounds(&p, NULL, hi) != CYLRAY_EINVAL ||
        cylray_bounds(NULL, lo, hi) != CYLRAY_EINVAL)
        fail(&c, "NULL: EINVAL", -1);
    printf("leaf: %ld checks, %ld failures\n", checks, failures);
    return failures != 0;
}

/* ---- split boxes ------------------------------------------------------------------- */

/* The rule of the header, from the floats: the count k = 0 must give. */
static size_t rule_count(const cylray_cylinder *c)
{
    const float *v = c->axis;
    int m = 0;
    for (int j = 1; j < 3; j++)
        if (fabsf(v[j]) > fabsf(v[m]))
            m = j;
    size_t k = 1;
    for (int j = 0; j < 3; j++) {
        if (j == m || v[j] == 0)
            continue;
        cylq S = (cylq)v[(j + 1) % 3] * v[(j + 1) % 3] + (cylq)v[(j + 2) % 3] * v[(j + 2) % 3];
        /* the smallest k with 2H|n_j|/k <= 2R sqrt(1 - n_j^2) */
        cylq ratio = (cylq)c->half_height * q_abs((cylq)v[j]) / ((cylq)c->radius * q_sqrt(S));
        while ((cylq)k < ratio && k < CYLRAY_SPLIT_MAX)
            k++;
    }
    return k;
}

static long check_split(const cylray_cylinder *c, const cylray_prepared *P, size_t k,
                        const float (*lo)[3], const float (*hi)[3], cylgen_rng *g)
{
    long bad = 0;
    tkq q;
    tk_exact(c, &q);
    cylq s[3], mag[3];
    for (int j = 0; j < 3; j++) {
        cylq vi = c->axis[(j + 1) % 3], vk = c->axis[(j + 2) % 3], vv = 0;
        for (int a = 0; a < 3; a++)
            vv += (cylq)c->axis[a] * c->axis[a];
        s[j] = q_sqrt((vi * vi + vk * vk) / vv);
        mag[j] = q_abs(q.c[j]) + q.H + q.R;
    }
    cylq *t = malloc((k + 1) * sizeof *t);
    for (size_t i = 0; i <= k; i++)
        t[i] = q.H * (cylq)(((double)i * 2.0 - (double)k) / (double)k);
    /* tightness: box i against the exact box of its two discs */
    for (size_t i = 0; i < k; i++) {
        for (int j = 0; j < 3; j++) {
            cylq m0 = q.c[j] + t[i] * q.n[j], m1 = q.c[j] + t[i + 1] * q.n[j];
            cylq F[2] = {q_min(m0, m1) - q.R * s[j], q_max(m0, m1) + q.R * s[j]};
            cylq eps = mag[j] * (cylq)0x1p-104, cancel = mag[j] * (cylq)0x1p-70;
            const float f[2] = {lo[i][j], hi[i][j]};
            for (int e = 0; e < 2; e++) {
                checks++;
                int outer = e == 0 ? (cylq)f[e] <= F[e] + eps : (cylq)f[e] >= F[e] - eps;
                if (!outer) {
                    fail(c, "split face inside its slice's exact box", j), bad++;
                    continue;
                }
                if (q_abs(F[e]) >= cancel) {
                    if (tk_steps(f[e], e ? F[e] + eps : F[e] - eps) > 1)
                        fail(c, "split face more than one float beyond the nearest", j), bad++;
                } else if (q_abs((cylq)f[e] - F[e]) > mag[j] * (cylq)0x1p-95) {
                    fail(c, "split face beyond 2^-95 of its magnitude (cancellation)", j),
                        bad++;
                }
            }
        }
    }
    /* coverage: points of the exact surface, each inside the box of its slice; the rims
     * of every slice disc and their extreme points among them */
    for (int pass = 0; pass < 64 + 6 * (int)(k + 1); pass++) {
        cylq z, r = q.R, pt[3];
        double co, si;
        if (pass < 64) {
            z = q.H * (cylq)(2 * tk_u(g) - 1);
            if (pass % 8 == 0)
                z = q.H * (pass % 16 ? 1 : -1);
            if (pass % 8 == 1)
                r = q.R * (cylq)tk_u(g), z = (pass % 16 > 8) ? q.H : -q.H;
            double th = 6.283185307179586 * tk_u(g);
            co = cos(th), si = sin(th);
        } else {
            int e = (pass - 64) % 6, j = e / 2, sg = e % 2 ? 1 : -1;
            z = t[(pass - 64) / 6];
            co = sg * (double)q.b1[j], si = sg * (double)q.b2[j];
            if (co == 0 && si == 0)
                co = 1;
        }
        tk_point(&q, z, co, si, r, pt);
        size_t i = 0;
        while (i + 1 < k && t[i + 1] < z)
            i++;
        int in = 0;
        for (size_t b = 0; b < k && !in; b++) {
            size_t bi = (i + b) % k; /* its own slice first */
            int ok = 1;
            for (int j = 0; j < 3; j++) {
                cylq eps = mag[j] * (cylq)0x1p-100;
                ok &= (cylq)lo[bi][j] <= pt[j] + eps && (cylq)hi[bi][j] >= pt[j] - eps;
            }
            in = ok;
        }
        checks++;
        if (!in)
            fail(c, "surface point in no split box", (int)k), bad++;
    }
    free(t);
    (void)P;
    return bad;
}

static int run_split(long n)
{
    cylgen_rng g;
    cylgen_seed(&g, 2424);
    long cyls = 0, boxes = 0, at_max = 0;
    float(*lo)[3] = malloc(1000 * sizeof *lo), (*hi)[3] = malloc(1000 * sizeof *hi);
    for (long it = 0; it < n; it++) {
        cylray_cylinder c;
        tk_cylinder(&g, (int)(it % 10), &c);
        if (it % 3 == 0) /* long rods */
            c.half_height = (float)(c.radius * tk_log(&g, 1, 1e5));
        cylray_prepared P;
        if (cylray_prepare(&P, &c) != CYLRAY_OK)
            continue;
        cyls++;
        size_t want = rule_count(&c), ks[4] = {0, 1, 2 + (size_t)(cylgen_next(&g) % 9), 997};
        checks++;
        if (cylray_split_boxes(&P, 0, NULL, NULL) != want ||
            cylray_split_boxes(&P, 0, lo, NULL) != want)
            fail(&c, "the rule's count", (int)want);
        at_max += want == CYLRAY_SPLIT_MAX;
        for (int a = 0; a < (it % 50 == 0 ? 4 : 3); a++) {
            size_t k = ks[a] ? ks[a] : want;
            lo[k][0] = 7;
            checks++;
            if (cylray_split_boxes(&P, ks[a], lo, hi) != k || lo[k][0] != 7) {
                fail(&c, "count returned or written", (int)k);
                continue;
            }
            boxes += (long)k;
            check_split(&c, &P, k, (const float(*)[3])lo, (const float(*)[3])hi, &g);
        }
    }
    cylray_cylinder c = {{1, 2, 3}, {0, 1, 1}, 1, INFINITY, 0};
    cylray_prepared P;
    cylray_prepare(&P, &c);
    lo[0][0] = 7;
    checks++;
    if (cylray_split_boxes(&P, 4, lo, hi) != 0 || cylray_split_boxes(&P, 0, NULL, NULL) != 0 ||
        lo[0][0] != 7)
        fail(&c, "infinite cylinder: 0, nothing written", 0);
    free(lo);
    free(hi);
    printf("split: %ld cylinders (%ld at CYLRAY_SPLIT_MAX by the rule), %ld boxes, %ld checks, "
           "%ld failures\n",
           cyls, at_max, boxes, checks, failures);
    return failures != 0;
}

int main(int argc, char **argv)
{
    long scale = tc_quick() ? 10 : 1;
    const char *what = argc > 1 ? argv[1] : "box";
    if (!strcmp(what, "box"))
        return run_box(40000 / scale, 0);
    if (!strcmp(what, "mutant"))
        return run_box(20000 / scale, 1);
    if (!strcmp(what, "split"))
        return run_split(6000 / scale);
    if (!strcmp(what, "leaf"))
        return run_leaf(3000 / scale);
    fprintf(stderr, "usage: bounds_test box|leaf|split|mutant\n");
    return 2;
}
