/* SPDX-License-Identifier: MIT */
/* geom.c - builds the Embree scenes of one eb_scene: Embree's cone curves (per-vertex
 * radii in a tapered scene), and cylray's adapter in its three arrangements. */
#include "geom.h"

#include "clocks.h"

#include <math.h>
#include <string.h>

const char *eb_variant_name(eb_variant v)
{
    static const char *const n[EB_NVARIANTS] = {"embree-curve", "cylray-single", "cylray-split",
                                                "cylray-leaf"};
    return v < EB_NVARIANTS ? n[v] : "?";
}

unsigned eb_cylray_options;
unsigned eb_leaf_options = CYLRAY_EMBREE_LEAVES | CYLRAY_EMBREE_NO_SPLIT;

unsigned eb_variant_options(eb_variant v)
{
    return eb_cylray_options | (v == EB_SPLIT  ? CYLRAY_EMBREE_SPLIT
                                : v == EB_LEAF ? eb_leaf_options
                                               : CYLRAY_EMBREE_NO_SPLIT);
}

cylray_embree_desc eb_scene_desc(const eb_scene *s, unsigned options, const cylray_kernels *k)
{
    return (cylray_embree_desc){
        .count = s->ns,
        .p0 = s->p0[0],
        .p0_stride = sizeof s->p0[0],
        .p1 = s->p1[0],
        .p1_stride = sizeof s->p1[0],
        .radius = s->cone ? &s->cone[0].r0 : &s->radius,
        .radius_stride = s->cone ? sizeof s->cone[0] : 0,
        .caps = s->caps,
        .caps_stride = sizeof s->caps[0],
        .options = options,
        .kernels = k,
        /* a tapered scene's cones: r0 and r1 from its cone table */
        .radius1 = s->cone ? &s->cone[0].r1 : NULL,
        .radius1_stride = sizeof s->cone[0],
    };
}

cylray_embree_sphere_desc eb_sphere_desc(const eb_scene *s, unsigned options,
                                         const cylray_kernels *k)
{
    return (cylray_embree_sphere_desc){
        .count = s->nsph,
        .center = s->nsph ? s->sph[0].center : NULL,
        .center_stride = sizeof s->sph[0],
        .radius = s->nsph ? &s->sph[0].radius : NULL,
        .radius_stride = sizeof s->sph[0],
        .options = options,
        .kernels = k,
    };
}

void eb_shape_bounds(const eb_scene *s, uint32_t id, struct RTCBounds *b)
{
    if (!(id & EB_SPHERE_BIT)) {
        eb_cylinder_bounds(s, id, b);
        return;
    }
    const cylray_sphere *sp = &s->sph[id & ~EB_SPHERE_BIT];
    float lo[3], hi[3];
    for (int k = 0; k < 3; k++) {
        double c = sp->center[k], r = sp->radius * (1 + 0x1p-18);
        double pad = 0x1p-20 * (fabs(c) + r);
        lo[k] = nextafterf((float)(c - r - pad), -INFINITY);
        hi[k] = nextafterf((float)(c + r + pad), INFINITY);
    }
    b->lower_x = lo[0], b->lower_y = lo[1], b->lower_z = lo[2];
    b->upper_x = hi[0], b->upper_y = hi[1], b->upper_z = hi[2];
}

void eb_cylinder_bounds(const eb_scene *s, uint32_t i, struct RTCBounds *b)
{
    const float *p = s->p0[i], *q = s->p1[i];
    double a[3], aa = 0;
    for (int k = 0; k < 3; k++)
        a[k] = (double)q[k] - p[k], aa += a[k] * a[k];
    /* a cone lies within the cylinder of its larger radius */
    double R = s->vrad ? fmax(s->vrad[s->first[i]], s->vrad[s->first[i] + 1]) : s->radius;
    float lo[3], hi[3];
    for (int k = 0; k < 3; k++) {
        /* a disc of radius r perpendicular to a reaches r sqrt(1 - a_k^2) along k */
        double e = R * sqrt(fmax(0.0, 1 - a[k] * a[k] / aa)) * (1 + 0x1p-18);
        double mn = fmin(p[k], q[k]) - e, mx = fmax(p[k], q[k]) + e;
        double pad = 0x1p-20 * fmax(fabs(mn), fabs(mx)) + 0x1p-20 * R;
        lo[k] = nextafterf((float)(mn - pad), -INFINITY);
        hi[k] = nextafterf((float)(mx + pad), INFINITY);
    }
    b->lower_x = lo[0], b->lower_y = lo[1], b->lower_z = lo[2];
    b->upper_x = hi[0], b->upper_y = hi[1], b->upper_z = hi[2];
}

static RTCGeometry native_geometry(RTCDevice dev, const eb_scene *s)
{
    RTCGeometry geo = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_CONE_LINEAR_CURVE);
    float *v = rtcSetNewGeometryBuffer(geo, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4,
                                       4 * sizeof(float), s->nv);
    unsigned *idx = rtcSetNewGeometryBuffer(geo, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT,
                                            sizeof(unsigned), s->ns);
    unsigned char *fl =
        rtcSetNewGeometryBuffer(geo, RTC_BUFFER_TYPE_FLAGS, 0, RTC_FORMAT_UCHAR, 1, s->ns);
    if (!v || !idx || !fl) {
        rtcReleaseGeometry(geo);
        return NULL;
    }
    for (size_t i = 0; i < s->nv; i++) {
        memcpy(v + 4 * i, s->vert[i], 3 * sizeof(float));
        v[4 * i + 3] = s->vrad ? s->vrad[i] : s->radius;
    }
    /* A segment is closed where it has no neighbour: Embree caps a cone curve's end
     * unless the flag says a segment joins there. */
    for (size_t i = 0; i < s->ns; i++) {
        idx[i] = s->first[i];
        fl[i] =
            (unsigned char)(((s->caps[i] & CYLRAY_CAPPED_LO) ? 0
                                                             : RTC_CURVE_FLAG_NEIGHBOR_LEFT) |
                            ((s->caps[i] & CYLRAY_CAPPED_HI) ? 0
                                                             : RTC_CURVE_FLAG_NEIGHBOR_RIGHT));
    }
    return geo;
}

/* Embree's own spheres: sphere points, the radius in each vertex's fourth float. */
static RTCGeometry native_spheres(RTCDevice dev, const eb_scene *s)
{
    RTCGeometry geo = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_SPHERE_POINT);
    float *v = rtcSetNewGeometryBuffer(geo, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4,
                                       4 * sizeof(float), s->nsph);
    if (!v) {
        rtcReleaseGeometry(geo);
        return NULL;
    }
    for (size_t i = 0; i < s->nsph; i++) {
        memcpy(v + 4 * i, s->sph[i].center, 3 * sizeof(float));
        v[4 * i + 3] = s->sph[i].radius;
    }
    return geo;
}

int eb_geom_build(eb_geom *g, RTCDevice dev, const eb_scene *s, eb_variant v,
                  const cylray_kernels *k)
{
    memset(g, 0, sizeof *g);
    g->variant = v;
    g->src = s;
    double t0 = eb_wall_s();
    RTCGeometry geo = NULL, sph = NULL;
    if (v == EB_NATIVE) {
        geo = s->ns ? native_geometry(dev, s) : NULL;
        sph = s->nsph ? native_spheres(dev, s) : NULL;
        g->nprim = s->ns + s->nsph;
    } else {
        cylray_embree_desc d = eb_scene_desc(s, eb_variant_options(v), k);
        /* a sphere's box is tight: the spheres of the split variant are the single's */
        cylray_embree_sphere_desc e =
            eb_sphere_desc(s, eb_cylray_options | (v == EB_LEAF ? eb_leaf_options : 0u), k);
        geo = g->cyl = s->ns ? cylray_embree_new_geometry(dev, &d, NULL) : NULL;
        sph = g->sph = s->nsph ? cylray_embree_new_spheres(dev, &e, NULL) : NULL;
        g->nprim = cylray_embree_primitives(geo) + cylray_embree_primitives(sph);
    }
    if ((s->ns && !geo) || (s->nsph && !sph)) {
        if (v == EB_NATIVE) {
            if (geo)
                rtcReleaseGeometry(geo);
            if (sph)
                rtcReleaseGeometry(sph);
        }
        eb_geom_free(g);
        return -1;
    }
    g->scene = rtcNewScene(dev);
    if (geo) {
        rtcCommitGeometry(geo);
        rtcAttachGeometryByID(g->scene, geo, 0);
    }
    if (sph) {
        rtcCommitGeometry(sph);
        rtcAttachGeometryByID(g->scene, sph, EB_SPHERE_GEOM);
    }
    /* the scene holds the geometries now; the adapter's are released in eb_geom_free */
    if (v == EB_NATIVE) {
        if (geo)
            rtcReleaseGeometry(geo);
        if (sph)
            rtcReleaseGeometry(sph);
    }
    rtcCommitScene(g->scene);
    g->build_s = eb_wall_s() - t0;
    return rtcGetDeviceError(dev) == RTC_ERROR_NONE ? 0 : -1;
}

void eb_geom_free(eb_geom *g)
{
    if (g->scene)
        rtcReleaseScene(g->scene);
    /* after the scene: nothing traces the geometry any more */
    cylray_embree_release_geometry(g->cyl);
    cylray_embree_release_geometry(g->sph);
    memset(g, 0, sizeof *g);
}
