/* SPDX-License-Identifier: MIT */
/* round_cone.c - cylray_prepare_round_cone: its refusals (*out untouched), dyadic round
 * cones whose answers are known exactly on every path and width (a capsule's side, its
 * caps, a seam, an open end passed through onto the side's inside, a point end's apex,
 * one sphere within the other), and what does not take round cones yet: the toolkit
 * refuses them and the secondary-ray calls give NaN, never a wrong point.
 *
 * The random and stress cases are cylcheck's (tests/ref/rcgen.h against rcref). */
#include "cylray.h"
#include "tcheck.h"

#include <math.h>
#include <string.h>

static void refusals(void)
{
    const cylray_round_cone good = {{0, 0, 0}, {0, 0, 4}, 1, 0.5f, CYLRAY_CAPPED};
    cylray_prepared p, before;
    memset(&p, 0x5a, sizeof p);
    before = p;
    CHECK(cylray_prepare_round_cone(&p, &good) == CYLRAY_OK, "the good round cone refused");
    CHECK(cylray_prepare_round_cone(NULL, &good) == CYLRAY_EINVAL, "NULL out taken");
    const float bad_r[] = {-1.0f, NAN, INFINITY, 0x1p-70f, 0x1p63f};
    for (int pass = 0; pass < 9; pass++) {
        cylray_round_cone c = good;
        switch (pass) {
        case 0:
            c.p0[1] = NAN;
            break;
        case 1:
            c.p1[2] = INFINITY;
            break;
        case 2:
            c.p0[0] = 0x1p63f;
            break;
        case 3:
            c.r0 = c.r1 = 0;
            break;
        case 4:
            c.flags = 0x20;
            break;
        default:
            c.r1 = bad_r[pass - 5];
            break;
        }
        memset(&p, 0x5a, sizeof p);
        CHECK(cylray_prepare_round_cone(&p, &c) == CYLRAY_EINVAL, "refusal %d taken", pass);
        CHECK(memcmp(&p, &before, sizeof p) == 0, "refusal %d wrote *out", pass);
    }
    CHECK(cylray_prepare_round_cone(&p, NULL) == CYLRAY_EINVAL, "NULL in taken");
}

/* One ray through every path and width (lane 1 of a packet, lane 2 of a stream). */
typedef struct {
    const char *what;
    cylray_round_cone c;
    float o[3], d[3];
    int hit, part; /* part -1: the side or a cap (a seam) */
    float t;
} hand;

static void check_hand(const hand *h)
{
    cylray_prepared P;
    if (cylray_prepare_round_cone(&P, &h->c) != CYLRAY_OK) {
        CHECK(0, "%s: refused", h->what);
        return;
    }
    for (int isa = 0; isa < CYLRAY_ISA_COUNT; isa++) {
        const cylray_kernels *K = cylray_kernels_for((cylray_isa)isa);
        if (!K)
            continue;
        for (int w = 0; w < 4; w++) {
            cylray_ray16 r;
            cylray_hit16 H;
            memset(&H, 0, sizeof H);
            for (int j = 0; j < 16; j++) {
                r.ox[j] = h->o[0], r.oy[j] = h->o[1], r.oz[j] = h->o[2];
                r.dx[j] = h->d[0], r.dy[j] = h->d[1], r.dz[j] = h->d[2];
                r.tmin[j] = 0, r.tmax[j] = INFINITY;
            }
            uint32_t m = 0;
            unsigned lane = 1;
#define PACKET_(n)                                                                             \
    do {                                                                                       \
        cylray_ray##n rn;                                                                      \
        cylray_hit##n hn;                                                                      \
        memset(&hn, 0, sizeof hn);                                                             \
        for (int j = 0; j < n; j++) {                                                          \
            rn.ox[j] = r.ox[j], rn.oy[j] = r.oy[j], rn.oz[j] = r.oz[j];                        \
            rn.dx[j] = r.dx[j], rn.dy[j] = r.dy[j], rn.dz[j] = r.dz[j];                        \
            rn.tmin[j] = r.tmin[j], rn.tmax[j] = r.tmax[j];                                    \
        }                                                                                      \
        m = K->intersect##n(&P, &rn, &hn, 0x2u, CYLRAY_NORMAL);                                \
        H.t[lane] = hn.t[lane], H.part[lane] = hn.part[lane];                                  \
    } while (0)
            if (w == 0)
                PACKET_(4);
            else if (w == 1)
                PACKET_(8);
            else if (w == 2)
                m = K->intersect16(&P, &r, &H, 0x2u, CYLRAY_NORMAL);
            else {
                const cylray_rays R = {r.ox, r.oy, r.oz, r.dx, r.dy, r.dz, r.tmin, r.tmax};
                const cylray_hits HS = {H.t, H.nx, H.ny, H.nz, H.part};
                lane = 2;
                K->intersect_stream(&P, &R, &HS, 3, CYLRAY_NORMAL);
                m = H.part[lane] ? 1u << lane : 0u;
            }
#undef PACKET_
            const int got = (m >> lane) & 1u;
            CHECK(got == h->hit, "%s: %s width %d: hit %d, not %d", h->what, K->name, w, got,
                  h->hit);
            if (got && h->hit) {
                /* (a seam: the side or the cap) */
                const int part = h->part < 0 ? H.part[lane] : h->part;
                CHECK(H.part[lane] == part && (h->part >= 0 || H.part[lane] != 0),
                      "%s: %s width %d: part %#x, not %#x", h->what, K->name, w,
                      (unsigned)H.part[lane], (unsigned)part);
                CHECK(fabsf(H.t[lane] - h->t) <= 2 * (nextafterf(h->t, INFINITY) - h->t),
                      "%s: %s width %d: t %.9g, not %.9g", h->what, K->name, w, H.t[lane],
                      h->t);
            }
        }
    }
}

static void hands(void)
{
    const cylray_round_cone capsule = {{0, 0, -1}, {0, 0, 1}, 0.5f, 0.5f, CYLRAY_CAPPED};
    cylray_round_cone open_lo = capsule;
    open_lo.flags = CYLRAY_CAPPED_HI;
    /* 3-4-5: r0 = 0 at the origin, r1 = 3 at z = 5: the cone tangent to the sphere has
     * sin alpha = 3/5, its side the line x = (3/4) z in the plane y = 0 up to the seam at
     * z = 4 cos alpha = 3.2, x = 2.4 */
    const cylray_round_cone point = {{0, 0, 0}, {0, 0, 5}, 0, 3, CYLRAY_CAPPED};
    const cylray_round_cone nested = {{0, 0, 0}, {0, 0, 0.25f}, 1, 0.5f, CYLRAY_CAPPED_LO};
    cylray_round_cone nested_open = nested;
    nested_open.flags = CYLRAY_CAPPED_HI; /* the smaller sphere's flag drops nothing */
    /* a case a line, as a table reads */
    /* clang-format off */
    const hand h[] = {
        {"capsule side", capsule, {4, 0, 0.5f}, {-1, 0, 0}, 1, CYLRAY_SIDE, 3.5f},
        {"capsule cap hi", capsule, {0, 0, 4}, {0, 0, -1}, 1, CYLRAY_CAP_HI, 2.5f},
        {"capsule cap lo", capsule, {0, 0, -4}, {0, 0, 1}, 1, CYLRAY_CAP_LO, 2.5f},
        {"capsule seam", capsule, {4, 0, 1}, {-1, 0, 0}, 1, -1, 3.5f},
        {"capsule from inside", capsule, {0, 0, 0}, {1, 0, 0}, 1, CYLRAY_SIDE | CYLRAY_BACKFACE, 0.5f},
        {"through the open end onto the far cap", open_lo, {0, 0, -4}, {0, 0, 1}, 1, CYLRAY_CAP_HI | CYLRAY_BACKFACE, 5.5f},
        {"through the open end onto the side", open_lo, {0, 0, -2}, {0.25f, 0, 1}, 1, CYLRAY_SIDE | CYLRAY_BACKFACE, 2},
        {"point end: the side", point, {8, 0, 2}, {-1, 0, 0}, 1, CYLRAY_SIDE, 6.5f},
        {"point end: the cap", point, {0, 0, 9}, {0, 0, -1}, 1, CYLRAY_CAP_HI, 1},
        {"point end: its apex", point, {0, 0, -2}, {0, 0, 1}, 1, CYLRAY_SIDE, 2},
        {"nested: the larger sphere", nested, {0, 0, 4}, {0, 0, -1}, 1, CYLRAY_CAP_LO, 3},
        {"nested, its end open", nested_open, {0, 0, 4}, {0, 0, -1}, 0, 0, 0},
    };
    /* clang-format on */
    for (size_t i = 0; i < sizeof h / sizeof h[0]; i++)
        check_hand(&h[i]);
}

/* What does not take round cones yet: a clear refusal, or NaN. */
static void not_yet(void)
{
    const cylray_round_cone c = {{0, 0, 0}, {0, 0, 4}, 1, 0.5f, CYLRAY_CAPPED};
    cylray_prepared P;
    CHECK(cylray_prepare_round_cone(&P, &c) == CYLRAY_OK, "refused");
    float lo[3], hi[3], box_lo[4][3], box_hi[4][3];
    CHECK(cylray_bounds(&P, lo, hi) == CYLRAY_EINVAL, "bounds taken");
    CHECK(cylray_split_boxes(&P, 4, box_lo, box_hi) == 0, "split boxes taken");
    const float o[3] = {4, 0, 2}, d[3] = {-1, 0, 0};
    float p[3], err = 0, out[3];
    cylray_hit_point(&P, o, d, 3.0f, CYLRAY_SIDE, p, &err);
    CHECK(isnan(p[0]) && isnan(p[1]) && isnan(p[2]), "a hit point");
    const float w[3] = {1, 0, 0};
    cylray_spawn_origin(&P, p, err, CYLRAY_SIDE, w, out);
    CHECK(isnan(out[0]) || isnan(out[1]) || isnan(out[2]), "a spawn origin");
}

int main(void)
{
    refusals();
    hands();
    not_yet();
    return tc_report("api-round-cone");
}
