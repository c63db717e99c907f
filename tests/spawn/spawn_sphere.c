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

static const cylray_kernels *isas[CYLRAY_ISA_COUNT];
static int nisa, quick;
static long failures;

static void fail(const char *what, const cylray_sphere *s, const char *fmt, double a, double b)
{
    if (failures++ < 20) {
        printf("FAIL %s: sphere c=(%a, %a, %a) R=%a: ", what, (double)s->center[0],
               (double)s->center[1], (double)s->center[2], (double)s->radius);
        printf(fmt, a, b);
        printf("\n");
    }
}

static double uni(cylgen_rng *r, double a, double b)
{
    return a + (b - a) * cylgen_uniform(r);
}

enum { K_NEAR, K_FAR, K_TINY, K_HUGE, K_COUNT };
static const char *const kind_name[K_COUNT] = {"near", "far", "tiny", "huge"};

static void make_sphere(cylgen_rng *r, int kind, cylray_sphere *s)
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
        R = ldexp(1 + cylgen_uniform(r), (int)uni(r, -58, -40));
        for (int k = 0; k < 3; k++)
            c[k] = R * uni(r, -1e3, 1e3);
        break;
    default:
        R = ldexp(1 + cylgen_uniform(r), (int)uni(r, 40, 60));
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
static void make_ray(cylgen_rng *r, const cylray_sphere *s, float o[3], float d[3])
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
static int too_soon(const cylray_sphere *s, const float x0[3], const float w[3], float tk)
{
    if (quick_ok(s, x0, w, tk))
        return 0;
    const double te = exact_t(s, x0, w);
    return !((double)tk >= 0.5 * te);
}

/* Which side of the sphere x lies on: +1 outside, -1 inside, 0 on it (exact; in double
 * where |x - c|^2 - R^2 is clear of its rounding, 5.01 units of 2^-53 of |x - c|^2). */
static int side_of(const cylray_sphere *s, const float x[3])
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
static int w_side(const cylray_sphere *s, const float p[3], const float w[3])
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
static int double_hit(const cylray_sphere *s, const float o[3], const float d[3], float *t,
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
static uint32_t trace(const cylray_kernels *K, const cylray_prepared *P, int cnt,
                      const float o[][3], const float d[][3], const float *tmax, float t[16],
                      int32_t part[16], float n[16][3])
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

static long scaled(long full)
{
    return quick ? (full + 99) / 100 : full;
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
        make_sphere(&rng, (int)(g % K_COUNT), &s);
        cylray_prepared P;
        if (cylray_prepare_sphere(&P, &s) != CYLRAY_OK)
            continue;
        float o[16][3], d[16][3];
        for (int i = 0; i < 16; i++)
            make_ray(&rng, &s, o[i], d[i]);
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
                    if (form)
                        cylray_hit_point_normal(&P, o[i], d[i], src ? tk[i] : t[i],
                                                src ? pk[i] : part[i], src ? nk[i] : n[i], p,
                                                &err);
                    else
                        cylray_hit_point(&P, o[i], d[i], src ? tk[i] : t[i],
                                         src ? pk[i] : part[i], p, &err);
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

/* ---- self-intersection ------------------------------------------------------------- */

enum { D_REFL, D_TRANS, D_SHADOW, D_COUNT };

/* Spawns from kernel hits on every path; side: 0 the plain form, 1 the side form. */
static int run_spawns(int side_form)
{
    const long N = scaled(side_form ? 6000 : 24000); /* groups of 16 rays a path */
    long spawns[CYLRAY_ISA_COUNT] = {0}, self[CYLRAY_ISA_COUNT] = {0};
    long wrong_side = 0, along_plane = 0, disagree = 0, hits_back = 0, too_big = 0;
    long same_as_plain = 0;
    double far = 0; /* the largest |sigma(x0)| over ulp(max|x0_k|) + ulp(R) */
    cylgen_rng rng;
    cylgen_seed(&rng, side_form ? 4303 : 4202);
    for (int ki = 0; ki < nisa; ki++) {
        const cylray_kernels *K = isas[ki];
        for (long g = 0; g < N; g++) {
            cylray_sphere s;
            make_sphere(&rng, (int)(g % K_COUNT), &s);
            cylray_prepared P;
            if (cylray_prepare_sphere(&P, &s) != CYLRAY_OK)
                continue;
            float o[16][3], d[16][3], t[16], n[16][3];
            int32_t part[16];
            for (int i = 0; i < 16; i++)
                make_ray(&rng, &s, o[i], d[i]);
            const uint32_t m =
                trace(K, &P, 16, (const float(*)[3])o, (const float(*)[3])d, NULL, t, part, n);
            if (!m)
                continue;
            /* the path's stream forms, against the scalar ones */
            float px[16], py[16], pz[16], pe[16], ox[16], oy[16], oz[16], tt[16], nx[16],
                ny[16], nz[16];
            float dx[16], dy[16], dz[16], fx[16], fy[16], fz[16];
            int32_t pp[16];
            for (int i = 0; i < 16; i++) {
                ox[i] = o[i][0], oy[i] = o[i][1], oz[i] = o[i][2];
                dx[i] = d[i][0], dy[i] = d[i][1], dz[i] = d[i][2];
                tt[i] = t[i], nx[i] = n[i][0], ny[i] = n[i][1], nz[i] = n[i][2];
                pp[i] = m >> i & 1u ? part[i] : CYLRAY_MISS;
            }
            const cylray_rays rays = {ox, oy, oz, dx, dy, dz, NULL, NULL};
            const cylray_hits hits = {tt, nx, ny, nz, pp};
            const cylray_points pts = {px, py, pz, pe};
            K->hit_points_normal_stream(&P, &rays, &hits, &pts, 16);
            /* the scalar forms, in one group of four (spawn_sphere batched compares all) */
            const int scalar = (g & 3) == 0;
            for (int i = 0; i < 16 && scalar; i++) {
                const float p[3] = {px[i], py[i], pz[i]};
                if (m >> i & 1u) {
                    float ps[3], es;
                    cylray_hit_point_normal(&P, o[i], d[i], t[i], part[i], n[i], ps, &es);
                    if (!sref_same3(p, ps) || !tc_same(es, pe[i]))
                        disagree++;
                }
            }
            for (int dir = 0; dir < D_COUNT; dir++) {
                float w[16][3], tmax[16], x0[16][3];
                int want[16];
                uint8_t outb[16];
                for (int i = 0; i < 16; i++) {
                    const float p[3] = {px[i], py[i], pz[i]};
                    double nn[3], l = 0;
                    for (int k = 0; k < 3; k++) {
                        nn[k] = (double)p[k] - s.center[k];
                        l += nn[k] * nn[k];
                    }
                    l = sqrt(l);
                    for (int k = 0; k < 3; k++)
                        nn[k] /= l;
                    const int inc = part[i] & CYLRAY_BACKFACE ? -1 : 1;
                    tmax[i] = INFINITY;
                    if (dir == D_SHADOW) {
                        double u[3], dist = s.radius * exp(cylgen_uniform(&rng) * 7);
                        sref_unit(&rng, u);
                        for (int k = 0; k < 3; k++)
                            w[i][k] = (float)(dist * u[k]);
                        tmax[i] = 1.0f;
                    } else {
                        sref_direction(&rng, nn, dir == D_REFL ? inc : -inc, w[i]);
                    }
                    /* the side form: the side from the kernel's (outward) normal, or at
                     * random one time in four */
                    const double wn = w[i][0] * n[i][0] + w[i][1] * n[i][1] + w[i][2] * n[i][2];
                    outb[i] = (uint8_t)(cylgen_uniform(&rng) < 0.25 ? cylgen_uniform(&rng) < 0.5
                                                                    : wn > 0);
                    want[i] = side_form ? (outb[i] ? 1 : -1) : w_side(&s, p, w[i]);
                    dx[i] = w[i][0], dy[i] = w[i][1], dz[i] = w[i][2];
                }
                const cylray_points dirs = {dx, dy, dz, NULL}, org = {fx, fy, fz, NULL};
                if (side_form)
                    K->spawn_stream_side(&P, &pts, pp, outb, &dirs, &org, 16);
                else
                    K->spawn_stream(&P, &pts, pp, &dirs, &org, 16);
                uint32_t use = 0;
                for (int i = 0; i < 16; i++) {
                    x0[i][0] = fx[i], x0[i][1] = fy[i], x0[i][2] = fz[i];
                    if (!(m >> i & 1u))
                        continue;
                    const float p[3] = {px[i], py[i], pz[i]};
                    float xs[3];
                    if (side_form)
                        cylray_spawn_origin_side(&P, p, pe[i], part[i], outb[i], w[i], xs);
                    else if (scalar)
                        cylray_spawn_origin(&P, p, pe[i], part[i], w[i], xs);
                    if ((side_form || scalar) && !sref_same3(xs, x0[i]))
                        disagree++;
                    /* the side asked for being w's side: the plain form's origin */
                    if (side_form && want[i] == w_side(&s, p, w[i])) {
                        float xp[3];
                        cylray_spawn_origin(&P, p, pe[i], part[i], w[i], xp);
                        same_as_plain++;
                        if (!sref_same3(xp, xs)) {
                            disagree++;
                            fail("side", &s,
                                 "not the plain form's origin where the side is w's", 0, 0);
                        }
                    }
                    double mv = 0;
                    for (int k = 0; k < 3; k++)
                        mv += ((double)x0[i][k] - p[k]) * ((double)x0[i][k] - p[k]);
                    if (!(sqrt(mv) <= 0.25 * s.radius)) {
                        too_big++; /* outside the guarantee: the float grid is too coarse */
                        continue;
                    }
                    use |= 1u << i;
                    spawns[ki]++;
                    const int sd = side_of(&s, x0[i]);
                    if (want[i] == 0) {
                        along_plane++; /* either side is w's: strictly off it */
                        if (sd == 0) {
                            wrong_side++;
                            fail("side", &s, "origin on the sphere (%a, %a)", x0[i][0],
                                 x0[i][1]);
                        }
                    } else if (sd != want[i]) {
                        wrong_side++;
                        fail("side", &s, "origin on the wrong side: want %g, got %g",
                             (double)want[i], (double)sd);
                    }
                    double aa = 0;
                    for (int k = 0; k < 3; k++)
                        aa +=
                            ((double)x0[i][k] - s.center[k]) * ((double)x0[i][k] - s.center[k]);
                    const double sig = fabs(sqrt(aa) - s.radius);
                    const double xm =
                        fmax(fabs(x0[i][0]), fmax(fabs(x0[i][1]), fabs(x0[i][2])));
                    int e1, e2;
                    frexp(xm, &e1);
                    frexp(s.radius, &e2);
                    far = fmax(far, sig / (ldexp(1, e1 - 24) + ldexp(1, e2 - 24)));
                }
                float th[16], nh[16][3];
                int32_t ph[16];
                const uint32_t mh = trace(K, &P, 16, (const float(*)[3])x0,
                                          (const float(*)[3])w, tmax, th, ph, nh);
                for (int i = 0; i < 16; i++) {
                    if (!((use & mh) >> i & 1u))
                        continue;
                    hits_back++;
                    if (too_soon(&s, x0[i], w[i], th[i])) {
                        self[ki]++;
                        fail("self", &s,
                             "the spawned ray meets the sphere again at t = %a (%g)", th[i],
                             (double)ph[i]);
                        printf("   p=(%a, %a, %a) err=%a part=%d w=(%a, %a, %a) x0=(%a, %a, %a)"
                               " path %s\n",
                               px[i], py[i], pz[i], pe[i], part[i], w[i][0], w[i][1], w[i][2],
                               x0[i][0], x0[i][1], x0[i][2], K->name);
                    }
                }
            }
        }
    }
    if (side_form)
        printf("side: %ld origins where the side asked for is w's: the plain form's\n",
               same_as_plain);
    long total_self = 0;
    for (int ki = 0; ki < nisa; ki++) {
        printf("%s: %s: %ld spawns, %ld self-intersections\n", side_form ? "side" : "self",
               isas[ki]->name, spawns[ki], self[ki]);
        total_self += self[ki];
    }
    printf("%s: %ld hits of spawned rays checked exactly or in double, %ld origins on the "
           "wrong side (%ld directions along the tangent plane), %ld stream/scalar "
           "differences; origins at most %.3g ulps (of the largest coordinate and of R) off "
           "the sphere; %ld spawns moved beyond R/4 (outside the guarantee) left out\n",
           side_form ? "side" : "self", hits_back, wrong_side, along_plane, disagree, far,
           too_big);
    return total_self == 0 && wrong_side == 0 && disagree == 0 && spawns[0] > 0;
}

/* ---- the batched forms, bit for bit ------------------------------------------------- */

static long diff3(const float a[3], const float b[3])
{
    return !sref_same3(a, b);
}

static int run_batched(void)
{
    const long N = scaled(4000);
    long lanes = 0, diff = 0;
    cylgen_rng rng;
    cylgen_seed(&rng, 4404);
    for (long g = 0; g < N; g++) {
        cylray_sphere s[16];
        for (int i = 0; i < 16; i++)
            make_sphere(&rng, (int)((g + (uint64_t)i * (g & 1)) % K_COUNT), &s[i]);
        cylray_prepared P;
        if (cylray_prepare_sphere(&P, &s[0]) != CYLRAY_OK)
            continue;
        cylray_leaf16 leaf;
        cylray_leaf8 leaf8;
        cylray_leaf4 leaf4;
        if (cylray_leaf_prepare_spheres16(&leaf, s, NULL, 16) != CYLRAY_OK ||
            cylray_leaf_prepare_spheres8(&leaf8, s, NULL, 8) != CYLRAY_OK ||
            cylray_leaf_prepare_spheres4(&leaf4, s, NULL, 4) != CYLRAY_OK)
            continue;
        /* rays at sphere 0 (the packet forms) and hits in double, with a few lanes given
         * a hit that is not one (t from elsewhere), which the forms must treat alike */
        cylray_ray16 ray;
        cylray_hit16 hit;
        memset(&ray, 0, sizeof ray);
        memset(&hit, 0, sizeof hit);
        uint32_t m = 0;
        float w[16][3], tl[16], nl[16][3];
        int32_t pl[16];
        cylray_ray1 r1[16];
        uint32_t lane[16];
        float ol[16][3], dl[16][3];
        for (int i = 0; i < 16; i++) {
            float o[3], d[3], t, n[3];
            int32_t part;
            make_ray(&rng, &s[0], o, d);
            if (!double_hit(&s[0], o, d, &t, &part, n)) {
                t = (float)uni(&rng, 0, 10), part = CYLRAY_SIDE;
                n[0] = 1, n[1] = n[2] = 0;
            }
            if (cylgen_uniform(&rng) < 0.3) /* face-forwarded */
                for (int k = 0; k < 3; k++)
                    n[k] = part & CYLRAY_BACKFACE ? -n[k] : n[k];
            ray.ox[i] = o[0], ray.oy[i] = o[1], ray.oz[i] = o[2];
            ray.dx[i] = d[0], ray.dy[i] = d[1], ray.dz[i] = d[2];
            hit.t[i] = t, hit.part[i] = part;
            hit.nx[i] = n[0], hit.ny[i] = n[1], hit.nz[i] = n[2];
            if (cylgen_uniform(&rng) < 0.9)
                m |= 1u << i;
            double u[3];
            sref_unit(&rng, u);
            for (int k = 0; k < 3; k++)
                w[i][k] = (float)(u[k] * pow(10, uni(&rng, -3, 3)));
            /* the leaf's lane i: a ray at its own sphere */
            lane[i] = (uint32_t)(cylgen_next(&rng) % 16);
            make_ray(&rng, &s[lane[i]], ol[i], dl[i]);
            if (!double_hit(&s[lane[i]], ol[i], dl[i], &tl[i], &pl[i], nl[i]))
                tl[i] = 1, pl[i] = CYLRAY_SIDE, nl[i][0] = 0, nl[i][1] = 1, nl[i][2] = 0;
            memcpy(r1[i].o, ol[i], sizeof ol[i]);
            memcpy(r1[i].d, dl[i], sizeof dl[i]);
            r1[i].tmin = 0, r1[i].tmax = INFINITY;
        }
        const uint32_t outward = (uint32_t)cylgen_next(&rng) & 0xffffu;
        /* the scalar answers */
        float p[2][16][3], e[2][16], x[2][16][3];
        float lp[2][16][3], le[2][16], lx[2][16][3];
        cylray_hit1 h1[16];
        for (int i = 0; i < 16; i++) {
            const float o[3] = {ray.ox[i], ray.oy[i], ray.oz[i]},
                        d[3] = {ray.dx[i], ray.dy[i], ray.dz[i]},
                        n[3] = {hit.nx[i], hit.ny[i], hit.nz[i]};
            cylray_hit_point(&P, o, d, hit.t[i], hit.part[i], p[0][i], &e[0][i]);
            cylray_hit_point_normal(&P, o, d, hit.t[i], hit.part[i], n, p[1][i], &e[1][i]);
            cylray_spawn_origin(&P, p[0][i], e[0][i], hit.part[i], w[i], x[0][i]);
            cylray_spawn_origin_side(&P, p[0][i], e[0][i], hit.part[i], outward >> i & 1u, w[i],
                                     x[1][i]);
            cylray_hit1 h = {tl[i], {nl[i][0], nl[i][1], nl[i][2]}, pl[i], 0, lane[i]};
            h1[i] = h;
            cylray_leaf_hit_point16(&leaf, &r1[i], &h1[i], lp[0][i], &le[0][i]);
            cylray_leaf_hit_point_normal16(&leaf, &r1[i], &h1[i], lp[1][i], &le[1][i]);
            cylray_leaf_spawn_origin16(&leaf, &h1[i], lp[0][i], le[0][i], w[i], lx[0][i]);
            cylray_leaf_spawn_origin_side16(&leaf, &h1[i], lp[0][i], le[0][i],
                                            outward >> i & 1u, w[i], lx[1][i]);
            /* the leaf's lane is sphere lane[i]: its scalar answers as a prepared sphere */
            cylray_prepared Q;
            float qp[3], qe, qx[3];
            cylray_prepare_sphere(&Q, &s[lane[i]]);
            cylray_hit_point_normal(&Q, ol[i], dl[i], tl[i], pl[i], nl[i], qp, &qe);
            cylray_spawn_origin(&Q, lp[0][i], le[0][i], pl[i], w[i], qx);
            diff += diff3(qp, lp[1][i]) + !tc_same(qe, le[1][i]) + diff3(qx, lx[0][i]);
            if (lane[i] < 8) {
                float a[3], ae, b[3];
                cylray_leaf_hit_point_normal8(&leaf8, &r1[i], &h1[i], a, &ae);
                diff += diff3(a, lp[1][i]) + !tc_same(ae, le[1][i]);
                cylray_leaf_spawn_origin_side8(&leaf8, &h1[i], lp[0][i], le[0][i],
                                               outward >> i & 1u, w[i], b);
                diff += diff3(b, lx[1][i]);
            }
            if (lane[i] < 4) {
                float a[3], ae, b[3];
                cylray_leaf_hit_point4(&leaf4, &r1[i], &h1[i], a, &ae);
                diff += diff3(a, lp[0][i]) + !tc_same(ae, le[0][i]);
                cylray_leaf_spawn_origin4(&leaf4, &h1[i], lp[0][i], le[0][i], w[i], b);
                diff += diff3(b, lx[0][i]);
            }
        }
        for (int ki = 0; ki < nisa; ki++) {
            const cylray_kernels *K = isas[ki];
            for (int normal = 0; normal < 2; normal++) {
                /* packets of 16, 8 and 4 */
                cylray_points16 q16;
                memset(&q16, 0, sizeof q16);
                (normal ? K->hit_points_normal16 : K->hit_points16)(&P, &ray, &hit, m, &q16);
                cylray_ray8 ray8;
                cylray_hit8 hit8;
                cylray_ray4 ray4;
                cylray_hit4 hit4;
                for (int i = 0; i < 8; i++) {
                    ray8.ox[i] = ray.ox[i], ray8.oy[i] = ray.oy[i], ray8.oz[i] = ray.oz[i];
                    ray8.dx[i] = ray.dx[i], ray8.dy[i] = ray.dy[i], ray8.dz[i] = ray.dz[i];
                    hit8.t[i] = hit.t[i], hit8.part[i] = hit.part[i];
                    hit8.nx[i] = hit.nx[i], hit8.ny[i] = hit.ny[i], hit8.nz[i] = hit.nz[i];
                    if (i < 4) {
                        ray4.ox[i] = ray.ox[i], ray4.oy[i] = ray.oy[i], ray4.oz[i] = ray.oz[i];
                        ray4.dx[i] = ray.dx[i], ray4.dy[i] = ray.dy[i], ray4.dz[i] = ray.dz[i];
                        hit4.t[i] = hit.t[i], hit4.part[i] = hit.part[i];
                        hit4.nx[i] = hit.nx[i], hit4.ny[i] = hit.ny[i], hit4.nz[i] = hit.nz[i];
                    }
                }
                cylray_points8 q8;
                cylray_points4 q4;
                memset(&q8, 0, sizeof q8);
                memset(&q4, 0, sizeof q4);
                (normal ? K->hit_points_normal8 : K->hit_points8)(&P, &ray8, &hit8, m & 0xffu,
                                                                  &q8);
                (normal ? K->hit_points_normal4 : K->hit_points4)(&P, &ray4, &hit4, m & 0xfu,
                                                                  &q4);
                for (int i = 0; i < 16; i++) {
                    if (!(m >> i & 1u))
                        continue;
                    lanes++;
                    const float a[3] = {q16.x[i], q16.y[i], q16.z[i]};
                    diff += diff3(a, p[normal][i]) + !tc_same(q16.err[i], e[normal][i]);
                    if (i < 8) {
                        const float b[3] = {q8.x[i], q8.y[i], q8.z[i]};
                        diff += diff3(b, p[normal][i]) + !tc_same(q8.err[i], e[normal][i]);
                    }
                    if (i < 4) {
                        const float b[3] = {q4.x[i], q4.y[i], q4.z[i]};
                        diff += diff3(b, p[normal][i]) + !tc_same(q4.err[i], e[normal][i]);
                    }
                }
                /* spawned rays from the plain points: packets, and the side form */
                cylray_points16 s16;
                for (int i = 0; i < 16; i++) {
                    s16.x[i] = p[0][i][0], s16.y[i] = p[0][i][1], s16.z[i] = p[0][i][2];
                    s16.err[i] = e[0][i];
                }
                cylray_ray16 out = ray;
                for (int i = 0; i < 16; i++)
                    out.dx[i] = w[i][0], out.dy[i] = w[i][1], out.dz[i] = w[i][2];
                if (normal)
                    K->spawn_rays_side16(&P, &s16, &hit, m, outward, &out);
                else
                    K->spawn_rays16(&P, &s16, &hit, m, &out);
                cylray_points8 s8;
                cylray_ray8 out8;
                cylray_points4 s4;
                cylray_ray4 out4;
                memset(&out8, 0, sizeof out8);
                memset(&out4, 0, sizeof out4);
                for (int i = 0; i < 8; i++) {
                    s8.x[i] = s16.x[i], s8.y[i] = s16.y[i], s8.z[i] = s16.z[i];
                    s8.err[i] = s16.err[i];
                    out8.dx[i] = w[i][0], out8.dy[i] = w[i][1], out8.dz[i] = w[i][2];
                    if (i < 4) {
                        s4.x[i] = s16.x[i], s4.y[i] = s16.y[i], s4.z[i] = s16.z[i];
                        s4.err[i] = s16.err[i];
                        out4.dx[i] = w[i][0], out4.dy[i] = w[i][1], out4.dz[i] = w[i][2];
                    }
                }
                if (normal) {
                    K->spawn_rays_side8(&P, &s8, &hit8, m & 0xffu, outward & 0xffu, &out8);
                    K->spawn_rays_side4(&P, &s4, &hit4, m & 0xfu, outward & 0xfu, &out4);
                } else {
                    K->spawn_rays8(&P, &s8, &hit8, m & 0xffu, &out8);
                    K->spawn_rays4(&P, &s4, &hit4, m & 0xfu, &out4);
                }
                for (int i = 0; i < 16; i++) {
                    if (!(m >> i & 1u))
                        continue;
                    const float a[3] = {out.ox[i], out.oy[i], out.oz[i]};
                    diff += diff3(a, x[normal][i]) + (out.tmin[i] != 0.0f);
                    if (i < 8) {
                        const float b[3] = {out8.ox[i], out8.oy[i], out8.oz[i]};
                        diff += diff3(b, x[normal][i]);
                    }
                    if (i < 4) {
                        const float b[3] = {out4.ox[i], out4.oy[i], out4.oz[i]};
                        diff += diff3(b, x[normal][i]);
                    }
                }
                /* streams of every length up to 16 */
                for (int len = 1; len <= 16; len += 1 + (int)(cylgen_next(&rng) % 4)) {
                    float px[16], py[16], pz[16], pe[16], fx[16], fy[16], fz[16];
                    float wx[16], wy[16], wz[16];
                    int32_t pp[16];
                    uint8_t ob[16];
                    for (int i = 0; i < 16; i++) {
                        pp[i] = m >> i & 1u ? hit.part[i] : CYLRAY_MISS;
                        wx[i] = w[i][0], wy[i] = w[i][1], wz[i] = w[i][2];
                        ob[i] = (uint8_t)(outward >> i & 1u);
                        fx[i] = fy[i] = fz[i] = px[i] = py[i] = pz[i] = pe[i] = -7.0f;
                    }
                    const cylray_rays rays = {ray.ox, ray.oy, ray.oz, ray.dx,
                                              ray.dy, ray.dz, NULL,   NULL};
                    const cylray_hits hits = {hit.t, hit.nx, hit.ny, hit.nz, pp};
                    const cylray_points pts = {px, py, pz, pe};
                    (normal ? K->hit_points_normal_stream
                            : K->hit_points_stream)(&P, &rays, &hits, &pts, len);
                    const cylray_points sp = {s16.x, s16.y, s16.z, s16.err};
                    const cylray_points dirs = {wx, wy, wz, NULL}, org = {fx, fy, fz, NULL};
                    if (normal)
                        K->spawn_stream_side(&P, &sp, pp, ob, &dirs, &org, len);
                    else
                        K->spawn_stream(&P, &sp, pp, &dirs, &org, len);
                    for (int i = 0; i < len; i++) {
                        if (!(m >> i & 1u))
                            continue;
                        const float a[3] = {px[i], py[i], pz[i]}, b[3] = {fx[i], fy[i], fz[i]};
                        diff += diff3(a, p[normal][i]) + !tc_same(pe[i], e[normal][i]) +
                                diff3(b, x[normal][i]);
                    }
                }
                /* leaves in bulk, 16 hits of 16-, 8- and 4-lane leaves */
                {
                    const cylray_leaf16 *lv[16];
                    float px[16], py[16], pz[16], pe[16], fx[16], fy[16], fz[16];
                    float wx[16], wy[16], wz[16];
                    uint8_t ob[16];
                    for (int i = 0; i < 16; i++) {
                        lv[i] = &leaf;
                        wx[i] = w[i][0], wy[i] = w[i][1], wz[i] = w[i][2];
                        ob[i] = (uint8_t)(outward >> i & 1u);
                    }
                    const cylray_points pts = {px, py, pz, pe};
                    (normal ? K->leaf_hit_points_normal16 : K->leaf_hit_points16)(lv, r1, h1,
                                                                                  &pts, 16);
                    const cylray_points sp = {px, py, pz, pe};
                    const cylray_points dirs = {wx, wy, wz, NULL}, org = {fx, fy, fz, NULL};
                    float lpx[16], lpy[16], lpz[16], lpe[16];
                    for (int i = 0; i < 16; i++)
                        lpx[i] = lp[0][i][0], lpy[i] = lp[0][i][1], lpz[i] = lp[0][i][2],
                        lpe[i] = le[0][i];
                    const cylray_points sp0 = {lpx, lpy, lpz, lpe};
                    (void)sp;
                    if (normal)
                        K->leaf_spawn_origins_side16(lv, h1, &sp0, ob, &dirs, &org, 16);
                    else
                        K->leaf_spawn_origins16(lv, h1, &sp0, &dirs, &org, 16);
                    for (int i = 0; i < 16; i++) {
                        const float a[3] = {px[i], py[i], pz[i]}, b[3] = {fx[i], fy[i], fz[i]};
                        diff += diff3(a, lp[normal][i]) + !tc_same(pe[i], le[normal][i]) +
                                diff3(b, lx[normal][i]);
                    }
                    /* 8- and 4-lane leaves: the hits that name their lanes */
                    const cylray_leaf8 *l8[16];
                    const cylray_leaf4 *l4[16];
                    cylray_ray1 r8[16], r4[16];
                    cylray_hit1 h8[16], h4[16];
                    int i8[16], i4[16], n8 = 0, n4 = 0;
                    for (int i = 0; i < 16; i++) {
                        if (lane[i] < 8)
                            l8[n8] = &leaf8, r8[n8] = r1[i], h8[n8] = h1[i], i8[n8++] = i;
                        if (lane[i] < 4)
                            l4[n4] = &leaf4, r4[n4] = r1[i], h4[n4] = h1[i], i4[n4++] = i;
                    }
                    (normal ? K->leaf_hit_points_normal8
                            : K->leaf_hit_points8)(l8, r8, h8, &pts, (size_t)n8);
                    for (int j = 0; j < n8; j++) {
                        const float a[3] = {px[j], py[j], pz[j]};
                        diff +=
                            diff3(a, lp[normal][i8[j]]) + !tc_same(pe[j], le[normal][i8[j]]);
                    }
                    (normal ? K->leaf_hit_points_normal4
                            : K->leaf_hit_points4)(l4, r4, h4, &pts, (size_t)n4);
                    for (int j = 0; j < n4; j++) {
                        const float a[3] = {px[j], py[j], pz[j]};
                        diff +=
                            diff3(a, lp[normal][i4[j]]) + !tc_same(pe[j], le[normal][i4[j]]);
                    }
                    for (int j = 0; j < n8; j++) {
                        lpx[j] = lp[0][i8[j]][0], lpy[j] = lp[0][i8[j]][1];
                        lpz[j] = lp[0][i8[j]][2], lpe[j] = le[0][i8[j]];
                        wx[j] = w[i8[j]][0], wy[j] = w[i8[j]][1], wz[j] = w[i8[j]][2];
                        ob[j] = (uint8_t)(outward >> i8[j] & 1u);
                    }
                    if (normal)
                        K->leaf_spawn_origins_side8(l8, h8, &sp0, ob, &dirs, &org, (size_t)n8);
                    else
                        K->leaf_spawn_origins8(l8, h8, &sp0, &dirs, &org, (size_t)n8);
                    for (int j = 0; j < n8; j++) {
                        const float b[3] = {fx[j], fy[j], fz[j]};
                        diff += diff3(b, lx[normal][i8[j]]);
                    }
                }
            }
        }
        if (diff && failures++ < 20)
            printf("FAIL batched: group %ld, sphere c=(%a, %a, %a) R=%a: %ld differences so "
                   "far\n",
                   g, (double)s[0].center[0], (double)s[0].center[1], (double)s[0].center[2],
                   (double)s[0].radius, diff);
    }
    printf("batched: %ld packet lanes on %d paths (packets 4/8/16, streams, leaves), %ld "
           "differences from the scalar forms\n",
           lanes, nisa, diff);
    return diff == 0 && lanes > 0;
}

int main(int argc, char **argv)
{
    quick = tc_quick();
    for (int i = 0; i < CYLRAY_ISA_COUNT; i++) {
        const cylray_kernels *k = cylray_kernels_for((cylray_isa)i);
        if (k)
            isas[nisa++] = k;
    }
    const char *mode = argc > 1 ? argv[1] : "";
    int ok;
    if (strcmp(mode, "bounds") == 0)
        ok = run_bounds();
    else if (strcmp(mode, "self") == 0)
        ok = run_spawns(0);
    else if (strcmp(mode, "side") == 0)
        ok = run_spawns(1);
    else if (strcmp(mode, "batched") == 0)
        ok = run_batched();
    else {
        fprintf(stderr, "usage: spawn_sphere bounds|self|side|batched\n");
        return 2;
    }
    (void)kind_name;
    printf("%s: %s\n", mode, ok ? "ok" : "FAILED");
    return ok ? 0 : 1;
}
