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
 *   bounds_test mutant   the checks of "box" applied to a box computed in float from the
 *                        rounded unit axis must fail (the test can fail)
 *
 * CYLRAY_TEST_QUICK=1 shrinks the counts tenfold. */
#include "cylray.h"
#include "tkgen.h"

#include <stdlib.h>

static long failures, checks;

static void fail(const cylray_cylinder *c, const char *what, int k)
{
    if (failures++ < 20)
        fprintf(stderr,
                "FAIL %s (k=%d): c=(%a %a %a) v=(%a %a %a) R=%a H=%a flags=%u\n", what, k,
                c->center[0], c->center[1], c->center[2], c->axis[0], c->axis[1], c->axis[2],
                c->radius, c->half_height, c->flags);
}

/* The naive box a user might write: float arithmetic on the rounded unit axis. */
static void naive_box(const cylray_cylinder *c, float lo[3], float hi[3])
{
    float l = sqrtf(c->axis[0] * c->axis[0] + c->axis[1] * c->axis[1] +
                    c->axis[2] * c->axis[2]);
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
                fail(c, aligned ? "face not the nearest float (coordinate axis)"
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

#define LEAF_CASE_(m)                                                                    \
    static void leaf_case##m(cylgen_rng *g)                                              \
    {                                                                                    \
        static cylray_leaf##m leaf;                                                      \
        cylray_cylinder cs[m];                                                           \
        size_t n = 1 + (size_t)(cylgen_next(g) % m);                                     \
        for (size_t i = 0; i < n; i++)                                                   \
            do                                                                           \
                tk_cylinder(g, (int)(cylgen_next(g) % 10), &cs[i]);                      \
            while (cylray_prepare(&(cylray_prepared){0}, &cs[i]) != CYLRAY_OK);          \
        if (cylray_leaf_prepare##m(&leaf, cs, NULL, n) != CYLRAY_OK) {                   \
            fail(&cs[0], "leaf_prepare", (int)n);                                        \
            return;                                                                      \
        }                                                                                \
        float lo[3], hi[3], el[3] = {INFINITY, INFINITY, INFINITY},                      \
                            eh[3] = {-INFINITY, -INFINITY, -INFINITY};                   \
        for (size_t i = 0; i < n; i++) {                                                 \
            cylray_prepared p;                                                           \
            float l[3], h[3];                                                            \
            cylray_prepare(&p, &cs[i]);                                                  \
            cylray_bounds(&p, l, h);                                                     \
            for (int k = 0; k < 3; k++)                                                  \
                el[k] = fminf(el[k], l[k]), eh[k] = fmaxf(eh[k], h[k]);                  \
        }                                                                                \
        checks++;                                                                        \
        if (cylray_leaf_bounds##m(&leaf, lo, hi) != CYLRAY_OK ||                         \
            memcmp(lo, el, sizeof lo) || memcmp(hi, eh, sizeof hi))                      \
            fail(&cs[0], "leaf box is not the union of its lanes' boxes", (int)n);      \
        /* an infinite lane: no box, nothing written */                                  \
        cs[n - 1].half_height = INFINITY;                                                \
        float sl[3] = {7, 7, 7}, sh[3] = {7, 7, 7};                                      \
        checks++;                                                                        \
        if (cylray_leaf_prepare##m(&leaf, cs, NULL, n) != CYLRAY_OK ||                   \
            cylray_leaf_bounds##m(&leaf, sl, sh) != CYLRAY_EINVAL || sl[0] != 7 ||       \
            sh[2] != 7)                                                                  \
            fail(&cs[0], "leaf with an infinite lane", (int)n);                          \
        checks++;                                                                        \
        if (cylray_leaf_prepare##m(&leaf, cs, NULL, 0) != CYLRAY_OK ||                   \
            cylray_leaf_bounds##m(&leaf, sl, sh) != CYLRAY_EINVAL || sl[1] != 7 ||       \
            cylray_leaf_bounds##m(NULL, sl, sh) != CYLRAY_EINVAL)                        \
            fail(&cs[0], "empty leaf or NULL", (int)n);                                  \
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
    if (cylray_bounds(&p, NULL, hi) != CYLRAY_EINVAL || cylray_bounds(NULL, lo, hi) != CYLRAY_EINVAL)
        fail(&c, "NULL: EINVAL", -1);
    printf("leaf: %ld checks, %ld failures\n", checks, failures);
    return failures != 0;
}

int main(int argc, char **argv)
{
    const char *quick = getenv("CYLRAY_TEST_QUICK");
    long scale = quick && *quick && *quick != '0' ? 10 : 1;
    const char *what = argc > 1 ? argv[1] : "box";
    if (!strcmp(what, "box"))
        return run_box(40000 / scale, 0);
    if (!strcmp(what, "mutant"))
        return run_box(20000 / scale, 1);
    if (!strcmp(what, "leaf"))
        return run_leaf(3000 / scale);
    fprintf(stderr, "usage: bounds_test box|leaf|mutant\n");
    return 2;
}
