/* SPDX-License-Identifier: MIT */
/* split_rods.c - what cylray_split_boxes saves a BVH: long thin rods (1,000 rods 10,000
 * radii long, along the coordinate axes or 1.1 to 6.4 degrees off them, around a point
 * 48,000 units from the origin, the camera among them: the far-rods scene of the
 * Embree comparison), traced through their boxes front to back as a BVH does, one box per rod
 * against the boxes of cylray_split_boxes.
 *
 *   split_rods [-s WxH] [-k K]     (K: boxes per rod for the last column; 0: the rule)
 *
 * For each camera ray it collects the boxes the ray enters, in order of entry, and
 * intersects a box's cylinder while the entry lies before the closest hit so far: the
 * calls a BVH makes to user geometry, without the BVH's own overhead. It prints the
 * calls per ray for each way of boxing, and fails if any ray's closest hit differs
 * between them (every box stands for its whole cylinder: no seams) or if the rule's
 * boxes do not save calls. */
#include "cylray.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define NRODS 1000

static uint64_t rng_state = 0x2545f4914f6cdd1du;
static double rnd(void) /* [0, 1): splitmix64 */
{
    uint64_t z = (rng_state += 0x9e3779b97f4a7c15u);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9u;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebu;
    return (double)((z ^ (z >> 31)) >> 11) * 0x1p-53;
}

typedef struct box {
    float lo[3], hi[3];
    uint32_t rod;
    float t; /* entry distance of the current ray */
} box;

static int by_t(const void *a, const void *b)
{
    float x = ((const box *)a)->t, y = ((const box *)b)->t;
    return (x > y) - (x < y);
}

/* Where the ray enters the box, or INFINITY. */
static float enter(const box *b, const float o[3], const float inv[3])
{
    float t0 = 0, t1 = INFINITY;
    for (int k = 0; k < 3; k++) {
        float a = (b->lo[k] - o[k]) * inv[k], c = (b->hi[k] - o[k]) * inv[k];
        if (a > c) {
            float s = a;
            a = c, c = s;
        }
        t0 = a > t0 ? a : t0;
        t1 = c < t1 ? c : t1;
    }
    return t0 <= t1 ? t0 : INFINITY;
}

/* One camera ray through the boxes, front to back; returns the closest t (INFINITY on
 * a miss) and adds the cylinder calls to *calls. */
static float trace(const cylray_prepared *rods, box *bx, size_t nb, box *hit, const float o[3],
                   const float d[3], long *calls)
{
    float inv[3] = {1 / d[0], 1 / d[1], 1 / d[2]};
    size_t n = 0;
    for (size_t i = 0; i < nb; i++) {
        float t = enter(&bx[i], o, inv);
        if (t < INFINITY) {
            hit[n] = bx[i];
            hit[n++].t = t;
        }
    }
    qsort(hit, n, sizeof *hit, by_t);
    cylray_ray4 r;
    cylray_hit4 h;
    memset(&r, 0, sizeof r);
    r.ox[0] = o[0], r.oy[0] = o[1], r.oz[0] = o[2];
    r.dx[0] = d[0], r.dy[0] = d[1], r.dz[0] = d[2];
    r.tmin[0] = 0, r.tmax[0] = INFINITY;
    for (size_t i = 0; i < n && hit[i].t <= r.tmax[0]; i++) {
        (*calls)++;
        cylray_intersect4(&rods[hit[i].rod], &r, &h, 1u, 0);
    }
    return r.tmax[0];
}

int main(int argc, char **argv)
{
    int w = 160, h = 120;
    size_t kfix = 8;
    for (int i = 1; i + 1 < argc; i += 2) {
        if (!strcmp(argv[i], "-s"))
            sscanf(argv[i + 1], "%dx%d", &w, &h);
        else if (!strcmp(argv[i], "-k"))
            kfix = (size_t)atoi(argv[i + 1]);
    }
    const double C[3] = {41000, 23000, 11000};
    cylray_prepared *rods = aligned_alloc(64, NRODS * sizeof *rods);
    size_t cap = NRODS * (size_t)(kfix > CYLRAY_SPLIT_MAX ? kfix : CYLRAY_SPLIT_MAX);
    box *bx[3], *hit = malloc(cap * sizeof *hit);
    size_t nb[3] = {0, 0, 0};
    for (int m = 0; m < 3; m++)
        bx[m] = malloc(cap * sizeof *bx[m]);
    float(*lo)[3] = malloc(cap * sizeof *lo), (*hi)[3] = malloc(cap * sizeof *hi);
    if (!rods || !hit || !bx[0] || !bx[1] || !bx[2] || !lo || !hi)
        return 1;
    for (int i = 0; i < NRODS; i++) {
        float p0[3], p1[3];
        /* along a coordinate axis (a third of them) or 1.1 to 6.4 degrees off one, in a
         * coordinate plane: (a, b, len) with a^2 + b^2 = len^2, permuted and signed */
        static const int q[6][3] = {{0, 1, 1},         {0, 1, 1},      {200, 9999, 10001},
                                    {120, 3599, 3601}, {60, 899, 901}, {36, 323, 325}};
        static const int P[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2},
                                    {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
        const int *qi = q[(int)(rnd() * 6)], *pi = P[(int)(rnd() * 6)];
        const double a[3] = {0, qi[0], qi[1]};
        double u[3];
        for (int k = 0; k < 3; k++)
            u[k] = a[pi[k]] / qi[2] * (rnd() < 0.5 ? -1 : 1);
        for (int k = 0; k < 3; k++) {
            double c = C[k] + 300 * rnd() - 150;
            p0[k] = (float)(c - 1250 * u[k]);
            p1[k] = (float)(c + 1250 * u[k]);
        }
        cylray_cylinder cy;
        if (cylray_cylinder_from_endpoints(&cy, p0, p1, 0.25f, 0) != CYLRAY_OK ||
            cylray_prepare(&rods[i], &cy) != CYLRAY_OK)
            return 1;
        /* one box, the rule's boxes, and kfix boxes */
        size_t ks[3] = {1, 0, kfix};
        for (int m = 0; m < 3; m++) {
            size_t k = cylray_split_boxes(&rods[i], ks[m], lo, hi);
            for (size_t j = 0; j < k; j++) {
                box *b = &bx[m][nb[m]++];
                memcpy(b->lo, lo[j], sizeof b->lo);
                memcpy(b->hi, hi[j], sizeof b->hi);
                b->rod = (uint32_t)i;
            }
        }
    }
    const float eye[3] = {(float)C[0] - 260, (float)C[1] + 40, (float)C[2] - 190};
    float fwd[3] = {260, -40, 190}, l = sqrtf(260 * 260 + 40 * 40 + 190 * 190);
    for (int k = 0; k < 3; k++)
        fwd[k] /= l;
    float right[3] = {-fwd[2], 0, fwd[0]}, rl = sqrtf(fwd[2] * fwd[2] + fwd[0] * fwd[0]);
    for (int k = 0; k < 3; k++)
        right[k] /= rl;
    float up[3] = {right[1] * fwd[2] - right[2] * fwd[1], right[2] * fwd[0] - right[0] * fwd[2],
                   right[0] * fwd[1] - right[1] * fwd[0]};
    const float tan_half = 0.2679492f; /* tan 15 degrees: a 30 degree field of view */
    long calls[3] = {0, 0, 0}, hits = 0, differ = 0, rays = 0;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            float sx = (2 * (x + 0.5f) / w - 1) * tan_half * w / h;
            float sy = (1 - 2 * (y + 0.5f) / h) * tan_half, d[3];
            for (int k = 0; k < 3; k++)
                d[k] = fwd[k] + sx * right[k] + sy * up[k];
            float t[3];
            for (int m = 0; m < 3; m++)
                t[m] = trace(rods, bx[m], nb[m], hit, eye, d, &calls[m]);
            rays++;
            hits += t[0] < INFINITY;
            differ += t[1] != t[0] || t[2] != t[0];
        }
    printf("split_rods: %d rods (R 0.25, length 2500), %ld camera rays, %ld hit\n", NRODS, rays,
           hits);
    printf("  one box per rod:        %6zu boxes, %7.2f cylinder calls per ray\n", nb[0],
           (double)calls[0] / (double)rays);
    printf("  the rule (k = 0):       %6zu boxes, %7.2f cylinder calls per ray\n", nb[1],
           (double)calls[1] / (double)rays);
    printf("  k = %-3zu                 %6zu boxes, %7.2f cylinder calls per ray\n", kfix,
           nb[2], (double)calls[2] / (double)rays);
    printf("  rays whose closest hit differs between them: %ld\n", differ);
    free(lo);
    free(hi);
    for (int m = 0; m < 3; m++)
        free(bx[m]);
    free(hit);
    free(rods);
    /* the point of the split: fewer calls; and no seams */
    return differ != 0 || calls[1] >= calls[0];
}
