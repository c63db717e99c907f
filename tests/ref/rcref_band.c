/* SPDX-License-Identifier: MIT */
/* rcref_band.c - the round cone's tolerance band: every outcome the exact intersection
 * (rcref.c) gives for the inputs moved within their rounding, and the judge.
 *
 * The exact answer is the hull's entry (the least of three pieces' entries) or exit (the
 * greatest of their exits); the band asks which piece may give each, over the box of
 * inputs and within 4 float ulps, and which of the comparisons with tmin and tmax may go
 * either way, and keeps every outcome those allow. No combination drops both pieces of a
 * seam: one of them is the least, whichever it is. */
#include "bandutil.h"
#include "rcref_eval.h"

#include "exact.h"

#include "../support/rng.h"

#include <stdint.h>
#include <string.h>

enum { IN_W = 0, IN_D = 3, IN_A = 6, IN_R0 = 9, IN_R1 = 10, IN_COUNT = 11 };
_Static_assert((int)IN_A == REF_AXIS_A && (int)IN_R1 == REF_AXIS_R1 &&
                   (int)IN_COUNT == REF_AXIS_COUNT,
               "the inputs as ref_axis_steps's");
/* the samples: one per input, the vertices, each input alone at +-1/4 and +-1/2 */
enum { N_GRAD = IN_COUNT, N_VTX = 2 + REF_RANDOM_VERTICES };
/* where each input's step the other way (-2) starts: the first-order reach of a quantity is
 * the larger move of the two, per input (t has kinks, at a point end's apex) */
enum { NEG0 = 1 + N_GRAD + N_VTX + 4 * IN_COUNT, N_SAMPLES = NEG0 + N_GRAD };

static void r_perturb(const rin_q *base, const cylq step[IN_COUNT],
                      const signed char k[IN_COUNT], cylq scale, rin_q *out)
{
    *out = *base;
    for (int i = 0; i < 3; i++) {
        out->w[i] += scale * step[IN_W + i] * k[IN_W + i];
        out->d[i] += scale * step[IN_D + i] * k[IN_D + i];
        out->a[i] += scale * step[IN_A + i] * k[IN_A + i];
    }
    const cylq s0 = scale * step[IN_R0] * k[IN_R0], s1 = scale * step[IN_R1] * k[IN_R1];
    out->r0 = base->r0 > 0 ? q_max(base->r0 + s0, base->r0 / 2) : 0;
    out->r1 = base->r1 > 0 ? q_max(base->r1 + s1, base->r1 / 2) : 0;
}

/* Per piece over the samples: whether it was met and missed, its entry's and exit's t
 * ranges, and how its exit faced. */
typedef struct {
    int seen_ex, seen_nex, seen_back, seen_front;
    double lo_lo, lo_hi, hi_lo, hi_hi;
} r_track;

static void track_init(r_track tr[RP_COUNT])
{
    for (int p = 0; p < RP_COUNT; p++) {
        memset(&tr[p], 0, sizeof tr[p]);
        tr[p].lo_lo = tr[p].hi_lo = INFINITY;
        tr[p].lo_hi = tr[p].hi_hi = -INFINITY;
    }
}

static void track(r_track tr[RP_COUNT], const rrec *r)
{
    for (int p = 0; p < RP_COUNT; p++) {
        r_track *x = &tr[p];
        if (!r->ex[p]) {
            x->seen_nex = 1;
            continue;
        }
        x->seen_ex = 1;
        const double lo = (double)(r->s0 + r->lo[p]), hi = (double)(r->s0 + r->hi[p]);
        x->lo_lo = fmin(x->lo_lo, lo);
        x->lo_hi = fmax(x->lo_hi, lo);
        x->hi_lo = fmin(x->hi_lo, hi);
        x->hi_hi = fmax(x->hi_hi, hi);
        if (r->face[p] > 0)
            x->seen_back = 1;
        else
            x->seen_front = 1;
    }
}

/* One reading of the shape (nested or not) over the box. */
typedef struct {
    const rin_q *qs; /* the samples' inputs, N_SAMPLES of them */
    cylq tmin, tmax;
    unsigned vflags;
    int ff, x0, p0;
    const double *n0;
    ref_set *set;
    double nmax;
    int evals;
} r_box;

static void add_outcome(ref_set *set, const rrec *r, int x)
{
    ref_add(set, x < 0 ? -1 : rcref_part_(r, x), x < 0 ? NAN : (double)rcref_t_(r, x));
}

static double wide(double t)
{
    return 4 * ref_float_ulp(t);
}

/* A ray that runs beside the side along a generator line (within the box's reach of it)
 * has no isolated roots: the box tilts it onto the cone anywhere along that stretch. Input
 * i moves the frustum's quadratic at t by G_i(t) - G(t) (each sample in its own shifted
 * frame), S(t) the sum of their sizes, widened by widen_by; sampled along the slab's
 * stretch (ref_reach_scan, as conref_band.c's c_reach), the back face only where it is
 * not culled. */
typedef struct {
    const rrec *r;
    const cylq (*gq)[4];
    double widen_by;
} f_beside;

static void f_reach_at(const void *ctx, cylq t, ref_reach *x)
{
    const f_beside *c = ctx;
    const rrec *r = c->r;
    const cylq u = t - r->s0;
    x->F = (r->qa[RP_F] * u + 2 * r->qb[RP_F]) * u + r->qc[RP_F];
    x->F1 = r->qa[RP_F] * u + r->qb[RP_F];
    cylq S = 0, S1 = 0;
    for (int k = 0; k < N_GRAD; k++) {
        cylq sk = 0, s1k = 0;
        for (int side = 0; side < 2; side++) {
            const cylq *g = c->gq[side * N_GRAD + k], v = t - g[3];
            sk = q_max(sk, q_abs((g[0] * v + 2 * g[1]) * v + g[2] - x->F));
            s1k = q_max(s1k, q_abs(g[0] * v + g[1] - x->F1));
        }
        S += sk;
        S1 += s1k;
    }
    x->S = S * (cylq)c->widen_by;
    x->S1 = S1 * (cylq)c->widen_by;
}

static void f_reach(r_box *b, const rrec *r, const cylq (*gq)[4], double widen_by)
{
    cylq sa = 0;
    for (int i = 0; i < N_GRAD; i++)
        sa += q_max(q_abs(gq[i][0] - r->qa[RP_F]), q_abs(gq[N_GRAD + i][0] - r->qa[RP_F]));
    if (r->nested || !(q_abs(r->qa[RP_F]) <= 256 * sa))
        return;
    const cylq ta = q_max(r->s0 + r->sl, b->tmin), tb = q_min(r->s0 + r->sh, b->tmax);
    const f_beside c = {r, gq, widen_by};
    ref_reach_scan(b->set, ta, tb, f_reach_at, NULL, &c, !(b->vflags & CYLRAY_CULL_BACK));
}

static void band_model(r_box *b, int model)
{
    const int cull = (b->vflags & CYLRAY_CULL_BACK) != 0;
    rrec rb, r;
    rcref_eval_(&b->qs[0], model, b->tmin, b->tmax, &rb);
    b->evals++;
    add_outcome(b->set, &rb, rcref_decide_(&rb, b->vflags));
    r_track tr[RP_COUNT];
    track_init(tr);
    track(tr, &rb);
    double sum_m[RP_COUNT][RM_COUNT] = {{0}}, sum_lo[RP_COUNT] = {0}, sum_hi[RP_COUNT] = {0};
    double sum_face[RP_COUNT] = {0};
    /* each gradient sample's frustum quadratic and shift, +2 then -2 */
    cylq gq[2 * N_GRAD][4];
    /* each input's moves at +2, kept for the larger of the two */
    double up_m[N_GRAD][RP_COUNT][RM_COUNT], up_lo[N_GRAD][RP_COUNT], up_hi[N_GRAD][RP_COUNT];
    double up_face[N_GRAD][RP_COUNT];
    for (int i = 1; i < N_SAMPLES; i++) {
        rcref_eval_(&b->qs[i], model, b->tmin, b->tmax, &r);
        b->evals++;
        const int up = i <= N_GRAD, down = i >= NEG0;
        if (up || down) {
            const int j = up ? i - 1 : i - NEG0;
            cylq *g = gq[up ? j : N_GRAD + j];
            g[0] = r.qa[RP_F];
            g[1] = r.qb[RP_F];
            g[2] = r.qc[RP_F];
            g[3] = r.s0;
            for (int p = 0; p < RP_COUNT; p++) {
                double dm[RM_COUNT];
                for (int k = 0; k < RM_COUNT; k++)
                    dm[k] = ref_qdiff(r.m[p][k], rb.m[p][k]);
                const double dl = ref_qdiff(r.s0 + r.lo[p], rb.s0 + rb.lo[p]);
                const double dh = ref_qdiff(r.s0 + r.hi[p], rb.s0 + rb.hi[p]);
                const double df = ref_qdiff(r.face[p], rb.face[p]);
                if (up) {
                    for (int k = 0; k < RM_COUNT; k++)
                        up_m[j][p][k] = dm[k];
                    up_lo[j][p] = dl, up_hi[j][p] = dh, up_face[j][p] = df;
                    continue;
                }
                for (int k = 0; k < RM_COUNT; k++)
                    sum_m[p][k] += fmax(dm[k], up_m[j][p][k]);
                sum_lo[p] += fmax(dl, up_lo[j][p]);
                sum_hi[p] += fmax(dh, up_hi[j][p]);
                sum_face[p] += fmax(df, up_face[j][p]);
            }
        }
        track(tr, &r);
        const int x = rcref_decide_(&r, b->vflags);
        add_outcome(b->set, &r, x);
        if (b->x0 >= 0 && x >= 0 && rcref_part_(&r, x) == b->p0) {
            double n[3];
            rcref_normal_(&r, x, b->ff, n);
            b->nmax = fmax(b->nmax, ref_angle3(n, b->n0));
        }
    }

    /* Close to nesting the box moves |a|^2 - dr^2 by a good part of itself, and with it
     * the cone's angle: first order then falls short, by about that part; every spread is
     * widened by it (a few such shapes showed outcomes up to twice the first order). */
    double grow = 1;
    if (!rb.nested) {
        double sd = 0;
        for (int i = 1; i <= N_GRAD; i++) {
            const rin_q *q = &b->qs[i];
            const cylq dr = q->r1 - q->r0;
            sd += ref_qdiff(ref_dot3(q->a, q->a) - dr * dr, rb.d2);
        }
        const double rel = sd / (double)rb.d2;
        if (rel > 1e-3) {
            grow = 1 + 8 * fmin(rel, 8);
            for (int p = 0; p < RP_COUNT; p++) {
                for (int g = 0; g < RM_COUNT; g++)
                    sum_m[p][g] *= grow;
                sum_lo[p] *= grow;
                sum_hi[p] *= grow;
                sum_face[p] *= grow;
            }
        }
    }
    /* Which pieces may be met, which missed, and where their entries and exits lie. */
    int may_ex[RP_COUNT], may_nex[RP_COUNT];
    double lo[RP_COUNT][2], hi[RP_COUNT][2];
    int sure = 0, any = 0;
    for (int p = 0; p < RP_COUNT; p++) {
        const cylq rad = p == RP_S0 ? rb.r0 : rb.r1;
        const int avail =
            q_isfinite(rb.lo[p]) && q_isfinite(rb.hi[p]) && (p == RP_F || rad > 0);
        int und = 0, flips = 1;
        for (int g = 0; g < RM_COUNT && avail; g++) {
            if (!q_isfinite(rb.m[p][g]))
                continue;
            const double mag = (double)q_abs(rb.m[p][g]);
            const int u = mag <= sum_m[p][g] + (double)rb.mw[p][g] || !(sum_m[p][g] < INFINITY);
            und |= u;
            if (rb.m[p][g] < 0 && !u)
                flips = 0;
        }
        may_ex[p] = (avail && (rb.ex[p] || flips)) || tr[p].seen_ex;
        may_nex[p] = !rb.ex[p] || tr[p].seen_nex || und;
        const double l0 = (double)(rb.s0 + rb.lo[p]), h0 = (double)(rb.s0 + rb.hi[p]);
        lo[p][0] = fmin(tr[p].lo_lo, l0 - sum_lo[p]);
        lo[p][1] = fmax(tr[p].lo_hi, l0 + sum_lo[p]);
        hi[p][0] = fmin(tr[p].hi_lo, h0 - sum_hi[p]);
        hi[p][1] = fmax(tr[p].hi_hi, h0 + sum_hi[p]);
        /* a piece met only past a tangency: its entry and exit are one point */
        if (!rb.ex[p]) {
            lo[p][0] = hi[p][0] = fmin(lo[p][0], hi[p][0]);
            lo[p][1] = hi[p][1] = fmax(lo[p][1], hi[p][1]);
        }
        /* near a tangency t moves with the square root of the margin, which the box moves
         * linearly: the roots reach -B / A -+ sqrt(D + its spread) / A, a sphere's margin
         * being D. The frustum's is -G at tg, the least of G on its slab's stretch, which
         * is the vertex -B / A or the stretch's end nearer to it: G <= its spread where
         * |t + B / A| <= sqrt((margin + spread) / A + (tg + B / A)^2), clipped to the
         * stretch; however small A is (f_reach's samples may pass over so short a one). */
        const cylq qa = rb.qa[p], tv = -rb.qb[p] / qa;
        const cylq tg = p != RP_F ? tv : tv < rb.sl ? rb.sl : tv > rb.sh ? rb.sh : tv;
        if (avail && qa > 0 && q_isfinite(tg) && q_isfinite(rb.m[p][RM_MEET]) &&
            !((double)q_abs(rb.m[p][RM_MEET]) >
              sum_m[p][RM_MEET] + (double)rb.mw[p][RM_MEET])) {
            const cylq dmax = rb.m[p][RM_MEET] + (cylq)sum_m[p][RM_MEET] + rb.mw[p][RM_MEET];
            const cylq dd = p == RP_F ? q_max(dmax, 0) * qa + qa * qa * (tg - tv) * (tg - tv)
                                      : q_max(dmax, 0);
            const cylq tc = rb.s0 + tv, half = q_sqrt(dd) / qa;
            cylq ta = tc - half, tb = tc + half, tm = tc; /* the frustum's: in its slab */
            if (p == RP_F) {
                const cylq sl = rb.s0 + rb.sl, sh = rb.s0 + rb.sh;
                ta = q_max(ta, sl);
                tb = q_min(tb, sh);
                tm = q_min(q_max(tm, sl), sh);
            }
            if (q_isfinite(ta) && q_isfinite(tb) && q_isfinite(tm)) {
                lo[p][0] = fmin(lo[p][0], (double)ta);
                lo[p][1] = fmax(lo[p][1], (double)tm);
                hi[p][0] = fmin(hi[p][0], (double)tm);
                hi[p][1] = fmax(hi[p][1], (double)tb);
            }
        }
        for (int j = 0; j < 2; j++) {
            const double wl = wide(fmax(fabs(lo[p][0]), fabs(lo[p][1])));
            const double wh = wide(fmax(fabs(hi[p][0]), fabs(hi[p][1])));
            lo[p][j] += j ? wl : -wl;
            hi[p][j] += j ? wh : -wh;
        }
        if (!(lo[p][0] <= lo[p][1]) || !(hi[p][0] <= hi[p][1]))
            may_ex[p] = 0; /* never met with a t to compare */
        any |= may_ex[p];
        sure |= may_ex[p] && !may_nex[p];
    }
    if (!sure)
        ref_add(b->set, -1, NAN); /* the hull itself may be missed */
    f_reach(b, &rb, (const cylq(*)[4])gq, grow);
    if (!any)
        return;

    const double tmin = (double)b->tmin, tmax = (double)b->tmax;
    for (int e = 0; e < RP_COUNT; e++) {
        int win = may_ex[e];
        for (int q = 0; q < RP_COUNT && win; q++)
            if (q != e && may_ex[q] && !may_nex[q] && !(lo[e][0] <= lo[q][1]))
                win = 0;
        if (!win)
            continue;
        const int pres = rcref_present_(&rb, b->vflags, e);
        if (pres && lo[e][1] >= tmin && lo[e][0] <= tmax)
            ref_add_range(b->set, rcref_part_(&rb, 2 * e) & ~CYLRAY_BACKFACE, lo[e][0],
                          lo[e][1]);
        if (lo[e][1] > tmax)
            ref_add(b->set, -1, NAN);
        if (pres && !(lo[e][0] < tmin))
            continue;
        for (int x = 0; x < RP_COUNT; x++) {
            int wx = may_ex[x];
            for (int q = 0; q < RP_COUNT && wx; q++)
                if (q != x && may_ex[q] && !may_nex[q] && !(hi[x][1] >= hi[q][0]))
                    wx = 0;
            if (!wx)
                continue;
            const double f0 = (double)rb.face[x];
            const int near0 =
                !(fabs(f0) > sum_face[x] + (double)rb.facew[x]) ||
                !(rb.m[x][RM_MEET] > sum_m[x][RM_MEET] + (double)rb.mw[x][RM_MEET]);
            const int back = tr[x].seen_back || f0 > 0 || near0;
            const int front = tr[x].seen_front || !(f0 > 0) || near0;
            const int px = rcref_present_(&rb, b->vflags, x);
            const int part = rcref_part_(&rb, 2 * x) & ~CYLRAY_BACKFACE;
            if (px && hi[x][1] >= tmin && hi[x][0] <= tmax) {
                if (back && !cull)
                    ref_add_range(b->set, part | CYLRAY_BACKFACE, hi[x][0], hi[x][1]);
                if (front)
                    ref_add_range(b->set, part, hi[x][0], hi[x][1]);
            }
            if (!px || hi[x][0] < tmin || hi[x][1] > tmax || (cull && back))
                ref_add(b->set, -1, NAN);
        }
    }
}

/* How far the exact outcome's normal may turn over the box and along its t range, where
 * the samples cannot show it: near a point end's apex (the side's normal turns with
 * x_perp's direction) and on a sphere small beside the ray's ulps. */
static double turn_bound(const rrec *r, int x, const cylq step[IN_COUNT], double t_lo,
                         double t_hi)
{
    const int p = x == RX_SEG ? RP_F : x / 2;
    const cylq tq = rcref_t_(r, x) - r->s0;
    double X[3], dm = 0, am = 0, dd = 0, wm = (double)step[IN_W];
    for (int k = 0; k < 3; k++) {
        X[k] = (double)(r->W[k] + tq * r->d[k]);
        dm = fmax(dm, fabs((double)r->d[k]));
        am = fmax(am, fabs((double)r->a[k]));
        dd += (double)r->d[k] * (double)r->d[k];
    }
    const double t = (double)rcref_t_(r, x), aa = (double)r->aa;
    const double dt = fmax(t - t_lo, t_hi - t) + wide(fmax(fabs(t_lo), fabs(t_hi)));
    const double rmax = fmax((double)r->r0, (double)r->r1);
    /* how far the box moves the hit point off the exact one, the t range aside */
    const double delta = 8 * (wm + fabs(t) * ref_float_ulp(dm) +
                              ref_float_ulp(am) * fmax(1, fabs(t) * dm / fmax(am, 1e-300)) +
                              ref_float_ulp(rmax));
    if (p != RP_F) {
        /* a sphere: its centre moves with the axis' half, the ray with w and d (sphref.c) */
        const double rad = (double)(p == RP_S0 ? r->r0 : r->r1);
        const double db =
            2 * sqrt(3.0) * (wm + fabs(t) * ref_float_ulp(dm) + ref_float_ulp(am)) +
            2 * ref_float_ulp(rad);
        const double chord = (db + sqrt(dd) * dt) / rad;
        return 2 * asin(fmin(1, chord / 2));
    }
    /* the side: the direction of x_perp, |x_perp| from the axis */
    double xa = 0, dp2 = 0, da = 0;
    for (int k = 0; k < 3; k++) {
        xa += X[k] * (double)r->a[k];
        da += (double)r->d[k] * (double)r->a[k];
    }
    double xp2 = 0;
    for (int k = 0; k < 3; k++) {
        const double c = X[k] - xa / aa * (double)r->a[k];
        xp2 += c * c;
    }
    dp2 = fmax(0, dd - da * da / aa);
    const double xp = sqrt(xp2), move = delta + sqrt(dp2) * dt;
    return move < xp ? 2 * asin(move / xp) : 3.14159265358979323846;
}

static void rc_band(const rcref_round_cone *s, const float o[3], const float d[3], float tmin,
                    float tmax, unsigned vflags, int ff, cylref_band *out)
{
    rin_q qs[N_SAMPLES];
    rcref_in_(s, o, d, &qs[0]);
    const rin_q *base = &qs[0];
    cylq step[IN_COUNT];
    ref_axis_steps(s->p0, s->p1, s->r0, s->r1, base->w, base->d, base->a, step);

    rrec r0;
    rcref_eval_(base, -1, tmin, tmax, &r0);
    const int x0 = rcref_decide_(&r0, vflags);
    const int p0 = x0 < 0 ? -1 : rcref_part_(&r0, x0);
    double n0[3] = {0, 0, 0};
    if (x0 >= 0) {
        rcref_normal_(&r0, x0, ff, n0);
        ref_band_exact(out, (double)rcref_t_(&r0, x0), p0, n0);
    }
    ref_set set = {0};
    ref_add(&set, p0, out->exact.t);

    /* The samples' inputs: the gradient's, the vertices (the two where t is extreme to
     * first order, found from the gradient's samples), each input alone at 1/4 and 1/2. */
    double dt[IN_COUNT] = {0};
    for (int i = 0; i < IN_COUNT; i++) {
        signed char k[IN_COUNT] = {0};
        k[i] = 2;
        r_perturb(base, step, k, 1, &qs[1 + i]);
        if (x0 >= 0) {
            rrec r;
            rcref_eval_(&qs[1 + i], -1, tmin, tmax, &r);
            const int x = rcref_decide_(&r, vflags);
            dt[i] = x == x0 ? ref_dt(rcref_t_(&r, x), rcref_t_(&r0, x0)) : 0;
        }
    }
    uint64_t seed = 0x72636f6eu;
    for (int k = 0; k < 3; k++)
        seed = seed * 0x100000001b3u ^ ref_fbits(o[k]) ^ (uint64_t)ref_fbits(d[k]) << 32 ^
               (uint64_t)ref_fbits(s->p0[k]) << 7 ^ (uint64_t)ref_fbits(s->p1[k]) << 19;
    seed ^= (uint64_t)ref_fbits(s->r0) << 11 ^ (uint64_t)ref_fbits(s->r1) << 29;
    for (int vtx = 0; vtx < N_VTX; vtx++) {
        signed char k[IN_COUNT];
        const uint64_t bits = rng_splitmix64(&seed);
        ref_vertex(k, IN_COUNT, vtx, bits, dt, x0 >= 0);
        r_perturb(base, step, k, 1, &qs[1 + N_GRAD + vtx]);
    }
    for (int i = 0; i < 4 * IN_COUNT; i++) {
        signed char k[IN_COUNT] = {0};
        k[i / 4] = (signed char)((i & 1 ? -1 : 1) * (i & 2 ? 2 : 1));
        r_perturb(base, step, k, (cylq)0.5, &qs[1 + N_GRAD + N_VTX + i]);
    }
    for (int i = 0; i < IN_COUNT; i++) {
        signed char k[IN_COUNT] = {0};
        k[i] = -2;
        r_perturb(base, step, k, 1, &qs[NEG0 + i]);
    }

    /* Nested or not: both readings where the box (or 4 ulps of |a|^2) reaches the
     * boundary |p1 - p0| = |r1 - r0|. */
    int seen[2] = {0, 0};
    for (int i = 0; i < N_SAMPLES; i++) {
        const rin_q *q = &qs[i];
        const cylq dr = q->r1 - q->r0;
        seen[!(ref_dot3(q->a, q->a) - dr * dr > 0)] = 1;
    }
    seen[r0.nested] = 1;
    if (!(q_abs(r0.d2) > r0.d2w))
        seen[0] = seen[1] = 1;

    r_box box = {qs, tmin, tmax, vflags, ff, x0, p0, n0, &set, 0, 1 + IN_COUNT};
    for (int m = 0; m < 2; m++)
        if (seen[m])
            band_model(&box, m);
    out->evals = box.evals;

    ref_band_keep_set(out, &set, x0 >= 0 ? p0 : -1);
    out->n_spread = 2 * box.nmax;
    if (x0 >= 0 && out->t_lo == out->t_lo)
        out->n_spread = fmax(out->n_spread, turn_bound(&r0, x0, step, out->t_lo, out->t_hi));
    out->n_spread = fmin(out->n_spread, 3.14159265358979323846);
}

REF_BAND_DEFINE(rcref, rcref_round_cone, rcref_valid, rc_band)

int rcref_judge(const cylref_band *b, int hit, int part, float t, double *ulps_beyond)
{
    return cylref_judge(b, hit, part, t, ulps_beyond);
}
