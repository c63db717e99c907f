/* SPDX-License-Identifier: MIT */
/* spawn_speed.c - cylspawnspeed: the cost of a secondary ray's start (hit point plus
 * origin) per ray, cylray's batched forms on every path beside pbrt-v4's scheme, on the
 * same hits in the same run, with each scheme's self-intersection rate.
 *
 *   cylspawnspeed [--rays=N] [--reps=N] [--quick]
 *
 * The hits: for each category of tests/ref's generator, one cylinder and the hits of
 * N / 8 rays shared by it (a stream per cylinder, as a tracer sorting its hits by
 * cylinder or leaf would have). Each hit gets one new direction: reflected or
 * transmitted about the exact normal at the hit point, or toward a light (tests/spawn).
 *
 * The rows, all point + origin for every hit, timed over the same arrays:
 *   pbrt-v4         pbrt-v4's scheme as a scalar float loop: the point o + t d projected
 *                   radially onto the side (axially onto a cap's plane), the bound
 *                   gamma(3) |p_k| per coordinate, OffsetRayOrigin: the origin moved
 *                   along the normal by sum |n_k| err_k, to w's side, each coordinate
 *                   pushed one float further in the direction of its move
 *   cylray <isa>    that path's cylray_hit_points_stream + cylray_spawn_stream
 *   cylray leaves   that path's leaves in bulk (cylray_leaf_hit_points8 +
 *                   cylray_leaf_spawn_origins8), one leaf of 8 per cylinder
 *   cylray 1 ray    the scalar pair, cylray_hit_point + cylray_spawn_origin, per hit
 * Timing: one warm-up pass of every row, then --reps rounds, each timing every row once
 * in turn (so that a slow moment of the machine falls on all rows alike) over several
 * passes of all the hits; the median round per row, in ns per ray, and its ratio to
 * pbrt-v4's median. Every output is read into a checksum afterwards, so no pass can be
 * left out by the compiler.
 * Self-intersections: each scheme's origins traced (tmin = 0) by the best path against
 * the cylinder left; a hit of the surface left at the point left counts
 * (tests/spawn/spawnref.h). */
#include "clock.h"
#include "machine.h"
#include "spawnref.h"

#include "cylray.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* One cylinder's hits, in SoA, and what every scheme writes. */
typedef struct stream {
    cylray_cylinder cyl;
    cylray_prepared P;
    cylray_leaf8 *leaf;
    size_t n;
    float *ox, *oy, *oz, *dx, *dy, *dz, *tmin, *tmax, *t;
    int32_t *part;
    float *wx, *wy, *wz, *wmax;  /* new directions, and tmax for them */
    float *px, *py, *pz, *err;   /* the hit points */
    float *x0, *y0, *z0;         /* the origins */
    const cylray_leaf8 **leaves; /* leaves in bulk: the same leaf for every hit */
    cylray_ray1 *r1;
    cylray_hit1 *h1;
} stream;

static float *falloc(size_t n)
{
    float *p = calloc(n ? n : 1, sizeof *p);
    if (!p) {
        fprintf(stderr, "cylspawnspeed: out of memory\n");
        exit(1);
    }
    return p;
}

/* ---- pbrt-v4's scheme, the peer ------------------------------------------------ */

static inline float next_float_up(float f)
{
    uint32_t b;
    if (f == 0.0f)
        return 0x1p-149f;
    memcpy(&b, &f, sizeof b);
    b = f > 0 ? b + 1 : b - 1;
    memcpy(&f, &b, sizeof f);
    return f;
}

static inline float next_float_down(float f)
{
    uint32_t b;
    if (f == 0.0f)
        return -0x1p-149f;
    memcpy(&b, &f, sizeof b);
    b = f > 0 ? b - 1 : b + 1;
    memcpy(&f, &b, sizeof f);
    return f;
}

/* One hit: the point reprojected in float (pbrt's Cylinder::Intersect: the hit point
 * scaled onto the radius, a cap's onto its plane), the error bound gamma(3)|p_k| and
 * OffsetRayOrigin. A scalar loop: vectorising it would no longer be the peer. */
#if defined(__GNUC__) && !defined(__clang__)
__attribute__((optimize("no-tree-vectorize")))
#endif
static void
pbrt_stream(const stream *s)
{
    const cylray_prepared *P = &s->P;
    const float cx = P->c[0], cy = P->c[1], cz = P->c[2];
    const float ax = P->n[0], ay = P->n[1], az = P->n[2];
    const float R = P->radius, H = P->half_height;
    const float g3 = 3 * 0x1p-24f / (1 - 3 * 0x1p-24f);
#if defined(__clang__)
#pragma clang loop vectorize(disable)
#endif
    for (size_t i = 0; i < s->n; i++) {
        const float t = s->t[i];
        float p[3] = {s->ox[i] + t * s->dx[i], s->oy[i] + t * s->dy[i],
                      s->oz[i] + t * s->dz[i]};
        const float qx = p[0] - cx, qy = p[1] - cy, qz = p[2] - cz;
        const float z = qx * ax + qy * ay + qz * az;
        const float rx = qx - z * ax, ry = qy - z * ay, rz = qz - z * az;
        float n[3];
        if ((s->part[i] & CYLRAY_PART_MASK) == CYLRAY_SIDE) {
            const float l = sqrtf(rx * rx + ry * ry + rz * rz), il = 1.0f / l, g = R * il;
            p[0] = cx + z * ax + rx * g, p[1] = cy + z * ay + ry * g,
            p[2] = cz + z * az + rz * g;
            n[0] = rx * il, n[1] = ry * il, n[2] = rz * il;
        } else {
            const float sg = (s->part[i] & CYLRAY_PART_MASK) == CYLRAY_CAP_HI ? 1.0f : -1.0f;
            const float h = sg * H;
            p[0] = cx + h * ax + rx, p[1] = cy + h * ay + ry, p[2] = cz + h * az + rz;
            n[0] = sg * ax, n[1] = sg * ay, n[2] = sg * az;
        }
        /* pi.Error() = gamma(3) |p|; OffsetRayOrigin */
        const float d = fabsf(n[0]) * g3 * fabsf(p[0]) + fabsf(n[1]) * g3 * fabsf(p[1]) +
                        fabsf(n[2]) * g3 * fabsf(p[2]);
        const float wn = s->wx[i] * n[0] + s->wy[i] * n[1] + s->wz[i] * n[2];
        const float dd = wn < 0 ? -d : d;
        float o[3];
        for (int k = 0; k < 3; k++) {
            const float off = dd * n[k];
            o[k] = p[k] + off;
            if (off > 0)
                o[k] = next_float_up(o[k]);
            else if (off < 0)
                o[k] = next_float_down(o[k]);
        }
        s->px[i] = p[0], s->py[i] = p[1], s->pz[i] = p[2];
        s->x0[i] = o[0], s->y0[i] = o[1], s->z0[i] = o[2];
    }
}

/* ---- cylray's forms ------------------------------------------------------------- */

static void cylray_streams(const cylray_kernels *K, const stream *s)
{
    cylray_rays rays = {s->ox, s->oy, s->oz, s->dx, s->dy, s->dz, s->tmin, s->tmax};
    cylray_hits hits = {s->t, NULL, NULL, NULL, s->part};
    cylray_points pts = {s->px, s->py, s->pz, s->err}, dirs = {s->wx, s->wy, s->wz, NULL};
    cylray_points org = {s->x0, s->y0, s->z0, NULL};
    K->hit_points_stream(&s->P, &rays, &hits, &pts, s->n);
    K->spawn_stream(&s->P, &pts, s->part, &dirs, &org, s->n);
}

static void cylray_leaves(const cylray_kernels *K, const stream *s)
{
    cylray_points pts = {s->px, s->py, s->pz, s->err}, dirs = {s->wx, s->wy, s->wz, NULL};
    cylray_points org = {s->x0, s->y0, s->z0, NULL};
    K->leaf_hit_points8(s->leaves, s->r1, s->h1, &pts, s->n);
    K->leaf_spawn_origins8(s->leaves, s->h1, &pts, &dirs, &org, s->n);
}

static void cylray_single(const stream *s)
{
    for (size_t i = 0; i < s->n; i++) {
        const float o[3] = {s->ox[i], s->oy[i], s->oz[i]},
                    d[3] = {s->dx[i], s->dy[i], s->dz[i]};
        const float w[3] = {s->wx[i], s->wy[i], s->wz[i]};
        float p[3], err, x[3];
        cylray_hit_point(&s->P, o, d, s->t[i], s->part[i], p, &err);
        cylray_spawn_origin(&s->P, p, err, s->part[i], w, x);
        s->px[i] = p[0], s->py[i] = p[1], s->pz[i] = p[2], s->err[i] = err;
        s->x0[i] = x[0], s->y0[i] = x[1], s->z0[i] = x[2];
    }
}

/* ---- rows ---------------------------------------------------------------------- */

enum {
    ROW_PBRT,
    ROW_STREAM0,
    ROW_LEAF0 = ROW_STREAM0 + CYLRAY_ISA_COUNT,
    ROW_SINGLE = ROW_LEAF0 + CYLRAY_ISA_COUNT,
    ROW_COUNT
};

static const cylray_kernels *row_isa(int row)
{
    if (row >= ROW_STREAM0 && row < ROW_LEAF0)
        return cylray_kernels_for((cylray_isa)(row - ROW_STREAM0));
    if (row >= ROW_LEAF0 && row < ROW_SINGLE)
        return cylray_kernels_for((cylray_isa)(row - ROW_LEAF0));
    return NULL;
}

static int row_exists(int row)
{
    return row == ROW_PBRT || row == ROW_SINGLE || row_isa(row) != NULL;
}

static void run_row(int row, const stream *S, size_t ns)
{
    const cylray_kernels *K = row_isa(row);
    for (size_t j = 0; j < ns; j++) {
        if (row == ROW_PBRT)
            pbrt_stream(&S[j]);
        else if (row == ROW_SINGLE)
            cylray_single(&S[j]);
        else if (row < ROW_LEAF0)
            cylray_streams(K, &S[j]);
        else
            cylray_leaves(K, &S[j]);
    }
}

/* The checksum of every output, read after the timed passes: a sum of the outputs'
 * bits, so that a NaN output (a miss's untouched lane) does not swallow the rest. */
static uint64_t checksum(const stream *S, size_t ns)
{
    uint64_t c = 0;
    for (size_t j = 0; j < ns; j++)
        for (size_t i = 0; i < S[j].n; i++) {
            const float f[4] = {S[j].x0[i], S[j].y0[i], S[j].z0[i], S[j].px[i]};
            for (int k = 0; k < 4; k++) {
                uint32_t b;
                memcpy(&b, &f[k], sizeof b);
                c = c * 0x100000001b3u + b;
            }
        }
    return c;
}

/* Self-intersections of the origins in S: each traced by the best path. */
static long self_hits(const stream *S, size_t ns, long *traced)
{
    const cylray_kernels *K = cylray_kernels_best();
    long self = 0;
    *traced = 0;
    for (size_t j = 0; j < ns; j++) {
        const stream *s = &S[j];
        for (size_t b = 0; b < s->n; b += 16) {
            cylray_ray16 r;
            cylray_hit16 h;
            memset(&r, 0, sizeof r);
            const size_t c = s->n - b < 16 ? s->n - b : 16;
            for (size_t i = 0; i < c; i++) {
                r.ox[i] = s->x0[b + i], r.oy[i] = s->y0[b + i], r.oz[i] = s->z0[b + i];
                r.dx[i] = s->wx[b + i], r.dy[i] = s->wy[b + i], r.dz[i] = s->wz[b + i];
                r.tmin[i] = 0.0f, r.tmax[i] = s->wmax[b + i];
            }
            const uint32_t got = K->intersect16(&s->P, &r, &h, (uint32_t)((1ull << c) - 1u), 0);
            *traced += (long)c;
            for (size_t i = 0; i < c; i++) {
                const float x0[3] = {s->x0[b + i], s->y0[b + i], s->z0[b + i]};
                const float w[3] = {s->wx[b + i], s->wy[b + i], s->wz[b + i]};
                if ((got >> i & 1u) &&
                    sref_self_hit(&s->cyl, x0, w, s->part[b + i], h.part[i], h.t[i]))
                    self++;
            }
        }
    }
    return self;
}

static int cmpd(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

int main(int argc, char **argv)
{
    long nrays = 32768, reps = 21;
    for (int i = 1; i < argc; i++) {
        if (strncmp(argv[i], "--rays=", 7) == 0)
            nrays = atol(argv[i] + 7);
        else if (strncmp(argv[i], "--reps=", 7) == 0)
            reps = atol(argv[i] + 7);
        else if (strcmp(argv[i], "--quick") == 0)
            nrays = 4096, reps = 5;
        else {
            fprintf(stderr, "usage: cylspawnspeed [--rays=N] [--reps=N] [--quick]\n");
            return 2;
        }
    }
    if (nrays < 64 || reps < 1) {
        fprintf(stderr, "cylspawnspeed: --rays must be at least 64 and --reps at least 1\n");
        return 2;
    }
    char pin[64];
    clk_pin(pin, sizeof pin);
    machine_info mi;
    machine_probe(&mi);

    /* the streams: one cylinder per category, its hits */
    const int ncat = cylgen_category_count();
    stream *S = calloc((size_t)ncat, sizeof *S);
    size_t ns = 0, total = 0;
    const size_t per = (size_t)nrays / (size_t)ncat;
    cylgen_case *cs = malloc(per * sizeof *cs);
    cylgen_rng rng;
    cylgen_seed(&rng, 2026);
    const cylray_kernels *best = cylray_kernels_best();
    for (int cat = 0; cat < ncat && cs; cat++) {
        cylgen_make_shared(cat, 777 + (uint64_t)cat, per, cs);
        stream *s = &S[ns];
        s->cyl = cs[0].cyl;
        if (cylray_prepare(&s->P, &s->cyl) != CYLRAY_OK)
            continue;
        float *f[24];
        for (int k = 0; k < 24; k++)
            f[k] = falloc(per);
        s->ox = f[0], s->oy = f[1], s->oz = f[2], s->dx = f[3], s->dy = f[4], s->dz = f[5];
        s->tmin = f[6], s->tmax = f[7], s->t = f[8], s->part = (int32_t *)(void *)f[9];
        s->wx = f[10], s->wy = f[11], s->wz = f[12], s->wmax = f[13];
        s->px = f[14], s->py = f[15], s->pz = f[16], s->err = f[17];
        s->x0 = f[18], s->y0 = f[19], s->z0 = f[20];
        for (int k = 21; k < 24; k++)
            free(f[k]);
        for (size_t i = 0; i < per; i++) {
            s->ox[i] = cs[i].o[0], s->oy[i] = cs[i].o[1], s->oz[i] = cs[i].o[2];
            s->dx[i] = cs[i].d[0], s->dy[i] = cs[i].d[1], s->dz[i] = cs[i].d[2];
            s->tmin[i] = cs[i].tmin, s->tmax[i] = cs[i].tmax;
            s->part[i] = CYLRAY_MISS;
        }
        cylray_rays rays = {s->ox, s->oy, s->oz, s->dx, s->dy, s->dz, s->tmin, s->tmax};
        cylray_hits hits = {s->t, NULL, NULL, NULL, s->part};
        best->intersect_stream(&s->P, &rays, &hits, per, 0);
        /* keep the hits only, in order */
        size_t n = 0;
        for (size_t i = 0; i < per; i++) {
            if ((s->part[i] & CYLRAY_PART_MASK) == CYLRAY_MISS)
                continue;
            s->ox[n] = s->ox[i], s->oy[n] = s->oy[i], s->oz[n] = s->oz[i];
            s->dx[n] = s->dx[i], s->dy[n] = s->dy[i], s->dz[n] = s->dz[i];
            s->tmin[n] = s->tmin[i], s->tmax[n] = s->tmax[i], s->t[n] = s->t[i];
            s->part[n] = s->part[i];
            n++;
        }
        s->n = n;
        if (!n)
            continue;
        /* the new directions, about the exact normal at the hit point */
        for (size_t i = 0; i < n; i++) {
            const float o[3] = {s->ox[i], s->oy[i], s->oz[i]},
                        d[3] = {s->dx[i], s->dy[i], s->dz[i]};
            float p[3], err, w[3];
            double nn[3];
            cylray_hit_point(&s->P, o, d, s->t[i], s->part[i], p, &err);
            sref_normal(&s->cyl, p, s->part[i] & CYLRAY_PART_MASK, nn);
            const int refl = s->part[i] & CYLRAY_BACKFACE ? -1 : 1;
            const int kind = (int)(i % 5);
            s->wmax[i] = INFINITY;
            if (kind == 4) {
                double u[3], dist = s->cyl.radius * exp(cylgen_uniform(&rng) * 7);
                sref_unit(&rng, u);
                for (int k = 0; k < 3; k++)
                    w[k] = (float)(dist * u[k]);
                s->wmax[i] = 1.0f;
            } else {
                sref_direction(&rng, nn, kind < 2 ? refl : -refl, w);
            }
            s->wx[i] = w[0], s->wy[i] = w[1], s->wz[i] = w[2];
        }
        /* a leaf of 8 holding the cylinder in lane 0, and the hits as its queries gave */
        s->leaf = aligned_alloc(64, (sizeof *s->leaf + 63) / 64 * 64);
        s->leaves = malloc(n * sizeof *s->leaves);
        s->r1 = malloc(n * sizeof *s->r1);
        s->h1 = malloc(n * sizeof *s->h1);
        if (!s->leaf || !s->leaves || !s->r1 || !s->h1 ||
            cylray_leaf_prepare8(s->leaf, &s->cyl, NULL, 1) != CYLRAY_OK) {
            fprintf(stderr, "cylspawnspeed: cannot build the leaves\n");
            return 1;
        }
        for (size_t i = 0; i < n; i++) {
            s->leaves[i] = s->leaf;
            cylray_ray1 r = {{s->ox[i], s->oy[i], s->oz[i]},
                             {s->dx[i], s->dy[i], s->dz[i]},
                             s->tmin[i],
                             s->t[i]};
            cylray_hit1 h = {s->t[i], {0, 0, 0}, s->part[i], 0, 0};
            s->r1[i] = r, s->h1[i] = h;
        }
        total += n;
        ns++;
    }
    free(cs);
    if (!total) {
        fprintf(stderr, "cylspawnspeed: no hits\n");
        return 1;
    }

    /* self-intersections per scheme */
    double self_rate[ROW_COUNT];
    long self_n[ROW_COUNT], traced = 0;
    for (int row = 0; row < ROW_COUNT; row++) {
        self_rate[row] = NAN;
        self_n[row] = -1;
        if (!row_exists(row))
            continue;
        run_row(row, S, ns);
        self_n[row] = self_hits(S, ns, &traced);
        self_rate[row] = (double)self_n[row] / (double)traced;
    }

    /* timing: warm-up, then rounds over every row in turn; passes per sample so that a
     * sample takes about 2 ms at 50 ns a ray */
    const int passes = (int)(40000 / (long)total) + 1;
    double *samples = malloc((size_t)reps * ROW_COUNT * sizeof *samples);
    uint64_t sink = 0;
    for (int row = 0; row < ROW_COUNT; row++)
        if (row_exists(row))
            run_row(row, S, ns);
    for (long r = 0; r < reps; r++)
        for (int row = 0; row < ROW_COUNT; row++) {
            if (!row_exists(row))
                continue;
            const double t0 = clk_ns();
            for (int k = 0; k < passes; k++)
                run_row(row, S, ns);
            samples[row * reps + r] = (clk_ns() - t0) / ((double)passes * (double)total);
            sink += checksum(S, ns);
        }
    double med[ROW_COUNT], lo[ROW_COUNT], hi[ROW_COUNT];
    for (int row = 0; row < ROW_COUNT; row++) {
        if (!row_exists(row))
            continue;
        double *v = samples + row * reps;
        qsort(v, (size_t)reps, sizeof *v, cmpd);
        med[row] = v[reps / 2];
        lo[row] = v[0];
        hi[row] = v[reps - 1];
    }

    printf("cylspawnspeed: %zu hits on %zu cylinders (one per category), point + origin "
           "per hit; %ld rounds of %d passes, median\n",
           total, ns, reps, passes);
    printf("machine: %s (%s), %d cores%s, %s, %s; %s\n", mi.cpu, mi.cpuid, mi.cores,
           mi.hypervisor ? " under a hypervisor" : "", mi.compiler, mi.buildtype, pin);
    printf("\n| scheme | ns/ray (median) | min - max | / pbrt-v4 | self-intersections |\n"
           "|---|---|---|---|---|\n");
    for (int row = 0; row < ROW_COUNT; row++) {
        if (!row_exists(row))
            continue;
        char name[64];
        if (row == ROW_PBRT)
            snprintf(name, sizeof name, "pbrt-v4 (scalar float)");
        else if (row == ROW_SINGLE)
            snprintf(name, sizeof name, "cylray scalar pair, one call a ray");
        else if (row < ROW_LEAF0)
            snprintf(name, sizeof name, "cylray %s stream", row_isa(row)->name);
        else
            snprintf(name, sizeof name, "cylray %s leaves in bulk", row_isa(row)->name);
        printf("| %s | %.2f | %.2f - %.2f | %.2f | %ld of %ld (%.3g %%) |\n", name, med[row],
               lo[row], hi[row], med[row] / med[ROW_PBRT], self_n[row], traced,
               100 * self_rate[row]);
    }
    printf("\n(checksum %016llx)\n", (unsigned long long)sink);
    free(samples);
    for (size_t j = 0; j < ns; j++) {
        float *f[21] = {S[j].ox, S[j].oy,   S[j].oz,   S[j].dx,   S[j].dy,
                        S[j].dz, S[j].tmin, S[j].tmax, S[j].t,    (float *)(void *)S[j].part,
                        S[j].wx, S[j].wy,   S[j].wz,   S[j].wmax, S[j].px,
                        S[j].py, S[j].pz,   S[j].err,  S[j].x0,   S[j].y0,
                        S[j].z0};
        for (int k = 0; k < 21; k++)
            free(f[k]);
        free(S[j].leaf);
        free(S[j].leaves);
        free(S[j].r1);
        free(S[j].h1);
    }
    free(S);
    return 0;
}
