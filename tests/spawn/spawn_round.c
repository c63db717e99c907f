/* SPDX-License-Identifier: MIT */
/* spawn_round.c - spawn_test round: the library's rounding to float. */

#include "rng.h"
#include "spawn_common.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- rounding to float --------------------------------------------------------- */

/* cylray_round_float_(x, 0) against the conversion on random doubles of every
 * magnitude a float reaches (subnormals, ties, overflow), and (hi, lo) against an exact
 * tie-break: hi a midpoint between two floats, lo of either sign. */
int run_round(void)
{
    const long N = quick ? 200000 : 20000000;
    long bad = 0, ties = 0;
    uint64_t s = 12345;
    for (long i = 0; i < N; i++) {
        uint64_t r = rng_splitmix64(&s), b;
        /* exponents from 2^-160 to 2^130; every third a float or a midpoint */
        const int ex = (int)(r % 291) - 160;
        b = ((uint64_t)(ex + 1023) << 52) | (rng_splitmix64(&s) & 0xfffffffffffffull);
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
