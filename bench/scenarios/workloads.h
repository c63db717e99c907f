/* SPDX-License-Identifier: MIT */
/* workloads.h - the scenarios: which rays, which cylinders (or sphere), which flag sets
 * and widths. */
#ifndef CYLBENCH_WORKLOADS_H
#define CYLBENCH_WORKLOADS_H

#include "bench.h"

/* The number of scenarios known, and the i-th one's name and group ("main", "stream",
 * "skips", "lanes", "spheres", "stress"). */
int workloads_count(void);
const char *workloads_name(int i);
const char *workloads_group(int i);

/* Does the --scenario= list select scenario i? NULL selects all. Accepts names, group
 * names, and "all". */
int workloads_selected(int i, const char *list);

/* Does the --scenario= list (NULL: everything) select a scenario outside the table,
 * by its name or its group? */
int workloads_selected_name(const char *list, const char *name, const char *group);

/* Builds scenario i (rays drawn, cylinders prepared). 0 on success. */
int workloads_build(int i, workload *w, const options *opt);
void workloads_free(workload *w);

/* Does the --scenario= list name anything unknown? Prints it and returns 1. */
int workloads_check_list(const char *list);

#endif
