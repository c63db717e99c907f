/* SPDX-License-Identifier: MIT */
/* fuzz_kernels.c - the libFuzzer target: arbitrary bytes become one kernel
 * call (fuzz_input.h), run on every ISA this machine has, through the guarded runner
 * (canaries, poison, the memory contract). A failure prints the case in hex floats and
 * aborts, which libFuzzer records as a crash. What must hold:
 *   - no crash, no sanitizer report, no write outside the owned lanes;
 *   - a cylinder prepare refuses gives no hit;
 *   - occluded reports exactly the lanes intersect hits;
 *   - every hit lies on the surface, inside [tmin, tmax], with a unit normal facing as
 *     the flags say (hitcheck.h);
 *   - every SIMD path agrees with the scalar one, except near a decision boundary
 *     (agree.h, which asks the exact reference when the geometry does not excuse it);
 *   - leaves of the cylinder and its variants answer as their lanes do alone, and as
 *     the packet kernels do (fuzz_leaf.h).
 * Built with clang -fsanitize=fuzzer,address,undefined; with other compilers,
 * standalone.c supplies a main() that replays files and random inputs. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "agree.h"
#include "cylray.h"
#include "fuzz_input.h"
#include "fuzz_leaf.h"
#include "fuzz_shape.h"
#ifdef HAVE_SPAWN
#include "fuzz_spawn.h"
#endif
#include "guarded.h"
#include "hitcheck.h"
#include "tcheck.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerInitialize(int *argc, char ***argv);

/* Calls per ISA, printed at exit: how much each path was exercised. */
static unsigned long runs[CYLRAY_ISA_COUNT];

static void report(void)
{
    fprintf(stderr, "cylray-fuzz: executions per ISA:");
    for (int i = 0; i < CYLRAY_ISA_COUNT; i++)
        if (cylray_kernels_for((cylray_isa)i))
            fprintf(stderr, " %s=%lu", cylray_isa_name((cylray_isa)i), runs[i]);
    fprintf(stderr,
            "; SIMD/scalar differences excused near a boundary: %lu, by the exact "
            "reference: %lu\n",
            fz_excused_geometric, fz_excused_exact);
    fprintf(stderr,
            "cylray-fuzz: spheres: %lu inputs, %lu lanes judged against the exact band\n",
            fz_sphere_cases, fz_sphere_lanes);
    fprintf(stderr, "cylray-fuzz: cones: %lu inputs, %lu lanes judged against the exact band\n",
            fz_cone_cases, fz_cone_lanes);
#ifdef HAVE_SPAWN
    fprintf(stderr,
            "cylray-fuzz: spawn: %lu hits through hit point and origin, %lu spawned "
            "rays traced on every ISA\n",
            fz_spawn_hits, fz_spawn_traced);
#endif
}

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    atexit(report);
    return 0;
}

static void dump(const fz_case *c, const char *what)
{
    char s[512];
    if (c->sphere)
        fprintf(stderr, "cylray-fuzz: sphere center (%a, %a, %a) radius %a\n",
                (double)c->sph.center[0], (double)c->sph.center[1], (double)c->sph.center[2],
                (double)c->sph.radius);
    if (c->cone)
        fprintf(stderr,
                "cylray-fuzz: cone p0 (%a, %a, %a) p1 (%a, %a, %a) r0 %a r1 %a flags %#x\n",
                (double)c->con.p0[0], (double)c->con.p0[1], (double)c->con.p0[2],
                (double)c->con.p1[0], (double)c->con.p1[1], (double)c->con.p1[2],
                (double)c->con.r0, (double)c->con.r1, c->con.flags);
    fprintf(stderr,
            "cylray-fuzz: %s\n  %s\n  width %s n %zu active %#x misalign %u flags %#x\n", what,
            g_cyl_str(&c->cyl, s, sizeof s), g_width_name(c->width), c->n, c->active,
            c->misalign, c->flags);
    for (size_t i = 0; i < c->n; i++)
        if (c->width == G_STREAM || ((c->active >> i) & 1u))
            fprintf(stderr, "  ray %zu: %s\n", i, g_ray_str(&c->rays, i, s, sizeof s));
}

#define FAIL_(...)                                                                             \
    do {                                                                                       \
        char msg_[1024];                                                                       \
        snprintf(msg_, sizeof msg_, __VA_ARGS__);                                              \
        dump(&c, msg_);                                                                        \
        abort();                                                                               \
    } while (0)

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static fz_case c;
    fz_decode(data, size, &c);
    const cylray_kernels *isas[CYLRAY_ISA_COUNT];
    const int nisa = g_isas(isas);
    if (c.sphere || c.cone) {
        char why[768];
        if (fz_shape(&c, isas, nisa, why, sizeof why))
            FAIL_("%s: %s", c.cone ? "cone" : "sphere", why);
        return 0;
    }

    cylray_prepared P;
    const int valid = cylray_prepare(&P, &c.cyl) == CYLRAY_OK;
    if (!valid)
        memset(&P, 0, sizeof P); /* what a careless caller passes on: must give nothing */

    static gresult res[CYLRAY_ISA_COUNT], occ[CYLRAY_ISA_COUNT];
    for (int ii = 0; ii < nisa; ii++) {
        const cylray_kernels *k = isas[ii];
        runs[k->isa]++;
        const long before = tc_failures_;
        g_intersect(k, c.width, &P, &c.rays, c.n, c.active, c.flags, c.misalign, &res[ii]);
        g_occluded(k, c.width, &P, &c.rays, c.n, c.active, c.flags, c.misalign, &occ[ii]);
        if (tc_failures_ != before)
            FAIL_("%s broke the memory contract (see above)", k->name);
        if (occ[ii].hit != res[ii].hit)
            FAIL_("%s: occluded %#llx, intersect %#llx", k->name,
                  (unsigned long long)occ[ii].hit, (unsigned long long)res[ii].hit);
        if (!valid && res[ii].hit)
            FAIL_("%s: hits with a cylinder prepare refused", k->name);
        const double slack = (c.flags & CYLRAY_FAST) ? 16 : 1;
        for (size_t i = 0; i < c.n; i++) {
            if (!((res[ii].hit >> i) & 1u))
                continue;
            float r[G_NFIELD];
            for (int f = 0; f < G_NFIELD; f++)
                r[f] = c.rays.f[f][i];
            const float n[3] = {res[ii].nx[i], res[ii].ny[i], res[ii].nz[i]};
            char why[256];
            if (hc_verify(&c.cyl, r, r + 3, r[G_TMIN], r[G_TMAX], res[ii].t[i], res[ii].part[i],
                          n, c.flags, slack, why, sizeof why))
                FAIL_("%s ray %zu: impossible hit: %s", k->name, i, why);
        }
    }
    /* Every SIMD path against the scalar one (isas[0]). */
    for (int ii = 1; ii < nisa; ii++)
        for (size_t i = 0; i < c.n; i++) {
            if (c.width != G_STREAM && !((c.active >> i) & 1u))
                continue;
            const fz_answer a = {(int)((res[0].hit >> i) & 1u), res[0].t[i], res[0].part[i]};
            const fz_answer b = {(int)((res[ii].hit >> i) & 1u), res[ii].t[i], res[ii].part[i]};
            float ray[G_NFIELD];
            for (int f = 0; f < G_NFIELD; f++)
                ray[f] = c.rays.f[f][i];
            char why[512];
            if (fz_agree(&c.cyl, ray, c.flags, &a, &b, why, sizeof why))
                FAIL_("scalar and %s disagree on ray %zu: %s", isas[ii]->name, i, why);
        }
    {
        char why[768];
        if (fz_leaf(&c, isas, nisa, why, sizeof why))
            FAIL_("leaf: %s", why);
    }
#ifdef HAVE_SPAWN
    if (valid) {
        char why[512];
        if (fz_spawn(&c, &P, &res[0], isas, nisa, why, sizeof why))
            FAIL_("spawn: %s", why);
    }
#endif
    return 0;
}
