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
 *   spawn_test batched  the packet, stream and leaf forms (plain, side and normal) of
 *                       every ISA equal the scalar pair bit for bit (bounds and self
 *                       also take their points and origins from each ISA's stream forms)
 *   spawn_test side     the side form: the tracer's side from the kernel's normal
 *                       (random hits, grazing directions, and fixed cases, far rods whose
 *                       kernel normal and exact normal disagree), the origin strictly
 *                       on that side, no hit of the part before the exact ray's
 *   spawn_test reintersect  pbrt-v4's Reintersect setup (open tubes of random size,
 *                       rotation, translation and scale, rays from far away): spawned
 *                       rays face-forwarded to the kernel's normal, as the README does,
 *                       never hit their tube again
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
#include <stdint.h>
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
                c->cyl.axis[1], c->cyl.axis[2], c->cyl.radius, c->cyl.half_height, c->cyl.flags,
                c->o[0], c->o[1], c->o[2], c->d[0], c->d[1], c->d[2], detail);
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

/* ISA k's stream form of the hit points of the lanes set in m (the others are passed as
 * CYLRAY_MISS and must stay unwritten), checked against the scalar pair bit for bit.
 * Returns the number of lanes that differ. */
static long isa_points(const cylray_kernels *k, const cylray_prepared *P,
                       const cylray_ray16 *ray, const cylray_hit16 *hit, uint32_t m,
                       float p[16][3], float err[16])
{
    float x[16], y[16], z[16], e[16];
    int32_t part[16];
    for (int i = 0; i < 16; i++) {
        part[i] = m >> i & 1u ? hit->part[i] : CYLRAY_MISS;
        x[i] = y[i] = z[i] = e[i] = -7.0f;
    }
    cylray_rays rs = {ray->ox, ray->oy, ray->oz,   ray->dx,
                      ray->dy, ray->dz, ray->tmin, (float *)(uintptr_t)ray->tmax};
    cylray_hits hs = {(float *)(uintptr_t)hit->t, NULL, NULL, NULL, part};
    cylray_points pts = {x, y, z, e};
    long bad = k->hit_points_stream(P, &rs, &hs, &pts, 16) != (size_t)popcount(m);
    for (int i = 0; i < 16; i++) {
        if (!(m >> i & 1u)) {
            bad += x[i] != -7.0f || y[i] != -7.0f || z[i] != -7.0f || e[i] != -7.0f;
            continue;
        }
        float sp[3], se;
        const float o[3] = {ray->ox[i], ray->oy[i], ray->oz[i]};
        const float d[3] = {ray->dx[i], ray->dy[i], ray->dz[i]};
        cylray_hit_point(P, o, d, hit->t[i], hit->part[i], sp, &se);
        p[i][0] = x[i], p[i][1] = y[i], p[i][2] = z[i], err[i] = e[i];
        bad += memcmp(sp, p[i], sizeof sp) != 0 || memcmp(&se, &err[i], sizeof se) != 0;
    }
    return bad;
}

/* ISA k's stream form of the origins of the lanes set in m, against the scalar pair. */
static long isa_origins(const cylray_kernels *k, const cylray_prepared *P,
                        const cylray_hit16 *hit, uint32_t m, const float p[16][3],
                        const float err[16], const float w[16][3], float x0[16][3])
{
    float px[16], py[16], pz[16], pe[16], wx[16], wy[16], wz[16];
    int32_t part[16];
    for (int i = 0; i < 16; i++) {
        part[i] = m >> i & 1u ? hit->part[i] : CYLRAY_MISS;
        px[i] = p[i][0], py[i] = p[i][1], pz[i] = p[i][2], pe[i] = err[i];
        wx[i] = w[i][0], wy[i] = w[i][1], wz[i] = w[i][2];
    }
    /* the origins over the directions, as the header allows */
    cylray_points pts = {px, py, pz, pe}, dirs = {wx, wy, wz, NULL};
    k->spawn_stream(P, &pts, part, &dirs, &dirs, 16);
    long bad = 0;
    for (int i = 0; i < 16; i++) {
        if (!(m >> i & 1u)) { /* untouched, bit for bit: an unused lane may hold a NaN */
            bad += memcmp(&wx[i], &w[i][0], sizeof wx[i]) != 0 ||
                   memcmp(&wy[i], &w[i][1], sizeof wy[i]) != 0 ||
                   memcmp(&wz[i], &w[i][2], sizeof wz[i]) != 0;
            continue;
        }
        float sx[3];
        cylray_spawn_origin(P, p[i], err[i], hit->part[i], w[i], sx);
        x0[i][0] = wx[i], x0[i][1] = wy[i], x0[i][2] = wz[i];
        bad += memcmp(sx, x0[i], sizeof sx) != 0;
    }
    return bad;
}

/* ---- bounds ------------------------------------------------------------------- */

static int run_bounds(void)
{
    long hits = 0, viol = 0, disagree = 0;
    const long G = groups_for(2000);
    printf("%-13s %9s %10s %12s %12s %12s\n", "category", "hits", "violations", "err/ulp p50",
           "err/ulp max", "err/exact p50");
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
                /* the points of this ISA's stream form, the same as the scalar pair's */
                float pk[16][3], ek[16];
                if (isa_points(isas[k], &P, &ray, &hit, m, pk, ek)) {
                    disagree++;
                    fail("bound", &c[0], "the stream form differs from cylray_hit_point");
                }
                for (int i = 0; i < SREF_GROUP; i++) {
                    if (!(m >> i & 1u))
                        continue;
                    const float *p = pk[i], err = ek[i];
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
    printf("bounds: %ld hits over %d ISAs (each ISA's hits through its own stream form), "
           "%ld violations, %ld groups where the stream form differs from the scalar one\n",
           hits, nisa, viol, disagree);
    return viol == 0 && disagree == 0 && hits > 0;
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
        if (P != c &&
            (cyl->flags & (c == CYLRAY_CAP_LO ? CYLRAY_CAPPED_LO : CYLRAY_CAPPED_HI)) &&
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
    long disagree = 0;
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
        const cylray_kernels *ks = isas[g % nisa];
        uint32_t m = trace_group(ks, &P, c, &ray, &hit);
        if (!m)
            continue;
        /* points and origins from that ISA's stream forms, checked against the scalar
         * pair bit for bit */
        float p[16][3], err[16];
        if (isa_points(ks, &P, &ray, &hit, m, p, err)) {
            disagree++;
            fail("self", &c[0], "the stream form differs from cylray_hit_point");
        }
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
                use |= 1u << i;
            }
            if (isa_origins(ks, &P, &hit, use, (const float(*)[3])p, err, (const float(*)[3])w,
                            x0)) {
                disagree++;
                fail("self", &c[0], "the stream form differs from cylray_spawn_origin");
            }
            const uint32_t spawned = use;
            use = 0;
            for (int i = 0; i < 16; i++) {
                if (!(spawned >> i & 1u))
                    continue;
                const int part = hit.part[i], Pm = part & CYLRAY_PART_MASK;
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
                                 kernel_fault
                                     ? " (an answer outside the kernel's tolerance band)"
                                     : "",
                                 hit.part[i], p[i][0], p[i][1], p[i][2], err[i], x0[i][0],
                                 x0[i][1], x0[i][2], w[i][0], w[i][1], w[i][2], hp[i], t[i]);
                        fail("self", &c[i], s);
                    }
            }
        }
    }
    long bad = wrong_side + exact_self + disagree;
    printf("self: points and origins from each ISA's stream forms in turn; %ld groups where "
           "they differ from the scalar pair\n",
           disagree);
    printf("self: outside the guarantee by category:");
    for (int c = 0; c < SREF_COUNT; c++)
        if (too_big_cat[c])
            printf(" %s %ld", sref_category_name(c), too_big_cat[c]);
    printf("\n");
    for (int k = 0; k < nisa; k++) {
        printf("self: %-7s %10ld spawned rays traced, %ld self-intersections\n", isas[k]->name,
               traced[k], self[k]);
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
            float tq;
            int32_t pq;
            if (sref_trace1(isas[k], &Pi, x0, w, &tq, &pq))
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
           "exact hit on it",
           tried, inside_inner, exact_hits);
    for (int k = 0; k < nisa; k++) {
        printf(", %s missed %ld", isas[k]->name, missed[k]);
        bad += missed[k];
    }
    printf(" (%ld excused: a graze within the tolerance band)\n", excused);
    return bad == 0 && exact_hits > tried / 2;
}

/* ---- batched forms -------------------------------------------------------------- */

/* The batched forms of ISA K (packets 4/8/16, a stream cut at every length, leaves one
 * at a time and in bulk) on the lanes in m, against the scalar pair (p, err, x). */
static long batched_isa(const cylray_kernels *K, const cylray_prepared *P, const cylgen_case *c,
                        const cylray_ray16 *ray, const cylray_hit16 *hit, uint32_t m,
                        const float p[16][3], const float err[16], const float w[16][3],
                        const float x[16][3], uint32_t outward, const float xs[16][3],
                        const cylray_leaf16 *leaf, uint32_t lane, long *lanes)
{
    long diff = 0;
    /* the side forms: packets, a stream, leaves in bulk */
    {
        cylray_points16 q16;
        cylray_points8 q8;
        cylray_points4 q4;
        cylray_ray16 o16 = *ray;
        cylray_ray8 o8;
        cylray_ray4 o4;
        float px[16], py[16], pz[16], pe[16], wx[16], wy[16], wz[16], ox[16], oy[16], oz[16];
        int32_t part[16];
        uint8_t outb[16];
        const cylray_leaf16 *lv[16];
        cylray_hit1 h1[16];
        memset(&o8, 0, sizeof o8), memset(&o4, 0, sizeof o4);
        memset(&q8, 0, sizeof q8), memset(&q4, 0, sizeof q4), memset(&q16, 0, sizeof q16);
        for (int i = 0; i < 16; i++) {
            q16.x[i] = px[i] = p[i][0], q16.y[i] = py[i] = p[i][1], q16.z[i] = pz[i] = p[i][2];
            q16.err[i] = pe[i] = err[i];
            o16.dx[i] = wx[i] = w[i][0], o16.dy[i] = wy[i] = w[i][1],
            o16.dz[i] = wz[i] = w[i][2];
            ox[i] = oy[i] = oz[i] = -3.0f;
            part[i] = m >> i & 1u ? hit->part[i] : CYLRAY_MISS;
            outb[i] = (uint8_t)(outward >> i & 1u);
            lv[i] = leaf;
            cylray_hit1 h = {hit->t[i], {0, 0, 0}, part[i], 0, lane};
            h1[i] = h;
            if (i < 8) {
                q8.x[i] = p[i][0], q8.y[i] = p[i][1], q8.z[i] = p[i][2], q8.err[i] = err[i];
                o8.dx[i] = w[i][0], o8.dy[i] = w[i][1], o8.dz[i] = w[i][2];
            }
            if (i < 4) {
                q4.x[i] = p[i][0], q4.y[i] = p[i][1], q4.z[i] = p[i][2], q4.err[i] = err[i];
                o4.dx[i] = w[i][0], o4.dy[i] = w[i][1], o4.dz[i] = w[i][2];
            }
        }
        K->spawn_rays_side16(P, &q16, hit, m, outward, &o16);
        {
            cylray_hit8 h8;
            cylray_hit4 h4;
            memset(&h8, 0, sizeof h8), memset(&h4, 0, sizeof h4);
            for (int i = 0; i < 8; i++)
                h8.part[i] = hit->part[i];
            for (int i = 0; i < 4; i++)
                h4.part[i] = hit->part[i];
            K->spawn_rays_side8(P, &q8, &h8, m & 0xffu, outward, &o8);
            K->spawn_rays_side4(P, &q4, &h4, m & 0xfu, outward, &o4);
        }
        cylray_points sp = {px, py, pz, pe}, dirs = {wx, wy, wz, NULL};
        cylray_points org = {ox, oy, oz, NULL};
        K->spawn_stream_side(P, &sp, part, outb, &dirs, &org, 16);
        /* leaves in bulk: the hits only, compacted */
        cylray_hit1 hc[16];
        float cx[16], cy[16], cz[16], ce[16], cwx[16], cwy[16], cwz[16];
        uint8_t cb[16];
        int nc = 0;
        for (int i = 0; i < 16; i++)
            if (m >> i & 1u) {
                hc[nc] = h1[i], cb[nc] = outb[i];
                cx[nc] = p[i][0], cy[nc] = p[i][1], cz[nc] = p[i][2], ce[nc] = err[i];
                cwx[nc] = w[i][0], cwy[nc] = w[i][1], cwz[nc] = w[i][2];
                nc++;
            }
        cylray_points lp = {cx, cy, cz, ce}, ld = {cwx, cwy, cwz, NULL};
        K->leaf_spawn_origins_side16(lv, hc, &lp, cb, &ld, &ld, (size_t)nc);
        for (int i = 0, j = 0; i < 16; i++) {
            if (!(m >> i & 1u)) {
                if (ox[i] != -3.0f || oy[i] != -3.0f || oz[i] != -3.0f) {
                    diff++;
                    fail("batched", &c[i], "a side stream wrote a lane it does not own");
                }
                continue;
            }
            const float a[3] = {o16.ox[i], o16.oy[i], o16.oz[i]}, b[3] = {ox[i], oy[i], oz[i]};
            const float l[3] = {cwx[j], cwy[j], cwz[j]};
            j++;
            int bad = !sref_same3(a, xs[i]) || o16.tmin[i] != 0.0f || !sref_same3(b, xs[i]) ||
                      !sref_same3(l, xs[i]);
            if (i < 8) {
                const float a8[3] = {o8.ox[i], o8.oy[i], o8.oz[i]};
                bad |= !sref_same3(a8, xs[i]);
            }
            if (i < 4) {
                const float a4[3] = {o4.ox[i], o4.oy[i], o4.oz[i]};
                bad |= !sref_same3(a4, xs[i]);
            }
            if (bad) {
                diff++;
                char s[96];
                snprintf(s, sizeof s, "%s: a side form differs from cylray_spawn_origin_side",
                         K->name);
                fail("batched", &c[i], s);
            }
        }
    }
    cylray_points16 pts;
    K->hit_points16(P, ray, hit, m, &pts);
    cylray_ray16 out = *ray;
    for (int i = 0; i < 16; i++)
        out.dx[i] = w[i][0], out.dy[i] = w[i][1], out.dz[i] = w[i][2];
    K->spawn_rays16(P, &pts, hit, m, &out);
    cylray_ray8 r8;
    cylray_hit8 h8;
    cylray_points8 p8;
    cylray_ray4 r4;
    cylray_hit4 h4;
    cylray_points4 p4;
    for (int i = 0; i < 8; i++) {
        r8.ox[i] = ray->ox[i], r8.oy[i] = ray->oy[i], r8.oz[i] = ray->oz[i];
        r8.dx[i] = ray->dx[i], r8.dy[i] = ray->dy[i], r8.dz[i] = ray->dz[i];
        h8.t[i] = hit->t[i], h8.part[i] = hit->part[i];
        if (i < 4) {
            r4.ox[i] = ray->ox[i], r4.oy[i] = ray->oy[i], r4.oz[i] = ray->oz[i];
            r4.dx[i] = ray->dx[i], r4.dy[i] = ray->dy[i], r4.dz[i] = ray->dz[i];
            h4.t[i] = hit->t[i], h4.part[i] = hit->part[i];
        }
    }
    K->hit_points8(P, &r8, &h8, m & 0xffu, &p8);
    K->hit_points4(P, &r4, &h4, m & 0xfu, &p4);
    for (int i = 0; i < 8; i++) {
        r8.dx[i] = w[i][0], r8.dy[i] = w[i][1], r8.dz[i] = w[i][2];
        if (i < 4)
            r4.dx[i] = w[i][0], r4.dy[i] = w[i][1], r4.dz[i] = w[i][2];
    }
    K->spawn_rays8(P, &p8, &h8, m & 0xffu, &r8);
    K->spawn_rays4(P, &p4, &h4, m & 0xfu, &r4);
    /* streams of every length 1..16 from lane 16 - len on, so that each length meets
     * full vectors and a tail of every size; what a stream does not cover stays */
    float wx[16], wy[16], wz[16];
    int32_t spart[16];
    for (int i = 0; i < 16; i++) {
        wx[i] = w[i][0], wy[i] = w[i][1], wz[i] = w[i][2];
        spart[i] = m >> i & 1u ? hit->part[i] : CYLRAY_MISS;
    }
    for (int len = 1; len <= 16; len++) {
        const int b = 16 - len;
        float sx[16], sy[16], sz[16], se[16], ox[16], oy[16], oz[16];
        for (int i = 0; i < 16; i++)
            sx[i] = sy[i] = sz[i] = se[i] = ox[i] = oy[i] = oz[i] = -5.0f;
        cylray_rays rs = {
            ray->ox + b, ray->oy + b, ray->oz + b,   ray->dx + b,
            ray->dy + b, ray->dz + b, ray->tmin + b, (float *)(uintptr_t)ray->tmax + b};
        cylray_hits hs = {(float *)(uintptr_t)hit->t + b, NULL, NULL, NULL, spart + b};
        cylray_points sp = {sx + b, sy + b, sz + b, se + b};
        cylray_points dirs = {wx + b, wy + b, wz + b, NULL},
                      org = {ox + b, oy + b, oz + b, NULL};
        size_t ns = K->hit_points_stream(P, &rs, &hs, &sp, (size_t)len);
        K->spawn_stream(P, &sp, spart + b, &dirs, &org, (size_t)len);
        if (ns != (size_t)popcount(m >> b)) {
            diff++;
            fail("batched", &c[0], "the stream's count of points is wrong");
        }
        for (int i = 0; i < 16; i++) {
            const int hitlane = i >= b && (m >> i & 1u);
            const float s1[3] = {sx[i], sy[i], sz[i]}, s2[3] = {ox[i], oy[i], oz[i]};
            const int bad =
                hitlane
                    ? !sref_same3(s1, p[i]) || se[i] != err[i] || !sref_same3(s2, x[i])
                    : sx[i] != -5.0f || sy[i] != -5.0f || sz[i] != -5.0f || se[i] != -5.0f ||
                          ox[i] != -5.0f || oy[i] != -5.0f || oz[i] != -5.0f;
            if (bad) {
                diff++;
                fail("batched", &c[i],
                     hitlane ? "a stream differs from the scalar pair"
                             : "a stream wrote a lane it does not own");
            }
        }
    }
    /* the leaf in bulk: the hits (in lane `lane`) in one call, through the same leaf */
    const cylray_leaf16 *lv[16];
    cylray_ray1 r1[16];
    cylray_hit1 h1[16];
    float lx[16], ly[16], lz[16], le[16], lwx[16], lwy[16], lwz[16];
    size_t nl = 0;
    for (int i = 0; i < 16; i++) {
        if (!(m >> i & 1u))
            continue;
        lv[nl] = leaf;
        cylray_ray1 r = {{c[i].o[0], c[i].o[1], c[i].o[2]},
                         {c[i].d[0], c[i].d[1], c[i].d[2]},
                         c[i].tmin,
                         hit->t[i]};
        cylray_hit1 h = {hit->t[i], {0, 0, 0}, hit->part[i], 7, lane};
        r1[nl] = r, h1[nl] = h;
        lwx[nl] = w[i][0], lwy[nl] = w[i][1], lwz[nl] = w[i][2];
        nl++;
    }
    cylray_points lp = {lx, ly, lz, le}, ldirs = {lwx, lwy, lwz, NULL};
    K->leaf_hit_points16(lv, r1, h1, &lp, nl);
    K->leaf_spawn_origins16(lv, h1, &lp, &ldirs, &ldirs, nl);
    for (int i = 0, j = 0; i < 16; i++) {
        if (!(m >> i & 1u))
            continue;
        (*lanes)++;
        const float a[3] = {pts.x[i], pts.y[i], pts.z[i]};
        const float bb[3] = {out.ox[i], out.oy[i], out.oz[i]};
        int bad = !sref_same3(a, p[i]) || pts.err[i] != err[i] || !sref_same3(bb, x[i]) ||
                  out.tmin[i] != 0.0f;
        if (i < 8) {
            const float a8[3] = {p8.x[i], p8.y[i], p8.z[i]};
            const float b8[3] = {r8.ox[i], r8.oy[i], r8.oz[i]};
            bad |= !sref_same3(a8, p[i]) || p8.err[i] != err[i] || !sref_same3(b8, x[i]);
        }
        if (i < 4) {
            const float a4[3] = {p4.x[i], p4.y[i], p4.z[i]};
            const float b4[3] = {r4.ox[i], r4.oy[i], r4.oz[i]};
            bad |= !sref_same3(a4, p[i]) || p4.err[i] != err[i] || !sref_same3(b4, x[i]);
        }
        const float q[3] = {lx[j], ly[j], lz[j]}, o[3] = {lwx[j], lwy[j], lwz[j]};
        bad |= !sref_same3(q, p[i]) || le[j] != err[i] || !sref_same3(o, x[i]);
        j++;
        if (bad) {
            diff++;
            char s[96];
            snprintf(s, sizeof s, "%s: a batched form differs from the scalar pair", K->name);
            fail("batched", &c[i], s);
        }
    }
    return diff;
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
        uint32_t m = trace_group(isas[g % nisa], &P, c, &ray, &hit);
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
                cylray_spawn_origin_side(&P, p[i], err[i], hit.part[i], outward >> i & 1u, w[i],
                                         xs[i]);
            }
        }
        /* the plain entry points (the path in use): packets of 16, and of 8 and 4 (their
         * lanes are the first ones) */
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
        cylray_points sp = {sx, sy, sz, se}, dirs = {wx, wy, wz, NULL},
                      org = {ox, oy, oz, NULL};
        size_t ns = cylray_hit_points_stream(&P, &rs, &hs, &sp, 16);
        cylray_spawn_stream(&P, &sp, spart, &dirs, &org, 16);
        float qx[16], qy[16], qz[16];
        uint8_t outw[16];
        for (int i = 0; i < 16; i++)
            outw[i] = (uint8_t)(outward >> i & 1u);
        cylray_points org_s = {qx, qy, qz, NULL};
        cylray_spawn_stream_side(&P, &sp, spart, outw, &dirs, &org_s, 16);
        if (ns != (size_t)popcount(m)) {
            diff++;
            fail("batched", &c[0], "cylray_hit_points_stream's count is wrong");
        }
        /* a leaf of 6 with the cylinder in lane 5 behind five others */
        cylray_leaf16 leaf;
        cylray_cylinder six[6];
        const uint32_t lane = 5;
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
        for (int i = 0; i < 16; i++) {
            if (!(m >> i & 1u))
                continue;
            cylray_ray1 r1 = {{c[i].o[0], c[i].o[1], c[i].o[2]},
                              {c[i].d[0], c[i].d[1], c[i].d[2]},
                              c[i].tmin,
                              hit.t[i]};
            cylray_hit1 h1 = {hit.t[i], {0, 0, 0}, hit.part[i], 7, lane};
            float lp[3], le, lx[3];
            cylray_leaf_hit_point16(&leaf, &r1, &h1, lp, &le);
            cylray_leaf_spawn_origin16(&leaf, &h1, lp, le, w[i], lx);
            const float a[3] = {pts.x[i], pts.y[i], pts.z[i]};
            const float b[3] = {out.ox[i], out.oy[i], out.oz[i]};
            const float s1[3] = {sx[i], sy[i], sz[i]}, s2[3] = {ox[i], oy[i], oz[i]};
            int bad = !sref_same3(a, p[i]) || pts.err[i] != err[i] || !sref_same3(b, x[i]) ||
                      out.tmin[i] != 0.0f || !sref_same3(s1, p[i]) || se[i] != err[i] ||
                      !sref_same3(s2, x[i]);
            if (i < 8) {
                const float a8[3] = {p8.x[i], p8.y[i], p8.z[i]};
                const float b8[3] = {r8.ox[i], r8.oy[i], r8.oz[i]};
                bad |= !sref_same3(a8, p[i]) || p8.err[i] != err[i] || !sref_same3(b8, x[i]);
            }
            if (i < 4) {
                const float a4[3] = {p4.x[i], p4.y[i], p4.z[i]};
                const float b4[3] = {r4.ox[i], r4.oy[i], r4.oz[i]};
                bad |= !sref_same3(a4, p[i]) || p4.err[i] != err[i] || !sref_same3(b4, x[i]);
            }
            bad |= !sref_same3(lp, p[i]) || le != err[i] || !sref_same3(lx, x[i]);
            /* the side forms */
            float ls[3];
            cylray_leaf_spawn_origin_side16(&leaf, &h1, lp, le, outward >> i & 1u, w[i], ls);
            const float s16[3] = {out_s.ox[i], out_s.oy[i], out_s.oz[i]};
            const float ss[3] = {qx[i], qy[i], qz[i]};
            bad |= !sref_same3(ls, xs[i]) || !sref_same3(s16, xs[i]) ||
                   !sref_same3(ss, xs[i]) || out_s.tmin[i] != 0.0f;
            if (i < 8) {
                const float s8[3] = {r8s.ox[i], r8s.oy[i], r8s.oz[i]};
                bad |= !sref_same3(s8, xs[i]);
            }
            if (i < 4) {
                const float s4[3] = {r4s.ox[i], r4s.oy[i], r4s.oz[i]};
                bad |= !sref_same3(s4, xs[i]);
            }
            /* the side w lies on, by a clear margin: the side form is the plain one
             * (where floats resolve the cylinder at p: a point far off a tiny radius
             * may lie next to the axis, where the radial direction is noise) */
            double ne[3];
            sref_normal(&c[i].cyl, p[i], hit.part[i] & CYLRAY_PART_MASK, ne);
            const double wn = ne[0] * w[i][0] + ne[1] * w[i][1] + ne[2] * w[i][2];
            if (fabs(wn) > 1e-6 &&
                err[i] < 0x1p-10 * fmin(c[i].cyl.radius, c[i].cyl.half_height)) {
                float xw[3];
                cylray_spawn_origin_side(&P, p[i], err[i], hit.part[i], wn > 0, w[i], xw);
                bad |= !sref_same3(xw, x[i]);
            }
            if (bad) {
                diff++;
                fail("batched", &c[i],
                     "a plain entry point or a leaf's scalar form differs "
                     "from the scalar pair");
            }
        }
        /* every ISA's table, and the plain entry points (the path in use) */
        for (int k = 0; k < nisa; k++)
            diff += batched_isa(isas[k], &P, c, &ray, &hit, m, (const float(*)[3])p, err,
                                (const float(*)[3])w, (const float(*)[3])x, outward,
                                (const float(*)[3])xs, &leaf, lane, &lanes);
        {
            cylray_points16 pts;
            cylray_hit_points16(&P, &ray, &hit, m, &pts);
            for (int i = 0; i < 16; i++) {
                const float a[3] = {pts.x[i], pts.y[i], pts.z[i]};
                if ((m >> i & 1u) && (!sref_same3(a, p[i]) || pts.err[i] != err[i])) {
                    diff++;
                    fail("batched", &c[i], "cylray_hit_points16 differs from the scalar pair");
                }
            }
        }
    }
    /* the normal forms: hits traced with normals, the point at the kernel's azimuth */
    long nlanes = 0;
    for (long g = 0; g < G; g++) {
        cylgen_case c[SREF_GROUP];
        sref_group((int)(g % SREF_COUNT), 19000 + (uint64_t)g, c);
        cylray_prepared P;
        cylray_leaf8 leaf;
        if (cylray_prepare(&P, &c[0].cyl) != CYLRAY_OK ||
            cylray_leaf_prepare8(&leaf, &c[0].cyl, NULL, 1) != CYLRAY_OK)
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
        const cylray_ray16 ray0 = ray;
        const uint32_t m = isas[g % nisa]->intersect16(
            &P, &ray, &hit, 0xffffu, CYLRAY_NORMAL | (g & 1 ? CYLRAY_FACE_FORWARD : 0));
        cylray_points16 p16;
        cylray_points8 p8;
        cylray_points4 p4;
        cylray_ray8 r8;
        cylray_hit8 h8;
        cylray_ray4 r4;
        cylray_hit4 h4;
        memset(&r8, 0, sizeof r8), memset(&h8, 0, sizeof h8);
        memset(&r4, 0, sizeof r4), memset(&h4, 0, sizeof h4);
        for (int i = 0; i < 8; i++) {
            r8.ox[i] = ray.ox[i], r8.oy[i] = ray.oy[i], r8.oz[i] = ray.oz[i];
            r8.dx[i] = ray.dx[i], r8.dy[i] = ray.dy[i], r8.dz[i] = ray.dz[i];
            h8.t[i] = hit.t[i], h8.part[i] = hit.part[i];
            h8.nx[i] = hit.nx[i], h8.ny[i] = hit.ny[i], h8.nz[i] = hit.nz[i];
            if (i < 4) {
                r4.ox[i] = ray.ox[i], r4.oy[i] = ray.oy[i], r4.oz[i] = ray.oz[i];
                r4.dx[i] = ray.dx[i], r4.dy[i] = ray.dy[i], r4.dz[i] = ray.dz[i];
                h4.t[i] = hit.t[i], h4.part[i] = hit.part[i];
                h4.nx[i] = hit.nx[i], h4.ny[i] = hit.ny[i], h4.nz[i] = hit.nz[i];
            }
        }
        cylray_hit_points_normal16(&P, &ray, &hit, m, &p16);
        cylray_hit_points_normal8(&P, &r8, &h8, m & 0xffu, &p8);
        cylray_hit_points_normal4(&P, &r4, &h4, m & 0xfu, &p4);
        float sx[16], sy[16], sz[16], se[16];
        int32_t spart[16];
        for (int i = 0; i < 16; i++)
            spart[i] = m >> i & 1u ? hit.part[i] : CYLRAY_MISS;
        cylray_rays rs = {ray.ox, ray.oy, ray.oz, ray.dx, ray.dy, ray.dz, ray.tmin, ray.tmax};
        cylray_hits hs = {hit.t, hit.nx, hit.ny, hit.nz, spart};
        cylray_points sp = {sx, sy, sz, se};
        if (cylray_hit_points_normal_stream(&P, &rs, &hs, &sp, 16) != (size_t)popcount(m))
            diff++;
        for (int i = 0; i < 16; i++) {
            if (!(m >> i & 1u))
                continue;
            nlanes++;
            const float o[3] = {ray0.ox[i], ray0.oy[i], ray0.oz[i]};
            const float d[3] = {ray0.dx[i], ray0.dy[i], ray0.dz[i]};
            const float n[3] = {hit.nx[i], hit.ny[i], hit.nz[i]};
            float p[3], err, lp[3], le;
            cylray_hit_point_normal(&P, o, d, hit.t[i], hit.part[i], n, p, &err);
            cylray_ray1 r1 = {{o[0], o[1], o[2]}, {d[0], d[1], d[2]}, 0, hit.t[i]};
            cylray_hit1 h1 = {hit.t[i], {n[0], n[1], n[2]}, hit.part[i], 0, 0};
            cylray_leaf_hit_point_normal8(&leaf, &r1, &h1, lp, &le);
            const float a[3] = {p16.x[i], p16.y[i], p16.z[i]}, b[3] = {sx[i], sy[i], sz[i]};
            int bad = !sref_same3(a, p) || p16.err[i] != err || !sref_same3(b, p) ||
                      se[i] != err || !sref_same3(lp, p) || le != err;
            if (i < 8) {
                const float a8[3] = {p8.x[i], p8.y[i], p8.z[i]};
                bad |= !sref_same3(a8, p) || p8.err[i] != err;
            }
            if (i < 4) {
                const float a4[3] = {p4.x[i], p4.y[i], p4.z[i]};
                bad |= !sref_same3(a4, p) || p4.err[i] != err;
            }
            /* the bound holds for this point too */
            bad |= !(sref_dist_part(&c[i].cyl, p, hit.part[i]) <= err);
            /* every ISA's normal forms: packets of 16, a stream, leaves in bulk */
            for (int k = 0; k < nisa; k++) {
                const cylray_kernels *K = isas[k];
                cylray_points16 q;
                float qx[16], qy[16], qz[16], qe[16];
                cylray_points qs = {qx, qy, qz, qe};
                const cylray_leaf8 *lv[1] = {&leaf};
                K->hit_points_normal16(&P, &ray, &hit, 1u << i, &q);
                K->hit_points_normal_stream(&P, &rs, &hs, &qs, 16);
                const float a16[3] = {q.x[i], q.y[i], q.z[i]}, as[3] = {qx[i], qy[i], qz[i]};
                float bx, by, bz, be;
                cylray_points qb = {&bx, &by, &bz, &be};
                K->leaf_hit_points_normal8(lv, &r1, &h1, &qb, 1);
                const float ab[3] = {bx, by, bz};
                bad |= !sref_same3(a16, p) || q.err[i] != err || !sref_same3(as, p) ||
                       qe[i] != err || !sref_same3(ab, p) || be != err;
            }
            if (bad) {
                diff++;
                fail("batched", &c[i],
                     "a normal form differs from the scalar one, or its bound");
            }
        }
    }
    printf("batched: %ld lanes of the normal forms compared (and their bounds)\n", nlanes);
    printf("batched: %ld lanes compared over %d ISAs (packets 4/8/16, streams of every "
           "length, leaves one by one and in bulk; plain, side and normal forms), %ld "
           "differ\n",
           lanes, nisa, diff);
    return diff == 0 && lanes > 0;
}

/* Rays down the axis onto a disc's center (a point where the radial direction is
 * undefined): the hit point stays at the center, within its bound of the cap's plane,
 * and the reflected ray's origin stays near the axis on the ray's side. */
static int run_axis(void)
{
    static const float axes[][3] = {
        {0, 0, 1}, {0, -3, 0}, {1, 0, 0}, {0.3f, -0.5f, 0.8f}, {-1e-3f, 2e-3f, 5e-4f}};
    static const float centers[][3] = {{0, 0, 0}, {1.5f, -2, 7}, {1e4f, -3e4f, 2e3f}};
    static const float radii[] = {1e-2f, 1, 250};
    long bad = 0, n = 0;
    for (size_t ai = 0; ai < sizeof axes / sizeof axes[0]; ai++)
        for (size_t ci = 0; ci < sizeof centers / sizeof centers[0]; ci++)
            for (size_t ri = 0; ri < sizeof radii / sizeof radii[0]; ri++)
                for (int end = 0; end < 2; end++) {
                    const float *a = axes[ai], *c0 = centers[ci];
                    const float R = radii[ri], H = 2 * R;
                    cylray_cylinder cyl = {
                        {c0[0], c0[1], c0[2]}, {a[0], a[1], a[2]}, R, H, CYLRAY_CAPPED};
                    cylray_prepared P;
                    if (cylray_prepare(&P, &cyl) != CYLRAY_OK)
                        continue;
                    /* floats must resolve the disc there (the guarantee's condition) */
                    const double cmax = fmax(fabs(c0[0]), fmax(fabs(c0[1]), fabs(c0[2])));
                    if (256 * cmax * 0x1p-24 > R)
                        continue;
                    const double al =
                        sqrt((double)a[0] * a[0] + (double)a[1] * a[1] + (double)a[2] * a[2]);
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

/* A hit of the part left at t is premature when the exact ray from x0 never meets the
 * cylinder, or meets it first at t_e with t < t_e / 2: the promise is about the
 * distance, so the exact ray runs on past the caller's tmax (a grazing exit at 1.006
 * that a kernel, within its tolerance, reports at 0.9998 < tmax = 1 keeps it). */
static int premature(const cylray_cylinder *cyl, const float x0[3], const float w[3], int left,
                     int hit_part, float t)
{
    if ((hit_part & CYLRAY_PART_MASK) != (left & CYLRAY_PART_MASK))
        return 0;
    cylref_hit eh;
    if (cylref_intersect(cyl, x0, w, 0.0f, INFINITY, 0, &eh) != 1)
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
                if ((got >> i & 1u) && premature(cyl, x0, w, part, hp[i], th[i])) {
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
                premature(cyl, x0, w, part, h1.part, h1.t)) {
                bad++;
                snprintf(s, sizeof s, "%s leaf: hit part %d at t %a", isas[k]->name,
                         (int)h1.part, h1.t);
                fail("side: self-hit", c, s);
            }
        }
    }
    return bad;
}

/* Fixed cases, the primary hit taken on every ISA, by packet, leaf and stream:
 * - two far rods: shadow rays whose kernel normal gives cos +0.0012 and whose exact
 *   normal at the rounded point -0.0007;
 * - a transmitted ray grazing the inside of a wide tube (cos -7.7e-7 to the exact
 *   normal), whose exact exit at t = 1.006 a kernel may report, within its tolerance,
 *   at 0.9998 (an AMD CPU's SSE4.1 shift did);
 * - a reflected ray sent outward whose w dips 0.0018 rad back into the side: from the
 *   plain clearance its line passed 5e-8 outside the tube, and every kernel took it for
 *   a hit (the spawn now clears such a tangency). */
static long side_fixed(long *spawned, long *too_big)
{
    static const struct {
        float c[3], a[3], R, H, o[3], d[3], w[3];
        unsigned flags;
    } rods[] = {
        {{0x1.3875fp+13f, 0x1.3889cp+13f, 0x1.387cfap+13f},
         {0x1.84198p+7f, 0x1.d021cp+9f, -0x1.3d4ap+8f},
         0x1.99999ap-5f,
         0x1.f40012p+8f,
         {0x1.3892eap+13f, 0x1.38a57cp+13f, 0x1.38a7d6p+13f},
         {-0x1.00ae34p-1f, -0x1.1a93f2p-1f, -0x1.552ffap-1f},
         {0x1.165p+3f, -0x1.9cp-1f, 0x1.5d28p+3f},
         CYLRAY_CAPPED},
        {{0x1.38834p+13f, 0x1.3883c4p+13f, 0x1.38798cp+13f},
         {0x1.e58b2p+9f, 0x1.6767p+6f, -0x1.ba588p+7f},
         0x1.99999ap-5f,
         0x1.f40006p+8f,
         {0x1.3892eap+13f, 0x1.38a57cp+13f, 0x1.38a7d6p+13f},
         {-0x1.0ffb68p-1f, -0x1.15e316p-1f, -0x1.4d16e4p-1f},
         {0x1.257p+3f, -0x1.3f8p-1f, 0x1.62e8p+3f},
         CYLRAY_CAPPED},
        {{-0x1.b4720cp+9f, 0x1.2e6726p+10f, 0x1.2d32d2p+8f},
         {-0x1.0d4002p-2f, 0x1.5db1aap-1f, 0x1.5ce78p-1f},
         0x1.76525ap+8f,
         0x1.1ecdcp+9f,
         {0x1.8ec392p+10f, 0x1.eb1586p+10f, -0x1.ac9a1cp+12f},
         {-0x1.70cdd8p-2f, -0x1.7ededp-4f, 0x1.db3c76p-1f},
         {0x1.2658e6p-1f, 0x1.a0d028p-1f, 0x1.509eecp-4f},
         CYLRAY_CAPPED_LO},
        {{-0x1.943bp+2f, 0x1.61ed98p+1f, -0x1.3caa96p+2f},
         {0x1.a8e0dap-5f, 0x1.050cc8p-2f, 0x1.4aa2cp+0f},
         0x1.974be6p+0f,
         0x1.420c16p+2f,
         {-0x1.2fb0fp+14f, 0x1.224dd4p+18f, -0x1.7ccb7cp+12f},
         {0x1.0b156ep-4f, -0x1.fecda4p-1f, 0x1.4ebb5p-6f},
         {-0x1.5cc75cp-1f, -0x1.750d4ap-2f, 0x1.45202p-1f},
         CYLRAY_CAPPED},
    };
    const int nrods = (int)(sizeof rods / sizeof rods[0]);
    long bad = 0;
    for (int r = 0; r < nrods; r++) {
        cylgen_case c;
        memset(&c, 0, sizeof c);
        for (int k = 0; k < 3; k++) {
            c.cyl.center[k] = rods[r].c[k], c.cyl.axis[k] = rods[r].a[k];
            c.o[k] = rods[r].o[k], c.d[k] = rods[r].d[k];
        }
        c.cyl.radius = rods[r].R, c.cyl.half_height = rods[r].H, c.cyl.flags = rods[r].flags;
        c.tmin = 0, c.tmax = INFINITY;
        cylray_prepared P;
        cylray_leaf8 leaf;
        if (cylray_prepare(&P, &c.cyl) != CYLRAY_OK ||
            cylray_leaf_prepare8(&leaf, &c.cyl, NULL, 1) != CYLRAY_OK) {
            fail("side: fixed cases", &c, "refused");
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
                    got =
                        isas[k]->intersect8(&P, &ray, &hit, 1u << (k % 8), CYLRAY_NORMAL) != 0;
                    const int i = k % 8;
                    t = hit.t[i], part = hit.part[i];
                    n[0] = hit.nx[i], n[1] = hit.ny[i], n[2] = hit.nz[i];
                } else if (form == 1) {
                    cylray_ray1 r1 = {
                        {c.o[0], c.o[1], c.o[2]}, {c.d[0], c.d[1], c.d[2]}, 0, INFINITY};
                    cylray_hit1 h1;
                    got = isas[k]->leaf_intersect8(&leaf, &r1, &h1, CYLRAY_NORMAL);
                    t = h1.t, part = h1.part;
                    memcpy(n, h1.n, sizeof n);
                } else {
                    float tmax = INFINITY, tmin = 0, ht = 0, nx = 0, ny = 0, nz = 0;
                    int32_t hpart = 0;
                    cylray_rays rs = {&c.o[0], &c.o[1], &c.o[2], &c.d[0],
                                      &c.d[1], &c.d[2], &tmin,   &tmax};
                    cylray_hits hs = {&ht, &nx, &ny, &nz, &hpart};
                    got = isas[k]->intersect_stream(&P, &rs, &hs, 1, CYLRAY_NORMAL) == 1;
                    t = ht, part = hpart, n[0] = nx, n[1] = ny, n[2] = nz;
                }
                if (!got || part != CYLRAY_SIDE) {
                    bad++;
                    fail("side: fixed cases", &c, "the primary ray does not hit the side");
                    continue;
                }
                long sp = *spawned, tb = *too_big;
                bad += side_case(&c, &P, t, part, n, rods[r].w, 1.0f, spawned, too_big);
                bad += side_case(&c, &P, t, part, n, rods[r].w, INFINITY, spawned, too_big);
                if (*too_big != tb || *spawned != sp + 2) {
                    bad++;
                    fail("side: fixed cases", &c, "outside the guarantee's condition");
                }
            }
    }
    return bad;
}

static int run_side(void)
{
    long spawned = 0, too_big = 0, bad = side_fixed(&spawned, &too_big);
    const long far_spawned = spawned, far_bad = bad;
    printf("side: fixed cases: %ld spawns (4 cases x %d ISAs x packet, leaf, stream x tmax 1, "
           "inf), %ld failures\n",
           far_spawned, nisa, far_bad);
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
            const double wl =
                sqrt((double)w[0] * w[0] + (double)w[1] * w[1] + (double)w[2] * w[2]);
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

/* ---- pbrt-v4's Reintersect ------------------------------------------------------ */

/* 10^u, u uniform in [-e, e] (pbrt's pExp). */
static double pexp(cylgen_rng *r, double e)
{
    return pow(10.0, (2 * cylgen_uniform(r) - 1) * e);
}

/* Traces 16 rays (x0, w) on ISA k at width 4 << (which % 3) and returns the mask of
 * those with any hit in [0, inf). */
static uint32_t occluded16(const cylray_kernels *k, int which, const cylray_prepared *P,
                           const float x0[16][3], const float w[16][3])
{
    const float tmax[16] = {INFINITY, INFINITY, INFINITY, INFINITY, INFINITY, INFINITY,
                            INFINITY, INFINITY, INFINITY, INFINITY, INFINITY, INFINITY,
                            INFINITY, INFINITY, INFINITY, INFINITY};
    float t[16];
    int32_t part[16];
    return trace16(k, 4 << (which % 3), P, x0, w, tmax, 0xffffu, t, part);
}

/* One tube of pbrt's test on one ISA: the primary hit with its normal, then `rays`
 * spawned rays, face-forwarded to the kernel's normal, in two ways: the README's (the
 * point at the kernel's azimuth, the side form, outward) and the plain pair (the point
 * from o + t d, the side from w). Adds the re-hits of each. */
static void reintersect_one(const cylray_kernels *k, const cylray_cylinder *cyl,
                            const float o[3], const float d[3], int rays, cylgen_rng *rng,
                            long *hits, long *spawned, long *rehit_readme, long *rehit_plain,
                            long *big, long *rehit_big)
{
    cylray_prepared P;
    if (cylray_prepare(&P, cyl) != CYLRAY_OK)
        return;
    cylray_ray4 r;
    cylray_hit4 h;
    memset(&r, 0, sizeof r);
    r.ox[0] = o[0], r.oy[0] = o[1], r.oz[0] = o[2];
    r.dx[0] = d[0], r.dy[0] = d[1], r.dz[0] = d[2];
    r.tmax[0] = INFINITY;
    if (!(k->intersect4(&P, &r, &h, 1u, CYLRAY_NORMAL) & 1u))
        return;
    ++*hits;
    const float n[3] = {h.nx[0], h.ny[0], h.nz[0]};
    float pn[3], en, pp[3], ep;
    cylray_hit_point_normal(&P, o, d, h.t[0], h.part[0], n, pn, &en);
    cylray_hit_point(&P, o, d, h.t[0], h.part[0], pp, &ep);
    const double lim = 0.25 * fmin(cyl->radius, cyl->half_height);
    for (int j = 0; j < rays; j += 16) {
        float xa[16][3], xb[16][3], w[16][3];
        int far_a[16];
        for (int i = 0; i < 16; i++) {
            double u[3];
            sref_unit(rng, u);
            const double un = u[0] * n[0] + u[1] * n[1] + u[2] * n[2];
            for (int c = 0; c < 3; c++)
                w[i][c] = (float)(un < 0 ? -u[c] : u[c]);
            cylray_spawn_origin_side(&P, pn, en, h.part[0], 1, w[i], xa[i]);
            cylray_spawn_origin(&P, pp, ep, h.part[0], w[i], xb[i]);
            double mv = 0;
            for (int c = 0; c < 3; c++)
                mv += ((double)xa[i][c] - pn[c]) * ((double)xa[i][c] - pn[c]);
            far_a[i] = !(sqrt(mv) <= lim);
            *big += far_a[i];
        }
        *spawned += 16;
        const uint32_t ma =
            occluded16(k, j / 16, &P, (const float(*)[3])xa, (const float(*)[3])w);
        const uint32_t mb =
            occluded16(k, j / 16, &P, (const float(*)[3])xb, (const float(*)[3])w);
        for (int i = 0; i < 16; i++) {
            if (ma >> i & 1u) {
                ++*rehit_readme;
                *rehit_big += far_a[i];
                if (*rehit_readme <= 5) {
                    char s[400];
                    snprintf(s, sizeof s,
                             "%s: hit t %a part %d n (%a %a %a), p (%a %a %a) err %a, "
                             "origin (%a %a %a) w (%a %a %a)%s",
                             k->name, h.t[0], h.part[0], n[0], n[1], n[2], pn[0], pn[1], pn[2],
                             en, xa[i][0], xa[i][1], xa[i][2], w[i][0], w[i][1], w[i][2],
                             far_a[i] ? " (outside the guarantee's condition)" : "");
                    cylgen_case c;
                    memset(&c, 0, sizeof c);
                    c.cyl = *cyl;
                    memcpy(c.o, o, sizeof c.o);
                    memcpy(c.d, d, sizeof c.d);
                    fail("reintersect", &c, s);
                }
            }
            *rehit_plain += mb >> i & 1u;
        }
    }
}

static int run_reintersect(void)
{
    const int ncyl = quick ? 100 : 1000, rays = quick ? 160 : 1008;
    long hits[CYLRAY_ISA_COUNT] = {0}, spawned[CYLRAY_ISA_COUNT] = {0};
    long readme[CYLRAY_ISA_COUNT] = {0}, plain[CYLRAY_ISA_COUNT] = {0};
    long big[CYLRAY_ISA_COUNT] = {0}, readme_big[CYLRAY_ISA_COUNT] = {0};
    long refused = 0;
    for (int i = 0; i < ncyl; i++) {
        cylgen_rng rng;
        cylgen_seed(&rng, 0x5eed0000u + (uint64_t)i);
        /* pbrt's tube: radius, zmin, zmax (pExp(4), random signs), then a random
         * rotation, uniform scale and translation (pExp(8)) */
        const double R = pexp(&rng, 4);
        double z0 = pexp(&rng, 4) * (cylgen_uniform(&rng) < 0.5 ? -1 : 1);
        double z1 = pexp(&rng, 4) * (cylgen_uniform(&rng) < 0.5 ? -1 : 1);
        if (z0 > z1) {
            const double t = z0;
            z0 = z1, z1 = t;
        }
        double axis[3], tr[3];
        sref_unit(&rng, axis);
        const double scale = pexp(&rng, 8);
        for (int k = 0; k < 3; k++)
            tr[k] = pexp(&rng, 8) * (cylgen_uniform(&rng) < 0.5 ? -1 : 1);
        cylray_cylinder cyl;
        memset(&cyl, 0, sizeof cyl);
        for (int k = 0; k < 3; k++) {
            cyl.axis[k] = (float)axis[k];
            cyl.center[k] = (float)(tr[k] + scale * 0.5 * (z0 + z1) * axis[k]);
        }
        cyl.radius = (float)(scale * R);
        cyl.half_height = (float)(scale * 0.5 * (z1 - z0));
        cyl.flags = 0; /* pbrt's cylinder is a tube */
        cylray_prepared P;
        if (cylray_prepare(&P, &cyl) != CYLRAY_OK || !(cyl.half_height > 0)) {
            refused++;
            continue;
        }
        /* the ray: from pExp(8) in each coordinate toward a random point of the
         * tube's bounding box, its direction normalised half the time */
        float o[3], d[3];
        double dd[3], dl = 0;
        const double al =
            sqrt((double)cyl.axis[0] * cyl.axis[0] + (double)cyl.axis[1] * cyl.axis[1] +
                 (double)cyl.axis[2] * cyl.axis[2]);
        for (int k = 0; k < 3; k++) {
            o[k] = (float)pexp(&rng, 8);
            const double ak = cyl.axis[k] / al;
            const double ext =
                fabs(ak) * cyl.half_height + cyl.radius * sqrt(fmax(0, 1 - ak * ak));
            const double tgt = cyl.center[k] + (2 * cylgen_uniform(&rng) - 1) * ext;
            dd[k] = tgt - o[k];
            dl += dd[k] * dd[k];
        }
        const int normalise = cylgen_uniform(&rng) < 0.5;
        for (int k = 0; k < 3; k++)
            d[k] = (float)(normalise ? dd[k] / sqrt(dl) : dd[k]);
        for (int k = 0; k < nisa; k++) {
            cylgen_rng r2 = rng; /* the same spawned directions on every ISA */
            reintersect_one(isas[k], &cyl, o, d, rays, &r2, &hits[k], &spawned[k], &readme[k],
                            &plain[k], &big[k], &readme_big[k]);
        }
    }
    long bad = 0;
    for (int k = 0; k < nisa; k++) {
        printf("reintersect: %-7s %5ld hits of %d tubes (%ld refused), %8ld spawned rays: "
               "%ld re-hits following the README (%ld of them outside the guarantee's "
               "condition, which %ld spawns were), %ld with the point from o + t d and the "
               "side from w\n",
               isas[k]->name, hits[k], ncyl, refused, spawned[k], readme[k], readme_big[k],
               big[k], plain[k]);
        bad += readme[k];
    }
    return bad == 0 && hits[0] > ncyl / 10;
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
    else if (strcmp(mode, "reintersect") == 0)
        ok = run_reintersect();
    else if (strcmp(mode, "round") == 0)
        ok = run_round();
    else {
        fprintf(stderr,
                "usage: spawn_test bounds|self|nested|batched|axis|side|reintersect|round\n");
        return 2;
    }
    printf("%s: %s\n", mode, ok ? "ok" : "FAILED");
    return ok ? 0 : 1;
}
