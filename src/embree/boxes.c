/* SPDX-License-Identifier: MIT */
/* embree/boxes.c - a cylinder's or cone's frame (the endpoint form and the basis for u,
 * v) and the boxes Embree builds its BVH over: one per shape, or pieces along a long
 * tilted one with a frame (unless CYLRAY_EMBREE_NO_SPLIT). */
#include "ceb.h"

#include <math.h>
#include <stdlib.h>

/* ---- geometry of one cylinder -------------------------------------------------- */

void ceb_frame_init(frame *f, const float p0[3], const float p1[3], float r0, float r1)
{
    double a[3], aa = 0;
    for (int k = 0; k < 3; k++) {
        f->p0[k] = p0[k];
        a[k] = (double)p1[k] - p0[k];
        f->a[k] = (float)a[k];
        aa += a[k] * a[k];
    }
    f->inv_aa = (float)(1.0 / aa);
    double l = sqrt(aa), n[3] = {a[0] / l, a[1] / l, a[2] / l};
    /* Duff et al., "Building an Orthonormal Basis, Revisited" (JCGT 2017) */
    double s = n[2] >= 0 ? 1.0 : -1.0, q = -1.0 / (s + n[2]), b = n[0] * n[1] * q;
    double b1[3] = {1.0 + s * n[0] * n[0] * q, s * b, -s * n[0]};
    double b2[3] = {b, s + n[1] * n[1] * q, -n[1]};
    for (int k = 0; k < 3; k++) {
        f->n[k] = (float)n[k];
        f->b1[k] = (float)b1[k];
        f->b2[k] = (float)b2[k];
    }
    f->pieces = 1;
    double dr = (double)r1 - r0;
    f->ns = (float)(-dr / sqrt(aa + dr * dr)) + 0.0f; /* + 0: no -0 */
}

void ceb_set_box(struct RTCBounds *b, const float lo[3], const float hi[3], float pad)
{
    b->lower_x = lo[0] - pad, b->lower_y = lo[1] - pad, b->lower_z = lo[2] - pad;
    b->upper_x = hi[0] + pad, b->upper_y = hi[1] + pad, b->upper_z = hi[2] + pad;
    b->align0 = b->align1 = 0;
}

/* The box of the whole cylinder: cylray_bounds, the exact box rounded outward. */
void ceb_whole_box(const cylray_prepared *p, struct RTCBounds *b)
{
    float lo[3], hi[3];
    cylray_bounds(p, lo, hi);
    ceb_set_box(b, lo, hi, 0);
}

/* center -+ radius rounded outward, then one float further: the double difference is
 * itself rounded when the two are far apart in magnitude, and a box one ulp too wide
 * costs nothing (cylray_bounds of a sphere is not relied on here). */
void ceb_sphere_box(const cylray_sphere *s, struct RTCBounds *b)
{
    float lo[3], hi[3];
    for (int k = 0; k < 3; k++) {
        double c = s->center[k], r = s->radius;
        float l = (float)(c - r), h = (float)(c + r);
        if ((double)l > c - r)
            l = nextafterf(l, -INFINITY);
        if ((double)h < c + r)
            h = nextafterf(h, INFINITY);
        lo[k] = nextafterf(l, -INFINITY);
        hi[k] = nextafterf(h, INFINITY);
    }
    ceb_set_box(b, lo, hi, 0);
}

/* The whole box of shape i of the geometry. */
void ceb_box_of(const ceb *g, size_t i, struct RTCBounds *b)
{
    g->shape->box(ceb_elem(g, i), &g->prep[i], b);
}

void *ceb_alloc_aligned(size_t bytes)
{
    size_t b = (bytes + 63) / 64 * 64;
    return aligned_alloc(64, b ? b : 64);
}

/* ---- one box a primitive, split along long tilted cylinders --------------------- */

/* Only a cylinder longer than CEB_SPLIT_LENGTH radii is split. A short one's box wastes
 * little room, and its pieces would cost Embree more primitives and each ray that meets
 * it one callback a piece: on the molecule (bonds about 10 radii long) splitting by the
 * box rule alone took 4-6 % more time, on the far rods (1e4 radii) 2.9x less. */
#define CEB_SPLIT_LENGTH 16.0
static int long_for_radius(const frame *f, float radius)
{
    double L2 = 0;
    for (int k = 0; k < 3; k++)
        L2 += (double)f->a[k] * f->a[k];
    return L2 > CEB_SPLIT_LENGTH * CEB_SPLIT_LENGTH * (double)radius * radius;
}

/* Shape i's widest radius: it is split as the cylinder of that radius is. */
static float rmax_of(const ceb *g, size_t i)
{
    return g->shape->rmax(ceb_elem(g, i));
}

/* How many boxes shape i takes: the toolkit's rule (cylray_split_boxes with k = 0), the
 * fewest pieces, at most CYLRAY_SPLIT_MAX, whose boxes are at most twice the cylinder's
 * width across; short or axis-aligned cylinders keep one box, and so does a shape
 * without a frame (no axis to split along). */
static uint32_t pieces_of(const ceb *g, size_t i)
{
    if (!g->fr || !long_for_radius(&g->fr[i], rmax_of(g, i)))
        return 1;
    size_t k = cylray_split_boxes(&g->prep[i], 0, NULL, NULL);
    return k < 1 ? 1u : (uint32_t)k;
}

int ceb_would_split(const ceb *g)
{
    for (size_t i = 0; i < g->n; i++)
        if (pieces_of(g, i) > 1)
            return 1;
    return 0;
}

int ceb_make_boxes(ceb *g)
{
    size_t total = 0;
    const int split = !(g->options & CYLRAY_EMBREE_NO_SPLIT);
    for (size_t i = 0; i < g->n; i++) {
        if (split && g->fr)
            g->fr[i].pieces = pieces_of(g, i);
        total += g->fr ? g->fr[i].pieces : 1;
    }
    if (total > 0xffffffffu)
        return CEB_BAD_INPUT;
    g->nprim = total;
    g->box = malloc(total * sizeof *g->box);
    if (!g->box)
        return CEB_NO_MEMORY;
    if (total == g->n) {
        for (size_t i = 0; i < g->n; i++)
            ceb_box_of(g, i, &g->box[i]);
        return 0;
    }
    g->prim_cyl = malloc(total * sizeof *g->prim_cyl);
    g->prim_piece = malloc(total * sizeof *g->prim_piece);
    float lo[CYLRAY_SPLIT_MAX][3], hi[CYLRAY_SPLIT_MAX][3];
    if (!g->prim_cyl || !g->prim_piece)
        return CEB_NO_MEMORY;
    size_t p = 0;
    for (size_t i = 0; i < g->n; i++) {
        const frame *f = &g->fr[i];
        uint32_t K = f->pieces;
        if (K == 1) {
            ceb_box_of(g, i, &g->box[p]);
            g->prim_cyl[p] = (uint32_t)i;
            g->prim_piece[p++] = 0;
            continue;
        }
        /* cylray_split_boxes' slice k holds the stretch u in [k/K, (k+1)/K] exactly; a
         * hit is owned by the slice its rounded u falls in, so each box reaches beyond
         * its stretch by more than that rounding and the hit point's: 2^-16 of the
         * coordinates and the length, in every direction */
        double big = 0, L = 0;
        for (int k = 0; k < 3; k++) {
            big = fmax(big, fabs(f->p0[k]) + fabs(f->a[k]));
            L += (double)f->a[k] * f->a[k];
        }
        float pad = (float)(0x1p-16 * (big + sqrt(L)) + 0x1p-10 * rmax_of(g, i));
        if (cylray_split_boxes(&g->prep[i], K, lo, hi) != K)
            return CEB_REFUSED;
        for (uint32_t k = 0; k < K; k++, p++) {
            ceb_set_box(&g->box[p], lo[k], hi[k], pad);
            g->prim_cyl[p] = (uint32_t)i;
            g->prim_piece[p] = k;
        }
    }
    return 0;
}
