/* SPDX-License-Identifier: MIT */
/* test_rc.h - what the round cone's tests share (test_rcgen.c): random round cones and rays
 * of ten kinds, a solver in double whose answers every band must allow, and answers from
 * inside a band's box. */
#ifndef TEST_RC_H
#define TEST_RC_H

#include "rcref.h"

#include <stdint.h>

enum {
    RC_ORDINARY,
    RC_FAR,     /* origins 1e3..1e6 hull sizes away */
    RC_STRONG,  /* r1 / r0 in 1e-3..1e3 */
    RC_SLIGHT,  /* r1 = r0 +- 1..4 ulps */
    RC_CAPSULE, /* r1 = r0 */
    RC_POINT,   /* one radius 0 */
    RC_NESTED,  /* |p1 - p0| < |r1 - r0| */
    RC_ZERO,    /* p1 = p0 */
    RC_THIN,    /* length / radius about 1e4 */
    RC_EDGE,    /* |p1 - p0| just above |r1 - r0| */
    RC_COUNT
};

extern const char *const rc_names[RC_COUNT];

typedef struct {
    rcref_round_cone rc;
    float o[3], d[3], tmin, tmax;
} rc_case;

/* n cases of kind cat from seed: a quarter with one or both ends open (the rest closed), a
 * fifth with tmin near the aimed point, a sixth with tmax there, a seventh from it. */
void rc_make(int cat, uint64_t seed, int n, rc_case *out);
/* Nonzero when CYLRAY_TEST_QUICK is set (sanitizer and qemu runs): the round cone's tests
 * then take a quarter of their cases (the same cases' first quarter). */
int rc_quick(void);
/* Uniform in [lo, hi) from the sequence *s seeds. */
double rc_unif(uint64_t *s, double lo, double hi);
/* The double solver's answer: 1 and *t, *part for a hit. */
int rc_dbl_solve(const rc_case *c, unsigned flags, float *t, int *part);
/* The exact answer for c's inputs moved to a random point of its band's box (up to 1.9
 * of the 2 ulps of each input; *s the draws): 1 and *t, *part and the normal n for a
 * hit. The band must allow it. */
int rc_inside_box(const rc_case *c, unsigned flags, uint64_t *s, int *part, float *t,
                  double n[3]);
/* Judges a solver's answer (what: "inside the box", "double solver") to case i of the
 * category cat under flags against the band b: returns the verdict, *ub the ulps beyond;
 * one judged wrong or more than allow ulps beyond counts in *bad, the first 4 printed. */
int rc_judge_answer(const cylref_band *b, const char *what, const char *cat, int i,
                    unsigned flags, int hit, float t, int part, double allow, int *bad,
                    double *ub);
/* The band over rcgen.h's categories (test_rcgen.c). */
void test_rcgen_bands(void);

#endif
