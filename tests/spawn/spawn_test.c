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

static const spawn_mode modes[] = {
    {"bounds", run_bounds},           {"self", run_self},  {"nested", run_nested},
    {"batched", run_batched},         {"axis", run_axis},  {"side", run_side},
    {"reintersect", run_reintersect}, {"round", run_round}};

int main(int argc, char **argv)
{
    return spawn_main(argc, argv, "spawn_test", modes, sizeof modes / sizeof modes[0]);
}
