/* SPDX-License-Identifier: MIT */
/* regress.c - fixed cases run on every path in every cylcheck run (category "regress"):
 * inputs that once made a kernel fail, kept so the failure cannot come back unseen, and
 * float-exact hand cases whose answer is known without the reference. */
#include "check.h"

#include <math.h>
#include <stdlib.h>

typedef struct regress_case {
    const char *why;
    cylray_cylinder cyl;
    float o[3], d[3], tmin, tmax;
} regress_case;

#define I INFINITY
#define CAP CYLRAY_CAPPED

static const regress_case table[] = {
    /* Found by cylcheck on kernel e9852b6 (fixed by bc57c49): CYLRAY_REFINE polished a
     * near-parallel root from a point 4e4 along the axis; t 3e4-5e4 ulps off, and
     * |n| - 1 = -1.2e-5 .. -3.6e-5. */
    {"refine, near-parallel, infinite, 4e4 away",
     {{0x1.12de0cp+2f, -0x1.ee4442p+1f, -0x1.c635ep-1f},
      {0x1.fb1a5cp+0f, 0x1.d1461cp+1f, -0x1.88019p+2f},
      0x1.02282ap-2f,
      I,
      0},
     {0x1.02c21ap+2f, -0x1.b6ce5p+1f, -0x1.b1e8ap-1f},
     {-0x1.125f2p-2f, -0x1.f77e3p-2f, 0x1.a833d8p-1f},
     0,
     I},
    /* Same defect, same kernel: t 1.1e6 instead of 1.2e6, |n| - 1 = -6.5e-4. */
    {"refine, near-parallel, infinite, 1e6 away",
     {{0x1.805f46p+2f, 0x1.6cf43ep+1f, 0x1.2924a8p+3f},
      {0x1.d0fe1ep-11f, 0x1.e303c4p-10f, 0x1.481588p-9f},
      0x1.74448p+0f,
      I,
      0},
     {0x1.738092p+3f, 0x1.7dd2f6p+3f, 0x1.6f8022p+4f},
     {-0x1.18fbb2p-2f, -0x1.23df8ap-1f, -0x1.8c8142p-1f},
     0,
     0x1.8f35ap+21f},
    /* Found on every kernel so far: 12.6 ulps on SSE4.1 (no FMA), 2.6 with FMA. Within
     * the band; kept for the record of the SSE4.1 accuracy. */
    {"huge, SSE4.1 12.6 ulps",
     {{-0x1.057584p+16f, -0x1.6a996cp+15f, 0x1.ebe74ap+14f},
      {-0x1.62d9acp-1f, -0x1.f7cc4ep-2f, -0x1.0dc35cp-1f},
      0x1.77271p+12f,
      0x1.5410dep+13f,
      0},
     {-0x1.bf1ffcp+15f, -0x1.3b5bfp+15f, 0x1.e1626p+14f},
     {-0x1.2d7592p-1f, -0x1.849a34p-1f, -0x1.1ca304p-2f},
     0,
     I},
    /* Found by libFuzzer on kernel f93de4d (SSE4.1, which hit where the others missed,
     * as the band allows): the line grazes a radius-2^-55 cylinder, the polish point's
     * discriminant clamps to 0 and the "small root" was a Newton step on a flat
     * quadratic, moving t from 7.3e-4 to 2.2e-2 (a side hit 10.6 from the axis). */
    {"refine, grazing a radius-2^-55 cylinder",
     {{0x1.f4p+9f, -0x1.f4p+9f, 0x1.f4p+8f},
      {-0x1.91999ap-3f, 0x1.ccccccp-1f, 0x1.99999ap-4f},
      0x1.ae14ep-56f,
      0x1.cp-9f,
      CAP},
     {0x1.f4p+9f, -0x1.f4p+9f, 0x1.f46p+8f},
     {0x1.e56e6ep-5f, -0x1.167e96p-2f, -0x1.fffffcp+8f},
     0,
     I},
    /* Found by the secondary-ray tests (AVX2 and AVX-512): an origin 1e-6 outside an
     * infinite tube, leaving it almost tangentially; D and C were each a few ulps of
     * R^2 off, C / q put the second root past the origin, and a back-face hit at
     * 6.05e-5 came back where both exact roots lie behind the origin. */
    {"near-tangent, origin just outside, roots behind",
     {{0x1.d7521ap+2f, 0x1.86ecdap+2f, 0x1.57858p+1f}, {0, -1, 0}, 0x1.142644p+1f, I, 0},
     {0x1.fedb86p+2f, 0x1.8e8894p+2f, 0x1.3bbd54p-1f},
     {-0x1.d0e582p-1f, -0x1.4588a8p-2f, -0x1.177294p-2f},
     0,
     I},
    /* Float-exact hand cases (R = 1, H = 2 along z unless said). */
    {"exactly through the rim, entering",
     {{0, 0, 0}, {0, 0, 1}, 1, 2, CAP},
     {-2, 0, 3},
     {1, 0, -1},
     0,
     I},
    {"exactly through the rim, axis of length 4",
     {{0, 0, 0}, {0, 0, 4}, 1, 2, CAP},
     {-2, 0, 3},
     {1, 0, -1},
     0,
     I},
    {"exactly through the rim, axis along -y",
     {{0, 0, 0}, {0, -1, 0}, 1, 2, CAP},
     {3, -3, 0},
     {-1, 1, 0},
     0,
     I},
    {"leaving through the rim",
     {{0, 0, 0}, {0, 0, 1}, 1, 2, CAP},
     {-0.5f, 0, 1.5f},
     {-1, 0, 1},
     0,
     I},
    {"through the center", {{0, 0, 0}, {0, 0, 1}, 1, 2, CAP}, {-5, 0, 0}, {1, 0, 0}, 0, I},
    {"along the axis inside, to the cap",
     {{0, 0, 0}, {0, 0, 1}, 1, 2, CAP},
     {0.5f, 0.25f, -10},
     {0, 0, 1},
     0,
     I},
    {"infinite with the capped flag, along the axis",
     {{0, 0, 0}, {0, 0, 1}, 1, I, CAP},
     {0.5f, 0.25f, -10},
     {0, 0, 1},
     0,
     I},
    {"origin 1e6 away on the x axis",
     {{0, 0, 0}, {0, 0, 1}, 1, 2, CAP},
     {-1e6f, 0, 0},
     {1, 0, 0},
     0,
     I},
    {"radius 2^-13 at 1e4",
     {{1e4f, 1e4f, 1e4f}, {0, 0, 1}, 0x1p-13f, 1, CAP},
     {1e4f - 1, 1e4f, 1e4f},
     {1, 0, 0},
     0,
     I},
    {"|d| = 1024", {{0, 0, 0}, {0, 0, 1}, 1, 2, CAP}, {-5, 0, 0}, {1024, 0, 0}, 0, I},
    {"open tube, in through the open end",
     {{0, 0, 0}, {0, 0, 1}, 1, 2, 0},
     {-0.5f, 0, 3},
     {0.5f, 0, -1},
     0,
     I},
};

#define N_CASES (sizeof table / sizeof table[0])
#define STREAM_LEN 3

ref_case *make_regress_cases(size_t *n_packet, const size_t **lengths, size_t *n_lengths,
                             size_t *total)
{
    static size_t lens[N_CASES];
    const size_t npk = N_CASES * CYLGEN_BATCH, n = npk + N_CASES * STREAM_LEN;
    ref_case *rc = calloc(n, sizeof *rc);
    if (!rc)
        exit(2);
    for (size_t i = 0; i < n; i++) {
        size_t k = i < npk ? i / CYLGEN_BATCH : (i - npk) / STREAM_LEN;
        const regress_case *t = &table[k];
        cylgen_case *c = &rc[i].c;
        c->cyl = t->cyl;
        for (int j = 0; j < 3; j++) {
            c->o[j] = t->o[j];
            c->d[j] = t->d[j];
        }
        c->tmin = t->tmin;
        c->tmax = t->tmax;
        rc[i].index = (int)k;
        if (i % CYLGEN_BATCH == 0 || i >= npk) {
            cylref_band_eval(&c->cyl, c->o, c->d, c->tmin, c->tmax, 0, &rc[i].band[0]);
            cylref_band_eval(&c->cyl, c->o, c->d, c->tmin, c->tmax, CYLRAY_CULL_BACK,
                             &rc[i].band[1]);
        } else {
            rc[i].band[0] = rc[i - 1].band[0];
            rc[i].band[1] = rc[i - 1].band[1];
        }
    }
    for (size_t k = 0; k < N_CASES; k++)
        lens[k] = STREAM_LEN;
    *n_packet = npk;
    *lengths = lens;
    *n_lengths = N_CASES;
    *total = n;
    return rc;
}

const char *regress_why(int index)
{
    return index >= 0 && (size_t)index < N_CASES ? table[index].why : "?";
}
