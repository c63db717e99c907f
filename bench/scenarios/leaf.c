/* SPDX-License-Identifier: MIT */
/* leaf.c - the leaf scenario: single incoherent rays, each against a run of leaves
 * (LEAF_RUN cylinders) of a scene of molecule bonds and pipes, with the cylinders in
 * leaves of 4, 8 and 16 (the lanes run across cylinders) and, for the same work, a scalar
 * loop over the cylinders and one-lane calls of the packet API.
 *
 * A BVH brings a ray to the leaves whose boxes it crosses: here the cylinders are sorted
 * along a Morton curve, so that a run of LEAF_RUN consecutive ones is a compact cluster
 * as a BVH's leaves are, and each ray is aimed at a random point of one run's box from a
 * few box sizes away. The closest hit is kept through tmax across the run (occlusion
 * stops at the first hit). The scene is sized so that its leaves sit in L1 (leaf-l1)
 * or in L2 (leaf-l2). Rates are ray-cylinder tests per second: LEAF_RUN per ray.
 *
 * sphere-leaf is the same with atoms (spheres, scenegen.c) in L1, and one more loop for
 * the same work: the textbook sphere formula over the run's spheres in plain scalar
 * float (textbook-loop), the loop a tracer would write instead of calling anything.
 * cone-leaf is leaf-l1's scene with every cylinder tapered into a cone (sg_taper), and
 * the textbook cone in the same scalar loop. */
#include "leaf.h"

#include "clock.h"

#include "scenegen.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define LEAF_RUN 32   /* cylinders a ray meets: 8 leaves of 4, 4 of 8, 2 of 16 */
#define LEAF_RAYS 256 /* rays per pass: 8 KB, beside the leaves in L1 */

/* leaf calls, scalar loop, one-lane packet calls, the textbook sphere loop */
enum { LK_LEAF, LK_LOOP, LK_LANE, LK_TB };

typedef struct leaf_scene {
    int ncyl;
    cylray_cylinder *cyl; /* for spheres: stand-ins (center, radius, zero height) that
                                   sort and aim as the spheres */
    cylray_sphere *sph;   /* NULL: a scene of cylinders */
    tb_sphere *tbs;
    cylray_cone *con; /* non-NULL: a scene of cones (cyl: the cylinders around them) */
    tb_cone *tbc;
    cylray_prepared *prep;
    cylray_leaf4 *l4;
    cylray_leaf8 *l8;
    cylray_leaf16 *l16;
    cylray_ray1 *ray; /* LEAF_RAYS; tmax here is never modified */
    uint32_t *run;    /* per ray: the index of its run of LEAF_RUN cylinders */
} leaf_scene;

typedef struct leaf_cfg {
    int kind, isa, m, op;
    const cylray_kernels *k;
    size_t row; /* its result */
} leaf_cfg;

static volatile uint64_t leaf_sink;

/* Leaf `first / M` of width M from the shapes first.. first+M-1. */
#define LEAF_PREP(M)                                                                           \
    static int leaf_prep##M(leaf_scene *s, int first, const uint32_t *ids)                     \
    {                                                                                          \
        cylray_leaf##M *L = &s->l##M[first / M];                                               \
        if (s->sph)                                                                            \
            return cylray_leaf_prepare_spheres##M(L, s->sph + first, ids, M) != CYLRAY_OK;     \
        if (s->con)                                                                            \
            return cylray_leaf_prepare_cones##M(L, s->con + first, ids, M) != CYLRAY_OK;       \
        return cylray_leaf_prepare##M(L, s->cyl + first, ids, M) != CYLRAY_OK;                 \
    }
LEAF_PREP(4)
LEAF_PREP(8)
LEAF_PREP(16)

/* Every shape prepared alone (for the loops) and in leaves of 4, 8 and 16. A cylinder
 * the library refuses (the one-end cap flags in a build without them) is capped at both
 * ends instead; -1 when a shape is refused even so. */
static int prepare_all(leaf_scene *s)
{
    for (int i = 0; i < s->ncyl; i++) {
        if (s->sph) {
            if (cylray_prepare_sphere(&s->prep[i], &s->sph[i]) != CYLRAY_OK)
                return -1;
            tb_prepare_sphere(&s->tbs[i], &s->sph[i]);
        } else if (s->con) {
            if (cylray_prepare_cone(&s->prep[i], &s->con[i]) != CYLRAY_OK)
                return -1;
            tb_prepare_cone(&s->tbc[i], &s->con[i]);
        } else if (cylray_prepare(&s->prep[i], &s->cyl[i]) != CYLRAY_OK) {
            s->cyl[i].flags = CYLRAY_CAPPED;
            if (cylray_prepare(&s->prep[i], &s->cyl[i]) != CYLRAY_OK)
                return -1;
        }
    }
    uint32_t ids[16];
    for (int i = 0; i < s->ncyl; i += 16) {
        for (int j = 0; j < 16; j++)
            ids[j] = (uint32_t)(i + j);
        for (int j = 0; j < 16; j += 4)
            if (leaf_prep4(s, i + j, ids + j))
                return -1;
        for (int j = 0; j < 16; j += 8)
            if (leaf_prep8(s, i + j, ids + j))
                return -1;
        if (leaf_prep16(s, i, ids))
            return -1;
    }
    return 0;
}

/* Rays: from 2-5 box diagonals away toward a random point of one run's box. */
static void aim_rays(leaf_scene *s, rng *g)
{
    const int nrun = s->ncyl / LEAF_RUN;
    for (int j = 0; j < LEAF_RAYS; j++) {
        int run = (int)(rng_unit(g) * nrun);
        double lo[3] = {INFINITY, INFINITY, INFINITY},
               hi[3] = {-INFINITY, -INFINITY, -INFINITY};
        for (int i = run * LEAF_RUN; i < (run + 1) * LEAF_RUN; i++) {
            const cylray_cylinder *c = &s->cyl[i];
            double al = sqrt((double)c->axis[0] * c->axis[0] + (double)c->axis[1] * c->axis[1] +
                             (double)c->axis[2] * c->axis[2]);
            for (int k = 0; k < 3; k++) {
                double ext = fabs(c->axis[k] / al) * c->half_height + c->radius;
                lo[k] = fmin(lo[k], c->center[k] - ext);
                hi[k] = fmax(hi[k], c->center[k] + ext);
            }
        }
        double diag =
            sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                 (hi[2] - lo[2]) * (hi[2] - lo[2]));
        double target[3], u[3], ul = 0;
        for (int k = 0; k < 3; k++) {
            target[k] = rng_range(g, lo[k], hi[k]);
            u[k] = rng_range(g, -1, 1);
            ul += u[k] * u[k];
        }
        ul = sqrt(ul) > 1e-3 ? sqrt(ul) : 1;
        double dist = rng_range(g, 2, 5) * diag;
        cylray_ray1 *r = &s->ray[j];
        for (int k = 0; k < 3; k++) {
            r->o[k] = (float)(target[k] + dist * u[k] / ul);
            r->d[k] = (float)(-u[k] / ul);
        }
        r->tmin = 0;
        r->tmax = INFINITY;
        s->run[j] = (uint32_t)run;
    }
}

static void scene_free(leaf_scene *s)
{
    free(s->cyl);
    free(s->sph);
    free(s->tbs);
    free(s->con);
    free(s->tbc);
    bench_free(s->prep);
    bench_free(s->l4);
    bench_free(s->l8);
    bench_free(s->l16);
    free(s->ray);
    free(s->run);
    memset(s, 0, sizeof *s);
}

/* shape: 0 cylinders, 1 spheres, 2 cones */
static int scene_build(leaf_scene *s, int ncyl, int shape, uint64_t seed)
{
    memset(s, 0, sizeof *s);
    s->ncyl = ncyl;
    s->cyl = calloc((size_t)ncyl, sizeof *s->cyl);
    s->prep = bench_alloc((size_t)ncyl * sizeof *s->prep);
    s->l4 = bench_alloc((size_t)ncyl / 4 * sizeof *s->l4);
    s->l8 = bench_alloc((size_t)ncyl / 8 * sizeof *s->l8);
    s->l16 = bench_alloc((size_t)ncyl / 16 * sizeof *s->l16);
    s->ray = calloc(LEAF_RAYS, sizeof *s->ray);
    s->run = calloc(LEAF_RAYS, sizeof *s->run);
    if (!s->cyl || !s->prep || !s->l4 || !s->l8 || !s->l16 || !s->ray || !s->run)
        return -1;
    rng g = {seed};
    if (shape == 1) {
        s->sph = calloc((size_t)ncyl, sizeof *s->sph);
        s->tbs = calloc((size_t)ncyl, sizeof *s->tbs);
        if (!s->sph || !s->tbs)
            return -1;
        const double base[3] = {0, 0, 0};
        sg_atoms(s->sph, ncyl, base, &g);
        for (int i = 0; i < ncyl; i++) {
            const cylray_sphere *q = &s->sph[i];
            s->cyl[i] = (cylray_cylinder){
                {q->center[0], q->center[1], q->center[2]}, {0, 0, 1}, q->radius, 0, 0};
        }
        if (sg_morton_sort(s->cyl, ncyl))
            return -1;
        for (int i = 0; i < ncyl; i++) {
            cylray_sphere q = {{s->cyl[i].center[0], s->cyl[i].center[1], s->cyl[i].center[2]},
                               s->cyl[i].radius};
            s->sph[i] = q;
        }
        if (prepare_all(s))
            return -1;
        aim_rays(s, &g);
        return 0;
    }
    const int half = ncyl / 2;
    const double size = 1.4 * cbrt(half / 1.5);
    const double mol_base[3] = {0, 0, 0}, pipe_base[3] = {1.1 * size, 0, 0};
    int k = sg_molecule(s->cyl, half, mol_base, &g);
    k += sg_pipes(s->cyl + k, ncyl - k, pipe_base, size, &g);
    if (k != ncyl || sg_morton_sort(s->cyl, ncyl))
        return -1;
    if (shape == 2) {
        s->con = calloc((size_t)ncyl, sizeof *s->con);
        s->tbc = calloc((size_t)ncyl, sizeof *s->tbc);
        if (!s->con || !s->tbc)
            return -1;
        sg_taper(s->cyl, s->con, ncyl, &g);
    }
    if (prepare_all(s))
        return -1;
    aim_rays(s, &g);
    return 0;
}

/* ---- the timed passes: every ray against its run, closest hit (or any hit) ------ */

/* The leaf calls of width M; the hit's id + 1 (or 1 for occluded) goes into the sum, so
 * nothing can be dropped. */
#define PASS_LEAF(M)                                                                           \
    static uint64_t pass_leaf##M(const leaf_scene *s, const leaf_cfg *c, uint32_t *out)        \
    {                                                                                          \
        uint64_t acc = 0;                                                                      \
        const unsigned fl = bench_op_flags[c->op];                                             \
        for (int j = 0; j < LEAF_RAYS; j++) {                                                  \
            cylray_ray1 r = s->ray[j];                                                         \
            const cylray_leaf##M *L = s->l##M + s->run[j] * (LEAF_RUN / M);                    \
            uint32_t res = 0;                                                                  \
            if (c->op == OP_OCC) {                                                             \
                for (int k = 0; k < LEAF_RUN / M && !res; k++)                                 \
                    res = (uint32_t)c->k->leaf_occluded##M(L + k, &r, fl);                     \
            } else {                                                                           \
                cylray_hit1 h;                                                                 \
                for (int k = 0; k < LEAF_RUN / M; k++)                                         \
                    if (c->k->leaf_intersect##M(L + k, &r, &h, fl))                            \
                        res = h.id + 1;                                                        \
            }                                                                                  \
            acc += res;                                                                        \
            if (out)                                                                           \
                out[j] = res;                                                                  \
        }                                                                                      \
        return acc;                                                                            \
    }
PASS_LEAF(4)
PASS_LEAF(8)
PASS_LEAF(16)

/* The same work one cylinder at a time through a packet call with one active lane:
 * the scalar path's 4-wide packet (the scalar loop) or the best path's 8-wide one. */
#define PASS_LANE(N)                                                                           \
    static uint64_t pass_lane##N(const leaf_scene *s, const leaf_cfg *c, uint32_t *out)        \
    {                                                                                          \
        uint64_t acc = 0;                                                                      \
        const unsigned fl = bench_op_flags[c->op];                                             \
        cylray_ray##N pk;                                                                      \
        cylray_hit##N h;                                                                       \
        memset(&pk, 0, sizeof pk);                                                             \
        for (int j = 0; j < LEAF_RAYS; j++) {                                                  \
            const cylray_ray1 *r = &s->ray[j];                                                 \
            pk.ox[0] = r->o[0], pk.oy[0] = r->o[1], pk.oz[0] = r->o[2];                        \
            pk.dx[0] = r->d[0], pk.dy[0] = r->d[1], pk.dz[0] = r->d[2];                        \
            pk.tmin[0] = r->tmin, pk.tmax[0] = r->tmax;                                        \
            const cylray_prepared *P = s->prep + s->run[j] * LEAF_RUN;                         \
            uint32_t res = 0;                                                                  \
            if (c->op == OP_OCC) {                                                             \
                for (int k = 0; k < LEAF_RUN && !res; k++)                                     \
                    res = c->k->occluded##N(P + k, &pk, 1u, fl);                               \
            } else {                                                                           \
                for (int k = 0; k < LEAF_RUN; k++)                                             \
                    if (c->k->intersect##N(P + k, &pk, &h, 1u, fl))                            \
                        res = s->run[j] * LEAF_RUN + (uint32_t)k + 1;                          \
            }                                                                                  \
            acc += res;                                                                        \
            if (out)                                                                           \
                out[j] = res;                                                                  \
        }                                                                                      \
        return acc;                                                                            \
    }
PASS_LANE(4)
PASS_LANE(8)

/* The textbook sphere (or cone) over the run's shapes, one ray at a time, in one call a
 * run (the formula inlined in its loop, as a tracer would have it). */
static uint64_t pass_textbook(const leaf_scene *s, const leaf_cfg *c, uint32_t *out)
{
    uint64_t acc = 0;
    const unsigned fl = bench_op_flags[c->op];
    for (int j = 0; j < LEAF_RAYS; j++) {
        cylray_ray1 r = s->ray[j];
        cylray_hit1 h;
        const uint32_t first = s->run[j] * LEAF_RUN;
        const int occ = c->op == OP_OCC;
        uint32_t k = s->sph ? tb_sphere_run_scalar(s->tbs + first, LEAF_RUN, &r, &h, fl, occ)
                            : tb_cone_run_scalar(s->tbc + first, LEAF_RUN, &r, &h, fl, occ);
        uint32_t res = c->op == OP_OCC ? k != 0 : k ? first + k : 0;
        acc += res;
        if (out)
            out[j] = res;
    }
    return acc;
}

static uint64_t run_pass(const leaf_scene *s, const leaf_cfg *c, uint32_t *out)
{
    if (c->kind == LK_TB)
        return pass_textbook(s, c, out);
    if (c->kind == LK_LOOP)
        return pass_lane4(s, c, out);
    if (c->kind == LK_LANE)
        return pass_lane8(s, c, out);
    return c->m == 4   ? pass_leaf4(s, c, out)
           : c->m == 8 ? pass_leaf8(s, c, out)
                       : pass_leaf16(s, c, out);
}

/* One round's sample of a configuration, as timing.c takes them: warm-up (which sizes
 * the sample) on the first visit, an untimed pass, then K timed passes. */
static void sample(const leaf_scene *s, const leaf_cfg *c, result *r, const options *opt,
                   int first_of_isa)
{
    uint64_t acc = 0;
    const double tests = (double)LEAF_RAYS * LEAF_RUN;
    if (r->passes_per_sample == 0) {
        double warm = first_of_isa ? opt->warm_ns : 2 * opt->sample_ns, pass_ns = 0;
        int passes = 0;
        double t0 = clk_ns();
        do {
            double a = clk_ns();
            acc += run_pass(s, c, NULL);
            pass_ns += clk_ns() - a;
            passes++;
        } while (passes < 2 || clk_ns() - t0 < warm);
        pass_ns /= passes;
        long k = (long)ceil(opt->sample_ns / (pass_ns > 1 ? pass_ns : 1));
        r->passes_per_sample = k < 1 ? 1 : k;
    }
    for (int tries = 0; tries < 8 && r->samples < BENCH_MAXSAMP; tries++) {
        acc += run_pass(s, c, NULL);
        double p0 = clk_cpu_ns(), a0 = clk_ns();
        uint64_t c0 = clk_ticks();
        for (long k = 0; k < r->passes_per_sample; k++)
            acc += run_pass(s, c, NULL);
        uint64_t c1 = clk_ticks();
        double a1 = clk_ns(), p1 = clk_cpu_ns();
        double per = (double)r->passes_per_sample * tests;
        int i = r->samples++;
        r->s_wall[i] = (a1 - a0) / per;
        r->s_cpu[i] = (p1 - p0) / per;
        r->s_tick[i] = (double)(c1 - c0) / per;
        r->s_clean[i] = p1 - p0 >= 0.95 * (a1 - a0);
        if (r->s_clean[i])
            break;
    }
    leaf_sink = leaf_sink + acc;
}

static const char *const size_name[LEAF_NSIZE] = {"leaf-l1", "leaf-l2", "sphere-leaf",
                                                  "cone-leaf"};
static const char *const size_group[LEAF_NSIZE] = {"leaf", "leaf", "spheres", "cones"};
/* 256 cylinders: 16 KB of leaves (32 KB as cylray_prepared for the loops), in a 48 KB
 * L1; 8192: 512 KB of leaves (1 MB prepared), past L1 and inside a 2 MB L2; 256
 * spheres, and 256 cones, in L1. */
static const int size_cyl[LEAF_NSIZE] = {256, 8192, 256, 256};

static int size_selected(const options *opt, int sz)
{
    if (!opt->scenarios)
        return 1;
    return workloads_selected_name(opt->scenarios, size_name[sz], "leaf") ||
           workloads_selected_name(opt->scenarios, size_name[sz], size_group[sz]);
}

int leaf_selected(const options *opt)
{
    int any = 0;
    for (int sz = 0; sz < LEAF_NSIZE; sz++)
        any |= size_selected(opt, sz);
    return any;
}

int leaf_available(void)
{
    const cylray_kernels *k = cylray_kernels_for(CYLRAY_ISA_SCALAR);
    return k && k->leaf_intersect4 != NULL;
}

void leaf_run(const options *opt, result_list *results, leaf_report *rep)
{
    memset(rep, 0, sizeof *rep);
    const cylray_kernels *best = cylray_kernels_best();
    if (!leaf_available() || !best)
        return;
    rep->have = 1;
    rep->run = LEAF_RUN;
    rep->bytes_per_cyl[0] = (int)(sizeof(cylray_leaf4) / 4);
    rep->bytes_per_cyl[1] = (int)(sizeof(cylray_leaf8) / 8);
    rep->bytes_per_cyl[2] = (int)(sizeof(cylray_leaf16) / 16);
    snprintf(rep->best, sizeof rep->best, "%s", best->name);
    for (int sz = 0; sz < LEAF_NSIZE; sz++) {
        if (!size_selected(opt, sz))
            continue;
        leaf_scene s;
        if (scene_build(&s, size_cyl[sz], sz < 2 ? 0 : sz - 1, 0x1eaf0000u + (uint64_t)sz)) {
            fprintf(stderr, "cylbench: %s: cannot build the scene; skipped\n", size_name[sz]);
            scene_free(&s);
            continue;
        }
        rep->ncyl[sz] = s.ncyl;
        leaf_cfg cfg[CYLRAY_ISA_COUNT * 9 + 9];
        int nc = 0;
        const int ops[3] = {OP_T, OP_NORMAL, OP_OCC};
        for (int o = 0; o < 3; o++) {
            for (int isa = 0; isa < CYLRAY_ISA_COUNT; isa++) {
                const cylray_kernels *k = cylray_kernels_for((cylray_isa)isa);
                if (!k || !k->leaf_intersect4 || !(opt->isa_mask >> isa & 1u))
                    continue;
                for (int m = 4; m <= 16; m *= 2)
                    cfg[nc++] = (leaf_cfg){LK_LEAF, isa, m, ops[o], k, 0};
            }
            cfg[nc++] = (leaf_cfg){
                LK_LOOP, CYLRAY_ISA_SCALAR, 1, ops[o], cylray_kernels_for(CYLRAY_ISA_SCALAR),
                0};
            cfg[nc++] = (leaf_cfg){LK_LANE, best->isa, 1, ops[o], best, 0};
            if (s.sph || s.con)
                cfg[nc++] = (leaf_cfg){LK_TB, CYLRAY_ISA_SCALAR, 1, ops[o], NULL, 0};
        }
        for (int i = 0; i < nc; i++) {
            result *r = results_push(results);
            if (!r) {
                nc = i;
                break;
            }
            leaf_cfg *c = &cfg[i];
            c->row = results->n - 1;
            snprintf(r->scenario, sizeof r->scenario, "%s", size_name[sz]);
            snprintf(r->group, sizeof r->group, "leaf");
            if (c->kind == LK_LEAF)
                snprintf(r->isa, sizeof r->isa, "%s", c->k->name);
            else if (c->kind == LK_LOOP)
                snprintf(r->isa, sizeof r->isa, "scalar-loop");
            else if (c->kind == LK_TB)
                snprintf(r->isa, sizeof r->isa, "textbook-loop");
            else
                snprintf(r->isa, sizeof r->isa, "1-lane:%s", c->k->name);
            snprintf(r->op, sizeof r->op, "%s", bench_op_name[c->op]);
            r->isa_id = c->kind == LK_LEAF ? c->isa : -1;
            r->width_id = c->m == 4 ? BW_4 : c->m == 8 ? BW_8 : c->m == 16 ? BW_16 : BW_STREAM;
            r->op_id = c->op;
            r->rays_timed = LEAF_RAYS;
            rep->sphere |= s.sph != NULL;
            rep->cone |= s.con != NULL;
            r->ncyl = LEAF_RUN;
        }
        /* rounds over all configurations, as the other scenarios are sampled */
        int warmed[CYLRAY_ISA_COUNT] = {0};
        for (int round = 0; round < opt->reps; round++)
            for (int i = 0; i < nc; i++) {
                int first = !warmed[cfg[i].isa];
                warmed[cfg[i].isa] = 1;
                sample(&s, &cfg[i], &results->r[cfg[i].row], opt, first);
            }
        /* The answers against the scalar loop's (same op class): hit or not and, for
         * intersections, the cylinder; a near tie may differ legitimately. */
        uint32_t *ref = malloc(LEAF_RAYS * sizeof *ref), *got = malloc(LEAF_RAYS * sizeof *got);
        static const workload none; /* bench_summarize reads only `big` */
        for (int i = 0; i < nc; i++) {
            result *r = &results->r[cfg[i].row];
            bench_summarize(&none, r, opt->reps);
            if (!ref || !got)
                continue;
            leaf_cfg loop = {
                LK_LOOP, CYLRAY_ISA_SCALAR, 1, cfg[i].op, cylray_kernels_for(CYLRAY_ISA_SCALAR),
                0};
            run_pass(&s, &loop, ref);
            run_pass(&s, &cfg[i], got);
            size_t hits = 0, diff = 0;
            for (int j = 0; j < LEAF_RAYS; j++) {
                hits += got[j] != 0;
                diff += cfg[i].op == OP_OCC ? (got[j] != 0) != (ref[j] != 0) : got[j] != ref[j];
            }
            r->hit_frac = (double)hits / LEAF_RAYS;
            rep->diff[sz] += diff;
        }
        free(ref), free(got);
        scene_free(&s);
    }
}
