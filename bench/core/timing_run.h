/* SPDX-License-Identifier: MIT */
/* timing_run.h - a configuration made ready to run: the rays packed for its width, its
 * outputs, and the pass function that sends one batch through the kernel. */
#ifndef CYLBENCH_TIMING_RUN_H
#define CYLBENCH_TIMING_RUN_H

#include "bench.h"

typedef struct runner runner;
typedef uint64_t (*pass_fn)(const runner *x, size_t batch);

struct runner {
    const workload *w;
    const cylray_kernels *k; /* NULL for the textbook peer */
    tb_stream_fn tb;         /* the textbook peer's build, or NULL */
    tb_sphere_fn tbs;        /* the same for a workload of spheres */
    tb_cone_fn tbc;          /* and of cones */
    int op, width_id, restore_outside;
    unsigned flags;
    pass_fn pass;
    size_t np, ppb; /* packets in all, per batch */
    void *pk, *hit; /* cylray_rayN[np], cylray_hitN[np] */
    float *tmax;    /* streams: the working tmax (the master stays intact) */
    float *t, *nx, *ny, *nz;
    int32_t *part;
    uint8_t *occ;
};

int runner_init(runner *x, const workload *w, int isa, int width_id, int op);
void runner_free(runner *x);

/* Runs the configuration once over all rays from the original tmax and reports per ray
 * whether it hit (or is occluded) and, for intersections, its t and part. */
int bench_run_once(const workload *w, int isa, int width_id, int op, uint8_t *hit, float *t,
                   int32_t *part);

#endif
