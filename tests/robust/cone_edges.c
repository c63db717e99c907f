/* SPDX-License-Identifier: MIT */
/* cone_edges.c - two places where a cone's quadratic degenerates, on every path, leaf
 * width and flag set:
 *   - a lane of a leaf of cones with r0 == r1 (a cylinder there) and a ray exactly
 *     parallel to its axis: A = D = 0, so no side root; the ray inside the tube meets
 *     the caps, outside it meets nothing (as the prepared cone's packet answers);
 *   - a ray into the apex of a tip cone: the side's gradient vanishes there, and the
 *     normal must still be a unit vector (the axis, away from the cone). */
#include "conref.h"
#include "cylray.h"

#include <math.h>
#include <stdio.h>

static int failures, checks;

static void fail(const char *isa, const char *what, int i, unsigned flags, const char *why)
{
    if (failures++ < 20)
        printf("FAIL %s %s case %d flags 0x%x: %s\n", isa, what, i, flags, why);
}

/* One ray against the leaf (width 4, 8, 16) and the exact answer. */
static void parallel_rays(const cylray_kernels *k)
{
    static const cylray_cone cones[] = {
        {{0, 0, -1}, {0, 0, 1}, 1, 1, CYLRAY_CAPPED},
        {{-1, 0, 0}, {1, 0, 0}, 0.5f, 0.5f, CYLRAY_CAPPED_LO},
        {{1, 2, 3}, {2, 4, 5}, 0.75f, 0.75f, CYLRAY_CAPPED},
        {{0, 0, -1}, {0, 0, 1}, 1, 0.5f, CYLRAY_CAPPED},
    };
    /* offsets across the axis, in units of the radius */
    static const float off[] = {0, 0.5f, 0.999f, 1.001f, 1.2f, 3};
    for (int c = 0; c < 4; c++) {
        const cylray_cone *cn = &cones[c];
        float a[3], n1[3] = {0, 0, 0}, len = 0;
        for (int j = 0; j < 3; j++)
            a[j] = cn->p1[j] - cn->p0[j], len += a[j] * a[j];
        /* a unit vector across the axis: the axis crossed with the coordinate axis it
         * least follows (exact here: the axes are coordinate axes or (1, 2, 2)) */
        if (c == 2)
            n1[0] = 0, n1[1] = 1, n1[2] = -1;
        else if (a[0] != 0)
            n1[1] = 1;
        else
            n1[0] = 1;
        const float nl = sqrtf(n1[0] * n1[0] + n1[1] * n1[1] + n1[2] * n1[2]);
        cylray_cone lanes[16];
        for (int l = 0; l < 16; l++)
            lanes[l] = *cn;
        cylray_leaf4 l4;
        cylray_leaf8 l8;
        cylray_leaf16 l16;
        if (cylray_leaf_prepare_cones4(&l4, lanes, NULL, 4) != CYLRAY_OK ||
            cylray_leaf_prepare_cones8(&l8, lanes, NULL, 8) != CYLRAY_OK ||
            cylray_leaf_prepare_cones16(&l16, lanes, NULL, 16) != CYLRAY_OK) {
            fail(k->name, "leaf prepare", c, 0, "refused");
            continue;
        }
        for (int i = 0; i < (int)(sizeof off / sizeof off[0]); i++)
            for (int dir = -1; dir <= 1; dir += 2) {
                const float r = fmaxf(cn->r0, cn->r1) * off[i] / nl;
                float o[3], d[3];
                for (int j = 0; j < 3; j++) {
                    d[j] = (float)dir * a[j];
                    o[j] = (dir > 0 ? cn->p0[j] : cn->p1[j]) - 3 * d[j] + r * n1[j];
                }
                for (unsigned flags = 0; flags <= CYLRAY_FLAGS_ALL; flags++) {
                    cylref_hit ex;
                    cylref_band band;
                    conref_intersect(cn, o, d, 0, INFINITY, flags, &ex);
                    conref_band_eval(cn, o, d, 0, INFINITY, flags, &band);
                    for (int w = 0; w < 3; w++) {
                        cylray_ray1 ray = {{o[0], o[1], o[2]}, {d[0], d[1], d[2]}, 0, INFINITY};
                        cylray_hit1 h;
                        const int hit = w == 0   ? k->leaf_intersect4(&l4, &ray, &h, flags)
                                        : w == 1 ? k->leaf_intersect8(&l8, &ray, &h, flags)
                                                 : k->leaf_intersect16(&l16, &ray, &h, flags);
                        double beyond = 0;
                        checks++;
                        if (conref_judge(&band, hit, hit ? (int)h.part : 0, hit ? h.t : 0,
                                         &beyond) != 0 ||
                            beyond > 4) {
                            char why[160];
                            snprintf(why, sizeof why,
                                     "leaf%d offset %g dir %d: %s t %g part %u; exact %s t %g",
                                     4 << w, off[i], dir, hit ? "hit" : "miss", hit ? h.t : 0,
                                     hit ? (unsigned)h.part : 0u, ex.hit ? "hit" : "miss",
                                     ex.t);
                            fail(k->name, "parallel", c, flags, why);
                        }
                    }
                }
            }
    }
}

static void apex_normals(const cylray_kernels *k)
{
    /* tips at p1 = (0, 0, 1) and at p0 = (0, 0, -1) */
    static const cylray_cone cones[] = {{{0, 0, -1}, {0, 0, 1}, 1, 0, CYLRAY_CAPPED},
                                        {{0, 0, -1}, {0, 0, 1}, 0, 1, CYLRAY_CAPPED}};
    static const float rays[][6] = {
        {0, 0, 3, 0, 0, -1},  {0, 0, -3, 0, 0, 1}, {-2, 0, 1, 1, 0, 0},
        {2, 0, -1, -1, 0, 0}, {0, -2, 1, 0, 1, 0}, {0, 2, -1, 0, -1, 0},
    };
    for (int c = 0; c < 2; c++) {
        cylray_prepared p;
        if (cylray_prepare_cone(&p, &cones[c]) != CYLRAY_OK) {
            fail(k->name, "prepare", c, 0, "refused");
            continue;
        }
        cylray_ray4 r4;
        for (int l = 0; l < 4; l++) {
            const float *x = rays[(2 * l + c) % 6];
            r4.ox[l] = x[0], r4.oy[l] = x[1], r4.oz[l] = x[2];
            r4.dx[l] = x[3], r4.dy[l] = x[4], r4.dz[l] = x[5];
            r4.tmin[l] = 0, r4.tmax[l] = INFINITY;
        }
        for (unsigned flags = 0; flags <= CYLRAY_FLAGS_ALL; flags++) {
            if (!(flags & CYLRAY_NORMAL))
                continue;
            cylray_hit4 h;
            const uint32_t m = k->intersect4(&p, &r4, &h, 0xfu, flags);
            for (int l = 0; l < 4; l++) {
                if (!((m >> l) & 1u))
                    continue;
                const double n2 = (double)h.nx[l] * h.nx[l] + (double)h.ny[l] * h.ny[l] +
                                  (double)h.nz[l] * h.nz[l];
                checks++;
                if (!(fabs(n2 - 1) < 1e-5)) {
                    char why[120];
                    snprintf(why, sizeof why, "lane %d t %g part %u: n (%g %g %g)", l, h.t[l],
                             h.part[l], h.nx[l], h.ny[l], h.nz[l]);
                    fail(k->name, "apex normal", c, flags, why);
                }
            }
        }
    }
}

int main(void)
{
    for (int isa = 0; isa < CYLRAY_ISA_COUNT; isa++) {
        const cylray_kernels *k = cylray_kernels_for((cylray_isa)isa);
        if (!k)
            continue;
        parallel_rays(k);
        apex_normals(k);
    }
    printf("robust-cone-edges: %d checks, %d failures\n", checks, failures);
    return failures != 0;
}
