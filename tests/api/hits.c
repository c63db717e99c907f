/* SPDX-License-Identifier: MIT */
/* hits.c - hand-checked hits: every case below has an answer worked out on paper,
 * exact in binary (integers, halves, Pythagorean triples), run on every ISA, at every
 * width, in every lane position, under every flag that changes the answer:
 *   CYLRAY_CULL_BACK   drops hits met from inside (the case then misses);
 *   CYLRAY_FACE_FORWARD flips the normal of such hits to face the ray;
 *   CYLRAY_NORMAL      writes a unit outward normal (checked against the paper one);
 *   CYLRAY_REFINE, CYLRAY_FAST must not change the answer beyond a few ulps. */
#include <float.h>
#include <math.h>
#include <string.h>

#include "cylray.h"
#include "flagsets.h"
#include "guarded.h"
#include "tcheck.h"

#define CAP CYLRAY_CAPPED
#define BACK CYLRAY_BACKFACE
#define SIDE CYLRAY_SIDE
#define LO CYLRAY_CAP_LO
#define HI CYLRAY_CAP_HI

typedef struct hcase {
    const char *name;
    cylray_cylinder cyl;
    float o[3], d[3], tmin, tmax;
    int hit;      /* without CYLRAY_CULL_BACK */
    float t;      /* the exact hit */
    int part;     /* with CYLRAY_BACKFACE when met from inside */
    float n[3];   /* outward unit normal */
    int alt_part; /* another acceptable part (a ray aimed at the rim), or 0 */
} hcase;

/* Cylinders: the unit one along z (infinite, capped, open, R = 5) and an oblique one. */
#define ZINF                                                                                   \
    {                                                                                          \
        {0, 0, 0}, {0, 0, 1}, 1, INFINITY, 0                                                   \
    }
#define ZCAP                                                                                   \
    {                                                                                          \
        {0, 0, 0}, {0, 0, 1}, 1, 2, CAP                                                        \
    }
#define ZOPEN                                                                                  \
    {                                                                                          \
        {0, 0, 0}, {0, 0, 1}, 1, 2, 0                                                          \
    }
#define Z5INF                                                                                  \
    {                                                                                          \
        {0, 0, 0}, {0, 0, 1}, 5, INFINITY, 0                                                   \
    }
/* center (1,2,3), axis (3,4,0) (unit (0.6,0.8,0), not normalised), R 5, H 5 */
#define OBL                                                                                    \
    {                                                                                          \
        {1, 2, 3}, {3, 4, 0}, 5, 5, CAP                                                        \
    }
#define OBLOPEN                                                                                \
    {                                                                                          \
        {1, 2, 3}, {3, 4, 0}, 5, 5, 0                                                          \
    }

static const hcase cases[] = {
    {"side, axis-aligned", ZINF, {-5, 0, 0}, {1, 0, 0}, 0, 100, 1, 4, SIDE, {-1, 0, 0}, 0},
    {"side, Pythagorean point",
     Z5INF,
     {3, 10, 7},
     {0, -1, 0},
     0,
     100,
     1,
     6,
     SIDE,
     {0.6f, 0.8f, 0},
     0},
    {"side, slanted ray",
     Z5INF,
     {3, 10, 7},
     {0, -1, 0.5f},
     0,
     100,
     1,
     6,
     SIDE,
     {0.6f, 0.8f, 0},
     0},
    {"unnormalised direction 2^-10",
     Z5INF,
     {3, 10, 7},
     {0, -0x1p-10f, 0},
     0,
     1e6f,
     1,
     6144,
     SIDE,
     {0.6f, 0.8f, 0},
     0},
    {"unnormalised direction 2^10",
     Z5INF,
     {3, 10, 7},
     {0, -1024, 0},
     0,
     1,
     1,
     0x1.8p-8f,
     SIDE,
     {0.6f, 0.8f, 0},
     0},
    {"from inside: backface",
     ZINF,
     {0, 0, 0},
     {1, 0, 0},
     0,
     100,
     1,
     1,
     SIDE | BACK,
     {1, 0, 0},
     0},
    {"behind the origin", ZINF, {5, 0, 0}, {1, 0, 0}, 0, 100, 0, 0, 0, {0, 0, 0}, 0},
    {"passes beside", ZINF, {-5, 2, 0}, {1, 0, 0}, 0, 100, 0, 0, 0, {0, 0, 0}, 0},
    {"tmax before the hit", ZINF, {-5, 0, 0}, {1, 0, 0}, 0, 3.5f, 0, 0, 0, {0, 0, 0}, 0},
    {"tmin past the entry",
     ZINF,
     {-5, 0, 0},
     {1, 0, 0},
     4.5f,
     100,
     1,
     6,
     SIDE | BACK,
     {1, 0, 0},
     0},
    {"closed interval [4, 4]", ZINF, {-5, 0, 0}, {1, 0, 0}, 4, 4, 1, 4, SIDE, {-1, 0, 0}, 0},
    {"tmax exactly at the hit", ZINF, {-5, 0, 0}, {1, 0, 0}, 0, 4, 1, 4, SIDE, {-1, 0, 0}, 0},
    {"tmin exactly at the exit",
     ZINF,
     {-5, 0, 0},
     {1, 0, 0},
     6,
     100,
     1,
     6,
     SIDE | BACK,
     {1, 0, 0},
     0},
    {"negative tmin: hit behind",
     ZINF,
     {0, 0, 0},
     {1, 0, 0},
     -10,
     100,
     1,
     -1,
     SIDE,
     {-1, 0, 0},
     0},
    {"along the axis inside an infinite one",
     ZINF,
     {0.5f, 0, 0},
     {0, 0, 1},
     -1e30f,
     1e30f,
     0,
     0,
     0,
     {0, 0, 0},
     0},
    {"far origin 2^20",
     ZINF,
     {-0x1p20f, 0, 0},
     {1, 0, 0},
     0,
     1e30f,
     1,
     0x1p20f - 1,
     SIDE,
     {-1, 0, 0},
     0},
    {"far center, radius 2^-10",
     {{4096, 4096, 0}, {0, 0, 1}, 0x1p-10f, INFINITY, 0},
     {4095, 4096, 5},
     {1, 0, 0},
     0,
     10,
     1,
     1 - 0x1p-10f,
     SIDE,
     {-1, 0, 0},
     0},

    {"upper cap from above", ZCAP, {0.5f, 0, 5}, {0, 0, -1}, 0, 100, 1, 3, HI, {0, 0, 1}, 0},
    {"lower cap from below", ZCAP, {0.5f, 0, -5}, {0, 0, 1}, 0, 100, 1, 3, LO, {0, 0, -1}, 0},
    {"upper cap from inside",
     ZCAP,
     {0, 0, 0},
     {0, 0, 1},
     0,
     100,
     1,
     2,
     HI | BACK,
     {0, 0, 1},
     0},
    {"side from inside, capped",
     ZCAP,
     {0, 0, 0},
     {1, 0, 0},
     0,
     100,
     1,
     1,
     SIDE | BACK,
     {1, 0, 0},
     0},
    {"slanted into the side, capped",
     ZCAP,
     {-5, 0, -2.5f},
     {1, 0, 0.5f},
     0,
     100,
     1,
     4,
     SIDE,
     {-1, 0, 0},
     0},
    {"slanted through the lower cap",
     ZCAP,
     {-5, 0, -6.5f},
     {1, 0, 1},
     0,
     100,
     1,
     4.5f,
     LO,
     {0, 0, -1},
     0},
    {"aimed at the rim", ZCAP, {-5, 0, -4}, {1, 0, 0.5f}, 0, 100, 1, 4, SIDE, {-1, 0, 0}, LO},
    {"axis 2^60 long",
     {{0, 0, 0}, {0, 0, 0x1p60f}, 1, 2, CAP},
     {0.5f, 0, 5},
     {0, 0, -1},
     0,
     100,
     1,
     3,
     HI,
     {0, 0, 1},
     0},
    {"axis FLT_MIN long",
     {{0, 0, 0}, {0, 0, FLT_MIN}, 1, 2, CAP},
     {0.5f, 0, 5},
     {0, 0, -1},
     0,
     100,
     1,
     3,
     HI,
     {0, 0, 1},
     0},
    {"axis pointing down",
     {{0, 0, 0}, {0, 0, -1}, 1, 2, CAP},
     {0.5f, 0, 5},
     {0, 0, -1},
     0,
     100,
     1,
     3,
     LO,
     {0, 0, 1},
     0},

    {"open tube, along the axis",
     ZOPEN,
     {0.5f, 0, 5},
     {0, 0, -1},
     0,
     100,
     0,
     0,
     0,
     {0, 0, 0},
     0},
    {"open tube, side", ZOPEN, {-5, 0, -2.5f}, {1, 0, 0.5f}, 0, 100, 1, 4, SIDE, {-1, 0, 0}, 0},
    {"open tube, near root clipped",
     ZOPEN,
     {-5, 0, -6.5f},
     {1, 0, 1},
     0,
     100,
     1,
     6,
     SIDE | BACK,
     {1, 0, 0},
     0},
    {"open tube, both roots clipped",
     ZOPEN,
     {-5, 0, -9},
     {1, 0, 1},
     0,
     100,
     0,
     0,
     0,
     {0, 0, 0},
     0},

    {"oblique axis, side",
     OBL,
     {-7, 8, 3},
     {4, -3, 0},
     0,
     100,
     1,
     1,
     SIDE,
     {-0.8f, 0.6f, 0},
     0},
    {"oblique axis, slanted into the side",
     OBL,
     {-8.5f, 6, 3},
     {7, 1, 0},
     0,
     100,
     1,
     1,
     SIDE,
     {-0.8f, 0.6f, 0},
     0},
    {"oblique axis, upper cap",
     OBL,
     {10, 14, 5},
     {-3, -4, 0},
     0,
     100,
     1,
     2,
     HI,
     {0.6f, 0.8f, 0},
     0},
    {"oblique axis, lower cap",
     OBL,
     {-8, -10, 1},
     {3, 4, 0},
     0,
     100,
     1,
     2,
     LO,
     {-0.6f, -0.8f, 0},
     0},
    {"oblique axis, exit through the upper cap",
     OBL,
     {1, 2, 3},
     {3, 4, 0},
     0,
     100,
     1,
     1,
     HI | BACK,
     {0.6f, 0.8f, 0},
     0},
    {"oblique open tube, along the axis",
     OBLOPEN,
     {10, 14, 5},
     {-3, -4, 0},
     0,
     100,
     0,
     0,
     0,
     {0, 0, 0},
     0},
};
#define NCASES (sizeof cases / sizeof cases[0])

static void fill_lane(gbatch *b, size_t i, const hcase *c)
{
    const float v[G_NFIELD] = {c->o[0], c->o[1], c->o[2], c->d[0],
                               c->d[1], c->d[2], c->tmin, c->tmax};
    for (int f = 0; f < G_NFIELD; f++)
        b->f[f][i] = v[f];
}

/* Checks lane i of r against the paper answer under `flags`. */
static void judge(const hcase *c, const gresult *r, size_t i, unsigned flags, const char *ctx)
{
    const int culled = (flags & CYLRAY_CULL_BACK) && (c->part & BACK);
    const int want = c->hit && !culled;
    const int got = (int)((r->hit >> i) & 1u);
    CHECK(got == want, "%s [%s] lane %zu: %s, expected %s", ctx, c->name, i,
          got ? "hit" : "miss", want ? "a hit" : "a miss");
    if (!got || !want)
        return;
    const double tol = (flags & CYLRAY_FAST) ? 16 : 4;
    CHECK(tc_ulps(r->t[i], c->t) <= tol, "%s [%s] lane %zu: t = %a, expected %a", ctx, c->name,
          i, r->t[i], c->t);
    CHECK(r->part[i] == c->part || (c->alt_part && r->part[i] == c->alt_part),
          "%s [%s] lane %zu: part %#x, expected %#x", ctx, c->name, i, (unsigned)r->part[i],
          (unsigned)c->part);
    if (!(flags & CYLRAY_NORMAL))
        return;
    /* The outward normal, flipped to face the ray for back faces under FACE_FORWARD. */
    float n[3] = {c->n[0], c->n[1], c->n[2]};
    if (c->alt_part && r->part[i] == c->alt_part) /* the rim: the cap's normal */
        n[0] = 0, n[1] = 0, n[2] = c->alt_part == LO ? -1.0f : 1.0f;
    const float s = ((flags & CYLRAY_FACE_FORWARD) && (r->part[i] & BACK)) ? -1.0f : 1.0f;
    const double ntol = (flags & CYLRAY_FAST) ? 1e-5 : 1e-6;
    const float got_n[3] = {r->nx[i], r->ny[i], r->nz[i]};
    double len = 0;
    for (int k = 0; k < 3; k++) {
        CHECK(fabs((double)got_n[k] - s * n[k]) <= ntol,
              "%s [%s] lane %zu: normal (%a, %a, %a), expected (%a, %a, %a)", ctx, c->name, i,
              got_n[0], got_n[1], got_n[2], s * n[0], s * n[1], s * n[2]);
        len += (double)got_n[k] * got_n[k];
    }
    CHECK(fabs(sqrt(len) - 1) <= ntol, "%s [%s] lane %zu: normal length %.9g", ctx, c->name, i,
          sqrt(len));
}

/* A ray that hits every cylinder above from far outside: the content of lanes that are
 * inactive, so that reading or writing them would show. */
static const hcase decoy = {
    "decoy", ZINF, {0.25f, 0.25f, 0.25f}, {1, 1, 1}, -1e30f, 1e30f, 1, 0, 0, {0, 0, 0}, 0};

int main(void)
{
    const cylray_kernels *isas[CYLRAY_ISA_COUNT];
    const int nisa = g_isas(isas);
    const int widths[] = {4, 8, 16, G_STREAM};
    const int quick = tc_quick();
    char ctx[128];

    for (size_t ci = 0; ci < NCASES; ci++) {
        const hcase *c = &cases[ci];
        cylray_prepared P;
        if (cylray_prepare(&P, &c->cyl) != CYLRAY_OK) {
            CHECK(0, "[%s]: prepare refused the cylinder", c->name);
            continue;
        }
        for (int ii = 0; ii < nisa; ii++)
            for (size_t fi = 0; fi < FLAG_SETS_ALL; fi++)
                for (size_t wi = 0; wi < 4; wi++) {
                    const unsigned flags = flag_sets[fi];
                    const int w = widths[wi];
                    gbatch b;
                    gresult r;
                    snprintf(ctx, sizeof ctx, "%s w=%s flags=%#x", isas[ii]->name,
                             g_width_name(w), flags);
                    if (w == G_STREAM) {
                        /* The case in every ray of streams of a few lengths. */
                        static const size_t lens[] = {1, 5, 17, 33};
                        for (size_t li = 0; li < 4; li++) {
                            for (size_t i = 0; i < lens[li]; i++)
                                fill_lane(&b, i, c);
                            g_intersect(isas[ii], w, &P, &b, lens[li], 0, flags,
                                        (unsigned)li & 3u, &r);
                            for (size_t i = 0; i < lens[li]; i++)
                                judge(c, &r, i, flags, ctx);
                        }
                        continue;
                    }
                    /* Every lane active and holding the case... */
                    for (int i = 0; i < w; i++)
                        fill_lane(&b, (size_t)i, c);
                    g_intersect(isas[ii], w, &P, &b, (size_t)w, (1u << w) - 1u, flags, 0, &r);
                    for (int i = 0; i < w; i++)
                        judge(c, &r, (size_t)i, flags, ctx);
                    /* ...then the case alone in one lane, decoys in the inactive rest. */
                    for (int j = 0; j < w; j++) {
                        if (quick && j != 0 && j != w - 1 && j != w / 2 + 1)
                            continue;
                        for (int i = 0; i < w; i++)
                            fill_lane(&b, (size_t)i, i == j ? c : &decoy);
                        g_intersect(isas[ii], w, &P, &b, (size_t)w, 1u << j, flags, 0, &r);
                        judge(c, &r, (size_t)j, flags, ctx);
                    }
                }
    }
    return tc_report("api-hits");
}
