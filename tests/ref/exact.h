/* SPDX-License-Identifier: MIT */
/* exact.h - inside the reference: one exact evaluation as a record of the quantities whose
 * signs decide the answer, and the decision logic as a function of those signs alone.
 *
 * Splitting "compute every quantity" from "decide from the comparisons" is what lets
 * band.c ask which answers become possible when some comparisons are too close to call. */
#ifndef CYLREF_EXACT_H
#define CYLREF_EXACT_H

#include "cylref.h"
#include "quad.h"

/* The inputs in binary128; perturbations move them off the float grid. */
typedef struct qin {
    cylq o[3], d[3], c[3], v[3], R, H;
    int kind;      /* QK_* */
    unsigned caps; /* QK_CAPPED: CYLRAY_CAPPED_LO | CYLRAY_CAPPED_HI */
} qin;

enum { QK_INFINITE, QK_OPEN, QK_CAPPED };

/* Candidate hit parameters ("primitives"): entry and exit of the infinite solid (the
 * side roots) and of the slab |z| <= H (the caps). */
enum { P_SLO, P_SHI, P_BLO, P_BHI, P_COUNT };

/* The comparisons; each is true when its margin is >= 0 (M_NOTPAR: > 0). */
enum {
    M_NOTPAR,  /* A = |d x v|^2 > 0: not parallel to the axis */
    M_DISC,    /* A R^2 - g^2 >= 0: the line meets the infinite cylinder */
    M_INTUBE,  /* R^2 v.v - |w x v|^2 >= 0: (parallel) origin inside the infinite solid */
    M_ZN,      /* open tube: H|v| - |z| >= 0 at the near root */
    M_ZF,      /* ... at the far root */
    M_SLABOK,  /* capped, d.v = 0: H|v| - |w.v| >= 0 */
    M_INSIDE,  /* capped: side entry >= slab entry: the entry is on the side */
    M_OUTSIDE, /* capped: slab exit >= side exit: the exit is on the side */
    M_X1,      /* capped: slab exit >= side entry */
    M_X2,      /* capped: side exit >= slab entry */
    M_GE_MIN,  /* P_COUNT of them: primitive - tmin >= 0 */
    M_LE_MAX = M_GE_MIN + P_COUNT, /* P_COUNT of them: tmax - primitive >= 0 */
    M_COUNT = M_LE_MAX + P_COUNT
};

typedef struct qrec {
    int valid; /* inputs describe a solid and a ray */
    int kind;
    unsigned caps;     /* the discs that are part of the surface */
    int par_exact;     /* A == 0 exactly: the side roots do not exist at all */
    int dv_zero;       /* d.v == 0 exactly: the slab is all or nothing */
    int dv_pos;        /* d.v > 0: the slab is entered at -H (CAP_LO) */
    cylq tp[P_COUNT];  /* +-INFINITY where unbounded */
    cylq m[M_COUNT];   /* the margins */
    cylq mw[M_COUNT];  /* how close to 0 a float kernel may legitimately get it wrong */
    int mrel[M_COUNT]; /* the comparison matters for this kind of cylinder */
    /* for the normals */
    cylq w[3], d[3], v[3], V;
} qrec;

/* An answer: hit, part (with BACKFACE), and the primitive its t comes from. */
typedef struct qout {
    int hit, part, prim;
} qout;

/* Builds q from the float inputs; 0 when the cylinder or the ray is unusable. */
int qin_from_float(qin *q, const cylray_cylinder *cyl, const float o[3], const float d[3]);
/* Evaluates every primitive and margin exactly. */
void q_eval(const qin *q, cylq tmin, cylq tmax, qrec *r);
/* The signs of r's margins, as decide() takes them. */
void q_bools(const qrec *r, unsigned char b[M_COUNT]);
/* The answer those comparison outcomes imply. */
qout q_decide(const qrec *r, const unsigned char b[M_COUNT], int cull);
/* The normal of answer o at its t (outward, or facing the ray when ff). */
void q_normal(const qrec *r, qout o, int ff, double n[3]);

/* Float spacing at |x|. */
double ref_float_ulp(double x);

#endif
