/* SPDX-License-Identifier: MIT */
/* leafcheck.c - leaves against the exact reference: every ISA x leaf size (4, 8, 16) x
 * all 32 flag sets, on leaves whose lanes draw their cylinder from every stress
 * category (so kinds, axes, radii and distances mix in one leaf), with padding lanes,
 * random ids, and one ray aimed at one of the lanes. For each call:
 *   - a miss only where every lane may miss (its exact band allows it);
 *   - a hit: the lane's answer allowed by its band, t within the tolerance of it, no
 *     lane that surely hits earlier (beyond the tolerance), the right id and lane
 *     unless two lanes' exact hits lie within the tolerance of each other; ray->tmax
 *     = t; the normal within the angle tolerance; nothing written without a hit, no
 *     normal without CYLRAY_NORMAL, nothing around *hit and *ray touched;
 *   - occluded agrees with intersect;
 *   - a leaf with a bad cylinder (or too many) is refused and left untouched; a ray
 *     with a NaN or infinite field misses.
 * Then the same for leaves of spheres (tests/ref/sphgen.h categories) and of cones
 * (tests/ref/congen.h, some lanes cylinders given as cones with r0 == r1), some holding
 * one shape in two lanes: of those equal hits the lower lane must win.
 * Usage: leafcheck [--isa=NAME] [--quick] [--seed=S]. Exit 0 ok, 1 failures, 77 no
 * such ISA here. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "conref.h"
#include "congen.h"
#include "cylray.h"
#include "cylref.h"
#include "gen.h"
#include "sphgen.h"
#include "sphref.h"
#include "tcheck.h"

#define TOL_ULPS 4.0
#define TOL_ULPS_FAST 8.0
#define TOL_ANGLE 1e-6
#define POISON 0x7fa5c3e1u

/* Calls where one sphere sits in two lanes and the ray hits it: the ties judged. */
static long ties_seen;

typedef struct lane_ref {
    cylray_cylinder cyl;
    cylray_sphere sph;   /* the lane's shape in a leaf of spheres */
    cylray_cone con;     /* the lane's shape in a leaf of cones */
    cylref_band band[2]; /* without, with CYLRAY_CULL_BACK */
} lane_ref;

typedef struct leaf_case {
    int n, m;
    int spheres; /* a leaf of spheres */
    int cones;   /* a leaf of cones */
    lane_ref lane[16];
    uint32_t id[16];
    float o[3], d[3], tmin, tmax;
} leaf_case;

static float fbits(uint32_t u)
{
    float f;
    memcpy(&f, &u, 4);
    return f;
}

/* Lanes from random categories; the ray is the one made for a random lane. */
static void make_leaf(leaf_case *lc, int m, cylgen_rng *r, uint64_t seed)
{
    memset(lc, 0, sizeof *lc);
    lc->m = m;
    uint64_t u = cylgen_next(r);
    lc->n = (u & 3) == 0 ? (int)((u >> 8) % (unsigned)(m + 1)) : m;
    if (lc->n == 0)
        lc->n = 1;
    const int aim = (int)((u >> 16) % (unsigned)lc->n);
    for (int k = 0; k < lc->n; k++) {
        int cat = (int)(cylgen_next(r) % CYLGEN_COUNT);
        cylgen_case c;
        cylgen_make(cat, seed + cylgen_next(r), 1, &c);
        lc->lane[k].cyl = c.cyl;
        lc->id[k] = (uint32_t)cylgen_next(r);
        if (k == aim) {
            memcpy(lc->o, c.o, sizeof c.o);
            memcpy(lc->d, c.d, sizeof c.d);
            lc->tmin = c.tmin;
            lc->tmax = c.tmax;
        }
    }
    for (int k = 0; k < lc->n; k++)
        for (int cull = 0; cull < 2; cull++)
            cylref_band_eval(&lc->lane[k].cyl, lc->o, lc->d, lc->tmin, lc->tmax,
                             cull ? CYLRAY_CULL_BACK : 0u, &lc->lane[k].band[cull]);
}

/* A leaf of spheres from random sphere categories; about one leaf in three repeats
 * one lane's sphere in a later lane, so that two lanes hit at exactly the same t. */
static void make_sphere_leaf(leaf_case *lc, int m, cylgen_rng *r, uint64_t seed)
{
    memset(lc, 0, sizeof *lc);
    lc->m = m;
    lc->spheres = 1;
    uint64_t u = cylgen_next(r);
    lc->n = (u & 3) == 0 ? (int)((u >> 8) % (unsigned)(m + 1)) : m;
    if (lc->n == 0)
        lc->n = 1;
    const int aim = (int)((u >> 16) % (unsigned)lc->n);
    for (int k = 0; k < lc->n; k++) {
        /* sph-bad's rays would make every lane miss: its spheres are ordinary ones. */
        int cat = (int)(cylgen_next(r) % (SPHGEN_COUNT - 1));
        sphgen_case c;
        sphgen_make(cat, seed + cylgen_next(r), 1, &c);
        lc->lane[k].sph = c.sph;
        lc->id[k] = (uint32_t)cylgen_next(r);
        if (k == aim) {
            memcpy(lc->o, c.o, sizeof c.o);
            memcpy(lc->d, c.d, sizeof c.d);
            lc->tmin = c.tmin;
            lc->tmax = c.tmax;
        }
    }
    /* The copy is of the lane the ray was made for, which it most likely hits, into a
     * lane below or above it. */
    if (lc->n > 1 && (u >> 24) % 3 == 0) {
        int to = (int)((u >> 40) % (unsigned)(lc->n - 1));
        lc->lane[to >= aim ? to + 1 : to].sph = lc->lane[aim].sph;
    }
    for (int k = 0; k < lc->n; k++)
        for (int cull = 0; cull < 2; cull++)
            sphref_band_eval(&lc->lane[k].sph, lc->o, lc->d, lc->tmin, lc->tmax,
                             cull ? CYLRAY_CULL_BACK : 0u, &lc->lane[k].band[cull]);
}

/* A leaf of cones from random cone categories, about one lane in four a cylinder (r1
 * set to r0), and as for spheres about one leaf in three repeating the aimed lane. */
static void make_cone_leaf(leaf_case *lc, int m, cylgen_rng *r, uint64_t seed)
{
    memset(lc, 0, sizeof *lc);
    lc->m = m;
    lc->cones = 1;
    uint64_t u = cylgen_next(r);
    lc->n = (u & 3) == 0 ? (int)((u >> 8) % (unsigned)(m + 1)) : m;
    if (lc->n == 0)
        lc->n = 1;
    const int aim = (int)((u >> 16) % (unsigned)lc->n);
    for (int k = 0; k < lc->n; k++) {
        /* Every category before cone-bad, whose rays would make every lane miss, and the
         * tiny ends. */
        int cat = (int)(cylgen_next(r) % (CONGEN_BAD + 1));
        cat = cat == CONGEN_BAD ? CONGEN_TINYEND : cat;
        congen_case c;
        congen_make(cat, seed + cylgen_next(r), 1, &c);
        if (cylgen_next(r) % 4 == 0 && c.cone.r0 > 0)
            c.cone.r1 = c.cone.r0;
        lc->lane[k].con = c.cone;
        lc->id[k] = (uint32_t)cylgen_next(r);
        if (k == aim) {
            memcpy(lc->o, c.o, sizeof c.o);
            memcpy(lc->d, c.d, sizeof c.d);
            lc->tmin = c.tmin;
            lc->tmax = c.tmax;
        }
    }
    if (lc->n > 1 && (u >> 24) % 3 == 0) {
        int to = (int)((u >> 40) % (unsigned)(lc->n - 1));
        lc->lane[to >= aim ? to + 1 : to].con = lc->lane[aim].con;
    }
    for (int k = 0; k < lc->n; k++)
        for (int cull = 0; cull < 2; cull++)
            conref_band_eval(&lc->lane[k].con, lc->o, lc->d, lc->tmin, lc->tmax,
                             cull ? CYLRAY_CULL_BACK : 0u, &lc->lane[k].band[cull]);
}

/* Lanes j and L hold the same shape (spheres and cones only). */
static int same_shape(const leaf_case *lc, int j, int L)
{
    if (lc->spheres)
        return memcmp(&lc->lane[j].sph, &lc->lane[L].sph, sizeof lc->lane[L].sph) == 0;
    if (lc->cones)
        return memcmp(&lc->lane[j].con, &lc->lane[L].con, sizeof lc->lane[L].con) == 0;
    return 0;
}

/* The latest t at which lane k surely hits, or INFINITY where it may miss. */
static double sure_hit_by(const cylref_band *b)
{
    if (!b->exact.hit || b->hit_unstable)
        return INFINITY;
    double hi = b->t_hi;
    for (int a = 0; a < b->n_alt; a++)
        hi = fmax(hi, b->alt[a].t_hi);
    return hi;
}

static void print_leaf(const leaf_case *lc)
{
    fprintf(stderr, "    ray o (%a, %a, %a) d (%a, %a, %a) t [%a, %a]\n", (double)lc->o[0],
            (double)lc->o[1], (double)lc->o[2], (double)lc->d[0], (double)lc->d[1],
            (double)lc->d[2], (double)lc->tmin, (double)lc->tmax);
    for (int k = 0; k < lc->n; k++) {
        const cylray_cylinder *c = &lc->lane[k].cyl;
        const cylray_sphere *s = &lc->lane[k].sph;
        const cylref_hit *e = &lc->lane[k].band[0].exact;
        if (lc->cones) {
            const cylray_cone *q = &lc->lane[k].con;
            fprintf(stderr,
                    "    lane %d: cone p0 (%a, %a, %a) p1 (%a, %a, %a) r0 %a r1 %a flags %u: "
                    "exact %s t %.9g part %d\n",
                    k, (double)q->p0[0], (double)q->p0[1], (double)q->p0[2], (double)q->p1[0],
                    (double)q->p1[1], (double)q->p1[2], (double)q->r0, (double)q->r1, q->flags,
                    e->hit ? "hit" : "miss", e->t, e->part);
            continue;
        }
        if (lc->spheres) {
            fprintf(stderr,
                    "    lane %d: sphere c (%a, %a, %a) R %a: exact %s t %.9g part %d\n", k,
                    (double)s->center[0], (double)s->center[1], (double)s->center[2],
                    (double)s->radius, e->hit ? "hit" : "miss", e->t, e->part);
            continue;
        }
        fprintf(stderr,
                "    lane %d: c (%a, %a, %a) v (%a, %a, %a) R %a H %a flags %u: exact %s t "
                "%.9g part %d\n",
                k, (double)c->center[0], (double)c->center[1], (double)c->center[2],
                (double)c->axis[0], (double)c->axis[1], (double)c->axis[2], (double)c->radius,
                (double)c->half_height, c->flags, e->hit ? "hit" : "miss", e->t, e->part);
    }
}

/* One call of intersect and occluded on the leaf held in `leaf` (of lc->m lanes). */
static void judge(const cylray_kernels *k, const leaf_case *lc, const void *leaf,
                  unsigned flags)
{
    const int cull = (flags & CYLRAY_CULL_BACK) != 0, normal = (flags & CYLRAY_NORMAL) != 0;
    const double tol = (flags & CYLRAY_FAST) ? TOL_ULPS_FAST : TOL_ULPS;
    struct {
        cylray_ray1 ray;
        uint32_t guard_r[4];
        cylray_hit1 hit;
        uint32_t guard_h[4];
    } io;
    for (size_t q = 0; q < sizeof io / 4; q++)
        memcpy((char *)&io + 4 * q, &(uint32_t){POISON}, 4);
    memcpy(io.ray.o, lc->o, sizeof lc->o);
    memcpy(io.ray.d, lc->d, sizeof lc->d);
    io.ray.tmin = lc->tmin, io.ray.tmax = lc->tmax;
    const cylray_ray1 before = io.ray;
    int got, occ;
    switch (lc->m) {
    case 4:
        got = k->leaf_intersect4(leaf, &io.ray, &io.hit, flags);
        occ = k->leaf_occluded4(leaf, &before, flags);
        break;
    case 8:
        got = k->leaf_intersect8(leaf, &io.ray, &io.hit, flags);
        occ = k->leaf_occluded8(leaf, &before, flags);
        break;
    default:
        got = k->leaf_intersect16(leaf, &io.ray, &io.hit, flags);
        occ = k->leaf_occluded16(leaf, &before, flags);
        break;
    }
    const long f0 = tc_failures_;
    CHECK(occ == got, "%s leaf%d flags %#x: occluded %d, intersect %d", k->name, lc->m, flags,
          occ, got);
    for (int q = 0; q < 4; q++)
        CHECK(io.guard_r[q] == POISON && io.guard_h[q] == POISON,
              "%s leaf%d: memory beside the ray or hit written", k->name, lc->m);
    CHECK(memcmp(io.ray.o, before.o, sizeof before.o) == 0 &&
              memcmp(io.ray.d, before.d, sizeof before.d) == 0 &&
              memcmp(&io.ray.tmin, &before.tmin, 4) == 0,
          "%s leaf%d: ray input written", k->name, lc->m);
    if (!got) {
        const cylray_hit1 *h = &io.hit;
        uint32_t w[7];
        memcpy(w, h, sizeof w);
        int untouched = memcmp(&io.ray.tmax, &before.tmax, 4) == 0;
        for (int q = 0; q < 7; q++)
            untouched &= w[q] == POISON;
        CHECK(untouched, "%s leaf%d flags %#x: a miss wrote the hit or tmax", k->name, lc->m,
              flags);
        for (int j = 0; j < lc->n; j++) {
            double ub;
            CHECK(cylref_judge(&lc->lane[j].band[cull], 0, 0, 0, &ub) == 0,
                  "%s leaf%d flags %#x: miss, but lane %d surely hits at %.9g", k->name, lc->m,
                  flags, j, lc->lane[j].band[cull].exact.t);
        }
    } else {
        const cylray_hit1 *h = &io.hit;
        const int L = (int)h->lane;
        CHECK(L >= 0 && L < lc->n, "%s leaf%d flags %#x: hit on lane %d of %d", k->name, lc->m,
              flags, L, lc->n);
        if (L >= 0 && L < lc->n) {
            const cylref_band *b = &lc->lane[L].band[cull];
            double ub = 0;
            int verdict = cylref_judge(b, 1, h->part, h->t, &ub);
            CHECK(
                verdict == 0 && ub <= tol,
                "%s leaf%d flags %#x: lane %d t %a part %d: %s (exact %s t %.9g part %d, %.2f "
                "ulps beyond)",
                k->name, lc->m, flags, L, (double)h->t, h->part,
                verdict == 1   ? "no hit allowed"
                : verdict == 2 ? "wrong part"
                               : "t off",
                b->exact.hit ? "hit" : "miss", b->exact.t, b->exact.part, ub);
            CHECK(h->id == lc->id[L], "%s leaf%d: id %#x for lane %d (%#x)", k->name, lc->m,
                  h->id, L, lc->id[L]);
            /* The same shape in a lower lane hits at the same t: it must win the tie. */
            for (int j = 0; j < lc->n; j++)
                if (j != L && same_shape(lc, j, L)) {
                    ties_seen++;
                    break;
                }
            for (int j = 0; j < L; j++)
                CHECK(!same_shape(lc, j, L),
                      "%s leaf%d flags %#x: lane %d won a tie with the same shape in lane %d",
                      k->name, lc->m, flags, L, j);
            CHECK(memcmp(&io.ray.tmax, &h->t, 4) == 0, "%s leaf%d: tmax %a, t %a", k->name,
                  lc->m, (double)io.ray.tmax, (double)h->t);
            /* No lane surely hits before t, beyond the tolerance. */
            for (int j = 0; j < lc->n; j++) {
                double by = sure_hit_by(&lc->lane[j].band[cull]);
                if (j == L || !isfinite(by))
                    continue;
                double slack = tol * cylref_float_ulp(by);
                CHECK((double)h->t <= by + slack,
                      "%s leaf%d flags %#x: lane %d hit at %a, lane %d surely hits by %.9g",
                      k->name, lc->m, flags, L, (double)h->t, j, by);
            }
            if (normal && verdict == 0 && b->exact.hit && h->part == b->exact.part) {
                const double len = sqrt((double)h->n[0] * h->n[0] + (double)h->n[1] * h->n[1] +
                                        (double)h->n[2] * h->n[2]);
                /* The bands are made without face-forward: it flips a back face. */
                const double sg =
                    (flags & CYLRAY_FACE_FORWARD) && (h->part & CYLRAY_BACKFACE) ? -1 : 1;
                const double en[3] = {sg * b->exact.n[0], sg * b->exact.n[1],
                                      sg * b->exact.n[2]};
                const double ang = cylref_angle(h->n, en);
                CHECK(fabs(len - 1) <= 1e-5 && ang <= TOL_ANGLE + b->n_spread,
                      "%s leaf%d flags %#x: lane %d normal off by %.3g rad (|n| %.9f)", k->name,
                      lc->m, flags, L, ang, len);
            } else if (!normal) {
                uint32_t w[3];
                memcpy(w, h->n, sizeof w);
                CHECK(w[0] == POISON && w[1] == POISON && w[2] == POISON,
                      "%s leaf%d: normal written without CYLRAY_NORMAL", k->name, lc->m);
            }
        }
    }
    if (tc_failures_ != f0 && tc_failures_ < 20)
        print_leaf(lc);
}

/* The leaf refuses a bad cylinder or too many and stays as it was. */
static void bad_input(const cylray_kernels *k, const cylray_cylinder *good)
{
    cylray_leaf8 leaf, copy;
    memset(&leaf, 0x5a, sizeof leaf);
    copy = leaf;
    cylray_cylinder cyl[9];
    for (int j = 0; j < 9; j++)
        cyl[j] = *good;
    CHECK(cylray_leaf_prepare8(&leaf, cyl, NULL, 9) == CYLRAY_EINVAL, "9 cylinders in a leaf8");
    cyl[5].radius = NAN;
    CHECK(cylray_leaf_prepare8(&leaf, cyl, NULL, 8) == CYLRAY_EINVAL, "a NaN radius accepted");
    cyl[5] = *good;
    cyl[2].flags = 0x40;
    CHECK(cylray_leaf_prepare8(&leaf, cyl, NULL, 8) == CYLRAY_EINVAL, "bad flags accepted");
    CHECK(memcmp(&leaf, &copy, sizeof leaf) == 0, "a refused leaf was written");
    cyl[2] = *good;
    CHECK(cylray_leaf_prepare8(&leaf, cyl, NULL, 8) == CYLRAY_OK, "a good leaf refused");
    const float bad[] = {NAN, INFINITY, -INFINITY, fbits(0x7f800001u)};
    for (int f = 0; f < 8; f++)
        for (size_t v = 0; v < sizeof bad / sizeof bad[0]; v++) {
            cylray_ray1 ray = {{good->center[0] - 5, good->center[1], good->center[2]},
                               {1, 0.01f, 0.02f},
                               0,
                               INFINITY};
            float *fld = f < 3    ? &ray.o[f]
                         : f < 6  ? &ray.d[f - 3]
                         : f == 6 ? &ray.tmin
                                  : &ray.tmax;
            if ((f == 6 && bad[v] == -INFINITY) || (f == 7 && bad[v] == INFINITY))
                continue; /* legal bounds */
            *fld = bad[v];
            cylray_hit1 h;
            for (unsigned fl = 0; fl <= CYLRAY_FLAGS_ALL; fl++)
                CHECK(!k->leaf_intersect8(&leaf, &ray, &h, fl) &&
                          !k->leaf_occluded8(&leaf, &ray, fl),
                      "%s: a ray with field %d = %a hits", k->name, f, (double)bad[v]);
        }
}

/* A leaf of spheres refuses too many or a bad sphere, and stays as it was; bad rays
 * miss it. */
static void bad_sphere_input(const cylray_kernels *k, const cylray_sphere *good)
{
    cylray_leaf8 leaf, copy;
    memset(&leaf, 0x5a, sizeof leaf);
    copy = leaf;
    cylray_sphere s[9];
    for (int j = 0; j < 9; j++)
        s[j] = *good;
    CHECK(cylray_leaf_prepare_spheres8(&leaf, s, NULL, 9) == CYLRAY_EINVAL,
          "9 spheres in a leaf8");
    s[5].radius = NAN;
    CHECK(cylray_leaf_prepare_spheres8(&leaf, s, NULL, 8) == CYLRAY_EINVAL,
          "a NaN radius accepted");
    s[5] = *good;
    s[3].center[1] = INFINITY;
    CHECK(cylray_leaf_prepare_spheres8(&leaf, s, NULL, 8) == CYLRAY_EINVAL,
          "an infinite center accepted");
    CHECK(memcmp(&leaf, &copy, sizeof leaf) == 0, "a refused leaf of spheres was written");
    s[3] = *good;
    CHECK(cylray_leaf_prepare_spheres8(&leaf, s, NULL, 8) == CYLRAY_OK, "a good leaf refused");
    const float bad[] = {NAN, INFINITY, -INFINITY, fbits(0x7f800001u)};
    for (int f = 0; f < 8; f++)
        for (size_t v = 0; v < sizeof bad / sizeof bad[0]; v++) {
            cylray_ray1 ray = {
                {good->center[0] - 5 * good->radius, good->center[1], good->center[2]},
                {1, 0.01f, 0.02f},
                0,
                INFINITY};
            float *fld = f < 3    ? &ray.o[f]
                         : f < 6  ? &ray.d[f - 3]
                         : f == 6 ? &ray.tmin
                                  : &ray.tmax;
            if ((f == 6 && bad[v] == -INFINITY) || (f == 7 && bad[v] == INFINITY))
                continue; /* legal bounds */
            *fld = bad[v];
            cylray_hit1 h;
            for (unsigned fl = 0; fl <= CYLRAY_FLAGS_ALL; fl++)
                CHECK(!k->leaf_intersect8(&leaf, &ray, &h, fl) &&
                          !k->leaf_occluded8(&leaf, &ray, fl),
                      "%s: a ray with field %d = %a hits a sphere", k->name, f, (double)bad[v]);
        }
}

int main(int argc, char **argv)
{
    const char *want = NULL;
    int quick = tc_quick();
    uint64_t seed = 20261201;
    for (int a = 1; a < argc; a++) {
        if (strncmp(argv[a], "--isa=", 6) == 0)
            want = argv[a] + 6;
        else if (strcmp(argv[a], "--quick") == 0)
            quick = 1;
        else if (strncmp(argv[a], "--seed=", 7) == 0)
            seed = strtoull(argv[a] + 7, NULL, 0);
        else {
            fprintf(stderr, "usage: leafcheck [--isa=NAME] [--quick] [--seed=S]\n");
            return 2;
        }
    }
    const cylray_kernels *isas[CYLRAY_ISA_COUNT];
    int nisa = 0;
    for (int i = 0; i < CYLRAY_ISA_COUNT; i++) {
        const cylray_kernels *k = cylray_kernels_for((cylray_isa)i);
        if (k && (!want || strcmp(want, k->name) == 0))
            isas[nisa++] = k;
    }
    if (!nisa) {
        printf("leafcheck: %s is not available here\n", want ? want : "no ISA");
        return 77;
    }
    printf("leafcheck: seed %llu\n", (unsigned long long)seed);
    const int leaves = quick ? 150 : 1500;
    static const int sizes[3] = {4, 8, 16};
    cylgen_rng r;
    cylgen_seed(&r, seed);
    long calls = 0, hits = 0, sphere_hits = 0, cone_hits = 0;
    /* Spheres: a quarter as many leaves (their kernel is a subset of the cylinder's). */
    const int sphere_leaves = leaves / 4, cone_leaves = leaves / 4;
    for (int si = 0; si < 3; si++) {
        const int m = sizes[si];
        for (int li = 0; li < leaves + sphere_leaves + cone_leaves; li++) {
            leaf_case lc;
            const int con = li >= leaves + sphere_leaves;
            const int sph = li >= leaves && !con;
            if (con)
                make_cone_leaf(&lc, m, &r,
                               (seed ^ 0x434f4e45ull) + (uint64_t)li * 131 + (uint64_t)m);
            else if (sph)
                make_sphere_leaf(&lc, m, &r,
                                 (seed ^ 0x5350484552ull) + (uint64_t)li * 131 + (uint64_t)m);
            else
                make_leaf(&lc, m, &r, seed + (uint64_t)li * 131 + (uint64_t)m);
            cylray_cylinder cyl[16];
            cylray_sphere sp[16];
            cylray_cone co[16];
            for (int j = 0; j < lc.n; j++) {
                cyl[j] = lc.lane[j].cyl;
                sp[j] = lc.lane[j].sph;
                co[j] = lc.lane[j].con;
            }
            union {
                cylray_leaf4 l4;
                cylray_leaf8 l8;
                cylray_leaf16 l16;
            } leaf;
            const size_t n = (size_t)lc.n;
            cylray_status st =
                con      ? (m == 4   ? cylray_leaf_prepare_cones4(&leaf.l4, co, lc.id, n)
                            : m == 8 ? cylray_leaf_prepare_cones8(&leaf.l8, co, lc.id, n)
                                     : cylray_leaf_prepare_cones16(&leaf.l16, co, lc.id, n))
                : sph    ? (m == 4   ? cylray_leaf_prepare_spheres4(&leaf.l4, sp, lc.id, n)
                            : m == 8 ? cylray_leaf_prepare_spheres8(&leaf.l8, sp, lc.id, n)
                                     : cylray_leaf_prepare_spheres16(&leaf.l16, sp, lc.id, n))
                : m == 4 ? cylray_leaf_prepare4(&leaf.l4, cyl, lc.id, n)
                : m == 8 ? cylray_leaf_prepare8(&leaf.l8, cyl, lc.id, n)
                         : cylray_leaf_prepare16(&leaf.l16, cyl, lc.id, n);
            CHECK(st == CYLRAY_OK, "leaf of %d refused", lc.n);
            if (st != CYLRAY_OK)
                continue;
            for (int i = 0; i < nisa; i++)
                for (unsigned flags = 0; flags <= CYLRAY_FLAGS_ALL; flags++) {
                    judge(isas[i], &lc, &leaf, flags);
                    calls++;
                }
            for (int j = 0; j < lc.n; j++) {
                hits += lc.lane[j].band[0].exact.hit;
                sphere_hits += sph && lc.lane[j].band[0].exact.hit;
                cone_hits += con && lc.lane[j].band[0].exact.hit;
            }
        }
    }
    cylgen_case c;
    cylgen_make(CYLGEN_ORDINARY, seed, 1, &c);
    sphgen_case sc;
    sphgen_make(SPHGEN_ORDINARY, seed, 1, &sc);
    for (int i = 0; i < nisa; i++) {
        bad_input(isas[i], &c.cyl);
        bad_sphere_input(isas[i], &sc.sph);
    }
    printf("leafcheck: %ld leaf calls, %ld exact lane hits (%ld on spheres, %ld on cones), "
           "%ld calls hit a shape held in two lanes\n",
           calls, hits, sphere_hits, cone_hits, ties_seen);
    return tc_report("leafcheck");
}
