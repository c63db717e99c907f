/* SPDX-License-Identifier: MIT */
/* cone_test.c - the toolkit for cones against exact arithmetic (binary128).
 *
 *   cone_test box   each face of cylray_bounds of a prepared cone on the outer side of
 *                   the exact frustum's extreme (the hull of its two discs) and within 2
 *                   floats of it; points of the exact surface inside; leaves of 4, 8
 *                   and 16 cones: the union of their prepared boxes (lanes with r0 ==
 *                   r1, prepared as cylinders, only contained)
 *   cone_test split cylray_split_boxes: k = 0 gives its count; each of k slices on the
 *                   outer side of the exact hull of its two end discs and within 2 floats
 *                   of it; points of the exact surface inside the box of their slice
 *   cone_test surface u, v, dpdu, dpdv at points of the side and discs against the same
 *                   formulas in double: u and v within 2^-20, the derivatives within
 *                   2^-18 of their length; the leaf form equals the prepared one
 *
 * The exact cone is the prepared one: radius ra + kap (z - za) between its discs (from
 * its narrower end, as the kernels form it), its ends at z = -+H|v|.
 * CYLRAY_TEST_QUICK=1 shrinks the counts tenfold. */
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

/* The prepared cone's radius at z = q H |v| is ra + dk (q - qa), dk = kap H |v|: formed
 * from its narrower end (radius ra as given, at q = qa), as the kernels form it. */
static double cone_ra(const cylray_prepared *P)
{
    return P->kap > 0 ? P->r0 : P->r1;
}
static double cone_qa(const cylray_prepared *P)
{
    return P->kap > 0 ? -1.0 : 1.0;
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
        r[0] = q_max(0, cone_ra(P) + dk * (-1 - cone_qa(P)));
        r[1] = q_max(0, cone_ra(P) + dk * (1 - cone_qa(P)));
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

/* The exact box of the slice of P between t = H qa and H qb (the hull of its discs). */
static void exact_slice(const cylray_prepared *P, double qa, double qb, cylq lo[3], cylq hi[3])
{
    cylq vv = 0;
    for (int k = 0; k < 3; k++)
        vv += (cylq)P->v[k] * P->v[k];
    const cylq sv = q_sqrt(vv), H = P->half_height, dk = (cylq)P->kap * H * sv;
    const cylq q[2] = {qa, qb};
    for (int k = 0; k < 3; k++) {
        const cylq a = P->v[(k + 1) % 3], b = P->v[(k + 2) % 3];
        const cylq n = (cylq)P->v[k] / sv, s = q_sqrt(a * a + b * b) / sv;
        lo[k] = 1e300, hi[k] = -1e300;
        for (int e = 0; e < 2; e++) {
            const cylq r = q_max(0, cone_ra(P) + dk * (q[e] - cone_qa(P))),
                       d = (cylq)P->c[k] + H * q[e] * n;
            lo[k] = q_min(lo[k], d - r * s);
            hi[k] = q_max(hi[k], d + r * s);
        }
    }
}

static int run_split(long N)
{
    long slices = 0, outside = 0, loose = 0, points = 0, uncovered = 0;
    cylgen_rng rng;
    cylgen_seed(&rng, 6202);
    for (long g = 0; g < N; g++) {
        cylray_cone c;
        cylray_prepared P;
        make_cone(&rng, (int)(g % 4), &c);
        if (cylray_prepare_cone(&P, &c) != CYLRAY_OK || P.kap == 0)
            continue;
        size_t k = cylray_split_boxes(&P, 0, NULL, NULL);
        if (g & 1)
            k += (size_t)(g % 7);
        if (k == 0 || k > 64) {
            outside++;
            continue;
        }
        float lo[64][3], hi[64][3];
        if (cylray_split_boxes(&P, k, lo, hi) != k) {
            outside++;
            continue;
        }
        double qa = -1;
        for (size_t i = 0; i < k; i++) {
            const double qb = ((double)(i + 1) * 2.0 - (double)k) / (double)k;
            cylq el[3], eh[3];
            exact_slice(&P, qa, qb, el, eh);
            slices++;
            for (int j = 0; j < 3; j++) {
                if (!((cylq)lo[i][j] <= el[j] && (cylq)hi[i][j] >= eh[j]) && outside++ < 10)
                    printf("FAIL slice %zu of %zu axis %d: [%a, %a] vs exact [%a, %a]\n", i, k,
                           j, (double)lo[i][j], (double)hi[i][j], (double)el[j], (double)eh[j]);
                const float l2 = nextafterf(nextafterf((float)el[j], -INFINITY), -INFINITY);
                const float h2 = nextafterf(nextafterf((float)eh[j], INFINITY), INFINITY);
                if ((lo[i][j] < l2 || hi[i][j] > h2) && loose++ < 10)
                    printf("FAIL loose slice %zu of %zu axis %d: [%a, %a] vs exact [%a, %a]\n",
                           i, k, j, (double)lo[i][j], (double)hi[i][j], (double)el[j],
                           (double)eh[j]);
            }
            qa = qb;
        }
        /* points of the side, in the box of their slice (a float margin of the slice's
         * own rounding: the point itself is evaluated in double) */
        double v[3], vv = 0, e1[3], e2[3];
        for (int j = 0; j < 3; j++)
            v[j] = P.v[j], vv += v[j] * v[j];
        const double sv = sqrt(vv), H = P.half_height, dk = (double)P.kap * H * sv;
        double t[3] = {v[1], -v[0], 0};
        if (fabs(v[2]) > fabs(v[0]))
            t[0] = 0, t[1] = v[2], t[2] = -v[1];
        const double tl = sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
        for (int j = 0; j < 3; j++)
            e1[j] = t[j] / tl;
        e2[0] = (v[1] * e1[2] - v[2] * e1[1]) / sv;
        e2[1] = (v[2] * e1[0] - v[0] * e1[2]) / sv;
        e2[2] = (v[0] * e1[1] - v[1] * e1[0]) / sv;
        for (int n = 0; n < 50; n++) {
            const double q = uni(&rng, -1, 1), ph = uni(&rng, 0, 6.283185307179586);
            const double r = fmax(0.0, cone_ra(&P) + dk * (q - cone_qa(&P)));
            size_t i = (size_t)((q + 1) / 2 * (double)k);
            if (i >= k)
                i = k - 1;
            int in = 0;
            for (size_t ii = i ? i - 1 : 0; ii <= i + 1 && ii < k && !in; ii++) {
                int all = 1;
                for (int j = 0; j < 3; j++) {
                    const double x =
                        P.c[j] + H * q * v[j] / sv + r * (cos(ph) * e1[j] + sin(ph) * e2[j]);
                    const double slack = 0x1p-50 * (fabs(P.c[j]) + H + r);
                    all &= x >= (double)lo[ii][j] - slack && x <= (double)hi[ii][j] + slack;
                }
                in = all;
            }
            points++;
            if (!in)
                uncovered++;
        }
    }
    printf("split: %ld slices, %ld not containing the exact one, %ld more than 2 floats out; "
           "%ld points of the side, %ld in no box near their slice\n",
           slices, outside, loose, points, uncovered);
    return slices > 0 && outside == 0 && loose == 0 && uncovered == 0;
}

static double rel3(const float a[3], const double b[3])
{
    double d = 0, l = 0;
    for (int k = 0; k < 3; k++)
        d += (a[k] - b[k]) * (a[k] - b[k]), l += b[k] * b[k];
    return sqrt(d) / fmax(sqrt(l), 1e-300);
}

static int run_surface(long N)
{
    long points = 0, bad_uv = 0, bad_d = 0, leaf_differ = 0;
    cylgen_rng rng;
    cylgen_seed(&rng, 6303);
    for (long g = 0; g < N; g++) {
        cylray_cone c[4];
        cylray_prepared P[4];
        int ok = 1;
        for (int j = 0; j < 4 && ok; j++) {
            make_cone(&rng, (int)((g + j) % 4), &c[j]);
            c[j].flags = CYLRAY_CAPPED;
            ok = cylray_prepare_cone(&P[j], &c[j]) == CYLRAY_OK && P[j].kap != 0;
        }
        cylray_leaf4 leaf;
        if (!ok || cylray_leaf_prepare_cones4(&leaf, c, NULL, 4) != CYLRAY_OK)
            continue;
        for (int j = 0; j < 4; j++) {
            const cylray_prepared *Q = &P[j];
            double n[3], vv = 0;
            for (int k = 0; k < 3; k++)
                vv += (double)Q->v[k] * Q->v[k];
            const double sv = sqrt(vv), H = Q->half_height, dk = (double)Q->kap * H * sv;
            for (int k = 0; k < 3; k++)
                n[k] = Q->v[k] / sv;
            const double sg = n[2] >= 0 ? 1.0 : -1.0, a = -1.0 / (sg + n[2]),
                         b = n[0] * n[1] * a;
            const double b1[3] = {1 + sg * n[0] * n[0] * a, sg * b, -sg * n[0]};
            const double b2[3] = {b, sg + n[1] * n[1] * a, -n[1]};
            const double rlo = fmax(0.0, cone_ra(Q) + dk * (-1 - cone_qa(Q))),
                         rhi = fmax(0.0, cone_ra(Q) + dk * (1 - cone_qa(Q)));
            for (int t = 0; t < 8; t++) {
                const int part = t < 4 ? CYLRAY_SIDE : t < 6 ? CYLRAY_CAP_LO : CYLRAY_CAP_HI;
                const double ph = uni(&rng, 0.01, 6.27), co = cos(ph), si = sin(ph);
                double u = part == CYLRAY_SIDE     ? uni(&rng, 0.01, 0.99)
                           : part == CYLRAY_CAP_LO ? 0
                                                   : 1;
                double rr = rlo + (rhi - rlo) * u;
                if (part != CYLRAY_SIDE && !(rr > 1e-3 * (rlo + rhi)))
                    continue; /* a tip's disc (radius 0 up to rounding): no azimuth */
                if (part != CYLRAY_SIDE)
                    rr *= uni(&rng, 0.05, 1);
                float p[3];
                for (int k = 0; k < 3; k++)
                    p[k] = (float)(Q->c[k] + (2 * u - 1) * H * n[k] +
                                   rr * (co * b1[k] + si * b2[k]));
                /* the reference at the float point */
                double r[3], z = 0, x1 = 0, x2 = 0;
                for (int k = 0; k < 3; k++) {
                    r[k] = (double)p[k] - Q->c[k];
                    z += r[k] * n[k], x1 += r[k] * b1[k], x2 += r[k] * b2[k];
                }
                double phi = atan2(x2, x1);
                if (phi < 0)
                    phi += 6.283185307179586;
                const double cph = cos(phi), sph = sin(phi), rho = sqrt(x1 * x1 + x2 * x2);
                const double ue = part == CYLRAY_SIDE ? (z + H) / (2 * H) : u;
                const double rz = part == CYLRAY_SIDE ? rlo + (rhi - rlo) * fmin(1, fmax(0, ue))
                                  : part == CYLRAY_CAP_LO ? rlo
                                                          : rhi;
                double du[3], dv[3];
                for (int k = 0; k < 3; k++) {
                    const double er = cph * b1[k] + sph * b2[k],
                                 ep = -sph * b1[k] + cph * b2[k];
                    du[k] = part == CYLRAY_SIDE ? 2 * H * n[k] + (rhi - rlo) * er : rz * er;
                    dv[k] = 6.283185307179586 * (part == CYLRAY_SIDE ? rz : rho) * ep;
                }
                float uv[2], pu[3], pv[3], luv[2], lpu[3], lpv[3];
                cylray_surface(Q, p, part, uv, pu, pv);
                cylray_hit1 h;
                memset(&h, 0, sizeof h);
                h.part = part, h.lane = (uint32_t)j;
                cylray_leaf_surface4(&leaf, &h, p, luv, lpu, lpv);
                points++;
                const double dvv = fabs(uv[1] - phi / 6.283185307179586);
                if (fabs(uv[0] - ue) > 0x1p-20 || fmin(dvv, 1 - dvv) > 0x1p-20) {
                    if (bad_uv++ < 10)
                        printf("FAIL uv: part %d: (%a, %a) vs (%a, %a)\n", part, (double)uv[0],
                               (double)uv[1], ue, phi / 6.283185307179586);
                }
                if (rel3(pu, du) > 0x1p-18 || rel3(pv, dv) > 0x1p-18) {
                    if (bad_d++ < 10)
                        printf("FAIL derivatives: part %d: %g %g\n", part, rel3(pu, du),
                               rel3(pv, dv));
                }
                if (memcmp(uv, luv, sizeof uv) || memcmp(pu, lpu, sizeof pu) ||
                    memcmp(pv, lpv, sizeof pv))
                    leaf_differ++;
            }
        }
    }
    printf("surface: %ld points, %ld uv off, %ld derivatives off, %ld leaf forms differ\n",
           points, bad_uv, bad_d, leaf_differ);
    return points > 0 && bad_uv == 0 && bad_d == 0 && leaf_differ == 0;
}

int main(int argc, char **argv)
{
    const long N = tc_quick() ? 300 : 3000;
    const char *mode = argc > 1 ? argv[1] : "";
    int ok;
    if (strcmp(mode, "box") == 0)
        ok = run_box(N);
    else if (strcmp(mode, "split") == 0)
        ok = run_split(N);
    else if (strcmp(mode, "surface") == 0)
        ok = run_surface(N);
    else {
        fprintf(stderr, "usage: cone_test box|split|surface\n");
        return 2;
    }
    printf("%s: %s\n", mode, ok ? "ok" : "FAILED");
    return ok ? 0 : 1;
}
