/* SPDX-License-Identifier: MIT */
/* conref_eval.h - what the cone's exact intersection (conref.c) gives its band
 * (conref_band.c): the candidates, their margins and the evaluation in binary128. */
#ifndef CONREF_EVAL_H
#define CONREF_EVAL_H

#include "conref.h"
#include "quad.h"

/* The candidates. */
enum { K_FRONT, K_BACK, K_LO, K_HI, K_COUNT };
/* Each candidate's margins, true when >= 0: [0] the discriminant (side) or the disc
 * (caps), [1] [2] the slab's two planes (side only), [3] t - tmin, [4] tmax - t. */
enum { G_MEET, G_ZLO, G_ZHI, G_GE, G_LE, G_COUNT };

typedef struct cin_q {
    cylq w[3], d[3], a[3], r0, r1;
} cin_q;

typedef struct crec {
    int exists[K_COUNT]; /* a root or plane crossing at a finite t */
    cylq t[K_COUNT];
    int back[K_COUNT];
    cylq m[K_COUNT][G_COUNT], mw[K_COUNT][G_COUNT];
    cylq u[3], wp[3], dp[3], zw, zd, k, L, r0;
    cylq A, B, C; /* the side: |x_perp(t)|^2 - r(z(t))^2 = A t^2 + 2 B t + C */
} crec;

int conref_present_(unsigned flags, int kand);
void conref_eval_(const cin_q *q, cylq tmin, cylq tmax, crec *r);
int conref_first_(const crec *r, const unsigned char valid[K_COUNT]);
void conref_valid_parts_(const crec *r, unsigned flags, unsigned char valid[K_COUNT]);
int conref_part_(const crec *r, int kand);
void conref_normal_(const crec *r, int kand, int ff, double n[3]);
void conref_in_(const cylray_cone *c, const float o[3], const float d[3], cin_q *q);

#endif
