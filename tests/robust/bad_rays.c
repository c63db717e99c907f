/* SPDX-License-Identifier: MIT */
/* bad_rays.c - one bad lane among good ones, on every ISA and width.
 *
 * A "victim" ray is damaged in one field (NaN, -NaN, a signalling NaN, +-Inf, 1e30,
 * FLT_MAX, a subnormal...) or as a whole (zero direction, tmin > tmax, ...) and put in
 * one lane of a packet or stream whose other lanes hold ordinary rays. Then:
 *   - every other lane is bit-identical to the run without the damage;
 *   - the damaged lane, by the kind of damage:
 *       MISS   must miss (NaN anywhere, an infinite origin or direction, tmin > tmax,
 *              tmin = +Inf, tmax = -Inf, a zero direction);
 *       SAME   must equal, bit for bit, the same ray with a finite stand-in
 *              (tmax = +Inf as tmax = FLT_MAX, tmin = -Inf as -FLT_MAX);
 *       VALID  is a finite ray with a meaningful answer (negative tmin, huge or
 *              subnormal values): a hit must be on the surface (hitcheck.h), and the
 *              outcome must be one the exact reference allows (tests/ref, cylref_judge),
 *              except that beyond the kernel's working range (in_range below) a miss
 *              is allowed;
 *   - in packets, the damaged lane inactive changes nothing and is never written.
 * The guarded runner adds its memory checks (canaries, poison) to every call. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cylray.h"
#include "flagsets.h"
#include "guarded.h"
#include "hitcheck.h"
#include "scene.h"
#include "tcheck.h"
#ifdef HAVE_CYLREF
#include "cylref.h"
#endif

enum expect { MISS, SAME, VALID };

typedef struct bad {
    char name[64];
    float ray[G_NFIELD];
    enum expect expect;
    float alt[G_NFIELD]; /* SAME: the stand-in ray */
#ifdef HAVE_CYLREF
    cylref_band band[2]; /* VALID: without and with CYLRAY_CULL_BACK */
#endif
} bad;

#define MAX_BAD 128
static const char *const field_name[G_NFIELD] = {"ox", "oy", "oz",   "dx",
                                                 "dy", "dz", "tmin", "tmax"};

static int add(bad *out, int n, const char *name, const float ray[G_NFIELD], enum expect e,
               const float *alt)
{
    if (n >= MAX_BAD)
        abort();
    snprintf(out[n].name, sizeof out[n].name, "%s", name);
    memcpy(out[n].ray, ray, sizeof out[n].ray);
    out[n].expect = e;
    if (alt)
        memcpy(out[n].alt, alt, sizeof out[n].alt);
    return n + 1;
}

/* Every damage of the victim, with what it must give. */
static int make_bad(const float v[G_NFIELD], bad *out)
{
    const float snan = g_bits(0x7f800001u), nsnan = g_bits(0xffc00001u);
    const float values[] = {NAN,    -NAN,    0,      INFINITY,      -INFINITY, 1e30f,
                            -1e30f, FLT_MAX, 1e-40f, -FLT_TRUE_MIN, -0.0f};
    const char *const vname[] = {"NaN",   "-NaN",    "sNaN",  "+Inf",        "-Inf", "1e30",
                                 "-1e30", "FLT_MAX", "1e-40", "-denorm_min", "-0"};
    int n = 0;
    char name[64];
    for (int f = 0; f < G_NFIELD; f++)
        for (size_t k = 0; k < sizeof values / sizeof values[0]; k++) {
            float r[G_NFIELD], alt[G_NFIELD];
            memcpy(r, v, sizeof r);
            memcpy(alt, v, sizeof alt);
            float x = k == 2 ? (f & 1 ? nsnan : snan) : values[k];
            r[f] = x;
            snprintf(name, sizeof name, "%s = %s", field_name[f], vname[k]);
            enum expect e;
            if (isnan(x))
                e = MISS;
            else if (f < G_TMIN)
                e = isinf(x) ? MISS : VALID;
            else if (f == G_TMIN)
                e = x == INFINITY ? MISS : x == -INFINITY ? SAME : VALID;
            else
                e = x == -INFINITY ? MISS : x == INFINITY ? SAME : VALID;
            if (e == SAME)
                alt[f] = x > 0 ? FLT_MAX : -FLT_MAX;
            n = add(out, n, name, r, e, e == SAME ? alt : NULL);
        }
    /* Damage to the ray as a whole. */
    const struct {
        const char *name;
        int fields; /* bit f: replace field f */
        float val[G_NFIELD];
        enum expect e;
    } whole[] = {
        {"zero direction", 0x38, {0, 0, 0, 0, 0, 0, 0, 0}, MISS},
        {"-0 direction", 0x38, {0, 0, 0, -0.0f, -0.0f, -0.0f, 0, 0}, MISS},
        {"subnormal direction", 0x38, {0, 0, 0, 1e-40f, -1e-40f, 3e-39f, 0, 0}, VALID},
        {"direction 1e-20", 0x38, {0, 0, 0, 1e-20f, 2e-20f, -1e-20f, 0, 0}, VALID},
        {"direction 1e20", 0x38, {0, 0, 0, 1e20f, 2e20f, -1e20f, 0, 0}, VALID},
        {"tmin > tmax", 0xc0, {0, 0, 0, 0, 0, 0, 2, 1}, MISS},
        {"tmin = tmax = 0", 0xc0, {0, 0, 0, 0, 0, 0, 0, 0}, VALID},
        {"tmin = -tmax", 0xc0, {0, 0, 0, 0, 0, 0, -1e3f, 1e3f}, VALID},
        {"tmin = -Inf, tmax = +Inf", 0xc0, {0, 0, 0, 0, 0, 0, -INFINITY, INFINITY}, SAME},
        {"every field NaN", 0xff, {NAN, NAN, NAN, NAN, NAN, NAN, NAN, NAN}, MISS},
        {"origin 1e30", 0x07, {1e30f, -1e30f, 1e30f, 0, 0, 0, 0, 0}, VALID},
        {"origin subnormal", 0x07, {1e-40f, -1e-41f, 1e-42f, 0, 0, 0, 0, 0}, VALID},
    };
    for (size_t w = 0; w < sizeof whole / sizeof whole[0]; w++) {
        float r[G_NFIELD], alt[G_NFIELD];
        memcpy(r, v, sizeof r);
        for (int f = 0; f < G_NFIELD; f++)
            if (whole[w].fields & (1 << f))
                r[f] = whole[w].val[f];
        memcpy(alt, r, sizeof alt);
        if (whole[w].e == SAME) {
            alt[G_TMIN] = -FLT_MAX;
            alt[G_TMAX] = FLT_MAX;
        }
        n = add(out, n, whole[w].name, r, whole[w].e, whole[w].e == SAME ? alt : NULL);
    }
    return n;
}

static void put(gbatch *b, size_t i, const float r[G_NFIELD])
{
    for (int f = 0; f < G_NFIELD; f++)
        b->f[f][i] = r[f];
}

/* The range the kernel works in. cylray_prepare refuses cylinders with coordinates
 * beyond 2^62 (src/api/prepare.c); an origin 2^62 from the center overflows the float
 * products. Such a ray may miss: cylray.h does not promise more. Any finite nonzero
 * direction is in range (the kernels scale it by a power of two), as long as the
 * answer's t is a float. Out of range, a ray must still never hit falsely. */
static int in_range(const cylray_cylinder *c, const float r[G_NFIELD], double exact_t)
{
    for (int k = 0; k < 3; k++)
        if (!(fabs((double)r[G_OX + k] - c->center[k]) <= 0x1p62))
            return 0;
    return fabs(exact_t) <= FLT_MAX;
}

/* Judges the damaged lane j of r. */
static void judge_bad(const cylray_cylinder *cyl, const bad *d, const gresult *r, size_t j,
                      unsigned flags, const gresult *alt, const char *ctx)
{
    char rs[256], why[256];
    const int hit = (int)((r->hit >> j) & 1u);
    g_cyl_str(cyl, rs, sizeof rs);
    switch (d->expect) {
    case MISS:
        CHECK(!hit, "%s lane %zu [%s]: hit at t %a, part %#x; must miss (%s)", ctx, j, d->name,
              r->t[j], (unsigned)r->part[j], rs);
        break;
    case SAME:
        /* tmax itself differs on a miss (it is the stand-in's); on a hit both are t */
        CHECK(hit == (int)((alt->hit >> j) & 1u) &&
                  (!hit || g_same_lane(r, j, alt, j, (flags & CYLRAY_NORMAL) != 0)),
              "%s lane %zu [%s]: differs from the finite stand-in (t %a/%a, hit %d/%d)", ctx, j,
              d->name, r->t[j], alt->t[j], hit, (int)((alt->hit >> j) & 1u));
        break;
    case VALID: {
        const double slack = (flags & CYLRAY_FAST) ? 16 : 1;
        if (hit) {
            const float n[3] = {r->nx[j], r->ny[j], r->nz[j]};
            int v = hc_verify(cyl, d->ray, d->ray + 3, d->ray[G_TMIN], d->ray[G_TMAX], r->t[j],
                              r->part[j], n, flags, slack, why, sizeof why);
            CHECK(v == 0, "%s lane %zu [%s]: impossible hit: %s (%s)", ctx, j, d->name, why,
                  rs);
        }
#ifdef HAVE_CYLREF
        const cylref_band *b = &d->band[(flags & CYLRAY_CULL_BACK) != 0];
        double beyond = 0;
        int verdict = cylref_judge(b, hit, r->part[j], r->t[j], &beyond);
        /* out of range, a miss is allowed; a hit must still be right */
        if (verdict == 1 && !hit && !in_range(cyl, d->ray, b->exact.t))
            verdict = 0;
        CHECK(verdict == 0,
              "%s lane %zu [%s]: %s (t %a part %#x), exact: %s at %.17g part %#x (%s)", ctx, j,
              d->name,
              verdict == 1 ? (hit ? "false hit" : "missed hit")
                           : "part differs from the exact answer",
              r->t[j], (unsigned)r->part[j], b->exact.hit ? "hit" : "miss", b->exact.t,
              (unsigned)b->exact.part, rs);
        const double tol = (flags & CYLRAY_FAST) ? 256 : 16;
        CHECK(verdict != 0 || !hit || beyond <= tol,
              "%s lane %zu [%s]: t %a is %.3g ulps beyond the exact band [%.17g, %.17g] (%s)",
              ctx, j, d->name, r->t[j], beyond, b->t_lo, b->t_hi, rs);
#endif
        break;
    }
    }
}

int main(void)
{
    const cylray_kernels *isas[CYLRAY_ISA_COUNT];
    const int nisa = g_isas(isas);
    cylray_cylinder cyl[SCENE_MAX_CYL];
    const int ncyl = scene_cylinders(cyl);
    const int quick = tc_quick();
    const int widths[] = {4, 8, 16, G_STREAM};
    const size_t stream_n = 16 + 3; /* whole vectors and a tail */
    static bad bads[MAX_BAD];
    char ctx[160];

    /* Cylinders: an open tube, an oblique capped one, an infinite one, the far small one. */
    const int use[] = {1, 5, 7, 9};
    for (size_t ui = 0; ui < sizeof use / sizeof use[0]; ui++) {
        const cylray_cylinder *c = &cyl[use[ui]];
        if (use[ui] >= ncyl)
            continue;
        cylray_prepared P;
        CHECK(cylray_prepare(&P, c) == CYLRAY_OK, "scene cylinder %d refused", use[ui]);
        gbatch base;
        scene_rays(777u + (uint64_t)ui, c, &base, 0, G_MAX);

        /* Two victims: the first ray the scalar path hits, and the first it misses. */
        gresult sr;
        g_intersect(isas[0], G_STREAM, &P, &base, G_MAX, 0, 0, 0, &sr);
        for (int want_hit = 1; want_hit >= 0; want_hit--) {
            size_t vi = 0;
            while (vi < G_MAX && (int)((sr.hit >> vi) & 1u) != want_hit)
                vi++;
            if (vi == G_MAX)
                continue;
            float victim[G_NFIELD];
            for (int f = 0; f < G_NFIELD; f++)
                victim[f] = base.f[f][vi];
            const int nbad = make_bad(victim, bads);
#ifdef HAVE_CYLREF
            for (int bi = 0; bi < nbad; bi++)
                if (bads[bi].expect == VALID)
                    for (int cull = 0; cull < 2; cull++)
                        cylref_band_eval(c, bads[bi].ray, bads[bi].ray + 3,
                                         bads[bi].ray[G_TMIN], bads[bi].ray[G_TMAX],
                                         cull ? CYLRAY_CULL_BACK : 0u, &bads[bi].band[cull]);
#endif
            for (int ii = 0; ii < nisa; ii++)
                for (size_t fi = 0; fi < (quick ? FLAG_SETS_QUICK : FLAG_SETS_FEW); fi++) {
                    const unsigned flags = flag_sets[fi];
                    for (int wi = 0; wi < 4; wi++) {
                        const int w = widths[wi];
                        const size_t n = w == G_STREAM ? stream_n : (size_t)w;
                        const uint32_t all = w == G_STREAM ? 0 : (uint32_t)((1ull << w) - 1u);
                        /* the victim's lane: first, last, one inside, and for the
                         * stream one in the tail (quick: first and last) */
                        const size_t lanes[4] = {0, n - 1, n / 2 + 1, n - 2};
                        for (int li = 0; li < (quick ? 2 : w == G_STREAM ? 4 : 3); li++) {
                            const size_t j = lanes[li];
                            gbatch b = base;
                            gresult r0, r, ralt;
                            memset(&ralt, 0, sizeof ralt);
                            /* clean: the victim itself in lane j */
                            put(&b, j, victim);
                            g_intersect(isas[ii], w, &P, &b, n, all, flags, (unsigned)j & 3u,
                                        &r0);
                            for (int bi = 0; bi < nbad; bi++) {
                                const bad *d = &bads[bi];
                                snprintf(ctx, sizeof ctx, "%s w=%s flags=%#x cyl %d",
                                         isas[ii]->name, g_width_name(w), flags, use[ui]);
                                put(&b, j, d->ray);
                                g_intersect(isas[ii], w, &P, &b, n, all, flags,
                                            (unsigned)j & 3u, &r);
                                for (size_t i = 0; i < n; i++)
                                    if (i != j)
                                        CHECK(g_same_lane(&r, i, &r0, i,
                                                          (flags & CYLRAY_NORMAL) != 0),
                                              "%s: lane %zu changed when lane %zu became "
                                              "[%s]",
                                              ctx, i, j, d->name);
                                if (d->expect == SAME) {
                                    put(&b, j, d->alt);
                                    g_intersect(isas[ii], w, &P, &b, n, all, flags,
                                                (unsigned)j & 3u, &ralt);
                                }
                                judge_bad(c, d, &r, j, flags, &ralt, ctx);
                                /* packets: the damaged lane inactive */
                                if (w != G_STREAM && !quick) {
                                    put(&b, j, d->ray);
                                    g_intersect(isas[ii], w, &P, &b, n, all & ~(1u << j), flags,
                                                0, &r);
                                    for (size_t i = 0; i < n; i++)
                                        if (i != j)
                                            CHECK(g_same_lane(&r, i, &r0, i,
                                                              (flags & CYLRAY_NORMAL) != 0),
                                                  "%s: lane %zu changed when inactive lane "
                                                  "%zu held [%s]",
                                                  ctx, i, j, d->name);
                                }
                                put(&b, j, victim);
                            }
                        }
                    }
                }
        }
    }
    return tc_report("robust-bad-rays");
}
