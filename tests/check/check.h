/* SPDX-License-Identifier: MIT */
/* check.h - what the parts of cylcheck share: the cases with their exact bands, one
 * kernel answer per lane, the verdict rules and the statistics. */
#ifndef CYLCHECK_H
#define CYLCHECK_H

#include <stddef.h>
#include <stdint.h>

#include "cylray.h"
#include "congen.h"
#include "conref.h"
#include "cylref.h"
#include "gen.h"
#include "rcgen.h"
#include "sphgen.h"
#include "sphref.h"

/* ---- the criteria --------------------------------------------------------------- */

/* t may lie this many float ulps outside the exact band (docs/design.md section 4). */
#define TOL_T_ULPS 4.0
/* With CYLRAY_FAST (hardware reciprocal / rsqrt estimates plus one Newton step): twice
 * the plain bound. Measured: no FAST answer outside the band at all, and the same p99
 * against the exact t as without FAST, on every ISA here. */
#define TOL_T_ULPS_FAST 8.0
/* |n| - 1. */
#define TOL_NORMAL_LEN 1e-5
/* Angle between the kernel's normal and the exact one, beyond what the band's input
 * perturbation itself turns the normal by (n_spread). Measured: at most 3e-7 rad on
 * every ISA and mode (about 2.5 float epsilons). */
#define TOL_NORMAL_ANGLE 1e-6

/* Headline numbers the default path (no REFINE, no FAST) must reach. */
#define HEADLINE_P99_ULPS 2.5
#define HEADLINE_FAR_MAX_ULPS 2.0

/* Categories: the cylinder generators' (gen.h), the fixed regression cases (regress.c),
 * then the sphere generators' (sphgen.h), CAT_SPHERE + SPHGEN_*, then the cone
 * generators' (congen.h), CAT_CONE + CONGEN_*, then the round cone generators'
 * (rcgen.h), CAT_ROUND + RCGEN_*. */
#define CAT_REGRESS CYLGEN_COUNT
#define CAT_SPHERE (CYLGEN_COUNT + 1)
#define CAT_CONE (CAT_SPHERE + SPHGEN_COUNT)
#define CAT_ROUND (CAT_CONE + CONGEN_COUNT)
#define CAT_COUNT (CAT_ROUND + RCGEN_COUNT)
static inline int cat_is_sphere(int category)
{
    return category >= CAT_SPHERE && category < CAT_CONE;
}
static inline int cat_is_cone(int category)
{
    return category >= CAT_CONE && category < CAT_ROUND;
}
static inline int cat_is_round(int category)
{
    return category >= CAT_ROUND && category < CAT_COUNT;
}
const char *cat_name(int category);
int cat_find(const char *name); /* -1 when unknown */

/* The modes the statistics are kept apart for. */
enum { MODE_PLAIN, MODE_REFINE, MODE_FAST, MODE_COUNT };
static inline int mode_of(unsigned flags)
{
    return (flags & CYLRAY_FAST)     ? MODE_FAST
           : (flags & CYLRAY_REFINE) ? MODE_REFINE
                                     : MODE_PLAIN;
}

/* ---- cases ---------------------------------------------------------------------- */

typedef struct ref_case {
    cylgen_case c; /* the ray; its cylinder unless `sphere` */
    int sphere;    /* the shape is sph, c.cyl is unused */
    cylray_sphere sph;
    int cone; /* the shape is con, c.cyl is unused */
    cylray_cone con;
    int round; /* the shape is rnd, c.cyl is unused */
    cylray_round_cone rnd;
    cylref_band band[2]; /* [0]: flags without CULL_BACK, [1]: with */
    int index;           /* within its category's case list */
} ref_case;

/* Prepares the case's shape, cylinder or sphere. */
cylray_status prepare_case(cylray_prepared *p, const ref_case *rc);

/* One kernel answer for one lane, with what the checks on memory need. */
typedef struct lane_out {
    int hit;
    float t, n[3];
    int32_t part;
} lane_out;

/* ---- options and shared state --------------------------------------------------- */

typedef struct options {
    uint64_t seed;
    int isa;        /* -1: every ISA the CPU has */
    int category;   /* -1: all */
    int only_case;  /* -1: all */
    int flags_only; /* -1: all 32 combinations */
    int fast_only;  /* only the combinations with CYLRAY_FAST */
    size_t n;       /* packet cases per category (multiple of 16) */
    int quick, report, verbose;
    int max_print;    /* failures printed in full */
    int headline;     /* assert the headline numbers */
    double show_ulps; /* print every hit whose t is this many ulps off the exact t (0: no) */
} options;

extern options opt;
extern long failures;

/* ---- statistics ------------------------------------------------------------------ */

typedef struct stat_cell {
    double *ulps; /* t error vs exact, hits with the exact part */
    size_t n_ulps, cap_ulps;
    long lanes, exact_hits, kernel_hits;
    long hm_excused, hm_unexcused;        /* hit/miss disagreements with the exact answer */
    long part_excused, part_unexcused;    /* part disagreements */
    long t_beyond;                        /* t outside the band by more than the tolerance */
    double max_beyond;                    /* ulps beyond the band, worst */
    double max_angle, max_angle_excess;   /* normal angle error; beyond n_spread */
    double max_len;                       /* ||n| - 1| */
    long vs_scalar, same_as_scalar;       /* lanes compared with scalar, bitwise equal */
    long scalar_hm;                       /* hit/miss or part differs from scalar */
    double max_vs_scalar;                 /* t ulps between the two (same part) */
    long rim_rays, rim_missed, rim_later; /* rim category: exact hit at the rim */
} stat_cell;

stat_cell *stat_at(int isa, int category, int mode);
void stat_add_ulps(stat_cell *s, double u);
/* Sorts and reads percentile p (0..1) of the t errors; NAN when empty. */
double stat_percentile(stat_cell *s, double p);
void stats_report(void);
/* Checks the headline numbers for one ISA (default mode); prints them; returns the
 * number of violated ones. */
int stats_headline(int isa);
/* Frees the samples and zeroes every counter. */
void stats_free(void);

/* ---- verdicts -------------------------------------------------------------------- */

typedef struct lane_ctx {
    const cylray_kernels *k;
    unsigned flags;
    int category;
    const char *width; /* "4", "8", "16", "stream" */
    int lane;
} lane_ctx;

/* Judges one lane's answer against the exact band (and the scalar answer when not
 * NULL); counts, and prints a failure. */
void check_lane(const lane_ctx *lc, const ref_case *rc, const lane_out *got,
                const lane_out *scalar);
/* A failure that is not about the numbers (memory, masks, return values). */
void fail_memory(const lane_ctx *lc, const ref_case *rc, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
void print_case(const ref_case *rc, unsigned flags);
const char *flags_name(unsigned flags);

/* n_packet cases of a category (one cylinder per batch of 16), then one stream segment
 * per length (one cylinder each), all with their exact bands (only case opt.only_case
 * when that is set). *total gets the count; free() the result. */
ref_case *make_cases(int cat, uint64_t seed, size_t n_packet, const size_t *lengths,
                     size_t n_lengths, size_t *total);

/* The regression cases: inputs that once made a kernel fail, and float-exact hand cases
 * whose answer is known. Each is repeated over one batch of 16 (its own cylinder) and
 * once as a stream of 3. Same layout as make_cases. */
ref_case *make_regress_cases(size_t *n_packet, const size_t **lengths, size_t *n_lengths,
                             size_t *total);
/* What regression case `index` is about. */
const char *regress_why(int index);

/* ---- the drivers ----------------------------------------------------------------- */

/* Every width of packet over cases[0..n) (n a multiple of CYLGEN_BATCH, one cylinder
 * per batch), with random active masks and poisoned outputs; scalar[i] (or NULL) is the
 * scalar path's answer for cases[i]. */
void drive_packets(const cylray_kernels *k, unsigned flags, int category, const ref_case *cases,
                   size_t n, const lane_out *scalar, uint64_t seed);
/* Streams of the given lengths over consecutive cases (each segment one cylinder),
 * misaligned, with guard zones. */
void drive_streams(const cylray_kernels *k, unsigned flags, int category, const ref_case *cases,
                   const size_t *lengths, size_t n_lengths, const lane_out *scalar,
                   uint64_t seed);
/* The scalar path's answers for cases[0..n), one call per cylinder-sharing segment. */
void scalar_answers(const cylray_kernels *scalar, unsigned flags, const ref_case *cases,
                    const size_t *segments, size_t n_segments, lane_out *out);

#endif
