/* textbook.c - the seed's formulas, exactly as written there, in plain float:
 *   A = d.d - (d.v)^2,  B = d.w - (d.v)(w.v),  C = w.w - (w.v)^2 - R^2,
 *   disc = B^2 - A C,   t = (-B -/+ sqrt(disc)) / A,
 * with a float-normalised axis and the sphere-style finite clip |x - c|^2 <= R^2 + H^2
 * on the hit point. It is the baseline that shows what the stable kernel buys; it is
 * deliberately not improved (no FMA: the project builds with -ffp-contract=off). */
#include "textbook.h"

#include <math.h>

void tb_prepare(tb_cylinder *out, const cylray_cylinder *in)
{
    const float *a = in->axis;
    float len = sqrtf(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    for (int k = 0; k < 3; k++) {
        out->c[k] = in->center[k];
        out->v[k] = a[k] / len;
    }
    out->rr = in->radius * in->radius;
    out->clip = out->rr + in->half_height * in->half_height; /* INFINITY: no clip */
}

static int tb_ray(const tb_cylinder *cy, const float o[3], const float d[3], float tmin,
                  float tmax, float *t_out, float n_out[3])
{
    const float *c = cy->c, *v = cy->v;
    float w[3] = {o[0] - c[0], o[1] - c[1], o[2] - c[2]};
    float dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    float dv = d[0] * v[0] + d[1] * v[1] + d[2] * v[2];
    float wv = w[0] * v[0] + w[1] * v[1] + w[2] * v[2];
    float dw = d[0] * w[0] + d[1] * w[1] + d[2] * w[2];
    float ww = w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
    float A = dd - dv * dv;
    float B = dw - dv * wv;
    float C = ww - wv * wv - cy->rr;
    float disc = B * B - A * C;
    if (!(disc >= 0.0f))
        return 0;
    float s = sqrtf(disc);
    float roots[2] = {(-B - s) / A, (-B + s) / A};
    for (int k = 0; k < 2; k++) {
        float t = roots[k];
        if (!(t >= tmin && t <= tmax))
            continue;
        float x[3] = {o[0] + t * d[0] - c[0], o[1] + t * d[1] - c[1], o[2] + t * d[2] - c[2]};
        if (!(x[0] * x[0] + x[1] * x[1] + x[2] * x[2] <= cy->clip))
            continue;
        /* The seed's normal: the hit point minus its projection on the axis, made unit. */
        float xv = x[0] * v[0] + x[1] * v[1] + x[2] * v[2];
        float n[3] = {x[0] - xv * v[0], x[1] - xv * v[1], x[2] - xv * v[2]};
        float nl = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        for (int j = 0; j < 3; j++)
            n_out[j] = n[j] / nl;
        *t_out = t;
        return 1;
    }
    return 0;
}

size_t tb_intersect_stream(const tb_cylinder *cyl, const cylray_rays *rays,
                           const cylray_hits *hits, size_t n, unsigned flags)
{
    size_t count = 0;
    for (size_t i = 0; i < n; i++) {
        float o[3] = {rays->ox[i], rays->oy[i], rays->oz[i]};
        float d[3] = {rays->dx[i], rays->dy[i], rays->dz[i]};
        float t, nn[3];
        if (!tb_ray(cyl, o, d, rays->tmin[i], rays->tmax[i], &t, nn))
            continue;
        count++;
        hits->t[i] = t;
        rays->tmax[i] = t;
        float dn = d[0] * nn[0] + d[1] * nn[1] + d[2] * nn[2];
        hits->part[i] = CYLRAY_SIDE | (dn > 0 ? CYLRAY_BACKFACE : 0);
        if (flags & CYLRAY_NORMAL) {
            hits->nx[i] = nn[0];
            hits->ny[i] = nn[1];
            hits->nz[i] = nn[2];
        }
    }
    return count;
}
