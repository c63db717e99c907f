/* SPDX-License-Identifier: MIT */
/* aimed.c - the aimed ray sets (rim, axis): the rays where the two geometries part,
 * kept apart from the scene's timing and judging. */
#include "aimed.h"
#include "run.h"

#include <math.h>
#include <stdint.h>

static void unit_frame(const double a[3], double e1[3], double e2[3])
{
    double t[3] = {fabs(a[0]) < 0.6 ? 1 : 0, fabs(a[0]) < 0.6 ? 0 : 1, 0}, l = 0, m = 0;
    e1[0] = a[1] * t[2] - a[2] * t[1], e1[1] = a[2] * t[0] - a[0] * t[2];
    e1[2] = a[0] * t[1] - a[1] * t[0];
    for (int k = 0; k < 3; k++)
        l += e1[k] * e1[k];
    for (int k = 0; k < 3; k++)
        e1[k] /= sqrt(l);
    e2[0] = a[1] * e1[2] - a[2] * e1[1], e2[1] = a[2] * e1[0] - a[0] * e1[2];
    e2[2] = a[0] * e1[1] - a[1] * e1[0];
    for (int k = 0; k < 3; k++)
        m += e2[k] * e2[k];
    for (int k = 0; k < 3; k++)
        e2[k] /= sqrt(m);
}

static void to_float_ray(eb_sample *s, const double o[3], const double d[3])
{
    double l = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (int k = 0; k < 3; k++) {
        s->o[k] = (float)o[k];
        s->d[k] = (float)(d[k] / l);
    }
    s->tmin = 0;
    s->tmax = INFINITY;
    s->pixel = SIZE_MAX;
}

/* The spheres' aimed rays: from the eye along the silhouette (grazing: the rim set), or
 * from just inside or outside the surface, 1e-7..1e-3 radii from it, in a random
 * direction (the axis set's counterpart: an origin where o - c is nearly R). */
static void aimed_sphere(eb_sample *s, const eb_scene *sc, int set, rng *g)
{
    const cylray_sphere *sp = &sc->sph[(size_t)(rng_unit(g) * (double)sc->nsph)];
    double C[3] = {sp->center[0], sp->center[1], sp->center[2]}, R = sp->radius;
    double ph = rng_range(g, 0, 6.283185307179586), a[3], e1[3], e2[3], l = 0, o[3], d[3];
    if (set == EB_SET_RIM) {
        for (int k = 0; k < 3; k++)
            a[k] = C[k] - sc->eye[k], l += a[k] * a[k];
        l = sqrt(l);
        for (int k = 0; k < 3; k++)
            a[k] /= l;
        unit_frame(a, e1, e2);
        double sn = R / l, cs = sqrt(1 - sn * sn);
        for (int k = 0; k < 3; k++)
            d[k] = cs * a[k] + sn * (cos(ph) * e1[k] + sin(ph) * e2[k]);
        to_float_ray(s, (const double[]){sc->eye[0], sc->eye[1], sc->eye[2]}, d);
        return;
    }
    double z = rng_range(g, -1, 1), r = sqrt(1 - z * z);
    double u[3] = {r * cos(ph), r * sin(ph), z};
    double gap = (rng_unit(g) < 0.5 ? -1 : 1) * pow(10, rng_range(g, -7, -3));
    double th = rng_range(g, 0, 6.283185307179586), zz = rng_range(g, -1, 1);
    double rr = sqrt(1 - zz * zz);
    for (int k = 0; k < 3; k++)
        o[k] = C[k] + R * (1 + gap) * u[k];
    d[0] = rr * cos(th), d[1] = rr * sin(th), d[2] = zz;
    to_float_ray(s, o, d);
}

/* Rays from the eye at points of the rim of a closed end (where Embree's curves test
 * side and disc apart), or down the axis: at a closed end from outside, at an open
 * joint from inside the tube, within 1e-7..1e-3 rad of the axis. In a scene with
 * spheres, half of them (all, without cylinders) are the spheres' counterparts. */
void eb_aimed(eb_sample *s, const eb_scene *sc, int set, rng *g)
{
    if (sc->nsph && (sc->ns == 0 || rng_unit(g) < 0.5)) {
        aimed_sphere(s, sc, set, g);
        return;
    }
    for (;;) {
        uint32_t id = (uint32_t)(rng_unit(g) * (double)sc->ns);
        const float *p0 = sc->vert[sc->first[id]], *p1 = sc->vert[sc->first[id] + 1];
        unsigned caps = sc->caps[id];
        int hi = rng_unit(g) < 0.5;
        int closed = (caps & (hi ? CYLRAY_CAPPED_HI : CYLRAY_CAPPED_LO)) != 0;
        /* the radius at that end (a tapered scene's own there; a tip has no rim) */
        double R = sc->vrad ? sc->vrad[sc->first[id] + (hi ? 1 : 0)] : sc->radius;
        if (set == EB_SET_RIM && (!closed || R == 0))
            continue;
        double a[3], l = 0, e1[3], e2[3], E[3], o[3], d[3];
        for (int k = 0; k < 3; k++)
            a[k] = (double)p1[k] - p0[k], l += a[k] * a[k];
        for (int k = 0; k < 3; k++) {
            a[k] /= sqrt(l);
            E[k] = hi ? p1[k] : p0[k];
        }
        unit_frame(a, e1, e2);
        double ph = rng_range(g, 0, 6.283185307179586);
        if (set == EB_SET_RIM) {
            for (int k = 0; k < 3; k++)
                d[k] = E[k] + R * (cos(ph) * e1[k] + sin(ph) * e2[k]) - sc->eye[k];
            to_float_ray(s, (const double[]){sc->eye[0], sc->eye[1], sc->eye[2]}, d);
            return;
        }
        double out = hi ? 1 : -1, th = pow(10, rng_range(g, -7, -3));
        double rr = closed ? 0 : R * rng_range(g, 0, 0.5);
        double dist = closed ? R * rng_range(g, 2, 20) : 0;
        /* closed: outside, looking back at the disc; open: inside, looking along */
        for (int k = 0; k < 3; k++) {
            o[k] = E[k] + out * dist * a[k] + rr * (cos(ph) * e1[k] + sin(ph) * e2[k]);
            d[k] = -out * a[k] + th * (cos(ph + 1) * e1[k] + sin(ph + 1) * e2[k]);
        }
        to_float_ray(s, o, d);
        return;
    }
}
