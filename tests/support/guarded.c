/* SPDX-License-Identifier: MIT */
/* guarded.c - the guarded kernel runner described in guarded.h. */
#include "guarded.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tcheck.h"

/* Packets are handled as flat float arrays: field f of lane i at f * width + i. The
 * header test checks this layout too; here it is what the runner relies on. */
#define FLAT_OK_(n)                                                                            \
    _Static_assert(offsetof(cylray_ray##n, tmax) == 7 * n * sizeof(float) &&                   \
                       sizeof(cylray_ray##n) == 8 * n * sizeof(float) &&                       \
                       offsetof(cylray_hit##n, part) == 4 * n * sizeof(float) &&               \
                       sizeof(cylray_hit##n) == 5 * n * sizeof(float),                         \
                   "packet " #n " is not flat SoA")
FLAT_OK_(4);
FLAT_OK_(8);
FLAT_OK_(16);

/* ---- AddressSanitizer: canaries are also made unaddressable ------------------ */
#if defined(__SANITIZE_ADDRESS__)
#define G_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define G_ASAN 1
#endif
#endif
#ifdef G_ASAN
void __asan_poison_memory_region(void const volatile *addr, size_t size);
void __asan_unpoison_memory_region(void const volatile *addr, size_t size);
#define POISON_(p, n) __asan_poison_memory_region(p, n)
#define UNPOISON_(p, n) __asan_unpoison_memory_region(p, n)
#else
#define POISON_(p, n) ((void)(p), (void)(n))
#define UNPOISON_(p, n) ((void)(p), (void)(n))
#endif

#define CANARY_BYTES 64
#define CANARY_BYTE 0xcbu

/* One guarded array: `size` bytes of payload starting `lead` bytes past a 64-byte
 * boundary, canary bytes on both sides. */
typedef struct garr {
    unsigned char *base;
    size_t total, lead, size;
} garr;

static void *garr_open(garr *a, size_t size, size_t lead)
{
    a->lead = CANARY_BYTES + lead;
    a->size = size;
    a->total = (a->lead + size + CANARY_BYTES + 63) / 64 * 64;
    a->base = aligned_alloc(64, a->total);
    if (!a->base) {
        fprintf(stderr, "out of memory\n");
        exit(2);
    }
    memset(a->base, CANARY_BYTE, a->total);
    return a->base + a->lead;
}

static void garr_arm(garr *a)
{
    POISON_(a->base, a->lead);
    POISON_(a->base + a->lead + a->size, a->total - a->lead - a->size);
}

/* Disarms, checks both canaries, frees. Returns 1 when a canary was hit. */
static int garr_close(garr *a, const char *what, const char *ctx)
{
    UNPOISON_(a->base, a->total);
    int bad = 0;
    for (size_t i = 0; i < a->total; i++) {
        if (i >= a->lead && i < a->lead + a->size)
            continue;
        if (a->base[i] != CANARY_BYTE) {
            long off = (long)i - (long)a->lead;
            if (off >= 0)
                off -= (long)a->size;
            CHECK(0, "%s: byte %+ld %s the %s array was written", ctx, off,
                  off < 0 ? "before" : "after", what);
            bad = 1;
            break;
        }
    }
    free(a->base);
    return bad;
}

float g_bits(uint32_t bits)
{
    float f;
    memcpy(&f, &bits, sizeof f);
    return f;
}

float g_poison(void)
{
    return g_bits(G_POISON_BITS);
}

static int is_poison(float x)
{
    uint32_t b;
    memcpy(&b, &x, sizeof b);
    return b == G_POISON_BITS;
}

static int same(float a, float b)
{
    return memcmp(&a, &b, sizeof a) == 0;
}

int g_isas(const cylray_kernels *out[CYLRAY_ISA_COUNT])
{
    int n = 0;
    for (int i = 0; i < CYLRAY_ISA_COUNT; i++) {
        const cylray_kernels *k = cylray_kernels_for((cylray_isa)i);
        if (k)
            out[n++] = k;
    }
    return n;
}

const char *g_width_name(int width)
{
    switch (width) {
    case 4:
        return "4";
    case 8:
        return "8";
    case 16:
        return "16";
    case G_STREAM:
        return "stream";
    }
    return "?";
}

const char *g_ray_str(const gbatch *b, size_t i, char *buf, size_t len)
{
    snprintf(buf, len, "o=(%a,%a,%a) d=(%a,%a,%a) t=[%a,%a]", b->f[G_OX][i], b->f[G_OY][i],
             b->f[G_OZ][i], b->f[G_DX][i], b->f[G_DY][i], b->f[G_DZ][i], b->f[G_TMIN][i],
             b->f[G_TMAX][i]);
    return buf;
}

const char *g_cyl_str(const cylray_cylinder *c, char *buf, size_t len)
{
    snprintf(buf, len, "cyl c=(%a,%a,%a) v=(%a,%a,%a) R=%a H=%a flags=%#x", c->center[0],
             c->center[1], c->center[2], c->axis[0], c->axis[1], c->axis[2], c->radius,
             c->half_height, c->flags);
    return buf;
}

int g_same_lane(const gresult *a, size_t i, const gresult *b, size_t j, int normal)
{
    int ha = (int)((a->hit >> i) & 1u), hb = (int)((b->hit >> j) & 1u);
    if (ha != hb || !same(a->tmax[i], b->tmax[j]))
        return 0;
    if (!ha)
        return 1;
    if (!same(a->t[i], b->t[j]) || a->part[i] != b->part[j])
        return 0;
    return !normal ||
           (same(a->nx[i], b->nx[j]) && same(a->ny[i], b->ny[j]) && same(a->nz[i], b->nz[j]));
}

static int valid_part(int32_t p, unsigned flags)
{
    int base = p & ~CYLRAY_BACKFACE;
    if (base < CYLRAY_SIDE || base > CYLRAY_CAP_HI)
        return 0;
    return !((flags & CYLRAY_CULL_BACK) && (p & CYLRAY_BACKFACE));
}

/* The per-lane checks shared by packets and streams. `hit` says whether the kernel
 * reported lane i. */
static int check_lane(const char *ctx, const gbatch *in, size_t i, int hit, unsigned flags,
                      const gresult *r)
{
    int bad = 0;
    char rs[256];
    const float tmin = in->f[G_TMIN][i], tmax = in->f[G_TMAX][i];
    const int normal = (flags & CYLRAY_NORMAL) != 0;
#define LANE_CHECK_(c, ...)                                                                    \
    do {                                                                                       \
        if (!(c)) {                                                                            \
            bad++;                                                                             \
            CHECK(0, "%s lane %zu (%s): " __VA_ARGS__);                                        \
        } else {                                                                               \
            tc_checks_++;                                                                      \
        }                                                                                      \
    } while (0)
    if (hit) {
        g_ray_str(in, i, rs, sizeof rs);
        LANE_CHECK_(same(r->tmax[i], r->t[i]), "tmax %a is not the hit t %a", ctx, i, rs,
                    r->tmax[i], r->t[i]);
        LANE_CHECK_(r->t[i] >= tmin && r->t[i] <= tmax, "hit t %a outside [tmin, tmax]", ctx, i,
                    rs, r->t[i]);
        LANE_CHECK_(valid_part(r->part[i], flags), "invalid part %#x for flags %#x", ctx, i, rs,
                    (unsigned)r->part[i], flags);
        if (normal)
            LANE_CHECK_(!is_poison(r->nx[i]) && !is_poison(r->ny[i]) && !is_poison(r->nz[i]),
                        "hit without a normal under CYLRAY_NORMAL", ctx, i, rs);
        else
            LANE_CHECK_(is_poison(r->nx[i]) && is_poison(r->ny[i]) && is_poison(r->nz[i]),
                        "normal written without CYLRAY_NORMAL", ctx, i, rs);
    } else {
        g_ray_str(in, i, rs, sizeof rs);
        LANE_CHECK_(is_poison(r->t[i]) && is_poison(r->nx[i]) && is_poison(r->ny[i]) &&
                        is_poison(r->nz[i]) && r->part[i] == G_POISON_PART,
                    "an output of a lane without a hit was written", ctx, i, rs);
        LANE_CHECK_(same(r->tmax[i], tmax), "tmax of a lane without a hit changed to %a", ctx,
                    i, rs, r->tmax[i]);
    }
#undef LANE_CHECK_
    return bad;
}

static void context(char *buf, size_t len, const cylray_kernels *k, int width, size_t n,
                    uint32_t active, unsigned flags, unsigned misalign, const char *op)
{
    if (width == G_STREAM)
        snprintf(buf, len, "%s %s stream n=%zu misalign=%u flags=%#x", k->name, op, n, misalign,
                 flags);
    else
        snprintf(buf, len, "%s %s%d active=%#x flags=%#x", k->name, op, width, active, flags);
}

/* ---- packets ------------------------------------------------------------- */

static int packet_run(const cylray_kernels *k, int w, const cylray_prepared *P,
                      const gbatch *in, uint32_t active, unsigned flags, int occluded,
                      gresult *out)
{
    char ctx[160];
    const char *op = occluded ? "occluded" : "intersect";
    context(ctx, sizeof ctx, k, w, (size_t)w, active, flags, 0, op);
    const size_t W = (size_t)w;
    garr ra, ha;
    float *ray = garr_open(&ra, 8 * W * sizeof(float), 0);
    float *hit = garr_open(&ha, 5 * W * sizeof(float), 0);
    for (int f = 0; f < G_NFIELD; f++)
        memcpy(ray + (size_t)f * W, in->f[f], W * sizeof(float));
    for (size_t i = 0; i < 4 * W; i++)
        hit[i] = g_poison();
    for (size_t i = 0; i < W; i++) {
        int32_t p = G_POISON_PART;
        memcpy(hit + 4 * W + i, &p, sizeof p);
    }
    garr_arm(&ra);
    garr_arm(&ha);

    uint32_t m = 0;
    if (occluded) {
        switch (w) {
        case 4:
            m = k->occluded4(P, (const cylray_ray4 *)(void *)ray, active, flags);
            break;
        case 8:
            m = k->occluded8(P, (const cylray_ray8 *)(void *)ray, active, flags);
            break;
        default:
            m = k->occluded16(P, (const cylray_ray16 *)(void *)ray, active, flags);
            break;
        }
    } else {
        switch (w) {
        case 4:
            m = k->intersect4(P, (cylray_ray4 *)(void *)ray, (cylray_hit4 *)(void *)hit, active,
                              flags);
            break;
        case 8:
            m = k->intersect8(P, (cylray_ray8 *)(void *)ray, (cylray_hit8 *)(void *)hit, active,
                              flags);
            break;
        default:
            m = k->intersect16(P, (cylray_ray16 *)(void *)ray, (cylray_hit16 *)(void *)hit,
                               active, flags);
            break;
        }
    }

    int bad = 0;
    const uint32_t lanes = (1u << w) - 1u;
    if (m & ~(active & lanes)) {
        bad++;
        CHECK(0, "%s: hit mask %#x reports lanes that were not active", ctx, m);
    }
    memset(out, 0, sizeof *out);
    out->hit = m & active & lanes;
    out->count = (size_t)__builtin_popcount(out->hit);
    for (size_t i = 0; i < W; i++) {
        out->t[i] = hit[i];
        out->nx[i] = hit[W + i];
        out->ny[i] = hit[2 * W + i];
        out->nz[i] = hit[3 * W + i];
        memcpy(&out->part[i], hit + 4 * W + i, sizeof(int32_t));
        out->tmax[i] = ray[7 * W + i];
        for (int f = 0; f < G_TMAX; f++)
            if (!same(ray[(size_t)f * W + i], in->f[f][i])) {
                bad++;
                CHECK(0, "%s lane %zu: input field %d was written", ctx, i, f);
            }
        if (occluded) {
            if (!same(out->tmax[i], in->f[G_TMAX][i])) {
                bad++;
                CHECK(0, "%s lane %zu: occluded wrote tmax", ctx, i);
            }
            continue;
        }
        bad += check_lane(ctx, in, i, (int)((out->hit >> i) & 1u), flags, out);
    }
    if (occluded)
        for (size_t i = 0; i < 4 * W; i++) {
            int32_t p;
            memcpy(&p, hit + 4 * W + i % W, sizeof p);
            if (!is_poison(hit[i]) || p != G_POISON_PART) {
                bad++;
                CHECK(0, "%s: occluded wrote a hit record", ctx);
                break;
            }
        }
    bad += garr_close(&ra, "ray packet", ctx);
    bad += garr_close(&ha, "hit packet", ctx);
    return bad;
}

/* ---- streams ------------------------------------------------------------- */

static int stream_run(const cylray_kernels *k, const cylray_prepared *P, const gbatch *in,
                      size_t n, unsigned flags, unsigned misalign, int occluded, gresult *out)
{
    char ctx[160];
    const char *op = occluded ? "occluded" : "intersect";
    context(ctx, sizeof ctx, k, G_STREAM, n, 0, flags, misalign, op);
    const size_t lead = misalign * sizeof(float);
    garr ra[G_NFIELD], ha[5], oa;
    float *f[G_NFIELD];
    for (int j = 0; j < G_NFIELD; j++) {
        f[j] = garr_open(&ra[j], n * sizeof(float), lead);
        memcpy(f[j], in->f[j], n * sizeof(float));
    }
    float *h[4];
    for (int j = 0; j < 4; j++) {
        h[j] = garr_open(&ha[j], n * sizeof(float), lead);
        for (size_t i = 0; i < n; i++)
            h[j][i] = g_poison();
    }
    int32_t *part = garr_open(&ha[4], n * sizeof(int32_t), lead);
    for (size_t i = 0; i < n; i++)
        part[i] = G_POISON_PART;
    uint8_t *occ = garr_open(&oa, n, misalign);
    memset(occ, G_POISON_OCC, n);
    for (int j = 0; j < G_NFIELD; j++)
        garr_arm(&ra[j]);
    for (int j = 0; j < 5; j++)
        garr_arm(&ha[j]);
    garr_arm(&oa);

    /* Without CYLRAY_NORMAL the header allows NULL normal arrays: pass NULL on odd
     * misalignments, real (poisoned) arrays that must stay untouched otherwise. */
    const int null_normals = !(flags & CYLRAY_NORMAL) && (misalign & 1u);
    cylray_rays R = {f[0], f[1], f[2], f[3], f[4], f[5], f[6], f[7]};
    cylray_hits H = {h[0], null_normals ? NULL : h[1], null_normals ? NULL : h[2],
                     null_normals ? NULL : h[3], part};
    size_t cnt = occluded ? k->occluded_stream(P, &R, occ, n, flags)
                          : k->intersect_stream(P, &R, &H, n, flags);

    int bad = 0;
    memset(out, 0, sizeof *out);
    out->count = cnt;
    size_t written = 0;
    for (size_t i = 0; i < n; i++) {
        out->t[i] = h[0][i];
        out->nx[i] = h[1][i];
        out->ny[i] = h[2][i];
        out->nz[i] = h[3][i];
        out->part[i] = part[i];
        out->tmax[i] = f[7][i];
        for (int j = 0; j < G_TMAX; j++)
            if (!same(f[j][i], in->f[j][i])) {
                bad++;
                CHECK(0, "%s ray %zu: input field %d was written", ctx, i, j);
            }
        if (occluded) {
            if (occ[i] == 1) {
                out->hit |= 1ull << i;
                written++;
            } else if (occ[i] != G_POISON_OCC) {
                bad++;
                CHECK(0, "%s ray %zu: occluded[i] = %u, expected 1 or untouched", ctx, i,
                      occ[i]);
            }
            if (!same(out->tmax[i], in->f[G_TMAX][i])) {
                bad++;
                CHECK(0, "%s ray %zu: occluded wrote tmax", ctx, i);
            }
            if (!is_poison(h[0][i]) || part[i] != G_POISON_PART) {
                bad++;
                CHECK(0, "%s ray %zu: occluded wrote a hit record", ctx, i);
            }
            continue;
        }
        /* A stream has no mask to say which rays hit: a written part says it. */
        int hit =
            part[i] != G_POISON_PART || !is_poison(h[0][i]) || !same(f[7][i], in->f[G_TMAX][i]);
        if (hit) {
            out->hit |= 1ull << i;
            written++;
        }
        bad += check_lane(ctx, in, i, hit, flags, out);
    }
    if (!occluded)
        for (size_t i = 0; i < n; i++)
            if (occ[i] != G_POISON_OCC) {
                bad++;
                CHECK(0, "%s: intersect wrote the occluded array", ctx);
                break;
            }
    if (written != cnt) {
        bad++;
        CHECK(0, "%s: returned %zu hits, wrote %zu", ctx, cnt, written);
    }
    static const char *const names[G_NFIELD] = {"ox", "oy", "oz",   "dx",
                                                "dy", "dz", "tmin", "tmax"};
    static const char *const hnames[5] = {"t", "nx", "ny", "nz", "part"};
    for (int j = 0; j < G_NFIELD; j++)
        bad += garr_close(&ra[j], names[j], ctx);
    for (int j = 0; j < 5; j++)
        bad += garr_close(&ha[j], hnames[j], ctx);
    bad += garr_close(&oa, "occluded", ctx);
    return bad;
}

static int run(const cylray_kernels *k, int width, const cylray_prepared *P, const gbatch *in,
               size_t n, uint32_t active, unsigned flags, unsigned misalign, int occluded,
               gresult *out)
{
    if (width == G_STREAM) {
        if (n > G_MAX || misalign > 15) {
            fprintf(stderr, "guarded: bad stream request n=%zu misalign=%u\n", n, misalign);
            exit(2);
        }
        return stream_run(k, P, in, n, flags, misalign, occluded, out);
    }
    if ((width != 4 && width != 8 && width != 16) || n != (size_t)width) {
        fprintf(stderr, "guarded: bad packet request width=%d n=%zu\n", width, n);
        exit(2);
    }
    return packet_run(k, width, P, in, active, flags, occluded, out);
}

int g_intersect(const cylray_kernels *k, int width, const cylray_prepared *P, const gbatch *in,
                size_t n, uint32_t active, unsigned flags, unsigned misalign, gresult *out)
{
    return run(k, width, P, in, n, active, flags, misalign, 0, out);
}

int g_occluded(const cylray_kernels *k, int width, const cylray_prepared *P, const gbatch *in,
               size_t n, uint32_t active, unsigned flags, unsigned misalign, gresult *out)
{
    return run(k, width, P, in, n, active, flags, misalign, 1, out);
}
