/* SPDX-License-Identifier: MIT */
/* drive.c - calling one path the way a tracer does (packets of 4, 8 and 16 with active
 * masks; streams of odd lengths at odd addresses) and checking what it may and may not
 * write: hit lanes get t, part, the normal (with CYLRAY_NORMAL) and tmax = t; missed
 * and inactive lanes keep every byte; the rays' inputs are never written. */
#include "check.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A NaN with a payload no kernel produces, so that a lane written with anything at all
 * differs from it bit for bit. */
#define POISON 0x7fa5a5a5u
#define POISON_BYTE 0x5a

static void poison(void *p, size_t bytes)
{
    uint32_t v = POISON;
    for (size_t i = 0; i + 4 <= bytes; i += 4)
        memcpy((char *)p + i, &v, 4);
}

static uint32_t bits_of(const void *p)
{
    uint32_t u;
    memcpy(&u, p, 4);
    return u;
}

/* Mostly every lane; else random lanes, a single lane, none; sometimes with garbage
 * above the packet's width, which the kernel must ignore. */
static uint32_t pick_active(cylgen_rng *r, int width)
{
    uint32_t full = width == 32 ? 0xffffffffu : (1u << width) - 1u;
    uint64_t u = cylgen_next(r);
    uint32_t a;
    switch (u % 10) {
    case 0:
    case 1:
    case 2:
        a = (uint32_t)(u >> 32) & full;
        break;
    case 3:
        a = 1u << ((u >> 32) % (unsigned)width);
        break;
    case 4:
        a = (u >> 40) % 8 == 0 ? 0 : full;
        break;
    default:
        a = full;
        break;
    }
    if ((u >> 20) % 8 == 0)
        a |= ~full & (uint32_t)cylgen_next(r);
    return a;
}

/* Checks lane j of a packet after the call. The packet's fields are passed as arrays
 * so that one function serves every width. */
typedef struct packet_view {
    const float *in[7]; /* ox oy oz dx dy dz tmin, after the call */
    const float *tmax;  /* after */
    const float *t, *nx, *ny, *nz;
    const int32_t *part;
} packet_view;

static void check_packet_lane(const lane_ctx *lc, const ref_case *rc, const packet_view *v,
                              int j, int active, int hit, const lane_out *scalar)
{
    const cylgen_case *c = &rc->c;
    const float want_in[7] = {c->o[0], c->o[1], c->o[2], c->d[0], c->d[1], c->d[2], c->tmin};
    for (int f = 0; f < 7; f++)
        if (bits_of(&v->in[f][j]) != bits_of(&want_in[f]))
            fail_memory(lc, rc, "ray input field %d was written", f);
    int normal = (lc->flags & CYLRAY_NORMAL) != 0;
    if (!hit) {
        if (bits_of(&v->tmax[j]) != bits_of(&c->tmax))
            fail_memory(lc, rc, "tmax written on a %s lane", active ? "missed" : "inactive");
        if (bits_of(&v->t[j]) != POISON || bits_of(&v->part[j]) != POISON ||
            bits_of(&v->nx[j]) != POISON || bits_of(&v->ny[j]) != POISON ||
            bits_of(&v->nz[j]) != POISON)
            fail_memory(lc, rc, "hit output written on a %s lane",
                        active ? "missed" : "inactive");
        if (!active)
            return;
    } else {
        if (bits_of(&v->tmax[j]) != bits_of(&v->t[j]))
            fail_memory(lc, rc, "tmax %a not set to t %a on a hit", (double)v->tmax[j],
                        (double)v->t[j]);
        if (!normal && (bits_of(&v->nx[j]) != POISON || bits_of(&v->ny[j]) != POISON ||
                        bits_of(&v->nz[j]) != POISON))
            fail_memory(lc, rc, "normal written without CYLRAY_NORMAL");
    }
    lane_out got = {hit, hit ? v->t[j] : 0, {0, 0, 0}, hit ? v->part[j] : 0};
    if (hit && normal) {
        got.n[0] = v->nx[j];
        got.n[1] = v->ny[j];
        got.n[2] = v->nz[j];
    }
    check_lane(lc, rc, &got, scalar);
}

#define DEFINE_PACKET(W)                                                                       \
    static void run_packet##W(const cylray_kernels *k, const cylray_prepared *p, lane_ctx *lc, \
                              const ref_case *rc, const lane_out *scalar, uint32_t active)     \
    {                                                                                          \
        cylray_ray##W ray, occ_ray;                                                            \
        cylray_hit##W hit;                                                                     \
        for (int j = 0; j < W; j++) {                                                          \
            const cylgen_case *c = &rc[j].c;                                                   \
            ray.ox[j] = c->o[0], ray.oy[j] = c->o[1], ray.oz[j] = c->o[2];                     \
            ray.dx[j] = c->d[0], ray.dy[j] = c->d[1], ray.dz[j] = c->d[2];                     \
            ray.tmin[j] = c->tmin, ray.tmax[j] = c->tmax;                                      \
        }                                                                                      \
        occ_ray = ray;                                                                         \
        poison(&hit, sizeof hit);                                                              \
        uint32_t m = k->intersect##W(p, &ray, &hit, active, lc->flags);                        \
        uint32_t o = k->occluded##W(p, &occ_ray, active, lc->flags);                           \
        uint32_t mine = W == 32 ? 0xffffffffu : (1u << W) - 1u;                                \
        if (m & ~(active & mine))                                                              \
            fail_memory(lc, rc, "intersect%d returned %#x for active %#x", W, m, active);      \
        if (o != m)                                                                            \
            fail_memory(lc, rc, "occluded%d returned %#x, intersect%d %#x (active %#x)", W, o, \
                        W, m, active);                                                         \
        packet_view v = {{ray.ox, ray.oy, ray.oz, ray.dx, ray.dy, ray.dz, ray.tmin},           \
                         ray.tmax,                                                             \
                         hit.t,                                                                \
                         hit.nx,                                                               \
                         hit.ny,                                                               \
                         hit.nz,                                                               \
                         hit.part};                                                            \
        for (int j = 0; j < W; j++) {                                                          \
            lc->lane = j;                                                                      \
            if (opt.only_case >= 0 && rc[j].index != opt.only_case)                            \
                continue;                                                                      \
            check_packet_lane(lc, &rc[j], &v, j, (int)(active >> j & 1), (int)(m >> j & 1),    \
                              scalar ? &scalar[j] : NULL);                                     \
            const cylgen_case *c = &rc[j].c;                                                   \
            if (bits_of(&occ_ray.tmax[j]) != bits_of(&c->tmax) ||                              \
                bits_of(&occ_ray.ox[j]) != bits_of(&c->o[0]))                                  \
                fail_memory(lc, &rc[j], "occluded%d wrote its ray", W);                        \
        }                                                                                      \
    }
DEFINE_PACKET(4)
DEFINE_PACKET(8)
DEFINE_PACKET(16)

void drive_packets(const cylray_kernels *k, unsigned flags, int category, const ref_case *cases,
                   size_t n, const lane_out *scalar, uint64_t seed)
{
    static const int widths[3] = {4, 8, 16};
    cylgen_rng r;
    cylgen_seed(&r, seed ^ (uint64_t)flags << 40 ^ (uint64_t)k->isa << 48 ^ (uint64_t)category);
    for (int wi = 0; wi < 3; wi++) {
        const int W = widths[wi];
        lane_ctx lc = {k, flags, category, wi == 0 ? "4" : wi == 1 ? "8" : "16", 0};
        for (size_t b = 0; b + CYLGEN_BATCH <= n; b += CYLGEN_BATCH) {
            cylray_prepared p;
            if (prepare_case(&p, &cases[b]) != CYLRAY_OK) {
                fail_memory(&lc, &cases[b], "cylray_prepare rejected the shape");
                continue;
            }
            for (size_t off = 0; off < CYLGEN_BATCH; off += (size_t)W) {
                const ref_case *rc = &cases[b + off];
                const lane_out *sc = scalar ? &scalar[b + off] : NULL;
                uint32_t active = pick_active(&r, W);
                if (W == 4)
                    run_packet4(k, &p, &lc, rc, sc, active);
                else if (W == 8)
                    run_packet8(k, &p, &lc, rc, sc, active);
                else
                    run_packet16(k, &p, &lc, rc, sc, active);
            }
        }
    }
}

/* ---- streams --------------------------------------------------------------------- */

#define GUARD 8

typedef struct stream_buf {
    float *block; /* 13 arrays of (n + 2 GUARD + 1) floats */
    float *a[12]; /* ox oy oz dx dy dz tmin tmax t nx ny nz, each shifted by 1 float */
    int32_t *part;
    uint8_t *occ;
    size_t n;
} stream_buf;

/* Poisoned stream arrays for n rays, holding the rays of rc[0..n). */
static void stream_load(stream_buf *s, const ref_case *rc, size_t n)
{
    size_t stride = n + 2 * GUARD + 1;
    s->n = n;
    s->block = malloc(13 * stride * sizeof(float));
    s->occ = malloc(n + 2 * GUARD);
    if (!s->block || !s->occ) {
        fprintf(stderr, "cylcheck: out of memory\n");
        exit(2);
    }
    poison(s->block, 13 * stride * sizeof(float));
    memset(s->occ, POISON_BYTE, n + 2 * GUARD);
    /* One float past an aligned start: the stream must not assume alignment. */
    for (int f = 0; f < 12; f++)
        s->a[f] = s->block + (size_t)f * stride + GUARD + 1;
    s->part = (int32_t *)(void *)(s->block + 12 * stride + GUARD + 1);
    for (size_t i = 0; i < n; i++) {
        const cylgen_case *c = &rc[i].c;
        const float in[8] = {c->o[0], c->o[1], c->o[2], c->d[0],
                             c->d[1], c->d[2], c->tmin, c->tmax};
        for (int f = 0; f < 8; f++)
            s->a[f][i] = in[f];
    }
}

static int guards_ok(const stream_buf *s)
{
    size_t stride = s->n + 2 * GUARD + 1;
    for (int f = 0; f < 13; f++) {
        const float *base = s->block + (size_t)f * stride;
        for (size_t i = 0; i < GUARD + 1; i++)
            if (bits_of(&base[i]) != POISON)
                return 0;
        for (size_t i = GUARD + 1 + s->n; i < stride; i++)
            if (bits_of(&base[i]) != POISON)
                return 0;
    }
    for (size_t i = 0; i < GUARD; i++)
        if (s->occ[i] != POISON_BYTE || s->occ[GUARD + s->n + i] != POISON_BYTE)
            return 0;
    return 1;
}

void drive_streams(const cylray_kernels *k, unsigned flags, int category, const ref_case *cases,
                   const size_t *lengths, size_t n_lengths, const lane_out *scalar,
                   uint64_t seed)
{
    (void)seed;
    lane_ctx lc = {k, flags, category, "stream", 0};
    size_t first = 0;
    for (size_t li = 0; li < n_lengths; first += lengths[li], li++) {
        const size_t n = lengths[li];
        const ref_case *rc = &cases[first];
        cylray_prepared p;
        if (prepare_case(&p, &rc[0]) != CYLRAY_OK) {
            fail_memory(&lc, rc, "cylray_prepare rejected the shape");
            continue;
        }
        stream_buf s;
        stream_load(&s, rc, n);
        int normal = (flags & CYLRAY_NORMAL) != 0;
        /* Without CYLRAY_NORMAL the normal arrays may be NULL: pass NULL every other
         * length, poisoned arrays otherwise. */
        int null_n = !normal && (li & 1);
        cylray_rays rays = {s.a[0], s.a[1], s.a[2], s.a[3], s.a[4], s.a[5], s.a[6], s.a[7]};
        cylray_hits hits = {s.a[8], null_n ? NULL : s.a[9], null_n ? NULL : s.a[10],
                            null_n ? NULL : s.a[11], s.part};
        size_t count = k->intersect_stream(&p, &rays, &hits, n, flags);

        /* The occluded stream sees the original tmax. */
        float *tmax_hit = malloc(n * sizeof(float));
        if (!tmax_hit) {
            fprintf(stderr, "cylcheck: out of memory\n");
            exit(2);
        }
        memcpy(tmax_hit, s.a[7], n * sizeof(float));
        for (size_t i = 0; i < n; i++)
            s.a[7][i] = rc[i].c.tmax;
        size_t occ_count = k->occluded_stream(&p, &rays, s.occ + GUARD, n, flags);

        size_t hits_seen = 0;
        packet_view v = {{s.a[0], s.a[1], s.a[2], s.a[3], s.a[4], s.a[5], s.a[6]},
                         tmax_hit,
                         s.a[8],
                         s.a[9],
                         s.a[10],
                         s.a[11],
                         s.part};
        for (size_t i = 0; i < n; i++) {
            lc.lane = (int)i;
            int hit = bits_of(&s.a[8][i]) != POISON;
            hits_seen += (size_t)hit;
            uint8_t ob = s.occ[GUARD + i];
            if (ob != (hit ? 1 : POISON_BYTE))
                fail_memory(&lc, &rc[i], "occluded_stream wrote %u for a %s", ob,
                            hit ? "hit" : "miss");
            if (opt.only_case >= 0 && rc[i].index != opt.only_case)
                continue;
            check_packet_lane(&lc, &rc[i], &v, (int)i, 1, hit,
                              scalar ? &scalar[first + i] : NULL);
        }
        if (count != hits_seen)
            fail_memory(&lc, rc, "intersect_stream returned %zu, wrote %zu hits (n %zu)", count,
                        hits_seen, n);
        if (occ_count != count)
            fail_memory(&lc, rc, "occluded_stream returned %zu, intersect_stream %zu (n %zu)",
                        occ_count, count, n);
        if (!guards_ok(&s))
            fail_memory(&lc, rc, "stream of %zu wrote outside its arrays", n);
        free(tmax_hit);
        free(s.block);
        free(s.occ);
    }
}

void scalar_answers(const cylray_kernels *scalar, unsigned flags, const ref_case *cases,
                    const size_t *segments, size_t n_segments, lane_out *out)
{
    size_t first = 0;
    for (size_t si = 0; si < n_segments; first += segments[si], si++) {
        size_t n = segments[si];
        const ref_case *rc = &cases[first];
        cylray_prepared p;
        for (size_t i = 0; i < n; i++)
            memset(&out[first + i], 0, sizeof out[0]);
        if (prepare_case(&p, &rc[0]) != CYLRAY_OK)
            continue;
        stream_buf s;
        stream_load(&s, rc, n);
        cylray_rays rays = {s.a[0], s.a[1], s.a[2], s.a[3], s.a[4], s.a[5], s.a[6], s.a[7]};
        cylray_hits hits = {s.a[8], s.a[9], s.a[10], s.a[11], s.part};
        scalar->intersect_stream(&p, &rays, &hits, n, flags);
        for (size_t i = 0; i < n; i++) {
            lane_out *o = &out[first + i];
            o->hit = bits_of(&s.a[8][i]) != POISON;
            if (!o->hit)
                continue;
            o->t = s.a[8][i];
            o->part = s.part[i];
            if (flags & CYLRAY_NORMAL)
                for (int f = 0; f < 3; f++)
                    o->n[f] = s.a[9 + f][i];
        }
        free(s.block);
        free(s.occ);
    }
}
