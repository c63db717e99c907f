/* SPDX-License-Identifier: MIT */
/* finite_t.c - a reported t is always finite: rays that the kernels take through their
 * rare instance (a direction far from unit length) inside an infinite cylinder and
 * parallel to its axis never exit it, and must not report an exit at t = INFINITY, in a
 * leaf (whose lanes run the capped solid's logic with an unbounded slab) or a packet,
 * on every path and flag set. */
#include "cylray.h"

#include <math.h>
#include <stdio.h>

int main(void)
{
    /* Found by leafcheck: an infinite cylinder along x, a ray from inside it along -x
     * within an ulp of the axis direction, |d| = 2^30. */
    const cylray_cylinder cyl = {{0x1.8a0822p+2f, 0x1.902628p+2f, -0x1.072cb4p+1f},
                                 {0x1.b8660cp+2f, 0, 0},
                                 0x1.c253bap-2f,
                                 INFINITY,
                                 0};
    const float o[3] = {0x1.28bc28p+3f, 0x1.8a8842p+2f, -0x1.df3a3cp+0f};
    const float scales[4] = {1.0f, 0x1p-20f, 0x1p-60f, 0x1p60f};
    int failures = 0, calls = 0;
    cylray_leaf8 leaf;
    cylray_prepared prep;
    if (cylray_leaf_prepare8(&leaf, &cyl, NULL, 1) != CYLRAY_OK ||
        cylray_prepare(&prep, &cyl) != CYLRAY_OK)
        return 1;
    for (int isa = 0; isa < CYLRAY_ISA_COUNT; isa++) {
        const cylray_kernels *k = cylray_kernels_for((cylray_isa)isa);
        if (!k)
            continue;
        for (int s = 0; s < 4; s++) {
            const float d[3] = {-0x1p+30f * scales[s], 0x1.7fd82ap+1f * scales[s],
                                -0x1.bcb6f2p+6f * scales[s]};
            for (unsigned flags = 0; flags <= CYLRAY_FLAGS_ALL; flags++) {
                cylray_ray1 ray = {{o[0], o[1], o[2]}, {d[0], d[1], d[2]}, 0, INFINITY};
                cylray_hit1 hit;
                if (k->leaf_intersect8(&leaf, &ray, &hit, flags) && !isfinite(hit.t)) {
                    printf("FAIL %s leaf8, d scaled by %a, flags 0x%x: t = %g\n", k->name,
                           scales[s], flags, hit.t);
                    failures++;
                }
                cylray_ray4 r4;
                cylray_hit4 h4;
                for (int l = 0; l < 4; l++) {
                    r4.ox[l] = o[0], r4.oy[l] = o[1], r4.oz[l] = o[2];
                    r4.dx[l] = d[0], r4.dy[l] = d[1], r4.dz[l] = d[2];
                    r4.tmin[l] = 0, r4.tmax[l] = INFINITY;
                }
                const uint32_t m = k->intersect4(&prep, &r4, &h4, 0xfu, flags);
                for (int l = 0; l < 4; l++)
                    if ((m >> l) & 1u && !isfinite(h4.t[l])) {
                        printf("FAIL %s packet4, d scaled by %a, flags 0x%x: t = %g\n", k->name,
                               scales[s], flags, h4.t[l]);
                        failures++;
                    }
                calls += 2;
            }
        }
    }
    printf("%d calls, %d with a non-finite t\n", calls, failures);
    return failures != 0;
}
