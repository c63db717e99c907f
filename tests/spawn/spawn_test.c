/* SPDX-License-Identifier: MIT */
/* spawn_test.c - secondary rays against exact arithmetic.
 *
 *   spawn_test bounds   every ISA's hits of every category: the hit point's bound
 *                       contains its exact distance from the part's surface
 *   spawn_test self     rays spawned from those points (reflection, transmission,
 *                       shadow) never meet the surface they leave there, traced on
 *                       every ISA and exactly; the origin is strictly on the ray's side
 *   spawn_test nested   a coaxial cylinder 1e-5 R inside is still hit by the
 *                       transmitted ray, and the spawned origin lies between the two
 *   spawn_test batched  the packet, stream and leaf forms equal the scalar pair
 *   spawn_test side     the side form: the tracer's side from the kernel's normal
 *                       (random hits, grazing directions, and two far rods whose
 *                       kernel normal and exact normal disagree), the origin strictly
 *                       on that side, no hit of the part before the exact ray's
 *   spawn_test round    the library's rounding to float on the bits equals the
 *                       hardware's, and a two-term sum is rounded once
 *
 * CYLRAY_TEST_QUICK=1 shrinks the counts about a hundredfold (sanitizers, emulators).
 * Every count is printed; any violation fails the test. */
#include "cylray.h"
#include "cylray_internal.h"
#include "cylref.h"
#include "spawnref.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const cylray_kernels *isas[CYLRAY_ISA_COUNT];
static int nisa;
static int quick;
static long failures;

static void fail(const char *what, const cylgen_case *c, const char *detail)
{
    if (failures++ < 20)
        fprintf(stderr,
                "FAIL %s: cyl c=(%a %a %a) v=(%a %a %a) R=%a H=%a flags=%u o=(%a %a %a) "
                "d=(%a %a %a): %s\n",
                what, c->cyl.center[0], c->cyl.center[1], c->cyl.center[2], c->cyl.axis[0],
                c->cyl.axis[1], c->cyl.axis[2], c->cyl.radius, c->cyl.half_height,
                c->cyl.flags, c->o[0], c->o[1], c->o[2], c->d[0], c->d[1], c->d[2], detail);
}

/* The hits of one ISA's 16-wide kernel on a group of cases; returns the hit mask. */
static uint32_t trace_group(const cylray_kernels *k, const cylray_prepared *P,
                            const cylgen_case *c, cylray_ray16 *ray, cylray_hit16 *hit)
{
    memset(ray, 0, sizeof *ray);
    memset(hit, 0, sizeof *hit);
    for (int i = 0; i < SREF_GROUP; i++) {
        ray->ox[i] = c[i].o[0], ray->oy[i] = c[i].o[1], ray->oz[i] = c[i].o[2];
        ray->dx[i] = c[i].d[0], ray->dy[i] = c[i].d[1], ray->dz[i] = c[i].d[2];
        ray->tmin[i] = c[i].tmin, ray->tmax[i] = c[i].tmax;
    }
    return k->intersect16(P, ray, hit, 0xffffu, 0);
}

/* A packet of 16 rays (origins x, directions w, tmax) traced by ISA k at width 4, 8 or
 * 16 (cycling), one cylinder. */
static uint32_t trace16(const cylray_kernels *k, int width, const cylray_prepared *P,
                        const float x[][3], const float w[][3], const float *tmax,
                        uint32_t mask, float *t, int32_t *part)
{
    uint32_t got = 0;
    for (int base = 0; base < 16; base += width) {
        cylray_ray16 r;
        cylray_hit16 h;
        memset(&h, 0, sizeof h);
        /* the 4- and 8-wide structs are prefixes of the same field order, at their own
         * strides: fill each layout explicitly */
        float *f = (float *)(void *)&r;
        for (int i = 0; i < width; i++) {
            int j = base + i;
            for (int a = 0; a < 3; a++) {
                f[a * width + i] = x[j][a];
                f[(3 + a) * width + i] = w[j][a];
            }
            f[6 * width + i] = 0.0f;
            f[7 * width + i] = tmax[j];
        }
        uint32_t m = (mask >> base) & ((1u << width) - 1u), res;
        if (width == 4)
            res = k->intersect4(P, (cylray_ray4 *)(void *)&r, (cylray_hit4 *)(void *)&h, m, 0);
        else if (width == 8)
            res = k->intersect8(P, (cylray_ray8 *)(void *)&r, (cylray_hit8 *)(void *)&h, m, 0);
        else
            res = k->intersect16(P, &r, &h, m, 0);
        const float *ht = (const float *)(void *)&h;
        const int32_t *hp = (const int32_t *)(const void *)(ht + 4 * width);
        for (int i = 0; i < width; i++)
            if (res >> i & 1u) {
                t[base + i] = ht[i];
                part[base + i] = hp[i];
            }
        got |= res << base;
    }
    return got;
}

static long popcount(uint32_t m)
{
    long n = 0;
    for (; m; m &= m - 1)
        n++;
    return n;
}

static int cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static long groups_for(long full)
{
    return quick ? full / 100 + 1 : full;
}

/* ---- bounds ------------------------------------------------------------------- */

static int run_bounds(void)
{
    long hits = 0, viol = 0;
    const long G = groups_for(2000);
    printf("%-13s %9s %10s %12s %12s %12s\n", "category", "hits", "violations",
           "err/ulp p50", "err/ulp max", "err/exact p50");
    for (int cat = 0; cat < SREF_COUNT; cat++) {
        long ch = 0, cv = 0;
        static double rel[2000 * 16 * CYLRAY_ISA_COUNT], ulps[2000 * 16 * CYLRAY_ISA_COUNT];
        long nr = 0, nu = 0;
        double umax = 0;
        for (long g = 0; g < G; g++) {
            cylgen_case c[SREF_GROUP];
            sref_group(cat, 1000 + (uint64_t)g, c);
            cylray_prepared P;
            if (cylray_prepare(&P, &c[0].cyl) != CYLRAY_OK)
                continue;
            for (int k = 0; k < nisa; k++) {
                cylray_ray16 ray;
                cylray_hit16 hit;
                uint32_t m = trace_group(isas[k], &P, c, &ray, &hit);
                for (int i = 0; i < SREF_GROUP; i++) {
                    if (!(m >> i & 1u))
                        continue;
                    float p[3], err;
                    cylray_hit_point(&P, c[i].o, c[i].d, hit.t[i], hit.part[i], p, &err);
                    const double dist = sref_dist_part(&c[i].cyl, p, hit.part[i]);
                    ch++;
                    if (!(dist <= err) || !isfinite(err)) {
                        cv++;
                        char s[160];
                        snprintf(s, sizeof s, "%s part %d: distance %.3g > bound %.3g",
                                 isas[k]->name, hit.part[i], dist, (double)err);
                        fail("bound", &c[i], s);
                        continue;
                    }
                    double pm = fmax(fabs(p[0]), fmax(fabs(p[1]), fabs(p[2])));
                    double u = err / cylref_float_ulp(pm);
                    ulps[nu++] = u;
                    umax = fmax(umax, u);
                    if (dist > 0)
                        rel[nr++] = err / dist;
                }
            }
        }
        qsort(ulps, (size_t)nu, sizeof *ulps, cmp);
        qsort(rel, (size_t)nr, sizeof *rel, cmp);
        printf("%-13s %9ld %10ld %12.3g %12.3g %12.3g\n", sref_category_name(cat), ch, cv,
               nu ? ulps[nu / 2] : 0.0, umax, nr ? rel[nr / 2] : 0.0);
        hits += ch;
        viol += cv;
    }
    printf("bounds: %ld hits over %d ISAs, %ld violations\n", hits, nisa, viol);
    return viol == 0 && hits > 0;
}

/* ---- self-intersection ------------------------------------------------------------ */

/* The surfaces a spawned origin must clear: the part left, and a cap or the side
 * within err of p (a rim). Bit s for surface s = SIDE, CAP_LO, CAP_HI. */
static unsigned near_surfaces(const cylray_cylinder *cyl, const float p[3], float err, int P)
{
    unsigned s = 1u << P;
    if (!isfinite(cyl->half_height))
        return s;
    if (P != CYLRAY_SIDE && sref_dist_part(cyl, p, CYLRAY_SIDE) <= err)
        s |= 1u << CYLRAY_SIDE;
    for (int c = CYLRAY_CAP_LO; c <= CYLRAY_CAP_HI; c++)
        if (P != c && (cyl->flags & (c == CYLRAY_CAP_LO ? CYLRAY_CAPPED_LO : CYLRAY_CAPPED_HI)) &&
            sref_dist_part(cyl, p, c) <= err)
            s |= 1u << c;
    return s;
}

/* The origin x0 lies strictly on w's side of every surface in `surf` (exact); a
 * direction within 1e-9 rad of a surface may go either way, but not onto it. */
static int strictly_on_side(const cylray_cylinder *cyl, const float p[3], unsigned surf,
                            const float w[3], const float x0[3])
{
    for (int s = CYLRAY_SIDE; s <= CYLRAY_CAP_HI; s++) {
        if (!(surf >> s & 1u))
            continue;
        double n[3], wl = sqrt((double)w[0] * w[0] + (double)w[1] * w[1] + (double)w[2] * w[2]);
        sref_normal(cyl, p, s, n);
        const double wn = (n[0] * w[0] + n[1] * w[1] + n[2] * w[2]) / wl;
        const double sig = sref_sigma(cyl, x0, s);
        if (fabs(wn) <= 1e-9 ? sig == 0 : (wn > 0) != (sig > 0))
            return 0;
    }
    return 1;
}

enum { K_REFL, K_TRANS, K_SHADOW, K_DIRS = 5 };

static int run_self(void)
{
    const long G = groups_for(200000);
    long spawns = 0, traced[CYLRAY_ISA_COUNT] = {0}, self[CYLRAY_ISA_COUNT] = {0};
    long wrong_side = 0, exact_checked = 0, exact_self = 0, too_big = 0, kernel_faults = 0;
    long too_big_cat[SREF_COUNT] = {0};
    cylgen_rng rng;
    cylgen_seed(&rng, 77);
    for (long g = 0; g < G; g++) {
        const int cat = (int)(g % SREF_COUNT);
        cylgen_case c[SREF_GROUP];
        sref_group(cat, 5000 + (uint64_t)g, c);
        const cylray_cylinder *cyl = &c[0].cyl;
        cylray_prepared P;
        if (cylray_prepare(&P, cyl) != CYLRAY_OK)
            continue;
        /* hits from one ISA per group, in turn */
        cylray_ray16 ray;
        cylray_hit16 hit;
        uint32_t m = trace_group(isas[g % nisa], &P, c, &ray, &hit);
        if (!m)
            continue;
        float p[16][3], err[16];
        for (int i = 0; i < 16; i++)
            if (m >> i & 1u)
                cylray_hit_point(&P, c[i].o, c[i].d, hit.t[i], hit.part[i], p[i], &err[i]);
        const double lim = 0.25 * fmin(cyl->radius, cyl->half_height);
        for (int dir = 0; dir < K_DIRS; dir++) {
            const int kind = dir < 2 ? K_REFL : dir < 4 ? K_TRANS : K_SHADOW;
            float x0[16][3], w[16][3], tmax[16];
            uint32_t use = 0;
            for (int i = 0; i < 16; i++) {
                if (!(m >> i & 1u))
                    continue;
                const int part = hit.part[i], Pm = part & CYLRAY_PART_MASK;
                double n[3];
                sref_normal(cyl, p[i], Pm, n);
                const int refl = part & CYLRAY_BACKFACE ? -1 : 1; /* the incident side */
                tmax[i] = INFINITY;
                if (kind == K_SHADOW) {
                    double u[3], dist = cyl->radius * exp(cylgen_uniform(&rng) * 7);
                    sref_unit(&rng, u);
                    for (int k = 0; k < 3; k++)
                        w[i][k] = (float)(dist * u[k]);
                    tmax[i] = 1.0f;
                } else {
                    sref_direction(&rng, n, kind == K_REFL ? refl : -refl, w[i]);
                }
                cylray_spawn_origin(&P, p[i], err[i], part, w[i], x0[i]);
                double mv = 0;
                for (int k = 0; k < 3; k++)
                    mv += ((double)x0[i][k] - p[i][k]) * ((double)x0[i][k] - p[i][k]);
                if (!(sqrt(mv) <= lim)) {
                    too_big++; /* outside the guarantee: the float grid is too coarse */
                    too_big_cat[cat]++;
                    continue;
                }
                spawns++;
                use |= 1u << i;
                unsigned surf = near_surfaces(cyl, p[i], err[i], Pm);
                if (!strictly_on_side(cyl, p[i], surf, w[i], x0[i])) {
                    wrong_side++;
                    fail("side", &c[i], "spawned origin not strictly on the ray's side");
                }
                if ((spawns & 31) == 0) {
                    cylref_hit h;
                    exact_checked++;
                    if (cylref_intersect(cyl, x0[i], w[i], 0.0f, tmax[i], 0, &h) == 1 &&
                        sref_self_hit(cyl, x0[i], w[i], part, h.part, (float)h.t)) {
                        exact_self++;
                        fail("self (exact)", &c[i], "the exact ray meets the surface left");
                    }
                }
            }
            for (int k = 0; k < nisa; k++) {
                float t[16];
                int32_t hp[16];
                const int width = 4 << ((dir + k) % 3);
                uint32_t got = trace16(isas[k], width, &P, (const float(*)[3])x0,
                                       (const float(*)[3])w, tmax, use, t, hp);
                traced[k] += popcount(use);
                for (int i = 0; i < 16; i++)
                    if ((got >> i & 1u) &&
                        sref_self_hit(cyl, x0[i], w[i], hit.part[i], hp[i], t[i])) {
                        self[k]++;
                        /* Is the kernel itself within its tolerance band there? If not,
                         * the fault is the kernel's, and the message says so. */
                        cylref_band b;
                        cylref_band_eval(cyl, x0[i], w[i], 0.0f, tmax[i], 0, &b);
                        const int kernel_fault = cylref_judge(&b, 1, hp[i], t[i], NULL) != 0;
                        kernel_faults += kernel_fault;
                        char s[400];
                        snprintf(s, sizeof s,
                                 "%s width %d%s: part %d left at (%a %a %a) err %a, "
                                 "spawned (%a %a %a) w (%a %a %a), hit part %d at t %a",
                                 isas[k]->name, width,
                                 kernel_fault ? " (an answer outside the kernel's tolerance band)"
                                              : "", hit.part[i], p[i][0], p[i][1], p[i][2],
                                 err[i], x0[i][0], x0[i][1], x0[i][2], w[i][0], w[i][1],
                                 w[i][2], hp[i], t[i]);
                        fail("self", &c[i], s);
                    }
            }
        }
    }
    long bad = wrong_side + exact_self;
    printf("self: outside the guarantee by category:");
    for (int c = 0; c < SREF_COUNT; c++)
        if (too_big_cat[c])
            printf(" %s %ld", sref_category_name(c), too_big_cat[c]);
    printf("\n");
    for (int k = 0; k < nisa; k++) {
        printf("self: %-7s %10ld spawned rays traced, %ld self-intersections\n",
               isas[k]->name, traced[k], self[k]);
        bad += self[k];
    }
    printf("self: %ld spawns, %ld not strictly on their side, %ld exact self-intersections "
           "in %ld checked exactly, %ld outside the guarantee (offset > min(R, H)/4); of the "
           "kernels' self-intersections, %ld are answers outside their own tolerance band\n",
           spawns, wrong_side, exact_self, exact_checked, too_big, kernel_faults);
    return bad == 0 && spawns > 0;
}

/* ---- nested ------------------------------------------------------------------ */

static int run_nested(void)
{
    const long N = quick ? 2000 : 200000;
    long tried = 0, inside_inner = 0, exact_hits = 0, missed[CYLRAY_ISA_COUNT] = {0};
    long excused = 0;
    cylgen_rng rng;
    cylgen_seed(&rng, 4242);
    for (long n = 0; n < N; n++) {
        cylgen_case c; /* the outer cylinder and the primary ray, for the messages */
        cylray_cylinder in;
        sref_nested(&rng, &c.cyl, &in, c.o, c.d);
        cylray_prepared Po, Pi;
        if (cylray_prepare(&Po, &c.cyl) || cylray_prepare(&Pi, &in))
            continue;
        cylray_ray4 r4;
        cylray_hit4 h4;
        memset(&r4, 0, sizeof r4);
        r4.ox[0] = c.o[0], r4.oy[0] = c.o[1], r4.oz[0] = c.o[2];
        r4.dx[0] = c.d[0], r4.dy[0] = c.d[1], r4.dz[0] = c.d[2];
        r4.tmax[0] = INFINITY;
        if (!isas[n % nisa]->intersect4(&Po, &r4, &h4, 1u, 0) || (h4.part[0] & CYLRAY_BACKFACE))
            continue;
        float p[3], err, w[3], x0[3];
        cylray_hit_point(&Po, c.o, c.d, h4.t[0], h4.part[0], p, &err);
        double nn[3];
        sref_normal(&c.cyl, p, h4.part[0], nn);
        sref_transmitted(&rng, nn, w);
        cylray_spawn_origin(&Po, p, err, h4.part[0], w, x0);
        tried++;
        if (sref_inside_solid(&in, x0)) {
            inside_inner++;
            fail("nested", &c, "the spawned origin is already inside the inner cylinder");
            continue;
        }
        cylref_hit eh;
        if (cylref_intersect(&in, x0, w, 0.0f, INFINITY, 0, &eh) != 1)
            continue;
        exact_hits++;
        for (int k = 0; k < nisa; k++) {
            cylray_ray4 q;
            cylray_hit4 qh;
            memset(&q, 0, sizeof q);
            q.ox[0] = x0[0], q.oy[0] = x0[1], q.oz[0] = x0[2];
            q.dx[0] = w[0], q.dy[0] = w[1], q.dz[0] = w[2];
            q.tmax[0] = INFINITY;
            if (isas[k]->intersect4(&Pi, &q, &qh, 1u, 0))
                continue;
            cylref_band b;
            cylref_band_eval(&in, x0, w, 0.0f, INFINITY, 0, &b);
            if (b.hit_unstable) {
                excused++;
                continue;
            }
            missed[k]++;
            fail("nested", &c, isas[k]->name);
        }
    }
    long bad = inside_inner;
    printf("nested: %ld transmitted rays, %ld origins inside the inner cylinder, %ld with an "
           "exact hit on it", tried, inside_inner, exact_hits);
    for (int k = 0; k < nisa; k++) {
        printf(", %s missed %ld", isas[k]->name, missed[k]);
        bad += missed[k];
    }
    printf(" (%ld excused: a graze within the tolerance band)\n", excused);
    return bad == 0 && exact_hits > tried / 2;
}

/* ---- batched forms -------------------------------------------------------------- */

static int same3(const float a[3], const float b[3])
{
    return memcmp(a, b, 3 * sizeof *a) == 0;
}

static int run_batched(void)
{
    const long G = groups_for(4000);
    long lanes = 0, diff = 0;
    cylgen_rng rng;
    cylgen_seed(&rng, 99);
    for (long g = 0; g < G; g++) {
        cylgen_case c[SREF_GROUP];
        sref_group((int)(g % SREF_COUNT), 9000 + (uint64_t)g, c);
        cylray_prepared P;
        if (cylray_prepare(&P, &c[0].cyl) != CYLRAY_OK)
            continue;
        cylray_ray16 ray;
        cylray_hit16 hit;
        uint32_t m = trace_group(isas[0], &P, c, &ray, &hit);
        /* the scalar pair */
        float p[16][3], err[16], w[16][3], x[16][3], xs[16][3];
        const uint32_t outward = (uint32_t)(cylgen_uniform(&rng) * 65536.0);
        for (int i = 0; i < 16; i++) {
            double u[3];
            sref_unit(&rng, u);
            for (int k = 0; k < 3; k++)
                w[i][k] = (float)u[k];
            if (m >> i & 1u) {
                cylray_hit_point(&P, c[i].o, c[i].d, hit.t[i], hit.part[i], p[i], &err[i]);
                cylray_spawn_origin(&P, p[i], err[i], hit.part[i], w[i], x[i]);
                cylray_spawn_origin_side(&P, p[i], err[i], hit.part[i], outward >> i & 1u,
                                         w[i], xs[i]);
            }
        }
        /* packets of 16, and of 8 and 4 (their lanes are the first ones) */
        cylray_points16 pts;
        cylray_hit_points16(&P, &ray, &hit, m, &pts);
        cylray_ray16 out = ray;
        for (int i = 0; i < 16; i++)
            out.dx[i] = w[i][0], out.dy[i] = w[i][1], out.dz[i] = w[i][2];
        cylray_spawn_rays16(&P, &pts, &hit, m, &out);
        cylray_ray8 r8;
        cylray_hit8 h8;
        cylray_points8 p8;
        cylray_ray4 r4;
        cylray_hit4 h4;
        cylray_points4 p4;
        for (int i = 0; i < 8; i++) {
            r8.ox[i] = ray.ox[i], r8.oy[i] = ray.oy[i], r8.oz[i] = ray.oz[i];
            r8.dx[i] = ray.dx[i], r8.dy[i] = ray.dy[i], r8.dz[i] = ray.dz[i];
            h8.t[i] = hit.t[i], h8.part[i] = hit.part[i];
            if (i < 4) {
                r4.ox[i] = ray.ox[i], r4.oy[i] = ray.oy[i], r4.oz[i] = ray.oz[i];
                r4.dx[i] = ray.dx[i], r4.dy[i] = ray.dy[i], r4.dz[i] = ray.dz[i];
                h4.t[i] = hit.t[i], h4.part[i] = hit.part[i];
            }
        }
        cylray_hit_points8(&P, &r8, &h8, m & 0xffu, &p8);
        cylray_hit_points4(&P, &r4, &h4, m & 0xfu, &p4);
        for (int i = 0; i < 8; i++) {
            r8.dx[i] = w[i][0], r8.dy[i] = w[i][1], r8.dz[i] = w[i][2];
            if (i < 4)
                r4.dx[i] = w[i][0], r4.dy[i] = w[i][1], r4.dz[i] = w[i][2];
        }
        cylray_spawn_rays8(&P, &p8, &h8, m & 0xffu, &r8);
        cylray_spawn_rays4(&P, &p4, &h4, m & 0xfu, &r4);
        /* the side forms, on copies of the packets */
        cylray_ray16 out_s = out;
        cylray_ray8 r8s = r8;
        cylray_ray4 r4s = r4;
        cylray_spawn_rays_side16(&P, &pts, &hit, m, outward, &out_s);
        cylray_spawn_rays_side8(&P, &p8, &h8, m & 0xffu, outward, &r8s);
        cylray_spawn_rays_side4(&P, &p4, &h4, m & 0xfu, outward, &r4s);
        /* a stream, and a leaf of 16 holding the cylinder in lane 5 */
        float sx[16], sy[16], sz[16], se[16], ox[16], oy[16], oz[16];
        float wx[16], wy[16], wz[16];
        for (int i = 0; i < 16; i++)
            wx[i] = w[i][0], wy[i] = w[i][1], wz[i] = w[i][2];
        int32_t spart[16];
        for (int i = 0; i < 16; i++)
            spart[i] = m >> i & 1u ? hit.part[i] : CYLRAY_MISS;
        cylray_rays rs = {ray.ox, ray.oy, ray.oz, ray.dx, ray.dy, ray.dz, ray.tmin, ray.tmax};
        cylray_hits hs = {hit.t, NULL, NULL, NULL, spart};
        cylray_points sp = {sx, sy, sz, se}, dirs = {wx, wy, wz, NULL}, org = {ox, oy, oz, NULL};
        size_t ns = cylray_hit_points_stream(&P, &rs, &hs, &sp, 16);
        cylray_spawn_stream(&P, &sp, spart, &dirs, &org, 16);
        float qx[16], qy[16], qz[16];
        uint8_t outw[16];
        for (int i = 0; i < 16; i++)
            outw[i] = (uint8_t)(outward >> i & 1u);
        cylray_points org_s = {qx, qy, qz, NULL};
        cylray_spawn_stream_side(&P, &sp, spart, outw, &dirs, &org_s, 16);
        /* a leaf of 6 with the cylinder in lane 5 behind five others */
        cylray_leaf16 leaf;
        cylray_cylinder six[6];
        const size_t lane = 5;
        for (int j = 0; j < 5; j++) {
            six[j] = c[0].cyl;
            six[j].center[0] += 1e5f;
            six[j].radius = 1.0f + (float)j;
        }
        six[lane] = c[0].cyl;
        if (cylray_leaf_prepare16(&leaf, six, NULL, 6) != CYLRAY_OK) {
            diff++;
            fail("batched", &c[0], "cylray_leaf_prepare16 refused the cylinder");
            continue;
        }
        if (ns != (size_t)popcount(m))
            diff++;
        for (int i = 0; i < 16; i++) {
            if (!(m >> i & 1u))
                continue;
            lanes++;
            const float a[3] = {pts.x[i], pts.y[i], pts.z[i]};
            const float b[3] = {out.ox[i], out.oy[i], out.oz[i]};
            const float s1[3] = {sx[i], sy[i], sz[i]}, s2[3] = {ox[i], oy[i], oz[i]};
            int bad = !same3(a, p[i]) || pts.err[i] != err[i] || !same3(b, x[i]) ||
                      out.tmin[i] != 0.0f || !same3(s1, p[i]) || se[i] != err[i] ||
                      !same3(s2, x[i]);
            if (i < 8) {
                const float a8[3] = {p8.x[i], p8.y[i], p8.z[i]};
                const float b8[3] = {r8.ox[i], r8.oy[i], r8.oz[i]};
                bad |= !same3(a8, p[i]) || p8.err[i] != err[i] || !same3(b8, x[i]);
            }
            if (i < 4) {
                const float a4[3] = {p4.x[i], p4.y[i], p4.z[i]};
                const float b4[3] = {r4.ox[i], r4.oy[i], r4.oz[i]};
                bad |= !same3(a4, p[i]) || p4.err[i] != err[i] || !same3(b4, x[i]);
            }
            cylray_ray1 r1 = {{c[i].o[0], c[i].o[1], c[i].o[2]}, {c[i].d[0], c[i].d[1], c[i].d[2]},
                              c[i].tmin, hit.t[i]};
            cylray_hit1 h1 = {hit.t[i], {0, 0, 0}, hit.part[i], 7, (uint32_t)lane};
            float lp[3], le, lx[3];
            cylray_leaf_hit_point16(&leaf, &r1, &h1, lp, &le);
            cylray_leaf_spawn_origin16(&leaf, &h1, lp, le, w[i], lx);
            bad |= !same3(lp, p[i]) || le != err[i] || !same3(lx, x[i]);
            /* the side forms */
            float ls[3];
            cylray_leaf_spawn_origin_side16(&leaf, &h1, lp, le, outward >> i & 1u, w[i], ls);
            const float s16[3] = {out_s.ox[i], out_s.oy[i], out_s.oz[i]};
            const float ss[3] = {qx[i], qy[i], qz[i]};
            bad |= !same3(ls, xs[i]) || !same3(s16, xs[i]) || !same3(ss, xs[i]) ||
                   out_s.tmin[i] != 0.0f;
            if (i < 8) {
                const float s8[3] = {r8s.ox[i], r8s.oy[i], r8s.oz[i]};
                bad |= !same3(s8, xs[i]);
            }
            if (i < 4) {
                const float s4[3] = {r4s.ox[i], r4s.oy[i], r4s.oz[i]};
                bad |= !same3(s4, xs[i]);
            }
            /* the side w lies on, by a clear margin: the side form is the plain one */
            double ne[3];
            sref_normal(&c[i].cyl, p[i], hit.part[i] & CYLRAY_PART_MASK, ne);
            const double wn = ne[0] * w[i][0] + ne[1] * w[i][1] + ne[2] * w[i][2];
            if (fabs(wn) > 1e-6) {
                float xw[3];
                cylray_spawn_origin_side(&P, p[i], err[i], hit.part[i], wn > 0, w[i], xw);
                bad |= !same3(xw, x[i]);
            }
            if (bad) {
                diff++;
                fail("batched", &c[i], "a batched form differs from the scalar pair");
            }
        }
    }
    printf("batched: %ld lanes compared (packets 4/8/16, stream, leaf; plain and side forms), "
           "%ld differ\n", lanes,
           diff);
    return diff == 0 && lanes > 0;
}

/* Rays down the axis onto a disc's center (a point where the radial direction is
 * undefined): the hit point stays at the center, within its bound of the cap's plane,
 * and the reflected ray's origin stays near the axis on the ray's side. */
static int run_axis(void)
{
    static const float axes[][3] = {{0, 0, 1}, {0, -3, 0}, {1, 0, 0}, {0.3f, -0.5f, 0.8f},
                                    {-1e-3f, 2e-3f, 5e-4f}};
    static const float centers[][3] = {{0, 0, 0}, {1.5f, -2, 7}, {1e4f, -3e4f, 2e3f}};
    static const float radii[] = {1e-2f, 1, 250};
    long bad = 0, n = 0;
    for (size_t ai = 0; ai < sizeof axes / sizeof axes[0]; ai++)
        for (size_t ci = 0; ci < sizeof centers / sizeof centers[0]; ci++)
            for (size_t ri = 0; ri < sizeof radii / sizeof radii[0]; ri++)
                for (int end = 0; end < 2; end++) {
                    const float *a = axes[ai], *c0 = centers[ci];
                    const float R = radii[ri], H = 2 * R;
                    cylray_cylinder cyl = {{c0[0], c0[1], c0[2]}, {a[0], a[1], a[2]}, R, H,
                                           CYLRAY_CAPPED};
                    cylray_prepared P;
                    if (cylray_prepare(&P, &cyl) != CYLRAY_OK)
                        continue;
                    /* floats must resolve the disc there (the guarantee's condition) */
                    const double cmax = fmax(fabs(c0[0]), fmax(fabs(c0[1]), fabs(c0[2])));
                    if (256 * cmax * 0x1p-24 > R)
                        continue;
                    const double al = sqrt((double)a[0] * a[0] + (double)a[1] * a[1] +
                                           (double)a[2] * a[2]);
                    const double sg = end ? 1 : -1; /* the ray comes from beyond that end */
                    float o[3], d[3];
                    for (int k = 0; k < 3; k++) {
                        o[k] = (float)(c0[k] + sg * 3 * H * a[k] / al);
                        d[k] = (float)(-sg * a[k] / al);
                    }
                    const int32_t part = end ? CYLRAY_CAP_HI : CYLRAY_CAP_LO;
                    cylray_ray4 ray;
                    cylray_hit4 hit;
                    for (int l = 0; l < 4; l++) {
                        ray.ox[l] = o[0], ray.oy[l] = o[1], ray.oz[l] = o[2];
                        ray.dx[l] = d[0], ray.dy[l] = d[1], ray.dz[l] = d[2];
                        ray.tmin[l] = 0, ray.tmax[l] = INFINITY;
                    }
                    if (!(cylray_intersect4(&P, &ray, &hit, 1u, 0) & 1u) ||
                        hit.part[0] != part) {
                        bad++;
                        fprintf(stderr, "axis: no cap hit (axis %zu center %zu R %g end %d)\n",
                                ai, ci, (double)R, end);
                        continue;
                    }
                    float p[3], err, org[3];
                    cylray_hit_point(&P, o, d, hit.t[0], part, p, &err);
                    const float w[3] = {-d[0], -d[1], -d[2]};
                    cylray_spawn_origin(&P, p, err, part, w, org);
                    double zp = 0, zo = 0, rp2 = 0, ro2 = 0;
                    double pc[3], oc[3];
                    for (int k = 0; k < 3; k++) {
                        pc[k] = (double)p[k] - c0[k];
                        oc[k] = (double)org[k] - c0[k];
                        zp += pc[k] * a[k] / al;
                        zo += oc[k] * a[k] / al;
                    }
                    for (int k = 0; k < 3; k++) {
                        rp2 += (pc[k] - zp * a[k] / al) * (pc[k] - zp * a[k] / al);
                        ro2 += (oc[k] - zo * a[k] / al) * (oc[k] - zo * a[k] / al);
                    }
                    const int ok = sqrt(rp2) <= 0.25 * R && fabs(fabs(zp) - H) <= err &&
                                   sqrt(ro2) <= 0.25 * R && sg * zo > H;
                    n++;
                    if (!ok) {
                        bad++;
                        fprintf(stderr,
                                "axis: axis %zu center %zu R %g end %d: point %g from the "
                                "axis, %g off the plane (err %g); origin %g from the axis, "
                                "%g beyond the plane\n",
                                ai, ci, (double)R, end, sqrt(rp2), fabs(fabs(zp) - H),
                                (double)err, sqrt(ro2), sg * zo - H);
                    }
                }
    printf("axis: %ld disc centers, %ld failures\n", n, bad);
    return n > 0 && bad == 0;
}

/* ---- the side form ------------------------------------------------------------- */

/* A hit of the part left at t is premature when the exact ray from x0 meets nothing in
 * [0, tmax], or meets something first at t_e with t < t_e / 2. */
static int premature(const cylray_cylinder *cyl, const float x0[3], const float w[3],
                     float tmax, int left, int hit_part, float t)
{
    if ((hit_part & CYLRAY_PART_MASK) != (left & CYLRAY_PART_MASK))
        return 0;
    cylref_hit eh;
    if (cylref_intersect(cyl, x0, w, 0.0f, tmax, 0, &eh) != 1)
        return 1;
    return (double)t < 0.5 * eh.t;
}

/* One case of the side form, from a primary hit (t, part, the kernel's outward normal
 * n) on every ISA's path: the side from n, the origin strictly there and on w's side of
 * other near surfaces, and the spawned ray traced on every ISA at widths 4, 8 and 16
 * and through a leaf. Returns the number of failures; *spawned counts the spawns. */
static long side_case(const cylgen_case *c, const cylray_prepared *P, float t, int32_t part,
                      const float n[3], const float w[3], float tmax, long *spawned,
                      long *too_big)
{
    const cylray_cylinder *cyl = &c->cyl;
    float p[3], err, x0[3];
    cylray_hit_point(P, c->o, c->d, t, part, p, &err);
    const double wn = (double)w[0] * n[0] + (double)w[1] * n[1] + (double)w[2] * n[2];
    const int outward = wn > 0, Pm = part & CYLRAY_PART_MASK;
    cylray_spawn_origin_side(P, p, err, part, outward, w, x0);
    double mv = 0;
    for (int k = 0; k < 3; k++)
        mv += ((double)x0[k] - p[k]) * ((double)x0[k] - p[k]);
    if (!(sqrt(mv) <= 0.25 * fmin(cyl->radius, cyl->half_height))) {
        ++*too_big;
        return 0;
    }
    ++*spawned;
    long bad = 0;
    char s[400];
    const double sig = sref_sigma(cyl, x0, Pm);
    const unsigned others = near_surfaces(cyl, p, err, Pm) & ~(1u << Pm);
    if (!(outward ? sig > 0 : sig < 0) || !strictly_on_side(cyl, p, others, w, x0)) {
        bad++;
        snprintf(s, sizeof s, "part %d outward %d: origin (%a %a %a) at %g from it", part,
                 outward, x0[0], x0[1], x0[2], sig);
        fail("side: wrong side", c, s);
    }
    /* the same ray 16 times over, so that every width and lane sees it */
    float xs[16][3], ws[16][3], tm[16], th[16];
    int32_t hp[16];
    for (int i = 0; i < 16; i++)
        for (int k = 0; k < 3; k++)
            xs[i][k] = x0[k], ws[i][k] = w[k], tm[i] = tmax;
    cylray_leaf4 leaf;
    const int leaf_ok = cylray_leaf_prepare4(&leaf, cyl, NULL, 1) == CYLRAY_OK;
    for (int k = 0; k < nisa; k++) {
        for (int width = 4; width <= 16; width *= 2) {
            const uint32_t lanes = width == 16 ? 0xffffu : (1u << width) - 1u;
            uint32_t got = trace16(isas[k], width, P, (const float(*)[3])xs,
                                   (const float(*)[3])ws, tm, lanes, th, hp);
            for (int i = 0; i < width; i++)
                if ((got >> i & 1u) && premature(cyl, x0, w, tmax, part, hp[i], th[i])) {
                    bad++;
                    snprintf(s, sizeof s,
                             "%s width %d lane %d: part %d outward %d left at (%a %a %a), "
                             "spawned (%a %a %a) w (%a %a %a), hit part %d at t %a",
                             isas[k]->name, width, i, part, outward, p[0], p[1], p[2], x0[0],
                             x0[1], x0[2], w[0], w[1], w[2], hp[i], th[i]);
                    fail("side: self-hit", c, s);
                    break;
                }
        }
        if (leaf_ok) {
            cylray_ray1 r1 = {{x0[0], x0[1], x0[2]}, {w[0], w[1], w[2]}, 0.0f, tmax};
            cylray_hit1 h1;
            if (isas[k]->leaf_intersect4(&leaf, &r1, &h1, 0) &&
                premature(cyl, x0, w, tmax, part, h1.part, h1.t)) {
                bad++;
                snprintf(s, sizeof s, "%s leaf: hit part %d at t %a", isas[k]->name,
                         (int)h1.part, h1.t);
                fail("side: self-hit", c, s);
            }
        }
    }
    return bad;
}

/* The two far rods: shadow rays whose kernel normal gives cos +0.0012 and whose exact
 * normal at the rounded point -0.0007; the primary hit on every ISA, by packet, leaf and
 * stream. */
static long side_far_rods(long *spawned, long *too_big)
{
    static const struct {
        float c[3], a[3], R, H, o[3], d[3], w[3];
    } rods[2] = {
        {{0x1.3875fp+13f, 0x1.3889cp+13f, 0x1.387cfap+13f},
         {0x1.84198p+7f, 0x1.d021cp+9f, -0x1.3d4ap+8f}, 0x1.99999ap-5f, 0x1.f40012p+8f,
         {0x1.3892eap+13f, 0x1.38a57cp+13f, 0x1.38a7d6p+13f},
         {-0x1.00ae34p-1f, -0x1.1a93f2p-1f, -0x1.552ffap-1f},
         {0x1.165p+3f, -0x1.9cp-1f, 0x1.5d28p+3f}},
        {{0x1.38834p+13f, 0x1.3883c4p+13f, 0x1.38798cp+13f},
         {0x1.e58b2p+9f, 0x1.6767p+6f, -0x1.ba588p+7f}, 0x1.99999ap-5f, 0x1.f40006p+8f,
         {0x1.3892eap+13f, 0x1.38a57cp+13f, 0x1.38a7d6p+13f},
         {-0x1.0ffb68p-1f, -0x1.15e316p-1f, -0x1.4d16e4p-1f},
         {0x1.257p+3f, -0x1.3f8p-1f, 0x1.62e8p+3f}},
    };
    long bad = 0;
    for (int r = 0; r < 2; r++) {
        cylgen_case c;
        memset(&c, 0, sizeof c);
        for (int k = 0; k < 3; k++) {
            c.cyl.center[k] = rods[r].c[k], c.cyl.axis[k] = rods[r].a[k];
            c.o[k] = rods[r].o[k], c.d[k] = rods[r].d[k];
        }
        c.cyl.radius = rods[r].R, c.cyl.half_height = rods[r].H, c.cyl.flags = CYLRAY_CAPPED;
        c.tmin = 0, c.tmax = INFINITY;
        cylray_prepared P;
        cylray_leaf8 leaf;
        if (cylray_prepare(&P, &c.cyl) != CYLRAY_OK ||
            cylray_leaf_prepare8(&leaf, &c.cyl, NULL, 1) != CYLRAY_OK) {
            fail("side: far rods", &c, "refused");
            bad++;
            continue;
        }
        for (int k = 0; k < nisa; k++)
            for (int form = 0; form < 3; form++) {
                float t = 0, n[3] = {0, 0, 0};
                int32_t part = 0;
                int got = 0;
                if (form == 0) {
                    cylray_ray8 ray;
                    cylray_hit8 hit;
                    memset(&ray, 0, sizeof ray);
                    for (int i = 0; i < 8; i++) {
                        ray.ox[i] = c.o[0], ray.oy[i] = c.o[1], ray.oz[i] = c.o[2];
                        ray.dx[i] = c.d[0], ray.dy[i] = c.d[1], ray.dz[i] = c.d[2];
                        ray.tmax[i] = INFINITY;
                    }
                    got = isas[k]->intersect8(&P, &ray, &hit, 1u << (k % 8), CYLRAY_NORMAL) != 0;
                    const int i = k % 8;
                    t = hit.t[i], part = hit.part[i];
                    n[0] = hit.nx[i], n[1] = hit.ny[i], n[2] = hit.nz[i];
                } else if (form == 1) {
                    cylray_ray1 r1 = {{c.o[0], c.o[1], c.o[2]}, {c.d[0], c.d[1], c.d[2]}, 0,
                                      INFINITY};
                    cylray_hit1 h1;
                    got = isas[k]->leaf_intersect8(&leaf, &r1, &h1, CYLRAY_NORMAL);
                    t = h1.t, part = h1.part;
                    memcpy(n, h1.n, sizeof n);
                } else {
                    float tmax = INFINITY, tmin = 0, ht = 0, nx = 0, ny = 0, nz = 0;
                    int32_t hpart = 0;
                    cylray_rays rs = {&c.o[0], &c.o[1], &c.o[2], &c.d[0], &c.d[1], &c.d[2],
                                      &tmin, &tmax};
                    cylray_hits hs = {&ht, &nx, &ny, &nz, &hpart};
                    got = isas[k]->intersect_stream(&P, &rs, &hs, 1, CYLRAY_NORMAL) == 1;
                    t = ht, part = hpart, n[0] = nx, n[1] = ny, n[2] = nz;
                }
                if (!got || part != CYLRAY_SIDE) {
                    bad++;
                    fail("side: far rods", &c, "the primary ray does not hit the side");
                    continue;
                }
                long sp = *spawned, tb = *too_big;
                bad += side_case(&c, &P, t, part, n, rods[r].w, 1.0f, spawned, too_big);
                bad += side_case(&c, &P, t, part, n, rods[r].w, INFINITY, spawned, too_big);
                if (*too_big != tb || *spawned != sp + 2) {
                    bad++;
                    fail("side: far rods", &c, "outside the guarantee's condition");
                }
            }
    }
    return bad;
}

static int run_side(void)
{
    long spawned = 0, too_big = 0, bad = side_far_rods(&spawned, &too_big);
    const long far_spawned = spawned, far_bad = bad;
    printf("side: far rods: %ld spawns (2 rods x %d ISAs x packet, leaf, stream x tmax 1, "
           "inf), %ld failures\n", far_spawned, nisa, far_bad);
    const long G = groups_for(20000);
    cylgen_rng rng;
    cylgen_seed(&rng, 31337);
    long grazing = 0, disagree = 0;
    for (long g = 0; g < G; g++) {
        const int cat = (int)(g % SREF_COUNT);
        cylgen_case c[SREF_GROUP];
        sref_group(cat, 70000 + (uint64_t)g, c);
        cylray_prepared P;
        if (cylray_prepare(&P, &c[0].cyl) != CYLRAY_OK)
            continue;
        cylray_ray16 ray;
        cylray_hit16 hit;
        memset(&ray, 0, sizeof ray);
        memset(&hit, 0, sizeof hit);
        for (int i = 0; i < SREF_GROUP; i++) {
            ray.ox[i] = c[i].o[0], ray.oy[i] = c[i].o[1], ray.oz[i] = c[i].o[2];
            ray.dx[i] = c[i].d[0], ray.dy[i] = c[i].d[1], ray.dz[i] = c[i].d[2];
            ray.tmin[i] = c[i].tmin, ray.tmax[i] = c[i].tmax;
        }
        uint32_t m = isas[g % nisa]->intersect16(&P, &ray, &hit, 0xffffu, CYLRAY_NORMAL);
        for (int i = 0; i < SREF_GROUP; i++) {
            if (!(m >> i & 1u))
                continue;
            const float n[3] = {hit.nx[i], hit.ny[i], hit.nz[i]};
            const double nd[3] = {n[0], n[1], n[2]};
            /* grazing the kernel's tangent plane on either side, 1e-7-1e-2 rad (or along
             * it), one in five; otherwise anywhere on that side */
            float w[3];
            sref_direction(&rng, nd, (g + i) & 1 ? 1 : -1, w);
            const double wn = (double)w[0] * n[0] + (double)w[1] * n[1] + (double)w[2] * n[2];
            const double wl = sqrt((double)w[0] * w[0] + (double)w[1] * w[1] + (double)w[2] * w[2]);
            grazing += fabs(wn) < 1e-2 * wl;
            double ne[3];
            float p[3], err;
            cylray_hit_point(&P, c[i].o, c[i].d, hit.t[i], hit.part[i], p, &err);
            sref_normal(&c[i].cyl, p, hit.part[i] & CYLRAY_PART_MASK, ne);
            disagree += (wn > 0) != (ne[0] * w[0] + ne[1] * w[1] + ne[2] * w[2] > 0);
            bad += side_case(&c[i], &P, hit.t[i], hit.part[i], n, w,
                             (g + i) % 3 ? INFINITY : 1.0f, &spawned, &too_big);
        }
    }
    printf("side: %ld spawns traced on %d ISAs (widths 4, 8, 16 and a leaf), %ld grazing, %ld "
           "whose kernel normal and exact normal at p disagree on w's side; %ld outside the "
           "guarantee (offset > min(R, H)/4); %ld failures\n",
           spawned, nisa, grazing, disagree, too_big, bad);
    return bad == 0 && spawned > far_spawned;
}

/* ---- rounding to float --------------------------------------------------------- */

static uint64_t rng_next(uint64_t *s)
{
    *s += 0x9e3779b97f4a7c15ull;
    uint64_t z = *s;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

/* cylray_round_float_(x, 0) against the conversion on random doubles of every
 * magnitude a float reaches (subnormals, ties, overflow), and (hi, lo) against an exact
 * tie-break: hi a midpoint between two floats, lo of either sign. */
static int run_round(void)
{
    const long N = quick ? 200000 : 20000000;
    long bad = 0, ties = 0;
    uint64_t s = 12345;
    for (long i = 0; i < N; i++) {
        uint64_t r = rng_next(&s), b;
        /* exponents from 2^-160 to 2^130; every third a float or a midpoint */
        const int ex = (int)(r % 291) - 160;
        b = ((uint64_t)(ex + 1023) << 52) | (rng_next(&s) & 0xfffffffffffffull);
        if (i % 3 == 1)
            b &= ~((1ull << 28) - 1) | (1ull << 28);
        else if (i % 3 == 2)
            b = (b & ~((1ull << 29) - 1)) | (1ull << 28); /* a midpoint of normal floats */
        b |= (r >> 63) << 63;
        double x;
        memcpy(&x, &b, sizeof x);
        volatile float ref = (float)x;
        float got = cylray_round_float_(x, 0);
        if (memcmp(&got, (const void *)&ref, sizeof got) != 0) {
            if (bad++ < 10)
                fprintf(stderr, "round: %a gives %a, the conversion %a\n", x, (double)got,
                        (double)ref);
        }
        /* a tie broken by lo: the nearest float on lo's side of the midpoint */
        if (i % 3 == 2 && ex > -126 && ex < 127) {
            const double lo = ldexp(x, -60) * ((r >> 7 & 1) ? 1 : -1);
            const float up = cylray_round_float_(x, fabs(lo) * (x > 0 ? 1 : -1));
            const float dn = cylray_round_float_(x, -fabs(lo) * (x > 0 ? 1 : -1));
            /* exact: the floats on each side of x, by magnitude */
            const double a = fabs((double)up), c = fabs((double)dn);
            ties++;
            if (!(a > fabs(x) && c < fabs(x) && a - fabs(x) == fabs(x) - c)) {
                if (bad++ < 10)
                    fprintf(stderr, "round: tie %a: up %a down %a\n", x, (double)up,
                            (double)dn);
            }
        }
    }
    printf("round: %ld doubles, %ld ties broken by a low part, %ld wrong\n", N, ties, bad);
    return bad == 0;
}

int main(int argc, char **argv)
{
    const char *q = getenv("CYLRAY_TEST_QUICK");
    quick = q && *q && strcmp(q, "0") != 0;
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
        ok = run_self();
    else if (strcmp(mode, "nested") == 0)
        ok = run_nested();
    else if (strcmp(mode, "batched") == 0)
        ok = run_batched();
    else if (strcmp(mode, "axis") == 0)
        ok = run_axis();
    else if (strcmp(mode, "side") == 0)
        ok = run_side();
    else if (strcmp(mode, "round") == 0)
        ok = run_round();
    else {
        fprintf(stderr, "usage: spawn_test bounds|self|nested|batched|axis|side|round\n");
        return 2;
    }
    printf("%s: %s\n", mode, ok ? "ok" : "FAILED");
    return ok ? 0 : 1;
}
