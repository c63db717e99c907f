/* SPDX-License-Identifier: MIT */
/* timing.c - the timing of one scene with one ISA (timing.h). */
#include "timing.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int eb_frame_alloc(eb_frame *f, size_t n)
{
    memset(f, 0, sizeof *f);
    f->shadow_tfar = malloc(n * sizeof *f->shadow_tfar);
    return !f->shadow_tfar || eb_rays_alloc(&f->prim, n) || eb_rays_alloc(&f->shadow, n) ||
                   eb_rays_alloc(&f->bounce, n)
               ? -1
               : 0;
}

void eb_frame_free(eb_frame *f)
{
    eb_rays_free(&f->prim);
    eb_rays_free(&f->shadow);
    eb_rays_free(&f->bounce);
    free(f->shadow_tfar);
}

static double mrays(size_t n, double s)
{
    return s > 0 ? (double)n / s * 1e-6 : NAN;
}

/* Best of `reps` passes (min time: the machine is shared, a busy spell only slows);
 * *cores (if not NULL) gets the CPU time over the wall time of that pass. With
 * t->cpu_clock the rates come from the CPU time the process got (over the threads),
 * which a machine shared with other work distorts less than the wall time. */
static double timed(const eb_timing *t, RTCScene sc, eb_rays *r, const float *tfar0, int packet,
                    int threads, int occ, double *cores)
{
    double best = INFINITY;
    size_t valid = 0;
    for (size_t i = 0; i < r->n; i++)
        valid += r->valid[i];
    for (int k = 0; k < t->reps; k++) {
        for (size_t i = 0; i < r->n; i++)
            r->tfar[i] = tfar0 ? tfar0[i] : INFINITY;
        double cpu, s = eb_trace(sc, r, packet, threads, occ, &cpu), wall = s;
        if (t->cpu_clock)
            s = cpu / threads;
        if (s < best && cores)
            *cores = cpu / wall;
        best = s < best ? s : best;
    }
    return mrays(valid, best);
}

eb_spread eb_spread_of(const double *x, int n)
{
    double v[EB_MAXRUNS];
    int m = 0;
    for (int i = 0; i < n && m < EB_MAXRUNS; i++) {
        if (isnan(x[i]))
            continue;
        int j = m++; /* insertion sort */
        for (; j > 0 && v[j - 1] > x[i]; j--)
            v[j] = v[j - 1];
        v[j] = x[i];
    }
    if (!m)
        return (eb_spread){NAN, NAN, NAN};
    return (eb_spread){(v[(m - 1) / 2] + v[m / 2]) / 2, v[0], v[m - 1]};
}

/* Scratch for the scaling passes: [variant][threads][run], a figure's runs side by side. */
typedef struct scaling_runs {
    double *rate, *cores;
} scaling_runs;

static size_t at(const eb_timing *t, int v, int n, int run)
{
    return ((size_t)v * (size_t)(t->threads + 1) + (size_t)n) * (size_t)t->runs + (size_t)run;
}

/* Primary rays, one ray a call, at 1..threads threads. */
static void time_scaling(const eb_timing *t, const eb_geom *geo, eb_frame *fr, const int *built,
                         int run, scaling_runs *s)
{
    for (int n = 1; n <= t->threads; n++)
        for (int v = 0; v < EB_NVARIANTS; v++)
            if (built[v])
                s->rate[at(t, v, n, run)] = timed(t, geo[v].scene, &fr[v].prim, NULL, 1, n, 0,
                                                  &s->cores[at(t, v, n, run)]);
}

/* Each variant at each packet size, one run: the primary rays (primary = 1), or the
 * bounce and shadow rays (0). */
static void time_packets(const eb_timing *t, cylray_isa isa, const eb_geom *geo, eb_frame *fr,
                         const int *built, eb_row *rows, int run, int primary)
{
    /* Embree offers a packet no wider than its ISA's vectors */
    int widest = isa == CYLRAY_ISA_SSE41 ? 4 : isa == CYLRAY_ISA_AVX2 ? 8 : 16;
    for (int q = 0; q < EB_NPACKETS; q++) {
        if (!t->packet_on[q] || eb_packets[q] > widest)
            continue;
        int k = eb_packets[q], T = t->threads;
        for (int v = 0; v < EB_NVARIANTS; v++) {
            if (!built[v])
                continue;
            double(*m)[EB_NPACKETS][EB_MAXRUNS] = rows[v].mrays_run;
            eb_frame *f = &fr[v];
            RTCScene sc = geo[v].scene;
            if (primary) {
                m[EB_PRIMARY][q][run] = timed(t, sc, &f->prim, NULL, k, T, 0, NULL);
            } else {
                m[EB_BOUNCE][q][run] = timed(t, sc, &f->bounce, NULL, k, T, 0, NULL);
                m[EB_SHADOW][q][run] = timed(t, sc, &f->shadow, f->shadow_tfar, k, T, 1, NULL);
            }
        }
    }
}

static void spawn(const eb_geom *geo, eb_frame *fr, const int *built)
{
    for (int v = 0; v < EB_NVARIANTS; v++) {
        if (!built[v])
            continue;
        eb_spawn(&geo[v], &fr[v].prim, &fr[v].shadow, &fr[v].bounce);
        memcpy(fr[v].shadow_tfar, fr[v].shadow.tfar, fr[v].prim.n * sizeof(float));
    }
}

/* The medians of a variant's runs. */
static void medians(const eb_timing *t, const scaling_runs *s, int v, eb_row *r)
{
    for (int p = 0; p < EB_NPHASES; p++)
        for (int q = 0; q < EB_NPACKETS; q++)
            r->mrays[p][q] = eb_spread_of(r->mrays_run[p][q], t->runs).med;
    for (int n = 1; n <= t->threads; n++) {
        int ok = s->rate != NULL;
        r->scaling[n] = ok ? eb_spread_of(&s->rate[at(t, v, n, 0)], t->runs).med : NAN;
        r->cores[n] = ok ? eb_spread_of(&s->cores[at(t, v, n, 0)], t->runs).med : NAN;
    }
}

void eb_time_scene(const eb_timing *t, cylray_isa isa, const eb_geom geo[EB_NVARIANTS],
                   eb_frame fr[EB_NVARIANTS], const int built[EB_NVARIANTS],
                   eb_row rows[EB_NVARIANTS])
{
    size_t ns = at(t, EB_NVARIANTS, 0, 0);
    double *scratch = malloc(2 * ns * sizeof(double));
    scaling_runs s = {scratch, scratch ? scratch + ns : NULL}; /* NULL: no scaling */
    /* Run after run, each measurement visits every variant in turn, so that a busy
     * spell of the shared machine lands on every variant alike, and a run's ratio of
     * two variants compares passes made close together. */
    for (int run = 0; run < t->runs; run++) {
        if (s.rate)
            time_scaling(t, geo, fr, built, run, &s);
        time_packets(t, isa, geo, fr, built, rows, run, 1);
        if (run == 0)
            spawn(geo, fr, built);
        time_packets(t, isa, geo, fr, built, rows, run, 0);
    }
    for (int v = 0; v < EB_NVARIANTS; v++)
        if (built[v])
            medians(t, &s, v, &rows[v]);
    free(scratch);
}
