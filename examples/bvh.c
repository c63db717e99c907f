/* SPDX-License-Identifier: MIT */
/* bvh.c - a binned-SAH BVH over boxes, whose leaves are cylray leaves of one shape
 * (cylinders or spheres: the caller makes them), traced one ray at a time. */
#include "bvh.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static float area(const float lo[3], const float hi[3])
{
    float e[3] = {hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]};
    return e[0] * e[1] + e[1] * e[2] + e[2] * e[0];
}

static void grow(float lo[3], float hi[3], const float l[3], const float h[3])
{
    for (int k = 0; k < 3; k++)
        lo[k] = fminf(lo[k], l[k]), hi[k] = fmaxf(hi[k], h[k]);
}

#define NBINS 12

/* Builds the subtree of it[0..n) into node ni; returns 0 on success. */
static int build(bvh *t, bvh_item *it, size_t n, size_t ni, bvh_leaf_fn make_leaf, void *ctx)
{
    bvh_node *nd = &t->nodes[ni];
    float lo[3] = {FLT_MAX, FLT_MAX, FLT_MAX}, hi[3] = {-FLT_MAX, -FLT_MAX, -FLT_MAX};
    float clo[3] = {FLT_MAX, FLT_MAX, FLT_MAX}, chi[3] = {-FLT_MAX, -FLT_MAX, -FLT_MAX};
    for (size_t i = 0; i < n; i++) {
        grow(lo, hi, it[i].lo, it[i].hi);
        grow(clo, chi, it[i].c, it[i].c);
    }
    int best_axis = -1;
    size_t best_split = 0;
    float best_cost = INFINITY;
    if (n > LEAF_WIDTH) {
        for (int k = 0; k < 3; k++) {
            float ext = chi[k] - clo[k];
            if (!(ext > 0))
                continue;
            size_t cnt[NBINS] = {0};
            float blo[NBINS][3], bhi[NBINS][3];
            for (int b = 0; b < NBINS; b++)
                for (int j = 0; j < 3; j++)
                    blo[b][j] = FLT_MAX, bhi[b][j] = -FLT_MAX;
            for (size_t i = 0; i < n; i++) {
                int b = (int)((it[i].c[k] - clo[k]) / ext * NBINS);
                b = b < 0 ? 0 : b >= NBINS ? NBINS - 1 : b;
                cnt[b]++;
                grow(blo[b], bhi[b], it[i].lo, it[i].hi);
            }
            /* cost of splitting after bin s: area-weighted counts of both sides */
            float rlo[3] = {FLT_MAX, FLT_MAX, FLT_MAX}, rhi[3] = {-FLT_MAX, -FLT_MAX, -FLT_MAX};
            float rarea[NBINS];
            size_t rcnt[NBINS], r = 0;
            for (int b = NBINS - 1; b > 0; b--) {
                grow(rlo, rhi, blo[b], bhi[b]);
                r += cnt[b];
                rarea[b] = area(rlo, rhi), rcnt[b] = r;
            }
            float llo[3] = {FLT_MAX, FLT_MAX, FLT_MAX}, lhi[3] = {-FLT_MAX, -FLT_MAX, -FLT_MAX};
            size_t l = 0;
            for (int b = 0; b < NBINS - 1; b++) {
                grow(llo, lhi, blo[b], bhi[b]);
                l += cnt[b];
                if (!l || !rcnt[b + 1])
                    continue;
                float cost = area(llo, lhi) * (float)l + rarea[b + 1] * (float)rcnt[b + 1];
                if (cost < best_cost)
                    best_cost = cost, best_axis = k, best_split = (size_t)b;
            }
        }
    }
    if (best_axis < 0 && n > LEAF_WIDTH) { /* all centroids alike: split the list */
        best_axis = 0;
        best_split = NBINS;
    }
    if (n <= LEAF_WIDTH) {
        uint32_t ids[LEAF_WIDTH];
        for (size_t i = 0; i < n; i++)
            ids[i] = it[i].id;
        leaf_t *leaf = &t->leaves[t->nleaves];
        if (make_leaf(ctx, leaf, ids, n) != CYLRAY_OK)
            return -1;
        /* the leaf's box: one call, rounded outward, the exact shapes inside */
        if (LW(cylray_leaf_bounds)(leaf, nd->lo, nd->hi) != CYLRAY_OK)
            return -1;
        memcpy(&t->leaf_ids[t->nleaves * LEAF_WIDTH], ids, n * sizeof ids[0]);
        nd->index = (uint32_t)t->nleaves++;
        nd->count = (uint32_t)n;
        return 0;
    }
    size_t mid = 0;
    if (best_split == NBINS) {
        mid = n / 2;
    } else {
        int k = best_axis;
        float ext = chi[k] - clo[k];
        for (size_t i = 0; i < n; i++) {
            int b = (int)((it[i].c[k] - clo[k]) / ext * NBINS);
            b = b < 0 ? 0 : b >= NBINS ? NBINS - 1 : b;
            if ((size_t)b <= best_split) {
                bvh_item tmp = it[i];
                it[i] = it[mid];
                it[mid++] = tmp;
            }
        }
    }
    memcpy(nd->lo, lo, sizeof lo);
    memcpy(nd->hi, hi, sizeof hi);
    size_t first = t->nnodes;
    t->nnodes += 2;
    nd->index = (uint32_t)first;
    nd->count = 0;
    if (build(t, it, mid, first, make_leaf, ctx))
        return -1;
    return build(t, it + mid, n - mid, first + 1, make_leaf, ctx);
}

int bvh_build(bvh *t, bvh_item *items, size_t n, bvh_leaf_fn make_leaf, void *ctx)
{
    memset(t, 0, sizeof *t);
    t->nodes = malloc(2 * n * sizeof *t->nodes);
    /* leaves need their vector alignment: aligned_alloc, a multiple of it in size */
    t->leaves = aligned_alloc(_Alignof(leaf_t), n * sizeof(leaf_t));
    t->leaf_ids = malloc(n * LEAF_WIDTH * sizeof *t->leaf_ids);
    if (!n || !t->nodes || !t->leaves || !t->leaf_ids)
        return -1;
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < 3; k++)
            items[i].c[k] = 0.5f * (items[i].lo[k] + items[i].hi[k]);
    t->nnodes = 1;
    return build(t, items, n, 0, make_leaf, ctx);
}

void bvh_free(bvh *t)
{
    free(t->nodes);
    free(t->leaves);
    free(t->leaf_ids);
}

/* The slab test: does the ray meet the box within [tmin, tmax]? */
int bvh_hits_box(const bvh_node *nd, const float o[3], const float inv[3], float tmin,
                 float tmax)
{
    for (int k = 0; k < 3; k++) {
        float t0 = (nd->lo[k] - o[k]) * inv[k], t1 = (nd->hi[k] - o[k]) * inv[k];
        if (t0 > t1) {
            float s = t0;
            t0 = t1, t1 = s;
        }
        /* NaN (0 * inf: the origin on a slab of a parallel ray) keeps the bound */
        tmin = t0 > tmin ? t0 : tmin;
        tmax = t1 < tmax ? t1 : tmax;
    }
    return tmin <= tmax;
}

int bvh_trace(const bvh *t, cylray_ray1 *ray, cylray_hit1 *hit, unsigned flags,
              const leaf_t **leaf_out)
{
    float inv[3];
    for (int k = 0; k < 3; k++)
        inv[k] = 1.0f / ray->d[k];
    uint32_t stack[64];
    int sp = 0, found = 0;
    stack[sp++] = 0;
    while (sp) {
        const bvh_node *nd = &t->nodes[stack[--sp]];
        if (!bvh_hits_box(nd, ray->o, inv, ray->tmin, ray->tmax))
            continue;
        if (nd->count) {
            const leaf_t *leaf = &t->leaves[nd->index];
            if (!hit) {
                if (LW(cylray_leaf_occluded)(leaf, ray, flags))
                    return 1;
            } else if (LW(cylray_leaf_intersect)(leaf, ray, hit, flags)) {
                found = 1; /* ray->tmax is now the hit's t: farther boxes drop out */
                *leaf_out = leaf;
            }
            continue;
        }
        /* the nearer child (by the ray's sign on the parent's widest axis) last, so
         * that it is popped first */
        int k = 0;
        for (int j = 1; j < 3; j++)
            if (nd->hi[j] - nd->lo[j] > nd->hi[k] - nd->lo[k])
                k = j;
        uint32_t a = nd->index, b = nd->index + 1;
        if (ray->d[k] < 0) {
            uint32_t s = a;
            a = b, b = s;
        }
        stack[sp++] = b;
        stack[sp++] = a;
    }
    return found;
}
