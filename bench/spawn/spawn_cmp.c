/* SPDX-License-Identifier: MIT */
/* spawn_cmp.c - cylspawn: secondary-ray origins compared on the same hits.
 *
 *   cylspawn [--hits=N] [--quick]
 *
 * Five ways to start a reflected, transmitted or shadow ray from a hit on a cylinder:
 *   cylray   cylray_hit_point + cylray_spawn_origin, tmin = 0
 *   pbrt-v4  the point o + t d reprojected radially in float (axially onto a cap), bound
 *            gamma(3) |p_k| per coordinate, origin offset along the normal by
 *            sum |n_k| gamma(3) |p_k| and pushed one float further (OffsetRayOrigin)
 *   mitsuba  the same reprojected point, origin offset along the normal by
 *            1500 2^-24 (1 + max|p_k|) = 8.94e-5 (1 + max|p_k|) (Interaction::offset_p)
 *   embree   the point o + t d unmoved, tmin = 1024 FLT_EPSILON max(|p_x|, |p_y|,
 *            |p_z|, t |d|) over |w| (the tutorials' dg.eps for round curves; other
 *            geometry there uses 32 instead of 1024)
 *   bare     the point o + t d, tmin = 0
 * For each: the rate of self-intersections (the kernel's first hit is the surface left,
 * at that point: tests/spawn/spawnref.h), the rate at which a coaxial cylinder 1e-5 R
 * inside is missed by the transmitted ray (where the exact ray meets it), the offset
 * (|origin - point|, or tmin |w|) over the exact distance from the point to the surface
 * (median), the offset in float ulps of max|p_k| (median), the offset over Mitsuba's for
 * the same ray (median) and the cost of point + origin in ns per ray (hits in L2). */
#include "clock.h"
#include "machine.h"
#include "cylref.h"
#include "spawnref.h"

#include "cylray.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { S_CYLRAY, S_PBRT, S_MITSUBA, S_EMBREE, S_BARE, S_COUNT };
static const char *const scheme_name[S_COUNT] = {"cylray", "pbrt-v4", "mitsuba", "embree",
                                                 "bare tmin=0"};

typedef struct hitrec {
    cylray_prepared P;
    int cyl_index;
    float o[3], d[3], t;
    int32_t part;
} hitrec;

/* The point as a float-arithmetic renderer reprojects it: radially onto the side, or
 * onto a cap's plane, with the unit axis of cylray_prepared (n). */
static void float_reproject(const cylray_prepared *P, const float o[3], const float d[3],
                            float t, int part, float p[3], float n[3])
{
    float q[3], z = 0, r[3], l = 0;
    for (int k = 0; k < 3; k++) {
        p[k] = o[k] + t * d[k];
        q[k] = p[k] - P->c[k];
        z += q[k] * P->n[k];
    }
    for (int k = 0; k < 3; k++) {
        r[k] = q[k] - z * P->n[k];
        l += r[k] * r[k];
    }
    l = sqrtf(l);
    const int pm = part & CYLRAY_PART_MASK;
    for (int k = 0; k < 3; k++) {
        if (pm == CYLRAY_SIDE) {
            p[k] = P->c[k] + z * P->n[k] + r[k] * (P->radius / l);
            n[k] = r[k] / l;
        } else {
            const float s = pm == CYLRAY_CAP_HI ? 1.0f : -1.0f;
            p[k] = P->c[k] + s * P->half_height * P->n[k] + r[k];
            n[k] = s * P->n[k];
        }
    }
}

static double vlen(const float a[3])
{
    return sqrt((double)a[0] * a[0] + (double)a[1] * a[1] + (double)a[2] * a[2]);
}

/* One scheme's start for direction w: origin x0 and tmin; p is its hit point. */
static void scheme(int s, const hitrec *h, const float w[3], float p[3], float x0[3],
                   float *tmin)
{
    float n[3];
    *tmin = 0;
    switch (s) {
    case S_CYLRAY: {
        float err;
        cylray_hit_point(&h->P, h->o, h->d, h->t, h->part, p, &err);
        cylray_spawn_origin(&h->P, p, err, h->part, w, x0);
        return;
    }
    case S_PBRT: {
        const float g3 = 3 * 0x1p-24f / (1 - 3 * 0x1p-24f);
        float_reproject(&h->P, h->o, h->d, h->t, h->part, p, n);
        float dd = 0, wn = 0;
        for (int k = 0; k < 3; k++) {
            dd += fabsf(n[k]) * g3 * fabsf(p[k]);
            wn += w[k] * n[k];
        }
        for (int k = 0; k < 3; k++) {
            float off = (wn < 0 ? -dd : dd) * n[k];
            x0[k] = p[k] + off;
            if (off > 0)
                x0[k] = nextafterf(x0[k], INFINITY);
            else if (off < 0)
                x0[k] = nextafterf(x0[k], -INFINITY);
        }
        return;
    }
    case S_MITSUBA: {
        float_reproject(&h->P, h->o, h->d, h->t, h->part, p, n);
        float m = fmaxf(fabsf(p[0]), fmaxf(fabsf(p[1]), fabsf(p[2])));
        float mag = (1 + m) * (1500 * 0x1p-24f), wn = w[0] * n[0] + w[1] * n[1] + w[2] * n[2];
        mag = wn < 0 ? -mag : mag;
        for (int k = 0; k < 3; k++)
            x0[k] = fmaf(mag, n[k], p[k]);
        return;
    }
    default: {
        for (int k = 0; k < 3; k++)
            x0[k] = p[k] = h->o[k] + h->t * h->d[k];
        if (s == S_EMBREE) {
            float m = fmaxf(fabsf(p[0]), fmaxf(fabsf(p[1]), fabsf(p[2])));
            m = fmaxf(m, h->t * (float)vlen(h->d));
            *tmin = (float)(1024 * FLT_EPSILON * m / vlen(w));
        }
        return;
    }
    }
}

static int cmpd(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *v, size_t n)
{
    if (!n)
        return NAN;
    qsort(v, n, sizeof *v, cmpd);
    return v[n / 2];
}

/* The first hit of one ray on one cylinder (best ISA); returns 1 and t, part on a hit. */
static int trace1(const cylray_kernels *k, const cylray_prepared *P, const float x0[3],
                  const float w[3], float tmin, float tmax, float *t, int32_t *part)
{
    cylray_ray4 r;
    cylray_hit4 h;
    memset(&r, 0, sizeof r);
    r.ox[0] = x0[0], r.oy[0] = x0[1], r.oz[0] = x0[2];
    r.dx[0] = w[0], r.dy[0] = w[1], r.dz[0] = w[2];
    r.tmin[0] = tmin, r.tmax[0] = tmax;
    if (!k->intersect4(P, &r, &h, 1u, 0))
        return 0;
    *t = h.t[0];
    *part = h.part[0];
    return 1;
}

int main(int argc, char **argv)
{
    long nhits = 200000;
    for (int i = 1; i < argc; i++) {
        if (strncmp(argv[i], "--hits=", 7) == 0)
            nhits = atol(argv[i] + 7);
        else if (strcmp(argv[i], "--quick") == 0)
            nhits = 20000;
        else {
            fprintf(stderr, "usage: cylspawn [--hits=N] [--quick]\n");
            return 2;
        }
    }
    const cylray_kernels *K = cylray_kernels_best();
    machine_info mi;
    machine_probe(&mi);

    /* the hits: every category in turn, one cylinder per group */
    hitrec *H = malloc((size_t)nhits * sizeof *H);
    cylray_cylinder *C = malloc((size_t)(nhits / 4 + SREF_COUNT + 1) * sizeof *C);
    long nh = 0, nc = 0;
    for (uint64_t g = 0; nh < nhits; g++) {
        cylgen_case c[SREF_GROUP];
        sref_group((int)(g % SREF_COUNT), 31000 + g, c);
        cylray_prepared P;
        if (cylray_prepare(&P, &c[0].cyl) != CYLRAY_OK)
            continue;
        C[nc] = c[0].cyl;
        for (int i = 0; i < SREF_GROUP && nh < nhits; i++) {
            float t;
            int32_t part;
            if (!trace1(K, &P, c[i].o, c[i].d, c[i].tmin, c[i].tmax, &t, &part))
                continue;
            hitrec *h = &H[nh++];
            h->P = P;
            h->cyl_index = (int)nc;
            memcpy(h->o, c[i].o, sizeof h->o);
            memcpy(h->d, c[i].d, sizeof h->d);
            h->t = t;
            h->part = part;
        }
        if (++nc >= nhits / 4 + SREF_COUNT)
            break;
    }

    /* the directions, the same for every scheme: 2 reflected, 2 transmitted, 1 shadow */
    enum { NDIR = 5 };
    float(*W)[NDIR][3] = malloc((size_t)nh * sizeof *W);
    float(*TM)[NDIR] = malloc((size_t)nh * sizeof *TM);
    cylgen_rng rng;
    cylgen_seed(&rng, 123);
    for (long i = 0; i < nh; i++) {
        float p[3], err;
        double n[3];
        cylray_hit_point(&H[i].P, H[i].o, H[i].d, H[i].t, H[i].part, p, &err);
        sref_normal(&C[H[i].cyl_index], p, H[i].part, n);
        const int refl = H[i].part & CYLRAY_BACKFACE ? -1 : 1;
        for (int j = 0; j < NDIR; j++) {
            TM[i][j] = INFINITY;
            if (j == 4) {
                double u[3], dist = C[H[i].cyl_index].radius * exp(cylgen_uniform(&rng) * 7);
                sref_unit(&rng, u);
                for (int k = 0; k < 3; k++)
                    W[i][j][k] = (float)(dist * u[k]);
                TM[i][j] = 1.0f;
            } else {
                sref_direction(&rng, n, j < 2 ? refl : -refl, W[i][j]);
            }
        }
    }

    double *ratio = malloc((size_t)nh * NDIR * sizeof *ratio);
    double *ulps = malloc((size_t)nh * NDIR * sizeof *ulps);
    double row_self[S_COUNT], row_ratio[S_COUNT], row_ulps[S_COUNT], row_ns[S_COUNT];
    double row_nested[S_COUNT], row_mits[S_COUNT];
    long spawned = nh * NDIR;
    /* Mitsuba's offsets, to which each scheme's are compared ray by ray */
    double *mits = malloc((size_t)nh * NDIR * sizeof *mits);
    for (long i = 0; i < nh; i++)
        for (int j = 0; j < NDIR; j++) {
            float p[3], x0[3], tmin;
            scheme(S_MITSUBA, &H[i], W[i][j], p, x0, &tmin);
            float dx[3] = {x0[0] - p[0], x0[1] - p[1], x0[2] - p[2]};
            mits[i * NDIR + j] = vlen(dx);
        }
    for (int s = 0; s < S_COUNT; s++) {
        long self = 0;
        size_t nr = 0, nu = 0;
        double *relm = malloc((size_t)nh * NDIR * sizeof *relm);
        size_t na = 0;
        for (long i = 0; i < nh; i++) {
            const cylray_cylinder *cyl = &C[H[i].cyl_index];
            for (int j = 0; j < NDIR; j++) {
                float p[3], x0[3], tmin, t;
                int32_t part;
                scheme(s, &H[i], W[i][j], p, x0, &tmin);
                if (trace1(K, &H[i].P, x0, W[i][j], tmin, TM[i][j], &t, &part) &&
                    sref_self_hit(cyl, x0, W[i][j], H[i].part, part, t))
                    self++;
                float dx[3] = {x0[0] - p[0], x0[1] - p[1], x0[2] - p[2]};
                const double off = vlen(dx) + tmin * vlen(W[i][j]);
                const double ex = sref_dist_part(cyl, p, H[i].part);
                const double pm = fmax(fabs(p[0]), fmax(fabs(p[1]), fabs(p[2])));
                relm[na++] = off / mits[i * NDIR + j];
                ulps[nu++] = off / (FLT_EPSILON * 0.5 * pm);
                if (ex > 0)
                    ratio[nr++] = off / ex;
            }
        }
        row_self[s] = (double)self / (double)spawned;
        row_ratio[s] = median(ratio, nr);
        row_ulps[s] = median(ulps, nu);
        row_mits[s] = median(relm, na);
        free(relm);

        /* cost: point + origin, one direction, over the first 2048 hits (in L2, so that
         * memory does not hide the arithmetic), 20 times a sample, best of 7 samples */
        const long nt = nh < 2048 ? nh : 2048;
        double best = INFINITY, sink = 0;
        for (int rep = 0; rep < 7; rep++) {
            double t0 = clk_ns();
            for (int pass = 0; pass < 20; pass++)
                for (long i = 0; i < nt; i++) {
                    float p[3], x0[3], tmin;
                    scheme(s, &H[i], W[i][0], p, x0, &tmin);
                    sink += x0[0] + tmin;
                }
            best = fmin(best, (clk_ns() - t0) / (20.0 * (double)nt));
        }
        row_ns[s] = sink == 12345.678 ? 0 : best;
    }

    /* nested: the transmitted ray must still find a cylinder 1e-5 R further in */
    long nn = 0, nmiss[S_COUNT] = {0};
    cylgen_rng nr_rng;
    cylgen_seed(&nr_rng, 4243);
    for (long i = 0; i < nh / 2; i++) {
        hitrec h;
        cylray_cylinder out, in;
        cylray_prepared Pi;
        sref_nested(&nr_rng, &out, &in, h.o, h.d);
        if (cylray_prepare(&h.P, &out) || cylray_prepare(&Pi, &in))
            continue;
        int32_t part;
        if (!trace1(K, &h.P, h.o, h.d, 0, INFINITY, &h.t, &part) || (part & CYLRAY_BACKFACE))
            continue;
        h.part = part;
        float p[3], err, w[3];
        double n[3];
        cylray_hit_point(&h.P, h.o, h.d, h.t, h.part, p, &err);
        sref_normal(&out, p, h.part, n);
        sref_transmitted(&nr_rng, n, w);
        /* only where the exact ray from cylray's origin (which tests/spawn proves lies
         * between the two) meets the inner cylinder: near a rim it may leave through the
         * gap between the two caps */
        {
            float x0[3], tmin;
            cylref_hit eh;
            scheme(S_CYLRAY, &h, w, p, x0, &tmin);
            if (cylref_intersect(&in, x0, w, 0.0f, INFINITY, 0, &eh) != 1)
                continue;
        }
        nn++;
        for (int s = 0; s < S_COUNT; s++) {
            float x0[3], tmin, t;
            int32_t ip;
            scheme(s, &h, w, p, x0, &tmin);
            if (!trace1(K, &Pi, x0, w, tmin, INFINITY, &t, &ip) || (ip & CYLRAY_BACKFACE))
                nmiss[s]++;
        }
    }
    for (int s = 0; s < S_COUNT; s++)
        row_nested[s] = (double)nmiss[s] / (double)(nn ? nn : 1);

    printf("cylspawn: %ld hits of %d categories, %ld spawned rays per scheme (2 reflected, "
           "2 transmitted, 1 shadow a hit), traced by the %s kernel; %ld nested pairs\n",
           nh, SREF_COUNT, spawned, K->name, nn);
    printf("machine: %s (%s), %d cores%s, %s, %s\n", mi.cpu, mi.cpuid, mi.cores,
           mi.hypervisor ? " under a hypervisor" : "", mi.compiler, mi.buildtype);
    printf("\n| scheme | self-intersections | nested surface missed | offset / exact error "
           "(median) | offset, ulps of max abs p_k (median) | offset / mitsuba's (median) "
           "| point + origin, ns/ray |\n|---|---|---|---|---|---|---|\n");
    for (int s = 0; s < S_COUNT; s++)
        printf("| %s | %.3g %% | %.3g %% | %.3g | %.3g | %.3g | %.1f |\n", scheme_name[s],
               100 * row_self[s], 100 * row_nested[s], row_ratio[s], row_ulps[s], row_mits[s],
               row_ns[s]);
    free(H);
    free(C);
    free(W);
    free(TM);
    free(ratio);
    free(ulps);
    free(mits);
    return 0;
}
