/* SPDX-License-Identifier: MIT */
/* outhash.c - one hash of every answer the kernels give, per path: a change meant to
 * keep the answers (a reorganisation, a new schedule of the same operations) must keep
 * every hash. Deterministic: a fixed seed, the public API only.
 *
 * Per path: 300 random cylinder sets (every kind, general and coordinate axes, caps on
 * one end, radii far from 1), rays with tiny, huge and scaled directions, NaN and
 * infinite lanes, partial masks; packets of 4, 8 and 16, streams of lengths 1-64 and
 * 200, leaves of 4, 8 and 16; intersect and occluded; all 32 flag sets; then 100
 * spheres, cones and round cones made from such cylinders, their packets and streams.
 * Every output array is hashed whole (what a kernel must leave untouched as well as
 * what it writes), with the returned masks and counts.
 *
 *     outhash [--no-fast] [--fast-plain] [CASES]
 *         prints "isa hash" per path the CPU runs, then "all hash"; --no-fast leaves
 *         out the flag sets with CYLRAY_FAST, whose estimates may differ by CPU (the
 *         others must not: tests/run.sh compares them across builds with other
 *         estimates); --fast-plain calls each of those without CYLRAY_FAST instead, the
 *         answers of a path that serves FAST with its exact kernels (fast_same.py) */
#include "cylray.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static uint64_t rng_state;
static uint32_t rnd(void)
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 7;
    rng_state ^= rng_state << 17;
    return (uint32_t)(rng_state >> 32);
}
static float unif(float a, float b)
{
    return a + (b - a) * (float)(rnd() >> 8) * 0x1p-24f;
}

static uint64_t hash_state;
static void hash(const void *p, size_t n)
{
    const unsigned char *b = p;
    for (size_t i = 0; i < n; i++)
        hash_state = (hash_state ^ b[i]) * 0x100000001b3ull;
}
static void hash_u(uint64_t v)
{
    hash(&v, sizeof v);
}

static void random_cylinder(cylray_cylinder *c)
{
    for (int j = 0; j < 3; j++) {
        c->center[j] = unif(-4.0f, 4.0f);
        c->axis[j] = unif(-1.0f, 1.0f);
    }
    const uint32_t r = rnd();
    if (r % 4 == 0) { /* a coordinate axis, either sign */
        int a = (int)(r / 4 % 3);
        c->axis[0] = c->axis[1] = c->axis[2] = 0.0f;
        c->axis[a] = r & 64 ? -unif(0.5f, 3.0f) : unif(0.5f, 3.0f);
    }
    c->radius = unif(0.1f, 2.0f);
    if (r % 7 == 1)
        c->radius *= 0x1p-30f; /* far from 1: the generic kernels */
    if (r % 11 == 2)
        c->radius *= 0x1p30f;
    c->half_height = r % 5 == 0 ? INFINITY : unif(0.1f, 3.0f);
    c->flags = (r >> 8) % 3 == 0 ? 0u : (r >> 10) % 4 == 0 ? (r >> 12) % 3 : CYLRAY_CAPPED;
}

/* Ray i aimed near cylinder c, with the odd lanes the kernels must survive. */
static void random_ray(const cylray_cylinder *c, float o[3], float d[3], float *tmin,
                       float *tmax)
{
    const float s = c->radius > 100.0f ? c->radius : 1.0f;
    for (int j = 0; j < 3; j++) {
        o[j] = c->center[j] + unif(-6.0f, 6.0f) * s;
        d[j] = c->center[j] + unif(-1.0f, 1.0f) * c->radius - o[j];
    }
    *tmin = 0.0f;
    *tmax = INFINITY;
    const uint32_t r = rnd();
    switch (r % 16) {
    case 0: /* tiny direction */
        for (int j = 0; j < 3; j++)
            d[j] *= 0x1p-50f;
        break;
    case 1: /* huge direction */
        for (int j = 0; j < 3; j++)
            d[j] *= 0x1p50f;
        break;
    case 2: /* along the axis */
        for (int j = 0; j < 3; j++)
            d[j] = c->axis[j] * ((r & 256) ? 1.0f : -1.0f);
        break;
    case 3:
        d[r / 16 % 3] = NAN;
        break;
    case 4:
        o[r / 16 % 3] = INFINITY;
        break;
    case 5:
        *tmin = unif(0.0f, 1.0f), *tmax = unif(0.0f, 2.0f);
        break;
    case 6:
        *tmax = NAN;
        break;
    case 7: /* a far origin */
        for (int j = 0; j < 3; j++)
            o[j] *= 0x1p20f;
        break;
    case 8:
        d[0] = d[1] = d[2] = 0.0f;
        break;
    case 9: /* a subnormal component */
        d[r / 16 % 3] = 1e-40f;
        break;
    default:
        break;
    }
}

#define MAXN 200

typedef struct {
    float ox[MAXN], oy[MAXN], oz[MAXN], dx[MAXN], dy[MAXN], dz[MAXN], tmin[MAXN], tmax[MAXN];
} soa;

static void fill(soa *s, const cylray_cylinder *c, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        float o[3], d[3];
        random_ray(c, o, d, &s->tmin[i], &s->tmax[i]);
        s->ox[i] = o[0], s->oy[i] = o[1], s->oz[i] = o[2];
        s->dx[i] = d[0], s->dy[i] = d[1], s->dz[i] = d[2];
    }
}

#define PACKET(n)                                                                              \
    static void packet##n(const cylray_kernels *k, const cylray_prepared *p, const soa *s,     \
                          uint32_t active, unsigned flags)                                     \
    {                                                                                          \
        cylray_ray##n ray;                                                                     \
        cylray_hit##n hit;                                                                     \
        memcpy(ray.ox, s->ox, sizeof ray.ox), memcpy(ray.oy, s->oy, sizeof ray.oy);            \
        memcpy(ray.oz, s->oz, sizeof ray.oz), memcpy(ray.dx, s->dx, sizeof ray.dx);            \
        memcpy(ray.dy, s->dy, sizeof ray.dy), memcpy(ray.dz, s->dz, sizeof ray.dz);            \
        memcpy(ray.tmin, s->tmin, sizeof ray.tmin);                                            \
        memcpy(ray.tmax, s->tmax, sizeof ray.tmax);                                            \
        hash_u(k->occluded##n(p, &ray, active, flags));                                        \
        memset(&hit, 0x5a, sizeof hit);                                                        \
        hash_u(k->intersect##n(p, &ray, &hit, active, flags));                                 \
        hash(&ray, sizeof ray), hash(&hit, sizeof hit);                                        \
    }
PACKET(4)
PACKET(8)
PACKET(16)

static void stream(const cylray_kernels *k, const cylray_prepared *p, const soa *s, size_t n,
                   unsigned flags)
{
    float tmax[MAXN + 1], t[MAXN + 1], nx[MAXN + 1], ny[MAXN + 1], nz[MAXN + 1];
    int32_t part[MAXN + 1];
    uint8_t occ[MAXN + 1];
    /* every byte hashed is defined: the lanes past n + 1 too, which a stream must not
     * touch */
    memset(tmax, 0x5a, sizeof tmax);
    memcpy(tmax, s->tmax, sizeof tmax[0] * n);
    tmax[n] = 7.0f;
    memset(t, 0x5a, sizeof t), memset(nx, 0x5a, sizeof nx), memset(ny, 0x5a, sizeof ny);
    memset(nz, 0x5a, sizeof nz), memset(part, 0x5a, sizeof part), memset(occ, 2, sizeof occ);
    const cylray_rays R = {s->ox, s->oy, s->oz, s->dx, s->dy, s->dz, s->tmin, tmax};
    const cylray_hits H = {t, nx, ny, nz, part};
    hash_u(k->occluded_stream(p, &R, occ, n, flags));
    hash_u(k->intersect_stream(p, &R, &H, n, flags));
    hash(tmax, sizeof tmax), hash(t, sizeof t), hash(nx, sizeof nx), hash(ny, sizeof ny);
    hash(nz, sizeof nz), hash(part, sizeof part), hash(occ, sizeof occ);
}

#define LEAF(m)                                                                                \
    static void leaf##m(const cylray_kernels *k, const cylray_cylinder *cyl, size_t count,     \
                        const soa *s, unsigned flags)                                          \
    {                                                                                          \
        cylray_leaf##m leaf;                                                                   \
        uint32_t ids[m];                                                                       \
        for (uint32_t j = 0; j < m; j++)                                                       \
            ids[j] = 100u + j;                                                                 \
        if (cylray_leaf_prepare##m(&leaf, cyl, ids, count) != CYLRAY_OK) {                     \
            hash_u(0xbad);                                                                     \
            return;                                                                            \
        }                                                                                      \
        for (size_t i = 0; i < 8; i++) {                                                       \
            cylray_ray1 ray = {{s->ox[i], s->oy[i], s->oz[i]},                                 \
                               {s->dx[i], s->dy[i], s->dz[i]},                                 \
                               s->tmin[i],                                                     \
                               s->tmax[i]};                                                    \
            cylray_hit1 hit;                                                                   \
            memset(&hit, 0x5a, sizeof hit);                                                    \
            hash_u((uint64_t)k->leaf_occluded##m(&leaf, &ray, flags));                         \
            hash_u((uint64_t)k->leaf_intersect##m(&leaf, &ray, &hit, flags));                  \
            hash(&ray, sizeof ray), hash(&hit, sizeof hit);                                    \
        }                                                                                      \
    }
LEAF(4)
LEAF(8)
LEAF(16)

/* The other shapes, each prepared from a random cylinder's numbers (its center and
 * axis as the endpoints, its radius, a second radius and its flags) and met by rays
 * aimed at it: a sphere, a cone and a round cone, their packets and streams. */
static void other_shapes(const cylray_kernels *k, int cases, int no_fast, int fast_plain)
{
    static soa s;
    for (int c = 0; c < cases; c++) {
        cylray_cylinder cyl;
        random_cylinder(&cyl);
        if (!(cyl.half_height < INFINITY))
            cyl.half_height = 2.0f;
        const float r1 = rnd() % 5 == 0 ? 0.0f : cyl.radius * unif(0.05f, 1.5f);
        cylray_prepared p[3];
        const cylray_sphere sph = {{cyl.center[0], cyl.center[1], cyl.center[2]}, cyl.radius};
        cylray_cone cone = {.r0 = cyl.radius, .r1 = r1, .flags = cyl.flags};
        for (int j = 0; j < 3; j++) {
            cone.p0[j] = cyl.center[j] - cyl.axis[j] * cyl.half_height;
            cone.p1[j] = cyl.center[j] + cyl.axis[j] * cyl.half_height;
        }
        const cylray_round_cone rc = {{cone.p0[0], cone.p0[1], cone.p0[2]},
                                      {cone.p1[0], cone.p1[1], cone.p1[2]},
                                      cone.r0,
                                      rnd() % 4 == 0 ? cone.r0 : cone.r1,
                                      cone.flags};
        const int ok[3] = {cylray_prepare_sphere(&p[0], &sph) == CYLRAY_OK,
                           cylray_prepare_cone(&p[1], &cone) == CYLRAY_OK,
                           cylray_prepare_round_cone(&p[2], &rc) == CYLRAY_OK};
        const size_t n = c % 4 == 0 ? MAXN : 1 + (size_t)(rnd() % 64);
        fill(&s, &cyl, MAXN);
        const uint32_t active = rnd() % 3 == 0 ? rnd() : 0xffffffffu;
        for (int sh = 0; sh < 3; sh++) {
            hash_u((uint64_t)ok[sh]);
            if (!ok[sh])
                continue;
            for (unsigned fl = 0; fl <= CYLRAY_FLAGS_ALL; fl++) {
                if (no_fast && (fl & CYLRAY_FAST))
                    continue;
                const unsigned flags = fast_plain ? fl & ~CYLRAY_FAST : fl;
                packet4(k, &p[sh], &s, active, flags);
                packet8(k, &p[sh], &s, active, flags);
                packet16(k, &p[sh], &s, active, flags);
                stream(k, &p[sh], &s, n, flags);
            }
        }
    }
}

int main(int argc, char **argv)
{
    int cases = 300, no_fast = 0, fast_plain = 0;
    for (int a = 1; a < argc; a++) {
        if (strcmp(argv[a], "--no-fast") == 0)
            no_fast = 1;
        else if (strcmp(argv[a], "--fast-plain") == 0)
            fast_plain = 1;
        else
            cases = atoi(argv[a]);
    }
    uint64_t all = 0xcbf29ce484222325ull;
    for (int isa = 0; isa < CYLRAY_ISA_COUNT; isa++) {
        const cylray_kernels *k = cylray_kernels_for((cylray_isa)isa);
        if (!k)
            continue;
        rng_state = 0x9e3779b97f4a7c15ull;
        hash_state = 0xcbf29ce484222325ull;
        static soa s;
        for (int c = 0; c < cases; c++) {
            cylray_cylinder cyl[16];
            for (int j = 0; j < 16; j++)
                random_cylinder(&cyl[j]);
            cylray_prepared p;
            if (cylray_prepare(&p, &cyl[0]) != CYLRAY_OK) {
                hash_u(0xbad);
                continue;
            }
            const size_t n = c % 4 == 0 ? MAXN : 1 + (size_t)(rnd() % 64);
            fill(&s, &cyl[0], MAXN);
            const uint32_t active = rnd() % 3 == 0 ? rnd() : 0xffffffffu;
            for (unsigned fl = 0; fl <= CYLRAY_FLAGS_ALL; fl++) {
                const size_t count = 1 + rnd() % 16;
                if (no_fast && (fl & CYLRAY_FAST))
                    continue;
                const unsigned flags = fast_plain ? fl & ~CYLRAY_FAST : fl;
                packet4(k, &p, &s, active, flags);
                packet8(k, &p, &s, active, flags);
                packet16(k, &p, &s, active, flags);
                stream(k, &p, &s, n, flags);
                leaf4(k, cyl, count < 4 ? count : 4, &s, flags);
                leaf8(k, cyl, count < 8 ? count : 8, &s, flags);
                leaf16(k, cyl, count, &s, flags);
            }
        }
        other_shapes(k, cases / 3, no_fast, fast_plain);
        printf("%-7s %016llx\n", k->name, (unsigned long long)hash_state);
        all = (all ^ hash_state) * 0x100000001b3ull;
    }
    printf("all     %016llx\n", (unsigned long long)all);
    return 0;
}
