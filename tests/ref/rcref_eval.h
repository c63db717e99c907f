/* SPDX-License-Identifier: MIT */
/* rcref_eval.h - what the round cone's exact intersection (rcref.c) gives its band
 * (rcref_band.c): the hull's three pieces along the ray, their margins and the
 * evaluation in binary128. */
#ifndef RCREF_EVAL_H
#define RCREF_EVAL_H

#include "quad.h"
#include "rcref.h"

/* The pieces, in the order that breaks ties (a seam is the side's). */
enum { RP_F, RP_S0, RP_S1, RP_COUNT };
/* A piece's margins, each true when >= 0: [0] the line meets it (a sphere's discriminant
 * A r^2 - |W x d|^2; the frustum's: minus the least of its quadratic along the tangent
 * slab's stretch of the line), [1] a line level across the axis lies inside the slab (the
 * frustum's, where d.a = 0; 1 otherwise and for a sphere). */
enum { RM_MEET, RM_LEN, RM_COUNT };
/* An outcome: 2 * piece + 0 (its entry) or 1 (its exit); RX_SEG: the ray runs along a
 * generator line of the side and starts on it (t = tmin); -1 a miss. */
enum { RX_SEG = 2 * RP_COUNT };

typedef struct rin_q {
    cylq w[3], d[3], a[3], r0, r1; /* w = o - (p0 + p1) / 2, a = p1 - p0 */
    unsigned flags;                /* the shape's: which of two equal spheres is taken */
} rin_q;

typedef struct rrec {
    int nested; /* one sphere inside the other: the hull is sphere `big` alone */
    int big;
    int ex[RP_COUNT]; /* the piece meets the ray: [lo, hi] */
    cylq s0;          /* the origin moved to o + s0 d; lo and hi count t from there */
    cylq lo[RP_COUNT], hi[RP_COUNT];
    cylq face[RP_COUNT], facew[RP_COUNT]; /* at hi: > 0 the ray leaves (a back face) */
    cylq m[RP_COUNT][RM_COUNT], mw[RP_COUNT][RM_COUNT];
    cylq qa[RP_COUNT], qb[RP_COUNT], qc[RP_COUNT]; /* each piece's A t^2 + 2 B t + C */
    cylq sl, sh;                                   /* the frustum's slab */
    cylq d2, d2w;                                  /* |a|^2 - (r1 - r0)^2: > 0 not nested */
    int fseg; /* the line lies on the tangent cone (its quadratic is 0) */
    cylq tmin, tmax;
    cylq W[3], d[3], a[3], aa, dr, r0, r1; /* W = o + s0 d - p0 */
} rrec;

void rcref_in_(const rcref_round_cone *s, const float o[3], const float d[3], rin_q *q);
/* force: -1 as the radii and length say, 0 read as not nested, 1 as nested. */
void rcref_eval_(const rin_q *q, int force, cylq tmin, cylq tmax, rrec *r);
/* The pieces whose entry and exit are the hull's (-1: the ray misses the hull). */
int rcref_entry_(const rrec *r);
int rcref_exit_(const rrec *r);
/* 1 when piece p is a surface that is there under the shape's flags. */
int rcref_present_(const rrec *r, unsigned flags, int p);
/* The outcome under flags (the shape's | CYLRAY_CULL_BACK), -1 for a miss. */
int rcref_decide_(const rrec *r, unsigned flags);
cylq rcref_t_(const rrec *r, int x);
int rcref_part_(const rrec *r, int x);
void rcref_normal_(const rrec *r, int x, int ff, double n[3]);

#endif
