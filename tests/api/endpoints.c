/* SPDX-License-Identifier: MIT */
/* endpoints.c - cylray_cylinder_from_endpoints rounds once: the axis p1 - p0, the
 * center (p0 + p1) / 2 and the half height |p1 - p0| / 2, each the float nearest the
 * exact value of the float inputs (ties to even), judged in binary128 on random pairs
 * whose exact values binary128 holds (every coordinate within 2^30 of the largest, so
 * that a sum of squares spans at most 112 bits; half of them within a factor 8 of it),
 * one pair in eight with exponents 30
 * apart, where a difference or a sum in double would round.
 *
 * And it refuses what it documents, leaving *out untouched: equal endpoints, non-finite
 * input, and every cylinder that cylray_prepare would refuse (a table of cases at and
 * beyond each of cylray_prepare's limits); what it takes, cylray_prepare takes.
 *
 * CYLRAY_TEST_QUICK=1 takes 10^4 pairs instead of 10^6. */
#include "cylray.h"
#include "quad.h"
#include "rng.h"
#include "tcheck.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static uint64_t rng_state = 0x243f6a8885a308d3ull;
static uint64_t next_u64(void)
{
    return rng_splitmix64(&rng_state);
}

/* A float in [-2^e, 2^e] with its exponent at least e - span (or zero). */
static float rand_float(int e, int span)
{
    uint64_t r = next_u64();
    if (r % 64 == 0)
        return 0.0f;
    const int ex = e - 1 - (int)((r >> 8) % (uint64_t)(span + 1));
    const float m = 1.0f + (float)((r >> 16) & 0x7fffff) * 0x1p-23f;
    return ldexpf(r >> 63 ? -m : m, ex);
}

/* f is x rounded to nearest float, ties to even (x exact in binary128, f finite). */
static int is_nearest(float f, cylq x)
{
    const float up = nextafterf(f, INFINITY), dn = nextafterf(f, -INFINITY);
    const cylq hi = ((cylq)f + (cylq)up) / 2, lo = ((cylq)f + (cylq)dn) / 2;
    uint32_t b;
    memcpy(&b, &f, sizeof b);
    const int even = (b & 1u) == 0;
    return (x < hi || (x == hi && even)) && (x > lo || (x == lo && even));
}

/* |a|/2 rounded to nearest: f against the squared midpoints, S = |a|^2 exact. */
static int half_norm_nearest(float f, cylq S)
{
    if (!(f > 0))
        return 0;
    const float up = nextafterf(f, INFINITY), dn = nextafterf(f, 0.0f);
    const cylq hi = (cylq)f + (cylq)up, lo = (cylq)f + (cylq)dn; /* 2 x the midpoints */
    uint32_t b;
    memcpy(&b, &f, sizeof b);
    const int even = (b & 1u) == 0;
    return (S < hi * hi || (S == hi * hi && even)) && (S > lo * lo || (S == lo * lo && even));
}

/* The documented refusals, each beside a case just inside the same limit. */
static long refusals(void)
{
    const float inf = INFINITY, nan = NAN, big = 0x1p62f;
    const struct {
        float p0[3], p1[3], r;
        unsigned flags;
        int ok;
        const char *what;
    } t[] = {
        {{0, 0, 0}, {0, 0, 1}, 1.0f, CYLRAY_CAPPED, 1, "ordinary"},
        {{1, 2, 3}, {1, 2, 3}, 1.0f, CYLRAY_CAPPED, 0, "equal endpoints"},
        {{0, 0, 0}, {0, 0, 1}, 0.0f, CYLRAY_CAPPED, 0, "radius 0"},
        {{0, 0, 0}, {0, 0, 1}, -1.0f, CYLRAY_CAPPED, 0, "negative radius"},
        {{0, 0, 0}, {0, 0, 1}, 0x1p-61f, 0, 0, "radius below 2^-60"},
        {{0, 0, 0}, {0, 0, 1}, 0x1p-60f, 0, 1, "radius 2^-60"},
        {{0, 0, 0}, {0, 0, 1}, 0x1p62f, 0, 1, "radius 2^62"},
        {{0, 0, 0}, {0, 0, 1}, 0x1p63f, 0, 0, "radius 2^63"},
        {{0, 0, 0}, {0, 0, 1}, inf, 0, 0, "infinite radius"},
        {{0, 0, 0}, {0, 0, 1}, nan, 0, 0, "NaN radius"},
        {{0, 0, 0}, {0, 0, 1}, 1.0f, CYLRAY_CAPPED_LO, 1, "one disc"},
        {{0, 0, 0}, {0, 0, 1}, 1.0f, 0x10u, 0, "unknown flag bit"},
        {{0, 0, 0}, {0, 0, 1}, 1.0f, 0x80000000u, 0, "high flag bit"},
        {{nan, 0, 0}, {0, 0, 1}, 1.0f, 0, 0, "NaN endpoint"},
        {{0, 0, 0}, {0, inf, 1}, 1.0f, 0, 0, "infinite endpoint"},
        {{big, 0, 0}, {big, 1, 0}, 1.0f, 0, 1, "center at 2^62"},
        {{-big, 0, 0}, {big, 0, 0}, 1.0f, 0, 0, "axis 2^63 long"},
        {{1.5f * big, 0, 0}, {1.5f * big, 1, 0}, 1.0f, 0, 0, "center beyond 2^62"},
        {{0, 0, 0}, {0x1p-140f, 0, 0}, 1.0f, 0, 0, "subnormal axis"},
        {{0, 0, 0}, {0x1p-126f, 0, 0}, 1.0f, 0, 1, "axis of FLT_MIN"},
    };
    long bad = 0;
    for (size_t i = 0; i < sizeof t / sizeof t[0]; i++) {
        cylray_cylinder c, before;
        memset(&c, 0xa5, sizeof c);
        before = c;
        const cylray_status st =
            cylray_cylinder_from_endpoints(&c, t[i].p0, t[i].p1, t[i].r, t[i].flags);
        cylray_prepared p;
        const int took = st == CYLRAY_OK;
        if (took != t[i].ok || (took && cylray_prepare(&p, &c) != CYLRAY_OK) ||
            (!took && (st != CYLRAY_EINVAL || memcmp(&c, &before, sizeof c) != 0))) {
            fprintf(stderr, "FAIL refusal: %s: status %d, expected %s\n", t[i].what, (int)st,
                    t[i].ok ? "success" : "CYLRAY_EINVAL with *out untouched");
            bad++;
        }
    }
    return bad;
}

int main(void)
{
    const long bad_refusals = refusals();
    const int quick = tc_quick();
    const long N = quick ? 10000 : 1000000;
    long tried = 0, bad_h = 0, bad_a = 0, bad_c = 0, refused = 0, far = 0;
    for (long n = 0; n < N; n++) {
        float p0[3], p1[3];
        /* one pair in eight: exponents 30 apart (a point near the origin and one far
         * away) */
        const int far_apart = n % 8 == 7;
        const int e = (int)(next_u64() % 40) - 20;
        for (int k = 0; k < 3; k++) {
            /* half of them in a box, as scene data is; the rest spread over 2^29 */
            const int span = n % 2 ? 29 : 2;
            p0[k] = rand_float(e, far_apart ? 20 : span);
            p1[k] = far_apart ? rand_float(e - 30, 0) : rand_float(e, span);
        }
        far += far_apart;
        cylray_cylinder c;
        if (cylray_cylinder_from_endpoints(&c, p0, p1, 1.0f, CYLRAY_CAPPED) != CYLRAY_OK) {
            refused++;
            continue;
        }
        tried++;
        cylq S = 0;
        for (int k = 0; k < 3; k++) {
            const cylq a = (cylq)p1[k] - (cylq)p0[k];
            S += a * a;
            if (!is_nearest(c.axis[k], a))
                bad_a++;
            if (!is_nearest(c.center[k], ((cylq)p0[k] + (cylq)p1[k]) / 2))
                bad_c++;
        }
        if (!half_norm_nearest(c.half_height, S)) {
            if (bad_h++ < 10)
                fprintf(stderr,
                        "FAIL half height: p0 (%a %a %a) p1 (%a %a %a): %a, exact %.17g\n",
                        p0[0], p0[1], p0[2], p1[0], p1[1], p1[2], c.half_height, (double)S);
        }
    }
    printf("endpoints: %ld pairs (%ld with exponents far apart), %ld refused; not rounded "
           "once: half height %ld, axis %ld, center %ld; documented refusals wrong: %ld\n",
           tried, far, refused, bad_h, bad_a, bad_c, bad_refusals);
    return bad_h == 0 && bad_a == 0 && bad_c == 0 && bad_refusals == 0 && tried > N / 2 ? 0 : 1;
}
