/* SPDX-License-Identifier: MIT */
/* scene.c - a fence, a pipe run and two molecules (a benzene ring and a double helix)
 * on a floor, all capped cylinders, traced as a tracer would use cylray without a BVH:
 * 4x4-pixel packets of 16 rays against every cylinder in turn, the closest hit kept
 * through tmax, then one shadow packet per primary packet toward a point light with
 * the occlusion query (stopping once every lane is blocked). */
#include "scene.h"

#include "clock.h"
#include "png.h"
#include "scenegen.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define SCENE_MAX 256

typedef struct scene {
    int n;
    cylray_cylinder cyl[SCENE_MAX];
    cylray_prepared *prep;
    float albedo[SCENE_MAX][3];
    int mat[SCENE_MAX];
} scene;

typedef struct kern16 {
    cylray_intersect16_fn isect;
    cylray_occluded16_fn occ;
} kern16;

static void normalize3(double v[3])
{
    double l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    v[0] /= l, v[1] /= l, v[2] /= l;
}

/* Renders into rgb; returns the shadow rays traced. */
static size_t render(const scene *s, const kern16 *k, int W, int H, uint8_t *rgb,
                     size_t *primary_hits)
{
    const double eye[3] = {0.3, 2.6, 7.4}, at[3] = {0.2, 1.0, 0}, light[3] = {5, 9, 7};
    double fw[3] = {at[0] - eye[0], at[1] - eye[1], at[2] - eye[2]}, up[3] = {0, 1, 0};
    normalize3(fw);
    double rt[3] = {fw[1] * up[2] - fw[2] * up[1], fw[2] * up[0] - fw[0] * up[2],
                    fw[0] * up[1] - fw[1] * up[0]};
    normalize3(rt);
    double cu[3] = {rt[1] * fw[2] - rt[2] * fw[1], rt[2] * fw[0] - rt[0] * fw[2],
                    rt[0] * fw[1] - rt[1] * fw[0]};
    const double tanh_ = tan(0.5 * 60 * 3.14159265358979 / 180), aspect = (double)W / H;
    size_t nshadow = 0, nhit = 0;
    CYLRAY_ALIGN(64) cylray_ray16 ray, sh;
    CYLRAY_ALIGN(64) cylray_hit16 hit;
    for (int ty = 0; ty < H; ty += 4)
        for (int tx = 0; tx < W; tx += 4) {
            int id[16];
            for (int l = 0; l < 16; l++) {
                int x = tx + (l & 3), y = ty + (l >> 2);
                double sx = (2 * (x + 0.5) / W - 1) * tanh_ * aspect;
                double sy = (1 - 2 * (y + 0.5) / H) * tanh_;
                double d[3];
                for (int c = 0; c < 3; c++)
                    d[c] = fw[c] + sx * rt[c] + sy * cu[c];
                normalize3(d);
                ray.ox[l] = (float)eye[0], ray.oy[l] = (float)eye[1], ray.oz[l] = (float)eye[2];
                ray.dx[l] = (float)d[0], ray.dy[l] = (float)d[1], ray.dz[l] = (float)d[2];
                ray.tmin[l] = 0;
                ray.tmax[l] = INFINITY;
                id[l] = -1;
            }
            uint32_t any = 0;
            for (int c = 0; c < s->n; c++) {
                uint32_t m = k->isect(&s->prep[c], &ray, &hit, 0xffffu,
                                      CYLRAY_NORMAL | CYLRAY_FACE_FORWARD);
                any |= m;
                for (; m; m &= m - 1)
                    id[__builtin_ctz(m)] = c; /* later hits are closer: tmax went down */
            }
            nhit += (size_t)__builtin_popcount(any);
            /* Shadow rays from the hit points, nudged off the surface along the normal. */
            double ldist[16];
            for (int l = 0; l < 16; l++) {
                if (!(any >> l & 1u)) {
                    sh.ox[l] = sh.oy[l] = sh.oz[l] = 0;
                    sh.dx[l] = 1, sh.dy[l] = sh.dz[l] = 0;
                    sh.tmin[l] = sh.tmax[l] = 0;
                    continue;
                }
                double t = hit.t[l];
                double p[3] = {ray.ox[l] + t * ray.dx[l], ray.oy[l] + t * ray.dy[l],
                               ray.oz[l] + t * ray.dz[l]};
                double n[3] = {hit.nx[l], hit.ny[l], hit.nz[l]};
                double L[3];
                for (int c = 0; c < 3; c++)
                    p[c] += 2e-3 * n[c], L[c] = light[c] - p[c];
                ldist[l] = sqrt(L[0] * L[0] + L[1] * L[1] + L[2] * L[2]);
                sh.ox[l] = (float)p[0], sh.oy[l] = (float)p[1], sh.oz[l] = (float)p[2];
                sh.dx[l] = (float)(L[0] / ldist[l]), sh.dy[l] = (float)(L[1] / ldist[l]);
                sh.dz[l] = (float)(L[2] / ldist[l]);
                sh.tmin[l] = 1e-3f;
                sh.tmax[l] = (float)ldist[l];
            }
            uint32_t occ = 0;
            nshadow += (size_t)__builtin_popcount(any);
            for (int c = 0; c < s->n && occ != any; c++)
                occ |= k->occ(&s->prep[c], &sh, any & ~occ, 0);
            for (int l = 0; l < 16; l++) {
                int x = tx + (l & 3), y = ty + (l >> 2);
                double col[3];
                if (!(any >> l & 1u)) {
                    double f = ray.dy[l] * 1.6;
                    f = f < 0 ? 0 : f > 1 ? 1 : f;
                    col[0] = 0.86 - 0.5 * f, col[1] = 0.9 - 0.35 * f, col[2] = 1.0 - 0.1 * f;
                } else {
                    int c = id[l];
                    double n[3] = {hit.nx[l], hit.ny[l], hit.nz[l]};
                    double ld[3] = {sh.dx[l], sh.dy[l], sh.dz[l]};
                    double ndl = n[0] * ld[0] + n[1] * ld[1] + n[2] * ld[2];
                    double lit = (occ >> l & 1u) ? 0 : 1;
                    ndl = ndl > 0 ? ndl : 0;
                    double alb[3] = {s->albedo[c][0], s->albedo[c][1], s->albedo[c][2]};
                    if (s->mat[c] == SG_FLOOR) {
                        double t = hit.t[l];
                        double px = ray.ox[l] + t * ray.dx[l], pz = ray.oz[l] + t * ray.dz[l];
                        int chk = ((int)floor(px) + (int)floor(pz)) & 1;
                        for (int q = 0; q < 3; q++)
                            alb[q] = chk ? 0.5 : 0.78;
                    }
                    double spec = 0;
                    if (s->mat[c] == SG_SHINY && lit > 0) {
                        /* Blinn: the half vector between the light and the eye */
                        double hv[3] = {ld[0] - ray.dx[l], ld[1] - ray.dy[l],
                                        ld[2] - ray.dz[l]};
                        normalize3(hv);
                        double nh = n[0] * hv[0] + n[1] * hv[1] + n[2] * hv[2];
                        spec = nh > 0 ? 0.45 * pow(nh, 48) : 0;
                    }
                    for (int q = 0; q < 3; q++)
                        col[q] = alb[q] * (0.2 + 0.8 * ndl * lit) + spec;
                }
                for (int q = 0; q < 3; q++) {
                    double v = col[q] < 0 ? 0 : col[q] > 1 ? 1 : col[q];
                    rgb[((size_t)y * (size_t)W + (size_t)x) * 3 + (size_t)q] =
                        (uint8_t)(255 * pow(v, 1 / 2.2) + 0.5);
                }
            }
        }
    if (primary_hits)
        *primary_hits = nhit;
    return nshadow;
}

/* A frame lasts 0.1 to 2 s, long enough for another process to take the core for a
 * while: frames that lost the CPU are set aside as in the microbenchmarks, and if most
 * did, the thread's CPU time stands in for the wall time (marked cpu_timed). */
static void push_row(result_list *results, const char *isa, int isa_id, const scene *s,
                     const scene_report *sc, double *ns, const double *cpu, int frames,
                     double hit_frac)
{
    result *r = results_push(results);
    if (!r)
        return;
    size_t rays = sc->primary + sc->shadow;
    snprintf(r->scenario, sizeof r->scenario, "scene");
    snprintf(r->group, sizeof r->group, "scene");
    snprintf(r->isa, sizeof r->isa, "%.15s", isa);
    snprintf(r->op, sizeof r->op, "frame");
    r->isa_id = isa_id;
    r->width_id = BW_16;
    r->op_id = OP_NORMAL;
    r->rays_timed = rays;
    r->ncyl = s->n;
    int clean = 0;
    for (int f = 0; f < frames; f++)
        if (cpu[f] >= 0.95 * ns[f])
            ns[clean++] = ns[f] / (double)rays;
    r->cpu_timed = clean < (frames + 1) / 2;
    if (r->cpu_timed) {
        clean = frames;
        for (int f = 0; f < frames; f++)
            ns[f] = cpu[f] / (double)rays;
    }
    stat_summary(ns, (size_t)clean, &r->ns);
    r->ticks = r->ns.med * clk_tsc_ghz();
    r->mrays = 1e3 / r->ns.med;
    r->reps = clean;
    r->samples = frames;
    r->clean = r->cpu_timed ? 0 : clean;
    r->hit_frac = hit_frac;
}

void scene_run(const options *opt, scene_report *sc, result_list *results)
{
    scene *s = calloc(1, sizeof *s);
    const int W = opt->scene_w, H = opt->scene_h;
    uint8_t *img = malloc((size_t)W * H * 3), *img2 = malloc((size_t)W * H * 3);
    if (!s || !img || !img2)
        goto done;
    sg_painted p = {0, SCENE_MAX, s->cyl, s->albedo, s->mat};
    sg_fence_scene(&p);
    s->n = p.n;
    s->prep = bench_alloc((size_t)s->n * sizeof *s->prep);
    if (!s->prep)
        goto done;
    for (int c = 0; c < s->n; c++)
        if (cylray_prepare(&s->prep[c], &s->cyl[c]) != CYLRAY_OK) {
            fprintf(stderr, "cylbench: scene cylinder %d rejected\n", c);
            goto done;
        }
    memset(sc, 0, sizeof *sc);
    sc->w = W, sc->h = H, sc->ncyl = s->n;
    snprintf(sc->plain_isa, sizeof sc->plain_isa, "%s", cylray_kernels_best()->name);

    /* The image, with the plain (dispatching) entry points; it doubles as warm-up. */
    const kern16 plain = {cylray_intersect16, cylray_occluded16};
    size_t nhit = 0;
    sc->shadow = render(s, &plain, W, H, img, &nhit);
    sc->primary = (size_t)W * H;
    double hit_frac = (double)nhit / (double)sc->primary;
    snprintf(sc->image, sizeof sc->image, "%s/scene.png", opt->out_dir);
    if (png_write_rgb(sc->image, img, (uint32_t)W, (uint32_t)H) != 0) {
        fprintf(stderr, "cylbench: cannot write %s\n", sc->image);
        sc->image[0] = 0;
    }
    sc->have = 1;

    /* Frames round-robin over the paths (the plain entry points first), so that a busy
     * spell of the machine falls on all of them alike. */
    const int frames = opt->quick ? 2 : 3;
    kern16 paths[BENCH_NISA + 1];
    int ids[BENCH_NISA + 1], np = 0;
    paths[np] = plain;
    ids[np++] = -1;
    for (int isa = 0; isa < CYLRAY_ISA_COUNT; isa++) {
        const cylray_kernels *k = cylray_kernels_for((cylray_isa)isa);
        if (!k || !(opt->isa_mask >> isa & 1u))
            continue;
        paths[np].isect = k->intersect16;
        paths[np].occ = k->occluded16;
        ids[np++] = isa;
    }
    double ns[BENCH_NISA + 1][8], cpu[BENCH_NISA + 1][8];
    for (int f = 0; f < frames; f++)
        for (int p = 0; p < np; p++) {
            double c = clk_cpu_ns(), a = clk_ns();
            render(s, &paths[p], W, H, img2, NULL);
            ns[p][f] = clk_ns() - a;
            cpu[p][f] = clk_cpu_ns() - c;
            if (ids[p] >= 0 && f == 0) {
                long diff = 0;
                for (size_t i = 0; i < (size_t)W * H; i++)
                    diff += memcmp(img + 3 * i, img2 + 3 * i, 3) != 0;
                sc->pix_diff[ids[p]] = diff;
                sc->timed[ids[p]] = 1;
            }
        }
    for (int p = 0; p < np; p++) {
        char name[24];
        if (ids[p] < 0)
            snprintf(name, sizeof name, "plain:%s", sc->plain_isa);
        else
            snprintf(name, sizeof name, "%s", cylray_kernels_for((cylray_isa)ids[p])->name);
        push_row(results, name, ids[p], s, sc, ns[p], cpu[p], frames, hit_frac);
    }
done:
    if (s)
        bench_free(s->prep);
    free(s);
    free(img);
    free(img2);
}
