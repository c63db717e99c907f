/* SPDX-License-Identifier: MIT */
/* bench.h - what the harness's parts share: options, workloads, and one result row. */
#ifndef CYLBENCH_BENCH_H
#define CYLBENCH_BENCH_H

#include "cylray.h"
#include "rays.h"
#include "stats.h"
#include "textbook.h"

#include <stddef.h>
#include <stdint.h>

/* Rays per timed batch: 512 rays of packets and hits take about 28 KB, so a batch stays
 * in the 48 KB L1 data cache while it is timed. */
#define BENCH_BATCH 512
#define BENCH_MAXCYL 64
#define BENCH_MAXSAMP 128 /* samples kept per configuration */

/* Widths: the packet sizes and the stream API (any length). */
enum { BW_4, BW_8, BW_16, BW_STREAM, BW_COUNT };
extern const int bench_width_lanes[BW_COUNT]; /* 4, 8, 16, 0 */
extern const char *const bench_width_name[BW_COUNT];

/* Flag sets. REFINE and FAST are measured with normals, beside "normal". */
enum { OP_T, OP_NORMAL, OP_OCC, OP_REFINE, OP_FAST, OP_COUNT };
extern const char *const bench_op_name[OP_COUNT];
extern const unsigned bench_op_flags[OP_COUNT];

/* The builds of the textbook peer (TB_*) as pseudo-ISAs, after the real ones. */
#define BENCH_ISA_TEXTBOOK CYLRAY_ISA_COUNT
#define BENCH_NISA (CYLRAY_ISA_COUNT + TB_COUNT)
const char *bench_isa_name(int isa);
static inline int bench_is_textbook(int isa)
{
    return isa >= BENCH_ISA_TEXTBOOK;
}

typedef struct options {
    unsigned isa_mask;     /* bit per cylray_isa and textbook build */
    unsigned width_mask;   /* bit per BW_* */
    const char *scenarios; /* comma-separated names or groups, NULL for all */
    int quick;
    int flush_subnormals; /* --flush-subnormals: DAZ/FTZ set for the whole run */
    const char *out_dir;
    int reps;         /* timed samples per configuration */
    double sample_ns; /* length of one sample */
    double warm_ns;   /* warm-up before the first configuration of an ISA */
    size_t big_rays;  /* rays in the larger-than-cache stream */
    int scene_w, scene_h;
} options;

/* The exact reference's answer for one ray (closest hit over the workload's cylinders). */
typedef struct ref_answer {
    double t; /* exact t; meaningless on a miss */
    int hit, part;
} ref_answer;

/* One scenario's rays and cylinders, timed in L1-sized batches (or, for a big stream,
 * as one pass over arrays far larger than the caches). */
typedef struct workload {
    const char *name, *group, *what;
    raysoa rays;  /* master copy; tmax here is never modified */
    size_t batch; /* rays per timed batch; rays.n for a big stream */
    int ncyl;
    int grouped;           /* 0: every ray meets every cylinder; k: ray i meets only
                                   cylinder i / k (the stress sets: 16 rays per cylinder) */
    cylray_cylinder *cyl;  /* ncyl */
    cylray_prepared *prep; /* ncyl, 64-byte aligned */
    tb_cylinder *tb;       /* ncyl, for the textbook peer */
    cylray_sphere *sph;    /* non-NULL: the shapes are ncyl spheres (cyl unused; prep
                                   and tbs from these) */
    tb_sphere *tbs;        /* ncyl with sph, for the textbook peer */
    cylray_cone *con;      /* non-NULL: the shapes are ncyl cones (as sph) */
    tb_cone *tbc;          /* ncyl with con, for the textbook peer */
    unsigned ops;          /* bit per OP_* measured */
    unsigned widths;       /* bit per BW_* measured (before the --width filter) */
    int textbook;          /* also time and check the textbook peer */
    int big;               /* stream over arrays far larger than the caches */
    uint32_t lanes;        /* the packets' active lanes (bit per lane; all: ~0u);
                                   the rays of the others hold a fill, never looked at */
    ref_answer *ref;       /* per ray, or NULL without a reference */
    size_t ref_stride;     /* big streams check every ref_stride-th ray */
    void **bands;          /* per ray, computed when a disagreement needs judging */
} workload;

typedef struct result {
    char scenario[24], group[16], isa[16], op[12];
    int isa_id, width_id, op_id;
    size_t rays_timed; /* rays per pass */
    int ncyl;
    stat5 ns;               /* ns per ray and cylinder: median, min, max, quartiles */
    double ticks;           /* median TSC ticks per ray and cylinder */
    double mrays;           /* 1e3 / median ns */
    double speedup;         /* scalar's median / this median, same scenario, width, op */
    double hit_frac;        /* share of rays with a hit (or occluded) */
    int reps;               /* samples the median is over */
    int samples, clean;     /* samples taken; of those, not interrupted */
    long passes_per_sample; /* set by the first visit's warm-up */
    double s_wall[BENCH_MAXSAMP], s_cpu[BENCH_MAXSAMP], s_tick[BENCH_MAXSAMP];
    unsigned char s_clean[BENCH_MAXSAMP];
    int cpu_timed; /* too few clean samples (a busy machine): the figures
                                   come from the thread's CPU time instead of wall time */
    /* error side (have_err == 0: no reference in this build) */
    int have_err;
    size_t n_cmp, n_hits_ref;
    double ulp_med, ulp_p99, ulp_max;
    double xs_p99, xs_max;        /* ulps outside the reference's tolerance band (rays within
                                   1 ulp of exact count as 0) */
    size_t extra_hits, lost_hits; /* kernel hit where the exact answer misses; reverse */
    size_t part_diff;             /* both hit, different part (side, cap, back face) */
    size_t unexcused;             /* of those, outside the reference's tolerance band */
    /* big streams */
    double gbytes_s, memcpy_gbytes_s;
} result;

typedef struct result_list {
    result *r;
    size_t n, cap;
} result_list;

result *results_push(result_list *l);

/* Cylinder tests per ray in one pass. */
static inline int bench_tests_per_ray(const workload *w)
{
    return w->grouped ? 1 : w->ncyl;
}

/* timing.c: warms (workload, ISA, width, op) up and appends `want` clean samples (ns,
 * CPU ns, TSC ticks per ray) to *r; called once per round, so that every configuration
 * is sampled across the whole run and a busy spell of the machine hits all alike. */
int bench_sample(const workload *w, int isa, int width_id, int op, const options *opt,
                 result *r, int want, int first_of_isa);
/* timing.c: the median and spread of the samples (reps: how many were wanted). */
void bench_summarize(const workload *w, result *r, int reps);
/* timing.c: the memcpy bound of a big stream, in bytes per second. */
double bench_memcpy_gbs(const workload *w, const options *opt);

/* accuracy.c */
int accuracy_available(void);
void accuracy_reference(workload *w); /* fills w->ref (or leaves it NULL) */
void accuracy_release(workload *w);
/* Runs the configuration once more on the same rays and compares with w->ref. */
void accuracy_measure(const workload *w, int isa, int width_id, int op, result *r);

#endif
