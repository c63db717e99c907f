/* cylray.h - SIMD ray/cylinder intersection kernels: the whole public API. */
#ifndef CYLRAY_H
#define CYLRAY_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define CYLRAY_VERSION_MAJOR 0
#define CYLRAY_VERSION_MINOR 1
#define CYLRAY_VERSION_PATCH 0

#if defined(_MSC_VER)
#define CYLRAY_ALIGN(n) __declspec(align(n))
#else
#define CYLRAY_ALIGN(n) __attribute__((aligned(n)))
#endif

/* ---- status ------------------------------------------------------------ */

typedef enum cylray_status {
    CYLRAY_OK = 0,
    CYLRAY_EINVAL = 1     /* a cylinder that describes no valid solid */
} cylray_status;

const char *cylray_strerror(cylray_status s);

/* ---- cylinders ----------------------------------------------------------- */

/* cylray_cylinder.flags. The low end is the one at axial coordinate -H, i.e. at
 * center - H axis/|axis|; the high end at +H. */
#define CYLRAY_CAPPED_LO 0x1u /* the disc at the low end is part of the surface */
#define CYLRAY_CAPPED_HI 0x2u /* the disc at the high end is part of the surface */
#define CYLRAY_CAPPED 0x3u    /* both discs: a closed solid */

typedef struct cylray_cylinder {
    float center[3];    /* a point on the axis, halfway between the ends */
    float axis[3];      /* direction of the axis; any nonzero length, taken as exact */
    float radius;       /* > 0 */
    float half_height;  /* > 0; INFINITY for an infinite cylinder */
    unsigned flags;     /* CYLRAY_CAPPED, CYLRAY_CAPPED_LO, CYLRAY_CAPPED_HI or 0 */
} cylray_cylinder;

/* What cylray_prepare derives once per cylinder; read-only for the kernels. The
 * fields are not part of the API. 64-byte aligned so that broadcasts never split a
 * cache line. */
typedef struct CYLRAY_ALIGN(64) cylray_prepared {
    float c[3];        /* center */
    float v[3];        /* axis scaled by an exact power of two */
    float n[3];        /* unit axis, for the cap normals */
    float inv_vv;      /* 1 / (v.v) */
    float rr_vv;       /* R^2 (v.v) */
    float sqrt_vv;     /* |v| */
    float h_v;         /* H |v|; INFINITY when infinite */
    float nscale;      /* 1 / (R v.v): scales v x (p x v) to a unit normal */
    float vk[3];       /* v * nscale */
    float bound2;      /* squared radius of a bounding sphere, with a margin */
    float rr_d;        /* R^2 2^-2j, for the discriminant: j keeps A R^2 in range */
    float g_s;         /* 2^-j, which scales g there */
    uint32_t kind;     /* CYLRAY_KIND_*: infinite, open tube, capped */
    uint32_t axis_id;  /* 0 general, 1..3: along +-x, +-y, +-z */
    uint32_t magic;    /* set by cylray_prepare; kernels reject anything else */
    float rr;          /* R^2 */
    float par_eps;     /* A below par_eps * d.d: parallel to the axis */
    float cr[3];       /* along a coordinate axis: the center with that axis third */
    float vr;          /* along a coordinate axis: its sign (v there is (0, 0, vr)) */
    float cap_up, cap_down; /* along a coordinate axis: the parts at renamed z = +-H */
    uint8_t order[3];  /* the renamed coordinates: the j-th is the user's order[j] */
    uint8_t variant;   /* which kernel table entry serves this cylinder */
    float radius;      /* R, as given */
    float half_height; /* H, as given */
    uint32_t caps;     /* CYLRAY_CAPPED_LO | CYLRAY_CAPPED_HI of a finite cylinder */
} cylray_prepared;

/* Returns CYLRAY_OK, or CYLRAY_EINVAL (leaving *out untouched) for NaN or Inf
 * coordinates, a zero or subnormal axis, a radius <= 0 or not finite, a half height
 * <= 0 or NaN, or unknown flag bits. Never aborts. */
cylray_status cylray_prepare(cylray_prepared *out, const cylray_cylinder *in);

/* ---- hit output ----------------------------------------------------------- */

#define CYLRAY_MISS     0
#define CYLRAY_SIDE     1
#define CYLRAY_CAP_LO   2    /* the disc at axial coordinate -H */
#define CYLRAY_CAP_HI   3    /* the disc at +H */
#define CYLRAY_PART_MASK 0x0f
#define CYLRAY_BACKFACE 0x10 /* met from inside the solid: dot(d, n_out) > 0 */

/* kernel flags */
#define CYLRAY_NORMAL       0x01u /* write nx, ny, nz; otherwise they stay untouched */
#define CYLRAY_FACE_FORWARD 0x02u /* flip the normal to face the ray */
#define CYLRAY_CULL_BACK    0x04u /* ignore hits met from inside */
#define CYLRAY_REFINE       0x08u /* polish the root once more from the first hit */
#define CYLRAY_FAST         0x10u /* approximate reciprocals and square roots */
#define CYLRAY_FLAGS_ALL    0x1fu

/* ---- packets (SoA, aligned to their width in bytes) --------------------- */

#define CYLRAY_PACKET_(n, al)                                                     \
    typedef struct CYLRAY_ALIGN(al) cylray_ray##n {                              \
        float ox[n], oy[n], oz[n], dx[n], dy[n], dz[n], tmin[n], tmax[n];        \
    } cylray_ray##n;                                                            \
    typedef struct CYLRAY_ALIGN(al) cylray_hit##n {                              \
        float t[n], nx[n], ny[n], nz[n];                                         \
        int32_t part[n];                                                         \
    } cylray_hit##n;
CYLRAY_PACKET_(4, 16)
CYLRAY_PACKET_(8, 32)
CYLRAY_PACKET_(16, 64)
#undef CYLRAY_PACKET_

/* For every lane i whose bit is set in `active`: on a hit at t in [tmin, tmax] the
 * kernel writes lane i of *hit, sets ray->tmax[i] = t and sets bit i of the result.
 * Misses and inactive lanes are not written. A lane with NaN inputs never hits. */
uint32_t cylray_intersect4(const cylray_prepared *cyl, cylray_ray4 *ray,
                           cylray_hit4 *hit, uint32_t active, unsigned flags);
uint32_t cylray_intersect8(const cylray_prepared *cyl, cylray_ray8 *ray,
                           cylray_hit8 *hit, uint32_t active, unsigned flags);
uint32_t cylray_intersect16(const cylray_prepared *cyl, cylray_ray16 *ray,
                            cylray_hit16 *hit, uint32_t active, unsigned flags);

/* Bit i set: lane i has some hit in [tmin, tmax]. Writes nothing. */
uint32_t cylray_occluded4(const cylray_prepared *cyl, const cylray_ray4 *ray,
                          uint32_t active, unsigned flags);
uint32_t cylray_occluded8(const cylray_prepared *cyl, const cylray_ray8 *ray,
                          uint32_t active, unsigned flags);
uint32_t cylray_occluded16(const cylray_prepared *cyl, const cylray_ray16 *ray,
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

/* Same per-ray semantics as the packets; returns the number of hits. */
size_t cylray_intersect_stream(const cylray_prepared *cyl, const cylray_rays *rays,
                               const cylray_hits *hits, size_t n, unsigned flags);
/* Sets occluded[i] = 1 for each ray with a hit, leaves the others; returns the count. */
size_t cylray_occluded_stream(const cylray_prepared *cyl, const cylray_rays *rays,
                              uint8_t *occluded, size_t n, unsigned flags);

/* ---- leaves: one ray against up to 4, 8 or 16 cylinders ------------------ */

/* One ray, x(t) = o + t d for t in [tmin, tmax], and one hit. */
typedef struct cylray_ray1 {
    float o[3], d[3], tmin, tmax;
} cylray_ray1;

typedef struct cylray_hit1 {
    float t, n[3];  /* n only with CYLRAY_NORMAL */
    int32_t part;   /* CYLRAY_SIDE, CYLRAY_CAP_LO or CYLRAY_CAP_HI, maybe | BACKFACE */
    uint32_t id;    /* the id given to cylray_leaf_prepareM for the hit cylinder */
    uint32_t lane;  /* its place in the leaf, 0..M-1 */
} cylray_hit1;

/* M prepared cylinders in SoA, 64 bytes a cylinder, aligned to the vector width.
 * The fields are not part of the API. */
#define CYLRAY_LEAF_(m, al)                                                       \
    typedef struct CYLRAY_ALIGN(al) cylray_leaf##m {                              \
        float geom_[14][m];                                                       \
        uint32_t meta_[m], id_[m];                                                \
    } cylray_leaf##m;
CYLRAY_LEAF_(4, 16)
CYLRAY_LEAF_(8, 32)
CYLRAY_LEAF_(16, 64)
#undef CYLRAY_LEAF_

/* Builds a leaf from cyl[0..n) with the user's ids[0..n) (ids may be NULL: the ids are
 * then 0..n-1). Returns CYLRAY_EINVAL, leaving *out untouched, when n > M, when a
 * pointer is NULL, or when any cylinder is refused by the rules of cylray_prepare.
 * Lanes n..M-1 are padding that never hits; n = 0 gives a leaf that never hits. */
cylray_status cylray_leaf_prepare4(cylray_leaf4 *out, const cylray_cylinder *cyl,
                                   const uint32_t *ids, size_t n);
cylray_status cylray_leaf_prepare8(cylray_leaf8 *out, const cylray_cylinder *cyl,
                                   const uint32_t *ids, size_t n);
cylray_status cylray_leaf_prepare16(cylray_leaf16 *out, const cylray_cylinder *cyl,
                                    const uint32_t *ids, size_t n);

/* The closest hit over the leaf's cylinders in [tmin, tmax]: returns 1, writes *hit
 * and sets ray->tmax = t; of cylinders hit at the same t the lowest lane wins.
 * Returns 0 and writes nothing on a miss. Flags as for the packets. */
int cylray_leaf_intersect4(const cylray_leaf4 *leaf, cylray_ray1 *ray, cylray_hit1 *hit,
                           unsigned flags);
int cylray_leaf_intersect8(const cylray_leaf8 *leaf, cylray_ray1 *ray, cylray_hit1 *hit,
                           unsigned flags);
int cylray_leaf_intersect16(const cylray_leaf16 *leaf, cylray_ray1 *ray, cylray_hit1 *hit,
                            unsigned flags);
/* 1 when any cylinder of the leaf is hit in [tmin, tmax]; writes nothing. */
int cylray_leaf_occluded4(const cylray_leaf4 *leaf, const cylray_ray1 *ray, unsigned flags);
int cylray_leaf_occluded8(const cylray_leaf8 *leaf, const cylray_ray1 *ray, unsigned flags);
int cylray_leaf_occluded16(const cylray_leaf16 *leaf, const cylray_ray1 *ray, unsigned flags);

/* ---- the endpoint form ------------------------------------------------------ */

/* The cylinder around the segment p0 -> p1 with the given radius; flags as in
 * cylray_cylinder, CYLRAY_CAPPED_LO being the disc at p0. The axis is p1 - p0 and the
 * center (p0 + p1) / 2, each rounded once to float; the half height is |p1 - p0| / 2
 * in world units, rounded once. Returns CYLRAY_EINVAL (leaving *out untouched) for
 * p0 == p1, non-finite input, or what cylray_prepare would refuse. */
cylray_status cylray_cylinder_from_endpoints(cylray_cylinder *out, const float p0[3],
                                             const float p1[3], float radius,
                                             unsigned flags);

/* ---- secondary rays ----------------------------------------------------------- */

/* The guarantee: a ray traced with tmin = 0 from the origin cylray_spawn_origin gives
 * never hits again, on any ISA, the surface it leaves at that point (nor, at a rim, the
 * other surface through it), and it starts strictly on its own side of each of them, by
 * twice the kernels' tested tolerance and no more, whenever that offset is below a
 * quarter of the radius and of the half height.
 *
 * For a hit of the ray o + t d at t on `part` of cyl: p, the hit point (moved onto
 * the surface of that part where that pays), and *err, a bound on the distance from p
 * to the exact surface of that part. */
void cylray_hit_point(const cylray_prepared *cyl, const float o[3], const float d[3],
                      float t, int32_t part, float p[3], float *err);
/* The origin for a new ray that leaves that hit in direction w, to be traced with
 * tmin = 0: strictly on w's side of every surface of cyl that passes within err of p
 * (at a rim, of both). */
void cylray_spawn_origin(const cylray_prepared *cyl, const float p[3], float err,
                         int32_t part, const float w[3], float out[3]);

/* Batched forms: plain loops over the lanes, the same answer as the scalar pair lane by
 * lane; a tracer that does not call them pays nothing. Hit points with their bounds,
 * in SoA like the packets: */
#define CYLRAY_POINTS_(n, al)                                                     \
    typedef struct CYLRAY_ALIGN(al) cylray_points##n {                           \
        float x[n], y[n], z[n], err[n];                                          \
    } cylray_points##n;
CYLRAY_POINTS_(4, 16)
CYLRAY_POINTS_(8, 32)
CYLRAY_POINTS_(16, 64)
#undef CYLRAY_POINTS_

/* Packets: for each lane i set in `mask` (the result of the intersect call), the hit
 * point of ray i (its o and d; t and part come from hit) into lane i of *pts. Other
 * lanes are not written. */
void cylray_hit_points4(const cylray_prepared *cyl, const cylray_ray4 *ray,
                        const cylray_hit4 *hit, uint32_t mask, cylray_points4 *pts);
void cylray_hit_points8(const cylray_prepared *cyl, const cylray_ray8 *ray,
                        const cylray_hit8 *hit, uint32_t mask, cylray_points8 *pts);
void cylray_hit_points16(const cylray_prepared *cyl, const cylray_ray16 *ray,
                         const cylray_hit16 *hit, uint32_t mask, cylray_points16 *pts);
/* For each lane i set in `mask`: out->dx..dz[i] hold the new direction on entry; the
 * spawned origin goes to out->ox..oz[i] and tmin[i] is set to 0 (tmax is the caller's:
 * INFINITY, or the distance to a light). *out may be the packet that was traced. */
void cylray_spawn_rays4(const cylray_prepared *cyl, const cylray_points4 *pts,
                        const cylray_hit4 *hit, uint32_t mask, cylray_ray4 *out);
void cylray_spawn_rays8(const cylray_prepared *cyl, const cylray_points8 *pts,
                        const cylray_hit8 *hit, uint32_t mask, cylray_ray8 *out);
void cylray_spawn_rays16(const cylray_prepared *cyl, const cylray_points16 *pts,
                         const cylray_hit16 *hit, uint32_t mask, cylray_ray16 *out);

/* Streams: separate arrays (err may be NULL where no bound is read or written). */
typedef struct cylray_points {
    float *x, *y, *z, *err;
} cylray_points;
/* For each ray i whose hits->part[i] is not CYLRAY_MISS (the caller clears part before
 * the intersect call), its hit point into pts; returns how many were written. */
size_t cylray_hit_points_stream(const cylray_prepared *cyl, const cylray_rays *rays,
                                const cylray_hits *hits, const cylray_points *pts, size_t n);
/* For each i whose part[i] is not CYLRAY_MISS, the origin that leaves point i of pts in
 * direction (dirs->x, y, z)[i], into (origins->x, y, z)[i]; origins may alias dirs. */
void cylray_spawn_stream(const cylray_prepared *cyl, const cylray_points *pts,
                         const int32_t *part, const cylray_points *dirs,
                         const cylray_points *origins, size_t n);

/* Leaves: the hit a leaf query returned (hit->lane names the cylinder; ray as it came
 * back from the query, whose o and d are unchanged). */
void cylray_leaf_hit_point4(const cylray_leaf4 *leaf, const cylray_ray1 *ray,
                            const cylray_hit1 *hit, float p[3], float *err);
void cylray_leaf_hit_point8(const cylray_leaf8 *leaf, const cylray_ray1 *ray,
                            const cylray_hit1 *hit, float p[3], float *err);
void cylray_leaf_hit_point16(const cylray_leaf16 *leaf, const cylray_ray1 *ray,
                             const cylray_hit1 *hit, float p[3], float *err);
void cylray_leaf_spawn_origin4(const cylray_leaf4 *leaf, const cylray_hit1 *hit,
                               const float p[3], float err, const float w[3], float out[3]);
void cylray_leaf_spawn_origin8(const cylray_leaf8 *leaf, const cylray_hit1 *hit,
                               const float p[3], float err, const float w[3], float out[3]);
void cylray_leaf_spawn_origin16(const cylray_leaf16 *leaf, const cylray_hit1 *hit,
                                const float p[3], float err, const float w[3], float out[3]);

/* ---- per-ISA access ------------------------------------------------------- */

typedef enum cylray_isa {
    CYLRAY_ISA_SCALAR,
    CYLRAY_ISA_SSE41,
    CYLRAY_ISA_AVX2,
    CYLRAY_ISA_AVX512,
    CYLRAY_ISA_NEON,
    CYLRAY_ISA_COUNT
} cylray_isa;

typedef uint32_t (*cylray_intersect4_fn)(const cylray_prepared *, cylray_ray4 *,
                                         cylray_hit4 *, uint32_t, unsigned);
typedef uint32_t (*cylray_intersect8_fn)(const cylray_prepared *, cylray_ray8 *,
                                         cylray_hit8 *, uint32_t, unsigned);
typedef uint32_t (*cylray_intersect16_fn)(const cylray_prepared *, cylray_ray16 *,
                                          cylray_hit16 *, uint32_t, unsigned);
typedef uint32_t (*cylray_occluded4_fn)(const cylray_prepared *, const cylray_ray4 *,
                                        uint32_t, unsigned);
typedef uint32_t (*cylray_occluded8_fn)(const cylray_prepared *, const cylray_ray8 *,
                                        uint32_t, unsigned);
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
typedef int (*cylray_leaf_intersect16_fn)(const cylray_leaf16 *, cylray_ray1 *,
                                          cylray_hit1 *, unsigned);
typedef int (*cylray_leaf_occluded4_fn)(const cylray_leaf4 *, const cylray_ray1 *, unsigned);
typedef int (*cylray_leaf_occluded8_fn)(const cylray_leaf8 *, const cylray_ray1 *, unsigned);
typedef int (*cylray_leaf_occluded16_fn)(const cylray_leaf16 *, const cylray_ray1 *,
                                         unsigned);

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
} cylray_kernels;

/* NULL when that path was not built or the CPU (or OS) lacks it. */
const cylray_kernels *cylray_kernels_for(cylray_isa isa);
/* The path the plain entry points use: the best the CPU has, or CYLRAY_ISA. */
const cylray_kernels *cylray_kernels_best(void);
const char *cylray_isa_name(cylray_isa isa);

#ifdef __cplusplus
}
#endif

#endif /* CYLRAY_H */
