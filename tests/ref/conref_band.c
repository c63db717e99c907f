/* SPDX-License-Identifier: MIT */
/* conref_band.c - the cone's tolerance band: every outcome the exact intersection
 * (conref.c) gives for the inputs moved within their rounding, and the judge. */
#include "conref_eval.h"
#include "bandutil.h"

#include "exact.h"

#include "../support/rng.h"

#include <stdint.h>
#include <string.h>

/* ---- the band ----------------------------------------------------------------------- */

enum { IN_W = 0, IN_D = 3, IN_A = 6, IN_R0 = 9, IN_R1 = 10, IN_COUNT = 11 };
_Static_assert((int)IN_A == REF_AXIS_A && (int)IN_R1 == REF_AXIS_R1 &&
                   (int)IN_COUNT == REF_AXIS_COUNT,
               "the inputs as ref_axis_steps's");

static void c_perturb(const cin_q *base, const cylq step[IN_COUNT],
                      const signed char k[IN_COUNT], cin_q *out)
{
    *out = *base;
    ref_perturb_ray(out->w, out->d, step, k);
    for (int i = 0; i < 3; i++)
        out->a[i] += step[IN_A + i] * k[IN_A + i];
    const cylq s0 = step[IN_R0] * k[IN_R0], s1 = step[IN_R1] * k[IN_R1];
    out->r0 = base->r0 > 0 ? q_max(base->r0 + s0, base->r0 / 2) : 0;
    out->r1 = base->r1 > 0 ? q_max(base->r1 + s1, base->r1 / 2) : 0;
}

REF_SAMPLE_DEFINE(c_at, cin_q, crec, c_perturb, conref_eval_)

/* Per candidate over the evaluations: its t range (where it exists), the parts it
 * showed, and whether its validity was seen both ways. */
typedef struct {
    double lo, hi;
    int seen_valid, seen_invalid, parts_back, parts_front;
} c_track;

static void track(c_track tr[K_COUNT], const crec *r, const unsigned char v[K_COUNT])
{
    for (int kand = 0; kand < K_COUNT; kand++) {
        c_track *x = &tr[kand];
        if (v[kand]) {
            x->seen_valid = 1;
            double t = (double)r->t[kand];
            x->lo = fmin(x->lo, t);
            x->hi = fmax(x->hi, t);
            if (r->back[kand])
                x->parts_back = 1;
            else
                x->parts_front = 1;
        } else {
            x->seen_invalid = 1;
        }
    }
}

/* The side's quadratic beside a stretch (ref_reach_scan): input i of the box moves it at t
 * by dA_i t^2 + 2 dB_i t + dC_i, S(t) the sum of their sizes; a run of the side's samples
 * counts unless a candidate sure to be taken comes first. */
typedef struct {
    const crec *r;
    const cylq (*dc)[3];
    const int *may_drop;
    const double *hi;
} c_beside;

static void c_reach_at(const void *ctx, cylq t, ref_reach *x)
{
    const c_beside *c = ctx;
    const crec *r = c->r;
    x->F = (r->A * t + 2 * r->B) * t + r->C;
    x->F1 = r->A * t + r->B;
    x->S = x->S1 = 0;
    for (int k = 0; k < IN_COUNT; k++) {
        x->S += q_abs((c->dc[k][0] * t + 2 * c->dc[k][1]) * t + c->dc[k][2]);
        x->S1 += q_abs(c->dc[k][0] * t + c->dc[k][1]);
    }
}

static int c_reach_keep(const void *ctx, double lo)
{
    const c_beside *c = ctx;
    int sure_before = 0;
    for (int j = 0; j < K_COUNT; j++)
        sure_before |= !c->may_drop[j] && c->hi[j] < lo;
    return !sure_before;
}

/* The side's runs beside a generator line, sampled along the ray's stretch inside the
 * slab (ref_reach_scan). */
static void c_reach(ref_set *set, const crec *r, const cylq (*dc)[3], cylq tmin, cylq tmax,
                    const int may_drop[K_COUNT], const double hi[K_COUNT])
{
    cylq sa = 0;
    for (int i = 0; i < IN_COUNT; i++)
        sa += q_abs(dc[i][0]);
    if (!(q_abs(r->A) <= 256 * sa) || r->zd == 0)
        return;
    cylq ta = (0 - r->zw) / r->zd, tb = (r->L - r->zw) / r->zd;
    if (ta > tb) {
        cylq x = ta;
        ta = tb;
        tb = x;
    }
    ta = q_max(ta, tmin);
    tb = tb < tmax ? tb : tmax;
    const c_beside c = {r, dc, may_drop, hi};
    ref_reach_scan(set, ta, tb, c_reach_at, c_reach_keep, &c, 1);
}

/* One point of the box: its outcome joins the set, its candidates the tracks, and the
 * turn of its normal from the exact one where it keeps the exact outcome. */
typedef struct {
    cylq tmin, tmax;
    unsigned vflags;
    int ff, x0, p0;
    const double *n0;
    c_track *tr;
    ref_set *set;
    double nmax;
    int evals;
} c_box;

static void c_sample(c_box *b, const cin_q *q)
{
    crec r;
    unsigned char v[K_COUNT];
    conref_eval_(q, b->tmin, b->tmax, &r);
    b->evals++;
    conref_valid_parts_(&r, b->vflags, v);
    track(b->tr, &r, v);
    const int x = conref_first_(&r, v);
    ref_add(b->set, x < 0 ? -1 : conref_part_(&r, x), x < 0 ? NAN : (double)r.t[x]);
    if (b->x0 >= 0 && x == b->x0 && conref_part_(&r, x) == b->p0) {
        double n[3];
        conref_normal_(&r, x, b->ff, n);
        b->nmax = fmax(b->nmax, ref_angle3(n, b->n0));
    }
}

static void cone_band(const cylray_cone *c, const float o[3], const float d[3], float tmin,
                      float tmax, unsigned vflags, int ff, cylref_band *out)
{
    cin_q base;
    conref_in_(c, o, d, &base);
    cylq step[IN_COUNT];
    ref_axis_steps(c->p0, c->p1, c->r0, c->r1, base.w, base.d, base.a, step);

    crec r0, r;
    conref_eval_(&base, tmin, tmax, &r0);
    unsigned char v0[K_COUNT], v[K_COUNT];
    conref_valid_parts_(&r0, vflags, v0);
    const int x0 = conref_first_(&r0, v0);
    const int p0 = x0 < 0 ? -1 : conref_part_(&r0, x0);
    out->evals = 1;
    double n0[3] = {0, 0, 0};
    if (x0 >= 0) {
        conref_normal_(&r0, x0, ff, n0);
        ref_band_exact(out, (double)r0.t[x0], p0, n0);
    }
    ref_set set = {0};
    ref_add(&set, p0, out->exact.t);
    c_track tr[K_COUNT];
    for (int kand = 0; kand < K_COUNT; kand++) {
        tr[kand].lo = INFINITY;
        tr[kand].hi = -INFINITY;
        tr[kand].seen_valid = tr[kand].seen_invalid = 0;
        tr[kand].parts_back = tr[kand].parts_front = 0;
    }
    track(tr, &r0, v0);

    double sum_m[K_COUNT][G_COUNT] = {{0}}, sum_t[K_COUNT] = {0}, dt[IN_COUNT] = {0};
    cylq sum_zd = 0;         /* the box's first-order reach of zd (d's rate along the axis) */
    cylq dcoef[IN_COUNT][3]; /* each input's move of A, B and C */
    double nmax = 0;
    for (int i = 0; i < IN_COUNT; i++) {
        signed char k[IN_COUNT] = {0};
        k[i] = 2;
        c_at(&base, step, k, tmin, tmax, &r, out);
        for (int kand = 0; kand < K_COUNT; kand++) {
            for (int g = 0; g < G_COUNT; g++)
                sum_m[kand][g] += ref_qdiff(r.m[kand][g], r0.m[kand][g]);
            sum_t[kand] += ref_qdiff(r.t[kand], r0.t[kand]);
        }
        dcoef[i][0] = r.A - r0.A, dcoef[i][1] = r.B - r0.B, dcoef[i][2] = r.C - r0.C;
        sum_zd += q_abs(r.zd - r0.zd);
        if (x0 >= 0)
            dt[i] = ref_dt(r.t[x0], r0.t[x0]);
        conref_valid_parts_(&r, vflags, v);
        track(tr, &r, v);
        int x = conref_first_(&r, v);
        ref_add(&set, x < 0 ? -1 : conref_part_(&r, x), x < 0 ? NAN : (double)r.t[x]);
        if (x0 >= 0 && x == x0 && conref_part_(&r, x) == p0) {
            double n[3];
            conref_normal_(&r, x, ff, n);
            nmax = fmax(nmax, ref_angle3(n, n0));
        }
    }
    uint64_t seed = 0x636f6e65u;
    for (int k = 0; k < 3; k++)
        seed = seed * 0x100000001b3u ^ ref_fbits(o[k]) ^ (uint64_t)ref_fbits(d[k]) << 32 ^
               (uint64_t)ref_fbits(c->p0[k]) << 7 ^ (uint64_t)ref_fbits(c->p1[k]) << 19;
    seed ^= (uint64_t)ref_fbits(c->r0) << 11 ^ (uint64_t)ref_fbits(c->r1) << 29;
    c_box box = {tmin, tmax, vflags, ff, x0, p0, n0, tr, &set, nmax, 0};
    for (int vtx = 0; vtx < 2 + REF_RANDOM_VERTICES; vtx++) {
        signed char k[IN_COUNT];
        uint64_t bits = rng_splitmix64(&seed);
        ref_vertex(k, IN_COUNT, vtx, bits, dt, x0 >= 0);
        cin_q q;
        c_perturb(&base, step, k, &q);
        c_sample(&box, &q);
    }

    /* Each input alone at a quarter and a half of the box's reach either way: t is not
     * monotonic across an apex (the double cone's radius is |r|), and on a cone as
     * short as the box's reach along its axis the vertices all leave the slab or meet
     * the tip while the box's inside meets the side at every t between. */
    cylq half[IN_COUNT];
    for (int i = 0; i < IN_COUNT; i++)
        half[i] = step[i] / 2;
    for (int i = 0; i < 4 * IN_COUNT; i++) {
        signed char k[IN_COUNT] = {0};
        k[i / 4] = (signed char)((i & 1 ? -1 : 1) * (i & 2 ? 2 : 1));
        cin_q q;
        c_perturb(&base, half, k, &q);
        c_sample(&box, &q);
    }
    /* Where the box takes d.v through 0, the ray that keeps its level along the axis:
     * its side's t is the farthest (a nearly level ray through a flat cone leaves it
     * sooner the faster it climbs), and no vertex has it. */
    if (q_abs(r0.zd) <= sum_zd && r0.zd != 0) {
        cin_q q = base;
        for (int k = 0; k < 3; k++)
            q.d[k] -= r0.zd * r0.u[k];
        c_sample(&box, &q);
    }
    /* And the rays of the box that cross an end's plane where the line passes the disc
     * (along its chord there, clipped to the range): with d.v near 0 the plane is met
     * far along the ray, at a t set by a hair of d's part along the axis and of the
     * origin's level, which no vertex has. Moving d along the axis by at most md and
     * the origin's level by at most mw reaches the plane at ts exactly where
     * |need(ts)| <= mw + |ts| md, need being the plane's level less the ray's there:
     * an interval on either side of ts = 0 (a convex condition on each), whose ends and
     * inside are sampled. The move is made d's part first and the origin's level for
     * the rest, with the ray climbing and falling (it meets the plane from either
     * side). */
    {
        cylq pp = 0, pd = 0, dd = 0, md = INFINITY, mw = INFINITY;
        for (int k = 0; k < 3; k++) {
            pp += r0.wp[k] * r0.wp[k], pd += r0.wp[k] * r0.dp[k], dd += r0.dp[k] * r0.dp[k];
            if (r0.u[k] != 0) {
                md = q_min(md, 2 * step[IN_D + k] / q_abs(r0.u[k]));
                mw = q_min(mw, 2 * step[IN_W + k] / q_abs(r0.u[k]));
            }
        }
        const cylq hair = (cylq)0x1p-20;
        for (int e = 0; e < 2 && dd > 0 && q_isfinite(md) && q_isfinite(mw); e++) {
            const cylq rad = e ? base.r1 : base.r0, tc = -pd / dd;
            const cylq dist2 = pp + tc * pd; /* |wp + tc dp|^2 */
            if (!(rad > 0) || !(dist2 < rad * rad))
                continue;
            const cylq half = q_sqrt((rad * rad - dist2) / dd) * (1 - hair);
            const cylq n0 = (e ? r0.L : 0) - r0.zw; /* need(ts) = n0 - ts zd */
            const cylq mwi = mw * (1 - hair), mdi = md * (1 - hair);
            for (int side = 0; side < 2; side++) {
                /* ts >= 0: ts (zd + md) >= n0 - mw and ts (zd - md) <= n0 + mw;
                 * ts <= 0: ts (md - zd) <= mw - n0 and ts (zd + md) <= n0 + mw. */
                cylq a = q_max(tc - half, (cylq)tmin), b = q_min(tc + half, (cylq)tmax);
                if (side)
                    b = q_min(b, 0);
                else
                    a = q_max(a, 0);
                const cylq k1 = side ? mdi - r0.zd : -(r0.zd + mdi), m1 = mwi - n0;
                const cylq k2 = side ? r0.zd + mdi : r0.zd - mdi, m2 = n0 + mwi;
                const cylq kk[2] = {k1, k2}, mm[2] = {m1, m2};
                for (int c2 = 0; c2 < 2; c2++) {
                    if (kk[c2] > 0)
                        b = q_min(b, mm[c2] / kk[c2]);
                    else if (kk[c2] < 0)
                        a = q_max(a, mm[c2] / kk[c2]);
                    else if (mm[c2] < 0)
                        b = a - 1;
                }
                if (!(a <= b) || !q_isfinite(a) || !q_isfinite(b))
                    continue;
                /* the ends themselves (the range's bound may be one), but a hair off
                 * ts = 0, where only the origin moves */
                if (a == 0)
                    a = b * (cylq)0x1p-100;
                if (b == 0)
                    b = a * (cylq)0x1p-100;
                static const double at[] = {0, 0.25, 0.5, 0.75, 1};
                for (int j = 0; j < 5; j++) {
                    const cylq ts = j == 4 ? b : a + (cylq)at[j] * (b - a);
                    if (ts == 0)
                        continue;
                    const cylq need = n0 - ts * r0.zd;
                    /* d's least move either way, and the ends of the moves that still
                     * meet the plane there: where those take d.v through 0, the ray
                     * meets it climbing as well as falling (a disc entered or left) */
                    const cylq da = (need - mwi) / ts, db = (need + mwi) / ts;
                    const cylq dzs[4] = {-q_abs(need / ts), q_abs(need / ts), q_min(da, db),
                                         q_max(da, db)};
                    for (int c3 = 0; c3 < 4; c3++) {
                        cylq dz = dzs[c3];
                        dz = dz > md ? md : dz < -md ? -md : dz;
                        const cylq dw = need - ts * dz;
                        if (!(q_abs(dw) <= mw))
                            continue;
                        cin_q q = base;
                        for (int k = 0; k < 3; k++)
                            q.d[k] += dz * r0.u[k], q.w[k] += dw * r0.u[k];
                        c_sample(&box, &q);
                    }
                }
            }
        }
    }
    nmax = box.nmax;
    out->evals += box.evals;

    /* Which candidates may be taken, which dropped: a margin within its first-order
     * spread over the box (or 4 ulps of its terms) of zero, or seen both ways. */
    int may_take[K_COUNT], may_drop[K_COUNT];
    double lo[K_COUNT], hi[K_COUNT];
    for (int kand = 0; kand < K_COUNT; kand++) {
        int allowed = conref_present_(vflags, kand);
        /* und: some margin may flip; flips: every failing margin may. */
        int und = 0, flips = 1;
        if (r0.exists[kand])
            for (int g = 0; g < G_COUNT; g++) {
                if (!q_isfinite(r0.m[kand][g]))
                    continue;
                double mag = (double)q_abs(r0.m[kand][g]);
                int u = mag <= sum_m[kand][g] + (double)r0.mw[kand][g] ||
                        !(sum_m[kand][g] < INFINITY);
                und |= u;
                if (r0.m[kand][g] < 0 && !u)
                    flips = 0;
            }
        may_take[kand] =
            allowed &&
            (v0[kand] || tr[kand].seen_valid ||
             (flips && r0.exists[kand] && !((vflags & CYLRAY_CULL_BACK) && r0.back[kand])));
        may_drop[kand] = !v0[kand] || tr[kand].seen_invalid || und;
        double t = (double)r0.t[kand];
        lo[kand] = fmin(tr[kand].lo, t - sum_t[kand]);
        hi[kand] = fmax(tr[kand].hi, t + sum_t[kand]);
        const double wdn = 4 * ref_float_ulp(fmax(fabs(lo[kand]), fabs(hi[kand])));
        lo[kand] -= wdn;
        hi[kand] += wdn;
    }
    /* An outcome j: j taken and every candidate surely before it dropped. */
    int all_drop = 1;
    for (int j = 0; j < K_COUNT; j++) {
        all_drop &= may_drop[j] || !conref_present_(vflags, j) || !r0.exists[j];
        if (!may_take[j] || !r0.exists[j])
            continue;
        int ok = 1;
        for (int i = 0; i < K_COUNT && ok; i++)
            if (i != j && !may_drop[i] && hi[i] < lo[j])
                ok = 0;
        if (!ok)
            continue;
        /* At a tangency (or a perturbation that reaches one) the two side roots meet
         * and either facing may be reported. */
        const int pp = conref_part_(&r0, j) & ~CYLRAY_BACKFACE;
        const int tangent =
            j < K_LO && (tr[K_FRONT].seen_invalid || !v0[K_FRONT]) &&
            (r0.m[K_FRONT][G_MEET] <= sum_m[K_FRONT][G_MEET] + (double)r0.mw[K_FRONT][G_MEET]);
        if (r0.back[j] || tr[j].parts_back || (j == K_BACK && tangent))
            ref_add_range(&set, pp | CYLRAY_BACKFACE, lo[j], hi[j]);
        if (!r0.back[j] || tr[j].parts_front || (j == K_BACK && tangent))
            ref_add_range(&set, pp, lo[j], hi[j]);
    }
    if (all_drop)
        ref_add(&set, -1, NAN);
    c_reach(&set, &r0, (const cylq(*)[3])dcoef, tmin, tmax, may_drop, hi);
    /* A ray whose rate along the axis the box takes through 0 (d.v = 0 within it) meets
     * the ends' planes at any t beyond those the samples saw, of either sign: a disc
     * the samples found is an outcome out to where the ray leaves the disc's reach
     * (|t| at most (r + |w_perp|) / |d_perp|, with a margin for the box) or the range's
     * bound. */
    if (q_abs(r0.zd) <= sum_zd) {
        double wp = 0, dp = 0;
        for (int k = 0; k < 3; k++)
            wp += (double)(r0.wp[k] * r0.wp[k]), dp += (double)(r0.dp[k] * r0.dp[k]);
        const double reach =
            (fmax(c->r0, c->r1) + sqrt(wp)) / sqrt(dp) * (1 + 0x1p-16); /* inf: dp = 0 */
        for (int i = 0; i < set.n; i++) {
            ref_outcome *x = &set.v[i];
            const int pp = x->part < 0 ? 0 : x->part & ~CYLRAY_BACKFACE;
            if (pp != CYLRAY_CAP_LO && pp != CYLRAY_CAP_HI)
                continue;
            if (x->hi > 0)
                x->hi = fmax(x->hi, fmin((double)tmax, reach));
            if (x->lo < 0)
                x->lo = fmin(x->lo, fmax((double)tmin, -reach));
        }
    }

    ref_band_keep_set(out, &set, x0 >= 0 ? p0 : -1);
    /* The gradient samples turn the normal by 2 ulps of one input each; the box's
     * corners by all at once: twice the worst sample bounds a sum of a few. */
    out->n_spread = 2 * nmax;
    for (int kand = K_FRONT; kand <= K_BACK; kand++) {
        /* Near the apex the side's normal turns all the way round it: its direction
         * across the axis is that of x_perp, which the box moves by about delta. Where
         * the samples do not happen to straddle the axis, this bound does. The side's
         * root taken exactly, or, where the exact answer is not the side, either root
         * (an alternative outcome's normal is judged by the same rule). */
        if (x0 == K_FRONT || x0 == K_BACK ? kand != x0 : !r0.exists[kand])
            continue;
        double dm = 0, am = 0, xp = 0;
        const cylq t = r0.t[kand];
        for (int k = 0; k < 3; k++) {
            dm = fmax(dm, fabs((double)base.d[k]));
            am = fmax(am, fabs((double)base.a[k]));
            const double x = (double)(r0.wp[k] + t * r0.dp[k]);
            xp += x * x;
        }
        const double zr = fabs((double)(r0.zw + t * r0.zd)) / (double)r0.L;
        const double delta =
            8 * ((double)step[IN_W] + fabs((double)t) * ref_float_ulp(dm) +
                 (1 + zr) * ref_float_ulp(am) * fmax(1, fabs((double)t) * dm / am) +
                 ref_float_ulp(fmax(c->r0, c->r1)));
        xp = sqrt(xp);
        out->n_spread =
            fmax(out->n_spread, xp > delta ? 2 * asin(delta / xp) : 3.14159265358979323846);
        /* The side's normal is a function of x_perp's direction alone. A t anywhere in
         * the exact outcome's band moves the point across the axis by up to |d_perp| dt,
         * turning that direction by up to asin(|d_perp| dt / |x_perp|): on a grazing ray,
         * or one leaving the surface, the band is wide and the samples, which keep the
         * exact outcome, do not move far along it. */
        if (kand == x0 && out->t_lo == out->t_lo) {
            double dp2 = 0;
            for (int k = 0; k < 3; k++)
                dp2 += (double)r0.dp[k] * (double)r0.dp[k];
            const double tt = (double)t,
                         move = sqrt(dp2) * fmax(tt - out->t_lo, out->t_hi - tt);
            out->n_spread = fmax(out->n_spread, move < xp ? asin(move / xp) + 2 * nmax
                                                          : 3.14159265358979323846);
        }
    }
    out->n_spread = fmin(out->n_spread, 3.14159265358979323846); /* opposite at most */
}

REF_BAND_DEFINE(conref, cylray_cone, conref_valid, cone_band)

int conref_judge(const cylref_band *b, int hit, int part, float t, double *ulps_beyond)
{
    return cylref_judge(b, hit, part, t, ulps_beyond);
}
