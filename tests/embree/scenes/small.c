/* SPDX-License-Identifier: MIT */
/* small.c - the agreement tests' small random scenes: cylinders of every cap kind, with
 * spheres among them, or cones. */
#include "build.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

int eb_scene_small(eb_scene *s, size_t n, uint64_t seed)
{
    return eb_scene_small_spheres(s, n, 0, seed);
}

int eb_scene_small_spheres(eb_scene *s, size_t n, size_t nsph, uint64_t seed)
{
    memset(s, 0, sizeof *s);
    snprintf(s->name, sizeof s->name, "small");
    eb_builder b = {.s = s, .quantum = 0x1p-10};
    eb_rng g = {seed};
    s->radius = 0.35f;
    static const unsigned kinds[4] = {0, CYLRAY_CAPPED_LO, CYLRAY_CAPPED_HI, CYLRAY_CAPPED};
    for (size_t i = 0; i < n; i++) {
        /* every fifth a long one, which gets split boxes */
        double p[3], q[3], reach = i % 5 == 4 ? 12 : 3;
        for (int k = 0; k < 3; k++) {
            p[k] = eb_range(&g, -8, 8);
            q[k] = p[k] + eb_range(&g, -reach, reach);
        }
        uint32_t v = eb_add_vertex(&b, p);
        eb_add_vertex(&b, q);
        eb_add_segment(&b, v, kinds[(int)(eb_unit(&g) * 4)]);
    }
    /* radii from 0.05 to 2.5: small ones among the cylinders, large ones that hold
     * some of them and some of each other (coincident and nested surfaces) */
    eb_rng gs = {seed ^ 0x5ca1ab1eull};
    for (size_t i = 0; i < nsph; i++) {
        double p[3];
        for (int k = 0; k < 3; k++)
            p[k] = eb_range(&gs, -8, 8);
        eb_add_sphere(&b, p, (float)(nearbyint(0.05 * pow(50, eb_unit(&gs)) * 1024) / 1024));
    }
    eb_set3(s->eye, 0, 3, 24);
    eb_set3(s->look, 0, 0, 0);
    eb_set3(s->light, 10, 30, 20);
    s->fov_deg = 55;
    s->scale = 16;
    if (eb_scene_finish(&b)) {
        eb_scene_free(s);
        return -1;
    }
    return 0;
}

int eb_scene_small_cones(eb_scene *s, size_t n, uint64_t seed)
{
    memset(s, 0, sizeof *s);
    snprintf(s->name, sizeof s->name, "small-cones");
    eb_builder b = {.s = s, .quantum = 0x1p-10};
    eb_rng g = {seed};
    static const unsigned kinds[4] = {0, CYLRAY_CAPPED_LO, CYLRAY_CAPPED_HI, CYLRAY_CAPPED};
    for (size_t i = 0; i < n; i++) {
        /* every fifth a long one, which gets split boxes */
        double p[3], q[3], reach = i % 5 == 4 ? 12 : 3;
        for (int k = 0; k < 3; k++) {
            p[k] = eb_range(&g, -8, 8);
            q[k] = p[k] + eb_range(&g, -reach, reach);
        }
        /* radii in steps of 1/1024 from 0.05 to 1.2: one in eight a tip at one end, one
         * in six a cylinder */
        float r0 = (float)(nearbyint(eb_range(&g, 0.05, 1.2) * 1024) / 1024);
        float r1 = (float)(nearbyint(eb_range(&g, 0.05, 1.2) * 1024) / 1024);
        double pick = eb_unit(&g);
        if (pick < 1.0 / 16)
            r0 = 0;
        else if (pick < 1.0 / 8)
            r1 = 0;
        else if (pick < 1.0 / 8 + 1.0 / 6)
            r1 = r0;
        uint32_t v = eb_add_vertex(&b, p);
        eb_set_vrad(&b, v, r0);
        eb_set_vrad(&b, eb_add_vertex(&b, q), r1);
        eb_add_segment(&b, v, kinds[(int)(eb_unit(&g) * 4)]);
    }
    s->radius = 0.05f; /* the smallest radius but the tips' */
    eb_set3(s->eye, 0, 3, 24);
    eb_set3(s->look, 0, 0, 0);
    eb_set3(s->light, 10, 30, 20);
    s->fov_deg = 55;
    s->scale = 16;
    if (eb_scene_finish(&b)) {
        eb_scene_free(s);
        return -1;
    }
    return 0;
}
