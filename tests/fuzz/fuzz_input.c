/* SPDX-License-Identifier: MIT */
/* fuzz_input.c - the byte decoder of fuzz_input.h. */
#include "fuzz_input.h"

#include <float.h>
#include <math.h>
#include <string.h>

#include "frame.h"

typedef struct reader {
    const uint8_t *p;
    size_t left;
} reader;

static uint8_t byte(reader *r)
{
    if (!r->left)
        return 0;
    r->left--;
    return *r->p++;
}

static float value(reader *r)
{
    static const float special[32] = {
        0.0f,    -0.0f,    1.0f,           -1.0f,         0.5f,      2.0f,    3.0f,
        -2.0f,   NAN,      -NAN,           INFINITY,      -INFINITY, FLT_MAX, -FLT_MAX,
        FLT_MIN, -FLT_MIN, FLT_TRUE_MIN,   -FLT_TRUE_MIN, 1e-40f,    1e30f,   -1e30f,
        1e-30f,  0x1p62f,  0x1p-62f,       1e10f,         -1e10f,    1e-10f,  1e6f,
        -1e6f,   1e-6f,    0x1.fffffep-1f, 0x1.000002p+0f};
    const uint8_t tag = byte(r);
    if (tag < 32)
        return special[tag];
    if (tag < 224) {
        const uint8_t lo = byte(r), hi = byte(r);
        const int16_t i = (int16_t)(uint16_t)(lo | hi << 8);
        return ldexpf((float)i, (tag - 32) % 24 - 20);
    }
    uint8_t b[4];
    for (int k = 0; k < 4; k++)
        b[k] = byte(r);
    float f;
    memcpy(&f, b, sizeof f);
    return f;
}

static void aimed(reader *r, const cylray_cylinder *c, float out[G_NFIELD], uint8_t tag)
{
    double u[3], e1[3], e2[3];
    axis_frame(c->axis, u, e1, e2);
    float o[3];
    for (int k = 0; k < 3; k++)
        o[k] = value(r);
    const double ang = byte(r) * (6.283185307179586 / 256);
    const double zf = (int8_t)byte(r) / 100.0; /* -1.28 .. 1.27 of the half height */
    const double rf = byte(r) / 128.0;         /* 0 .. 2 radii from the axis */
    const int len = byte(r) % 24 - 12;         /* direction length 2^-12 .. 2^11 */
    const double H = isfinite(c->half_height) ? c->half_height : 4.0 * c->radius;
    double d[3], dl = 0;
    for (int k = 0; k < 3; k++) {
        const double tgt = c->center[k] + zf * H * u[k] +
                           rf * c->radius * (cos(ang) * e1[k] + sin(ang) * e2[k]);
        /* origins are relative to the cylinder's center, so they land near it */
        o[k] = (float)((double)c->center[k] + o[k]);
        d[k] = tgt - o[k];
        dl += d[k] * d[k];
    }
    dl = sqrt(dl);
    for (int k = 0; k < 3; k++) {
        out[G_OX + k] = o[k];
        out[G_DX + k] = dl > 0 ? (float)(d[k] / dl * ldexp(1.0, len)) : 0.0f;
    }
    switch (tag & 3) {
    case 0:
        out[G_TMIN] = 0, out[G_TMAX] = INFINITY;
        break;
    case 1:
        out[G_TMIN] = -INFINITY, out[G_TMAX] = INFINITY;
        break;
    case 2:
        out[G_TMIN] = 0, out[G_TMAX] = value(r);
        break;
    default:
        out[G_TMIN] = value(r), out[G_TMAX] = value(r);
        break;
    }
}

void fz_decode(const uint8_t *data, size_t size, fz_case *c)
{
    reader r = {data, size};
    memset(c, 0, sizeof *c);
    const uint8_t mode = byte(&r);
    static const int widths[4] = {4, 8, 16, G_STREAM};
    c->width = widths[mode & 3];
    c->misalign = (mode >> 2) & 3u;
    c->flags = byte(&r) & CYLRAY_FLAGS_ALL;
    const uint8_t a0 = byte(&r), a1 = byte(&r);
    c->active = (uint32_t)(a0 | a1 << 8);
    c->n = c->width == G_STREAM ? (size_t)(a0 % 50) : (size_t)c->width;
    if (c->width != G_STREAM)
        c->active &= (uint32_t)((1ull << c->width) - 1u);
    for (int k = 0; k < 3; k++)
        c->cyl.center[k] = value(&r);
    for (int k = 0; k < 3; k++)
        c->cyl.axis[k] = value(&r);
    c->cyl.radius = value(&r);
    c->cone = (mode & 0xe0) == 0xa0;
    const float r1 = c->cone ? value(&r) : 0.0f;
    c->cyl.half_height = (mode & 0x20) ? INFINITY : value(&r);
    c->cyl.flags = (mode & 0x10) ? CYLRAY_CAPPED : 0u;
    c->sphere = (mode & 0xc0) == 0xc0;
    for (int k = 0; k < 3; k++)
        c->sph.center[k] = c->cyl.center[k];
    c->sph.radius = c->cyl.radius;
    /* A sphere's rays aim at its ball: the "cylinder" they aim at is R high. */
    cylray_cylinder aim = c->cyl;
    if (c->sphere)
        aim.half_height = aim.radius;
    if (c->cone) {
        for (int k = 0; k < 3; k++) {
            c->con.p0[k] = c->cyl.center[k];
            c->con.p1[k] = (float)((double)c->cyl.center[k] + c->cyl.axis[k]);
        }
        c->con.r0 = c->cyl.radius, c->con.r1 = r1;
        c->con.flags = c->cyl.flags;
        /* the rays aim at the cylinder of the larger radius about the same ends */
        if (cylray_cylinder_from_endpoints(&aim, c->con.p0, c->con.p1, fmaxf(c->con.r0, r1),
                                           c->con.flags) != CYLRAY_OK)
            aim = c->cyl;
    }
    for (size_t i = 0; i < c->n; i++) {
        float ray[G_NFIELD];
        const uint8_t tag = byte(&r);
        if (tag < 0x80) {
            for (int f = 0; f < G_NFIELD; f++)
                ray[f] = value(&r);
        } else {
            aimed(&r, &aim, ray, tag);
        }
        for (int f = 0; f < G_NFIELD; f++)
            c->rays.f[f][i] = ray[f];
    }
}
