/* SPDX-License-Identifier: MIT */
/* congen.c - the cone stress-ray generators.
 *
 * The cone is drawn in double, rounded to float, and every ray is then built in double
 * from the float cone (the values the kernel is given), so that "a surface point" or
 * "a rim" is one of the float cone, off only by the rounding of o and d. */
#include "congen.h"

#include "genutil.h"

#include <float.h>
#include <math.h>
#include <string.h>

/* ---- cones --------------------------------------------------------------------- */

static float radius_f(double r)
{
    float f = (float)r;
    return f < 0x1p-60f ? 0x1p-60f : f;
}

static const unsigned modes[4] = {0, CYLRAY_CAPPED_LO, CYLRAY_CAPPED_HI, CYLRAY_CAPPED};

/* A flat to steep cone with one end 2^-40..2^-12 of the other (or a tip), which is
 * where a radius formed from the wide end cancels to that end's rounding and where the
 * cone is far smaller than its distance from the center. The tiny end lies at the
 * origin most of the time, so that rays from close by keep their aim to a part of its
 * radius (see gen_tinyend). */
static void tinyend_cone(cylgen_rng *r, cylray_cone *out)
{
    const double R = gen_uni(r, 0.1, 10), L = R * gen_logu(r, -6, 4),
                 rt = R * gen_logu(r, -40, -12);
    const v3 u = gen_dir(r);
    v3 at = mk(0, 0, 0);
    if (gen_chance(r, 0.3)) {
        const double z = gen_uni(r, -10, 10), y = gen_uni(r, -10, 10), x = gen_uni(r, -10, 10);
        at = mk(x, y, z);
    }
    const int lo = gen_chance(r, 0.5);
    float *tiny = lo ? out->p0 : out->p1, *wide = lo ? out->p1 : out->p0;
    to_f(tiny, at);
    to_f(wide, axpy(mk(tiny[0], tiny[1], tiny[2]), L, u));
    *(lo ? &out->r0 : &out->r1) = gen_chance(r, 0.25) ? 0.0f : radius_f(rt); /* or a tip */
    *(lo ? &out->r1 : &out->r0) = radius_f(R);
    out->flags = modes[cylgen_next(r) % 4];
}

void congen_cone(int cat, cylgen_rng *r, cylray_cone *out)
{
    if (cat == CONGEN_TINYEND) {
        tinyend_cone(r, out);
        return;
    }
    double R = gen_uni(r, 0.1, 10), span = 10, L = R * gen_uni(r, 0.3, 6);
    switch (cat) {
    case CONGEN_FLAT:
        L = R * gen_logu(r, -10, -3);
        break;
    case CONGEN_LONG:
        L = R * gen_uni(r, 0.5e4, 2e4);
        span = L;
        break;
    case CONGEN_TINY:
        R = gen_uni(r, 1e-4, 1e-3);
        /* Float ends 1e4 out are 2^-10 apart at best: at least ten of those long. */
        L = R * gen_uni(r, 0.3, 6) + 0.01;
        span = 1e4;
        break;
    case CONGEN_HUGE:
        R = gen_uni(r, 1e4, 1e6);
        L = R * gen_uni(r, 0.3, 6);
        span = gen_uni(r, 1e5, 1e6);
        break;
    case CONGEN_SCALED: {
        int e = 21 + (int)(cylgen_next(r) % 30);
        double k = ldexp(1.0, gen_chance(r, 0.5) ? e : -e);
        R *= k;
        L *= k;
        span *= k;
        break;
    }
    default:
        break;
    }
    v3 c, u = gen_dir(r);
    for (int k = 0; k < 3; k++) {
        c.x[k] = gen_uni(r, -span, span);
        if (cat == CONGEN_TINY) {
            const double sign = gen_chance(r, 0.5) ? -1 : 1;
            c.x[k] = sign * gen_uni(r, 0.5 * span, span);
        }
    }
    to_f(out->p0, axpy(c, -L / 2, u));
    to_f(out->p1, axpy(c, L / 2, u));
    if (cat == CONGEN_TINY) {
        /* A center that rounds is a shift of the whole cone by up to half an ulp of
         * 1e4, more than the cone: keep (p0 + p1) / 2 a float so the band stays tight. */
        for (int k = 0; k < 3; k++)
            for (int i = 0; i < 4; i++) {
                double m = ((double)out->p0[k] + (double)out->p1[k]) / 2;
                if ((double)(float)m == m)
                    break;
                out->p1[k] = nextafterf(out->p1[k], out->p0[k]);
            }
    }
    double r0 = R * gen_uni(r, 0.05, 1), r1 = R * gen_uni(r, 0.05, 1);
    if (cat == CONGEN_APEX || gen_chance(r, 0.1)) {
        if (gen_chance(r, 0.5))
            r0 = 0;
        else
            r1 = 0;
    } else if (gen_chance(r, 0.1)) { /* an end tiny beside the other: a near tip, no apex */
        if (gen_chance(r, 0.5))
            r0 = R * gen_logu(r, -34, -8);
        else
            r1 = R * gen_logu(r, -34, -8);
    }
    out->r0 = r0 == 0 ? 0 : radius_f(r0);
    out->r1 = r1 == 0 ? 0 : radius_f(r1);
    if (cat == CONGEN_NEARCYL) {
        out->r1 = out->r0 = radius_f(R);
        int steps = 1 + (int)(cylgen_next(r) % 6);
        for (int i = 0; i < steps; i++)
            out->r1 = nextafterf(out->r1, gen_chance(r, 0.5) ? INFINITY : 0);
    }
    out->flags = modes[cylgen_next(r) % 4];
}

/* The float cone in double. */
typedef struct {
    v3 p0, u;
    double L, r0, r1, R;
} cgeo;

static cgeo geo_of(const cylray_cone *c)
{
    cgeo g;
    v3 a = mk((double)c->p1[0] - c->p0[0], (double)c->p1[1] - c->p0[1],
              (double)c->p1[2] - c->p0[2]);
    g.p0 = mk(c->p0[0], c->p0[1], c->p0[2]);
    g.L = sqrt(dot(a, a));
    g.u = unit(a);
    g.r0 = c->r0;
    g.r1 = c->r1;
    g.R = fmax(fmax(g.r0, g.r1), g.L / 2);
    return g;
}

static double rad_at(const cgeo *g, double z)
{
    return g->r0 + (g->r1 - g->r0) * (z / g->L);
}

/* A point of the side at height z, direction e (perpendicular to u) from the axis. */
static v3 side_point(const cgeo *g, double z, v3 e)
{
    return axpy(axpy(g->p0, z, g->u), rad_at(g, z), e);
}

/* The outward normal of the side at direction e. */
static v3 side_normal(const cgeo *g, v3 e)
{
    double k = (g->r1 - g->r0) / g->L;
    return unit(axpy(e, -k, g->u));
}

static v3 point_in(cylgen_rng *r, const cgeo *g, double slack)
{
    double z = gen_uni(r, 0, g->L);
    v3 e = gen_perp(r, g->u);
    double s = sqrt(cylgen_uniform(r)) * slack;
    return axpy(axpy(g->p0, z, g->u), s * rad_at(g, z), e);
}

static void aim(cylgen_rng *r, v3 target, v3 d, double dist, congen_case *c)
{
    to_f(c->o, axpy(target, -dist, d));
    to_f(c->d, d);
    gen_interval(r, dist, &c->tmin, &c->tmax);
}

static void towards(cylgen_rng *r, const cgeo *g, double dist, double slack, congen_case *c)
{
    const v3 d = gen_dir(r), p = point_in(r, g, slack);
    aim(r, p, d, dist, c);
}

static void gen_grazing(cylgen_rng *r, const cgeo *g, congen_case *c)
{
    v3 e = gen_perp(r, g->u), n = side_normal(g, e);
    v3 p = side_point(g, gen_uni(r, 0, g->L), e);
    v3 d = gen_perp(r, n);
    double eps = gen_logu(r, -23, -7);
    eps *= gen_chance(r, 0.5) ? 1 : -1;
    aim(r, axpy(p, g->R * eps, n), d, g->R * gen_uni(r, 2, 10), c);
}

static void gen_surface(cylgen_rng *r, const cgeo *g, congen_case *c)
{
    v3 e = gen_perp(r, g->u), p, n;
    unsigned caps = c->cone.flags;
    int where = (int)(cylgen_next(r) % 3);
    if (where == 1 && (caps & CYLRAY_CAPPED_LO) && g->r0 > 0) {
        p = axpy(g->p0, g->r0 * sqrt(cylgen_uniform(r)), e);
        n = neg(g->u);
    } else if (where == 2 && (caps & CYLRAY_CAPPED_HI) && g->r1 > 0) {
        p = axpy(axpy(g->p0, g->L, g->u), g->r1 * sqrt(cylgen_uniform(r)), e);
        n = g->u;
    } else {
        p = side_point(g, gen_uni(r, 0, g->L), e);
        n = side_normal(g, e);
    }
    v3 d = gen_dir(r);
    if ((dot(d, n) > 0) != gen_chance(r, 0.5))
        d = neg(d);
    to_f(c->o, p);
    to_f(c->d, d);
    c->tmin = 0.0f;
    c->tmax = INFINITY;
}

static void gen_rim(cylgen_rng *r, const cgeo *g, congen_case *c)
{
    v3 e = gen_perp(r, g->u);
    int hi = gen_chance(r, 0.5);
    if ((hi ? g->r1 : g->r0) == 0)
        hi = !hi;
    v3 p = side_point(g, hi ? g->L : 0, e);
    /* off the rim by a part of the cone's size or of that end's own radius (a tiny end's
     * rim is far smaller than the cone) */
    const int own = gen_chance(r, 0.5);
    const double size = own ? (hi ? g->r1 : g->r0) : g->R;
    if (gen_chance(r, 0.5)) {
        const v3 dir = gen_dir(r);
        double off = size * gen_logu(r, -24, own ? 7 : -10);
        off *= gen_chance(r, 0.5) ? 1 : -1;
        p = axpy(p, off, dir);
    }
    const double dist = g->R * gen_uni(r, 1.5, 10);
    aim(r, p, gen_dir(r), dist, c);
}

static void gen_apex(cylgen_rng *r, const cgeo *g, congen_case *c)
{
    v3 apex = axpy(g->p0, g->r0 == 0 ? 0 : g->L, g->u);
    if (g->r0 != 0 && g->r1 != 0) {
        towards(r, g, g->R * gen_uni(r, 1.5, 10), 1.2, c);
        return;
    }
    double off = gen_chance(r, 0.3) ? 0 : g->R * gen_logu(r, -24, -4);
    const double dist = g->R * gen_uni(r, 1.5, 10);
    const v3 d = gen_dir(r), o = axpy(apex, off, gen_dir(r));
    aim(r, o, d, dist, c);
}

static void gen_axial(cylgen_rng *r, const cgeo *g, congen_case *c)
{
    if (gen_chance(r, 0.5)) {
        /* Along the axis, from the axis or off it within the larger radius. */
        v3 d = gen_chance(r, 0.5) ? g->u : neg(g->u);
        double off = gen_chance(r, 0.3) ? 0 : gen_uni(r, 0, 1.2) * fmax(g->r0, g->r1);
        v3 o = axpy(axpy(g->p0, g->L / 2, g->u), off, gen_perp(r, g->u));
        aim(r, o, d, g->L * gen_uni(r, 1, 5), c);
        return;
    }
    /* Along a generator line, on it or slightly out or in. */
    v3 e = gen_perp(r, g->u);
    v3 a = side_point(g, 0, e), b = side_point(g, g->L, e);
    v3 d = unit(axpy(b, -1, a));
    if (gen_chance(r, 0.5))
        d = neg(d);
    double off = 0;
    if (!gen_chance(r, 0.3)) {
        off = g->R * gen_logu(r, -24, -6);
        off *= gen_chance(r, 0.5) ? 1 : -1;
    }
    v3 mid = axpy(side_point(g, g->L / 2, e), off, side_normal(g, e));
    aim(r, mid, d, g->R * gen_uni(r, 2, 10), c);
}

/* About a tiny end (tinyend_cone): at radial offsets from a quarter of its radius (a
 * tip's: 2^-30 of the other) out to past the wide radius's ulp, in its plane, a little off it or by the side next to
 * it; across the disc's plane, parallel to it or nearly along the axis; most from close
 * by, where the float origin keeps the aim. */
static void gen_tinyend(cylgen_rng *r, const cgeo *g, congen_case *c)
{
    const int lo = g->r0 <= g->r1;
    const double rt = lo ? g->r0 : g->r1, rw = lo ? g->r1 : g->r0;
    const v3 end = lo ? g->p0 : axpy(g->p0, g->L, g->u), in = lo ? g->u : neg(g->u);
    const double rq = rt > 0 ? rt : rw * 0x1p-30;
    const double rho = rq * exp2(gen_uni(r, -2, fmax(log2(rw / rq) - 18, 3)));
    const v3 e = gen_perp(r, g->u);
    v3 p = axpy(end, rho, e);
    const uint64_t where = cylgen_next(r) % 3;
    if (where == 1) {
        double off = rho * gen_logu(r, -8, 3);
        off *= gen_chance(r, 0.5) ? 1 : -1;
        p = axpy(p, off, in);
    } else if (where == 2) {
        const double z = fmin(rho * gen_logu(r, -6, 4), g->L);
        const double rz = rt + (rw - rt) * (z / g->L);
        double off = gen_logu(r, -24, -2);
        off *= gen_chance(r, 0.5) ? 1 : -1;
        p = axpy(axpy(end, z, in), rz * (1 + off), e);
    }
    const uint64_t how = cylgen_next(r) % 3;
    v3 d = how == 0 ? gen_dir(r) : gen_perp(r, g->u);
    if (how == 2) {
        const double tilt = gen_uni(r, -0.3, 0.3);
        d = unit(axpy(gen_chance(r, 0.5) ? in : neg(in), tilt, d));
    }
    const double dist =
        gen_chance(r, 0.8) ? fmax(rho, rq) * gen_uni(r, 2, 64) : g->R * gen_uni(r, 1.5, 10);
    aim(r, p, d, dist, c);
}

static void rim_hook(cylgen_rng *r, const void *g, void *c)
{
    gen_rim(r, g, c);
}

GEN_RAY_ROW_DEFINE(cone_rays, towards, gen_grazing, gen_surface, point_in, rim_hook);

/* The categories the sphere shares (gen_ray_kind); the others, ORDINARY's 0 here, are
 * the cone's own. */
static const unsigned char shared_kind[CONGEN_COUNT] = {
    [CONGEN_FAR] = GEN_RAY_FAR,         [CONGEN_GRAZING] = GEN_RAY_GRAZING,
    [CONGEN_SURFACE] = GEN_RAY_SURFACE, [CONGEN_INSIDE] = GEN_RAY_INSIDE,
    [CONGEN_TINY] = GEN_RAY_TINY,       [CONGEN_HUGE] = GEN_RAY_HUGE,
    [CONGEN_UNNORM] = GEN_RAY_UNNORM,   [CONGEN_CAMERA] = GEN_RAY_CAMERA,
    [CONGEN_BAD] = GEN_RAY_BAD,         [CONGEN_SCALED] = GEN_RAY_SCALED};

void congen_ray(int cat, cylgen_rng *r, cylgen_rng *cam, size_t index, const cylray_cone *cone,
                congen_case *c)
{
    const cgeo gg = geo_of(cone), *g = &gg;
    memset(c, 0, sizeof *c);
    c->cone = *cone;
    switch (cat) {
    case CONGEN_RIM:
        gen_rim(r, g, c);
        break;
    case CONGEN_APEX:
        gen_apex(r, g, c);
        break;
    case CONGEN_AXIAL:
        gen_axial(r, g, c);
        break;
    case CONGEN_NEARCYL:
    case CONGEN_FLAT:
    case CONGEN_LONG: {
        uint64_t u = cylgen_next(r) % 4;
        if (u == 0)
            gen_grazing(r, g, c);
        else if (u == 1)
            gen_rim(r, g, c);
        else
            towards(r, g, g->R * gen_uni(r, 1.5, 10), 1.2, c);
        break;
    }
    case CONGEN_TINYEND:
        gen_tinyend(r, g, c);
        break;
    default: {
        const v3 mid = axpy(g->p0, g->L / 2, g->u); /* where the camera looks */
        const gen_ray_at at = {&cone_rays, g, g->R, mid, 0.8, 1.5, GEN_RAY_CASE(c)};
        gen_shared_ray(cat >= 0 && cat < CONGEN_COUNT ? shared_kind[cat] : GEN_RAY_ORDINARY, r,
                       cam, index, &at);
        break;
    }
    }
}

static const char *const names[CONGEN_COUNT] = {
    "cone-ordinary", "cone-far",    "cone-grazing", "cone-surface", "cone-inside",
    "cone-rim",      "cone-apex",   "cone-nearcyl", "cone-flat",    "cone-long",
    "cone-tiny",     "cone-huge",   "cone-unnorm",  "cone-axial",   "cone-camera",
    "cone-bad",      "cone-scaled", "cone-tinyend"};

static const char *const descriptions[CONGEN_COUNT] = {
    "cone: from 1.5-10 R at a point within 1.2 r(z)",
    "cone: origin 1e3-1e6 R away",
    "cone: tangent to the side, 1e-7-1e-2 R off",
    "cone: origin a float-rounded point of the side or a present disc, tmin 0",
    "cone: origin inside",
    "cone: aimed at a rim, on it or 2^-24..2^-10 R off",
    "cone: tip cones, aimed at the apex or 2^-24..2^-4 R off",
    "cone: r0 and r1 1-6 ulps apart",
    "cone: length 2^-10..2^-3 of the radius",
    "cone: length 1e4 radii",
    "cone: radii 1e-4..1e-3, center around 1e4 (a float)",
    "cone: radii 1e4..1e6, center around 1e5..1e6",
    "cone: |d| 2^-30..2^30",
    "cone: along the axis and along generator lines",
    "cone: 4 x 4 pixel blocks of a pinhole camera",
    "cone: NaN, Inf, zero-direction and empty-interval lanes among good ones",
    "cone: scenes scaled by 2^+-(21..50), |d| 2^-20..2^20",
    "cone: one end 2^-40..2^-12 of the other or a tip, rays at and about it from close by"};

GEN_SHAPE_DEFINE(congen, cylray_cone, names, descriptions, CONGEN_COUNT, 0x636f6e6573ull,
                 congen_cone, congen_ray)
