/* SPDX-License-Identifier: MIT */
/* rcgen.c - the round-cone stress-ray generators.
 *
 * The round cone is drawn in double and rounded to float, and every ray is then built in
 * double from the float shape (the values the kernel is given), so that "a surface
 * point" or "a seam" is one of the float shape, off only by the rounding of o and d.
 * The geometry (rcref.c's derivation): with a = p1 - p0, L = |a|, u = a / L,
 * k = (r1 - r0) / L and n_rho = sqrt(1 - k^2), sphere i's seam is the circle of radius
 * r_i n_rho about p_i - r_i k u, the side's outward normal n_rho e - k u (e across the
 * axis), the generator line's direction k e + n_rho u. */
#include "rcgen.h"

#include "genutil.h"

#include <float.h>
#include <math.h>
#include <string.h>

/* ---- round cones --------------------------------------------------------------- */

static float radius_f(double r)
{
    float f = (float)r;
    return f < 0x1p-60f ? 0x1p-60f : f;
}

static const unsigned modes[4] = {0, CYLRAY_CAPPED_LO, CYLRAY_CAPPED_HI, CYLRAY_CAPPED};

static void make_rc(int cat, cylgen_rng *r, rcref_round_cone *out)
{
    double R = gen_uni(r, 0.1, 10), span = 10;
    double r0 = R * gen_uni(r, 0.3, 1);
    double r1 = R * gen_uni(r, 0.3, 1);
    double L = R * gen_uni(r, 0.3, 6);
    switch (cat) {
    case RCGEN_CAPSULE: {
        /* equal (5 in 8), or 1..3 ulps apart */
        const float f = (float)r0;
        float h = f;
        const int steps = (int)(cylgen_next(r) % 8);
        for (int j = 4; j < steps; j++)
            h = nextafterf(h, INFINITY);
        r0 = f;
        r1 = h;
        break;
    }
    case RCGEN_TAPER:
        r1 = r0 * gen_logu(r, -10, 10);
        L = fabs(r1 - r0) * (1 + gen_uni(r, 0.05, 3)) + 0.01 * R;
        break;
    case RCGEN_NESTED: {
        const uint64_t kind = cylgen_next(r) % 3;
        const double dr = fabs(r1 - r0) + 0.1 * R;
        r1 = r0 + (gen_chance(r, 0.5) ? dr : -fmin(dr, 0.9 * r0));
        if (kind == 0)
            L = fabs(r1 - r0) * gen_uni(r, 0, 0.95);
        else if (kind == 1)
            L = 0;
        else
            L = fabs(r1 - r0) * (1 + gen_logu(r, -20, -8));
        break;
    }
    case RCGEN_POINT:
        rcgen_point_end(gen_chance(r, 0.5), &r0, &r1, &L);
        break;
    case RCGEN_LONG:
        r1 = r0 * gen_uni(r, 0.8, 1.25);
        L = r0 * gen_uni(r, 0.5e4, 2e4);
        span = L;
        break;
    case RCGEN_SCALED: {
        const int e = 21 + (int)(cylgen_next(r) % 30);
        const double k = ldexp(1.0, gen_chance(r, 0.5) ? e : -e);
        r0 *= k;
        r1 *= k;
        L *= k;
        span *= k;
        break;
    }
    }
    const double x = gen_uni(r, -span, span);
    const double y = gen_uni(r, -span, span);
    const double z = gen_uni(r, -span, span);
    const v3 p0 = mk(x, y, z), u = gen_dir(r);
    to_f(out->p0, p0);
    to_f(out->p1, axpy(from_f(out->p0), L, u));
    out->r0 = r0 > 0 ? radius_f(r0) : 0.0f;
    out->r1 = r1 > 0 ? radius_f(r1) : 0.0f;
    if (out->r0 == 0 && out->r1 == 0)
        out->r1 = radius_f(R);
    out->flags = gen_chance(r, 0.5) ? CYLRAY_CAPPED : modes[cylgen_next(r) % 4];
}

/* ---- the float shape's geometry ------------------------------------------------- */

typedef struct {
    v3 p0, p1, u;
    double L, r0, r1, k, nr, size, rmax;
    int nested;
} rgeo;

static rgeo geo_of(const rcref_round_cone *s)
{
    rgeo g;
    g.p0 = from_f(s->p0);
    g.p1 = from_f(s->p1);
    const v3 a = axpy(g.p1, -1, g.p0);
    g.L = sqrt(dot(a, a));
    g.r0 = s->r0;
    g.r1 = s->r1;
    g.rmax = fmax(g.r0, g.r1);
    g.size = g.L / 2 + g.rmax;
    const double dr = g.r1 - g.r0;
    g.nested = !(g.L > fabs(dr) * (1 + 1e-9));
    g.u = g.L > 0 ? scl(a, 1 / g.L) : mk(0, 0, 1);
    g.k = g.nested ? 0 : dr / g.L;
    g.nr = g.nested ? 0 : sqrt((g.L - fabs(dr)) * (g.L + fabs(dr))) / g.L;
    return g;
}

/* A point of the surface and its outward normal: of the side (at a fraction f between
 * the seams, e across the axis), or of sphere `end` beyond its seam; nested: of the
 * larger sphere. rloc: the size of the surface there (for offsets). */
typedef struct {
    v3 x, n;
    double rloc;
} spot;

static spot sphere_spot(cylgen_rng *r, const rgeo *g, int end)
{
    const v3 c = end ? g->p1 : g->p0;
    const double rad = end ? g->r1 : g->r0;
    spot s;
    s.n = end ? g->u : neg(g->u); /* the pole, on the cap for any k */
    for (int t = 0; t < 8; t++) {
        const v3 v = gen_dir(r);
        const double ax = dot(v, g->u);
        if (g->nested || (end ? ax >= -g->k : ax <= -g->k)) {
            s.n = v;
            break;
        }
    }
    s.x = axpy(c, rad, s.n);
    s.rloc = rad;
    return s;
}

static spot side_spot(const rgeo *g, v3 e, double f)
{
    const v3 s0 = axpy(axpy(g->p0, -g->r0 * g->k, g->u), g->r0 * g->nr, e);
    const v3 s1 = axpy(axpy(g->p1, -g->r1 * g->k, g->u), g->r1 * g->nr, e);
    spot s;
    s.x = add(scl(s0, 1 - f), scl(s1, f));
    s.n = axpy(scl(e, g->nr), -g->k, g->u);
    s.rloc = fmax(g->rmax * g->nr, 1e-30);
    return s;
}

static spot any_spot(cylgen_rng *r, const rgeo *g)
{
    if (g->nested)
        return sphere_spot(r, g, g->r1 > g->r0);
    const double pick = cylgen_uniform(r);
    if (pick < 0.5) {
        const v3 e = gen_perp(r, g->u);
        return side_spot(g, e, gen_uni(r, 0, 1));
    }
    const int end = pick < 0.75 ? 0 : 1;
    if ((end ? g->r1 : g->r0) > 0)
        return sphere_spot(r, g, end);
    const v3 e = gen_perp(r, g->u);
    return side_spot(g, e, gen_uni(r, 0, 1));
}

/* ---- rays ------------------------------------------------------------------------ */

static void aim(cylgen_rng *r, v3 target, v3 d, double dist, rcgen_case *c)
{
    to_f(c->o, axpy(target, -dist, d));
    to_f(c->d, d);
    gen_interval(r, dist, &c->tmin, &c->tmax);
}

/* At a point within slack of the larger radius of a point of the segment (a little
 * beyond its ends), from dist away. */
static void towards(cylgen_rng *r, const rgeo *g, double dist, double slack, rcgen_case *c)
{
    const double s = gen_uni(r, -0.1, 1.1), off = gen_uni(r, 0, slack) * g->rmax;
    const v3 v = gen_dir(r), d = gen_dir(r);
    const v3 target = axpy(axpy(g->p0, s * g->L, g->u), off, v);
    aim(r, target, d, dist, c);
}

static void gen_grazing(cylgen_rng *r, const rgeo *g, rcgen_case *c)
{
    const spot s = any_spot(r, g);
    const v3 d = gen_perp(r, s.n);
    double eps = gen_logu(r, -23, -7);
    eps *= gen_chance(r, 0.5) ? 1 : -1;
    aim(r, axpy(s.x, eps * s.rloc, s.n), d, g->size * gen_uni(r, 2, 10), c);
}

/* A secondary ray: a point of the surface rounded to float, leaving or going in. */
static void gen_surface(cylgen_rng *r, const rgeo *g, rcgen_case *c)
{
    const spot s = any_spot(r, g);
    v3 d = gen_dir(r);
    const int outward = gen_chance(r, 0.5);
    if ((dot(d, s.n) > 0) != outward)
        d = neg(d);
    to_f(c->o, s.x);
    to_f(c->d, d);
    c->tmin = 0.0f;
    c->tmax = INFINITY;
}

/* A point of the sphere c(s), r(s) of the family grown by slack (of its radius): inside
 * the hull where slack < 1. */
static v3 point_in(cylgen_rng *r, const rgeo *g, double slack)
{
    const double s = gen_uni(r, 0, 1), f = gen_uni(r, 0, slack);
    const v3 v = gen_dir(r);
    const double rs = g->r0 + s * (g->r1 - g->r0);
    return axpy(axpy(g->p0, s * g->L, g->u), f * rs, v);
}

static void gen_inside(cylgen_rng *r, const rgeo *g, rcgen_case *c)
{
    to_f(c->o, point_in(r, g, 0.95));
    to_f(c->d, gen_dir(r));
    gen_interval(r, g->size, &c->tmin, &c->tmax);
}

/* Through a point of a seam, or 2^-24..2^-10 of the hull's size off it along the
 * generator line, going in across it. */
static void gen_seam(cylgen_rng *r, const rgeo *g, rcgen_case *c)
{
    int end = gen_chance(r, 0.5);
    if ((end ? g->r1 : g->r0) == 0)
        end = !end;
    const v3 e = gen_perp(r, g->u);
    if (g->nested) {
        towards(r, g, g->size * gen_uni(r, 2, 10), 1.2, c);
        return;
    }
    spot s = side_spot(g, e, end);
    const v3 gen = axpy(scl(e, g->k), g->nr, g->u), tang = cross(g->u, e);
    if (gen_chance(r, 0.5)) {
        double eps = gen_logu(r, -24, -10);
        eps *= gen_chance(r, 0.5) ? 1 : -1;
        s.x = axpy(s.x, eps * g->size, gen);
    }
    const double tw = gen_uni(r, -0.7, 0.7), tz = gen_uni(r, -0.7, 0.7);
    const v3 d = unit(axpy(axpy(neg(s.n), tw, tang), tz, gen));
    aim(r, s.x, d, g->size * gen_uni(r, 2, 10), c);
}

/* At a point end's apex, exactly or 2^-30..2^-5 of the size off, from directions that
 * go on into the hull (within the cone the generator lines leave the apex in, tan of
 * its half angle |k| / n_rho) or just miss it (up to 1.3 times that). */
static void gen_point(cylgen_rng *r, const rgeo *g, rcgen_case *c)
{
    const int at0 = g->r0 == 0;
    v3 apex = at0 ? g->p0 : g->p1;
    if (gen_chance(r, 0.5)) {
        const double off = g->size * gen_logu(r, -30, -5);
        apex = axpy(apex, off, gen_dir(r)); /* one draw a statement: the same everywhere */
    }
    const v3 e = gen_perp(r, g->u), in = at0 ? g->u : neg(g->u);
    const double spread = g->nested ? 1 : gen_uni(r, 0, 1.3) * fabs(g->k) / g->nr;
    const v3 d = unit(axpy(in, spread, e));
    aim(r, apex, d, g->size * gen_uni(r, 2, 10), c);
}

/* Along the axis (on it, or 2^-24..2^-4 of the larger radius off), or along a generator
 * line of the side (on it or that much off, in or out). */
static void gen_axial(cylgen_rng *r, const rgeo *g, rcgen_case *c)
{
    const v3 e = gen_perp(r, g->u);
    const int along_gen = !g->nested && gen_chance(r, 0.5);
    v3 x = along_gen ? side_spot(g, e, 0).x : g->p0, d = g->u;
    if (along_gen)
        d = axpy(scl(e, g->k), g->nr, g->u);
    if (gen_chance(r, 0.7)) {
        double eps = gen_logu(r, -24, -4);
        eps *= gen_chance(r, 0.5) ? 1 : -1;
        x = axpy(x, eps * g->rmax, along_gen ? side_spot(g, e, 0).n : e);
    }
    if (gen_chance(r, 0.5))
        d = neg(d);
    aim(r, x, d, g->size * gen_uni(r, 2, 10) + (dot(d, g->u) < 0 ? g->L : 0), c);
}

GEN_RAY_ROW_DEFINE(rc_rays, towards, gen_grazing, gen_surface, point_in, NULL);

/* The categories the sphere and the cone share (gen_ray_kind), ordinary rays from 2-10
 * hull sizes; the others, ORDINARY's 0 here, are the round cone's own: one draw each
 * (own_ray), the camera, and the shapes' mix. */
static const unsigned char shared_kind[RCGEN_COUNT] = {
    [RCGEN_FAR] = GEN_RAY_FAR,         [RCGEN_GRAZING] = GEN_RAY_GRAZING,
    [RCGEN_SURFACE] = GEN_RAY_SURFACE, [RCGEN_UNNORM] = GEN_RAY_UNNORM,
    [RCGEN_BAD] = GEN_RAY_BAD,         [RCGEN_SCALED] = GEN_RAY_SCALED};

typedef void rc_draw(cylgen_rng *r, const rgeo *g, rcgen_case *c);
static rc_draw *const own_ray[RCGEN_COUNT] = {[RCGEN_INSIDE] = gen_inside,
                                              [RCGEN_SEAM] = gen_seam,
                                              [RCGEN_POINT] = gen_point,
                                              [RCGEN_AXIAL] = gen_axial};

static void gen_case(int cat, cylgen_rng *r, const rgeo *g, cylgen_rng *cam, size_t index,
                     rcgen_case *c)
{
    /* no shared camera: the round cone's own frames rmax + L / 4 */
    const gen_ray_at at = {&rc_rays, g, g->size, mk(0, 0, 0), 0, 2, GEN_RAY_CASE(c)};
    if (cat < 0 || cat >= RCGEN_COUNT)
        cat = RCGEN_ORDINARY;
    if (own_ray[cat]) {
        own_ray[cat](r, g, c);
        return;
    }
    switch (cat) {
    case RCGEN_CAMERA: {
        const v3 mid = scl(add(g->p0, g->p1), 0.5);
        gen_camera(cam, index, mid, g->rmax + g->L / 4, 1.3, c->o, c->d);
        c->tmin = 0.0f;
        c->tmax = INFINITY;
        break;
    }
    case RCGEN_CAPSULE:
    case RCGEN_TAPER:
    case RCGEN_NESTED:
    case RCGEN_LONG: {
        const double pick = cylgen_uniform(r);
        if (pick < 0.15)
            gen_grazing(r, g, c);
        else if (pick < 0.3)
            gen_seam(r, g, c);
        else
            gen_shared_ray(GEN_RAY_ORDINARY, r, cam, index, &at);
        break;
    }
    default:
        gen_shared_ray(shared_kind[cat], r, cam, index, &at);
        break;
    }
}

static const char *const names[RCGEN_COUNT] = {
    "rc-ordinary", "rc-far",     "rc-grazing", "rc-surface", "rc-inside", "rc-seam",
    "rc-point",    "rc-capsule", "rc-taper",   "rc-nested",  "rc-long",   "rc-unnorm",
    "rc-axial",    "rc-camera",  "rc-bad",     "rc-scaled"};

static const char *const descriptions[RCGEN_COUNT] = {
    "round cone: from 2-10 hull sizes at a point within 1.2 r of the segment",
    "round cone: origin 1e3-1e6 hull sizes away",
    "round cone: tangent to the side or a cap, 2^-23..2^-7 of it off either way",
    "round cone: origin a float-rounded point of the side or a cap, in- and outward, tmin 0",
    "round cone: origin inside the hull",
    "round cone: through a seam point, on it or 2^-24..2^-10 of the size off it",
    "round cone: a point end, at its apex or 2^-30..2^-5 of the size off",
    "round cone: r0 == r1, or a few ulps apart",
    "round cone: r1 / r0 in 2^-10..2^10",
    "round cone: one sphere inside the other, zero length, or almost nested",
    "round cone: length 1e4 radii",
    "round cone: |d| 2^-30..2^30",
    "round cone: along the axis and along generator lines, on them or off",
    "round cone: 4 x 4 pixel blocks of a pinhole camera",
    "round cone: NaN, Inf, zero-direction and empty-interval lanes among good ones",
    "round cone: ordinary and grazing scenes scaled by 2^+-(21..50), |d| 2^-20..2^20"};

static void rc_ray(int cat, cylgen_rng *r, cylgen_rng *cam, size_t index,
                   const rcref_round_cone *rc, rcgen_case *c)
{
    memset(c, 0, sizeof *c);
    c->rc = *rc;
    const rgeo g = geo_of(&c->rc);
    gen_case(cat, r, &g, cam, index, c);
}

GEN_SHAPE_DEFINE(rcgen, rcref_round_cone, names, descriptions, RCGEN_COUNT, 0x72636f6e65ull,
                 make_rc, rc_ray)
