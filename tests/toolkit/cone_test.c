/* SPDX-License-Identifier: MIT */
/* cone_test.c - the toolkit for cones against exact arithmetic (binary128).
 *
 *   cone_test box   each face of cylray_bounds of a prepared cone on the outer side of
 *                   the exact frustum's extreme (the hull of its two discs) and within 2
 *                   floats of it; points of the exact surface inside; leaves of 4, 8
 *                   and 16 cones: the union of their prepared boxes (lanes with r0 ==
 *                   r1, prepared as cylinders, only contained)
 *
 * The exact cone is the prepared one: radius rm + kap z between its discs, its ends at
 * z = -+H|v|. CYLRAY_TEST_QUICK=1 shrinks the counts tenfold. */
#include "cylray.h"
#include "cylref.h"
#include "gen.h"
#include "quad.h"
#include "tcheck.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static double uni(cylgen_rng *r, double a, double b)
{
    return a + (b - a) * cylgen_uniform(r);
}

static void make_cone(cylgen_rng *r, int kind, cylray_cone *c)
{
    double u[3], m[3], l = 0;
    for (int k = 0; k < 3; k++) {
        u[k] = uni(r, -1, 1) * (kind == 3 && k ? 1e-5 : 1); /* nearly axis-aligned */
        l += u[k] * u[k];
    }
    l = sqrt(l);
    const double S = pow(10, uni(r, -3, 3)), D = kind & 1 ? 1e4 * S : S;
    for (int k = 0; k < 3; k++)
        m[k] = D * uni(r, -1, 1);
    double h = S * uni(r, 0.01, 5), r0 = S * uni(r, 0, 2), r1 = S * uni(r, 0, 2);
    if (kind == 2)
        r0 = 0;
    if (r0 == 0 && r1 == 0)
        r1 = S;
    for (int k = 0; k < 3; k++) {
        c->p0[k] = (float)(m[k] - 0.5 * h * u[k] / l);
        c->p1[k] = (float)(m[k] + 0.5 * h * u[k] / l);
    }
    c->r0 = (float)r0, c->r1 = (float)r1;
    c->flags = CYLRAY_CAPPED;
}

/* The exact box of the prepared cone P: lo, hi in binary128. */
static void exact_box(const cylray_prepared *P, cylq lo[3], cylq hi[3])
{
    cylq vv = 0;
    for (int k = 0; k < 3; k++)
        vv += (cylq)P->v[k] * P->v[k];
    const cylq sv = q_sqrt(vv), H = P->half_height;
    cylq r[2];
    if (P->kap == 0)
        r[0] = r[1] = P->radius;
    else {
        const cylq dk = (cylq)P->kap * H * sv;
        r[0] = q_max(0, (cylq)P->rm - dk), r[1] = q_max(0, (cylq)P->rm + dk);
    }
    for (int k = 0; k < 3; k++) {
        const cylq a = P->v[(k + 1) % 3], b = P->v[(k + 2) % 3];
        const cylq n = (cylq)P->v[k] / sv, s = q_sqrt(a * a + b * b) / sv;
        lo[k] = 1e300, hi[k] = -1e300;
        for (int e = 0; e < 2; e++) {
            const cylq d = (cylq)P->c[k] + (e ? H : -H) * n;
            lo[k] = q_min(lo[k], d - r[e] * s);
            hi[k] = q_max(hi[k], d + r[e] * s);
        }
    }
}

static int run_box(long N)
{
    long boxes = 0, outside = 0, loose = 0, leaves = 0, leaf_bad = 0;
    cylgen_rng rng;
    cylgen_seed(&rng, 6101);
    for (long g = 0; g < N; g++) {
        cylray_cone c[16];
        cylray_prepared P[16];
        float ul[3] = {INFINITY, INFINITY, INFINITY}, uh[3] = {-INFINITY, -INFINITY, -INFINITY};
        int ok = 1;
        for (int j = 0; j < 16 && ok; j++) {
            make_cone(&rng, (int)((g + j) % 4), &c[j]);
            if (j == 15 && (g & 1))
                c[j].r1 = c[j].r0 = fmaxf(c[j].r0, c[j].r1); /* a cylinder among cones */
            ok = cylray_prepare_cone(&P[j], &c[j]) == CYLRAY_OK;
        }
        if (!ok)
            continue;
        for (int j = 0; j < 16; j++) {
            float lo[3], hi[3];
            if (cylray_bounds(&P[j], lo, hi) != CYLRAY_OK) {
                outside++;
                continue;
            }
            cylq el[3], eh[3];
            exact_box(&P[j], el, eh);
            boxes++;
            for (int k = 0; k < 3; k++) {
                ul[k] = fminf(ul[k], lo[k]), uh[k] = fmaxf(uh[k], hi[k]);
                if (!((cylq)lo[k] <= el[k] && (cylq)hi[k] >= eh[k])) {
                    if (outside++ < 10)
                        printf("FAIL box: r0=%a r1=%a axis %d: [%a, %a] vs exact [%a, %a]\n",
                               (double)c[j].r0, (double)c[j].r1, k, (double)lo[k],
                               (double)hi[k], (double)el[k], (double)eh[k]);
                }
                if (P[j].kap == 0)
                    continue; /* a cylinder: the cylinder's box, tested elsewhere */
                const float l2 = nextafterf(nextafterf((float)el[k], -INFINITY), -INFINITY);
                const float h2 = nextafterf(nextafterf((float)eh[k], INFINITY), INFINITY);
                if (lo[k] < l2 || hi[k] > h2) {
                    if (loose++ < 10)
                        printf("FAIL loose: r0=%a r1=%a axis %d: [%a, %a] vs exact [%a, %a]\n",
                               (double)c[j].r0, (double)c[j].r1, k, (double)lo[k],
                               (double)hi[k], (double)el[k], (double)eh[k]);
                }
            }
        }
        /* leaves: the union of the lanes' boxes */
        cylray_leaf16 leaf;
        if (cylray_leaf_prepare_cones16(&leaf, c, NULL, 16) != CYLRAY_OK)
            continue;
        float ll[3], lh[3];
        leaves++;
        if (cylray_leaf_bounds16(&leaf, ll, lh) != CYLRAY_OK) {
            leaf_bad++;
            continue;
        }
        for (int k = 0; k < 3; k++) {
            /* the cylinder lane may make the leaf's box differ by its own rounding */
            const int exact_union = !(g & 1);
            if (ll[k] > ul[k] || lh[k] < uh[k] ||
                (exact_union && (ll[k] != ul[k] || lh[k] != uh[k]))) {
                cylq el[3], eh[3];
                exact_box(&P[15], el, eh);
                if (!(g & 1) || ll[k] > (float)el[k] || lh[k] < (float)eh[k]) {
                    if (leaf_bad++ < 10)
                        printf("FAIL leaf: axis %d: [%a, %a] vs union [%a, %a]\n", k,
                               (double)ll[k], (double)lh[k], (double)ul[k], (double)uh[k]);
                }
            }
        }
    }
    printf("box: %ld boxes, %ld not containing the exact one, %ld more than 2 floats out; "
           "%ld leaves, %ld wrong\n",
           boxes, outside, loose, leaves, leaf_bad);
    return boxes > 0 && outside == 0 && loose == 0 && leaf_bad == 0;
}

int main(int argc, char **argv)
{
    const long N = tc_quick() ? 300 : 3000;
    const char *mode = argc > 1 ? argv[1] : "";
    int ok;
    if (strcmp(mode, "box") == 0)
        ok = run_box(N);
    else {
        fprintf(stderr, "usage: cone_test box\n");
        return 2;
    }
    printf("%s: %s\n", mode, ok ? "ok" : "FAILED");
    return ok ? 0 : 1;
}
