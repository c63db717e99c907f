/* SPDX-License-Identifier: MIT */
/* isolation.c - lanes and memory are isolated, on every ISA:
 *   - inactive lanes: whatever they hold (rays that would hit, NaN, signalling NaN,
 *     Inf, huge and subnormal garbage), the active lanes' answers are bit-identical
 *     to the all-active run, for every active mask of 4 and 8 lanes and many of 16;
 *     inactive lanes are never reported nor written (the guarded runner checks);
 *   - streams of every length 0 .. 3*16+1, at every misalignment of 0..3 floats,
 *     answer each ray exactly as a 16-packet does, and touch nothing outside their
 *     arrays (canaries, also AddressSanitizer-poisoned in sanitizer builds);
 *   - a cylray_prepared that did not come from cylray_prepare (zeroed, garbage, a
 *     corrupted kind) and NULL pointers give no hit and write nothing. */
#include <float.h>
#include <math.h>
#include <string.h>

#include "cylray.h"
#include "flagsets.h"
#include "guarded.h"
#include "rng.h"
#include "scene.h"
#include "tcheck.h"

/* What an inactive lane may hold: kind 0 keeps the lane's own (often hitting) ray. */
#define NPOISON 4
static void poison_lane(gbatch *b, size_t i, int kind)
{
    static const float garbage[NPOISON][G_NFIELD] = {
        {0, 0, 0, 0, 0, 0, 0, 0},
        {NAN, NAN, NAN, NAN, NAN, NAN, NAN, NAN},
        {INFINITY, -INFINITY, 1e30f, -FLT_MAX, 1e-40f, -0.0f, -INFINITY, INFINITY},
        {0, 0, 0, 1, 1, 1, -INFINITY, INFINITY}, /* a line through the center */
    };
    if (kind == 0)
        return;
    for (int f = 0; f < G_NFIELD; f++)
        b->f[f][i] = garbage[kind][f];
    if (kind == 1) /* signalling NaNs in half the fields */
        for (int f = 0; f < G_NFIELD; f += 2)
            b->f[f][i] = g_bits(0x7f800001u + (uint32_t)f);
}

static void masks(const cylray_kernels *k, const cylray_prepared *P, const gbatch *rays,
                  unsigned flags, int w, uint64_t *seed, int quick)
{
    const int normal = (flags & CYLRAY_NORMAL) != 0;
    const uint32_t full = (uint32_t)((1ull << w) - 1u);
    gresult all, r;
    g_intersect(k, w, P, rays, (size_t)w, full, flags, 0, &all);
    const uint32_t count = w <= 8 ? (1u << w) : (quick ? 40u : 300u);
    for (uint32_t mi = 0; mi < count; mi++) {
        uint32_t m = w <= 8 ? mi : (uint32_t)rng_splitmix64(seed) & full;
        if (w > 8 && mi < 16)
            m = 1u << mi; /* every single lane */
        for (int kind = 0; kind < NPOISON; kind++) {
            if (quick && kind != 1 && (mi & 3u))
                continue;
            gbatch b = *rays;
            for (int i = 0; i < w; i++)
                if (!((m >> i) & 1u))
                    poison_lane(&b, (size_t)i, kind);
            g_intersect(k, w, P, &b, (size_t)w, m, flags, 0, &r);
            for (int i = 0; i < w; i++)
                if ((m >> i) & 1u)
                    CHECK(g_same_lane(&r, (size_t)i, &all, (size_t)i, normal),
                          "%s packet%d flags=%#x mask %#x poison %d: lane %d differs from "
                          "the all-active run (t %a/%a)",
                          k->name, w, flags, m, kind, i, r.t[i], all.t[i]);
            gresult o;
            g_occluded(k, w, P, &b, (size_t)w, m, flags, 0, &o);
            CHECK(o.hit == (all.hit & m),
                  "%s occluded%d flags=%#x mask %#x poison %d: %#llx, "
                  "expected %#llx",
                  k->name, w, flags, m, kind, (unsigned long long)o.hit,
                  (unsigned long long)(all.hit & m));
        }
    }
}

static void streams(const cylray_kernels *k, const cylray_prepared *P, const gbatch *rays,
                    unsigned flags)
{
    const int normal = (flags & CYLRAY_NORMAL) != 0;
    /* The per-ray answers from 16-packets (all active). */
    gresult pk[G_MAX / 16];
    for (int p = 0; p < G_MAX / 16; p++) {
        gbatch b;
        for (int f = 0; f < G_NFIELD; f++)
            memcpy(b.f[f], rays->f[f] + 16 * p, 16 * sizeof(float));
        g_intersect(k, 16, P, &b, 16, 0xffffu, flags, 0, &pk[p]);
    }
    for (size_t n = 0; n <= 3 * 16 + 1; n++)
        for (unsigned mis = 0; mis < 4; mis++) {
            gresult r, o;
            g_intersect(k, G_STREAM, P, rays, n, 0, flags, mis, &r);
            g_occluded(k, G_STREAM, P, rays, n, 0, flags, mis, &o);
            size_t hits = 0;
            for (size_t i = 0; i < n; i++) {
                const gresult *q = &pk[i / 16];
                hits += (q->hit >> (i % 16)) & 1u;
                CHECK(g_same_lane(&r, i, q, i % 16, normal),
                      "%s stream n=%zu misalign=%u flags=%#x: ray %zu differs from the "
                      "16-packet (t %a/%a)",
                      k->name, n, mis, flags, i, r.t[i], q->t[i % 16]);
            }
            CHECK(r.count == hits && o.count == hits && o.hit == r.hit,
                  "%s stream n=%zu misalign=%u flags=%#x: %zu hits (occluded %zu), packets "
                  "%zu",
                  k->name, n, mis, flags, r.count, o.count, hits);
        }
}

/* Prepared structs the kernels must refuse, and NULL pointers. */
static void refusals(const cylray_kernels *k, const cylray_prepared *good, const gbatch *rays)
{
    cylray_prepared bad[4];
    memset(&bad[0], 0, sizeof bad[0]);
    memset(&bad[1], 0xff, sizeof bad[1]);
    bad[2] = *good;
    bad[2].kind = 77; /* magic intact, kind impossible */
    bad[3] = *good;
    bad[3].magic ^= 1u;
    for (int bi = 0; bi < 4; bi++) {
        const int widths[] = {4, 8, 16, G_STREAM};
        for (int wi = 0; wi < 4; wi++) {
            const int w = widths[wi];
            const size_t n = w == G_STREAM ? 21 : (size_t)w;
            gresult r, o;
            g_intersect(k, w, &bad[bi], rays, n, 0xffffu, CYLRAY_NORMAL, 1, &r);
            g_occluded(k, w, &bad[bi], rays, n, 0xffffu, 0, 1, &o);
            CHECK(r.count == 0 && r.hit == 0 && o.hit == 0 && o.count == 0,
                  "%s w=%s: a prepared struct not from cylray_prepare (%d) gave hits", k->name,
                  g_width_name(w), bi);
        }
    }
    /* NULL cylinder, rays, hits: nothing happens. */
    cylray_ray16 ray;
    cylray_hit16 hit;
    memset(&ray, 0, sizeof ray);
    memset(&hit, 0, sizeof hit);
    CHECK(k->intersect16(NULL, &ray, &hit, 0xffffu, 0) == 0, "%s: NULL cylinder hit", k->name);
    CHECK(k->intersect16(good, NULL, &hit, 0xffffu, 0) == 0, "%s: NULL rays hit", k->name);
    CHECK(k->intersect16(good, &ray, NULL, 0xffffu, 0) == 0, "%s: NULL hits hit", k->name);
    CHECK(k->occluded8(NULL, (const cylray_ray8 *)(const void *)&ray, 0xffu, 0) == 0,
          "%s: NULL cylinder occluded", k->name);
    CHECK(k->occluded4(good, NULL, 0xfu, 0) == 0, "%s: NULL rays occluded", k->name);
    const cylray_rays nr = {NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL};
    const cylray_hits nh = {NULL, NULL, NULL, NULL, NULL};
    CHECK(k->intersect_stream(good, &nr, &nh, 0, CYLRAY_NORMAL) == 0,
          "%s: empty stream of NULL arrays", k->name);
    CHECK(k->occluded_stream(good, &nr, NULL, 0, 0) == 0, "%s: empty occluded stream", k->name);
    CHECK(k->intersect_stream(good, NULL, &nh, 5, 0) == 0, "%s: NULL rays stream", k->name);
    CHECK(k->intersect_stream(NULL, &nr, &nh, 5, 0) == 0, "%s: NULL cylinder stream", k->name);
}

int main(void)
{
    const cylray_kernels *isas[CYLRAY_ISA_COUNT];
    const int nisa = g_isas(isas);
    cylray_cylinder cyl[SCENE_MAX_CYL];
    const int ncyl = scene_cylinders(cyl);
    const int quick = tc_quick();
    uint64_t seed = 99;

    for (int ci = 0; ci < ncyl; ci++) {
        if (quick && ci % 3 != 0)
            continue;
        cylray_prepared P;
        if (cylray_prepare(&P, &cyl[ci]) != CYLRAY_OK) {
            CHECK(0, "scene cylinder %d refused", ci);
            continue;
        }
        gbatch rays;
        scene_rays(4242u + (uint64_t)ci, &cyl[ci], &rays, 0, G_MAX);
        for (int ii = 0; ii < nisa; ii++) {
            for (size_t fi = 0; fi < (quick ? FLAG_SETS_QUICK : FLAG_SETS_FEW); fi++) {
                masks(isas[ii], &P, &rays, flag_sets[fi], 4, &seed, quick);
                masks(isas[ii], &P, &rays, flag_sets[fi], 8, &seed, quick);
                masks(isas[ii], &P, &rays, flag_sets[fi], 16, &seed, quick);
                streams(isas[ii], &P, &rays, flag_sets[fi]);
            }
            if (ci == 0)
                refusals(isas[ii], &P, &rays);
        }
    }
    return tc_report("robust-isolation");
}
