/* SPDX-License-Identifier: MIT */
/* leaf.h - the leaf scenarios: one ray against leaves of 4, 8 or 16 cylinders (or
 * spheres, or cones), against the same work done one shape at a time. */
#ifndef CYLBENCH_LEAF_H
#define CYLBENCH_LEAF_H

#include "bench.h"
#include "workloads.h"

/* The scenes: leaf-l1, leaf-l2, sphere-leaf, cone-leaf. */
#define LEAF_NSIZE 4

typedef struct leaf_report {
    int have;                /* the scenario ran */
    int run;                 /* cylinders each ray meets */
    int ncyl[LEAF_NSIZE];    /* shapes in the scene: cylinders with data in L1, in L2;
                                   spheres in L1; cones in L1 */
    int bytes_per_cyl[3];    /* a leaf of 4, 8, 16: its bytes over its cylinders */
    char best[16];           /* the path of the one-lane packet calls */
    size_t diff[LEAF_NSIZE]; /* answers that differ from the scalar loop's, all configs */
    int sphere;              /* sphere-leaf ran */
    int cone;                /* cone-leaf ran */
} leaf_report;

/* 1 when this build of the harness and the library have the leaf kernels. */
int leaf_available(void);

/* Does the --scenario= list select any of leaf-l1, leaf-l2, sphere-leaf, cone-leaf? */
int leaf_selected(const options *opt);

/* Builds the scenes, times every configuration in rounds, appends rows with scenario
 * "leaf-l1" / "leaf-l2" / "sphere-leaf" / "cone-leaf" (ns per ray-shape test) to
 * `results`. */
void leaf_run(const options *opt, result_list *results, leaf_report *rep);

#endif
