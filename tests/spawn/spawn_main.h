/* SPDX-License-Identifier: MIT */
/* spawn_main.h - what every spawn executable shares (cylinders, spheres, cones, lengths):
 * the paths under test, the quick switch, the failure count, and main's dispatch over a
 * table of modes. A shape's executable is its modes and its main one line long. */
#ifndef SPAWN_MAIN_H
#define SPAWN_MAIN_H

#include "cylray.h"
#include "gen.h"

#include <stddef.h>
#include <stdint.h>

extern const cylray_kernels *isas[CYLRAY_ISA_COUNT]; /* the paths this CPU runs */
extern int nisa;
extern int quick;     /* CYLRAY_TEST_QUICK: counts about a hundredfold smaller */
extern long failures; /* each executable prints its first 20 */

/* A uniform double in [a, b). */
double uni(cylgen_rng *r, double a, double b);
/* A count of `full`, a hundredth of it rounded up when quick. */
long scaled(long full);

/* The hit point of (t, part) and its bound, in the plain form (form 0) or from the
 * kernel's normal n (form 1): every shape's bounds test checks both. */
void hit_point_form(const cylray_prepared *P, const float o[3], const float d[3], float t,
                    int32_t part, const float n[3], int form, float p[3], float *err);

/* The first 8 and 4 lanes of a packet of 16 and of its hits (t, part, normal), so that the
 * narrower packet forms are given the same rays and hits as the 16-wide one. */
void narrow_packet(const cylray_ray16 *ray, const cylray_hit16 *hit, cylray_ray8 *r8,
                   cylray_hit8 *h8, cylray_ray4 *r4, cylray_hit4 *h4);

/* What a mode that compares forms found: the lanes (or hits) compared and the
 * differences seen. */
typedef struct spawn_tally {
    long compared, differ;
} spawn_tally;

/* The frame of such a mode: group(rng, g, t) for each of n groups, every group drawing
 * on from one generator seeded with seed, so that a group's draws are those it has
 * always had. Returns nonzero when something was compared and nothing differed. */
int spawn_groups(long n, uint64_t seed, void (*group)(cylgen_rng *rng, long g, spawn_tally *t),
                 spawn_tally *t);

typedef struct spawn_mode {
    const char *name;
    int (*run)(void); /* nonzero when every check held */
} spawn_mode;

/* Fills isas and quick, runs the mode argv[1] names and prints "<mode>: ok" or
 * "<mode>: FAILED"; returns main's status (2 with the usage for an unknown mode). */
int spawn_main(int argc, char **argv, const char *prog, const spawn_mode *modes, size_t n);

#endif
