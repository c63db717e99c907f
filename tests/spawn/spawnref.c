/* SPDX-License-Identifier: MIT */
/* spawnref.c - exact distances from a cylinder's surfaces (binary128), the two extra
 * hit categories, direction sampling and the self-intersection test. */
#include "spawnref.h"

#include "quad.h"

#include <math.h>
#include <string.h>

static double uni(cylgen_rng *r, double a, double b)
{
    return a + (b - a) * cylgen_uniform(r);
}

/* Log-uniform in [a, b]; exp and log from libm are fine here (a test draw, not a
 * reproducible catalogue shared with other tools). */
static double logu(cylgen_rng *r, double a, double b)
{
    return exp(uni(r, log(a), log(b)));
}

void sref_unit(cylgen_rng *rng, double u[3])
{
    double l;
    do {
        for (int k = 0; k < 3; k++)
            u[k] = uni(rng, -1, 1);
        l = u[0] * u[0] + u[1] * u[1] + u[2] * u[2];
    } while (l > 1 || l < 1e-6);
    l = sqrt(l);
    for (int k = 0; k < 3; k++)
        u[k] /= l;
}

void sref_secondary(cylgen_rng *rng, const double n[3], double size, int shadow, int side,
                    float w[3], float *tmax)
{
    *tmax = INFINITY;
    if (shadow) {
        double u[3], dist = size * exp(cylgen_uniform(rng) * 7);
        sref_unit(rng, u);
        for (int k = 0; k < 3; k++)
            w[k] = (float)(dist * u[k]);
        *tmax = 1.0f;
    } else {
        sref_direction(rng, n, side, w);
    }
}

const char *sref_category_name(int cat)
{
    if (cat == SREF_LONG)
        return "long";
    if (cat == SREF_FARCENTER)
        return "far-center";
    return cylgen_category_name(cat);
}

/* Rays from 2-20 R away at random points of the solid. */
static void aim_at(cylgen_rng *r, const cylray_cylinder *cyl, cylgen_case *c)
{
    double a[3], al = 0, u[3], t[3];
    for (int k = 0; k < 3; k++)
        al += (double)cyl->axis[k] * cyl->axis[k];
    al = sqrt(al);
    for (int k = 0; k < 3; k++)
        a[k] = cyl->axis[k] / al;
    double H = isfinite(cyl->half_height) ? cyl->half_height : 100.0 * cyl->radius;
    double z = uni(r, -H, H) * 1.05, rho = cyl->radius * sqrt(cylgen_uniform(r)) * 1.05;
    sref_unit(r, u);
    double ua = u[0] * a[0] + u[1] * a[1] + u[2] * a[2];
    for (int k = 0; k < 3; k++)
        u[k] -= ua * a[k];
    double ul = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    for (int k = 0; k < 3; k++)
        t[k] = cyl->center[k] + z * a[k] + rho * u[k] / ul;
    double dir[3], dist = cyl->radius * uni(r, 2, 20);
    sref_unit(r, dir);
    for (int k = 0; k < 3; k++) {
        c->o[k] = (float)(t[k] - dist * dir[k]);
        c->d[k] = (float)dir[k];
    }
    c->tmin = 0;
    c->tmax = INFINITY;
    c->cyl = *cyl;
}

void sref_group(int cat, uint64_t seed, cylgen_case out[SREF_GROUP])
{
    if (cat < CYLGEN_COUNT) {
        cylgen_make(cat, seed, SREF_GROUP, out);
        return;
    }
    cylgen_rng rng;
    cylgen_seed(&rng, seed * 0x9e3779b97f4a7c15u + (uint64_t)cat);
    cylray_cylinder cyl;
    memset(&cyl, 0, sizeof cyl);
    double u[3], R, H, C;
    if (cat == SREF_LONG) {
        R = logu(&rng, 1e-2, 1e2);
        H = R * logu(&rng, 1e2, 1e4);
        C = R * uni(&rng, 0, 10);
    } else {
        R = logu(&rng, 1e-4, 1e4);
        H = R * logu(&rng, 0.5, 100);
        C = logu(&rng, 1e3, 1e6);
    }
    sref_unit(&rng, u);
    for (int k = 0; k < 3; k++)
        cyl.center[k] = (float)(C * u[k]);
    sref_unit(&rng, u);
    const int along = (int)(cylgen_next(&rng) % 6); /* 0-2: a coordinate axis */
    for (int k = 0; k < 3; k++)
        cyl.axis[k] = along < 3 ? (float)(k == along) : (float)u[k];
    cyl.radius = (float)R;
    cyl.half_height = (float)H;
    cyl.flags = (unsigned)(cylgen_next(&rng) % 4); /* open, LO, HI, both */
    for (int i = 0; i < SREF_GROUP; i++)
        aim_at(&rng, &cyl, &out[i]);
}

/* ---- exact geometry ---------------------------------------------------------- */

/* Axial coordinate z and distance from the axis rho of x, exact but for binary128's
 * own rounding (the difference x - c of floats is exact there). */
static void qcoords(const cylray_cylinder *cyl, const float x[3], cylq *z, cylq *rho)
{
    cylq q[3], v[3], vv = 0, qv = 0;
    for (int k = 0; k < 3; k++) {
        q[k] = (cylq)x[k] - (cylq)cyl->center[k];
        v[k] = cyl->axis[k];
        vv += v[k] * v[k];
        qv += q[k] * v[k];
    }
    cylq cx = q[1] * v[2] - q[2] * v[1], cy = q[2] * v[0] - q[0] * v[2],
         cz = q[0] * v[1] - q[1] * v[0];
    cylq sv = q_sqrt(vv);
    *z = qv / sv;
    *rho = q_sqrt(cx * cx + cy * cy + cz * cz) / sv;
}

double sref_sigma(const cylray_cylinder *cyl, const float x[3], int part)
{
    cylq z, rho;
    qcoords(cyl, x, &z, &rho);
    switch (part & CYLRAY_PART_MASK) {
    case CYLRAY_CAP_LO:
        return (double)(-z - (cylq)cyl->half_height);
    case CYLRAY_CAP_HI:
        return (double)(z - (cylq)cyl->half_height);
    default:
        return (double)(rho - (cylq)cyl->radius);
    }
}

double sref_dist_part(const cylray_cylinder *cyl, const float x[3], int part)
{
    cylq z, rho, R = cyl->radius, H = cyl->half_height;
    qcoords(cyl, x, &z, &rho);
    cylq a, b; /* distance to the unbounded surface, and beyond its edge */
    switch (part & CYLRAY_PART_MASK) {
    case CYLRAY_CAP_LO:
    case CYLRAY_CAP_HI:
        a = (part & CYLRAY_PART_MASK) == CYLRAY_CAP_HI ? z - H : -z - H;
        b = rho > R ? rho - R : 0;
        break;
    default:
        a = rho - R;
        b = isfinite(cyl->half_height) && q_abs(z) > H ? q_abs(z) - H : 0;
        break;
    }
    return (double)q_sqrt(a * a + b * b);
}

void sref_normal(const cylray_cylinder *cyl, const float x[3], int part, double n[3])
{
    double v[3], vv = 0, qv = 0, q[3];
    for (int k = 0; k < 3; k++) {
        v[k] = cyl->axis[k];
        q[k] = (double)x[k] - cyl->center[k];
        vv += v[k] * v[k];
        qv += q[k] * v[k];
    }
    const int P = part & CYLRAY_PART_MASK;
    double l = 0;
    for (int k = 0; k < 3; k++) {
        n[k] = P == CYLRAY_SIDE ? q[k] - qv / vv * v[k] : P == CYLRAY_CAP_HI ? v[k] : -v[k];
        l += n[k] * n[k];
    }
    l = sqrt(l);
    for (int k = 0; k < 3; k++)
        n[k] /= l;
}

void sref_direction(cylgen_rng *rng, const double n[3], int side, float w[3])
{
    double u[3];
    sref_unit(rng, u);
    double un = u[0] * n[0] + u[1] * n[1] + u[2] * n[2];
    if (cylgen_uniform(rng) < 0.2) {
        /* grazing: the tangential part of u, tilted by eps towards the side */
        double eps = cylgen_uniform(rng) < 0.1 ? 0.0 : logu(rng, 1e-7, 1e-2);
        double t[3], tl = 0;
        for (int k = 0; k < 3; k++) {
            t[k] = u[k] - un * n[k];
            tl += t[k] * t[k];
        }
        tl = sqrt(tl);
        for (int k = 0; k < 3; k++)
            w[k] = (float)(t[k] / tl + side * eps * n[k]);
        return;
    }
    const double flip = (un >= 0) == (side > 0) ? 1.0 : -1.0;
    for (int k = 0; k < 3; k++)
        w[k] = (float)(flip * u[k]);
}

int sref_self_hit(const cylray_cylinder *cyl, const float x0[3], const float w[3],
                  int left_part, int hit_part, float t)
{
    const int P = left_part & CYLRAY_PART_MASK;
    if ((hit_part & CYLRAY_PART_MASK) != P)
        return 0;
    if (P != CYLRAY_SIDE)
        return 1;
    const double sigma = sref_sigma(cyl, x0, CYLRAY_SIDE);
    if (!(sigma < 0))
        return 1;
    /* From inside: the forward root of |x_perp(t)|^2 = R^2, in double (half of it is the
     * threshold, so its relative accuracy hardly matters); C = (rho-R)(rho+R) < 0. */
    double v[3], vv = 0, q[3], qv = 0, wv = 0;
    for (int k = 0; k < 3; k++) {
        v[k] = cyl->axis[k];
        q[k] = (double)x0[k] - cyl->center[k];
        vv += v[k] * v[k];
        qv += q[k] * v[k];
        wv += (double)w[k] * v[k];
    }
    double A = 0, B = 0;
    for (int k = 0; k < 3; k++) {
        double qp = q[k] - qv / vv * v[k], wp = w[k] - wv / vv * v[k];
        A += wp * wp;
        B += qp * wp;
    }
    const double R = cyl->radius, C = sigma * (2 * R + sigma);
    if (!(A > 0))
        return 1; /* along the axis from inside: the side is never met */
    const double sq = sqrt(B * B - A * C);
    const double tc = B > 0 ? -C / (B + sq) : (sq - B) / A;
    return (double)t < 0.5 * tc;
}

void sref_nested(cylgen_rng *rng, cylray_cylinder *out, cylray_cylinder *in, float o[3],
                 float d[3])
{
    double u[3], a[3], dir[3], tgt[3];
    const double R = exp(cylgen_uniform(rng) * 18.4 - 9.2); /* 1e-4 .. 1e4 */
    memset(out, 0, sizeof *out);
    sref_unit(rng, u);
    const double C = R * 4 * cylgen_uniform(rng);
    for (int k = 0; k < 3; k++)
        out->center[k] = (float)(C * u[k]);
    sref_unit(rng, u);
    const int along = (int)(cylgen_next(rng) % 6);
    for (int k = 0; k < 3; k++)
        out->axis[k] = along < 3 ? (float)(k == along) : (float)u[k];
    out->radius = (float)R;
    out->half_height = (float)(R * (0.5 + 3 * cylgen_uniform(rng)));
    out->flags = (unsigned)(cylgen_next(rng) % 4);
    *in = *out;
    in->radius = (float)(out->radius * (1 - 1e-5));
    if (out->flags)
        in->half_height = (float)(out->half_height - 1e-5 * R);
    double al = 0;
    for (int k = 0; k < 3; k++)
        al += (double)out->axis[k] * out->axis[k];
    al = sqrt(al);
    for (int k = 0; k < 3; k++)
        a[k] = out->axis[k] / al;
    const double z = (2 * cylgen_uniform(rng) - 1) * out->half_height;
    sref_unit(rng, u);
    double ua = u[0] * a[0] + u[1] * a[1] + u[2] * a[2], ul = 0;
    for (int k = 0; k < 3; k++) {
        u[k] -= ua * a[k];
        ul += u[k] * u[k];
    }
    ul = sqrt(ul);
    for (int k = 0; k < 3; k++)
        tgt[k] = out->center[k] + z * a[k] + R * u[k] / ul;
    sref_unit(rng, dir);
    if (dir[0] * u[0] + dir[1] * u[1] + dir[2] * u[2] > 0)
        for (int k = 0; k < 3; k++)
            dir[k] = -dir[k];
    for (int k = 0; k < 3; k++) {
        o[k] = (float)(tgt[k] - 5 * R * dir[k]);
        d[k] = (float)dir[k];
    }
}

void sref_transmitted(cylgen_rng *rng, const double n[3], float w[3])
{
    do
        sref_direction(rng, n, -1, w);
    while (!(w[0] * n[0] + w[1] * n[1] + w[2] * n[2] <
             -0.05 * sqrt((double)w[0] * w[0] + (double)w[1] * w[1] + (double)w[2] * w[2])));
}

int sref_inside_solid(const cylray_cylinder *cyl, const float x[3])
{
    if (!(sref_sigma(cyl, x, CYLRAY_SIDE) < 0))
        return 0;
    if (!isfinite(cyl->half_height))
        return 1;
    return sref_sigma(cyl, x, CYLRAY_CAP_LO) < 0 && sref_sigma(cyl, x, CYLRAY_CAP_HI) < 0;
}

int sref_same3(const float a[3], const float b[3])
{
    return memcmp(a, b, 3 * sizeof *a) == 0;
}

int sref_trace1(const cylray_kernels *k, const cylray_prepared *P, const float x[3],
                const float w[3], float *t, int32_t *part)
{
    cylray_ray4 r;
    cylray_hit4 h;
    memset(&r, 0, sizeof r);
    r.ox[0] = x[0], r.oy[0] = x[1], r.oz[0] = x[2];
    r.dx[0] = w[0], r.dy[0] = w[1], r.dz[0] = w[2];
    r.tmax[0] = INFINITY;
    if (!k->intersect4(P, &r, &h, 1u, 0))
        return 0;
    *t = h.t[0], *part = h.part[0];
    return 1;
}
