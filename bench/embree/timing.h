/* SPDX-License-Identifier: MIT */
/* timing.h - the timing of one scene with one ISA: every variant, ray set and packet
 * size, repeated over several runs, the variants visited in turn in each. */
#ifndef EB_TIMING_H
#define EB_TIMING_H

#include "run.h"
#include "trace.h"

/* One variant's rays on one scene: the camera's, and the secondary rays spawned from
 * their hits. */
typedef struct eb_frame {
    eb_rays prim, shadow, bounce;
    float *shadow_tfar; /* the shadow rays' tfar before tracing */
} eb_frame;

int eb_frame_alloc(eb_frame *f, size_t n); /* 0 on success */
void eb_frame_free(eb_frame *f);

/* How to time. */
typedef struct eb_timing {
    int runs, reps, threads;
    int cpu_clock; /* rates from the CPU time the process got, not the wall time */
    int packet_on[EB_NPACKETS];
} eb_timing;

/* Times each variant v with built[v] (its camera rays in fr[v].prim) t->runs times,
 * writing each run's rates and their medians in rows[v], and spawns its secondary rays
 * (once, in the first run). fr[v] keeps the answers of the last pass of each ray set,
 * which the judging and the pictures read. */
void eb_time_scene(const eb_timing *t, cylray_isa isa, const eb_geom geo[EB_NVARIANTS],
                   eb_frame fr[EB_NVARIANTS], const int built[EB_NVARIANTS],
                   eb_row rows[EB_NVARIANTS]);

#endif
