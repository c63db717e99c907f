/* SPDX-License-Identifier: MIT */
/* timing.c - the timed loops: one pass of a batch through one ISA's kernel at one width,
 * warm-up, repeated samples, median and spread.
 *
 * Per-ISA timing goes through the cylray_kernels table's pointers (the plain entry
 * points would always take the best path). A pass restores each packet's tmax before
 * the call, because a hit lowers it and REFINE may then reject its own unrefined root:
 * the restore is a 16..64-byte copy per packet, the price any tracer pays to start a
 * ray. Hit counts are summed into a volatile sink, so no pass can be optimised away. */
#include "bench.h"
#include "clock.h"
#include "internal/compiler.h" /* CYLRAY_POPCOUNT, the library's own lane count */
#include "timing_run.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

const int bench_width_lanes[BW_COUNT] = {4, 8, 16, 0};
const char *const bench_width_name[BW_COUNT] = {"4", "8", "16", "stream"};
const char *const bench_op_name[OP_COUNT] = {"t", "normal", "occluded", "refine", "fast"};
const unsigned bench_op_flags[OP_COUNT] = {0u, CYLRAY_NORMAL, 0u, CYLRAY_NORMAL | CYLRAY_REFINE,
                                           CYLRAY_NORMAL | CYLRAY_FAST};

static volatile uint64_t sink; /* where every pass's hit count ends up */

const char *bench_isa_name(int isa)
{
    return bench_is_textbook(isa) ? tb_variant_name(isa - BENCH_ISA_TEXTBOOK)
                                  : cylray_isa_name((cylray_isa)isa);
}

result *results_push(result_list *l)
{
    if (l->n == l->cap) {
        size_t cap = l->cap ? 2 * l->cap : 256;
        result *r = realloc(l->r, cap * sizeof *r);
        if (!r)
            return NULL;
        l->r = r;
        l->cap = cap;
    }
    result *r = &l->r[l->n++];
    memset(r, 0, sizeof *r);
    return r;
}

/* The hit lanes of a packet, counted as the library counts its streams': on any x86-64
 * this file is compiled for, __builtin_popcount is a call into libgcc, which would be
 * timed with every packet. */
static inline unsigned popc(uint32_t m)
{
    return CYLRAY_POPCOUNT(m);
}

/* One pass over batch b for packets of N lanes: every packet against every cylinder,
 * keeping the closest hit through tmax (occlusion stops once all lanes are blocked);
 * or, for grouped sets, each packet against its own group's cylinder. */
#define PASS_PACKET(N)                                                                         \
    static uint64_t pass_##N(const runner *x, size_t b)                                        \
    {                                                                                          \
        cylray_ray##N *pk = (cylray_ray##N *)x->pk + b * x->ppb;                               \
        cylray_hit##N *h = (cylray_hit##N *)x->hit + b * x->ppb;                               \
        const float *t0 = x->w->rays.tmax + b * x->w->batch;                                   \
        const cylray_prepared *P = x->w->prep;                                                 \
        const int nc = x->w->ncyl;                                                             \
        const size_t grp = (size_t)x->w->grouped, first = b * x->w->batch;                     \
        const unsigned fl = x->flags;                                                          \
        const uint32_t full = (uint32_t)((1ull << N) - 1u) & x->w->lanes;                      \
        uint64_t acc = 0;                                                                      \
        if (x->op == OP_OCC) {                                                                 \
            const cylray_occluded##N##_fn f = x->k->occluded##N;                               \
            if (grp) {                                                                         \
                for (size_t p = 0; p < x->ppb; p++)                                            \
                    acc += popc(f(P + (first + p * N) / grp, pk + p, full, fl));               \
                return acc;                                                                    \
            }                                                                                  \
            for (size_t p = 0; p < x->ppb; p++) {                                              \
                uint32_t m = 0;                                                                \
                for (int c = 0; c < nc && m != full; c++)                                      \
                    m |= f(P + c, pk + p, full & ~m, fl);                                      \
                acc += popc(m);                                                                \
            }                                                                                  \
            return acc;                                                                        \
        }                                                                                      \
        const cylray_intersect##N##_fn f = x->k->intersect##N;                                 \
        if (grp) {                                                                             \
            for (size_t p = 0; p < x->ppb; p++) {                                              \
                memcpy(pk[p].tmax, t0 + p * N, sizeof pk[p].tmax);                             \
                acc += popc(f(P + (first + p * N) / grp, pk + p, h + p, full, fl));            \
            }                                                                                  \
            return acc;                                                                        \
        }                                                                                      \
        for (size_t p = 0; p < x->ppb; p++) {                                                  \
            uint32_t m = 0;                                                                    \
            memcpy(pk[p].tmax, t0 + p * N, sizeof pk[p].tmax);                                 \
            for (int c = 0; c < nc; c++)                                                       \
                m |= f(P + c, pk + p, h + p, full, fl);                                        \
            acc += popc(m);                                                                    \
        }                                                                                      \
        return acc;                                                                            \
    }
PASS_PACKET(4)
PASS_PACKET(8)
PASS_PACKET(16)

static cylray_rays stream_rays(const runner *x, size_t off)
{
    const raysoa *r = &x->w->rays;
    cylray_rays R = {r->ox + off, r->oy + off, r->oz + off,   r->dx + off,
                     r->dy + off, r->dz + off, r->tmin + off, x->tmax + off};
    return R;
}

static cylray_hits stream_hits(const runner *x, size_t off)
{
    cylray_hits H = {x->t + off, x->nx + off, x->ny + off, x->nz + off, x->part + off};
    return H;
}

/* The stream API has no lane mask, so with several cylinders every one sees every ray;
 * grouped sets call it once per group; a big stream's tmax is restored outside the
 * timed region (restore_outside). */
static uint64_t pass_stream(const runner *x, size_t b)
{
    const size_t n = x->w->batch, off = b * n, grp = (size_t)x->w->grouped;
    const cylray_prepared *P = x->w->prep;
    uint64_t acc = 0;
    if (!x->restore_outside && x->op != OP_OCC)
        memcpy(x->tmax + off, x->w->rays.tmax + off, n * sizeof(float));
    if (grp) {
        for (size_t g = off; g < off + n; g += grp) {
            cylray_rays R = stream_rays(x, g);
            cylray_hits H = stream_hits(x, g);
            if (x->op == OP_OCC)
                acc += x->k->occluded_stream(P + g / grp, &R, x->occ + g, grp, x->flags);
            else
                acc += x->k->intersect_stream(P + g / grp, &R, &H, grp, x->flags);
        }
        return acc;
    }
    cylray_rays R = stream_rays(x, off);
    if (x->op == OP_OCC) {
        for (int c = 0; c < x->w->ncyl; c++)
            acc += x->k->occluded_stream(P + c, &R, x->occ + off, n, x->flags);
        return acc;
    }
    cylray_hits H = stream_hits(x, off);
    for (int c = 0; c < x->w->ncyl; c++)
        acc += x->k->intersect_stream(P + c, &R, &H, n, x->flags);
    return acc;
}

/* The textbook peer through the same stream contract (single shape or grouped). */
static uint64_t pass_textbook(const runner *x, size_t b)
{
    const size_t n = x->w->batch, off = b * n;
    const size_t grp = x->w->grouped ? (size_t)x->w->grouped : n;
    if (!x->restore_outside)
        memcpy(x->tmax + off, x->w->rays.tmax + off, n * sizeof(float));
    uint64_t acc = 0;
    for (size_t g = off; g < off + n; g += grp) {
        cylray_rays R = stream_rays(x, g);
        cylray_hits H = stream_hits(x, g);
        const size_t c = x->w->grouped ? g / grp : 0;
        acc += x->tbs   ? x->tbs(&x->w->tbs[c], &R, &H, grp)
               : x->tbc ? x->tbc(&x->w->tbc[c], &R, &H, grp)
                        : x->tb(&x->w->tb[c], &R, &H, grp);
    }
    return acc;
}

/* Packs the rays into packets of the width, or allocates the stream's outputs. */
#define PACK(N)                                                                                \
    do {                                                                                       \
        cylray_ray##N *pk = bench_alloc(x->np * sizeof *pk);                                   \
        x->pk = pk;                                                                            \
        x->hit = bench_alloc(x->np * sizeof(cylray_hit##N));                                   \
        if (!pk || !x->hit)                                                                    \
            return -1;                                                                         \
        for (size_t g = 0; g < x->np; g++)                                                     \
            for (int l = 0; l < N; l++) {                                                      \
                size_t i = g * N + (size_t)l;                                                  \
                pk[g].ox[l] = r->ox[i], pk[g].oy[l] = r->oy[i], pk[g].oz[l] = r->oz[i];        \
                pk[g].dx[l] = r->dx[i], pk[g].dy[l] = r->dy[i], pk[g].dz[l] = r->dz[i];        \
                pk[g].tmin[l] = r->tmin[i], pk[g].tmax[l] = r->tmax[i];                        \
            }                                                                                  \
        x->pass = pass_##N;                                                                    \
    } while (0)

int runner_init(runner *x, const workload *w, int isa, int width_id, int op)
{
    memset(x, 0, sizeof *x);
    x->w = w;
    x->op = op;
    x->flags = bench_op_flags[op];
    x->width_id = width_id;
    x->restore_outside = w->big;
    const raysoa *r = &w->rays;
    if (bench_is_textbook(isa)) {
        if (w->sph)
            x->tbs = tb_sphere_variant(isa - BENCH_ISA_TEXTBOOK);
        else if (w->con)
            x->tbc = tb_cone_variant(isa - BENCH_ISA_TEXTBOOK);
        else
            x->tb = tb_variant(isa - BENCH_ISA_TEXTBOOK);
        if ((!x->tb && !x->tbs && !x->tbc) || op != OP_NORMAL || width_id != BW_STREAM)
            return -1;
        x->pass = pass_textbook;
    } else {
        x->k = cylray_kernels_for((cylray_isa)isa);
        if (!x->k)
            return -1;
    }
    int lanes = bench_width_lanes[width_id];
    if (lanes) {
        x->np = r->n / (size_t)lanes;
        x->ppb = w->batch / (size_t)lanes;
        if (lanes == 4)
            PACK(4);
        else if (lanes == 8)
            PACK(8);
        else
            PACK(16);
        return 0;
    }
    size_t n = r->n;
    x->tmax = bench_alloc(n * sizeof(float));
    if (!x->tmax)
        return -1;
    memcpy(x->tmax, r->tmax, n * sizeof(float));
    if (op == OP_OCC) {
        x->occ = bench_alloc(n);
        if (!x->occ)
            return -1;
    } else {
        x->t = bench_alloc(n * sizeof(float));
        x->part = bench_alloc(n * sizeof(int32_t));
        if (!x->t || !x->part)
            return -1;
        for (size_t i = 0; i < n; i++)
            x->part[i] = -1; /* a miss leaves it: run_once reads hits from here */
        if (x->flags & CYLRAY_NORMAL) {
            x->nx = bench_alloc(n * sizeof(float));
            x->ny = bench_alloc(n * sizeof(float));
            x->nz = bench_alloc(n * sizeof(float));
            if (!x->nx || !x->ny || !x->nz)
                return -1;
        }
    }
    if (!x->pass)
        x->pass = pass_stream;
    return 0;
}

void runner_free(runner *x)
{
    void *p[] = {x->pk, x->hit, x->tmax, x->t, x->nx, x->ny, x->nz, x->part, x->occ};
    for (size_t i = 0; i < sizeof p / sizeof p[0]; i++)
        bench_free(p[i]);
    memset(x, 0, sizeof *x);
}

static void restore_all(runner *x)
{
    if (x->tmax)
        memcpy(x->tmax, x->w->rays.tmax, x->w->rays.n * sizeof(float));
}

int bench_sample(const workload *w, int isa, int width_id, int op, const options *opt,
                 result *res, int want, int first_of_isa)
{
    runner x;
    if (runner_init(&x, w, isa, width_id, op)) {
        runner_free(&x);
        return -1;
    }
    const size_t nb = w->rays.n / w->batch;
    const double per_sample = (double)w->batch * bench_tests_per_ray(w);
    uint64_t acc = 0;

    /* Warm-up, on the first visit: caches, branch predictors, and on AVX-512 the wide
     * units and the clock licence; the first configuration of each ISA warms for
     * longer. It also times a pass, which sizes the samples. A big stream needs none:
     * its arrays were written when allocated (no page faults left), it cannot be cached,
     * and a sample is one pass whatever the pass takes. Later visits run one untimed pass
     * over the sample's batch before timing it. */
    if (w->big) {
        res->passes_per_sample = 1;
    } else if (res->passes_per_sample == 0) {
        double warm = first_of_isa ? opt->warm_ns : 2 * opt->sample_ns;
        int passes = 0;
        double t0 = clk_ns(), pass_ns = 0;
        do {
            double a = clk_ns();
            acc += x.pass(&x, 0);
            pass_ns += clk_ns() - a;
            passes++;
        } while (passes < 2 || clk_ns() - t0 < warm);
        pass_ns /= passes;
        long k = (long)ceil(opt->sample_ns / (pass_ns > 1 ? pass_ns : 1));
        res->passes_per_sample = k < 1 ? 1 : k;
    }
    const long K = res->passes_per_sample;

    /* Samples: wall time, the thread's CPU time and TSC ticks. A sample during which
     * the thread lost the CPU (another process on this 2-core machine) is marked
     * unclean and retaken, up to 8 tries per wanted sample (a big stream: no retries). */
    const int max_try = w->big ? want : 8 * want;
    int clean = 0;
    for (int tries = 0; tries < max_try && clean < want && res->samples < BENCH_MAXSAMP;
         tries++) {
        size_t b = (size_t)res->samples % nb;
        if (x.restore_outside)
            restore_all(&x);
        else
            acc += x.pass(&x, b); /* untimed: batch b into L1, the predictors trained */
        uint64_t hits = 0;
        double p0 = clk_cpu_ns(), a0 = clk_ns();
        uint64_t c0 = clk_ticks();
        for (long k = 0; k < K; k++)
            hits += x.pass(&x, b);
        uint64_t c1 = clk_ticks();
        double a1 = clk_ns(), p1 = clk_cpu_ns();
        double per = (double)K * per_sample;
        int i = res->samples++;
        res->s_wall[i] = (a1 - a0) / per;
        res->s_cpu[i] = (p1 - p0) / per;
        res->s_tick[i] = (double)(c1 - c0) / per;
        res->s_clean[i] = p1 - p0 >= 0.95 * (a1 - a0);
        clean += res->s_clean[i];
        acc += hits;
    }
    sink = sink + acc;
    res->rays_timed = w->batch;
    res->ncyl = bench_tests_per_ray(w);
    runner_free(&x);
    return 0;
}

void bench_summarize(const workload *w, result *res, int reps)
{
    double ns[BENCH_MAXSAMP], tk[BENCH_MAXSAMP];
    int clean = 0;
    for (int i = 0; i < res->samples; i++)
        if (res->s_clean[i]) {
            ns[clean] = res->s_wall[i];
            tk[clean++] = res->s_tick[i];
        }
    res->clean = clean;
    /* Wall time over the clean samples when there are enough of them; otherwise the
     * thread's CPU time over all of them (marked: the machine was too busy). */
    if (clean >= 1 && clean >= (reps + 1) / 2) {
        stat_summary(ns, (size_t)clean, &res->ns);
        stat5 ts;
        stat_summary(tk, (size_t)clean, &ts);
        res->ticks = ts.med;
        res->reps = clean;
        res->cpu_timed = 0;
    } else {
        for (int i = 0; i < res->samples; i++)
            ns[i] = res->s_cpu[i];
        stat_summary(ns, (size_t)res->samples, &res->ns);
        res->ticks = res->ns.med * clk_tsc_ghz();
        res->reps = res->samples;
        res->cpu_timed = 1;
    }
    res->mrays = res->ns.med > 0 ? 1e3 / res->ns.med : 0;
    if (w->big) /* the bytes a ray stream moves: 8 input floats per ray */
        res->gbytes_s = 32.0 / res->ns.med;
}

/* The lane's outputs from a packet array of N lanes. */
#define LANE_OUT(N)                                                                            \
    do {                                                                                       \
        const cylray_hit##N *hh = (const cylray_hit##N *)x.hit + i / N;                        \
        pt = hh->part[i % N], tt = hh->t[i % N];                                               \
    } while (0)

int bench_run_once(const workload *w, int isa, int width_id, int op, uint8_t *hit, float *t,
                   int32_t *part)
{
    runner x;
    if (runner_init(&x, w, isa, width_id, op)) {
        runner_free(&x);
        return -1;
    }
    const size_t n = w->rays.n, nb = n / w->batch;
    const int lanes = bench_width_lanes[width_id];
    for (size_t b = 0; b < nb; b++) {
        if (x.restore_outside && x.tmax)
            memcpy(x.tmax + b * w->batch, w->rays.tmax + b * w->batch,
                   w->batch * sizeof(float));
        x.pass(&x, b);
    }
    memset(hit, 0, n);
    if (op == OP_OCC) {
        if (!lanes) {
            memcpy(hit, x.occ, n);
        } else {
            /* The pass keeps only counts; the masks come from the same calls again. */
            const cylray_prepared *P = w->prep;
            const uint32_t full = (uint32_t)((1ull << lanes) - 1u) & w->lanes;
            for (size_t g = 0; g < x.np; g++) {
                uint32_t m = 0;
                int c0 = 0, c1 = w->ncyl;
                if (w->grouped)
                    c0 = (int)(g * (size_t)lanes / (size_t)w->grouped), c1 = c0 + 1;
                for (int c = c0; c < c1 && m != full; c++) {
                    if (lanes == 4)
                        m |= x.k->occluded4(P + c, (cylray_ray4 *)x.pk + g, full & ~m, x.flags);
                    else if (lanes == 8)
                        m |= x.k->occluded8(P + c, (cylray_ray8 *)x.pk + g, full & ~m, x.flags);
                    else
                        m |= x.k->occluded16(P + c, (cylray_ray16 *)x.pk + g, full & ~m,
                                             x.flags);
                }
                for (int l = 0; l < lanes; l++)
                    hit[g * (size_t)lanes + (size_t)l] = (uint8_t)(m >> l & 1u);
            }
        }
        runner_free(&x);
        return 0;
    }
    /* A lane hit iff the kernel wrote its part: packet hit arrays start zeroed
     * (CYLRAY_MISS, which the kernel never writes), stream parts start at -1. */
    for (size_t i = 0; i < n; i++) {
        int32_t pt;
        float tt;
        if (lanes == 4)
            LANE_OUT(4);
        else if (lanes == 8)
            LANE_OUT(8);
        else if (lanes == 16)
            LANE_OUT(16);
        else
            pt = x.part[i], tt = x.t[i];
        if (pt > 0) {
            hit[i] = 1;
            t[i] = tt;
            part[i] = pt;
        }
    }
    runner_free(&x);
    return 0;
}

double bench_memcpy_gbs(const workload *w, const options *opt)
{
    const raysoa *r = &w->rays;
    size_t n = r->n, bytes = n * sizeof(float);
    /* eight destination arrays, as large as the sources: nothing stays in a cache */
    float *dst = bench_alloc(8 * bytes);
    if (!dst)
        return 0;
    const float *src[8] = {r->ox, r->oy, r->oz, r->dx, r->dy, r->dz, r->tmin, r->tmax};
    int reps = opt->reps < 3 ? 3 : opt->reps;
    double *s = malloc((size_t)reps * sizeof *s);
    if (!s) {
        bench_free(dst);
        return 0;
    }
    for (int k = 0; k <= reps; k++) {
        double a = clk_ns();
        for (int f = 0; f < 8; f++) {
            memcpy(dst + (size_t)f * n, src[f], bytes);
            sink = sink + (uint64_t)dst[(size_t)f * n + (size_t)f * 977 % n];
        }
        double e = clk_ns() - a;
        if (k > 0) /* the first copy is the warm-up */
            s[k - 1] = 8.0 * (double)bytes / e;
    }
    stat5 st;
    stat_summary(s, (size_t)reps, &st);
    free(s);
    bench_free(dst);
    return st.med;
}
