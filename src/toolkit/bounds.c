/* SPDX-License-Identifier: MIT */
/* toolkit/bounds.c - the float box of a prepared cylinder and of a leaf, rounded outward. */
#include "faces.h"
#include "internal/shape.h"

#include <string.h>

/* The box of a finite cylinder: that of its two rims, c_k -+ (H |n_k| + R s_k); the
 * discs and the side lie inside it whatever the caps. */
static void cyl_box(const float c[3], const float v[3], double R, double H, float lo[3],
                    float hi[3])
{
    for (int k = 0; k < 3; k++) {
        double n, s;
        const int exact = axis_coord_d(v, k, &n, &s);
        const double h = H * fabs(n), r = R * s;
        if (face_quick(c[k], -h, -r, exact, -1, &lo[k]) &&
            face_quick(c[k], h, r, exact, 1, &hi[k]))
            continue;
        axis_k a = axis_coord(v, k);
        cylray_dd hd = dd_mul_d(dd_make(fabs(a.n.hi), a.n.hi < 0 ? -a.n.lo : a.n.lo), H);
        cylray_dd rd = dd_mul_d(a.s, R);
        lo[k] = face(c[k], dd_neg(hd), dd_neg(rd), a.exact, -1);
        hi[k] = face(c[k], hd, rd, a.exact, 1);
    }
}

/* The box of a sphere, c_k -+ R: the sum of two floats is exact as a double-double, so
 * each face is the float next to the exact one on its outer side (the smallest box). */
static void sphere_box(const float c[3], double R, float lo[3], float hi[3])
{
    const cylray_dd z = dd_make(0.0, 0.0);
    for (int k = 0; k < 3; k++) {
        lo[k] = face(c[k], dd_make(-R, 0.0), z, 1, -1);
        hi[k] = face(c[k], dd_make(R, 0.0), z, 1, 1);
    }
}

/* The float at or below (dir -1) or above (dir 1) the double x. */
static float round_out(double x, int dir)
{
    const float f = (float)x;
    if (dir < 0 ? (double)f > x : (double)f < x)
        return nextafterf(f, dir < 0 ? -INFINITY : INFINITY);
    return f;
}

/* The box of a cone (radius ra + kap (z - za) at z = (x - c).v, internal/leaf.h; its
 * ends at z = -+H|v|): the frustum is the hull of its two discs, and a disc of radius r
 * about d with unit normal n spans d_k -+ r sqrt(1 - n_k^2) along axis k. Evaluated in
 * double (each product and quotient to a few units of 2^-53 relative), each face lies
 * within a few units of 2^-53 of (|c_k| + H + r) of its exact value; 2^-48 of that is
 * taken off outward before the face is rounded outward to float (at most an ulp more
 * than the smallest box). */
static void cone_box(const float c[3], const float v[3], double ra, double kap, double H,
                     float lo[3], float hi[3])
{
    const double vv = (double)v[0] * v[0] + (double)v[1] * v[1] + (double)v[2] * v[2];
    const double sv = sqrt(vv), hv = H * sv;
    const double r[2] = {cylray_cone_radius_(ra, kap, hv, -hv),
                         cylray_cone_radius_(ra, kap, hv, hv)};
    for (int k = 0; k < 3; k++) {
        /* sqrt(1 - n_k^2) from the other two components: no cancellation near n_k = 1 */
        const double a = v[(k + 1) % 3], b = v[(k + 2) % 3];
        const double n = v[k] / sv, s = sqrt(a * a + b * b) / sv;
        double l = INFINITY, h = -INFINITY;
        for (int e = 0; e < 2; e++) {
            const double d = c[k] + (e ? H : -H) * n;
            l = fmin(l, d - r[e] * s);
            h = fmax(h, d + r[e] * s);
        }
        const double slack = 0x1p-48 * (fabs(c[k]) + H + fmax(r[0], r[1]));
        lo[k] = round_out(l - slack, -1);
        hi[k] = round_out(h + slack, 1);
    }
}

/* The box of a finite shape. */
static void shape_box(const cylray_shape_ *s, float lo[3], float hi[3])
{
    switch (s->shape) {
    case CYLRAY_SHAPE_SPHERE:
        sphere_box(s->c, s->r, lo, hi);
        break;
    case CYLRAY_SHAPE_CONE:
        cone_box(s->c, s->v, s->r, s->kap, s->h, lo, hi);
        break;
    default:
        cyl_box(s->c, s->v, s->r, s->h, lo, hi);
    }
}

cylray_status cylray_bounds(const cylray_prepared *cyl, float lo[3], float hi[3])
{
    if (!cylray_prepared_ok_(cyl) || !lo || !hi || cyl->kind == CYLRAY_KIND_INFINITE ||
        cyl->kind == CYLRAY_KIND_ROUND)
        return CYLRAY_EINVAL;
    float l[3], h[3];
    const cylray_shape_ s = cylray_shape_of_(cyl);
    shape_box(&s, l, h);
    memcpy(lo, l, sizeof l);
    memcpy(hi, h, sizeof h);
    return CYLRAY_OK;
}

/* A leaf's geometry is geom[field * m + lane] (internal/leaf.h). */
static cylray_status leaf_bounds(const float *geom, const uint32_t *meta, unsigned m,
                                 float lo[3], float hi[3])
{
    if (!geom || !lo || !hi)
        return CYLRAY_EINVAL;
    uint32_t used = meta[CYLRAY_LM_USED] & (m == 32 ? ~0u : (1u << m) - 1u);
    if (!used)
        return CYLRAY_EINVAL;
    float l[3] = {INFINITY, INFINITY, INFINITY}, h[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (unsigned i = 0; i < m; i++) {
        if (!((used >> i) & 1u))
            continue;
        const cylray_shape_ s = cylray_leaf_shape_(geom, meta, m, i);
        if (!isfinite(s.h))
            return CYLRAY_EINVAL;
        float bl[3], bh[3];
        shape_box(&s, bl, bh);
        for (int k = 0; k < 3; k++) {
            l[k] = fminf(l[k], bl[k]);
            h[k] = fmaxf(h[k], bh[k]);
        }
    }
    memcpy(lo, l, sizeof l);
    memcpy(hi, h, sizeof h);
    return CYLRAY_OK;
}

#define LEAF_BOUNDS_(m)                                                                        \
    cylray_status cylray_leaf_bounds##m(const cylray_leaf##m *leaf, float lo[3], float hi[3])  \
    {                                                                                          \
        if (!leaf)                                                                             \
            return CYLRAY_EINVAL;                                                              \
        return leaf_bounds(&leaf->geom_[0][0], leaf->meta_, m, lo, hi);                        \
    }
LEAF_BOUNDS_(4)
LEAF_BOUNDS_(8)
LEAF_BOUNDS_(16)
