/* SPDX-License-Identifier: MIT */
/* spawn_length.c - spawned rays along directions of any length. The kernels' t is a
 * float: below 2^-126 its spacing is 2^-149, so along a direction of length FLT_MAX a
 * surface up to 2^-19 from the origin can be met at t = 0, and the spawned origin's
 * margins must grow with the direction's length.
 *
 *   spawn_length fuzz   the fuzzer's cases: tubes of radius 1e-10 hit at t = 0 by rays
 *                       of length FLT_MAX, spawned back along the ray and on through
 *                       the surface (as tests/fuzz/fuzz_spawn.c does)
 *   spawn_length sweep  hits of every category of spawnref.h (at its scale and shrunk
 *                       by 2^-20 and 2^-40), spawned along reflected, transmitted,
 *                       reversed and random directions of lengths from 1 to FLT_MAX
 *
 * Both: every ISA's batched forms (a packet of 16, a stream) equal the scalar forms bit
 * for bit; where the guarantee's condition holds (offset below R/4 and H/4, and w clear
 * of the tangent plane), the origin lies strictly on its side and no ISA's kernel meets
 * the surface it leaves (spawnref.h's test). Any violation fails the test. */
#include "cylray.h"
#include "spawn_main.h"
#include "spawnref.h"
#include "tcheck.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void fail(const cylray_cylinder *cyl, const float p[3], const float w[3],
                 const char *what)
{
    if (failures++ < 20)
        fprintf(stderr,
                "FAIL: cyl c=(%a %a %a) v=(%a %a %a) R=%a H=%a flags=%u p=(%a %a %a) "
                "w=(%a %a %a): %s\n",
                cyl->center[0], cyl->center[1], cyl->center[2], cyl->axis[0], cyl->axis[1],
                cyl->axis[2], cyl->radius, cyl->half_height, cyl->flags, p[0], p[1], p[2], w[0],
                w[1], w[2], what);
}

typedef struct stats {
    long spawned, traced, selfhits;
} stats;

/* The spawned origins leaving p (bound err) on `part` along w, at lane L of a packet:
 * the batched forms against the scalar ones, then the guarantee where it holds. */
static void check(const cylray_cylinder *cyl, const cylray_prepared *P, const float p[3],
                  float err, int32_t part, const float w[3], int L, stats *st)
{
    const int pm = part & CYLRAY_PART_MASK;
    double n[3];
    sref_normal(cyl, p, pm, n);
    const double wn = n[0] * w[0] + n[1] * w[1] + n[2] * w[2];
    float x0[3], xs[3];
    cylray_spawn_origin(P, p, err, part, w, x0);
    cylray_spawn_origin_side(P, p, err, part, wn > 0, w, xs);
    st->spawned++;
    for (int k = 0; k < nisa; k++) {
        const cylray_kernels *K = isas[k];
        cylray_points16 q;
        cylray_hit16 h;
        cylray_ray16 r;
        memset(&q, 0, sizeof q), memset(&h, 0, sizeof h), memset(&r, 0, sizeof r);
        q.x[L] = p[0], q.y[L] = p[1], q.z[L] = p[2], q.err[L] = err;
        h.part[L] = part;
        r.dx[L] = w[0], r.dy[L] = w[1], r.dz[L] = w[2];
        cylray_ray16 rs = r;
        K->spawn_rays16(P, &q, &h, 1u << L, &r);
        K->spawn_rays_side16(P, &q, &h, 1u << L, (uint32_t)(wn > 0) << L, &rs);
        float sx = p[0], sy = p[1], sz = p[2], se = err, ox = 0, oy = 0, oz = 0;
        float wx = w[0], wy = w[1], wz = w[2];
        const cylray_points pts = {&sx, &sy, &sz, &se}, dirs = {&wx, &wy, &wz, NULL};
        const cylray_points org = {&ox, &oy, &oz, NULL};
        K->spawn_stream(P, &pts, &part, &dirs, &org, 1);
        const float a[3] = {r.ox[L], r.oy[L], r.oz[L]}, b[3] = {rs.ox[L], rs.oy[L], rs.oz[L]};
        const float c[3] = {ox, oy, oz};
        if (!sref_same3(a, x0) || !sref_same3(b, xs) || !sref_same3(c, x0)) {
            char why[96];
            snprintf(why, sizeof why, "%s's batched origins differ from the scalar forms'",
                     K->name);
            fail(cyl, p, w, why);
        }
    }
    double mv = 0;
    for (int k = 0; k < 3; k++)
        mv += ((double)x0[k] - p[k]) * ((double)x0[k] - p[k]);
    const double wl = sqrt((double)w[0] * w[0] + (double)w[1] * w[1] + (double)w[2] * w[2]);
    if (!(sqrt(mv) <= 0.25 * fmin(cyl->radius, cyl->half_height)) || fabs(wn) <= 1e-6 * wl)
        return;
    const double sig = sref_sigma(cyl, x0, pm);
    if ((wn > 0) != (sig > 0) || sig == 0)
        fail(cyl, p, w, "the origin is not strictly on w's side");
    st->traced++;
    for (int k = 0; k < nisa; k++) {
        float th;
        int32_t ph;
        if (sref_trace1(isas[k], P, x0, w, &th, &ph) &&
            sref_self_hit(cyl, x0, w, part, ph, th)) {
            st->selfhits++;
            char why[160];
            snprintf(why, sizeof why, "%s meets the surface it leaves at t %a from %a %a %a",
                     isas[k]->name, (double)th, x0[0], x0[1], x0[2]);
            fail(cyl, p, w, why);
        }
    }
}

/* The hit of the scalar kernel (as the fuzzer takes it), through the hit point. */
static int hit_of(const cylray_prepared *P, const float o[3], const float d[3], float *t,
                  int32_t *part, float p[3], float *err)
{
    if (!sref_trace1(cylray_kernels_for(CYLRAY_ISA_SCALAR), P, o, d, t, part))
        return 0;
    cylray_hit_point(P, o, d, *t, *part, p, err);
    return isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]) && isfinite(*err);
}

#define TEN (0x1.b7cdfep-34f) /* 1e-10f, one of the fuzzer's special values */

/* The libFuzzer run (seed 1) met its own surface at t = 0 from origins spawned at these
 * side points of infinite tubes (the hit points and bounds of rays o + t d hit at t = 0,
 * d the direction below), back along d and on along it. */
static const struct {
    float c[3], v[3], p[3], err, d[3];
} fuzz_cases[] = {
    {{0x1.340668p-75f, TEN, TEN},
     {TEN, TEN, 0x1p+62f},
     {TEN, TEN, TEN},
     0x1.011448p-74f,
     {FLT_MAX, TEN, TEN}},
    {{0x1.340668p-75f, TEN, TEN},
     {TEN, 0x1.fffffep-1f, 0x1p+62f},
     {TEN, TEN, TEN},
     0x1.011448p-74f,
     {FLT_MAX, TEN, TEN}},
    {{TEN, TEN, TEN},
     {TEN, TEN, TEN},
     {0x1.d8c0aap-34f, 0x1.d8c0aap-34f, -0x1.079566p-36f},
     0x1.87a71p-60f,
     {FLT_MAX, 0x1.3p-12f, 0}},
    {{TEN, TEN, TEN},
     {0x1p-62f, TEN, TEN},
     {0x1p-86f, TEN, TEN},
     0x1.49da8p-76f,
     {FLT_MAX, TEN, TEN}},
};

static int run_fuzz(void)
{
    stats st = {0, 0, 0};
    const int ncase = (int)(sizeof fuzz_cases / sizeof fuzz_cases[0]);
    for (int i = 0; i < ncase; i++) {
        cylray_cylinder cyl;
        memset(&cyl, 0, sizeof cyl);
        memcpy(cyl.center, fuzz_cases[i].c, sizeof cyl.center);
        memcpy(cyl.axis, fuzz_cases[i].v, sizeof cyl.axis);
        cyl.radius = TEN, cyl.half_height = INFINITY;
        cylray_prepared P;
        const float *p = fuzz_cases[i].p, *d = fuzz_cases[i].d;
        if (cylray_prepare(&P, &cyl) != CYLRAY_OK) {
            fail(&cyl, p, d, "the fuzzer's tube is refused");
            continue;
        }
        for (int dir = 0; dir < 2; dir++) {
            const float w[3] = {dir ? d[0] : -d[0], dir ? d[1] : -d[1], dir ? d[2] : -d[2]};
            check(&cyl, &P, p, fuzz_cases[i].err, CYLRAY_SIDE, w, (i + dir) % 16, &st);
        }
    }
    printf("fuzz: %ld origins spawned, %ld rays traced on %d ISAs, %ld meeting their surface\n",
           st.spawned, st.traced, nisa, st.selfhits);
    return failures == 0;
}

/* Lengths of the spawned directions: 2^e, FLT_MAX for the last. */
static const int lengths[] = {0, 40, 100, 120, 125, 126, 127, 128};
#define NLEN ((int)(sizeof lengths / sizeof lengths[0]))

static int run_sweep(void)
{
    stats st[NLEN];
    memset(st, 0, sizeof st);
    const int groups = quick ? 4 : 150;
    cylgen_rng rng;
    cylgen_seed(&rng, 0x5eed1e9u);
    for (int cat = 0; cat < SREF_COUNT; cat++) {
        for (int gi = 0; gi < groups; gi++) {
            cylgen_case c[SREF_GROUP];
            sref_group(cat, (uint64_t)cat << 32 | (unsigned)gi, c);
            /* a third of the scenes at their scale, the others shrunk by 2^-20 or 2^-40
             * (exact): radii down to 1e-16, which long directions cross in one step of t */
            const float scale = gi % 3 == 0 ? 1.0f : gi % 3 == 1 ? 0x1p-20f : 0x1p-40f;
            for (int i = 0; i < SREF_GROUP; i++) {
                for (int k = 0; k < 3; k++) {
                    c[i].cyl.center[k] *= scale;
                    c[i].o[k] *= scale;
                }
                c[i].cyl.radius *= scale;
                c[i].cyl.half_height *= scale;
            }
            cylray_prepared P;
            if (cylray_prepare(&P, &c[0].cyl) != CYLRAY_OK)
                continue;
            for (int i = 0; i < SREF_GROUP; i++) {
                float t, p[3], err;
                int32_t part;
                if (!hit_of(&P, c[i].o, c[i].d, &t, &part, p, &err))
                    continue;
                double n[3], dn = 0, u[3];
                sref_normal(&c[0].cyl, p, part & CYLRAY_PART_MASK, n);
                for (int k = 0; k < 3; k++)
                    dn += c[i].d[k] * n[k];
                /* reflected, transmitted and reversed, then a random direction */
                for (int j = 0; j < 4; j++) {
                    if (j == 3)
                        sref_unit(&rng, u);
                    for (int k = 0; k < 3; k++)
                        u[k] = j == 0   ? c[i].d[k] - 2 * dn * n[k]
                               : j == 1 ? c[i].d[k]
                               : j == 2 ? -c[i].d[k]
                                        : u[k];
                    const double ul = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
                    const int e = (int)(cylgen_next(&rng) % NLEN);
                    const double s = lengths[e] == 128 ? FLT_MAX : ldexp(1.0, lengths[e]);
                    float w[3];
                    for (int k = 0; k < 3; k++)
                        w[k] = (float)(u[k] / ul * s);
                    check(&c[0].cyl, &P, p, err, part, w, (i + j) % 16, &st[e]);
                }
            }
        }
    }
    long traced_long = 0;
    for (int e = 0; e < NLEN; e++) {
        printf("sweep: length 2^%d: %ld origins spawned, %ld rays traced on %d ISAs, %ld "
               "meeting their surface\n",
               lengths[e], st[e].spawned, st[e].traced, nisa, st[e].selfhits);
        if (lengths[e] >= 126)
            traced_long += st[e].traced;
    }
    /* not vacuous: the longest directions leave most unit-scale hits inside the
     * guarantee's condition */
    if (traced_long < (quick ? 20 : 2000)) {
        fprintf(stderr, "FAIL: only %ld rays of length 2^126 and more traced\n", traced_long);
        failures++;
    }
    return failures == 0;
}

static const spawn_mode modes[] = {{"fuzz", run_fuzz}, {"sweep", run_sweep}};

int main(int argc, char **argv)
{
    return spawn_main(argc, argv, "spawn_length", modes, sizeof modes / sizeof modes[0]);
}
