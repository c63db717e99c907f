/* SPDX-License-Identifier: MIT */
/* conref.c - the exact ray/cone intersection (its tolerance band: conref_band.c).
 *
 * Frame: u = a / |a| with a = p1 - p0, w = o - c with c = (p0 + p1) / 2, z measured
 * from p0: z(t) = zw + t zd with zw = w.u + L/2, zd = d.u, L = |a|. The radius
 * r(z) = r0 + k z, k = (r1 - r0) / L, and with x_perp = w_perp + t d_perp the side
 * |x_perp|^2 - r(z)^2 = 0 is A t^2 + 2 B t + C = 0:
 *   A = d_perp.d_perp - k^2 zd^2,  B = w_perp.d_perp - k zd r(zw),  C = |w_perp|^2 - r(zw)^2.
 * Half the gradient of |x_perp|^2 - r(z)^2 along d is A t + B = +-sqrt(B^2 - A C), so
 * the root with +sqrt is where the ray leaves (a back face) whatever the sign of A.
 * Inside the slab 0 <= z <= L, r(z) lies between r0 and r1 and is >= 0, so the slab
 * alone keeps the mirror nappe out. The solid is convex, so along a line its entry
 * precedes its exit and dropping back faces before or after taking the first hit is
 * the same. A disc of radius 0 (a tip) is a point, no surface. */
#include "conref_eval.h"
#include "bandutil.h"

#include "exact.h"
#include "quad.h"

#include "../support/rng.h"

#include <stdint.h>
#include <string.h>

int conref_present_(unsigned flags, int kand)
{
    return kand < K_LO || (flags & (kand == K_LO ? CYLRAY_CAPPED_LO : CYLRAY_CAPPED_HI));
}

int conref_valid(const cylray_cone *c)
{
    if (!c || !ref_ends_ok(c->p0, c->p1, c->r0, c->r1))
        return 0;
    int big = 0;
    for (int k = 0; k < 3; k++) {
        float a = c->p1[k] - c->p0[k];
        big |= fabsf(a) >= 0x1p-126f;
    }
    if (!big)
        return 0;
    /* the ends at most 2^62 apart in each rounded coordinate and in half length, and
     * the slope |r1 - r0| / |p1 - p0| at most 2^40, max(r0, r1) (1 + slope) +
     * |r1 - r0| / 2 at most 2^61, unless r0 == r1 (cylray.h) */
    double len2 = 0;
    for (int k = 0; k < 3; k++) {
        const double a = (double)c->p1[k] - c->p0[k];
        if (!(fabsf((float)a) <= 0x1p62f))
            return 0;
        len2 += a * a;
    }
    if (!((float)(0.5 * sqrt(len2)) <= 0x1p62f))
        return 0;
    const double slope = fabs((double)c->r1 - c->r0) / sqrt(len2);
    if (c->r0 != c->r1 &&
        (!(slope <= 0x1p40) ||
         !(fmax(c->r0, c->r1) * (1.0 + slope) + 0.5 * fabs((double)c->r1 - c->r0) <= 0x1p61)))
        return 0;
    return (c->flags & ~(unsigned)CYLRAY_CAPPED) == 0;
}

static cylq widen(cylq mag)
{
    return (cylq)(4 * ref_float_ulp((double)q_abs(mag)));
}

static void range_margins(crec *r, int kand, cylq tmin, cylq tmax)
{
    const cylq t = r->t[kand];
    r->m[kand][G_GE] = t - tmin;
    r->mw[kand][G_GE] = widen(q_max(q_abs(t), q_abs(tmin)));
    r->m[kand][G_LE] = tmax - t;
    r->mw[kand][G_LE] = widen(q_max(q_abs(t), q_abs(tmax)));
}

void conref_eval_(const cin_q *q, cylq tmin, cylq tmax, crec *r)
{
    memset(r, 0, sizeof *r);
    const cylq L = q_sqrt(ref_dot3(q->a, q->a));
    for (int k = 0; k < 3; k++)
        r->u[k] = q->a[k] / L;
    const cylq zc = ref_dot3(q->w, r->u), zd = ref_dot3(q->d, r->u), zw = zc + L / 2;
    for (int k = 0; k < 3; k++) {
        r->wp[k] = q->w[k] - zc * r->u[k];
        r->dp[k] = q->d[k] - zd * r->u[k];
    }
    const cylq kk = (q->r1 - q->r0) / L, rw = q->r0 + kk * zw;
    r->zw = zw;
    r->zd = zd;
    r->k = kk;
    r->L = L;
    r->r0 = q->r0;
    const cylq dd = ref_dot3(r->dp, r->dp), kz = kk * zd;
    const cylq A = dd - kz * kz, B = ref_dot3(r->wp, r->dp) - kz * rw;
    const cylq C = ref_dot3(r->wp, r->wp) - rw * rw;
    const cylq D = B * B - A * C;
    r->A = A, r->B = B, r->C = C;
    const cylq rmax = q_max(q->r0, q->r1);
    const cylq sq = q_sqrt(q_max(D, 0));
    /* The stable pair: q / A and C / q are the roots with -sgn(B) sqrt and +sgn(B) sqrt
     * in A t + B; sqrt(max(D, 0)) keeps them continuous through a tangency. */
    const cylq qq = -(B + q_copysign(sq, B));
    cylq t_minus, t_plus; /* A t + B = -sqrt(D), +sqrt(D) */
    cylq ra = A != 0 ? qq / A : (cylq)INFINITY, rc = qq != 0 ? C / qq : ra;
    if (B >= 0) {
        t_minus = ra;
        t_plus = rc;
    } else {
        t_minus = rc;
        t_plus = ra;
    }
    if (A == 0 && B == 0) {
        /* d along a generator line through the apex's line: no isolated root. */
        t_minus = t_plus = (cylq)INFINITY;
    }
    const cylq tt[2] = {t_minus, t_plus};
    for (int s = 0; s < 2; s++) {
        const int kand = s ? K_BACK : K_FRONT;
        r->t[kand] = tt[s];
        r->exists[kand] = q_isfinite(tt[s]);
        r->back[kand] = s == 1 && D > 0;
        r->m[kand][G_MEET] = D;
        r->mw[kand][G_MEET] = widen(q_max(q_abs(dd), kz * kz) * rmax * rmax);
        if (!r->exists[kand])
            continue;
        const cylq z = zw + tt[s] * zd;
        const cylq zmag = q_max(q_max(L, q_abs(zw)), q_abs(tt[s] * zd));
        r->m[kand][G_ZLO] = z;
        r->mw[kand][G_ZLO] = widen(zmag);
        r->m[kand][G_ZHI] = L - z;
        r->mw[kand][G_ZHI] = widen(zmag);
        range_margins(r, kand, tmin, tmax);
    }
    for (int e = 0; e < 2; e++) {
        const int kand = e ? K_HI : K_LO;
        const cylq rad = e ? q->r1 : q->r0;
        r->back[kand] = e ? zd > 0 : zd < 0;
        r->exists[kand] = zd != 0 && rad > 0;
        if (!r->exists[kand])
            continue;
        const cylq t = ((e ? L : 0) - zw) / zd;
        r->t[kand] = t;
        cylq x[3];
        for (int k = 0; k < 3; k++)
            x[k] = r->wp[k] + t * r->dp[k];
        r->m[kand][G_MEET] = rad * rad - ref_dot3(x, x);
        r->mw[kand][G_MEET] = widen(rad * rad);
        r->m[kand][G_ZLO] = r->m[kand][G_ZHI] = 1;
        range_margins(r, kand, tmin, tmax);
    }
}

/* valid[kand]: 1 taken, 0 dropped. Returns the first taken candidate by t, or -1. */
int conref_first_(const crec *r, const unsigned char valid[K_COUNT])
{
    int best = -1;
    for (int kand = 0; kand < K_COUNT; kand++)
        if (valid[kand] && (best < 0 || r->t[kand] < r->t[best]))
            best = kand;
    return best;
}

void conref_valid_parts_(const crec *r, unsigned flags, unsigned char valid[K_COUNT])
{
    for (int kand = 0; kand < K_COUNT; kand++) {
        int v = r->exists[kand] && conref_present_(flags, kand) &&
                !((flags & CYLRAY_CULL_BACK) && r->back[kand]);
        for (int g = 0; g < G_COUNT && v; g++)
            v = r->m[kand][g] >= 0;
        valid[kand] = (unsigned char)v;
    }
}

int conref_part_(const crec *r, int kand)
{
    int p = kand == K_LO ? CYLRAY_CAP_LO : kand == K_HI ? CYLRAY_CAP_HI : CYLRAY_SIDE;
    return p | (r->back[kand] ? CYLRAY_BACKFACE : 0);
}

void conref_normal_(const crec *r, int kand, int ff, double n[3])
{
    cylq g[3];
    if (kand == K_LO || kand == K_HI) {
        for (int k = 0; k < 3; k++)
            g[k] = kand == K_LO ? -r->u[k] : r->u[k];
    } else {
        const cylq t = r->t[kand], rz = r->r0 + r->k * (r->zw + t * r->zd);
        for (int k = 0; k < 3; k++)
            g[k] = r->wp[k] + t * r->dp[k] - rz * r->k * r->u[k];
    }
    cylq len = q_sqrt(ref_dot3(g, g));
    n[0] = n[1] = n[2] = 0;
    if (!(len > 0))
        return;
    cylq s = (ff && r->back[kand]) ? -1 / len : 1 / len;
    for (int k = 0; k < 3; k++)
        n[k] = (double)(g[k] * s);
}

void conref_in_(const cylray_cone *c, const float o[3], const float d[3], cin_q *q)
{
    ref_axis_in(c->p0, c->p1, o, d, q->w, q->d, q->a);
    q->r0 = c->r0;
    q->r1 = c->r1;
}

/* The candidate taken: conref_first_ over those valid with the shape's discs. */
static int decide(const crec *r, const cylray_cone *c, unsigned flags)
{
    unsigned char v[K_COUNT];
    conref_valid_parts_(r, c->flags | (flags & CYLRAY_CULL_BACK), v);
    return conref_first_(r, v);
}

static cylq t_of(const crec *r, int kand)
{
    return r->t[kand];
}

REF_INTERSECT_DEFINE(conref, cylray_cone, cin_q, crec, conref_valid, conref_in_, conref_eval_,
                     decide, t_of, conref_part_, conref_normal_)

void conref_as_cylinder(const cylray_cone *c, cylray_cylinder *out)
{
    memset(out, 0, sizeof *out);
    for (int k = 0; k < 3; k++) {
        out->center[k] = (float)(((double)c->p0[k] + (double)c->p1[k]) / 2);
        out->axis[k] = c->p1[k] - c->p0[k];
    }
    double aa = 0;
    for (int k = 0; k < 3; k++)
        aa += (double)out->axis[k] * out->axis[k];
    out->radius = c->r0;
    out->half_height = (float)(sqrt(aa) / 2);
    out->flags = c->flags;
}
