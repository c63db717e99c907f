/* SPDX-License-Identifier: MIT */
/* toolkit/split.c - boxes along a long cylinder (cylray_split_boxes): slices whose boxes
 * hug a tilted axis far closer than its one box does. */
#include "faces.h"
#include "internal/shape.h"

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
 * extent from the radius, 2R sqrt(1 - n_j^2); 1 to CYLRAY_SPLIT_MAX. R is the widest
 * radius (a cone's prepared cylinder's, its wider end's). */
static size_t split_count(const cylray_shape_ *cyl, double R_wide)
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
        double ratio = (double)cyl->h * fabs((double)v[j]) / (R_wide * sqrt(vi * vi + vk * vk));
        want = fmax(want, ceil(ratio));
    }
    return want >= CYLRAY_SPLIT_MAX ? CYLRAY_SPLIT_MAX : (size_t)want;
}

/* A sphere's slices are cut across z, as its surface coordinates are measured (v along
 * z): slice i of k lies between the planes z = c_z + R q_i and c_z + R q_(i+1), q_i as
 * for a cylinder, and spans c_x, c_y -+ R sqrt(1 - q^2) at the q of its range nearest 0
 * (R where the range holds 0). */
static void sphere_slices(const cylray_shape_ *cyl, size_t k, float (*lo)[3], float (*hi)[3])
{
    const double R = cyl->r;
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
    if (!cylray_prepared_ok_(cyl) || cyl->kind == CYLRAY_KIND_INFINITE ||
        cyl->kind == CYLRAY_KIND_ROUND)
        return 0;
    const cylray_shape_ s = cylray_shape_of_(cyl);
    if (k == 0)
        k = s.shape == CYLRAY_SHAPE_SPHERE ? 1 : split_count(&s, cyl->radius);
    if (!lo || !hi)
        return k;
    if (s.shape == CYLRAY_SHAPE_SPHERE) {
        sphere_slices(&s, k, lo, hi);
        return k;
    }
    /* Slice i runs between the discs at t_i = H q_i, q_i = (2i - k) / k rounded once:
     * q_0 = -1 and q_k = 1 exactly and the q_i increase, so neighbouring slices share
     * their disc exactly and together cover the cylinder; H q_i is exact as a
     * double-double. */
    const double H = s.h, R = s.r;
    /* A cone's slice is the hull of its two discs, of radius r(hv q) at t = H q (hv =
     * H |v|, r as internal/leaf.h forms it): evaluated in double to a few units of 2^-53
     * of ra + |kap| 2 hv, which 2^-48 of it covers */
    const int cone = s.shape == CYLRAY_SHAPE_CONE;
    double ra = 0, kap = 0, hv = 0, pad = 0;
    if (cone) {
        const double vv =
            (double)s.v[0] * s.v[0] + (double)s.v[1] * s.v[1] + (double)s.v[2] * s.v[2];
        ra = s.r, kap = s.kap, hv = H * sqrt(vv);
        pad = 0x1p-48 * (ra + 2 * fabs(kap) * hv);
    }
    float plo[3], phi[3];
    disc_box(s.c, s.v, cone ? cylray_cone_radius_(ra, kap, hv, -hv) + pad : R,
             dd_two_prod(H, -1.0), plo, phi);
    for (size_t i = 0; i < k; i++) {
        double q = ((double)(i + 1) * 2.0 - (double)k) / (double)k;
        float nlo[3], nhi[3];
        disc_box(s.c, s.v, cone ? cylray_cone_radius_(ra, kap, hv, hv * q) + pad : R,
                 dd_two_prod(H, q), nlo, nhi);
        for (int j = 0; j < 3; j++) {
            lo[i][j] = fminf(plo[j], nlo[j]);
            hi[i][j] = fmaxf(phi[j], nhi[j]);
            plo[j] = nlo[j];
            phi[j] = nhi[j];
        }
    }
    return k;
}
