/* SPDX-License-Identifier: MIT */
/* spawn_sphere.c - secondary rays from spheres against exact (binary128) arithmetic.
 *
 *   spawn_sphere bounds   hit points (plain and normal forms) of hits found in double and
 *                         by every ISA's kernel: the bound contains the point's exact
 *                         distance from the sphere
 *   spawn_sphere self     rays spawned from kernel hits (reflection, transmission,
 *                         shadow) on every ISA: the origin is strictly on w's side, and no
 *                         ray meets the sphere before half the exact ray's distance
 *   spawn_sphere side     the side form, its side from the kernel's normal or at random:
 *                         strictly on that side, no hit before half the exact distance
 *   spawn_sphere batched  the packet, stream and leaf forms (plain, normal, side) of
 *                         every ISA equal the scalar ones bit for bit
 *
 * Spheres of four kinds: near the world origin, far from it, tiny (radius 2^-58 to
 * 2^-40) and huge (2^40 to 2^60). CYLRAY_TEST_QUICK=1 shrinks the counts a
 * hundredfold. Every count is printed; any violation fails the test. */
#include "spawn_sphere.h"
#include "cylray.h"
#include "cylref.h"
#include "quad.h"
#include "spawnref.h"
#include "tcheck.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void fail(const char *what, const cylray_sphere *s, const char *fmt, double a, double b)
{
    if (failures++ < 20) {
        printf("FAIL %s: sphere c=(%a, %a, %a) R=%a: ", what, (double)s->center[0],
               (double)s->center[1], (double)s->center[2], (double)s->radius);
        printf(fmt, a, b);
        printf("\n");
    }
}

/* A mantissa in [1, 2) times 2^e, e uniform in [lo, hi): the exponent drawn first. */
static double binade(cylgen_rng *r, double lo, double hi)
{
    const int e = (int)uni(r, lo, hi);
    return ldexp(1 + cylgen_uniform(r), e);
}

void make_sphere(cylgen_rng *r, int kind, cylray_sphere *s)
{
    double R, c[3], u[3];
    sref_unit(r, u);
    switch (kind) {
    case K_NEAR:
        R = pow(10, uni(r, -3, 3));
        for (int k = 0; k < 3; k++)
            c[k] = R * uni(r, -4, 4);
        break;
    case K_FAR: {
        R = pow(10, uni(r, -4, 4));
        const double D = pow(10, uni(r, 3, 6)) * (1 + R);
        for (int k = 0; k < 3; k++)
            c[k] = D * u[k];
        break;
    }
    case K_TINY:
        R = binade(r, -58, -40);
        for (int k = 0; k < 3; k++)
            c[k] = R * uni(r, -1e3, 1e3);
        break;
    default:
        R = binade(r, 40, 60);
        for (int k = 0; k < 3; k++)
            c[k] = R * uni(r, -2, 2);
        break;
    }
    for (int k = 0; k < 3; k++)
        s->center[k] = (float)c[k];
    s->radius = (float)R;
}

/* A ray at the sphere: from outside (2 in 3), 1.01 to 1000 R from the center, at a
 * random point of it (grazing ones included); or from inside. Directions of length
 * 1e-2 to 1e2. */
int sphere_rays(cylgen_rng *r, long g, cylray_sphere *s, cylray_prepared *P, float o[16][3],
                float d[16][3])
{
    make_sphere(r, (int)(g % K_COUNT), s);
    if (cylray_prepare_sphere(P, s) != CYLRAY_OK)
        return 0;
    for (int i = 0; i < 16; i++)
        make_ray(r, s, o[i], d[i]);
    return 1;
}

void make_ray(cylgen_rng *r, const cylray_sphere *s, float o[3], float d[3])
{
    double u[3], v[3], R = s->radius, len = pow(10, uni(r, -2, 2));
    sref_unit(r, u);
    sref_unit(r, v);
    if (cylgen_uniform(r) < 2.0 / 3) {
        const double D = R * pow(10, uni(r, 0.005, 3));
        double t[3];
        for (int k = 0; k < 3; k++) {
            o[k] = (float)(s->center[k] + D * u[k]);
            t[k] = s->center[k] + R * v[k];
        }
        double l = 0;
        for (int k = 0; k < 3; k++)
            l += (t[k] - o[k]) * (t[k] - o[k]);
        l = sqrt(l);
        for (int k = 0; k < 3; k++)
            d[k] = (float)(len * (t[k] - o[k]) / l);
    } else {
        const double a = R * uni(r, 0, 0.999);
        for (int k = 0; k < 3; k++) {
            o[k] = (float)(s->center[k] + a * u[k]);
            d[k] = (float)(len * v[k]);
        }
    }
}

/* ---- exact geometry --------------------------------------------------------------- */

/* |x - c|^2 - R^2 in binary128 (differences of floats, their squares: exact for the
 * ranges here to far below the tolerances tested). */
static cylq q_excess(const cylray_sphere *s, const float x[3])
{
    cylq a2 = 0;
    for (int k = 0; k < 3; k++) {
        const cylq a = (cylq)x[k] - (cylq)s->center[k];
        a2 += a * a;
    }
    return a2 - (cylq)s->radius * (cylq)s->radius;
}

/* The exact distance of x from the sphere. */
static double exact_dist(const cylray_sphere *s, const float x[3])
{
    cylq a2 = 0;
    for (int k = 0; k < 3; k++) {
        const cylq a = (cylq)x[k] - (cylq)s->center[k];
        a2 += a * a;
    }
    return (double)q_abs(q_sqrt(a2) - (cylq)s->radius);
}

/* The least t >= 0 at which the exact ray x0 + t w meets the sphere; INFINITY: never. */
static double exact_t(const cylray_sphere *s, const float x0[3], const float w[3])
{
    cylq a[3], A = 0, B = 0, C;
    for (int k = 0; k < 3; k++) {
        a[k] = (cylq)x0[k] - (cylq)s->center[k];
        A += (cylq)w[k] * w[k];
        B += a[k] * (cylq)w[k];
    }
    C = q_excess(s, x0);
    const cylq D = B * B - A * C;
    if (D < 0)
        return INFINITY;
    const cylq sd = q_sqrt(D);
    if (C < 0)
        return (double)((-B + sd) / A);
    if (B >= 0)
        return C == 0 ? 0.0 : INFINITY;
    return (double)(C / (-B + sd));
}

/* The same in double, for the cases that need no binary128: 1 and *t where decided (a
 * hit at tk clearly beyond half of it, or clearly not a self-hit), else 0. */
static int quick_ok(const cylray_sphere *s, const float x0[3], const float w[3], float tk)
{
    double a[3], A = 0, B = 0, aa = 0;
    for (int k = 0; k < 3; k++) {
        a[k] = (double)x0[k] - s->center[k];
        A += (double)w[k] * w[k];
        B += a[k] * w[k];
        aa += a[k] * a[k];
    }
    const double R = s->radius, C = (sqrt(aa) - R) * (sqrt(aa) + R);
    if (!(C < -1e-6 * R * R)) /* from outside, or too near the surface to tell */
        return 0;
    const double D = B * B - A * C, t = (-B + sqrt(D)) / A;
    return tk >= 0.6 * t;
}

/* 1 where the kernel's hit at tk of the ray x0 + t w meets the sphere too soon: before
 * half the exact ray's distance (never, where the exact ray misses). */
int too_soon(const cylray_sphere *s, const float x0[3], const float w[3], float tk)
{
    if (quick_ok(s, x0, w, tk))
        return 0;
    const double te = exact_t(s, x0, w);
    return !((double)tk >= 0.5 * te);
}

/* Which side of the sphere x lies on: +1 outside, -1 inside, 0 on it (exact; in double
 * where |x - c|^2 - R^2 is clear of its rounding, 5.01 units of 2^-53 of |x - c|^2). */
int side_of(const cylray_sphere *s, const float x[3])
{
    double aa = 0;
    for (int k = 0; k < 3; k++) {
        const double a = (double)x[k] - s->center[k];
        aa += a * a;
    }
    const double ed = aa - (double)s->radius * s->radius;
    if (fabs(ed) > 0x1p-48 * aa)
        return ed > 0 ? 1 : -1;
    const cylq e = q_excess(s, x);
    return e > 0 ? 1 : e < 0 ? -1 : 0;
}

/* The sign of w.(p - c), exact: w's side of the sphere at p (0: along the plane). */
int w_side(const cylray_sphere *s, const float p[3], const float w[3])
{
    /* in double where clear of its rounding (a few units of 2^-53 of the terms) */
    double wd = 0, mag = 0;
    for (int k = 0; k < 3; k++) {
        const double t = (double)w[k] * ((double)p[k] - s->center[k]);
        wd += t;
        mag += fabs(t);
    }
    if (fabs(wd) > 0x1p-48 * mag)
        return wd > 0 ? 1 : -1;
    cylq wn = 0;
    for (int k = 0; k < 3; k++)
        wn += (cylq)w[k] * ((cylq)p[k] - (cylq)s->center[k]);
    return wn > 0 ? 1 : wn < 0 ? -1 : 0;
}

/* A hit found in double (t rounded to float, the part, the outward normal rounded to
 * float, face-forwarded where ff): 0 on a miss. */
int double_hit(const cylray_sphere *s, const float o[3], const float d[3], float *t,
               int32_t *part, float n[3])
{
    double a[3], A = 0, B = 0, aa = 0;
    for (int k = 0; k < 3; k++) {
        a[k] = (double)o[k] - s->center[k];
        A += (double)d[k] * d[k];
        B += a[k] * d[k];
        aa += a[k] * a[k];
    }
    const double R = s->radius, C = (sqrt(aa) - R) * (sqrt(aa) + R), D = B * B - A * C;
    if (D < 0)
        return 0;
    double tt;
    if (C < 0)
        tt = (-B + sqrt(D)) / A;
    else if (B < 0)
        tt = C / (-B + sqrt(D));
    else
        return 0;
    *t = (float)tt;
    double x[3], l = 0;
    for (int k = 0; k < 3; k++) {
        x[k] = a[k] + tt * d[k];
        l += x[k] * x[k];
    }
    l = sqrt(l);
    for (int k = 0; k < 3; k++)
        n[k] = (float)(x[k] / l);
    *part = CYLRAY_SIDE | (C < 0 ? CYLRAY_BACKFACE : 0);
    return 1;
}

/* Traces n <= 16 rays on path K with normals: their hits into t, part, n (returns the
 * mask). */
uint32_t trace(const cylray_kernels *K, const cylray_prepared *P, int cnt, const float o[][3],
               const float d[][3], const float *tmax, float t[16], int32_t part[16],
               float n[16][3])
{
    cylray_ray16 ray;
    cylray_hit16 hit;
    memset(&ray, 0, sizeof ray);
    memset(&hit, 0, sizeof hit);
    for (int i = 0; i < cnt; i++) {
        ray.ox[i] = o[i][0], ray.oy[i] = o[i][1], ray.oz[i] = o[i][2];
        ray.dx[i] = d[i][0], ray.dy[i] = d[i][1], ray.dz[i] = d[i][2];
        ray.tmin[i] = 0, ray.tmax[i] = tmax ? tmax[i] : INFINITY;
    }
    const uint32_t act = cnt == 16 ? 0xffffu : (1u << cnt) - 1u;
    const uint32_t m = K->intersect16(P, &ray, &hit, act, CYLRAY_NORMAL);
    for (int i = 0; i < 16; i++) {
        t[i] = hit.t[i], part[i] = hit.part[i];
        n[i][0] = hit.nx[i], n[i][1] = hit.ny[i], n[i][2] = hit.nz[i];
    }
    return m;
}

/* ---- bounds ------------------------------------------------------------------------ */

static int run_bounds(void)
{
    const long N = scaled(12000);
    long checked = 0, viol = 0, kernel_hits = 0;
    double worst = 0; /* the largest err over ulp(max |p_k|) */
    cylgen_rng rng;
    cylgen_seed(&rng, 4101);
    for (long g = 0; g < N; g++) {
        cylray_sphere s;
        cylray_prepared P;
        float o[16][3], d[16][3];
        if (!sphere_rays(&rng, g, &s, &P, o, d))
            continue;
        /* hits in double, and the hits one ISA's kernel finds (t, n as given) */
        float t[16], n[16][3], tk[16], nk[16][3];
        int32_t part[16], pk[16];
        uint32_t md = 0;
        for (int i = 0; i < 16; i++)
            md |= (uint32_t)double_hit(&s, o[i], d[i], &t[i], &part[i], n[i]) << i;
        const uint32_t mk = trace(isas[g % nisa], &P, 16, (const float(*)[3])o,
                                  (const float(*)[3])d, NULL, tk, pk, nk);
        kernel_hits += __builtin_popcount(mk);
        for (int src = 0; src < 2; src++) {
            const uint32_t m = src ? mk : md;
            for (int i = 0; i < 16; i++) {
                if (!(m >> i & 1u))
                    continue;
                for (int form = 0; form < 2; form++) {
                    float p[3], err;
                    hit_point_form(&P, o[i], d[i], src ? tk[i] : t[i], src ? pk[i] : part[i],
                                   src ? nk[i] : n[i], form, p, &err);
                    const double dist = exact_dist(&s, p);
                    checked++;
                    if (!(dist <= err)) {
                        viol++;
                        fail("bound", &s, "exact distance %a > err %a", dist, err);
                    }
                    double pm = fmax(fabs(p[0]), fmax(fabs(p[1]), fabs(p[2])));
                    int e;
                    frexp(pm, &e);
                    worst = fmax(worst, err / ldexp(1, e - 24));
                }
            }
        }
    }
    printf("bounds: %ld points checked (%ld kernel hits), %ld bound violations; largest err "
           "%.3g ulps of the largest coordinate\n",
           checked, kernel_hits, viol, worst);
    return viol == 0 && checked > 0;
}

static int run_self(void)
{
    return run_spawns(0);
}
static int run_side(void)
{
    return run_spawns(1);
}

static const spawn_mode modes[] = {
    {"bounds", run_bounds}, {"self", run_self}, {"side", run_side}, {"batched", run_batched}};

int main(int argc, char **argv)
{
    return spawn_main(argc, argv, "spawn_sphere", modes, sizeof modes / sizeof modes[0]);
}
