/* SPDX-License-Identifier: MIT */
/* embree/shapes.c - the rows of the shapes a geometry is built from (ceb_shape, ceb.h):
 * what differs between cylinders, cones and spheres while a geometry is built. A new
 * kind of shape is a new row here and its reading in cylray_embree.c. */
#include "ceb.h"

#include <math.h>
#include <string.h>

/* Elements ids[0..n) of elems (each size bytes) side by side in out, as the leaf
 * preparations take them. */
static void gather(void *out, const void *elems, size_t size, const uint32_t *ids, size_t n)
{
    for (size_t j = 0; j < n; j++)
        memcpy((char *)out + j * size, (const char *)elems + ids[j] * size, size);
}

/* ---- cylinders and cones: a cylray_cone each, r1 = r0 for a cylinder ------------ */

/* A cylinder keeps its endpoint form: the frame needs p0 and p1 as given, which
 * cylray_cylinder's center and axis have rounded. */
static cylray_status cylinder_from(cylray_cylinder *c, const cylray_cone *e)
{
    return cylray_cylinder_from_endpoints(c, e->p0, e->p1, e->r0, e->flags);
}

static cylray_status prepare_cylinder(cylray_prepared *p, const void *e)
{
    cylray_cylinder c;
    cylray_status st = cylinder_from(&c, e);
    return st != CYLRAY_OK ? st : cylray_prepare(p, &c);
}

static cylray_status prepare_cone(cylray_prepared *p, const void *e)
{
    return cylray_prepare_cone(p, e);
}

static void cone_frame(frame *f, const void *e)
{
    const cylray_cone *c = e;
    ceb_frame_init(f, c->p0, c->p1, c->r0, c->r1);
}

static float cone_rmax(const void *e)
{
    const cylray_cone *c = e;
    return fmaxf(c->r0, c->r1);
}

static void prepared_box(const void *e, const cylray_prepared *p, struct RTCBounds *b)
{
    (void)e;
    ceb_whole_box(p, b);
}

/* A leaf of cones whose radii all agree at both ends is built as a leaf of cylinders
 * (cylray_prepare_cone prepares such a cone as that cylinder): a leaf of cylinders
 * alone takes the faster query. 1 when cones ids[0..n) are all of that kind. */
static int all_cylinders(const cylray_cone *cone, const uint32_t *ids, size_t n)
{
    for (size_t j = 0; j < n; j++)
        if (cone[ids[j]].r0 != cone[ids[j]].r1)
            return 0;
    return 1;
}

#define CEB_CONE_LEAVES(M)                                                                     \
    static cylray_status cylinder_leaf##M(cylray_leaf##M *lv, const void *elems,               \
                                          const uint32_t *ids, size_t n)                       \
    {                                                                                          \
        const cylray_cone *e = elems;                                                          \
        cylray_cylinder cc[M];                                                                 \
        for (size_t j = 0; j < n; j++)                                                         \
            if (cylinder_from(&cc[j], &e[ids[j]]) != CYLRAY_OK)                                \
                return CYLRAY_EINVAL;                                                          \
        return cylray_leaf_prepare##M(lv, cc, ids, n);                                         \
    }                                                                                          \
    static cylray_status cone_leaf##M(cylray_leaf##M *lv, const void *elems,                   \
                                      const uint32_t *ids, size_t n)                           \
    {                                                                                          \
        const cylray_cone *e = elems;                                                          \
        if (all_cylinders(e, ids, n))                                                          \
            return cylinder_leaf##M(lv, elems, ids, n);                                        \
        cylray_cone kk[M];                                                                     \
        gather(kk, e, sizeof *e, ids, n);                                                      \
        return cylray_leaf_prepare_cones##M(lv, kk, ids, n);                                   \
    }
CEB_CONE_LEAVES(4)
CEB_CONE_LEAVES(8)

const ceb_shape ceb_cylinders = {
    .size = sizeof(cylray_cone),
    .prepare = prepare_cylinder,
    .frame = cone_frame,
    .rmax = cone_rmax,
    .box = prepared_box,
    .leaf4 = cylinder_leaf4,
    .leaf8 = cylinder_leaf8,
};

const ceb_shape ceb_cones = {
    .size = sizeof(cylray_cone),
    .prepare = prepare_cone,
    .frame = cone_frame,
    .rmax = cone_rmax,
    .box = prepared_box,
    .leaf4 = cone_leaf4,
    .leaf8 = cone_leaf8,
};

/* ---- spheres: a cylray_sphere each ----------------------------------------------- */

static cylray_status prepare_sphere(cylray_prepared *p, const void *e)
{
    return cylray_prepare_sphere(p, e);
}

static void sphere_box(const void *e, const cylray_prepared *p, struct RTCBounds *b)
{
    (void)p;
    ceb_sphere_box(e, b);
}

#define CEB_SPHERE_LEAVES(M)                                                                   \
    static cylray_status sphere_leaf##M(cylray_leaf##M *lv, const void *elems,                 \
                                        const uint32_t *ids, size_t n)                         \
    {                                                                                          \
        cylray_sphere ss[M];                                                                   \
        gather(ss, elems, sizeof ss[0], ids, n);                                               \
        return cylray_leaf_prepare_spheres##M(lv, ss, ids, n);                                 \
    }
CEB_SPHERE_LEAVES(4)
CEB_SPHERE_LEAVES(8)

const ceb_shape ceb_spheres = {
    .size = sizeof(cylray_sphere),
    .prepare = prepare_sphere,
    .frame = NULL,
    .rmax = NULL,
    .box = sphere_box,
    .leaf4 = sphere_leaf4,
    .leaf8 = sphere_leaf8,
    .sphere_test = 1,
};
