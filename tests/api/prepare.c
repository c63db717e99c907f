/* SPDX-License-Identifier: MIT */
/* prepare.c - cylray_prepare refuses every cylinder that describes no solid, leaves
 * *out untouched when it does, and accepts the legitimate edge cases (an infinite
 * half height, a tiny but normal axis). */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cylray.h"
#include "guarded.h"
#include "tcheck.h"

static const cylray_cylinder good = {
    {1.0f, -2.0f, 3.0f}, {0.0f, 1.0f, 1.0f}, 0.5f, 2.0f, CYLRAY_CAPPED};

/* Runs prepare on a heap copy (so AddressSanitizer sees any read past the struct) into
 * a prepared struct filled with a byte pattern, and checks the verdict; a refusal must
 * leave every byte of the pattern. */
static void expect(const cylray_cylinder *c, cylray_status want, const char *what)
{
    cylray_cylinder *in = malloc(sizeof *in);
    cylray_prepared *out = aligned_alloc(64, sizeof *out);
    unsigned char pattern[sizeof *out];
    if (!in || !out)
        exit(2);
    *in = *c;
    memset(pattern, 0xa5, sizeof pattern);
    memcpy(out, pattern, sizeof *out);
    cylray_status s = cylray_prepare(out, in);
    char cs[256];
    CHECK(s == want, "%s: prepare returned %d, expected %d (%s)", what, (int)s, (int)want,
          g_cyl_str(c, cs, sizeof cs));
    if (want != CYLRAY_OK)
        CHECK(memcmp(out, pattern, sizeof *out) == 0, "%s: refused, but *out was written",
              what);
    CHECK(memcmp(in, c, sizeof *c) == 0, "%s: prepare wrote its input", what);
    free(in);
    free(out);
}

int main(void)
{
    const float bad_coord[] = {NAN, -NAN, INFINITY, -INFINITY};
    const char *const bad_name[] = {"NaN", "-NaN", "+Inf", "-Inf"};
    char what[128];

    expect(&good, CYLRAY_OK, "the good cylinder");

    /* NaN and Inf in each coordinate of the center and of the axis. */
    for (int k = 0; k < 3; k++)
        for (int b = 0; b < 4; b++) {
            cylray_cylinder c = good;
            c.center[k] = bad_coord[b];
            snprintf(what, sizeof what, "center[%d] = %s", k, bad_name[b]);
            expect(&c, CYLRAY_EINVAL, what);
            c = good;
            c.axis[k] = bad_coord[b];
            snprintf(what, sizeof what, "axis[%d] = %s", k, bad_name[b]);
            expect(&c, CYLRAY_EINVAL, what);
        }

    /* Zero and subnormal axes: no direction, or one whose bits are mostly gone. */
    const float zero_axes[][3] = {
        {0, 0, 0},
        {-0.0f, 0, -0.0f},
        {FLT_TRUE_MIN, 0, 0},
        {0, -FLT_TRUE_MIN, 0},
        {1e-40f, 1e-40f, 1e-40f},
        {0, 0, FLT_MIN / 2},
        {-1e-39f, 0, 1e-42f},
    };
    for (size_t i = 0; i < sizeof zero_axes / sizeof zero_axes[0]; i++) {
        cylray_cylinder c = good;
        memcpy(c.axis, zero_axes[i], sizeof c.axis);
        snprintf(what, sizeof what, "axis (%a, %a, %a)", c.axis[0], c.axis[1], c.axis[2]);
        expect(&c, CYLRAY_EINVAL, what);
    }

    /* Radius: not positive, or not finite. */
    const float bad_r[] = {0.0f, -0.0f, -1.0f, -FLT_TRUE_MIN, NAN, -NAN, INFINITY, -INFINITY};
    for (size_t i = 0; i < sizeof bad_r / sizeof bad_r[0]; i++) {
        cylray_cylinder c = good;
        c.radius = bad_r[i];
        snprintf(what, sizeof what, "radius %a", c.radius);
        expect(&c, CYLRAY_EINVAL, what);
    }

    /* Half height: not positive, or NaN (INFINITY is legal: an infinite cylinder). */
    const float bad_h[] = {0.0f, -0.0f, -2.0f, -FLT_TRUE_MIN, NAN, -NAN, -INFINITY};
    for (size_t i = 0; i < sizeof bad_h / sizeof bad_h[0]; i++) {
        for (unsigned f = 0; f <= CYLRAY_CAPPED; f++) {
            cylray_cylinder c = good;
            c.half_height = bad_h[i];
            c.flags = f;
            snprintf(what, sizeof what, "half height %a, flags %u", c.half_height, f);
            expect(&c, CYLRAY_EINVAL, what);
        }
    }

    /* Unknown cylinder flag bits. */
    const unsigned bad_flags[] = {0x4u, 0x7u, 0x80u, 0x80000000u, ~0u, CYLRAY_NORMAL << 4};
    for (size_t i = 0; i < sizeof bad_flags / sizeof bad_flags[0]; i++) {
        cylray_cylinder c = good;
        c.flags = bad_flags[i];
        snprintf(what, sizeof what, "flags %#x", c.flags);
        expect(&c, CYLRAY_EINVAL, what);
    }

    /* NULL pointers: refused, nothing written, no crash. */
    {
        cylray_prepared out;
        unsigned char pattern[sizeof out];
        memset(pattern, 0x5a, sizeof pattern);
        memcpy(&out, pattern, sizeof out);
        CHECK(cylray_prepare(&out, NULL) == CYLRAY_EINVAL, "prepare(out, NULL) accepted");
        CHECK(memcmp(&out, pattern, sizeof out) == 0, "prepare(out, NULL) wrote *out");
        CHECK(cylray_prepare(NULL, &good) == CYLRAY_EINVAL, "prepare(NULL, in) accepted");
        CHECK(cylray_prepare(NULL, NULL) == CYLRAY_EINVAL, "prepare(NULL, NULL) accepted");
    }

    /* Legitimate edge cases. */
    for (unsigned f = 0; f <= CYLRAY_CAPPED; f++) {
        cylray_cylinder c = good;
        c.half_height = INFINITY;
        c.flags = f;
        snprintf(what, sizeof what, "infinite half height, flags %u", f);
        expect(&c, CYLRAY_OK, what);
    }
    {
        cylray_cylinder c = good;
        c.axis[0] = 0;
        c.axis[1] = FLT_MIN; /* the smallest normal float: still a direction */
        c.axis[2] = 0;
        expect(&c, CYLRAY_OK, "axis (0, FLT_MIN, 0)");
        c.axis[1] = -3.0f;
        c.axis[2] = 1e-30f; /* wildly different magnitudes in one axis */
        expect(&c, CYLRAY_OK, "axis (0, -3, 1e-30)");
        c = good;
        c.radius = 1e-3f;
        c.half_height = 1e-3f;
        expect(&c, CYLRAY_OK, "small radius and height");
        c = good;
        c.center[0] = -0.0f;
        expect(&c, CYLRAY_OK, "center with -0");
    }

    /* Messages: every status has one, the error's differs from success's. */
    const char *ok = cylray_strerror(CYLRAY_OK), *inv = cylray_strerror(CYLRAY_EINVAL);
    CHECK(ok && *ok, "strerror(CYLRAY_OK) gives no message");
    CHECK(inv && *inv, "strerror(CYLRAY_EINVAL) gives no message");
    CHECK(ok && inv && strcmp(ok, inv) != 0, "CYLRAY_OK and CYLRAY_EINVAL read the same");
    const char *nomem = cylray_strerror(CYLRAY_ENOMEM);
    CHECK(nomem && *nomem, "strerror(CYLRAY_ENOMEM) gives no message");
    CHECK(nomem && ok && inv && strcmp(nomem, ok) != 0 && strcmp(nomem, inv) != 0,
          "CYLRAY_ENOMEM reads as another status");
    const char *unk = cylray_strerror((cylray_status)12345);
    CHECK(unk && *unk, "strerror of an unknown status gives no message");

    return tc_report("api-prepare");
}
