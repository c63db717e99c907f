/* SPDX-License-Identifier: MIT */
/* rcref.c - the exact ray/round-cone intersection (its tolerance band: rcref_band.c).
 *
 * The derivation (docs/design.md section 11 has it as prose).
 *
 * Let a = p1 - p0, L = |a|, u = a / L, dr = r1 - r0, k = dr / L, and for a point x let
 * z = (x - p0).u be its axial coordinate and rho = |x_perp| its distance from the axis.
 * The hull is the union of the spheres c(s) = p0 + s a, r(s) = r0 + s dr for s in [0, 1].
 *
 * Nested (L <= |dr|, p0 == p1 included): |c(s) - c(1)| = (1 - s) L <= (1 - s) |dr|, so
 * every sphere lies inside the one with the larger radius, which is the hull.
 *
 * Not nested (L > |dr|). In a plane through the axis, a line {n.x = h} touching both
 * circles from outside, n = (n_z, n_rho) a unit vector pointing away from both centres,
 * is at distance r_i from centre i: h - n.p_i = r_i. With p0 at z = 0 and p1 at z = L:
 * h = r0 and h - L n_z = r1, so n_z = -dr / L = -k (sin alpha = dr / L, alpha the cone's
 * half angle) and n_rho = sqrt(1 - k^2). Turned about the axis this line is the tangent
 * cone:
 *   - it touches sphere i along a circle (the seam) in the plane at s_i = -r_i dr / L
 *     from p_i along u, of radius r_i sqrt(1 - dr^2 / L^2);
 *   - its radius at z is rho(z) = (r0 + k z) / n_rho, r_i / sqrt(1 - dr^2 / L^2) at p_i's
 *     level; its apex (rho = 0) is at z = -r0 / k, outside the slab between the planes;
 *   - its outward unit normal is n = n_rho x_perp / |x_perp| - k u.
 * Sphere i's outward normal (x - p_i) / r_i has an axial component below -k (sphere 0)
 * or above it (sphere 1) exactly beyond its seam's plane, where the sphere is outside the
 * cone: so the hull's surface is the cone between the planes (CYLRAY_SIDE) and each
 * sphere beyond its plane (CAP_LO, CAP_HI), and the hull is the union of three convex
 * pieces: sphere 0, sphere 1, and the frustum F of the cone between the planes (the
 * planes are z0 = -r0 k and z1 = L - r1 k, z1 - z0 = (L^2 - dr^2) / L > 0; F's flat ends
 * are sections of the spheres). The hull being convex, a line meets its surface at its
 * entry and its exit only (or along a segment of a generator line); the entry is the
 * least of the pieces' entries, the exit the greatest of their exits, and the part is
 * the piece's, F's being the side (where F wins through its flat end, it ties with the
 * sphere's entry at the seam). A missing cap takes its piece's points off the surface:
 * an entry there is a hole, and the ray goes on to the exit (the side's inside, the
 * other cap, or the other hole). No margin decides a seam: a ray through a seam gets the
 * least of the pieces' entries, whichever piece gives it.
 *
 * Without cancellation and without L. 1 - k^2 = (L - |dr|)(L + |dr|) / L^2 = D2 / a.a with
 * D2 = a.a - dr^2 formed directly (a and dr are exact differences of floats in
 * binary128, a.a and dr^2 round once each: no square root, no 1 - k^2 formed). With
 * Z = (x - p0).a = z L the planes are Z0 = -r0 dr and Z1 = a.a - r1 dr, exactly, and the
 * cone is G(x) = 0 with
 *   G = D2 |(x - p0) x a|^2 - (r0 a.a + dr Z)^2 = a.a^2 ((1 - k^2) rho^2 - (r0 + k z)^2),
 * negative inside. Along the ray, X(t) = W + t d with W = o - p0, e = d x a, f = W x a,
 * Zw = W.a, Zd = d.a and Rw = r0 a.a + dr Zw: G = A t^2 + 2 B t + C with
 *   A = D2 e.e - dr^2 Zd^2,  B = D2 e.f - dr Zd Rw,  C = D2 f.f - Rw^2,
 * and on the cone A t + B = a.a^2 n_rho |x_perp| (d.n): the root where A t + B =
 * +sqrt(B^2 - A C) > 0 is where the ray leaves (a back face), whatever A's sign. F's
 * interval is the piece of {G <= 0} on the real nappe (with A < 0 the one towards which
 * r0 + k z grows, sign(dr Zd)) clipped to the slab Z0 <= Zw + t Zd <= Z1. Each sphere:
 * Lagrange's discriminant A r^2 - |W_i x d|^2 and the stable pair q / A, C / q (sphref.c).
 * Far origins: o is first moved to its closest approach to the centre, o + s0 d with
 * s0 = -(w.d) / (d.d), w = o - (p0 + p1) / 2, and s0 is added back to every t: the
 * quadratics' error then grows with the hull's size, not with the origin's distance. */
#include "bandutil.h"
#include "rcref_eval.h"

#include "exact.h"

#include <string.h>

int rcref_valid(const rcref_round_cone *s)
{
    if (!s || !ref_ends_ok(s->p0, s->p1, s->r0, s->r1))
        return 0;
    return (s->flags & ~(unsigned)CYLRAY_CAPPED) == 0;
}

static cylq widen(cylq mag)
{
    return (cylq)(4 * ref_float_ulp((double)q_abs(mag)));
}

static void cross3(const cylq a[3], const cylq b[3], cylq c[3])
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

void rcref_in_(const rcref_round_cone *s, const float o[3], const float d[3], rin_q *q)
{
    ref_axis_in(s->p0, s->p1, o, d, q->w, q->d, q->a);
    q->r0 = s->r0;
    q->r1 = s->r1;
    q->flags = s->flags;
}

/* Sphere piece p (centre at Wc from the moved origin, radius rad). */
static void sphere_piece(rrec *r, int p, const cylq Wc[3], cylq rad)
{
    cylq x[3];
    cross3(Wc, r->d, x);
    const cylq A = ref_dot3(r->d, r->d), B = ref_dot3(Wc, r->d), RR = rad * rad;
    const cylq C = ref_dot3(Wc, Wc) - RR, AR2 = A * RR, D = AR2 - ref_dot3(x, x);
    const cylq sq = q_sqrt(q_max(D, 0)), qq = -(B + q_copysign(sq, B));
    const cylq t1 = qq / A, t2 = qq != 0 ? C / qq : t1;
    r->lo[p] = q_min(t1, t2);
    r->hi[p] = q_max(t1, t2);
    if (D < 0) /* missed: both at the closest approach, where a box that meets it does */
        r->lo[p] = r->hi[p] = -B / A;
    r->face[p] = sq;
    r->facew[p] = widen(q_sqrt(A) * rad);
    r->qa[p] = A;
    r->qb[p] = B;
    r->qc[p] = C;
    r->m[p][RM_MEET] = D;
    r->mw[p][RM_MEET] = widen(AR2);
    r->m[p][RM_LEN] = 1;
    r->mw[p][RM_LEN] = 0;
    r->ex[p] = rad > 0 && D >= 0;
}

/* The frustum of the tangent cone between the seams' planes. */
static void frustum_piece(rrec *r)
{
    const int p = RP_F;
    const cylq *a = r->a, *W = r->W, *d = r->d, aa = r->aa, dr = r->dr;
    const cylq D2 = q_max(r->d2, 0), r0 = r->r0;
    cylq e[3], f[3];
    cross3(d, a, e);
    cross3(W, a, f);
    const cylq Zw = ref_dot3(W, a), Zd = ref_dot3(d, a), Rw = r0 * aa + dr * Zw;
    const cylq A = D2 * ref_dot3(e, e) - dr * dr * Zd * Zd;
    const cylq B = D2 * ref_dot3(e, f) - dr * Zd * Rw;
    const cylq C = D2 * ref_dot3(f, f) - Rw * Rw;
    const cylq Dq = B * B - A * C;
    r->qa[p] = A;
    r->qb[p] = B;
    r->qc[p] = C;
    const cylq sq = q_sqrt(q_max(Dq, 0)), qq = -(B + q_copysign(sq, B));
    const cylq ra = A != 0 ? qq / A : (cylq)INFINITY, rc = qq != 0 ? C / qq : ra;
    const cylq tm = B >= 0 ? ra : rc, tp = B >= 0 ? rc : ra; /* A t + B = -sq, +sq */
    const cylq inf = (cylq)INFINITY;
    cylq cl, ch; /* {G <= 0} on the real nappe */
    int cone = 1;
    r->fseg = 0;
    if (A > 0) {
        cl = tm;
        ch = tp;
        cone = Dq >= 0;
    } else if (A < 0) {
        if (Dq < 0)
            cl = -inf, ch = inf;
        else if (dr * Zd > 0)
            cl = tm, ch = inf;
        else
            cl = -inf, ch = tp;
    } else if (B != 0) {
        const cylq t = -C / (2 * B);
        cl = B < 0 ? t : -inf;
        ch = B < 0 ? inf : t;
    } else {
        cl = -inf, ch = inf;
        cone = C <= 0;
        r->fseg = C == 0;
    }
    const cylq Z0 = -r0 * dr, Z1 = aa - r->r1 * dr;
    cylq sl = -inf, sh = inf, slab = 1;
    if (Zd != 0) {
        const cylq ta = (Z0 - Zw) / Zd, tb = (Z1 - Zw) / Zd;
        sl = q_min(ta, tb);
        sh = q_max(ta, tb);
    } else {
        slab = q_min(Zw - Z0, Z1 - Zw);
    }
    r->sl = sl;
    r->sh = sh;
    const int lo_root = cl >= sl, hi_root = ch <= sh;
    r->lo[p] = lo_root ? cl : sl;
    r->hi[p] = hi_root ? ch : sh;
    r->face[p] = hi_root ? sq : A * r->hi[p] + B;
    r->facew[p] = hi_root ? widen(q_sqrt(q_max(B * B, q_abs(A * C))))
                          : widen(q_max(q_abs(A * r->hi[p]), q_abs(B)));
    /* Meeting F: the least of G along the slab's stretch is <= 0, a margin continuous in
     * the inputs whatever A's sign (a ray beside a generator line included); where F is
     * not met its entry and exit are put at that least value's t. */
    cylq gmin = inf, tg = 0;
    if (Zd != 0) {
        const cylq ts[3] = {sl, sh, A > 0 ? -B / A : sl};
        for (int j = 0; j < 3; j++) {
            const cylq t = ts[j];
            if (j == 2 && !(t > sl && t < sh))
                continue;
            const cylq g = (A * t + 2 * B) * t + C;
            if (g < gmin)
                gmin = g, tg = t;
        }
        r->m[p][RM_LEN] = 1;
        r->mw[p][RM_LEN] = 0;
    } else { /* A > 0: d across the axis */
        tg = -B / A;
        gmin = -Dq / A;
        r->m[p][RM_LEN] = slab;
        r->mw[p][RM_LEN] = widen(q_max(q_abs(Zw), q_max(q_abs(Z0), q_abs(Z1))));
    }
    r->m[p][RM_MEET] = -gmin;
    /* 4 float ulps of G's size at the side, a.a^2 (r0 + k z)^2 with r0 + k z at most the
     * larger radius in the slab (the terms' size at some t of the ray may be far larger:
     * a float kernel compares in a frame of its own) */
    const cylq rm = q_max(r0, r->r1);
    r->mw[p][RM_MEET] = widen(aa * aa * rm * rm);
    r->ex[p] = cone && slab >= 0 && r->lo[p] <= r->hi[p] && q_isfinite(r->lo[p]) &&
               q_isfinite(r->hi[p]);
    if (!r->ex[p])
        r->lo[p] = r->hi[p] = tg;
}

void rcref_eval_(const rin_q *q, int force, cylq tmin, cylq tmax, rrec *r)
{
    memset(r, 0, sizeof *r);
    r->tmin = tmin;
    r->tmax = tmax;
    memcpy(r->d, q->d, sizeof r->d);
    memcpy(r->a, q->a, sizeof r->a);
    r->r0 = q->r0;
    r->r1 = q->r1;
    r->aa = ref_dot3(q->a, q->a);
    r->dr = q->r1 - q->r0;
    r->d2 = r->aa - r->dr * r->dr;
    r->d2w = widen(r->aa);
    r->nested = force < 0 ? !(r->d2 > 0) : force;
    /* the larger sphere; of two equal ones (p0 == p1), sphere 0 when its end is capped */
    r->big = q->r1 > q->r0 || (q->r1 == q->r0 && !(q->flags & CYLRAY_CAPPED_LO));
    /* the origin moved to its closest approach to the centre */
    r->s0 = -ref_dot3(q->w, q->d) / ref_dot3(q->d, q->d);
    cylq w1[3];
    for (int k = 0; k < 3; k++) {
        const cylq wm = q->w[k] + r->s0 * q->d[k];
        r->W[k] = wm + q->a[k] / 2;
        w1[k] = wm - q->a[k] / 2;
    }
    for (int p = 0; p < RP_COUNT; p++) {
        r->lo[p] = r->hi[p] = (cylq)NAN;
        r->m[p][RM_MEET] = r->m[p][RM_LEN] = -1;
    }
    if (!r->nested || !r->big)
        sphere_piece(r, RP_S0, r->W, q->r0);
    if (!r->nested || r->big)
        sphere_piece(r, RP_S1, w1, q->r1);
    if (!r->nested)
        frustum_piece(r);
}

int rcref_entry_(const rrec *r)
{
    int best = -1;
    for (int p = 0; p < RP_COUNT; p++)
        if (r->ex[p] && (best < 0 || r->lo[p] < r->lo[best]))
            best = p;
    return best;
}

int rcref_exit_(const rrec *r)
{
    int best = -1;
    for (int p = 0; p < RP_COUNT; p++)
        if (r->ex[p] && (best < 0 || r->hi[p] > r->hi[best]))
            best = p;
    return best;
}

int rcref_present_(const rrec *r, unsigned flags, int p)
{
    (void)r;
    return p == RP_F || (flags & (p == RP_S0 ? CYLRAY_CAPPED_LO : CYLRAY_CAPPED_HI));
}

/* An exit is a back face unless the ray only touches there (d.n = 0). */
static int exit_back(const rrec *r, int p)
{
    return r->face[p] > 0;
}

int rcref_decide_(const rrec *r, unsigned flags)
{
    const int e = rcref_entry_(r), x = rcref_exit_(r);
    if (e < 0)
        return -1;
    const cylq te = r->s0 + r->lo[e], tx = r->s0 + r->hi[x];
    if (te > r->tmax)
        return -1;
    if (te >= r->tmin && rcref_present_(r, flags, e))
        return 2 * e;
    /* along a generator line the side is the whole stretch between the seams */
    if (r->fseg && x == RP_F && te < r->tmin && r->tmin <= tx && r->tmin <= r->tmax)
        return RX_SEG;
    if (tx >= r->tmin && tx <= r->tmax && rcref_present_(r, flags, x) &&
        !((flags & CYLRAY_CULL_BACK) && exit_back(r, x)))
        return 2 * x + 1;
    return -1;
}

cylq rcref_t_(const rrec *r, int x)
{
    if (x == RX_SEG)
        return r->tmin;
    return r->s0 + (x & 1 ? r->hi[x / 2] : r->lo[x / 2]);
}

int rcref_part_(const rrec *r, int x)
{
    if (x == RX_SEG)
        return CYLRAY_SIDE;
    const int p = x / 2;
    const int part = p == RP_F ? CYLRAY_SIDE : p == RP_S0 ? CYLRAY_CAP_LO : CYLRAY_CAP_HI;
    return part | ((x & 1) && exit_back(r, p) ? CYLRAY_BACKFACE : 0);
}

void rcref_normal_(const rrec *r, int x, int ff, double n[3])
{
    const int p = x == RX_SEG ? RP_F : x / 2;
    const cylq t = x == RX_SEG ? r->tmin - r->s0 : x & 1 ? r->hi[p] : r->lo[p];
    cylq X[3], g[3];
    for (int k = 0; k < 3; k++)
        X[k] = r->W[k] + t * r->d[k]; /* from p0 */
    n[0] = n[1] = n[2] = 0;
    if (p == RP_F) {
        /* n_rho x_perp / |x_perp| - k u, x_perp = a x (X x a) / a.a */
        cylq c[3], xp[3];
        cross3(X, r->a, c);
        cross3(r->a, c, xp);
        const cylq len = q_sqrt(ref_dot3(xp, xp));
        if (!(len > 0))
            return; /* the apex of a point end */
        const cylq nrho = q_sqrt(q_max(r->d2, 0) / r->aa);
        for (int k = 0; k < 3; k++)
            g[k] = nrho * xp[k] / len - r->dr * r->a[k] / r->aa;
    } else {
        for (int k = 0; k < 3; k++)
            g[k] = p == RP_S0 ? X[k] : X[k] - r->a[k];
    }
    const cylq len = q_sqrt(ref_dot3(g, g));
    if (!(len > 0))
        return;
    const cylq s = (ff && (rcref_part_(r, x) & CYLRAY_BACKFACE)) ? -1 / len : 1 / len;
    for (int k = 0; k < 3; k++)
        n[k] = (double)(g[k] * s);
}

static void rc_eval(const rin_q *q, cylq tmin, cylq tmax, rrec *r)
{
    rcref_eval_(q, -1, tmin, tmax, r);
}

static int rc_decide(const rrec *r, const rcref_round_cone *s, unsigned flags)
{
    return rcref_decide_(r, s->flags | (flags & CYLRAY_CULL_BACK));
}

REF_INTERSECT_DEFINE(rcref, rcref_round_cone, rin_q, rrec, rcref_valid, rcref_in_, rc_eval,
                     rc_decide, rcref_t_, rcref_part_, rcref_normal_)
