/* SPDX-License-Identifier: MIT */
/* consumer.c - a program that uses cylray as any user of an installed copy would:
 * <cylray.h> and the linker, nothing from the source tree. consumers.py builds it
 * against the installed tree with pkg-config, with CMake, and with cylray as a meson
 * subproject; it fails unless the library gives the answers worked out below. */
#include <cylray.h>

#include <math.h>
#include <stdio.h>

int main(void)
{
    /* Radius 1 around the z axis, |z| <= 2, both ends closed. */
    const cylray_cylinder c = {{0, 0, 0}, {0, 0, 1}, 1.0f, 2.0f, CYLRAY_CAPPED};
    cylray_prepared p;
    if (cylray_prepare(&p, &c) != CYLRAY_OK) {
        fprintf(stderr, "consumer: a valid cylinder was refused\n");
        return 1;
    }
    const cylray_cylinder bad = {{0, 0, 0}, {0, 0, 1}, -1.0f, 2.0f, CYLRAY_CAPPED};
    cylray_prepared q;
    if (cylray_prepare(&q, &bad) != CYLRAY_EINVAL || !cylray_strerror(CYLRAY_EINVAL)) {
        fprintf(stderr, "consumer: a negative radius was not refused\n");
        return 1;
    }

    /* Rays along +x from x = -5: lane 0 passes below the low cap and misses; the
     * others meet the side at x = -1, t = 4, where the outward normal is -x. */
    const float z[4] = {-3.0f, -1.0f, 0.0f, 1.5f};
    cylray_ray4 r;
    cylray_hit4 h;
    for (int i = 0; i < 4; i++) {
        r.ox[i] = -5, r.oy[i] = 0, r.oz[i] = z[i];
        r.dx[i] = 1, r.dy[i] = 0, r.dz[i] = 0;
        r.tmin[i] = 0, r.tmax[i] = INFINITY;
    }
    const uint32_t hits = cylray_intersect4(&p, &r, &h, 0xfu, CYLRAY_NORMAL);
    int bad_lanes = hits != 0xeu;
    for (int i = 1; i < 4; i++)
        bad_lanes += fabsf(h.t[i] - 4.0f) > 1e-5f || h.part[i] != CYLRAY_SIDE ||
                     fabsf(h.nx[i] + 1.0f) > 1e-5f || r.tmax[i] != h.t[i];
    if (bad_lanes) {
        fprintf(stderr, "consumer: hit mask %#x, expected 0xe, or a wrong hit\n",
                (unsigned)hits);
        return 1;
    }
    printf("consumer: cylray %d.%d.%d, %s path: 3 hits and 1 miss, as expected\n",
           CYLRAY_VERSION_MAJOR, CYLRAY_VERSION_MINOR, CYLRAY_VERSION_PATCH,
           cylray_kernels_best()->name);
    return 0;
}
