/* SPDX-License-Identifier: MIT */
/* threads.c - many threads make their first call at once. The plain entry
 * points choose their path on the first call; eight threads released together by a
 * barrier all make that first call, through every entry point, repeatedly. Every
 * thread must then see the same path and get answers bit-identical to one thread's.
 * run.sh also builds this under ThreadSanitizer, which reports any data race in the
 * choice even when the answers happen to agree. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <pthread.h>
#include <string.h>

#include "cylray.h"
#include "guarded.h"
#include "scene.h"
#include "tcheck.h"

#define NTHREADS 8
#define REPS 20

typedef struct work {
    const cylray_prepared *P;
    gbatch rays;
    /* outputs of the last repetition */
    cylray_ray16 r16;
    cylray_hit16 h16;
    cylray_ray8 r8;
    cylray_hit8 h8;
    cylray_ray4 r4;
    cylray_hit4 h4;
    uint32_t m16, m8, m4, o16, o8, o4;
    float st[G_MAX], stmax[G_MAX], snx[G_MAX], sny[G_MAX], snz[G_MAX];
    int32_t spart[G_MAX];
    uint8_t occ[G_MAX];
    size_t sn, on;
    const cylray_kernels *seen;
} work;

static pthread_barrier_t start;

static void load(const gbatch *g, float *dst, size_t w, size_t first)
{
    for (int f = 0; f < G_NFIELD; f++)
        memcpy(dst + (size_t)f * w, g->f[f] + first, w * sizeof(float));
}

/* One round through every plain entry point. */
static void round_trip(work *w, unsigned flags)
{
    load(&w->rays, (float *)(void *)&w->r16, 16, 0);
    load(&w->rays, (float *)(void *)&w->r8, 8, 16);
    load(&w->rays, (float *)(void *)&w->r4, 4, 24);
    memset(&w->h16, 0, sizeof w->h16);
    memset(&w->h8, 0, sizeof w->h8);
    memset(&w->h4, 0, sizeof w->h4);
    w->o16 = cylray_occluded16(w->P, &w->r16, 0xffffu, flags);
    w->m16 = cylray_intersect16(w->P, &w->r16, &w->h16, 0xffffu, flags);
    w->o8 = cylray_occluded8(w->P, &w->r8, 0xffu, flags);
    w->m8 = cylray_intersect8(w->P, &w->r8, &w->h8, 0xffu, flags);
    w->o4 = cylray_occluded4(w->P, &w->r4, 0xfu, flags);
    w->m4 = cylray_intersect4(w->P, &w->r4, &w->h4, 0xfu, flags);
    memcpy(w->stmax, w->rays.f[G_TMAX], sizeof w->stmax);
    memset(w->st, 0, sizeof w->st);
    memset(w->snx, 0, sizeof w->snx);
    memset(w->sny, 0, sizeof w->sny);
    memset(w->snz, 0, sizeof w->snz);
    memset(w->spart, 0, sizeof w->spart);
    memset(w->occ, 0, sizeof w->occ);
    const cylray_rays R = {w->rays.f[G_OX], w->rays.f[G_OY], w->rays.f[G_OZ],   w->rays.f[G_DX],
                           w->rays.f[G_DY], w->rays.f[G_DZ], w->rays.f[G_TMIN], w->stmax};
    const cylray_hits H = {w->st, w->snx, w->sny, w->snz, w->spart};
    w->on = cylray_occluded_stream(w->P, &R, w->occ, G_MAX - 3, flags);
    w->sn = cylray_intersect_stream(w->P, &R, &H, G_MAX - 3, flags);
}

static void *thread_main(void *arg)
{
    work *w = arg;
    pthread_barrier_wait(&start);
    /* The first thing every thread does is a plain call: the choice races here. */
    for (int rep = 0; rep < REPS; rep++)
        round_trip(w, CYLRAY_NORMAL | (rep & 1 ? CYLRAY_REFINE : 0u));
    w->seen = cylray_kernels_best();
    return NULL;
}

int main(void)
{
    cylray_cylinder cyl[SCENE_MAX_CYL];
    scene_cylinders(cyl);
    cylray_prepared P;
    if (cylray_prepare(&P, &cyl[5]) != CYLRAY_OK)
        return 1;
    static work w[NTHREADS + 1];
    for (int t = 0; t <= NTHREADS; t++) {
        w[t].P = &P;
        scene_rays(31337, &cyl[5], &w[t].rays, 0, G_MAX);
    }

    pthread_barrier_init(&start, NULL, NTHREADS);
    pthread_t th[NTHREADS];
    for (int t = 0; t < NTHREADS; t++)
        if (pthread_create(&th[t], NULL, thread_main, &w[t]) != 0) {
            CHECK(0, "pthread_create failed");
            return tc_report("robust-threads");
        }
    for (int t = 0; t < NTHREADS; t++)
        pthread_join(th[t], NULL);
    pthread_barrier_destroy(&start);

    /* One thread's answers, now that the choice is made. */
    work *ref = &w[NTHREADS];
    round_trip(ref, CYLRAY_NORMAL | CYLRAY_REFINE); /* REPS - 1 is odd: REFINE */
    ref->seen = cylray_kernels_best();
    CHECK(ref->m16 | ref->m8 | ref->m4, "no ray hit: the comparison would prove nothing");
    for (int t = 0; t < NTHREADS; t++) {
        CHECK(w[t].seen == ref->seen, "thread %d sees path %s, main sees %s", t,
              w[t].seen ? w[t].seen->name : "NULL", ref->seen->name);
        CHECK(w[t].m16 == ref->m16 && w[t].m8 == ref->m8 && w[t].m4 == ref->m4,
              "thread %d: hit masks %#x %#x %#x, single thread %#x %#x %#x", t, w[t].m16,
              w[t].m8, w[t].m4, ref->m16, ref->m8, ref->m4);
        CHECK(w[t].o16 == ref->o16 && w[t].o8 == ref->o8 && w[t].o4 == ref->o4,
              "thread %d: occluded masks differ", t);
        CHECK(memcmp(&w[t].h16, &ref->h16, sizeof ref->h16) == 0 &&
                  memcmp(&w[t].r16, &ref->r16, sizeof ref->r16) == 0 &&
                  memcmp(&w[t].h8, &ref->h8, sizeof ref->h8) == 0 &&
                  memcmp(&w[t].r8, &ref->r8, sizeof ref->r8) == 0 &&
                  memcmp(&w[t].h4, &ref->h4, sizeof ref->h4) == 0 &&
                  memcmp(&w[t].r4, &ref->r4, sizeof ref->r4) == 0,
              "thread %d: packet results differ from a single thread's", t);
        CHECK(w[t].sn == ref->sn && w[t].on == ref->on &&
                  memcmp(w[t].st, ref->st, sizeof ref->st) == 0 &&
                  memcmp(w[t].stmax, ref->stmax, sizeof ref->stmax) == 0 &&
                  memcmp(w[t].snx, ref->snx, sizeof ref->snx) == 0 &&
                  memcmp(w[t].spart, ref->spart, sizeof ref->spart) == 0 &&
                  memcmp(w[t].occ, ref->occ, sizeof ref->occ) == 0,
              "thread %d: stream results differ from a single thread's", t);
    }
    return tc_report("robust-threads");
}
