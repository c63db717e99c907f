/* SPDX-License-Identifier: MIT */
/* leaf.h - the leaf scenario: one ray against leaves of 4, 8 or 16 cylinders, against
 * the same work done one cylinder at a time. */
#ifndef CYLBENCH_LEAF_H
#define CYLBENCH_LEAF_H

#include "bench.h"
#include "workloads.h"

typedef struct leaf_report {
    int have;             /* the scenario ran */
    int run;              /* cylinders each ray meets */
    int ncyl[2];          /* cylinders in the scene: data in L1, in L2 */
    int bytes_per_cyl[3]; /* a leaf of 4, 8, 16: its bytes over its cylinders */
    char best[16];        /* the path of the one-lane packet calls */
    size_t diff[2];       /* answers that differ from the scalar loop's, all configs */
} leaf_report;

/* 1 when this build of the harness and the library have the leaf kernels. */
int leaf_available(void);

/* Builds the scenes, times every configuration in rounds, appends rows with scenario
 * "leaf-l1" / "leaf-l2" (ns per ray-cylinder test) to `results`. */
void leaf_run(const options *opt, result_list *results, leaf_report *rep);

#endif
