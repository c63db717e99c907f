/* SPDX-License-Identifier: MIT */
/* spawn_test.c - secondary rays against exact arithmetic.
 *
 *   spawn_test bounds   every ISA's hits of every category: the hit point's bound
 *                       contains its exact distance from the part's surface
 *   spawn_test self     rays spawned from those points (reflection, transmission,
 *                       shadow) never meet the surface they leave there, traced on
 *                       every ISA and exactly; the origin is strictly on the ray's side
 *   spawn_test nested   a coaxial cylinder 1e-5 R inside is still hit by the
 *                       transmitted ray, and the spawned origin lies between the two
 *   spawn_test batched  the packet, stream and leaf forms (plain, side and normal) of
 *                       every ISA equal the scalar pair bit for bit (bounds and self
 *                       also take their points and origins from each ISA's stream forms)
 *   spawn_test side     the side form: the tracer's side from the kernel's normal
 *                       (random hits, grazing directions, and fixed cases, far rods whose
 *                       kernel normal and exact normal disagree), the origin strictly
 *                       on that side, no hit of the part before the exact ray's
 *   spawn_test reintersect  pbrt-v4's Reintersect setup (open tubes of random size,
 *                       rotation, translation and scale, rays from far away): spawned
 *                       rays face-forwarded to the kernel's normal, as the README does,
 *                       never hit their tube again
 *   spawn_test round    the library's rounding to float on the bits equals the
 *                       hardware's, and a two-term sum is rounded once
 *
 * CYLRAY_TEST_QUICK=1 shrinks the counts about a hundredfold (sanitizers, emulators).
 * Every count is printed; any violation fails the test. */
#include "spawn_common.h"
#include "tcheck.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int main(int argc, char **argv)
{
    quick = tc_quick();
    for (int i = 0; i < CYLRAY_ISA_COUNT; i++) {
        const cylray_kernels *k = cylray_kernels_for((cylray_isa)i);
        if (k)
            isas[nisa++] = k;
    }
    const char *mode = argc > 1 ? argv[1] : "";
    int ok;
    if (strcmp(mode, "bounds") == 0)
        ok = run_bounds();
    else if (strcmp(mode, "self") == 0)
        ok = run_self();
    else if (strcmp(mode, "nested") == 0)
        ok = run_nested();
    else if (strcmp(mode, "batched") == 0)
        ok = run_batched();
    else if (strcmp(mode, "axis") == 0)
        ok = run_axis();
    else if (strcmp(mode, "side") == 0)
        ok = run_side();
    else if (strcmp(mode, "reintersect") == 0)
        ok = run_reintersect();
    else if (strcmp(mode, "round") == 0)
        ok = run_round();
    else {
        fprintf(stderr,
                "usage: spawn_test bounds|self|nested|batched|axis|side|reintersect|round\n");
        return 2;
    }
    printf("%s: %s\n", mode, ok ? "ok" : "FAILED");
    return ok ? 0 : 1;
}
