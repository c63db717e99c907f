/* SPDX-License-Identifier: MIT */
/* main.c - cylembree: cylray inside Embree (3 or 4: the one the adapter was built
 * against) against that Embree's own cone curves and sphere points, on nine scenes (three
 * of them tapered: cones), time and error side by side.
 *
 *   cylembree [--quick] [--scene=molecule,pipes,far-rods,lattice,balls,far-cloud,
 *              molecule-taper,reducers,far-taper]
 *             [--isa=best|all|LIST]
 *             [--packet=1,4,8,16] [--threads=N] [--size=WxH]
 *             [--samples=N] [--runs=N] [--reps=N] [--clock=wall|cpu] [--no-angles]
 *             [--out=DIR]
 *
 * Each timing is repeated --runs times (default 3, --quick too), the runs interleaved:
 * run after run every variant is timed in turn, each run keeping the best of --reps
 * passes. The tables print the median over the runs; the relative times, each run's
 * ratio to Embree's curves in that run, with their range over the runs.
 */
#include "aimed.h"
#include "image.h"
#include "machine.h"
#include "png.h"
#include "rays.h"
#include "run.h"
#include "timing.h"
#include "trace.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

typedef struct opts {
    int quick, w, h, runs, reps, threads, samples;
    int cpu_clock; /* rates from the CPU time the process got, not the wall time */
    int scene_on[EB_NSCENES];
    int packet_on[EB_NPACKETS];
    int isa_on[CYLRAY_ISA_COUNT];
    const char *out;
} opts;

static const char *embree_isa(cylray_isa i)
{
    return i == CYLRAY_ISA_SSE41 ? "sse4.2" : i == CYLRAY_ISA_AVX2 ? "avx2" : "avx512";
}

static int list_has(const char *list, const char *name)
{
    size_t n = strlen(name);
    for (const char *p = list; p && *p;) {
        const char *e = strchr(p, ',');
        size_t l = e ? (size_t)(e - p) : strlen(p);
        if (l == n && !strncmp(p, name, n))
            return 1;
        p = e ? e + 1 : NULL;
    }
    return 0;
}

static int parse(opts *o, int argc, char **argv)
{
    long nproc = sysconf(_SC_NPROCESSORS_ONLN);
    *o = (opts){.w = 1024,
                .h = 768,
                .runs = 3,
                .reps = 3,
                .samples = 20000,
                .threads = nproc > 0 ? (int)(nproc < EB_MAXT ? nproc : EB_MAXT) : 1,
                .out = "bench/out"};
    const char *scenes = NULL, *isas = "best", *packets = NULL;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "--quick"))
            o->quick = 1;
        else if (!strncmp(a, "--scene=", 8))
            scenes = a + 8;
        else if (!strncmp(a, "--isa=", 6))
            isas = a + 6;
        else if (!strncmp(a, "--packet=", 9))
            packets = a + 9;
        else if (!strncmp(a, "--threads=", 10))
            o->threads = atoi(a + 10);
        else if (!strncmp(a, "--size=", 7))
            sscanf(a + 7, "%dx%d", &o->w, &o->h);
        else if (!strncmp(a, "--samples=", 10))
            o->samples = atoi(a + 10);
        else if (!strncmp(a, "--runs=", 7))
            o->runs = atoi(a + 7);
        else if (!strncmp(a, "--reps=", 7))
            o->reps = atoi(a + 7);
        else if (!strcmp(a, "--no-angles"))
            eb_cylray_options |= CYLRAY_EMBREE_NO_ANGLES;
        else if (!strcmp(a, "--clock=cpu"))
            o->cpu_clock = 1;
        else if (!strcmp(a, "--clock=wall"))
            o->cpu_clock = 0;
        else if (!strncmp(a, "--out=", 6))
            o->out = a + 6;
        else {
            fprintf(stderr, "cylembree: unknown option %s (see the top of main.c)\n", a);
            return -1;
        }
    }
    if (o->quick) {
        int explicit_size = 0;
        for (int i = 1; i < argc; i++)
            explicit_size |= !strncmp(argv[i], "--size=", 7);
        if (!explicit_size)
            o->w = o->h = 512;
        o->samples = 2000;
        int explicit_reps = 0;
        for (int i = 1; i < argc; i++)
            explicit_reps |= !strncmp(argv[i], "--reps=", 7);
        if (!explicit_reps)
            o->reps = 1;
    }
    if (o->w < 16 || o->h < 16 || o->w % 16 || o->h % 16 || o->threads < 1 ||
        o->threads > EB_MAXT || o->runs < 1 || o->runs > EB_MAXRUNS || o->reps < 1) {
        fprintf(stderr,
                "cylembree: --size must be multiples of 16, --threads 1..%d, --runs 1..%d, "
                "--reps at least 1\n",
                EB_MAXT, EB_MAXRUNS);
        return -1;
    }
    for (int s = 0; s < EB_NSCENES; s++)
        o->scene_on[s] = !scenes || list_has(scenes, eb_scene_name(s));
    for (int k = 0; k < EB_NPACKETS; k++) {
        char b[8];
        snprintf(b, sizeof b, "%d", eb_packets[k]);
        o->packet_on[k] = packets ? list_has(packets, b) : (o->quick ? k == 0 || k == 2 : 1);
    }
    for (int i = CYLRAY_ISA_SSE41; i <= CYLRAY_ISA_AVX512; i++) {
        int have = cylray_kernels_for((cylray_isa)i) != NULL;
        o->isa_on[i] = have && (list_has(isas, "all") || list_has(isas, cylray_isa_name(i)));
    }
    if (list_has(isas, "best"))
        for (int i = CYLRAY_ISA_AVX512; i >= CYLRAY_ISA_SSE41; i--)
            if (cylray_kernels_for((cylray_isa)i)) {
                o->isa_on[i] = 1;
                break;
            }
    return 0;
}

/* ---- one scene --------------------------------------------------------------------- */

static void judge_variant(eb_row *row, const eb_geom *g, const eb_ref *ref,
                          eb_sample *const sets[EB_NSETS], const size_t nset[EB_NSETS],
                          const eb_frame *f)
{
    for (int s = 0; s < EB_NSETS; s++) {
        eb_err *e = &row->err[s];
        eb_err_init(e, nset[s]);
        for (size_t i = 0; i < nset[s]; i++) {
            const eb_sample *x = &sets[s][i];
            size_t p = x->pixel;
            uint32_t prim;
            float t = 0, ng[3] = {0, 0, 0};
            if (p != SIZE_MAX) {
                prim = f->prim.prim[p], t = f->prim.tfar[p];
                ng[0] = f->prim.ngx[p], ng[1] = f->prim.ngy[p], ng[2] = f->prim.ngz[p];
            } else {
                prim = eb_trace1(g->scene, x->o, x->d, x->tmin, x->tmax, &t, ng);
            }
            eb_judge(e, ref, x, prim, t, ng);
            /* the secondary rays of a primary hit on the exact cylinder */
            if (p == SIZE_MAX || prim != x->xid || !x->xhit)
                continue;
            const eb_rays *sec[2] = {&f->shadow, &f->bounce};
            for (int k = 0; k < 2; k++) {
                if (!sec[k]->valid[p])
                    continue;
                float o[3], w[3], st, sn[3];
                eb_rays_get(sec[k], p, o, w);
                uint32_t hit = eb_trace1(g->scene, o, w, sec[k]->tnear[p],
                                         k == 0 ? f->shadow_tfar[p] : INFINITY, &st, sn);
                eb_judge_secondary(e, x, w, hit);
            }
        }
    }
}

/* Runs every variant on one scene with one ISA; appends a row per variant. */
static int run_scene(const opts *o, RTCDevice dev, cylray_isa isa, int which, eb_row *rows,
                     size_t *nrows)
{
    eb_scene sc;
    if (eb_scene_make(&sc, which, 20261201) != 0)
        return -1;
    const cylray_kernels *k = cylray_kernels_for(isa);
    fprintf(stderr, "cylembree: %s/%s: %zu cylinders, %zu spheres\n", cylray_isa_name(isa),
            sc.name, sc.ns, sc.nsph);
    size_t npix = (size_t)o->w * (size_t)o->h;

    /* the judged rays and their exact answers, shared by the variants */
    eb_ref ref;
    if (eb_ref_init(&ref, dev, &sc)) {
        eb_scene_free(&sc);
        return -1;
    }
    size_t nset[EB_NSETS] = {(size_t)o->samples, (size_t)o->samples / 4,
                             (size_t)o->samples / 4};
    eb_sample *sets[EB_NSETS];
    rng g = {77 + (uint64_t)which};
    for (int s = 0; s < EB_NSETS; s++) {
        sets[s] = calloc(nset[s] ? nset[s] : 1, sizeof *sets[s]);
        for (size_t i = 0; sets[s] && i < nset[s]; i++) {
            eb_sample *x = &sets[s][i];
            if (s == EB_SET_CAMERA) {
                size_t p = (size_t)(rng_unit(&g) * (double)npix);
                int px, py;
                eb_pixel_of(p, o->w, o->h, &px, &py);
                eb_camera_ray(&sc, o->w, o->h, px + 0.5, py + 0.5, x->o, x->d);
                x->tmin = 0, x->tmax = INFINITY, x->pixel = p;
            } else {
                eb_aimed(x, &sc, s, &g);
            }
            eb_sample_solve(x, &ref);
        }
    }

    eb_frame fr[EB_NVARIANTS];
    eb_geom geo[EB_NVARIANTS];
    int built[EB_NVARIANTS] = {0};
    size_t first_row = *nrows;
    uint8_t *img = calloc(npix * 3 * (EB_NVARIANTS + 1), 1);
    for (int v = 0; v < EB_NVARIANTS; v++) {
        eb_row *r = &rows[(*nrows)++];
        memset(r, 0, sizeof *r);
        snprintf(r->isa, sizeof r->isa, "%s", cylray_isa_name(isa));
        snprintf(r->scene, sizeof r->scene, "%s", sc.name);
        snprintf(r->variant, sizeof r->variant, "%s", eb_variant_name((eb_variant)v));
        r->threads = o->threads, r->runs = o->runs, r->reps = o->reps;
        r->ns = sc.ns;
        for (int p = 0; p < EB_NPHASES; p++)
            for (int q = 0; q < EB_NPACKETS; q++) {
                r->mrays[p][q] = NAN;
                for (int run = 0; run < EB_MAXRUNS; run++)
                    r->mrays_run[p][q][run] = NAN;
            }
        if (eb_frame_alloc(&fr[v], npix) ||
            eb_geom_build(&geo[v], dev, &sc, (eb_variant)v, k)) {
            r->skipped = 1;
            snprintf(r->why, sizeof r->why, "build failed");
            continue;
        }
        built[v] = 1;
        r->build_s = geo[v].build_s;
        r->nprim = geo[v].nprim;
        r->nsph = sc.nsph;
        r->leaf_m = (int)cylray_embree_leaf_size(geo[v].cyl ? geo[v].cyl : geo[v].sph);
        eb_camera_rays(&fr[v].prim, &sc, o->w, o->h);
    }

    eb_timing t = {
        .runs = o->runs, .reps = o->reps, .threads = o->threads, .cpu_clock = o->cpu_clock};
    memcpy(t.packet_on, o->packet_on, sizeof t.packet_on);
    eb_time_scene(&t, isa, geo, fr, built, &rows[first_row]);

    /* Error, pictures. */
    int base = built[EB_NATIVE] ? EB_NATIVE : -1;
    for (int v = 0; v < EB_NVARIANTS; v++) {
        if (!built[v])
            continue;
        fprintf(stderr, "cylembree: %s/%s: judging %s\n", cylray_isa_name(isa), sc.name,
                eb_variant_name((eb_variant)v));
        judge_variant(&rows[first_row + v], &geo[v], &ref, sets, nset, &fr[v]);
        if (img)
            eb_shade(&sc, &fr[v].prim, &fr[v].shadow, &fr[v].bounce, o->w, o->h,
                     img + npix * 3 * (size_t)v);
        /* the last panel ends up with the last cylray variant's difference */
        if (base >= 0 && v != base && img)
            rows[first_row + v].diff_pixels =
                eb_diff(&fr[base].prim, &fr[base].shadow, &fr[v].prim, &fr[v].shadow, o->w,
                        o->h, img + npix * 3 * EB_NVARIANTS);
    }
    if (img) {
        /* the panels side by side: the variants, then the difference of the last
         * cylray variant from Embree's curves */
        int W = o->w * (EB_NVARIANTS + 1);
        uint8_t *row = malloc((size_t)W * 3 * (size_t)o->h);
        if (row) {
            for (int y = 0; y < o->h; y++)
                for (int p = 0; p <= EB_NVARIANTS; p++)
                    memcpy(row + ((size_t)y * (size_t)W + (size_t)p * (size_t)o->w) * 3,
                           img + npix * 3 * (size_t)p + (size_t)y * (size_t)o->w * 3,
                           (size_t)o->w * 3);
            char path[512];
            snprintf(path, sizeof path, "%s/embree_%s_%s.png", o->out, sc.name,
                     cylray_isa_name(isa));
            if (png_write_rgb(path, row, (uint32_t)W, (uint32_t)o->h) == 0)
                fprintf(stderr, "cylembree: wrote %s\n", path);
            free(row);
        }
        free(img);
    }
    for (int v = 0; v < EB_NVARIANTS; v++)
        if (built[v]) {
            eb_geom_free(&geo[v]);
            eb_frame_free(&fr[v]);
        }
    for (int s = 0; s < EB_NSETS; s++)
        free(sets[s]);
    eb_ref_free(&ref);
    eb_scene_free(&sc);
    return 0;
}

int main(int argc, char **argv)
{
    opts o;
    eb_leaf_options = CYLRAY_EMBREE_LEAVES; /* as a user asks for leaves */
    if (parse(&o, argc, argv))
        return 2;
    mkdir(o.out, 0777);
    machine_info mi;
    machine_probe(&mi);
    char machine[1024];
    snprintf(machine, sizeof machine, "%s (%s), %d logical CPUs%s, %s; Embree %s; %s", mi.cpu,
             mi.cpuid, mi.cores, mi.hypervisor ? ", virtual machine" : "", mi.os,
             RTC_VERSION_STRING, mi.compiler);
    eb_row *rows = calloc(CYLRAY_ISA_COUNT * EB_NSCENES * EB_NVARIANTS, sizeof *rows);
    size_t nrows = 0;
    if (!rows)
        return 1;
    for (int i = CYLRAY_ISA_SSE41; i <= CYLRAY_ISA_AVX512; i++) {
        if (!o.isa_on[i])
            continue;
        char cfg[64];
        snprintf(cfg, sizeof cfg, "isa=%s,threads=%d", embree_isa((cylray_isa)i), o.threads);
        RTCDevice dev = rtcNewDevice(cfg);
        if (!dev) {
            fprintf(stderr, "cylembree: Embree refused \"%s\"\n", cfg);
            continue;
        }
        for (int s = 0; s < EB_NSCENES; s++)
            if (o.scene_on[s] && run_scene(&o, dev, (cylray_isa)i, s, rows, &nrows))
                fprintf(stderr, "cylembree: scene %s failed\n", eb_scene_name(s));
        rtcReleaseDevice(dev);
    }
    eb_report(stdout, rows, nrows, machine);
    char path[512];
    snprintf(path, sizeof path, "%s/embree.txt", o.out);
    FILE *f = fopen(path, "w");
    if (f) {
        eb_report(f, rows, nrows, machine);
        fclose(f);
    }
    snprintf(path, sizeof path, "%s/embree.csv", o.out);
    if ((f = fopen(path, "w"))) {
        eb_report_csv(f, rows, nrows);
        fclose(f);
    }
    for (size_t i = 0; i < nrows; i++)
        for (int s = 0; s < EB_NSETS; s++)
            eb_err_free(&rows[i].err[s]);
    free(rows);
    return 0;
}
