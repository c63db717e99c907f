/* SPDX-License-Identifier: MIT */
/* exact.c - the exact intersection: every candidate t and decision margin in binary128,
 * then the decision (docs/design.md sections 1-3) from the margins' signs.
 *
 * With V = v.v (the axis is never normalised), w = o - c, e = d x v, f = w x v:
 *   side:  A t^2 + 2 B t + C = 0,  A = e.e,  B = e.f,  C = f.f - R^2 V,
 *          B^2 - A C = V (A R^2 - g^2),  g = e.w   (Lagrange's identity),
 *   slab:  z(t) = w.v + t d.v  (axial coordinate times |v|),  |z| <= H sqrt(V).
 * The float inputs make w, e and the slab terms exact in binary128 (differences of
 * 48-bit products) in every realistic case; the rest rounds at 2^-113. */
#include "exact.h"

#include <string.h>

double ref_float_ulp(double x)
{
    x = fabs(x);
    if (!(x < INFINITY))
        return x == x ? INFINITY : NAN;
    if (x < 0x1p-126)
        return 0x1p-149;
    int e = ilogb(x);
    return ldexp(1.0, e - 23);
}

double cylref_float_ulp(double x)
{
    return ref_float_ulp(x);
}

static int f_finite3(const float a[3])
{
    return isfinite(a[0]) && isfinite(a[1]) && isfinite(a[2]);
}

int qin_from_float(qin *q, const cylray_cylinder *cyl, const float o[3], const float d[3])
{
    memset(q, 0, sizeof *q);
    if (!cyl || !o || !d)
        return 0;
    if (!f_finite3(cyl->center) || !f_finite3(cyl->axis) || !f_finite3(o) || !f_finite3(d))
        return 0;
    if (!(cyl->radius > 0) || !isfinite(cyl->radius) || !(cyl->half_height > 0))
        return 0;
    if (cyl->axis[0] == 0 && cyl->axis[1] == 0 && cyl->axis[2] == 0)
        return 0;
    if (d[0] == 0 && d[1] == 0 && d[2] == 0)
        return 0;
    for (int k = 0; k < 3; k++) {
        q->o[k] = o[k];
        q->d[k] = d[k];
        q->c[k] = cyl->center[k];
        q->v[k] = cyl->axis[k];
    }
    q->R = cyl->radius;
    q->H = cyl->half_height;
    q->caps = cyl->flags & CYLRAY_CAPPED;
    q->kind = !isfinite(cyl->half_height)    ? QK_INFINITE
              : (cyl->flags & CYLRAY_CAPPED) ? QK_CAPPED
                                             : QK_OPEN;
    return 1;
}

static cylq qdot(const cylq a[3], const cylq b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void qcross(cylq out[3], const cylq a[3], const cylq b[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

/* A kernel decides with float values of size `mag`: within a few of its ulps of zero
 * its comparison may go either way. 4 ulps, as the checker's t tolerance. */
static cylq widen(cylq mag)
{
    return (cylq)(4 * ref_float_ulp((double)q_abs(mag)));
}

static void set_margin(qrec *r, int k, cylq m, cylq mag, int relevant)
{
    r->m[k] = m;
    r->mw[k] = widen(mag);
    r->mrel[k] = relevant;
}

void q_eval(const qin *q, cylq tmin, cylq tmax, qrec *r)
{
    memset(r, 0, sizeof *r);
    r->valid = 1;
    r->kind = q->kind;
    r->caps = q->caps;
    const cylq inf = (cylq)INFINITY;
    cylq w[3], e[3], f[3];
    for (int k = 0; k < 3; k++) {
        w[k] = q->o[k] - q->c[k];
        r->w[k] = w[k];
        r->d[k] = q->d[k];
        r->v[k] = q->v[k];
    }
    const cylq V = qdot(q->v, q->v);
    r->V = V;
    qcross(e, q->d, q->v);
    qcross(f, w, q->v);
    const cylq A = qdot(e, e), B = qdot(e, f), RRV = q->R * q->R * V;
    const cylq C = qdot(f, f) - RRV;
    const cylq g = qdot(e, w);
    const cylq AR2 = A * q->R * q->R;
    const cylq D = AR2 - g * g;

    r->par_exact = A == 0;
    set_margin(r, M_NOTPAR, A, 0, 1);
    r->mw[M_NOTPAR] = 0; /* the documented parallel threshold lies inside the band */
    set_margin(r, M_DISC, D, AR2, 1);
    set_margin(r, M_INTUBE, -C, RRV, q->kind == QK_CAPPED);

    /* Side roots, with sqrt(max(D, 0)) so that they move continuously through a
     * tangency: a perturbation that makes D negative still has a t to compare. */
    cylq tn, tf;
    if (A > 0) {
        cylq sq = q_sqrt(V * q_max(D, 0));
        cylq qq = -(B + q_copysign(sq, B));
        cylq r1 = qq / A, r2 = qq != 0 ? C / qq : r1;
        tn = q_min(r1, r2);
        tf = q_max(r1, r2);
    } else {
        tn = -inf; /* the parallel ray: inside for all t or never (M_INTUBE) */
        tf = inf;
    }
    r->tp[P_SLO] = tn;
    r->tp[P_SHI] = tf;

    const cylq dv = qdot(q->d, q->v), z0 = qdot(w, q->v);
    const cylq Hv = q->kind == QK_INFINITE ? inf : q->H * q_sqrt(V);
    r->dv_zero = dv == 0;
    r->dv_pos = dv > 0;
    r->tp[P_BLO] = -inf;
    r->tp[P_BHI] = inf;
    if (q->kind == QK_OPEN) {
        cylq zn = z0 + tn * dv, zf = z0 + tf * dv;
        set_margin(r, M_ZN, Hv - q_abs(zn), q_max(Hv, q_abs(zn)), 1);
        set_margin(r, M_ZF, Hv - q_abs(zf), q_max(Hv, q_abs(zf)), 1);
    }
    if (q->kind == QK_CAPPED) {
        if (dv != 0) {
            cylq ta = (-Hv - z0) / dv, tb = (Hv - z0) / dv;
            r->tp[P_BLO] = q_min(ta, tb);
            r->tp[P_BHI] = q_max(ta, tb);
        }
        set_margin(r, M_SLABOK, Hv - q_abs(z0), q_max(Hv, q_abs(z0)), dv == 0);
        const cylq *t = r->tp;
        set_margin(r, M_INSIDE, t[P_SLO] - t[P_BLO], q_max(q_abs(t[P_SLO]), q_abs(t[P_BLO])),
                   1);
        set_margin(r, M_OUTSIDE, t[P_BHI] - t[P_SHI], q_max(q_abs(t[P_BHI]), q_abs(t[P_SHI])),
                   1);
        set_margin(r, M_X1, t[P_BHI] - t[P_SLO], q_max(q_abs(t[P_BHI]), q_abs(t[P_SLO])), 1);
        set_margin(r, M_X2, t[P_SHI] - t[P_BLO], q_max(q_abs(t[P_SHI]), q_abs(t[P_BLO])), 1);
    }
    for (int p = 0; p < P_COUNT; p++) {
        int rel = p < P_BLO || q->kind == QK_CAPPED;
        cylq t = r->tp[p];
        set_margin(r, M_GE_MIN + p, t - tmin, q_max(q_abs(t), q_abs(tmin)), rel);
        set_margin(r, M_LE_MAX + p, tmax - t, q_max(q_abs(t), q_abs(tmax)), rel);
    }
}

void q_bools(const qrec *r, unsigned char b[M_COUNT])
{
    for (int k = 0; k < M_COUNT; k++)
        b[k] = r->m[k] >= 0;
    b[M_NOTPAR] = r->m[M_NOTPAR] > 0;
}

/* t = tp[p] is a hit parameter: finite and inside [tmin, tmax]. */
static int in_range(const qrec *r, const unsigned char *b, int p)
{
    return q_isfinite(r->tp[p]) && b[M_GE_MIN + p] && b[M_LE_MAX + p];
}

static int slab_part(const qrec *r, int p)
{
    /* Moving up (d.v > 0) the slab is entered at -H and left at +H. */
    return (p == P_BLO) == (r->dv_pos != 0) ? CYLRAY_CAP_LO : CYLRAY_CAP_HI;
}

qout q_decide(const qrec *r, const unsigned char b[M_COUNT], int cull)
{
    qout out = {0, CYLRAY_MISS, -1};
    int side_exists, side_all = 0;
    if (b[M_NOTPAR] && !r->par_exact) {
        side_exists = b[M_DISC];
    } else {
        /* Parallel: no side root. Only a capped solid still has its caps. */
        if (r->kind != QK_CAPPED)
            return out;
        side_exists = b[M_INTUBE];
        side_all = 1;
    }
    if (!side_exists)
        return out;
    int pin, pout, ok_in, ok_out;
    if (r->kind == QK_CAPPED) {
        int slab_all = r->dv_zero;
        if (slab_all && !b[M_SLABOK])
            return out;
        /* Entry = the later of the two entries, exit = the earlier of the exits; an
         * unbounded interval never wins. */
        int side_in = slab_all || (!side_all && b[M_INSIDE]);
        int side_out = slab_all || (!side_all && b[M_OUTSIDE]);
        pin = side_in ? P_SLO : P_BLO;
        pout = side_out ? P_SHI : P_BHI;
        int nonempty = slab_all || side_all || (b[M_X1] && b[M_X2]);
        ok_in = ok_out = nonempty;
        /* A bound made by a disc that is not part of the surface is no hit: the ray
         * passes through that open end (the solid still decides entry and exit). */
        if (pin != P_SLO &&
            !(r->caps &
              (slab_part(r, pin) == CYLRAY_CAP_LO ? CYLRAY_CAPPED_LO : CYLRAY_CAPPED_HI)))
            ok_in = 0;
        if (pout != P_SHI &&
            !(r->caps &
              (slab_part(r, pout) == CYLRAY_CAP_LO ? CYLRAY_CAPPED_LO : CYLRAY_CAPPED_HI)))
            ok_out = 0;
    } else {
        pin = P_SLO;
        pout = P_SHI;
        ok_in = r->kind == QK_OPEN ? b[M_ZN] : 1;
        ok_out = r->kind == QK_OPEN ? b[M_ZF] : 1;
    }
    if (ok_in && in_range(r, b, pin)) {
        out.hit = 1;
        out.prim = pin;
        out.part = pin == P_SLO ? CYLRAY_SIDE : slab_part(r, pin);
    } else if (!cull && ok_out && in_range(r, b, pout)) {
        out.hit = 1;
        out.prim = pout;
        out.part = (pout == P_SHI ? CYLRAY_SIDE : slab_part(r, pout)) | CYLRAY_BACKFACE;
    }
    return out;
}

void q_normal(const qrec *r, qout o, int ff, double n[3])
{
    n[0] = n[1] = n[2] = 0;
    if (!o.hit)
        return;
    cylq m[3];
    if (o.prim == P_SLO || o.prim == P_SHI) {
        /* The hit point relative to the center, minus its axial part. */
        cylq t = r->tp[o.prim], p[3];
        for (int k = 0; k < 3; k++)
            p[k] = r->w[k] + t * r->d[k];
        cylq s = qdot(p, r->v) / r->V;
        for (int k = 0; k < 3; k++)
            m[k] = p[k] - s * r->v[k];
    } else {
        cylq s = (o.part & CYLRAY_PART_MASK) == CYLRAY_CAP_LO ? -1 : 1;
        for (int k = 0; k < 3; k++)
            m[k] = s * r->v[k];
    }
    cylq len = q_sqrt(qdot(m, m));
    if (!(len > 0))
        return;
    cylq s = ((o.part & CYLRAY_BACKFACE) && ff) ? -1 / len : 1 / len;
    for (int k = 0; k < 3; k++)
        n[k] = (double)(m[k] * s);
}

int cylref_intersect(const cylray_cylinder *cyl, const float o[3], const float d[3], float tmin,
                     float tmax, unsigned flags, cylref_hit *out)
{
    memset(out, 0, sizeof *out);
    qin q;
    if (!cyl || !qin_from_float(&q, cyl, o, d)) {
        int bad_cyl = !cyl || !f_finite3(cyl->center) || !f_finite3(cyl->axis) ||
                      !(cyl->radius > 0) || !isfinite(cyl->radius) || !(cyl->half_height > 0) ||
                      (cyl->axis[0] == 0 && cyl->axis[1] == 0 && cyl->axis[2] == 0);
        return bad_cyl ? -1 : 0;
    }
    if (tmin != tmin || tmax != tmax)
        return 0;
    qrec r;
    q_eval(&q, tmin, tmax, &r);
    unsigned char b[M_COUNT];
    q_bools(&r, b);
    qout h = q_decide(&r, b, (flags & CYLRAY_CULL_BACK) != 0);
    if (!h.hit)
        return 0;
    out->hit = 1;
    out->t = (double)r.tp[h.prim];
    out->part = h.part;
    q_normal(&r, h, (flags & CYLRAY_FACE_FORWARD) != 0, out->n);
    return 1;
}
