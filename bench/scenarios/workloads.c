/* SPDX-License-Identifier: MIT */
/* workloads.c - the scenario table and how each scenario's rays and cylinders are made.
 *
 * Every ray set is BENCH_BATCH rays times a number of batches (each batch is timed while
 * it sits in L1); the big stream is one set far larger than the last-level cache. The
 * stress scenarios take the reference's own generators (tests/ref/gen.h), 16 rays per
 * cylinder, when the reference is built. */
#include "workloads.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gen.h"

#define ALL_OPS ((1u << OP_COUNT) - 1u)
#define ALL_WIDTHS ((1u << BW_COUNT) - 1u)

enum { S_PLAIN, S_CLUSTER, S_ALIGNED, S_GENERAL, S_GEN };

/* What the inactive lanes of a half-active packet hold. */
enum { FILL_NONE, FILL_ZERO, FILL_SUBNORMAL };

typedef struct scen_def {
    const char *name, *group, *what;
    int build; /* S_*: how the cylinders and rays are made */
    ray_kind rays;
    int cyl_kind; /* 0 infinite, 1 open, 2 capped */
    int ops;      /* OP_* bits, or -1 for the default of the group */
    unsigned widths;
    int textbook, big;
    int gen_category; /* S_GEN: the cylgen category */
    int fill;         /* FILL_*: every other lane inactive, holding this */
    int shape;        /* SH_*: the cylinder, or sph_general(), or con_general(k) */
} scen_def;

/* The shapes of S_PLAIN: SH_CONE + k is con_general(k). */
enum { SH_CYL, SH_SPHERE, SH_CONE };

#define MAX_SCEN 64
static char gen_names[MAX_SCEN][40]; /* "stress-" + the category names of gen.h */

static scen_def table[MAX_SCEN];
static int ntable;

static void init_table(void)
{
    if (ntable)
        return;
    const unsigned occn = (1u << OP_NORMAL) | (1u << OP_OCC);
    const scen_def fixed[] = {
        {"coherent", "main",
         "camera rays in 4x4 pixel tiles at a capped cylinder, general axis", S_PLAIN,
         RK_CAMERA, 2, ALL_OPS, ALL_WIDTHS, 1, 0, 0, 0, 0},
        {"incoherent", "main",
         "ordinary rays: random origins 3-6 sizes away at a capped cylinder, general axis",
         S_PLAIN, RK_INCOHERENT, 2, ALL_OPS, ALL_WIDTHS, 1, 0, 0, 0, 0},
        {"shadow", "main", "shadow rays from a floor to a point light past a capped cylinder",
         S_PLAIN, RK_SHADOW, 2, (1u << OP_OCC) | (1u << OP_T), ALL_WIDTHS, 0, 0, 0, 0, 0},
        {"bvh-leaf", "main",
         "one packet against 32 capped cylinders (a BVH leaf, all in L1), closest hit; "
         "ns per ray and cylinder",
         S_CLUSTER, RK_CLUSTER, 2, (1u << OP_T) | occn, ALL_WIDTHS, 0, 0, 0, 0, 0},
        {"miss-mix", "main", "90% misses and 10% hits, mixed across lanes (capped)", S_PLAIN,
         RK_MISS_MIX, 2, (int)occn, ALL_WIDTHS, 0, 0, 0, 0, 0},
        {"hit-mix", "main", "90% hits and 10% misses, mixed across lanes (capped)", S_PLAIN,
         RK_HIT_MIX, 2, (int)occn, ALL_WIDTHS, 0, 0, 0, 0, 0},
        {"big-stream", "stream",
         "a stream far larger than the caches (incoherent rays, capped); bytes of rays per "
         "second against memcpy",
         S_PLAIN, RK_INCOHERENT, 2, (1u << OP_T) | occn, 1u << BW_STREAM, 0, 1, 0, 0, 0},
        {"aligned", "skips", "capped cylinder along +z (axis-aligned kernel), incoherent rays",
         S_ALIGNED, RK_INCOHERENT, 2, 1u << OP_NORMAL, ALL_WIDTHS, 0, 0, 0, 0, 0},
        {"general", "skips", "the same rays and cylinder rotated to a general axis (capped)",
         S_GENERAL, RK_INCOHERENT, 2, 1u << OP_NORMAL, ALL_WIDTHS, 0, 0, 0, 0, 0},
        {"open", "skips", "the `general` rays against the open tube (no caps)", S_GENERAL,
         RK_INCOHERENT, 1, 1u << OP_NORMAL, ALL_WIDTHS, 0, 0, 0, 0, 0},
        {"infinite", "skips", "the `general` rays against the infinite cylinder", S_GENERAL,
         RK_INCOHERENT, 0, 1u << OP_NORMAL, ALL_WIDTHS, 0, 0, 0, 0, 0},
        {"open-coherent", "skips", "the `coherent` camera rays against the open tube", S_PLAIN,
         RK_CAMERA, 1, 1u << OP_NORMAL, ALL_WIDTHS, 0, 0, 0, 0, 0},
        {"infinite-coherent", "skips",
         "the `coherent` camera rays against the infinite cylinder", S_PLAIN, RK_CAMERA, 0,
         1u << OP_NORMAL, ALL_WIDTHS, 0, 0, 0, 0, 0},
        {"all-miss", "skips", "every ray misses even the infinite cylinder (capped)", S_PLAIN,
         RK_ALL_MISS, 2, 1u << OP_NORMAL, ALL_WIDTHS, 0, 0, 0, 0, 0},
        {"all-hit", "skips", "every ray hits (capped)", S_PLAIN, RK_ALL_HIT, 2, 1u << OP_NORMAL,
         ALL_WIDTHS, 0, 0, 0, 0, 0},
        {"half-zero", "lanes",
         "incoherent rays in every other lane, the others inactive and all zeros (capped)",
         S_PLAIN, RK_INCOHERENT, 2, 1u << OP_NORMAL, (1u << BW_8) | (1u << BW_16), 0, 0, 0,
         FILL_ZERO, 0},
        {"half-subnormal", "lanes",
         "the same packets with the inactive lanes holding subnormals: a tracer's dead rays "
         "or stack garbage",
         S_PLAIN, RK_INCOHERENT, 2, 1u << OP_NORMAL, (1u << BW_8) | (1u << BW_16), 0, 0, 0,
         FILL_SUBNORMAL, 0},
        {"sphere-incoherent", "spheres",
         "ordinary rays: random origins 3-6 sizes away at a sphere", S_PLAIN, RK_INCOHERENT, 2,
         ALL_OPS, ALL_WIDTHS, 1, 0, 0, 0, SH_SPHERE},
        {"sphere-coherent", "spheres", "camera rays in 4x4 pixel tiles at a sphere", S_PLAIN,
         RK_CAMERA, 2, ALL_OPS, ALL_WIDTHS, 1, 0, 0, 0, SH_SPHERE},
        {"sphere-far", "spheres",
         "origins 1e4-1e6 radii away at a sphere: where the textbook's c = w.w - R^2 "
         "loses R",
         S_PLAIN, RK_VERY_FAR, 2, ALL_OPS, ALL_WIDTHS, 1, 0, 0, 0, SH_SPHERE},
        {"cone-incoherent", "cones",
         "ordinary rays: random origins 3-6 sizes away at a capped cone (radii 1 and 0.4)",
         S_PLAIN, RK_INCOHERENT, 2, ALL_OPS, ALL_WIDTHS, 1, 0, 0, 0, SH_CONE},
        {"cone-coherent", "cones", "camera rays in 4x4 pixel tiles at the capped cone", S_PLAIN,
         RK_CAMERA, 2, ALL_OPS, ALL_WIDTHS, 1, 0, 0, 0, SH_CONE},
        {"cone-far", "cones",
         "origins 1e4-1e6 radii away at the capped cone: where the textbook's C = w.w - ... "
         "loses R",
         S_PLAIN, RK_VERY_FAR, 2, ALL_OPS, ALL_WIDTHS, 1, 0, 0, 0, SH_CONE},
        {"cone-tip", "cones", "the incoherent rays at a tip cone (radii 1 and 0, capped)",
         S_PLAIN, RK_INCOHERENT, 2, 1u << OP_NORMAL, ALL_WIDTHS, 1, 0, 0, 0, SH_CONE + 1},
        {"cone-nearcyl", "cones",
         "the incoherent rays at a near-cylinder cone (radii 3 ulps apart, capped)", S_PLAIN,
         RK_INCOHERENT, 2, 1u << OP_NORMAL, ALL_WIDTHS, 1, 0, 0, 0, SH_CONE + 2},
        {"cone-slender", "cones",
         "the incoherent rays at a slender cone (1000 of its wider radius long, radii in "
         "5:2, capped): each lane framed where the ray passes",
         S_PLAIN, RK_INCOHERENT, 2, 1u << OP_NORMAL, ALL_WIDTHS, 1, 0, 0, 0, SH_CONE + 3},
    };
    for (size_t i = 0; i < sizeof fixed / sizeof fixed[0]; i++)
        table[ntable++] = fixed[i];
    for (int c = 0; c < cylgen_category_count() && ntable < MAX_SCEN; c++) {
        snprintf(gen_names[c], sizeof gen_names[c], "stress-%s", cylgen_category_name(c));
        scen_def s = {gen_names[c],
                      "stress",
                      cylgen_category_description(c),
                      S_GEN,
                      RK_INCOHERENT,
                      2,
                      (1 << OP_NORMAL) | (1 << OP_REFINE) | (1 << OP_FAST),
                      1u << BW_16,
                      1,
                      0,
                      c,
                      0,
                      0};
        table[ntable++] = s;
    }
}

int workloads_count(void)
{
    init_table();
    return ntable;
}

const char *workloads_name(int i)
{
    init_table();
    return table[i].name;
}

const char *workloads_group(int i)
{
    init_table();
    return table[i].group;
}

/* Is `word` one of the comma-separated items of `list`? */
static int in_list(const char *list, const char *word)
{
    size_t n = strlen(word);
    for (const char *p = list; *p;) {
        size_t k = strcspn(p, ",");
        if (k == n && strncmp(p, word, n) == 0)
            return 1;
        p += k;
        if (*p == ',')
            p++;
    }
    return 0;
}

int workloads_selected(int i, const char *list)
{
    init_table();
    if (!list || in_list(list, "all"))
        return 1;
    return in_list(list, table[i].name) || in_list(list, table[i].group);
}

int workloads_selected_name(const char *list, const char *name, const char *group)
{
    return !list || in_list(list, "all") || in_list(list, name) || in_list(list, group);
}

int workloads_check_list(const char *list)
{
    init_table();
    int bad = 0;
    for (const char *p = list; p && *p;) {
        size_t k = strcspn(p, ",");
        char word[64];
        snprintf(word, sizeof word, "%.*s", (int)(k < 63 ? k : 63), p);
        int ok = !strcmp(word, "all") || !strcmp(word, "scene") || !strcmp(word, "main") ||
                 !strcmp(word, "stream") || !strcmp(word, "skips") || !strcmp(word, "stress") ||
                 !strcmp(word, "lanes") || !strcmp(word, "leaf") || !strcmp(word, "leaf-l1") ||
                 !strcmp(word, "leaf-l2") || !strcmp(word, "spheres") ||
                 !strcmp(word, "sphere-leaf") || !strcmp(word, "cones") ||
                 !strcmp(word, "cone-leaf");
        for (int i = 0; i < ntable && !ok; i++)
            ok = !strcmp(word, table[i].name);
        if (!ok) {
            fprintf(stderr, "cylbench: unknown scenario '%s'\n", word);
            bad = 1;
        }
        p += k;
        if (*p == ',')
            p++;
    }
    return bad;
}

static int alloc_cyls(workload *w, int n)
{
    w->ncyl = n;
    w->cyl = calloc((size_t)n, sizeof *w->cyl);
    w->prep = bench_alloc((size_t)n * sizeof *w->prep);
    w->tb = calloc((size_t)n, sizeof *w->tb);
    return w->cyl && w->prep && w->tb ? 0 : -1;
}

static uint64_t seed_of(const char *name)
{
    uint64_t h = 1469598103934665603ull; /* FNV-1a: a fixed seed per scenario name */
    for (; *name; name++)
        h = (h ^ (unsigned char)*name) * 1099511628211ull;
    return h;
}

int workloads_build(int idx, workload *w, const options *opt)
{
    init_table();
    const scen_def *s = &table[idx];
    memset(w, 0, sizeof *w);
    w->name = s->name;
    w->group = s->group;
    w->what = s->what;
    w->ops = (unsigned)s->ops;
    w->widths = s->widths;
    w->textbook = s->textbook;
    w->big = s->big;
    size_t n = s->big ? opt->big_rays : 8 * (size_t)BENCH_BATCH;
    w->batch = s->big ? n : BENCH_BATCH;
    if (raysoa_alloc(&w->rays, n))
        return -1;
    /* the half-active pair: the same rays in the active lanes */
    rng g = {seed_of(s->fill ? "half" : s->name)};
    rng shared = {seed_of("skips")}; /* aligned, general, open, infinite: the same rays */

    switch (s->build) {
    case S_PLAIN:
        if (alloc_cyls(w, 1))
            return -1;
        w->cyl[0] = cyl_general(s->cyl_kind);
        if (s->shape == SH_SPHERE) {
            w->sph = calloc(1, sizeof *w->sph);
            w->tbs = calloc(1, sizeof *w->tbs);
            if (!w->sph || !w->tbs)
                return -1;
            w->sph[0] = sph_general();
            w->cyl[0] = sph_box(&w->sph[0]); /* the rays' target; never intersected */
        }
        if (s->shape >= SH_CONE) {
            w->con = calloc(1, sizeof *w->con);
            w->tbc = calloc(1, sizeof *w->tbc);
            if (!w->con || !w->tbc)
                return -1;
            w->con[0] = con_general(s->shape - SH_CONE);
            w->cyl[0] = con_box(&w->con[0]); /* the rays' target; never intersected */
        }
        rays_generate(&w->rays, s->rays, &w->cyl[0], 0, &g);
        break;
    case S_CLUSTER: {
        const double extent = 4.0;
        if (alloc_cyls(w, 32))
            return -1;
        cyl_cluster(w->cyl, 32, extent, &g);
        cylray_cylinder box = cyl_general(2);
        box.center[0] = box.center[1] = box.center[2] = 0;
        rays_generate(&w->rays, RK_CLUSTER, &box, extent, &g);
        break;
    }
    case S_ALIGNED:
    case S_GENERAL: {
        if (alloc_cyls(w, 1))
            return -1;
        cylray_cylinder al = cyl_aligned(2);
        rays_generate(&w->rays, RK_INCOHERENT, &al, 0, &shared);
        if (s->build == S_ALIGNED) {
            w->cyl[0] = cyl_aligned(s->cyl_kind);
        } else {
            raysoa tmp;
            if (raysoa_alloc(&tmp, n))
                return -1;
            rays_to_general(&tmp, &w->rays);
            raysoa_free(&w->rays);
            w->rays = tmp;
            w->cyl[0] = cyl_general(s->cyl_kind);
        }
        break;
    }
    case S_GEN: {
        size_t ncases = n;
        cylgen_case *cs = malloc(ncases * sizeof *cs);
        if (!cs || alloc_cyls(w, (int)(ncases / CYLGEN_BATCH))) {
            free(cs);
            return -1;
        }
        cylgen_make(s->gen_category, seed_of(s->name), ncases, cs);
        w->grouped = CYLGEN_BATCH;
        for (size_t i = 0; i < ncases; i++) {
            raysoa *r = &w->rays;
            r->ox[i] = cs[i].o[0], r->oy[i] = cs[i].o[1], r->oz[i] = cs[i].o[2];
            r->dx[i] = cs[i].d[0], r->dy[i] = cs[i].d[1], r->dz[i] = cs[i].d[2];
            r->tmin[i] = cs[i].tmin, r->tmax[i] = cs[i].tmax;
            if (i % CYLGEN_BATCH == 0)
                w->cyl[i / CYLGEN_BATCH] = cs[i].cyl;
        }
        free(cs);
        break;
    }
    }
    w->lanes = ~0u;
    if (s->fill) {
        /* 1e-40: subnormal, and so is every product the kernel forms from it */
        const float v = s->fill == FILL_SUBNORMAL ? 1e-40f : 0.0f;
        raysoa *r = &w->rays;
        w->lanes = 0x55555555u;
        for (size_t i = 1; i < n; i += 2)
            r->ox[i] = r->oy[i] = r->oz[i] = r->dx[i] = r->dy[i] = r->dz[i] = r->tmin[i] =
                r->tmax[i] = v;
    }
    for (int c = 0; c < w->ncyl && w->sph; c++) {
        if (cylray_prepare_sphere(&w->prep[c], &w->sph[c]) != CYLRAY_OK) {
            fprintf(stderr, "cylbench: %s: sphere %d rejected by cylray_prepare_sphere\n",
                    s->name, c);
            return -1;
        }
        tb_prepare_sphere(&w->tbs[c], &w->sph[c]);
    }
    for (int c = 0; c < w->ncyl && w->con; c++) {
        if (cylray_prepare_cone(&w->prep[c], &w->con[c]) != CYLRAY_OK) {
            fprintf(stderr, "cylbench: %s: cone %d rejected by cylray_prepare_cone\n", s->name,
                    c);
            return -1;
        }
        tb_prepare_cone(&w->tbc[c], &w->con[c]);
    }
    for (int c = 0; c < w->ncyl && !w->sph && !w->con; c++) {
        if (cylray_prepare(&w->prep[c], &w->cyl[c]) != CYLRAY_OK) {
            fprintf(stderr, "cylbench: %s: cylinder %d rejected by cylray_prepare\n", s->name,
                    c);
            return -1;
        }
        tb_prepare(&w->tb[c], &w->cyl[c]);
    }
    if (w->big)
        w->ref_stride = n / 16384 ? n / 16384 : 1; /* 16 Ki rays checked against exact */
    return 0;
}

void workloads_free(workload *w)
{
    accuracy_release(w);
    raysoa_free(&w->rays);
    free(w->cyl);
    bench_free(w->prep);
    free(w->tb);
    free(w->sph);
    free(w->tbs);
    free(w->con);
    free(w->tbc);
    memset(w, 0, sizeof *w);
}
