/* SPDX-License-Identifier: MIT */
/* toolkit/surface.c - surface coordinates (u, v) and their derivatives at a point: the
 * entry points, spheres and cones (the cylinder's path, compiled twice, is
 * surface_cylinder.c's). */
#include "surface.h"
#include "internal/shape.h"

/* A sphere, as pbrt-v4's full sphere about the z axis through its center, at the point
 * where the ray from the center through p meets it: with r = p - c, h = |(r_x, r_y)|
 * and L = |r|, u = phi / 2pi with phi = atan2(r_y, r_x) in [0, 2pi) (0 on the z axis),
 * v = atan2(h, -r_z) / pi (pi - theta, theta measured from +z: 0 at the -z pole, 1 at
 * +z, free of the cancellation of 1 - theta/pi near 0), dpdu = 2pi (-y, x, 0) and dpdv =
 * pi (-z cos(phi), -z sin(phi), R sin(theta)) at that point. Each is a few double
 * roundings (and libm's atan2) from its exact value, relative to itself: u and v
 * round to within a float ulp, the derivatives to a few float ulps. The center itself
 * is taken for the -z pole. */
#define PI_ 3.14159265358979323846
static void sphere_surface(const float c[3], double R, const float p[3], int32_t part,
                           float uv[2], float dpdu[3], float dpdv[3])
{
    if ((part & CYLRAY_PART_MASK) != CYLRAY_SIDE)
        return;
    double r[3];
    for (int k = 0; k < 3; k++)
        r[k] = (double)p[k] - (double)c[k];
    /* the coordinates' differences are 0 or at least 2^-149: no square underflows */
    const double h = sqrt(r[0] * r[0] + r[1] * r[1]);
    if (h == 0 && r[2] == 0)
        r[2] = -1.0;
    const double co = h > 0 ? r[0] / h : 1.0, si = h > 0 ? r[1] / h : 0.0;
    if (uv) {
        double t = h > 0 ? atan2(r[1], r[0]) / TWO_PI : 0.0;
        if (t < 0)
            t += 1.0;
        const float f = (float)t + 0.0f; /* + 0: no -0 */
        uv[0] = f < 1.0f ? f : BELOW_ONE;
        uv[1] = (float)(atan2(h, -r[2]) / PI_) + 0.0f;
    }
    if (!dpdu && !dpdv)
        return;
    const double s = R / sqrt(h * h + r[2] * r[2]); /* R / L */
    if (dpdu) {
        dpdu[0] = (float)(-TWO_PI * s * r[1]) + 0.0f;
        dpdu[1] = (float)(TWO_PI * s * r[0]) + 0.0f;
        dpdu[2] = 0.0f;
    }
    if (dpdv) {
        dpdv[0] = (float)(-PI_ * s * r[2] * co) + 0.0f;
        dpdv[1] = (float)(-PI_ * s * r[2] * si) + 0.0f;
        dpdv[2] = (float)(PI_ * s * h);
    }
}

/* The FMA instance where the dispatch says it goes with the path chosen. */
static void surface_at(const surf_cyl *s, const float p[3], int32_t part, float uv[2],
                       float dpdu[3], float dpdv[3])
{
#ifdef CYLRAY_HAVE_SURFACE_FMA
    if (cylray_surface_fma_()) {
        cylray_surface_at_fma_(s, p, part, uv, dpdu, dpdv);
        return;
    }
#endif
    cylray_surface_at_plain_(s, p, part, uv, dpdu, dpdv);
}

/* A cone (radius ra + kap (z |v| - za) at axial coordinate z, internal/leaf.h): its u and v are
 * the cylinder's, and so are its derivatives with R the radius where they are taken (a
 * disc's own; on the side the radius at p's axial coordinate, for dpdv), except the
 * side's dpdu, which follows the slope: 2H n + (r1 - r0) e_r, e_r = cos(phi) b1 +
 * sin(phi) b2 the radial direction at p (b1 on the axis, where phi = 0). All in double:
 * e_r is good to 2^-50 |r| / rho, within 2^-20 where the cylinder's derivatives are. */
static void cone_surface(surf_cyl *s, double ra, double kap, const float p[3], int32_t part,
                         float uv[2], float dpdu[3], float dpdv[3])
{
    double n[3], r[3], vv = 0, z = 0;
    for (int k = 0; k < 3; k++)
        vv += (double)s->v[k] * s->v[k];
    const double sv = sqrt(vv), H = s->H, hv = H * sv;
    for (int k = 0; k < 3; k++) {
        n[k] = s->v[k] / sv;
        r[k] = (double)p[k] - s->c[k];
        z += r[k] * n[k];
    }
    const double rlo = cylray_cone_radius_(ra, kap, hv, -hv),
                 rhi = cylray_cone_radius_(ra, kap, hv, hv);
    s->R = part == CYLRAY_CAP_LO ? rlo
           : part == CYLRAY_CAP_HI
               ? rhi
               : cylray_cone_radius_(ra, kap, hv, sv * fmin(H, fmax(-H, z)));
    surface_at(s, p, part, uv, dpdu, dpdv);
    if (!dpdu || part != CYLRAY_SIDE)
        return;
    double e[3], l = 0;
    for (int k = 0; k < 3; k++) {
        e[k] = r[k] - z * n[k];
        l += e[k] * e[k];
    }
    l = sqrt(l);
    if (!(l > 0)) { /* on the axis: b1 of the frame (Duff et al.) */
        const double sg = n[2] >= 0 ? 1.0 : -1.0, a = -1.0 / (sg + n[2]);
        e[0] = 1 + sg * n[0] * n[0] * a, e[1] = sg * n[0] * n[1] * a, e[2] = -sg * n[0];
        l = 1;
    }
    for (int k = 0; k < 3; k++)
        dpdu[k] = (float)(2 * H * n[k] + (rhi - rlo) * e[k] / l);
}

static void shape_surface(const cylray_shape_ *sh, const float p[3], int32_t part, float uv[2],
                          float dpdu[3], float dpdv[3])
{
    if (sh->shape == CYLRAY_SHAPE_SPHERE) {
        sphere_surface(sh->c, sh->r, p, part, uv, dpdu, dpdv);
        return;
    }
    surf_cyl s;
    for (int k = 0; k < 3; k++) {
        s.c[k] = sh->c[k];
        s.v[k] = sh->v[k];
    }
    s.R = sh->r;
    s.H = sh->h;
    /* (a leaf's cylinder given as a cone, of slope 0, is a cylinder here) */
    if (sh->shape == CYLRAY_SHAPE_CONE && sh->kap != 0)
        cone_surface(&s, sh->r, sh->kap, p, part, uv, dpdu, dpdv);
    else
        surface_at(&s, p, part, uv, dpdu, dpdv);
}

void cylray_surface(const cylray_prepared *cyl, const float p[3], int32_t part, float uv[2],
                    float dpdu[3], float dpdv[3])
{
    if (!cylray_prepared_ok_(cyl) || !p || cyl->kind == CYLRAY_KIND_ROUND)
        return;
    const cylray_shape_ s = cylray_shape_of_(cyl);
    shape_surface(&s, p, part, uv, dpdu, dpdv);
}

static void leaf_surface(const float *geom, const uint32_t *meta, unsigned m,
                         const cylray_hit1 *hit, const float p[3], float uv[2], float dpdu[3],
                         float dpdv[3])
{
    if (!hit || !p || hit->lane >= m || !((meta[CYLRAY_LM_USED] >> hit->lane) & 1u))
        return;
    const cylray_shape_ s = cylray_leaf_shape_(geom, meta, m, hit->lane);
    shape_surface(&s, p, hit->part, uv, dpdu, dpdv);
}

#define LEAF_SURFACE_(m)                                                                       \
    void cylray_leaf_surface##m(const cylray_leaf##m *leaf, const cylray_hit1 *hit,            \
                                const float p[3], float uv[2], float dpdu[3], float dpdv[3])   \
    {                                                                                          \
        if (leaf)                                                                              \
            leaf_surface(&leaf->geom_[0][0], leaf->meta_, m, hit, p, uv, dpdu, dpdv);          \
    }
LEAF_SURFACE_(4)
LEAF_SURFACE_(8)
LEAF_SURFACE_(16)
