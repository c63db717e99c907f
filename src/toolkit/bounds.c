/* SPDX-License-Identifier: MIT */
/* toolkit/bounds.c - the float box of a prepared cylinder and of a leaf, rounded outward. */
#include "cylray_internal.h"
#include "internal/dd.h"

#include <string.h>

/* The unit axis n = v / |v| and the rim's half extent s = sqrt(1 - n_k^2) along
 * coordinate k, as double-doubles. Both are exact when the axis lies along k (n_k =
 * +-1, s = 0) or across it (n_k = 0, s = 1); otherwise each is within 2^-100 of its
 * value relative to itself, and *exact is cleared. */
typedef struct axis_k {
    cylray_dd n, s;
    int exact;
} axis_k;

static axis_k axis_coord(const float v[3], int k)
{
    axis_k a;
    const double vk = v[k], vi = v[(k + 1) % 3], vj = v[(k + 2) % 3];
    if (vi == 0 && vj == 0) {
        a.n = dd_make(vk > 0 ? 1.0 : -1.0, 0.0);
        a.s = dd_make(0.0, 0.0);
        a.exact = 1;
        return a;
    }
    if (vk == 0) {
        a.n = dd_make(0.0, 0.0);
        a.s = dd_make(1.0, 0.0);
        a.exact = 1;
        return a;
    }
    /* The squares of floats are exact as double-doubles, so S and V are good to a few
     * 2^-104, and so are their roots and the quotients. */
    cylray_dd S = dd_add(dd_two_prod(vi, vi), dd_two_prod(vj, vj));
    cylray_dd V = dd_add(S, dd_two_prod(vk, vk));
    cylray_dd sv = dd_sqrt(V);
    a.n = dd_div(dd_make(vk, 0.0), sv);
    a.s = dd_div(dd_sqrt(S), sv);
    a.exact = 0;
    return a;
}

/* c + a + b rounded down (dir < 0) or up (dir > 0) to float, where a and b carry a
 * relative error of at most 2^-100 unless exact. The sum in double-double adds a few
 * 2^-104 of the magnitudes; 2^-96 of them covers everything, so the float is on the
 * outer side of the exact value and, unless the sum cancels to below about 2^-70 of
 * its terms, at most one float step beyond the closest float there. */
static float face(double c, cylray_dd a, cylray_dd b, int exact, int dir)
{
    cylray_dd x = dd_add(dd_add(dd_make(c, 0.0), a), b);
    if (!exact) {
        double mag = fabs(c) + fabs(a.hi) + fabs(b.hi);
        x = dd_add(x, dd_make(dir * ldexp(mag, -96), 0.0));
    }
    return dir < 0 ? dd_floor_float(x) : dd_ceil_float(x);
}

/* ---- the same faces in plain double first ------------------------------------------
 * The double-double path above costs about 300 ns a coordinate (square roots and
 * divisions in a chain). Each face is first formed in double with a bound on its
 * error, and taken where every value within the bound rounds outward to the same
 * float: that float is then the double-double path's too, which rounds the exact
 * value, pushed outward by 2^-96 of the magnitudes, the same way. */

/* n_k and s_k in double, within 3 and 4.5 units of 2^-53 of themselves (sums of exact
 * squares, square roots, divisions); exact along k and across it, as axis_coord. */
static int axis_coord_d(const float v[3], int k, double *n, double *s)
{
    const double vk = v[k], vi = v[(k + 1) % 3], vj = v[(k + 2) % 3];
    if (vi == 0 && vj == 0) {
        *n = vk > 0 ? 1.0 : -1.0, *s = 0.0;
        return 1;
    }
    if (vk == 0) {
        *n = 0.0, *s = 1.0;
        return 1;
    }
    const double S = vi * vi + vj * vj, sv = sqrt(S + vk * vk);
    *n = vk / sv, *s = sqrt(S) / sv;
    return 0;
}

/* x rounded down or up to float (x not NaN) */
static float outward_f(double x, int dir)
{
    return dir < 0 ? dd_floor_float(dd_make(x, 0.0)) : dd_ceil_float(dd_make(x, 0.0));
}

/* c + a + b rounded outward to float, where a and b are within 6 units of 2^-53 of
 * themselves (exact where `exact`): 1 and *out where decided. The sum's two roundings
 * add 2 units of the magnitudes; 2^-48 of them (32 units) bounds every error, the
 * roundings of x -+ e included. */
static inline int face_quick(double c, double a, double b, int exact, int dir, float *out)
{
    const cylray_dd s1 = dd_two_sum(c, a), s2 = dd_two_sum(s1.hi, b);
    const double x = s2.hi;
    if (exact && s1.lo == 0 && s2.lo == 0) {
        *out = outward_f(x, dir); /* the sum is exact */
        return 1;
    }
    const double e = (fabs(c) + fabs(a) + fabs(b)) * 0x1p-48;
    const float f = outward_f(x + dir * e, dir);
    if (f != outward_f(x - dir * e, dir))
        return 0;
    *out = f;
    return 1;
}

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

cylray_status cylray_bounds(const cylray_prepared *cyl, float lo[3], float hi[3])
{
    if (!cylray_prepared_ok_(cyl) || !lo || !hi || cyl->kind == CYLRAY_KIND_INFINITE)
        return CYLRAY_EINVAL;
    float l[3], h[3];
    if (cyl->kind == CYLRAY_KIND_SPHERE)
        sphere_box(cyl->c, cyl->radius, l, h);
    else
        cyl_box(cyl->c, cyl->v, cyl->radius, cyl->half_height, l, h);
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
        float c[3], v[3], bl[3], bh[3];
        for (int k = 0; k < 3; k++) {
            c[k] = geom[(CYLRAY_LF_CX + k) * m + i];
            v[k] = geom[(CYLRAY_LF_VX + k) * m + i];
        }
        double H = geom[CYLRAY_LF_H * m + i];
        if (!isfinite(H))
            return CYLRAY_EINVAL;
        if ((meta[CYLRAY_LM_SPHERE] >> i) & 1u)
            sphere_box(c, geom[CYLRAY_LF_R * m + i], bl, bh);
        else
            cyl_box(c, v, geom[CYLRAY_LF_R * m + i], H, bl, bh);
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

/* ---- boxes along a long cylinder ------------------------------------------------ */

/* The box of the disc of radius R centred on the axis at t (world units, exact as a
 * double-double) from the center: coordinate k spans c_k + t n_k -+ R s_k. */
static void disc_box(const float c[3], const float v[3], double R, cylray_dd t, float lo[3],
                     float hi[3])
{
    for (int k = 0; k < 3; k++) {
        /* t n_k in double: the product's rounding and t's own add 2 units of 2^-53 to
         * n_k's 3; always pushed outward, as below */
        double n, s;
        axis_coord_d(v, k, &n, &s);
        const double m_d = (t.hi + t.lo) * n, r_d = R * s;
        if (face_quick(c[k], m_d, -r_d, 0, -1, &lo[k]) &&
            face_quick(c[k], m_d, r_d, 0, 1, &hi[k]))
            continue;
        axis_k a = axis_coord(v, k);
        cylray_dd m = dd_mul(t, a.n), r = dd_mul_d(a.s, R);
        /* even along a coordinate axis c_k + t is not always a double-double */
        lo[k] = face(c[k], m, dd_neg(r), 0, -1);
        hi[k] = face(c[k], m, r, 0, 1);
    }
}

/* The rule for k = 0: the smallest k at which, in each coordinate j but the one the
 * axis is closest to, a slice's extent from the tilt, 2H |n_j| / k, is at most its
 * extent from the radius, 2R sqrt(1 - n_j^2); 1 to CYLRAY_SPLIT_MAX. */
static size_t split_count(const cylray_prepared *cyl)
{
    const float *v = cyl->v;
    int m = 0;
    for (int j = 1; j < 3; j++)
        if (fabsf(v[j]) > fabsf(v[m]))
            m = j;
    double want = 1;
    for (int j = 0; j < 3; j++) {
        if (j == m || v[j] == 0)
            continue;
        double vi = v[(j + 1) % 3], vk = v[(j + 2) % 3];
        double ratio = (double)cyl->half_height * fabs((double)v[j]) /
                       ((double)cyl->radius * sqrt(vi * vi + vk * vk));
        want = fmax(want, ceil(ratio));
    }
    return want >= CYLRAY_SPLIT_MAX ? CYLRAY_SPLIT_MAX : (size_t)want;
}

/* A sphere's slices are cut across z, as its surface coordinates are measured (v along
 * z): slice i of k lies between the planes z = c_z + R q_i and c_z + R q_(i+1), q_i as
 * for a cylinder, and spans c_x, c_y -+ R sqrt(1 - q^2) at the q of its range nearest 0
 * (R where the range holds 0). */
static void sphere_slices(const cylray_prepared *cyl, size_t k, float (*lo)[3], float (*hi)[3])
{
    const double R = cyl->radius;
    const cylray_dd z = dd_make(0.0, 0.0);
    double qa = -1.0;
    for (size_t i = 0; i < k; i++) {
        const double qb = ((double)(i + 1) * 2.0 - (double)k) / (double)k;
        /* R q is exact as a double-double; so is c_z + R q where R q is one double (q =
         * 0 or +-1 among others: one slice is the box of cylray_bounds), and elsewhere
         * it is pushed out as disc_box's */
        const cylray_dd za = dd_two_prod(R, qa), zb = dd_two_prod(R, qb);
        lo[i][2] = face(cyl->c[2], za, z, za.lo == 0, -1);
        hi[i][2] = face(cyl->c[2], zb, z, zb.lo == 0, 1);
        const double m = qa <= 0 && qb >= 0 ? 0.0 : fmin(fabs(qa), fabs(qb));
        /* (1 - m)(1 + m), its root and the product by R are within 4 units of 2^-53
         * of themselves; 2^-48 more keeps the half width above the exact one, and the
         * face at most one float step beyond the nearest */
        const double w = m == 0 ? R : R * sqrt((1.0 - m) * (1.0 + m)) * (1 + 0x1p-48);
        const int exact = m == 0;
        for (int j = 0; j < 2; j++) {
            lo[i][j] = face(cyl->c[j], dd_make(-w, 0.0), z, exact, -1);
            hi[i][j] = face(cyl->c[j], dd_make(w, 0.0), z, exact, 1);
        }
        qa = qb;
    }
}

size_t cylray_split_boxes(const cylray_prepared *cyl, size_t k, float (*lo)[3], float (*hi)[3])
{
    if (!cylray_prepared_ok_(cyl) || cyl->kind == CYLRAY_KIND_INFINITE)
        return 0;
    if (k == 0)
        k = cyl->kind == CYLRAY_KIND_SPHERE ? 1 : split_count(cyl);
    if (!lo || !hi)
        return k;
    if (cyl->kind == CYLRAY_KIND_SPHERE) {
        sphere_slices(cyl, k, lo, hi);
        return k;
    }
    /* Slice i runs between the discs at t_i = H q_i, q_i = (2i - k) / k rounded once:
     * q_0 = -1 and q_k = 1 exactly and the q_i increase, so neighbouring slices share
     * their disc exactly and together cover the cylinder; H q_i is exact as a
     * double-double. */
    const double H = cyl->half_height, R = cyl->radius;
    float plo[3], phi[3];
    disc_box(cyl->c, cyl->v, R, dd_two_prod(H, -1.0), plo, phi);
    for (size_t i = 0; i < k; i++) {
        double q = ((double)(i + 1) * 2.0 - (double)k) / (double)k;
        float nlo[3], nhi[3];
        disc_box(cyl->c, cyl->v, R, dd_two_prod(H, q), nlo, nhi);
        for (int j = 0; j < 3; j++) {
            lo[i][j] = fminf(plo[j], nlo[j]);
            hi[i][j] = fmaxf(phi[j], nhi[j]);
            plo[j] = nlo[j];
            phi[j] = nhi[j];
        }
    }
    return k;
}
