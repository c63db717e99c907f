/* SPDX-License-Identifier: MIT */
/* bvh.h - the examples' BVH: a binned-SAH tree over boxes whose leaves are cylray
 * leaves of LEAF_WIDTH lanes (4, 8 or 16), each holding cylinders or spheres. */
#ifndef EXAMPLE_BVH_H
#define EXAMPLE_BVH_H

#include "cylray.h"

#include <stddef.h>
#include <stdint.h>

#ifndef LEAF_WIDTH
#define LEAF_WIDTH 8
#endif

/* The leaf calls of the chosen width. */
#define LW_CAT_(a, b) a##b
#define LW_CAT(a, b) LW_CAT_(a, b)
#define LW(name) LW_CAT(name, LEAF_WIDTH)
typedef LW(cylray_leaf) leaf_t;

typedef struct bvh_node {
    float lo[3], hi[3];
    uint32_t index; /* inner: the first child (the second follows); leaf: the leaf */
    uint32_t count; /* 0 for an inner node, else the number of shapes in the leaf */
} bvh_node;

typedef struct bvh {
    bvh_node *nodes;
    leaf_t *leaves;
    uint32_t *leaf_ids; /* for packet paths: leaf l's ids at l * LEAF_WIDTH + lane */
    size_t nnodes, nleaves;
} bvh;

/* A shape to place: its box (cylray_bounds) and the id its leaf reports. */
typedef struct bvh_item {
    float lo[3], hi[3], c[3]; /* c: set by bvh_build */
    uint32_t id;
} bvh_item;

/* Makes *leaf from the shapes ids[0..n) (cylray_leaf_prepareM or _spheresM). */
typedef cylray_status (*bvh_leaf_fn)(void *ctx, leaf_t *leaf, const uint32_t *ids, size_t n);

/* Builds t over items[0..n) (reordered); 0 on success. bvh_free releases it (also after
 * a failed build). */
int bvh_build(bvh *t, bvh_item *items, size_t n, bvh_leaf_fn make_leaf, void *ctx);
void bvh_free(bvh *t);

/* The slab test: does the ray o + t / inv meet the node's box within [tmin, tmax]? */
int bvh_hits_box(const bvh_node *nd, const float o[3], const float inv[3], float tmin,
                 float tmax);

/* The closest hit (occlusion when hit is NULL: 1 at the first hit found); on a hit
 * ray->tmax is its t and *leaf_out the leaf that holds the shape. */
int bvh_trace(const bvh *t, cylray_ray1 *ray, cylray_hit1 *hit, unsigned flags,
              const leaf_t **leaf_out);

#endif
