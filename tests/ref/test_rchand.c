/* SPDX-License-Identifier: MIT */
/* test_rchand.c - the exact round-cone reference against cases worked out by hand (dyadic
 * inputs whose answers are known exactly), the shapes it must refuse and those at the
 * limits it must take. */
#include "test_ref.h"

#include <math.h>

void test_hand_round_cone(void)
{
    const float I = INFINITY;
    const unsigned CAP = CYLRAY_CAPPED, LOC = CYLRAY_CAPPED_LO, HIC = CYLRAY_CAPPED_HI;
    const unsigned FF = CYLRAY_FACE_FORWARD, CB = CYLRAY_CULL_BACK;
    const int S = CYLRAY_SIDE, SB = CYLRAY_SIDE | CYLRAY_BACKFACE, LO = CYLRAY_CAP_LO,
              HI = CYLRAY_CAP_HI, HB = CYLRAY_CAP_HI | CYLRAY_BACKFACE;
    /* A capsule along z: radius 1 from p0 = 0 to p1 = (0, 0, 2); its seams are the
     * circles of radius 1 at z = 0 and z = 2. */
    const rcref_round_cone cap = {{0, 0, 0}, {0, 0, 2}, 1, 1, CAP};
    const rcref_round_cone cap_hi = {{0, 0, 0}, {0, 0, 2}, 1, 1, HIC};
    /* A point end at p0 and a sphere of radius 1 at p1 = (0, 0, 2): sin(alpha) = 1/2,
     * n_rho = sqrt(3)/2, the cone's radius z / sqrt(3), the seam at z = 2 - 1/2. */
    const rcref_round_cone tip = {{0, 0, 0}, {0, 0, 2}, 0, 1, CAP};
    const rcref_round_cone tip_open = {{0, 0, 0}, {0, 0, 2}, 0, 1, 0};
    /* 3-4-5: radius 3 at p0, a point at p1 = (0, 0, 5): k = -3/5, n_rho = 4/5, the seam
     * at z = 9/5 (radius 12/5), the cone's radius 15/4 - 3z/4. */
    const rcref_round_cone tri = {{0, 0, 0}, {0, 0, 5}, 3, 0, CAP};
    /* Nested: the sphere of radius 2 at (0, 0, 1/4) holds the one of radius 1/2 at 0. */
    const rcref_round_cone nest_lo = {{0, 0, 0}, {0, 0, 0.25f}, 0.5f, 2, LOC};
    const rcref_round_cone nest_hi = {{0, 0, 0}, {0, 0, 0.25f}, 0.5f, 2, HIC};
    const rcref_round_cone one = {{1, 2, 3}, {1, 2, 3}, 1, 1, LOC};
    const rcref_round_cone one_hi = {{1, 2, 3}, {1, 2, 3}, 1, 1, HIC};
    const rcref_round_cone one_open = {{1, 2, 3}, {1, 2, 3}, 1, 1, 0};
    const rcref_round_cone one_small_capped = {{1, 2, 3}, {1, 2, 3}, 1, 0.5f, HIC};
    const double s3 = sqrt(3.0);
    /* a case a line, as a table reads */
    /* clang-format off */
    const ref_hand cases[] = {
        {"capsule side", {.rc = cap}, {5, 0, 1}, {-1, 0, 0}, 0, I, 0, 1, 4, S, {1, 0, 0}},
        {"capsule side, unnormalized d", {.rc = cap}, {5, 0, 1}, {-2, 0, 0}, 0, I, 0, 1, 2, S, {1, 0, 0}},
        {"capsule cap hi", {.rc = cap}, {0, 0, 5}, {0, 0, -1}, 0, I, 0, 1, 2, HI, {0, 0, 1}},
        {"capsule cap lo", {.rc = cap}, {0, 0, -5}, {0, 0, 1}, 0, I, 0, 1, 4, LO, {0, 0, -1}},
        {"capsule cap lo off the axis", {.rc = cap}, {0.6f, 0, -5}, {0, 0, 1}, 0, I, 0, 1, 5 - sqrt(1 - (double)0.6f * 0.6f), LO, {0.6f, 0, -sqrt(1 - (double)0.6f * 0.6f)}},
        /* (2, 0, -1) + t (-1, 0, 1) meets sphere 0 at t = 1, 2, the cylinder at t = 1, 3,
        * sphere 1 at t = 2, 3: it enters through the seam (1, 0, 0) and leaves through
        * the other, (-1, 0, 2), both of them the side's. */
        {"through a seam", {.rc = cap}, {2, 0, -1}, {-1, 0, 1}, 0, I, 0, 1, 1, S, {1, 0, 0}},
        {"through a seam, lo open", {.rc = cap_hi}, {2, 0, -1}, {-1, 0, 1}, 0, I, 0, 1, 1, S, {1, 0, 0}},
        {"out through the other seam", {.rc = cap}, {2, 0, -1}, {-1, 0, 1}, 2, I, 0, 1, 3, SB, {-1, 0, 0}},
        /* along the generator line x = 1: it touches the hull from z = 0 to z = 2 */
        {"along a generator line", {.rc = cap}, {1, 0, -5}, {0, 0, 1}, 0, I, 0, 1, 5, S, {1, 0, 0}},
        {"along a generator line, from on it", {.rc = cap}, {1, 0, -5}, {0, 0, 1}, 6, I, 0, 1, 6, S, {1, 0, 0}},
        {"tangent to a cap", {.rc = cap}, {-5, 0, 3}, {1, 0, 0}, 0, I, 0, 1, 5, HI, {0, 0, 1}},
        {"from inside", {.rc = cap}, {0, 0, 1}, {1, 0, 0}, 0, I, 0, 1, 1, SB, {1, 0, 0}},
        {"from inside, face forward", {.rc = cap}, {0, 0, 1}, {1, 0, 0}, 0, I, FF, 1, 1, SB, {-1, 0, 0}},
        {"from inside, culled", {.rc = cap}, {0, 0, 1}, {1, 0, 0}, 0, I, CB, 0, 0, 0, {0}},
        {"from inside through a cap", {.rc = cap}, {0, 0, 1}, {0, 0, 1}, 0, I, 0, 1, 2, HB, {0, 0, 1}},
        /* (-1, 0, -3/2) + t (1, 0, 1): in through sphere 0 at z < 0 (open: a hole), out
        * through the side at t = 2, (1, 0, 1/2) */
        {"through the open end onto the side's inside", {.rc = cap_hi}, {-1, 0, -1.5f}, {1, 0, 1}, 0, I, 0, 1, 2, SB, {1, 0, 0}},
        {"through the open end, culled", {.rc = cap_hi}, {-1, 0, -1.5f}, {1, 0, 1}, 0, I, CB, 0, 0, 0, {0}},
        {"through the open end and out of the cap", {.rc = cap_hi}, {0.6f, 0, -5}, {0, 0, 1}, 0, I, 0, 1, 7 + sqrt(1 - (double)0.6f * 0.6f), HB, {0.6f, 0, sqrt(1 - (double)0.6f * 0.6f)}},
        {"tmax short", {.rc = cap}, {5, 0, 1}, {-1, 0, 0}, 0, 3.5f, 0, 0, 0, 0, {0}},
        {"tmax at the hit", {.rc = cap}, {5, 0, 1}, {-1, 0, 0}, 0, 4, 0, 1, 4, S, {1, 0, 0}},
        {"point end: its apex", {.rc = tip}, {0, 0, -5}, {0, 0, 1}, 0, I, 0, 1, 5, S, {0}},
        {"point end: its apex, no flags", {.rc = tip_open}, {0, 0, -5}, {0, 0, 1}, 0, I, 0, 1, 5, S, {0}},
        {"point end: the side", {.rc = tip}, {5, 0, 1}, {-1, 0, 0}, 0, I, 0, 1, 5 - 1 / s3, S, {s3 / 2, 0, -0.5}},
        {"point end: the sphere", {.rc = tip}, {0, 0, 5}, {0, 0, -1}, 0, I, 0, 1, 2, HI, {0, 0, 1}},
        {"point end: the sphere open", {.rc = tip_open}, {0.25f, 0, 5}, {0, 0, -1}, 0, I, 0, 1, 5 - 0.25 * s3, SB, {s3 / 2, 0, -0.5}},
        {"3-4-5: side", {.rc = tri}, {10, 0, 3}, {-1, 0, 0}, 0, I, 0, 1, 8.5, S, {0.8, 0, 0.6}},
        {"3-4-5: cap lo", {.rc = tri}, {0, 0, -10}, {0, 0, 1}, 0, I, 0, 1, 7, LO, {0, 0, -1}},
        {"3-4-5: the apex", {.rc = tri}, {0, 0, 10}, {0, 0, -1}, 0, I, 0, 1, 5, S, {0}},
        {"3-4-5: the sphere below the seam", {.rc = tri}, {10, 0, 1}, {-1, 0, 0}, 0, I, 0, 1, 10 - sqrt(8.0), LO, {sqrt(8.0) / 3, 0, 1.0 / 3}},
        {"nested, the larger's end open", {.rc = nest_lo}, {0, 0, 5}, {0, 0, -1}, 0, I, 0, 0, 0, 0, {0}},
        {"nested, the larger's end open, from inside", {.rc = nest_lo}, {0, 0, 0}, {1, 0, 0}, 0, I, 0, 0, 0, 0, {0}},
        {"nested", {.rc = nest_hi}, {0, 0, 5}, {0, 0, -1}, 0, I, 0, 1, 2.75, HI, {0, 0, 1}},
        {"nested, from inside the smaller", {.rc = nest_hi}, {0, 0, 0}, {0, 0, -1}, 0, I, 0, 1, 1.75, HB, {0, 0, -1}},
        {"zero length", {.rc = one}, {1, 2, -3}, {0, 0, 1}, 0, I, 0, 1, 5, LO, {0, 0, -1}},
        {"zero length, hi only", {.rc = one_hi}, {1, 2, -3}, {0, 0, 1}, 0, I, 0, 1, 5, HI, {0, 0, -1}},
        {"zero length, no flags", {.rc = one_open}, {1, 2, -3}, {0, 0, 1}, 0, I, 0, 0, 0, 0, {0}},
        {"zero length, the larger's end open", {.rc = one_small_capped}, {1, 2, -3}, {0, 0, 1}, 0, I, 0, 0, 0, 0, {0}},
        {"NaN origin", {.rc = cap}, {NAN, 0, 1}, {-1, 0, 0}, 0, I, 0, 0, 0, 0, {0}},
        {"zero direction", {.rc = cap}, {5, 0, 1}, {0, 0, 0}, 0, I, 0, 0, 0, 0, {0}},
    };
    /* clang-format on */
    ref_run_hand(&ref_round_cone, cases, sizeof cases / sizeof cases[0]);

    const float big = 0x1p63f;
    const ref_shape bad[] = {
        {.rc = {{NAN, 0, 0}, {0, 0, 1}, 1, 1, 0}},
        {.rc = {{0, 0, 0}, {0, INFINITY, 1}, 1, 1, 0}},
        {.rc = {{0, 0, big}, {0, 0, 1}, 1, 1, 0}},
        {.rc = {{0, 0, 0}, {0, 0, 1}, 0, 0, 0}},
        {.rc = {{0, 0, 0}, {0, 0, 1}, -1, 1, 0}},
        {.rc = {{0, 0, 0}, {0, 0, 1}, NAN, 1, 0}},
        {.rc = {{0, 0, 0}, {0, 0, 1}, 1, INFINITY, 0}},
        {.rc = {{0, 0, 0}, {0, 0, 1}, 1, 0x1p-61f, 0}},
        {.rc = {{0, 0, 0}, {0, 0, 1}, big, 1, 0}},
        {.rc = {{0, 0, 0}, {0, 0, 1}, 1, 1, 4}},
    };
    const float o[3] = {5, 0, 0.5f}, d[3] = {-1, 0, 0};
    ref_run_refused(&ref_round_cone, bad, sizeof bad / sizeof bad[0], o, d);
    const ref_shape edge[] = {
        {.rc = {{0, 0, 0}, {0, 0, 1}, 0x1p-60f, 0x1p-60f, CAP}},
        {.rc = {{0, 0, 0}, {0, 0, 1}, 0x1p62f, 0, CAP}},
        {.rc = {{0x1p62f, -0x1p62f, 0}, {-0x1p62f, 0x1p62f, 0}, 1, 1, 0}},
        {.rc = {{1, 1, 1}, {1, 1, 1}, 1, 0, LOC}},
        {.rc = {{0, 0, 0}, {0, 0, 0x1p-140f}, 1, 1, HIC}},
    };
    ref_run_valid(&ref_round_cone, edge, sizeof edge / sizeof edge[0]);
}

/* The band at rays made by hand: what it must allow and what it must not. */
void test_band_round_cone(void)
{
    const rcref_round_cone cap = {{0, 0, 0}, {0, 0, 2}, 1, 1, CYLRAY_CAPPED};
    const rcref_round_cone cap_hi = {{0, 0, 0}, {0, 0, 2}, 1, 1, CYLRAY_CAPPED_HI};
    cylref_band b;
    double ub;
    /* an ordinary side hit at t = 4: stable and narrow */
    const float o[3] = {5, 0, 1.25f}, d[3] = {-1, 0, 0.125f};
    rcref_band_eval(&cap, o, d, 0, INFINITY, 0, &b);
    CHECK(b.exact.hit && b.exact.t == 4 && !b.decision_unstable, "ordinary: unstable");
    CHECK(cylref_ulps((float)b.t_lo, 4) < 40 && cylref_ulps((float)b.t_hi, 4) < 40,
          "ordinary: band [%a, %a] too wide", b.t_lo, b.t_hi);
    CHECK(b.evals >= 60 && b.evals <= 160, "evals %d", b.evals);
    CHECK(rcref_judge(&b, 1, CYLRAY_SIDE, 4.0f, &ub) == 0 && ub == 0, "ordinary: exact");
    CHECK(rcref_judge(&b, 1, CYLRAY_CAP_HI, 4.0f, &ub) == 2, "ordinary: the cap allowed");
    CHECK(rcref_judge(&b, 0, 0, 0, &ub) == 1, "ordinary: a miss allowed");
    /* t = tmax: hit or miss */
    rcref_band_eval(&cap, o, d, 0, 4, 0, &b);
    CHECK(b.exact.hit && b.hit_unstable, "t = tmax: stable?");

    /* exactly through a seam: a hit for sure, the side or the cap */
    const float os[3] = {2, 0, -1}, ds[3] = {-1, 0, 1};
    rcref_band_eval(&cap, os, ds, 0, INFINITY, 0, &b);
    CHECK(b.exact.hit && !b.hit_unstable && b.part_unstable,
          "seam: hit %d hit_unstable %d part_unstable %d", b.exact.hit, b.hit_unstable,
          b.part_unstable);
    CHECK(rcref_judge(&b, 1, CYLRAY_SIDE, 1.0f, &ub) == 0 && ub == 0, "seam: the side refused");
    CHECK(rcref_judge(&b, 1, CYLRAY_CAP_LO, 1.0f, &ub) == 0 && ub == 0,
          "seam: the cap refused");
    CHECK(rcref_judge(&b, 0, 0, 0, &ub) == 1, "seam: a miss allowed");
    /* ... with that end open: the side at the rim, or through the hole to the exit */
    rcref_band_eval(&cap_hi, os, ds, 0, INFINITY, 0, &b);
    CHECK(b.exact.hit && b.exact.part == CYLRAY_SIDE, "open seam: exact part %#x",
          b.exact.part);
    CHECK(rcref_judge(&b, 1, CYLRAY_SIDE, 1.0f, &ub) == 0 && ub == 0,
          "open seam: the side refused");
    CHECK(rcref_judge(&b, 1, CYLRAY_CAP_LO, 1.0f, &ub) != 0, "open seam: the hole hit");

    /* tangent to a cap: hit or miss */
    const float ot[3] = {-5, 0, 3}, dt[3] = {1, 0, 0};
    rcref_band_eval(&cap, ot, dt, 0, INFINITY, 0, &b);
    CHECK(b.exact.hit && b.hit_unstable, "tangent: stable?");
    CHECK(rcref_judge(&b, 0, 0, 0, &ub) == 0, "tangent: the miss refused");

    /* a secondary ray leaving a point of the side: its own surface at t = 0, or nothing */
    const float on[3] = {1, 0, 1}, dn[3] = {0.6f, 0.8f, 0};
    rcref_band_eval(&cap, on, dn, 0, INFINITY, 0, &b);
    CHECK(b.hit_unstable, "surface: stable?");

    /* spheres touching inside (|p1 - p0| = r1 - r0): nested or not, either cap where they
     * touch */
    const rcref_round_cone touch = {{0, 0, 0}, {0, 0, 1}, 1, 2, CYLRAY_CAPPED};
    const float oa[3] = {0, 0, -5}, da[3] = {0, 0, 1};
    rcref_band_eval(&touch, oa, da, 0, INFINITY, 0, &b);
    CHECK(b.exact.hit && b.exact.part == CYLRAY_CAP_HI && b.exact.t == 4,
          "touching: exact %d part %#x t %g", b.exact.hit, b.exact.part, b.exact.t);
    CHECK(rcref_judge(&b, 1, CYLRAY_CAP_LO, 4.0f, &ub) == 0 && ub == 0,
          "touching: the smaller cap refused");
    CHECK(!b.hit_unstable, "touching: a miss allowed");
}
