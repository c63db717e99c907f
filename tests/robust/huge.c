/* SPDX-License-Identifier: MIT */
/* huge.c - huge but finite cylinders: cylray_prepare either refuses them
 * (CYLRAY_EINVAL) or the kernels answer correctly for them; never a false hit.
 *
 * Magnitudes from 1e10 to FLT_MAX go into the center, the radius, the half height
 * and the axis length. For every accepted cylinder, rays at its own scale (entering
 * the side, coming down onto a cap, passing at twice the radius, pointing away) run on
 * every ISA and width. A hit must lie on the surface (hitcheck.h) and agree with the
 * exact reference (tests/ref) where available; the rays built to miss must miss. The
 * axis length alone must not matter at all: an axis scaled by a power of two gives
 * bit-identical answers. */
#include <float.h>
#include <math.h>
#include <string.h>

#include "cylray.h"
#include "frame.h"
#include "guarded.h"
#include "hitcheck.h"
#include "tcheck.h"
#ifdef HAVE_CYLREF
#include "cylref.h"
#endif

#define NRAYS 16

/* Rays at the cylinder's own scale. Lanes 0..7 are aimed inside the solid (they hit,
 * unless the float rounding of so large a scene moved them: the reference decides);
 * lanes 8..15 pass at twice the radius or point away: they must miss. */
static void rays_for(const cylray_cylinder *c, gbatch *b)
{
    double u[3], e[3], e2[3]; /* e: a unit vector perpendicular to the axis */
    axis_frame(c->axis, u, e, e2);
    const double R = c->radius;
    const double H = isfinite(c->half_height) ? c->half_height : 4 * R;
    for (int i = 0; i < NRAYS; i++) {
        double o[3], d[3];
        const double z = (i % 4 - 1.5) * 0.4 * H; /* axial offsets within the height */
        for (int k = 0; k < 3; k++) {
            switch (i / 4) {
            case 0: /* from 3R beside the axis, toward it: enters the side */
                o[k] = c->center[k] + 3 * R * e[k] + z * u[k];
                d[k] = -e[k] + 0.01 * (i + 1) * u[k];
                break;
            case 1: /* from 1.5H above (below) the center, down (up) the axis */
                o[k] = c->center[k] + (i & 1 ? 1.5 : -1.5) * H * u[k] + 0.3 * R * e[k];
                d[k] = (i & 1 ? -1.0 : 1.0) * u[k];
                break;
            case 2: /* parallel to the axis at twice the radius: misses */
                o[k] = c->center[k] + 2 * R * e[k] + (z - 3 * H) * u[k];
                d[k] = u[k];
                break;
            default: /* from 3R beside the axis, pointing away */
                o[k] = c->center[k] + 3 * R * e[k] + z * u[k];
                d[k] = e[k] + 0.1 * u[k];
                break;
            }
        }
        for (int k = 0; k < 3; k++) {
            b->f[G_OX + k][i] = (float)o[k];
            b->f[G_DX + k][i] = (float)d[k];
        }
        b->f[G_TMIN][i] = 0;
        b->f[G_TMAX][i] = INFINITY;
    }
}

static void run_cylinder(const cylray_cylinder *c, const char *what)
{
    cylray_prepared P;
    if (cylray_prepare(&P, c) != CYLRAY_OK)
        return; /* refused: allowed */
    const cylray_kernels *isas[CYLRAY_ISA_COUNT];
    const int nisa = g_isas(isas);
    gbatch b;
    rays_for(c, &b);
    char cs[256], why[256];
    g_cyl_str(c, cs, sizeof cs);
    /* The rays built to miss still miss after rounding to float only when the float
     * grid at the scene's coordinates is fine against the radius; otherwise only the
     * reference can tell. */
    double big = 0;
    for (int i = 0; i < NRAYS; i++)
        for (int k = 0; k < 3; k++)
            big = fmax(big, fabs((double)b.f[G_OX + k][i]));
    const double coarse = big > 0 ? ldexp(1.0, ilogb(big) - 23) : 0;
#ifdef HAVE_CYLREF
    /* The exact verdicts, once per ray, without and with CYLRAY_CULL_BACK. */
    static cylref_band band[NRAYS][2];
    for (int i = 0; i < NRAYS; i++)
        for (int cull = 0; cull < 2; cull++) {
            const float o[3] = {b.f[G_OX][i], b.f[G_OY][i], b.f[G_OZ][i]};
            const float d[3] = {b.f[G_DX][i], b.f[G_DY][i], b.f[G_DZ][i]};
            cylref_band_eval(c, o, d, b.f[G_TMIN][i], b.f[G_TMAX][i],
                             cull ? CYLRAY_CULL_BACK : 0u, &band[i][cull]);
        }
#endif
    const unsigned flag_sets[] = {CYLRAY_NORMAL, CYLRAY_NORMAL | CYLRAY_REFINE,
                                  CYLRAY_CULL_BACK | CYLRAY_FAST};
    for (int ii = 0; ii < nisa; ii++)
        for (int fi = 0; fi < 3; fi++) {
            const unsigned flags = flag_sets[fi];
            const int widths[] = {4, 8, 16, G_STREAM};
            for (int wi = 0; wi < 4; wi++) {
                const int w = widths[wi];
                for (int first = 0; first < NRAYS; first += w == G_STREAM ? NRAYS : w) {
                    const size_t n = w == G_STREAM ? NRAYS : (size_t)w;
                    gbatch s;
                    for (int f = 0; f < G_NFIELD; f++)
                        memcpy(s.f[f], b.f[f] + first, n * sizeof(float));
                    gresult r;
                    g_intersect(isas[ii], w, &P, &s, n, 0xffffu, flags, 1, &r);
                    for (size_t j = 0; j < n; j++) {
                        const size_t i = (size_t)first + j;
                        const float o[3] = {s.f[G_OX][j], s.f[G_OY][j], s.f[G_OZ][j]};
                        const float d[3] = {s.f[G_DX][j], s.f[G_DY][j], s.f[G_DZ][j]};
                        const int hit = (int)((r.hit >> j) & 1u);
                        if (i >= 8 && coarse * 16 < c->radius)
                            CHECK(!hit,
                                  "%s %s w=%s flags=%#x ray %zu: false hit at t %a on a "
                                  "ray built to miss (%s)",
                                  what, isas[ii]->name, g_width_name(w), flags, i, r.t[j], cs);
                        if (hit) {
                            const float n3[3] = {r.nx[j], r.ny[j], r.nz[j]};
                            int v =
                                hc_verify(c, o, d, 0, INFINITY, r.t[j], r.part[j], n3, flags,
                                          flags & CYLRAY_FAST ? 16 : 1, why, sizeof why);
                            CHECK(v == 0,
                                  "%s %s w=%s flags=%#x ray %zu: impossible hit: %s (%s)", what,
                                  isas[ii]->name, g_width_name(w), flags, i, why, cs);
                        }
#ifdef HAVE_CYLREF
                        {
                            const cylref_band *bd = &band[i][(flags & CYLRAY_CULL_BACK) != 0];
                            double beyond = 0;
                            int v = cylref_judge(bd, hit, r.part[j], r.t[j], &beyond);
                            CHECK(v == 0,
                                  "%s %s w=%s flags=%#x ray %zu: %s (t %a part %#x), exact: %s "
                                  "at %.17g part %#x (%s)",
                                  what, isas[ii]->name, g_width_name(w), flags, i,
                                  hit ? "hit" : "miss", r.t[j], (unsigned)r.part[j],
                                  bd->exact.hit ? "hit" : "miss", bd->exact.t,
                                  (unsigned)bd->exact.part, cs);
                        }
#endif
                    }
                }
            }
        }
}

/* The axis length must not matter: powers of two from 2^-126 to 2^62 give answers
 * bit-identical to the unit axis (or, beyond what prepare accepts, a refusal). */
static void axis_scale(void)
{
    const cylray_cylinder unit = {{1, 2, 3}, {0.5f, -1, 0.25f}, 1.5f, 2, CYLRAY_CAPPED};
    cylray_prepared P0;
    cylray_prepare(&P0, &unit);
    gbatch b;
    rays_for(&unit, &b);
    const cylray_kernels *isas[CYLRAY_ISA_COUNT];
    const int nisa = g_isas(isas);
    gresult r0[CYLRAY_ISA_COUNT];
    for (int ii = 0; ii < nisa; ii++)
        g_intersect(isas[ii], G_STREAM, &P0, &b, NRAYS, 0, CYLRAY_NORMAL, 0, &r0[ii]);
    const int exps[] = {-126, -100, -60, -20, -1, 1, 20, 40, 60, 62, 63, 64, 100};
    for (size_t ei = 0; ei < sizeof exps / sizeof exps[0]; ei++) {
        cylray_cylinder c = unit;
        for (int k = 0; k < 3; k++)
            c.axis[k] = ldexpf(unit.axis[k], exps[ei]);
        cylray_prepared P;
        if (cylray_prepare(&P, &c) != CYLRAY_OK) {
            CHECK(exps[ei] > 62 || exps[ei] < -125, "an axis scaled by 2^%d was refused",
                  exps[ei]);
            continue;
        }
        for (int ii = 0; ii < nisa; ii++) {
            gresult r;
            g_intersect(isas[ii], G_STREAM, &P, &b, NRAYS, 0, CYLRAY_NORMAL, 0, &r);
            for (size_t i = 0; i < NRAYS; i++)
                CHECK(g_same_lane(&r, i, &r0[ii], i, 1),
                      "%s: axis scaled by 2^%d changes ray %zu (t %a, unit axis %a)",
                      isas[ii]->name, exps[ei], i, r.t[i], r0[ii].t[i]);
        }
    }
}

int main(void)
{
    const float mags[] = {1e10f, 1e15f, 1e18f, 0x1p62f, 1e19f,
                          1e20f, 1e25f, 1e30f, 1e38f,   FLT_MAX};
    char what[96];
    int accepted = 0;
    for (size_t mi = 0; mi < sizeof mags / sizeof mags[0]; mi++) {
        const float m = mags[mi];
        cylray_cylinder c;
        cylray_status s;
        cylray_prepared P;
        /* a huge center, the cylinder a quarter of its size */
        c = (cylray_cylinder){
            {m, -m / 2, m / 4}, {0.3f, 0.4f, -1}, m / 4, m / 4, CYLRAY_CAPPED};
        snprintf(what, sizeof what, "center %g, R = H = %g", m, m / 4);
        s = cylray_prepare(&P, &c);
        accepted += s == CYLRAY_OK;
        run_cylinder(&c, what);
        /* a huge center, a unit cylinder */
        c = (cylray_cylinder){{m, m, -m}, {0, 1, 0}, 1, 1, CYLRAY_CAPPED};
        snprintf(what, sizeof what, "center %g, unit size", m);
        run_cylinder(&c, what);
        /* a huge radius and height at the origin, open and capped */
        for (unsigned f = 0; f <= CYLRAY_CAPPED; f++) {
            c = (cylray_cylinder){{0, 0, 0}, {1, 1, 0}, m, m, f};
            snprintf(what, sizeof what, "R = H = %g, flags %u", m, f);
            run_cylinder(&c, what);
        }
        /* a huge half height, unit radius */
        c = (cylray_cylinder){{1, 2, 3}, {0, 0, 1}, 1, m, CYLRAY_CAPPED};
        snprintf(what, sizeof what, "H = %g, R = 1", m);
        run_cylinder(&c, what);
        /* a huge radius, unit half height */
        c = (cylray_cylinder){{1, 2, 3}, {0, 0, 1}, m, 1, CYLRAY_CAPPED};
        snprintf(what, sizeof what, "R = %g, H = 1", m);
        run_cylinder(&c, what);
    }
    CHECK(accepted > 0, "no huge cylinder was accepted: nothing was tested");
    axis_scale();
    return tc_report("robust-huge");
}
