/* SPDX-License-Identifier: MIT */
/* scene.h - a small realistic scene (a fence, pipes, molecules on a floor) traced with
 * the packet API, written as a PNG and timed as a workload. */
#ifndef CYLBENCH_SCENE_H
#define CYLBENCH_SCENE_H

#include "bench.h"

typedef struct scene_report {
    int have, w, h, ncyl;
    char image[600];           /* path of the PNG, or "" if it could not be written */
    char plain_isa[16];        /* the path the plain entry points took */
    size_t primary, shadow;    /* rays per frame */
    long pix_diff[BENCH_NISA]; /* pixels that differ from the plain render, per ISA */
    int timed[BENCH_NISA];
} scene_report;

/* Renders the scene with the plain entry points (the image), then times a frame per ISA
 * through the kernels table and with the plain entry points; appends rows with
 * scenario "scene" to `results`. */
void scene_run(const options *opt, scene_report *sc, result_list *results);

#endif
