/* SPDX-License-Identifier: MIT */
/* embree/group.c - a geometry's shapes grouped into cylray leaves with Embree's SAH
 * builder (CYLRAY_EMBREE_LEAVES): one primitive per leaf, made by the shape's row. */
#include "ceb.h"

#include <math.h>
#include <stdatomic.h>
#include <stdlib.h>

/* ---- grouping into leaves with Embree's SAH builder ----------------------------- */

/* Leaf l holds the cylinders order[first[l] .. first[l] + count[l]). rtcBuildBVH runs
 * its callbacks on several threads: a leaf takes its slots with atomic counters. */
typedef struct sah_ctx {
    uint32_t *order;
    size_t *first, *count;
    atomic_size_t used, leaves;
} sah_ctx;

static void *sah_node(RTCThreadLocalAllocator al, unsigned n, void *u)
{
    (void)n, (void)u;
    return rtcThreadLocalAlloc(al, 16, 16);
}

static void sah_children(void *node, void **c, unsigned n, void *u)
{
    (void)node, (void)c, (void)n, (void)u;
}

static void sah_bounds(void *node, const struct RTCBounds **b, unsigned n, void *u)
{
    (void)node, (void)b, (void)n, (void)u;
}

static void *sah_leaf(RTCThreadLocalAllocator al, const struct RTCBuildPrimitive *p, size_t n,
                      void *u)
{
    sah_ctx *c = u;
    size_t at = atomic_fetch_add(&c->used, n), l = atomic_fetch_add(&c->leaves, 1);
    for (size_t i = 0; i < n; i++)
        c->order[at + i] = p[i].primID;
    c->first[l] = at;
    c->count[l] = n;
    return rtcThreadLocalAlloc(al, 16, 16);
}

static void box_union(struct RTCBounds *u, const struct RTCBounds *b)
{
    u->lower_x = fminf(u->lower_x, b->lower_x), u->upper_x = fmaxf(u->upper_x, b->upper_x);
    u->lower_y = fminf(u->lower_y, b->lower_y), u->upper_y = fmaxf(u->upper_y, b->upper_y);
    u->lower_z = fminf(u->lower_z, b->lower_z), u->upper_z = fmaxf(u->upper_z, b->upper_z);
}

#define CEB_LEAF_BUILD(M)                                                                      \
    static int build_leaves##M(ceb *g, const sah_ctx *c)                                       \
    {                                                                                          \
        cylray_leaf##M *lv = ceb_alloc_aligned(g->nprim * sizeof *lv);                         \
        if (!lv)                                                                               \
            return CEB_NO_MEMORY;                                                              \
        g->leaves = lv;                                                                        \
        for (size_t l = 0; l < g->nprim; l++)                                                  \
            if (g->shape->leaf##M(&lv[l], g->elems, c->order + c->first[l], c->count[l]) !=    \
                CYLRAY_OK)                                                                     \
                return CEB_REFUSED;                                                            \
        return 0;                                                                              \
    }
CEB_LEAF_BUILD(4)
CEB_LEAF_BUILD(8)

int ceb_group_leaves(ceb *g, RTCDevice dev)
{
    int M = g->m, bad = CEB_NO_MEMORY;
    size_t n = g->n;
    struct RTCBuildPrimitive *prims = ceb_alloc_aligned(n * sizeof *prims);
    sah_ctx c = {.order = malloc(n * sizeof *c.order),
                 .first = malloc(n * sizeof *c.first),
                 .count = malloc(n * sizeof *c.count)};
    atomic_init(&c.used, 0);
    atomic_init(&c.leaves, 0);
    if (prims && c.order && c.first && c.count) {
        for (size_t i = 0; i < n; i++) {
            struct RTCBounds b;
            ceb_box_of(g, i, &b);
            prims[i] = (struct RTCBuildPrimitive){b.lower_x, b.lower_y, b.lower_z, 0,
                                                  b.upper_x, b.upper_y, b.upper_z, (unsigned)i};
        }
        RTCBVH bvh = rtcNewBVH(dev);
        struct RTCBuildArguments a = rtcDefaultBuildArguments();
        a.buildQuality = RTC_BUILD_QUALITY_MEDIUM;
        a.maxDepth = 64;
        /* a leaf is one vector test whether it holds 1 or M: split only above M */
        a.minLeafSize = (unsigned)M;
        a.maxLeafSize = (unsigned)M;
        a.bvh = bvh;
        a.primitives = prims;
        a.primitiveCount = a.primitiveArrayCapacity = n;
        a.createNode = sah_node;
        a.setNodeChildren = sah_children;
        a.setNodeBounds = sah_bounds;
        a.createLeaf = sah_leaf;
        a.userPtr = &c;
        void *root = bvh ? rtcBuildBVH(&a) : NULL;
        if (bvh)
            rtcReleaseBVH(bvh);
        g->nprim = atomic_load(&c.leaves);
        if (!root || atomic_load(&c.used) != n)
            bad = CEB_REFUSED;
        else if ((g->box = malloc(g->nprim * sizeof *g->box)))
            bad = M == 4 ? build_leaves4(g, &c) : build_leaves8(g, &c);
        for (size_t l = 0; !bad && l < g->nprim; l++) {
            const uint32_t *ids = c.order + c.first[l];
            /* the builder reorders prims in place: the boxes are made again */
            for (size_t j = 0; j < c.count[l]; j++) {
                struct RTCBounds b;
                ceb_box_of(g, ids[j], &b);
                if (j == 0)
                    g->box[l] = b;
                box_union(&g->box[l], &b);
            }
        }
    }
    free(prims);
    free(c.order);
    free(c.first);
    free(c.count);
    return bad;
}
