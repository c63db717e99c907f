/* SPDX-License-Identifier: MIT */
/* judge.h - a variant's answers against the exact reference: wrong hit/miss, t and
 * normal error, self-intersections of secondary rays. */
#ifndef EB_JUDGE_H
#define EB_JUDGE_H

#include "exact.h"
#include "geom.h"

/* One judged ray, with its exact answer (computed once, shared by the variants). */
typedef struct eb_sample {
    float o[3], d[3], tmin, tmax;
    size_t pixel; /* the camera ray of this pixel, or SIZE_MAX for aimed rays */
    int xhit;
    uint32_t xid;
    cylref_hit xh;
} eb_sample;

typedef struct eb_err {
    size_t rays;      /* judged */
    size_t wrong;     /* unexcused hit/miss or wrong-object answers */
    size_t leak;      /* of those: the ray went past (or through) the exact first surface */
    size_t phantom;   /* of those: a hit where, or before, there is none */
    size_t excused;   /* disagreements within the reference's tolerance band */
    size_t nt, nn;    /* t and normal errors collected (hits on the exact cylinder) */
    double *t_ulps;   /* |t - t_exact| in float ulps */
    double *t_beyond; /* float ulps outside the tolerance band (0 inside) */
    double *n_rad;    /* angle to the exact normal, up to sign */
    size_t sec, self; /* secondary rays judged, and those that hit their own surface */
} eb_err;

int eb_err_init(eb_err *e, size_t cap);
void eb_err_free(eb_err *e);

/* Fills s with the exact answer for its ray. */
void eb_sample_solve(eb_sample *s, const eb_ref *ref);

/* Judges the answer (vprim, vt, vng) of a variant to sample s. */
void eb_judge(eb_err *e, const eb_ref *ref, const eb_sample *s, uint32_t vprim, float vt,
              const float vng[3]);

/* A secondary ray that left the exact first surface of s (a front face) in direction
 * w, and the primitive it hit first: a hit on that same convex surface is a
 * self-intersection. */
void eb_judge_secondary(eb_err *e, const eb_sample *s, const float w[3], uint32_t vprim);

/* Median, 99th percentile and maximum of n values (sorted in place). */
void eb_quantiles(double *v, size_t n, double *med, double *p99, double *max);

#endif
