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

void eb_time_scene(const eb_timing *t, cylray_isa isa, const eb_geom geo[EB_NVARIANTS],
                   eb_frame fr[EB_NVARIANTS], const int built[EB_NVARIANTS],
                   eb_row rows[EB_NVARIANTS])
{
    /* each measurement visits every variant in turn, so a busy spell of the shared
     * machine does not land on one variant only */
    for (int n = 1; n <= t->threads; n++)
        for (int v = 0; v < EB_NVARIANTS; v++)
            if (built[v])
                rows[v].scaling[n] =
                    timed(t, geo[v].scene, &fr[v].prim, NULL, 1, n, 0, &rows[v].cores[n]);
    /* Embree offers a packet no wider than its ISA's vectors */
    int widest = isa == CYLRAY_ISA_SSE41 ? 4 : isa == CYLRAY_ISA_AVX2 ? 8 : 16;
    for (int q = 0; q < EB_NPACKETS; q++) {
        if (!t->packet_on[q] || eb_packets[q] > widest)
            continue;
        for (int v = 0; v < EB_NVARIANTS; v++)
            if (built[v])
                rows[v].mrays[EB_PRIMARY][q] = timed(t, geo[v].scene, &fr[v].prim, NULL,
                                                     eb_packets[q], t->threads, 0, NULL);
    }
    for (int v = 0; v < EB_NVARIANTS; v++) {
        if (!built[v])
            continue;
        eb_spawn(&geo[v], &fr[v].prim, &fr[v].shadow, &fr[v].bounce);
        memcpy(fr[v].shadow_tfar, fr[v].shadow.tfar, fr[v].prim.n * sizeof(float));
    }
    for (int q = 0; q < EB_NPACKETS; q++) {
        if (!t->packet_on[q] || eb_packets[q] > widest)
            continue;
        for (int v = 0; v < EB_NVARIANTS; v++)
            if (built[v]) {
                eb_row *r = &rows[v];
                eb_frame *f = &fr[v];
                r->mrays[EB_BOUNCE][q] = timed(t, geo[v].scene, &f->bounce, NULL, eb_packets[q],
                                               t->threads, 0, NULL);
                r->mrays[EB_SHADOW][q] = timed(t, geo[v].scene, &f->shadow, f->shadow_tfar,
                                               eb_packets[q], t->threads, 1, NULL);
            }
    }
}
