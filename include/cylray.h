/* cylray.h - SIMD ray/cylinder intersection kernels: the whole public API.
 * SPDX-License-Identifier: MIT
 *
 * A tracer prepares each cylinder once (cylray_prepare) and then asks for the closest
 * hit of packets of 4, 8 or 16 rays, of streams of any length, or of one ray against a
 * leaf of up to 16 cylinders. The answers are those of exact arithmetic on the float
 * inputs to within a few float ulps, except where changing the inputs by 2 ulps could
 * change the exact answer itself (docs/design.md, section 4).
 *
 * Rays. x(t) = o + t d for t in the closed interval [tmin, tmax]; d need not be unit
 * length. tmin = -INFINITY and tmax = INFINITY mean no bound; a reported t is always
 * finite. A call that finds a hit in [tmin, tmax] writes it and sets tmax = t, and
 * writes nothing otherwise, so a tracer walks its cylinders with the same rays and
 * keeps the closest hit. Because the interval is closed, a later cylinder hit at
 * exactly the current tmax replaces the earlier hit: of hits at the same t the last
 * call wins (within one leaf, the lowest lane).
 *
 * Rays in an end's plane. The solid is closed: a ray lying in the plane of an end
 * (d.a = 0, the origin's axial coordinate -H or +H) lies in its boundary and meets the
 * cylinder where it crosses the side's circle (the rim), whether that end is capped or
 * open, on every path, in packets, streams and leaves alike. That holds exactly where
 * the axial coordinate is computed exactly (an axis along a coordinate axis, floats
 * that place the plane); otherwise a ray within 2 ulps of the plane may hit or miss.
 *
 * Working range. cylray_prepare refuses cylinders beyond its limits (see there). Any
 * finite nonzero direction is answered as accurately as a unit one. The origin must
 * lie within 2^62 of the center in each coordinate and the exact t within FLT_MAX;
 * beyond that a lane may miss, but a hit it reports still lies on the surface.
 *
 * Alignment. The packet and leaf types carry the alignment of their vector width (16,
 * 32 or 64 bytes), and it is required: the kernels may use aligned vector loads and
 * stores on them. Automatic and static objects and aligned_alloc() have it; malloc()
 * does not promise it. Streams take any alignment. The 64 bytes of cylray_prepared are
 * advisory (the object then starts a cache line): the kernels read it with scalar
 * loads and broadcasts only, and cylray_prepare needs 16 bytes (it may store with
 * 16-byte vector moves), so one from malloc() on a 64-bit platform serves.
 *
 * Threads. Every function is re-entrant and keeps no state between calls but one: the
 * path the plain entry points use, chosen once on first use (reading CYLRAY_ISA then),
 * thread-safely. Prepared cylinders and leaves are only read by the kernels and may be
 * shared between threads; rays being intersected are written (tmax) and may not.
 *
 * Versions and ABI. CYLRAY_VERSION_* name this header's version. While the major
 * version is 0, a new minor version may change the API and the ABI, and the shared
 * library's soname changes with it; a patch version changes neither. The sizes and
 * alignments of the opaque types (cylray_prepared, cylray_leafM) are part of the ABI,
 * since the caller allocates them; their fields are not part of the API. */
#ifndef CYLRAY_H
#define CYLRAY_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define CYLRAY_VERSION_MAJOR 0
#define CYLRAY_VERSION_MINOR 2
#define CYLRAY_VERSION_PATCH 0

#if defined(_MSC_VER)
#define CYLRAY_ALIGN(n) __declspec(align(n))
#else
#define CYLRAY_ALIGN(n) __attribute__((aligned(n)))
#endif

/* CYLRAY_API marks the functions the shared library exports: it is built with every
 * other symbol hidden, and defines CYLRAY_BUILDING. On Windows a DLL's users import
 * its functions, and a program that links the static library defines CYLRAY_STATIC. */
#if defined(_WIN32) || defined(__CYGWIN__)
#if defined(CYLRAY_STATIC)
#define CYLRAY_API
#elif defined(CYLRAY_BUILDING)
#define CYLRAY_API __declspec(dllexport)
#else
#define CYLRAY_API __declspec(dllimport)
#endif
#elif defined(CYLRAY_BUILDING) && (defined(__GNUC__) || defined(__clang__))
#define CYLRAY_API __attribute__((visibility("default")))
#else
#define CYLRAY_API
#endif

/* ---- status ------------------------------------------------------------ */

typedef enum cylray_status {
    CYLRAY_OK = 0,
    CYLRAY_EINVAL = 1, /* an argument outside the documented limits (cylray_prepare) */
    CYLRAY_ENOMEM = 2  /* memory ran out (cylray_embree_new_geometry; the core library
                        * allocates nothing) */
} cylray_status;

/* A constant English sentence for s (never NULL, also for an unknown status). */
CYLRAY_API const char *cylray_strerror(cylray_status s);

/* ---- cylinders ----------------------------------------------------------- */

/* cylray_cylinder.flags. The low end is the one at axial coordinate -H, i.e. at
 * center - H axis/|axis|; the high end at +H. An infinite cylinder has no ends and
 * ignores these flags. */
#define CYLRAY_CAPPED_LO 0x1u /* the disc at the low end is part of the surface */
#define CYLRAY_CAPPED_HI 0x2u /* the disc at the high end is part of the surface */
#define CYLRAY_CAPPED 0x3u    /* both discs: a closed solid */

typedef struct cylray_cylinder {
    float center[3];   /* a point on the axis, halfway between the ends */
    float axis[3];     /* direction of the axis; any nonzero length (cylray_prepare),
                         * taken as exact: never normalised, the floats given are the
                         * geometry */
    float radius;      /* in world units */
    float half_height; /* in world units whatever the axis length: the ends are at
                         * center +- half_height axis/|axis|; INFINITY: infinite */
    unsigned flags;    /* CYLRAY_CAPPED, CYLRAY_CAPPED_LO, CYLRAY_CAPPED_HI or 0 */
} cylray_cylinder;

/* What cylray_prepare derives once per cylinder; read-only for the kernels. The
 * fields are not part of the API; the size is part of the ABI. 64-byte aligned so that
 * it starts a cache line; that alignment is advisory (see the top of this file): 16
 * bytes serve. It holds no pointers: a memcpy of it is as good as it. */
typedef struct CYLRAY_ALIGN(64) cylray_prepared {
    float c[3];             /* center */
    float v[3];             /* axis scaled by an exact power of two */
    float n[3];             /* unit axis, for the cap normals */
    float inv_vv;           /* 1 / (v.v) */
    float rr_vv;            /* R^2 (v.v) */
    float sqrt_vv;          /* |v| */
    float h_v;              /* H |v|; INFINITY when infinite */
    float nscale;           /* 1 / (R v.v): scales v x (p x v) to a unit normal */
    float vk[3];            /* v * nscale */
    float bound2;           /* squared radius of a bounding sphere, with a margin */
    float rr_d;             /* R^2 2^-2j, for the discriminant: j keeps A R^2 in range */
    float g_s;              /* 2^-j, which scales g there */
    uint32_t kind;          /* CYLRAY_KIND_*: infinite, open tube, capped */
    uint32_t axis_id;       /* 0 general, 1..3: along +-x, +-y, +-z */
    uint32_t magic;         /* set by cylray_prepare; kernels reject anything else */
    float rr;               /* R^2 */
    float par_eps;          /* A below par_eps * d.d: parallel to the axis */
    float cr[3];            /* along a coordinate axis: the center with that axis third */
    float vr;               /* along a coordinate axis: its sign (v there is (0, 0, vr)) */
    float cap_up, cap_down; /* along a coordinate axis: the parts at renamed z = +-H */
    uint8_t order[3];       /* the renamed coordinates: the j-th is the user's order[j] */
    uint8_t variant;        /* which kernel table entry serves this cylinder */
    float radius;           /* R, as given */
    float half_height;      /* H, as given */
    uint32_t caps;          /* CYLRAY_CAPPED_LO | CYLRAY_CAPPED_HI of a finite cylinder */
    float r0, r1;           /* a cone: the radii at p0 (axial -H) and p1 (+H), as given */
    float rm;               /* a cone: (r0 + r1) / 2, the radius at the center */
    float kap;              /* a cone: (r1 - r0) / (2 H |v|), the radius's slope per v.p */
    float cnrm;             /* a cone: 1 / sqrt(1 + ((r1 - r0) / 2H)^2) */
    float rc_s;             /* a round cone: its spheres' centers c -+ rc_s v (p0, p1) */
    float rc_rr[2];         /* their squared radii (0 for a point end) */
    float rc_z[2];          /* the tangent circles' planes: axial coordinates, as h_v's */
    float rc_rim[2];        /* the tangent circles' radii */
    uint32_t rc_caps;       /* the spheres on the surface (CYLRAY_CAPPED_LO, _HI) */
} cylray_prepared;

/* Checks *in and derives what the kernels need into *out. Returns CYLRAY_OK, or
 * CYLRAY_EINVAL (leaving *out untouched) when a pointer is NULL or *in breaks one of
 * these limits (beyond them R^2 v.v and the kernels' products of it would overflow,
 * or R^2 be subnormal):
 *   - every center and axis coordinate finite, with |x| <= 2^62;
 *   - an axis that is neither zero nor subnormal: its largest |component| is at least
 *     FLT_MIN (2^-126);
 *   - a radius in [2^-60, 2^62] (NaN is refused);
 *   - a half height > 0 and not NaN: INFINITY, or finite and at most 2^62;
 *   - no flag bits but CYLRAY_CAPPED_LO and CYLRAY_CAPPED_HI.
 * Never aborts. A kernel given a cylray_prepared this did not fill (a zeroed one, say)
 * returns 0 and writes nothing. */
CYLRAY_API cylray_status cylray_prepare(cylray_prepared *out, const cylray_cylinder *in);

/* ---- cones --------------------------------------------------------------- */

/* A truncated cone: the disc of radius r0 centred at p0 and the disc of radius r1 at
 * p1, the side joining their rims. flags: CYLRAY_CAPPED_LO (the disc at p0, part
 * CYLRAY_CAP_LO), CYLRAY_CAPPED_HI (at p1, CYLRAY_CAP_HI), CYLRAY_CAPPED, or 0. */
typedef struct cylray_cone {
    float p0[3], p1[3];
    float r0, r1;   /* in world units; one may be 0 (a tip), not both */
    unsigned flags; /* CYLRAY_CAPPED, CYLRAY_CAPPED_LO, CYLRAY_CAPPED_HI or 0 */
} cylray_cone;

/* Checks *in and prepares it as cylray_prepare does a cylinder: a prepared cone goes
 * wherever a prepared cylinder goes, with the same flags and the same guarantee for the
 * cone of the float inputs. The axis p1 - p0 and the center (p0 + p1) / 2 are each
 * rounded once to float, as cylray_cylinder_from_endpoints rounds them, so the ends
 * the kernels see lie within about one float ulp of p0 and p1. r0 == r1 prepares the
 * cylinder of that radius (and runs as fast as one). Parts: CYLRAY_SIDE, CYLRAY_CAP_LO
 * (the disc at p0), CYLRAY_CAP_HI (at p1), with CYLRAY_BACKFACE from inside the solid.
 * Returns CYLRAY_EINVAL (leaving *out untouched) when a pointer is NULL, a coordinate
 * is NaN, infinite or beyond 2^62 in magnitude, p0 == p1 (or p1 - p0 rounds to a zero
 * or subnormal vector), the ends so far apart that p1 - p0 or the half height passes
 * 2^62 (as cylray_cylinder_from_endpoints refuses them), a cone steeper than
 * |r1 - r0| = 2^40 |p1 - p0| or with max(r0, r1) (1 + slope) + |r1 - r0| / 2 beyond
 * 2^61, slope = |r1 - r0| / |p1 - p0| (its radius near its bounding sphere, which the
 * kernels square; r0 == r1 is a cylinder and exempt), a radius is neither 0 nor in [2^-60, 2^62] (NaN is refused),
 * both radii are 0, or a flag bit is not CYLRAY_CAPPED_LO or CYLRAY_CAPPED_HI. */
CYLRAY_API cylray_status cylray_prepare_cone(cylray_prepared *out, const cylray_cone *in);

/* ---- spheres ------------------------------------------------------------- */

/* A sphere: the float center and radius given are the exact geometry. */
typedef struct cylray_sphere {
    float center[3];
    float radius; /* in world units */
} cylray_sphere;

/* Checks *in and prepares it as cylray_prepare does a cylinder: a prepared sphere goes
 * wherever a prepared cylinder goes (packets, streams, occluded, the secondary-ray
 * calls, bounds, surface coordinates) with the same flags and the same guarantee. Its
 * hits report part CYLRAY_SIDE, with CYLRAY_BACKFACE from inside. Returns CYLRAY_OK, or
 * CYLRAY_EINVAL (leaving *out untouched) when a pointer is NULL, a center coordinate is
 * NaN, infinite or beyond 2^62 in magnitude, or the radius lies outside [2^-60, 2^62]
 * (NaN is refused). */
CYLRAY_API cylray_status cylray_prepare_sphere(cylray_prepared *out, const cylray_sphere *in);

/* ---- round cones --------------------------------------------------------- */

/* The convex hull of the spheres (p0, r0) and (p1, r1): a capsule when r0 == r1; the
 * segment of Embree's ROUND_LINEAR_CURVE and ANARI's curve. Parts: CYLRAY_SIDE (the
 * cone tangent to both spheres, between the circles where it touches them),
 * CYLRAY_CAP_LO / _HI (the part of sphere 0 / sphere 1 on the hull). flags:
 * CYLRAY_CAPPED_LO / _HI include that end's sphere (CYLRAY_CAPPED: the closed hull);
 * without it the side still ends at that tangent circle and the end is open, a hole
 * a ray passes through. r0, r1 >= 0, not both 0. */
typedef struct cylray_round_cone {
    float p0[3], p1[3];
    float r0, r1;   /* in world units; one may be 0 (a point end), not both */
    unsigned flags; /* CYLRAY_CAPPED, CYLRAY_CAPPED_LO, CYLRAY_CAPPED_HI or 0 */
} cylray_round_cone;

/* Checks *in and prepares it for the packet, stream and occluded kernels, with the
 * same flags and the same guarantee for the hull of the float inputs (docs/design.md,
 * "Round cones"): the kernels place the spheres and the tangent cone from p0, p1 and
 * the axis and center a cone on p0 and p1 has, and derive the cone's radii and the
 * planes of its tangent circles in double, rounded once to float. Not yet taken by
 * leaves, bounds, split boxes and surface coordinates (which return CYLRAY_EINVAL, 0 or
 * nothing) nor by the secondary-ray calls (whose points and origins are then NaN).
 * Returns CYLRAY_EINVAL (leaving
 * *out untouched) when a pointer is NULL, a coordinate is NaN, infinite or beyond 2^62
 * in magnitude, a radius is neither 0 nor in [2^-60, 2^62] or both are 0, a flag bit
 * is not CYLRAY_CAPPED_LO or CYLRAY_CAPPED_HI, one sphere lies within the other
 * (|p1 - p0| <= |r1 - r0|), or the tangent cone breaks cylray_prepare_cone's limits. */
CYLRAY_API cylray_status cylray_prepare_round_cone(cylray_prepared *out,
                                                   const cylray_round_cone *in);

/* ---- hit output ----------------------------------------------------------- */

#define CYLRAY_MISS 0
#define CYLRAY_SIDE 1
#define CYLRAY_CAP_LO 2       /* the disc at axial coordinate -H: center - H axis/|axis| */
#define CYLRAY_CAP_HI 3       /* the disc at +H: center + H axis/|axis| */
#define CYLRAY_PART_MASK 0x0f /* part & CYLRAY_PART_MASK: SIDE, CAP_LO or CAP_HI */
/* OR'ed into part: met from inside the solid, dot(d, n_out) > 0 with n_out the
 * outward normal (also with one cap or none, where the surface is not closed) */
#define CYLRAY_BACKFACE 0x10

/* Kernel flags, OR'ed. Each selects a kernel compiled for it, so a flag not given
 * costs nothing. Normals are unit length and outward unless CYLRAY_FACE_FORWARD. */
#define CYLRAY_NORMAL 0x01u       /* write nx, ny, nz; otherwise they stay untouched */
#define CYLRAY_FACE_FORWARD 0x02u /* flip the normal to face the ray: dot(n, d) <= 0 */
#define CYLRAY_CULL_BACK 0x04u    /* ignore hits met from inside (BACKFACE) */
#define CYLRAY_REFINE 0x08u       /* polish the root once more from the first hit */
/* CYLRAY_FAST: reciprocal and square-root estimates refined by Newton steps instead
 * of divisions and square roots; t is held to 8 ulps beyond the exact band instead of
 * 4 (docs/design.md, section 4). The estimates are the CPU's: on SSE4.1 and AVX2 their
 * tables differ between vendors, and so may FAST's answers (each within that rule).
 * Where the CPU divides faster than the estimates refine (AMD's and Hygon's cores), the
 * x86 paths answer FAST with their exact kernels, as without the flag. Without it, one
 * build answers bit for bit alike on every CPU of a path's ISA. */
#define CYLRAY_FAST 0x10u
#define CYLRAY_FLAGS_ALL 0x1fu

/* ---- packets (SoA, aligned to their width in bytes: required) ------------- */

#define CYLRAY_PACKET_(n, al)                                                                  \
    typedef struct CYLRAY_ALIGN(al) cylray_ray##n {                                            \
        float ox[n], oy[n], oz[n], dx[n], dy[n], dz[n], tmin[n], tmax[n];                      \
    } cylray_ray##n;                                                                           \
    typedef struct CYLRAY_ALIGN(al) cylray_hit##n {                                            \
        float t[n], nx[n], ny[n], nz[n];                                                       \
        int32_t part[n];                                                                       \
    } cylray_hit##n;
CYLRAY_PACKET_(4, 16)
CYLRAY_PACKET_(8, 32)
CYLRAY_PACKET_(16, 64)
#undef CYLRAY_PACKET_

/* For every lane i whose bit is set in `active` (bits at and beyond the width are
 * ignored): on a hit at t in [tmin, tmax] the kernel writes lane i of *hit (t, part,
 * and the normal with CYLRAY_NORMAL), sets ray->tmax[i] = t and sets bit i of the
 * result. A lane that misses keeps its values (when every lane is active, the kernel
 * may store them back unchanged as part of a whole-vector store, which is cheaper
 * than a masked store on AMD CPUs); an inactive lane is never written; nothing else
 * of *ray is. A lane never hits when a field is NaN or infinite (but tmin = -INFINITY,
 * tmax = INFINITY), when its direction is zero, or when tmin > tmax; the other lanes'
 * answers do not depend on it. */
CYLRAY_API uint32_t cylray_intersect4(const cylray_prepared *cyl, cylray_ray4 *ray,
                                      cylray_hit4 *hit, uint32_t active, unsigned flags);
CYLRAY_API uint32_t cylray_intersect8(const cylray_prepared *cyl, cylray_ray8 *ray,
                                      cylray_hit8 *hit, uint32_t active, unsigned flags);
CYLRAY_API uint32_t cylray_intersect16(const cylray_prepared *cyl, cylray_ray16 *ray,
                                       cylray_hit16 *hit, uint32_t active, unsigned flags);

/* Bit i set: lane i has some hit in [tmin, tmax] (one the intersect call with the
 * same flags would report). Writes nothing. */
CYLRAY_API uint32_t cylray_occluded4(const cylray_prepared *cyl, const cylray_ray4 *ray,
                                     uint32_t active, unsigned flags);
CYLRAY_API uint32_t cylray_occluded8(const cylray_prepared *cyl, const cylray_ray8 *ray,
                                     uint32_t active, unsigned flags);
CYLRAY_API uint32_t cylray_occluded16(const cylray_prepared *cyl, const cylray_ray16 *ray,
                                      uint32_t active, unsigned flags);

/* ---- streams (any length, any alignment) ---------------------------------- */

typedef struct cylray_rays {
    const float *ox, *oy, *oz, *dx, *dy, *dz, *tmin;
    float *tmax;
} cylray_rays;

typedef struct cylray_hits {
    float *t, *nx, *ny, *nz; /* nx, ny, nz may be NULL without CYLRAY_NORMAL */
    int32_t *part;
} cylray_hits;

/* Rays 0..n-1 of separate arrays, any length and alignment; nothing before or after
 * them is read or written. Same per-ray semantics as the packets, and the same answers
 * bit for bit; returns the number of hits. The throughput path: with many rays per
 * call the kernels keep more than one vector of rays in flight where that pays, which
 * packets, one call per vector, cannot. */
CYLRAY_API size_t cylray_intersect_stream(const cylray_prepared *cyl, const cylray_rays *rays,
                                          const cylray_hits *hits, size_t n, unsigned flags);
/* Sets occluded[i] = 1 for each ray with a hit, leaves the others; returns the count. */
CYLRAY_API size_t cylray_occluded_stream(const cylray_prepared *cyl, const cylray_rays *rays,
                                         uint8_t *occluded, size_t n, unsigned flags);

/* ---- leaves: one ray against up to 4, 8 or 16 cylinders ------------------ */

/* One ray, x(t) = o + t d for t in [tmin, tmax], and one hit. */
typedef struct cylray_ray1 {
    float o[3], d[3], tmin, tmax;
} cylray_ray1;

typedef struct cylray_hit1 {
    float t, n[3]; /* n only with CYLRAY_NORMAL */
    int32_t part;  /* CYLRAY_SIDE, CYLRAY_CAP_LO or CYLRAY_CAP_HI, maybe | BACKFACE */
    uint32_t id;   /* the id given to cylray_leaf_prepareM for the hit cylinder */
    uint32_t lane; /* its place in the leaf, 0..M-1 */
} cylray_hit1;

/* M prepared cylinders in SoA, 64 bytes a cylinder, aligned to the vector width
 * (required). The fields are not part of the API; the size is part of the ABI. */
#define CYLRAY_LEAF_(m, al)                                                                    \
    typedef struct CYLRAY_ALIGN(al) cylray_leaf##m {                                           \
        float geom_[14][m];                                                                    \
        uint32_t meta_[m], id_[m];                                                             \
    } cylray_leaf##m;
CYLRAY_LEAF_(4, 16)
CYLRAY_LEAF_(8, 32)
CYLRAY_LEAF_(16, 64)
#undef CYLRAY_LEAF_

/* Builds a leaf from cyl[0..n) with the user's ids[0..n) (ids may be NULL: the ids are
 * then 0..n-1). Returns CYLRAY_EINVAL, leaving *out untouched, when n > M, when a
 * pointer is NULL, or when any cylinder is refused by the rules of cylray_prepare.
 * Lanes n..M-1 are padding that never hits; n = 0 gives a leaf that never hits. */
CYLRAY_API cylray_status cylray_leaf_prepare4(cylray_leaf4 *out, const cylray_cylinder *cyl,
                                              const uint32_t *ids, size_t n);
CYLRAY_API cylray_status cylray_leaf_prepare8(cylray_leaf8 *out, const cylray_cylinder *cyl,
                                              const uint32_t *ids, size_t n);
CYLRAY_API cylray_status cylray_leaf_prepare16(cylray_leaf16 *out, const cylray_cylinder *cyl,
                                               const uint32_t *ids, size_t n);
/* The same for a leaf of spheres (the rules of cylray_prepare_sphere), and for a leaf of
 * cones (those of cylray_prepare_cone); queried, bounded and used for secondary rays by
 * the same calls as a leaf of cylinders. A leaf holds cylinders, cones or spheres; a
 * leaf of cones may hold cylinders too, as cones with r0 == r1 (a leaf of cylinders
 * alone is faster). */
CYLRAY_API cylray_status cylray_leaf_prepare_cones4(cylray_leaf4 *out, const cylray_cone *c,
                                                    const uint32_t *ids, size_t n);
CYLRAY_API cylray_status cylray_leaf_prepare_cones8(cylray_leaf8 *out, const cylray_cone *c,
                                                    const uint32_t *ids, size_t n);
CYLRAY_API cylray_status cylray_leaf_prepare_cones16(cylray_leaf16 *out, const cylray_cone *c,
                                                     const uint32_t *ids, size_t n);
CYLRAY_API cylray_status cylray_leaf_prepare_spheres4(cylray_leaf4 *out, const cylray_sphere *s,
                                                      const uint32_t *ids, size_t n);
CYLRAY_API cylray_status cylray_leaf_prepare_spheres8(cylray_leaf8 *out, const cylray_sphere *s,
                                                      const uint32_t *ids, size_t n);
CYLRAY_API cylray_status cylray_leaf_prepare_spheres16(cylray_leaf16 *out,
                                                       const cylray_sphere *s,
                                                       const uint32_t *ids, size_t n);

/* The closest hit over the leaf's cylinders in [tmin, tmax]: returns 1, writes *hit
 * and sets ray->tmax = t; of cylinders hit at the same t the lowest lane wins.
 * Returns 0 and writes nothing on a miss. Flags as for the packets. */
CYLRAY_API int cylray_leaf_intersect4(const cylray_leaf4 *leaf, cylray_ray1 *ray,
                                      cylray_hit1 *hit, unsigned flags);
CYLRAY_API int cylray_leaf_intersect8(const cylray_leaf8 *leaf, cylray_ray1 *ray,
                                      cylray_hit1 *hit, unsigned flags);
CYLRAY_API int cylray_leaf_intersect16(const cylray_leaf16 *leaf, cylray_ray1 *ray,
                                       cylray_hit1 *hit, unsigned flags);
/* 1 when any cylinder of the leaf is hit in [tmin, tmax]; writes nothing. */
CYLRAY_API int cylray_leaf_occluded4(const cylray_leaf4 *leaf, const cylray_ray1 *ray,
                                     unsigned flags);
CYLRAY_API int cylray_leaf_occluded8(const cylray_leaf8 *leaf, const cylray_ray1 *ray,
                                     unsigned flags);
CYLRAY_API int cylray_leaf_occluded16(const cylray_leaf16 *leaf, const cylray_ray1 *ray,
                                      unsigned flags);

/* ---- the endpoint form ------------------------------------------------------ */

/* The cylinder around the segment p0 -> p1 with the given radius; flags as in
 * cylray_cylinder, CYLRAY_CAPPED_LO being the disc at p0. The axis is p1 - p0 and the
 * center (p0 + p1) / 2, each rounded once to float; the half height is |p1 - p0| / 2
 * in world units, rounded once. Returns CYLRAY_EINVAL (leaving *out untouched) for
 * p0 == p1, non-finite input, or what cylray_prepare would refuse. */
CYLRAY_API cylray_status cylray_cylinder_from_endpoints(cylray_cylinder *out, const float p0[3],
                                                        const float p1[3], float radius,
                                                        unsigned flags);

/* ---- secondary rays ----------------------------------------------------------- */

/* The guarantee: a ray traced with tmin = 0 from the origin cylray_spawn_origin gives
 * never hits again, on any ISA, the surface it leaves at that point (nor, at a rim, the
 * other surface through it), and it starts strictly on its own side of each of them, by
 * twice the kernels' tested tolerance and no more, whenever that offset is below a
 * quarter of the radius and of the half height (a sphere: of the radius). (The side form sending a ray outward
 * along a w that dips back into the side starts it up to three tolerances further
 * out: near a tangency, far enough that the exact ray and the kernels miss alike.) The tolerance includes that of t, a
 * float whose spacing at 0 is 2^-149: along a direction w the origin keeps about
 * 2^-147 |w| from the surface, which matters only for directions far longer than the
 * scene (2^-19 for |w| = FLT_MAX).
 *
 * For a hit of the ray o + t d at t on `part` of cyl: p, the hit point (moved onto
 * the surface of that part where that pays), and *err, a bound on the distance from p
 * to the exact surface of that part. A sphere (any part is taken for its side): p is
 * c + R (x - c) / |x - c| with x = o + t d, evaluated in double and rounded to float,
 * and *err p's distance from the exact sphere, evaluated with its rounding error (less
 * than 2^-50 R) and rounded up to float. A cone: p is the nearest point of the part hit
 * (the side, or the disc of radius r0 or r1) to x, in the half plane through the axis
 * that holds x, and *err p's distance from that part evaluated likewise (the cone being
 * the prepared one: radius r0 and r1 at its discs as given, linear in z between). */
CYLRAY_API void cylray_hit_point(const cylray_prepared *cyl, const float o[3], const float d[3],
                                 float t, int32_t part, float p[3], float *err);
/* The same, given also the normal n the kernel returned for that hit (CYLRAY_NORMAL;
 * outward or face-forwarded alike). Where float t or the float coordinates cannot
 * place the hit (ulp(t)|d| or the coordinates' ulp not small against R, as with a ray
 * from far away), the point o + t d rebuilds can lie up to a quarter turn around the
 * tube from the hit the kernel found; on the side this form puts p at the kernel's
 * azimuth, so that the exact normal at p is n's to within float rounding, and a tracer
 * that shades, face-forwards and picks the spawn side with n stays consistent with p.
 * err is a bound as above. A tracer that asks for normals should use this form. A
 * sphere: p is c + R n / |n|, n taken outward as on the side, and *err as above. A
 * cone's side: the kernel's azimuth and axial coordinate, then as cylray_hit_point. */
CYLRAY_API void cylray_hit_point_normal(const cylray_prepared *cyl, const float o[3],
                                        const float d[3], float t, int32_t part,
                                        const float n[3], float p[3], float *err);
/* The origin for a new ray that leaves that hit in direction w, to be traced with
 * tmin = 0: strictly on w's side of every surface of cyl that passes within err of p
 * (at a rim, of both). A sphere has one surface: the origin is moved along the radius
 * through p by the rule of the side, its margin the kernels' tolerance for the sphere
 * (2 ulps of the origin's coordinates and of R), doubled. A cone's side is moved along
 * its tilted normal (the gradient of |x_perp| - r(z)), its margin also counting the
 * slope's tolerance; at a rim the move meets the side's and the disc's margins both
 * (the two normals are not perpendicular there). At the apex of a tip cone the normal
 * is that of an arbitrary azimuth: an origin there is cleared of that azimuth's side
 * only (docs/secondary-rays.md, "Cones"). */
CYLRAY_API void cylray_spawn_origin(const cylray_prepared *cyl, const float p[3], float err,
                                    int32_t part, const float w[3], float out[3]);
/* The spawn side the tracer chooses. A tracer picks reflection or transmission (or
 * whether a light is above the horizon) with the normal the kernel returned; near a
 * tangency that normal and the exact normal at p may put w on different sides, and
 * cylray_spawn_origin, which follows w, then starts the ray on the other side from the
 * one the tracer shaded. This form starts it where the tracer says: outward != 0 on
 * the side the part's outward normal points to, 0 on the other. With the kernel's
 * outward normal n (CYLRAY_NORMAL without CYLRAY_FACE_FORWARD), outward = dot(w, n) > 0.
 * Any other surface within err of p (at a rim) is cleared to w's side, as above.
 * The guarantee, on any ISA and under the condition above: the origin lies strictly on
 * the requested side of the part (and on w's side of any other surface within err of
 * p), and a ray traced from it with tmin = 0 meets the part it leaves no sooner than
 * the exact ray from that origin can (half that distance at the least): a ray sent
 * back into the surface meets it where the geometry says, never at its own origin.
 * Where the side requested is w's side of the exact normal at p, the origin is
 * cylray_spawn_origin's, bit for bit. A sphere: its one surface is the part, cleared to
 * the side asked for by the rules of the side (a w that dips back into it included). A
 * cone: as cylray_spawn_origin for cones; its side's dip rule reads the cone as the
 * cylinder along its ruling with radius r(z) / cos(tilt). */
CYLRAY_API void cylray_spawn_origin_side(const cylray_prepared *cyl, const float p[3],
                                         float err, int32_t part, int outward, const float w[3],
                                         float out[3]);

/* Batched forms: vectorised on every path (in double, several lanes at a time), with
 * the same answer as the scalar pair lane by lane, bit for bit, on every path; a tracer
 * that does not call them pays nothing. Hit points with their bounds, in SoA like the
 * packets: */
#define CYLRAY_POINTS_(n, al)                                                                  \
    typedef struct CYLRAY_ALIGN(al) cylray_points##n {                                         \
        float x[n], y[n], z[n], err[n];                                                        \
    } cylray_points##n;
CYLRAY_POINTS_(4, 16)
CYLRAY_POINTS_(8, 32)
CYLRAY_POINTS_(16, 64)
#undef CYLRAY_POINTS_

/* Packets: for each lane i set in `mask` (the result of the intersect call), the hit
 * point of ray i (its o and d; t and part come from hit) into lane i of *pts. Other
 * lanes are not written. */
CYLRAY_API void cylray_hit_points4(const cylray_prepared *cyl, const cylray_ray4 *ray,
                                   const cylray_hit4 *hit, uint32_t mask, cylray_points4 *pts);
CYLRAY_API void cylray_hit_points8(const cylray_prepared *cyl, const cylray_ray8 *ray,
                                   const cylray_hit8 *hit, uint32_t mask, cylray_points8 *pts);
CYLRAY_API void cylray_hit_points16(const cylray_prepared *cyl, const cylray_ray16 *ray,
                                    const cylray_hit16 *hit, uint32_t mask,
                                    cylray_points16 *pts);
/* The same from the normals in hit (traced with CYLRAY_NORMAL), as
 * cylray_hit_point_normal. */
CYLRAY_API void cylray_hit_points_normal4(const cylray_prepared *cyl, const cylray_ray4 *ray,
                                          const cylray_hit4 *hit, uint32_t mask,
                                          cylray_points4 *pts);
CYLRAY_API void cylray_hit_points_normal8(const cylray_prepared *cyl, const cylray_ray8 *ray,
                                          const cylray_hit8 *hit, uint32_t mask,
                                          cylray_points8 *pts);
CYLRAY_API void cylray_hit_points_normal16(const cylray_prepared *cyl, const cylray_ray16 *ray,
                                           const cylray_hit16 *hit, uint32_t mask,
                                           cylray_points16 *pts);
/* For each lane i set in `mask`: out->dx..dz[i] hold the new direction on entry; the
 * spawned origin goes to out->ox..oz[i] and tmin[i] is set to 0 (tmax is the caller's:
 * INFINITY, or the distance to a light). *out may be the packet that was traced. */
CYLRAY_API void cylray_spawn_rays4(const cylray_prepared *cyl, const cylray_points4 *pts,
                                   const cylray_hit4 *hit, uint32_t mask, cylray_ray4 *out);
CYLRAY_API void cylray_spawn_rays8(const cylray_prepared *cyl, const cylray_points8 *pts,
                                   const cylray_hit8 *hit, uint32_t mask, cylray_ray8 *out);
CYLRAY_API void cylray_spawn_rays16(const cylray_prepared *cyl, const cylray_points16 *pts,
                                    const cylray_hit16 *hit, uint32_t mask, cylray_ray16 *out);
/* The same with the side of each lane's part chosen by the tracer: bit i of outward
 * set, the side its outward normal points to (as cylray_spawn_origin_side). */
CYLRAY_API void cylray_spawn_rays_side4(const cylray_prepared *cyl, const cylray_points4 *pts,
                                        const cylray_hit4 *hit, uint32_t mask, uint32_t outward,
                                        cylray_ray4 *out);
CYLRAY_API void cylray_spawn_rays_side8(const cylray_prepared *cyl, const cylray_points8 *pts,
                                        const cylray_hit8 *hit, uint32_t mask, uint32_t outward,
                                        cylray_ray8 *out);
CYLRAY_API void cylray_spawn_rays_side16(const cylray_prepared *cyl, const cylray_points16 *pts,
                                         const cylray_hit16 *hit, uint32_t mask,
                                         uint32_t outward, cylray_ray16 *out);

/* Streams: separate arrays (err may be NULL where no bound is read or written). */
typedef struct cylray_points {
    float *x, *y, *z, *err;
} cylray_points;
/* For each ray i whose hits->part[i] is not CYLRAY_MISS (the caller clears part before
 * the intersect call), its hit point into pts; returns how many were written. */
CYLRAY_API size_t cylray_hit_points_stream(const cylray_prepared *cyl, const cylray_rays *rays,
                                           const cylray_hits *hits, const cylray_points *pts,
                                           size_t n);
/* The same from the normals in hits (nx, ny, nz required), as cylray_hit_point_normal. */
CYLRAY_API size_t cylray_hit_points_normal_stream(const cylray_prepared *cyl,
                                                  const cylray_rays *rays,
                                                  const cylray_hits *hits,
                                                  const cylray_points *pts, size_t n);
/* For each i whose part[i] is not CYLRAY_MISS, the origin that leaves point i of pts in
 * direction (dirs->x, y, z)[i], into (origins->x, y, z)[i]; origins may alias dirs. */
CYLRAY_API void cylray_spawn_stream(const cylray_prepared *cyl, const cylray_points *pts,
                                    const int32_t *part, const cylray_points *dirs,
                                    const cylray_points *origins, size_t n);
/* The same with the side chosen by the tracer: outward[i] nonzero, the side ray i's
 * part's outward normal points to (as cylray_spawn_origin_side). */
CYLRAY_API void cylray_spawn_stream_side(const cylray_prepared *cyl, const cylray_points *pts,
                                         const int32_t *part, const uint8_t *outward,
                                         const cylray_points *dirs,
                                         const cylray_points *origins, size_t n);

/* Leaves: the hit a leaf query returned (hit->lane names the cylinder; ray as it came
 * back from the query, whose o and d are unchanged). A leaf of spheres: each lane as the
 * prepared sphere, bit for bit. */
CYLRAY_API void cylray_leaf_hit_point4(const cylray_leaf4 *leaf, const cylray_ray1 *ray,
                                       const cylray_hit1 *hit, float p[3], float *err);
CYLRAY_API void cylray_leaf_hit_point8(const cylray_leaf8 *leaf, const cylray_ray1 *ray,
                                       const cylray_hit1 *hit, float p[3], float *err);
CYLRAY_API void cylray_leaf_hit_point16(const cylray_leaf16 *leaf, const cylray_ray1 *ray,
                                        const cylray_hit1 *hit, float p[3], float *err);
/* From the hit's normal (the query made with CYLRAY_NORMAL), as cylray_hit_point_normal. */
CYLRAY_API void cylray_leaf_hit_point_normal4(const cylray_leaf4 *leaf, const cylray_ray1 *ray,
                                              const cylray_hit1 *hit, float p[3], float *err);
CYLRAY_API void cylray_leaf_hit_point_normal8(const cylray_leaf8 *leaf, const cylray_ray1 *ray,
                                              const cylray_hit1 *hit, float p[3], float *err);
CYLRAY_API void cylray_leaf_hit_point_normal16(const cylray_leaf16 *leaf,
                                               const cylray_ray1 *ray, const cylray_hit1 *hit,
                                               float p[3], float *err);
CYLRAY_API void cylray_leaf_spawn_origin4(const cylray_leaf4 *leaf, const cylray_hit1 *hit,
                                          const float p[3], float err, const float w[3],
                                          float out[3]);
CYLRAY_API void cylray_leaf_spawn_origin8(const cylray_leaf8 *leaf, const cylray_hit1 *hit,
                                          const float p[3], float err, const float w[3],
                                          float out[3]);
CYLRAY_API void cylray_leaf_spawn_origin16(const cylray_leaf16 *leaf, const cylray_hit1 *hit,
                                           const float p[3], float err, const float w[3],
                                           float out[3]);
/* With the side chosen by the tracer (as cylray_spawn_origin_side). */
CYLRAY_API void cylray_leaf_spawn_origin_side4(const cylray_leaf4 *leaf, const cylray_hit1 *hit,
                                               const float p[3], float err, int outward,
                                               const float w[3], float out[3]);
CYLRAY_API void cylray_leaf_spawn_origin_side8(const cylray_leaf8 *leaf, const cylray_hit1 *hit,
                                               const float p[3], float err, int outward,
                                               const float w[3], float out[3]);
CYLRAY_API void cylray_leaf_spawn_origin_side16(const cylray_leaf16 *leaf,
                                                const cylray_hit1 *hit, const float p[3],
                                                float err, int outward, const float w[3],
                                                float out[3]);
/* Leaves' hits in bulk: hit i, returned by a query of leaf[i] with ray[i] (a leaf may
 * appear many times), into point i of pts (err may be NULL). */
CYLRAY_API void cylray_leaf_hit_points4(const cylray_leaf4 *const *leaf, const cylray_ray1 *ray,
                                        const cylray_hit1 *hit, const cylray_points *pts,
                                        size_t n);
CYLRAY_API void cylray_leaf_hit_points8(const cylray_leaf8 *const *leaf, const cylray_ray1 *ray,
                                        const cylray_hit1 *hit, const cylray_points *pts,
                                        size_t n);
CYLRAY_API void cylray_leaf_hit_points16(const cylray_leaf16 *const *leaf,
                                         const cylray_ray1 *ray, const cylray_hit1 *hit,
                                         const cylray_points *pts, size_t n);
/* The origin leaving point i of pts (err NULL: 0) of hit[i] on leaf[i] in direction
 * (dirs->x, y, z)[i], into (origins->x, y, z)[i]; origins may alias dirs. */
CYLRAY_API void cylray_leaf_spawn_origins4(const cylray_leaf4 *const *leaf,
                                           const cylray_hit1 *hit, const cylray_points *pts,
                                           const cylray_points *dirs,
                                           const cylray_points *origins, size_t n);
CYLRAY_API void cylray_leaf_spawn_origins8(const cylray_leaf8 *const *leaf,
                                           const cylray_hit1 *hit, const cylray_points *pts,
                                           const cylray_points *dirs,
                                           const cylray_points *origins, size_t n);
CYLRAY_API void cylray_leaf_spawn_origins16(const cylray_leaf16 *const *leaf,
                                            const cylray_hit1 *hit, const cylray_points *pts,
                                            const cylray_points *dirs,
                                            const cylray_points *origins, size_t n);
/* The same from the hits' normals (the queries made with CYLRAY_NORMAL), as
 * cylray_hit_point_normal. */
CYLRAY_API void cylray_leaf_hit_points_normal4(const cylray_leaf4 *const *leaf,
                                               const cylray_ray1 *ray, const cylray_hit1 *hit,
                                               const cylray_points *pts, size_t n);
CYLRAY_API void cylray_leaf_hit_points_normal8(const cylray_leaf8 *const *leaf,
                                               const cylray_ray1 *ray, const cylray_hit1 *hit,
                                               const cylray_points *pts, size_t n);
CYLRAY_API void cylray_leaf_hit_points_normal16(const cylray_leaf16 *const *leaf,
                                                const cylray_ray1 *ray, const cylray_hit1 *hit,
                                                const cylray_points *pts, size_t n);
/* With the side chosen by the tracer: outward[i] nonzero, the side hit i's part's
 * outward normal points to (as cylray_spawn_origin_side). */
CYLRAY_API void cylray_leaf_spawn_origins_side4(
    const cylray_leaf4 *const *leaf, const cylray_hit1 *hit, const cylray_points *pts,
    const uint8_t *outward, const cylray_points *dirs, const cylray_points *origins, size_t n);
CYLRAY_API void cylray_leaf_spawn_origins_side8(
    const cylray_leaf8 *const *leaf, const cylray_hit1 *hit, const cylray_points *pts,
    const uint8_t *outward, const cylray_points *dirs, const cylray_points *origins, size_t n);
CYLRAY_API void cylray_leaf_spawn_origins_side16(
    const cylray_leaf16 *const *leaf, const cylray_hit1 *hit, const cylray_points *pts,
    const uint8_t *outward, const cylray_points *dirs, const cylray_points *origins, size_t n);

/* ---- per-ISA access ------------------------------------------------------- */

typedef enum cylray_isa {
    CYLRAY_ISA_SCALAR,
    CYLRAY_ISA_SSE41,
    CYLRAY_ISA_AVX2,
    CYLRAY_ISA_AVX512,
    CYLRAY_ISA_NEON,
    CYLRAY_ISA_COUNT
} cylray_isa;

typedef uint32_t (*cylray_intersect4_fn)(const cylray_prepared *, cylray_ray4 *, cylray_hit4 *,
                                         uint32_t, unsigned);
typedef uint32_t (*cylray_intersect8_fn)(const cylray_prepared *, cylray_ray8 *, cylray_hit8 *,
                                         uint32_t, unsigned);
typedef uint32_t (*cylray_intersect16_fn)(const cylray_prepared *, cylray_ray16 *,
                                          cylray_hit16 *, uint32_t, unsigned);
typedef uint32_t (*cylray_occluded4_fn)(const cylray_prepared *, const cylray_ray4 *, uint32_t,
                                        unsigned);
typedef uint32_t (*cylray_occluded8_fn)(const cylray_prepared *, const cylray_ray8 *, uint32_t,
                                        unsigned);
typedef uint32_t (*cylray_occluded16_fn)(const cylray_prepared *, const cylray_ray16 *,
                                         uint32_t, unsigned);
typedef size_t (*cylray_intersect_stream_fn)(const cylray_prepared *, const cylray_rays *,
                                             const cylray_hits *, size_t, unsigned);
typedef size_t (*cylray_occluded_stream_fn)(const cylray_prepared *, const cylray_rays *,
                                            uint8_t *, size_t, unsigned);
typedef int (*cylray_leaf_intersect4_fn)(const cylray_leaf4 *, cylray_ray1 *, cylray_hit1 *,
                                         unsigned);
typedef int (*cylray_leaf_intersect8_fn)(const cylray_leaf8 *, cylray_ray1 *, cylray_hit1 *,
                                         unsigned);
typedef int (*cylray_leaf_intersect16_fn)(const cylray_leaf16 *, cylray_ray1 *, cylray_hit1 *,
                                          unsigned);
typedef int (*cylray_leaf_occluded4_fn)(const cylray_leaf4 *, const cylray_ray1 *, unsigned);
typedef int (*cylray_leaf_occluded8_fn)(const cylray_leaf8 *, const cylray_ray1 *, unsigned);
typedef int (*cylray_leaf_occluded16_fn)(const cylray_leaf16 *, const cylray_ray1 *, unsigned);

typedef struct cylray_kernels {
    cylray_isa isa;
    const char *name; /* "scalar", "sse41", "avx2", "avx512", "neon" */
    cylray_intersect4_fn intersect4;
    cylray_intersect8_fn intersect8;
    cylray_intersect16_fn intersect16;
    cylray_occluded4_fn occluded4;
    cylray_occluded8_fn occluded8;
    cylray_occluded16_fn occluded16;
    cylray_intersect_stream_fn intersect_stream;
    cylray_occluded_stream_fn occluded_stream;
    cylray_leaf_intersect4_fn leaf_intersect4;
    cylray_leaf_intersect8_fn leaf_intersect8;
    cylray_leaf_intersect16_fn leaf_intersect16;
    cylray_leaf_occluded4_fn leaf_occluded4;
    cylray_leaf_occluded8_fn leaf_occluded8;
    cylray_leaf_occluded16_fn leaf_occluded16;
    /* Secondary rays: the batched forms above, on this path. Slots are only ever
     * appended, so a table read through an older header is a prefix of this one. */
    void (*hit_points4)(const cylray_prepared *, const cylray_ray4 *, const cylray_hit4 *,
                        uint32_t, cylray_points4 *);
    void (*hit_points8)(const cylray_prepared *, const cylray_ray8 *, const cylray_hit8 *,
                        uint32_t, cylray_points8 *);
    void (*hit_points16)(const cylray_prepared *, const cylray_ray16 *, const cylray_hit16 *,
                         uint32_t, cylray_points16 *);
    void (*spawn_rays4)(const cylray_prepared *, const cylray_points4 *, const cylray_hit4 *,
                        uint32_t, cylray_ray4 *);
    void (*spawn_rays8)(const cylray_prepared *, const cylray_points8 *, const cylray_hit8 *,
                        uint32_t, cylray_ray8 *);
    void (*spawn_rays16)(const cylray_prepared *, const cylray_points16 *, const cylray_hit16 *,
                         uint32_t, cylray_ray16 *);
    size_t (*hit_points_stream)(const cylray_prepared *, const cylray_rays *,
                                const cylray_hits *, const cylray_points *, size_t);
    void (*spawn_stream)(const cylray_prepared *, const cylray_points *, const int32_t *,
                         const cylray_points *, const cylray_points *, size_t);
    void (*leaf_hit_points4)(const cylray_leaf4 *const *, const cylray_ray1 *,
                             const cylray_hit1 *, const cylray_points *, size_t);
    void (*leaf_hit_points8)(const cylray_leaf8 *const *, const cylray_ray1 *,
                             const cylray_hit1 *, const cylray_points *, size_t);
    void (*leaf_hit_points16)(const cylray_leaf16 *const *, const cylray_ray1 *,
                              const cylray_hit1 *, const cylray_points *, size_t);
    void (*leaf_spawn_origins4)(const cylray_leaf4 *const *, const cylray_hit1 *,
                                const cylray_points *, const cylray_points *,
                                const cylray_points *, size_t);
    void (*leaf_spawn_origins8)(const cylray_leaf8 *const *, const cylray_hit1 *,
                                const cylray_points *, const cylray_points *,
                                const cylray_points *, size_t);
    void (*leaf_spawn_origins16)(const cylray_leaf16 *const *, const cylray_hit1 *,
                                 const cylray_points *, const cylray_points *,
                                 const cylray_points *, size_t);
    /* the normal and side forms */
    void (*hit_points_normal4)(const cylray_prepared *, const cylray_ray4 *,
                               const cylray_hit4 *, uint32_t, cylray_points4 *);
    void (*hit_points_normal8)(const cylray_prepared *, const cylray_ray8 *,
                               const cylray_hit8 *, uint32_t, cylray_points8 *);
    void (*hit_points_normal16)(const cylray_prepared *, const cylray_ray16 *,
                                const cylray_hit16 *, uint32_t, cylray_points16 *);
    void (*spawn_rays_side4)(const cylray_prepared *, const cylray_points4 *,
                             const cylray_hit4 *, uint32_t, uint32_t, cylray_ray4 *);
    void (*spawn_rays_side8)(const cylray_prepared *, const cylray_points8 *,
                             const cylray_hit8 *, uint32_t, uint32_t, cylray_ray8 *);
    void (*spawn_rays_side16)(const cylray_prepared *, const cylray_points16 *,
                              const cylray_hit16 *, uint32_t, uint32_t, cylray_ray16 *);
    size_t (*hit_points_normal_stream)(const cylray_prepared *, const cylray_rays *,
                                       const cylray_hits *, const cylray_points *, size_t);
    void (*spawn_stream_side)(const cylray_prepared *, const cylray_points *, const int32_t *,
                              const uint8_t *, const cylray_points *, const cylray_points *,
                              size_t);
    void (*leaf_hit_points_normal4)(const cylray_leaf4 *const *, const cylray_ray1 *,
                                    const cylray_hit1 *, const cylray_points *, size_t);
    void (*leaf_hit_points_normal8)(const cylray_leaf8 *const *, const cylray_ray1 *,
                                    const cylray_hit1 *, const cylray_points *, size_t);
    void (*leaf_hit_points_normal16)(const cylray_leaf16 *const *, const cylray_ray1 *,
                                     const cylray_hit1 *, const cylray_points *, size_t);
    void (*leaf_spawn_origins_side4)(const cylray_leaf4 *const *, const cylray_hit1 *,
                                     const cylray_points *, const uint8_t *,
                                     const cylray_points *, const cylray_points *, size_t);
    void (*leaf_spawn_origins_side8)(const cylray_leaf8 *const *, const cylray_hit1 *,
                                     const cylray_points *, const uint8_t *,
                                     const cylray_points *, const cylray_points *, size_t);
    void (*leaf_spawn_origins_side16)(const cylray_leaf16 *const *, const cylray_hit1 *,
                                      const cylray_points *, const uint8_t *,
                                      const cylray_points *, const cylray_points *, size_t);
} cylray_kernels;

/* One path's table, for validation and microbenchmarks: the same signatures and
 * contract as the plain entry points of the same names. NULL when that path was not
 * built or the CPU (or the OS, which must save its registers) lacks it. */
CYLRAY_API const cylray_kernels *cylray_kernels_for(cylray_isa isa);
/* The path the plain entry points use, chosen on the first call: the best the CPU
 * has, or the one the environment variable CYLRAY_ISA names (scalar, sse41, avx2,
 * avx512, neon) if it is available; otherwise one line on stderr and the best. */
CYLRAY_API const cylray_kernels *cylray_kernels_best(void);
/* "scalar", "sse41", "avx2", "avx512", "neon"; "unknown" out of range. */
CYLRAY_API const char *cylray_isa_name(cylray_isa isa);

/* ---- bounds ---------------------------------------------------------------- */

/* The box of the exact cylinder that cylray_prepare derived (the floats given are the
 * geometry): the box of its two rims, which holds the side and the discs whatever the
 * caps. Coordinate k spans center_k -+ (H |n_k| + R sqrt(1 - n_k^2)), n the unit axis,
 * evaluated to about 2^-100 and rounded outward: no face lies inside the exact box,
 * and each is the nearest float outside it or the next one (the smallest float box,
 * exactly, when the axis lies along a coordinate axis). Only where a face's exact
 * value cancels to below 2^-70 of |center_k| + the extent may it lie further out, by at
 * most 2^-95 of that. A sphere: center_k -+ R, each face the nearest float outside the
 * exact one (the smallest float box). Returns CYLRAY_EINVAL and writes nothing for an
 * infinite cylinder (it has no box), a NULL pointer, or a cyl cylray_prepare did not fill. */
CYLRAY_API cylray_status cylray_bounds(const cylray_prepared *cyl, float lo[3], float hi[3]);
/* A cone's box is its frustum's, the hull of its two discs (radii r0 and r1 about the
 * prepared ends), each face within 2 floats of the exact one, on its outer side. */
/* The box of a leaf's used lanes (the union of their cylray_bounds boxes); CYLRAY_EINVAL
 * and nothing written when a lane is infinite or no lane is used. */
CYLRAY_API cylray_status cylray_leaf_bounds4(const cylray_leaf4 *leaf, float lo[3],
                                             float hi[3]);
CYLRAY_API cylray_status cylray_leaf_bounds8(const cylray_leaf8 *leaf, float lo[3],
                                             float hi[3]);
CYLRAY_API cylray_status cylray_leaf_bounds16(const cylray_leaf16 *leaf, float lo[3],
                                              float hi[3]);

/* Boxes along a long cylinder, for a BVH builder: a rod tilted off the coordinate axes
 * fills a box far wider than itself, so every ray through that box visits it. Slice i of
 * k (0 <= i < k) is the part of the cylinder between the discs at axial coordinates
 * H q_i and H q_(i+1), q_i = (2i - k) / k rounded once to double; its box is that of
 * the two discs' rims (a disc's box: center + t n -+ R sqrt(1 - n_k^2) per coordinate),
 * rounded outward as cylray_bounds rounds (one float step beyond the nearest, at most).
 * Neighbouring slices share their disc exactly, so the k boxes together hold every
 * point of the cylinder. Every box stands for the whole cylinder: a tracer that meets
 * two of them intersects the same cylinder twice and keeps one hit through tmax.
 *
 * k = 0 chooses k by a rule of the shape: the smallest k at which, in each coordinate
 * j but the one the axis is closest to, a slice's extent from the tilt (2H |n_j| / k) is
 * at most its extent from the radius (2R sqrt(1 - n_j^2)), so that each box is at most
 * twice the rod's width across; at least 1 (a cylinder along a coordinate axis: 1) and
 * at most CYLRAY_SPLIT_MAX. Writes k boxes to lo[0..k), hi[0..k) and returns k; with
 * lo or hi NULL, writes nothing and returns the k it would use. Returns 0 and writes
 * nothing for an infinite cylinder or a cyl cylray_prepare did not fill.
 *
 * A sphere is cut across z, the axis of its surface coordinates: slice i lies between
 * the planes z = center_z + R q_i and center_z + R q_(i+1), its box spanning center_x
 * and center_y -+ R sqrt(1 - q^2) at the q of [q_i, q_(i+1)] nearest 0, rounded
 * outward as above. k = 0 gives 1: the box of cylray_bounds.
 *
 * A cone is cut as a cylinder of radius max(r0, r1) is (k = 0: the same rule), each
 * slice's box that of its two discs, of the cone's radius at their axial coordinates. */
#define CYLRAY_SPLIT_MAX 32
CYLRAY_API size_t cylray_split_boxes(const cylray_prepared *cyl, size_t k, float (*lo)[3],
                                     float (*hi)[3]);

/* ---- surface coordinates --------------------------------------------------------- */

/* Surface coordinates at a point p of `part` (CYLRAY_BACKFACE is ignored), for a hit
 * point from cylray_hit_point or o + t d, measured in the frame every user and binding
 * can build alike: n the unit axis (the axis given, from the low end to the high end,
 * p0 to p1 of cylray_cylinder_from_endpoints), and (b1, b2) the orthonormal basis of
 * Duff et al., "Building an Orthonormal Basis, Revisited" (JCGT 2017), from n with the
 * sign s = +1 where n_z >= 0 (a zero of either sign) and -1 otherwise:
 *     a = -1 / (s + n_z), b = n_x n_y a,
 *     b1 = (1 + s n_x^2 a, s b, -s n_x), b2 = (b, s + n_y^2 a, -n_y).
 * With r = p - center, z = r.n and the azimuth phi = atan2(r.b2, r.b1):
 *   side:  u = (z + H) / 2H, 0 at the low end and 1 at the high end (an infinite
 *          cylinder: u = z, the signed axial distance from the center); v = phi / 2pi
 *          wrapped to [0, 1); dpdu = 2H n (infinite: n); dpdv = 2pi R (-sin(phi) b1 +
 *          cos(phi) b2).
 *   discs: u = 0 (CYLRAY_CAP_LO) or 1 (CYLRAY_CAP_HI); v = phi / 2pi as on the side;
 *          the disc's radial coordinate w = rho / R in [0, 1] (rho the distance from the
 *          axis) takes the place of u in the derivatives: dpdu = dp/dw = R (cos(phi) b1 +
 *          sin(phi) b2), outward, and dpdv = 2pi rho (-sin(phi) b1 + cos(phi) b2), so w
 *          = |dpdv| / (2pi R).
 * On the axis (rho = 0) phi is 0: v = 0, and a disc's dpdv is 0 and its dpdu R b1.
 * A v whose value rounds to 1 is given as the float below 1.
 * Accuracy: u and v are the exact values at p (the float point as given) to within one
 * float ulp plus 2^-90 |r| / 2H (u; infinite: 2^-90 |r|) and 2^-90 |r| / rho (v); dpdu
 * and dpdv to within 2^-20 of their length (those that turn with phi: where rho >
 * 2^-60 |r|, short of which phi says little). Any of uv, dpdu, dpdv may be NULL: it is not
 * written, and what only it needs is not computed. Nothing is written for a part other
 * than SIDE, CAP_LO and CAP_HI, or a cyl cylray_prepare did not fill.
 *
 * A sphere: pbrt-v4's full sphere about the z axis through its center, at the point
 * (x, y, z) = R r / |r| where the ray from the center through p meets it (r = p -
 * center; the center itself counts as the -z pole): u = phi / 2pi, phi = atan2(y, x) in
 * [0, 2pi) (0 on the z axis; a u that rounds to 1 is the float below 1); v = 1 -
 * theta / pi, theta = acos(z / R): 0 at the -z pole, 1 at +z; dpdu = 2pi (-y, x, 0) (0
 * at the poles); dpdv = pi (-z cos(phi), -z sin(phi), R sin(theta)). u and v within
 * one float ulp of their exact values at p, dpdu and dpdv within 2^-20 of their length.
 * Only the side: nothing is written for another part.
 *
 * A cone: u and v as a cylinder's (u = 0 at p0, 1 at p1; v the azimuth about p1 - p0 in
 * the frame above); the discs as a cylinder's, R the disc's radius; on the side dpdu =
 * 2H n + (r1 - r0) (cos(phi) b1 + sin(phi) b2), along the cone's ruling, and dpdv =
 * 2pi r(z) (-sin(phi) b1 + cos(phi) b2), r(z) the radius at p's axial coordinate. */
CYLRAY_API void cylray_surface(const cylray_prepared *cyl, const float p[3], int32_t part,
                               float uv[2], float dpdu[3], float dpdv[3]);
/* The same for the hit a leaf query returned (hit->lane and hit->part name the cylinder
 * or sphere and the part); nothing is written for a lane the leaf does not use. */
CYLRAY_API void cylray_leaf_surface4(const cylray_leaf4 *leaf, const cylray_hit1 *hit,
                                     const float p[3], float uv[2], float dpdu[3],
                                     float dpdv[3]);
CYLRAY_API void cylray_leaf_surface8(const cylray_leaf8 *leaf, const cylray_hit1 *hit,
                                     const float p[3], float uv[2], float dpdu[3],
                                     float dpdv[3]);
CYLRAY_API void cylray_leaf_surface16(const cylray_leaf16 *leaf, const cylray_hit1 *hit,
                                      const float p[3], float uv[2], float dpdu[3],
                                      float dpdv[3]);

#ifdef __cplusplus
}
#endif

#endif /* CYLRAY_H */
