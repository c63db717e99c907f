/* SPDX-License-Identifier: MIT */
/* main.c - cylbench: every ISA x width x flag set x scenario, run time against error.
 *
 *   cylbench [--isa=LIST] [--width=LIST] [--scenario=LIST] [--quick] [--out=DIR]
 *            [--reps=N] [--sample-ms=X]
 *
 * Prints a readable table on stdout and writes results.csv, results.json, table.txt,
 * time_vs_error.svg, speedup.svg and scene.png into DIR (default bench/out). */
#include "bench.h"
#include "clock.h"
#include "leaf.h"
#include "machine.h"
#include "report.h"
#include "scene.h"
#include "workloads.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static void usage(FILE *f)
{
    fprintf(f,
            "usage: cylbench [options]\n"
            "  --isa=LIST       scalar,sse41,avx2,avx512,neon, and the textbook peer's builds\n"
            "                   textbook (scalar), auto-sse41, auto-avx2, auto-avx512,\n"
            "                   auto-neon (default: all this CPU runs)\n"
            "  --width=LIST     4,8,16,stream (default: each scenario's own)\n"
            "  --scenario=LIST  names or groups: main, stream, skips, lanes, spheres, cones,\n"
            "                   stress, leaf, scene, all\n"
            "                   (main: coherent incoherent shadow bvh-leaf miss-mix hit-mix;\n"
            "                    stream: big-stream; skips: aligned general open infinite\n"
            "                    open-coherent infinite-coherent all-miss all-hit;\n"
            "                    lanes: half-zero half-subnormal;\n"
            "                    spheres: sphere-incoherent sphere-coherent sphere-far\n"
            "                    sphere-leaf; cones: cone-incoherent cone-coherent\n"
            "                    cone-far cone-tip cone-nearcyl cone-leaf;\n"
            "                    leaf: leaf-l1 leaf-l2 sphere-leaf cone-leaf;\n"
            "                    stress: stress-<category of tests/ref/gen.h>)\n"
            "  --quick          fewer and shorter samples, smaller big stream\n"
            "  --flush-subnormals  run with subnormals flushed to zero (x86 DAZ and FTZ,\n"
            "                   AArch64 FZ): shows what subnormals cost; the error figures\n"
            "                   are then those of that environment\n"
            "  --out=DIR        output directory (default bench/out)\n"
            "  --reps=N         timed samples per configuration (default 15, quick 7)\n"
            "  --sample-ms=X    length of one sample in ms (default 1, quick 0.4)\n");
}

/* Bit per item of a comma-separated list, from a table of names; -1 on an unknown one. */
static long parse_list(const char *arg, const char *const *names, int n)
{
    long mask = 0;
    for (const char *p = arg; *p;) {
        size_t k = strcspn(p, ",");
        int found = -1;
        for (int i = 0; i < n; i++)
            if (names[i] && strlen(names[i]) == k && strncmp(p, names[i], k) == 0)
                found = i;
        if (found < 0) {
            fprintf(stderr, "cylbench: unknown item '%.*s' in '%s'\n", (int)k, p, arg);
            return -1;
        }
        mask |= 1L << found;
        p += k;
        if (*p == ',')
            p++;
    }
    return mask;
}

static int parse_options(int argc, char **argv, options *o)
{
    memset(o, 0, sizeof *o);
    o->isa_mask = ~0u;
    o->width_mask = 0; /* 0: each scenario's own */
    o->out_dir = "bench/out";
    int reps = 0;
    double sample_ms = 0;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strncmp(a, "--isa=", 6)) {
            const char *names[BENCH_NISA];
            for (int k = 0; k < BENCH_NISA; k++)
                names[k] = bench_isa_name(k);
            long m = parse_list(a + 6, names, BENCH_NISA);
            if (m < 0)
                return -1;
            o->isa_mask = (unsigned)m;
        } else if (!strncmp(a, "--width=", 8)) {
            long m = parse_list(a + 8, bench_width_name, BW_COUNT);
            if (m < 0)
                return -1;
            o->width_mask = (unsigned)m;
        } else if (!strncmp(a, "--scenario=", 11)) {
            o->scenarios = a + 11;
            if (workloads_check_list(o->scenarios))
                return -1;
        } else if (!strcmp(a, "--quick")) {
            o->quick = 1;
        } else if (!strcmp(a, "--flush-subnormals")) {
            o->flush_subnormals = 1;
        } else if (!strncmp(a, "--out=", 6)) {
            o->out_dir = a + 6;
        } else if (!strncmp(a, "--reps=", 7)) {
            reps = atoi(a + 7);
        } else if (!strncmp(a, "--sample-ms=", 12)) {
            sample_ms = atof(a + 12);
        } else if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            usage(stdout);
            exit(0);
        } else {
            fprintf(stderr, "cylbench: unknown option '%s'\n", a);
            usage(stderr);
            return -1;
        }
    }
    o->reps = reps > 0 ? reps : o->quick ? 7 : 15;
    o->sample_ns = (sample_ms > 0 ? sample_ms : o->quick ? 0.4 : 1.0) * 1e6;
    o->warm_ns = o->quick ? 20e6 : 60e6;
    /* 4 Mi or 8 Mi rays: 128 or 256 MB of ray input, beyond any cache here */
    o->big_rays = o->quick ? (size_t)4 << 20 : (size_t)8 << 20;
    o->scene_w = 640;
    o->scene_h = 360;
    return 0;
}

static int mkdir_p(const char *path)
{
    char buf[1024];
    snprintf(buf, sizeof buf, "%s", path);
    for (char *p = buf + 1; *p; p++)
        if (*p == '/') {
            *p = 0;
            if (mkdir(buf, 0777) && errno != EEXIST)
                return -1;
            *p = '/';
        }
    return mkdir(buf, 0777) && errno != EEXIST ? -1 : 0;
}

/* The ISAs to run: those asked for that this build and CPU have. */
static int isa_runs(const options *o, int isa)
{
    if (!(o->isa_mask >> isa & 1u))
        return 0;
    if (bench_is_textbook(isa))
        return tb_variant(isa - BENCH_ISA_TEXTBOOK) != NULL;
    return cylray_kernels_for((cylray_isa)isa) != NULL;
}

static unsigned widths_of(const workload *w, const options *o)
{
    if (!o->width_mask)
        return w->widths;
    return w->big ? o->width_mask & (1u << BW_STREAM) : o->width_mask;
}

/* The configurations a workload runs, in order: flag set, width, then ISA innermost,
 * so that the ISAs of one configuration are measured close together in time. */
typedef void (*config_fn)(void *ctx, workload *w, int op, int wid, int isa);

static int for_configs(workload *w, const options *o, config_fn fn, void *ctx)
{
    int n = 0;
    unsigned widths = widths_of(w, o);
    for (int op = 0; op < OP_COUNT; op++) {
        if (!(w->ops >> op & 1u))
            continue;
        for (int wid = 0; wid < BW_COUNT; wid++) {
            if (!(widths >> wid & 1u))
                continue;
            for (int isa = 0; isa < CYLRAY_ISA_COUNT; isa++)
                if (isa_runs(o, isa)) {
                    if (fn)
                        fn(ctx, w, op, wid, isa);
                    n++;
                }
        }
        /* The textbook peer: a stream with normals, each of its builds. */
        if (w->textbook && op == OP_NORMAL)
            for (int isa = BENCH_ISA_TEXTBOOK; isa < BENCH_NISA; isa++)
                if (isa_runs(o, isa)) {
                    if (fn)
                        fn(ctx, w, op, BW_STREAM, isa);
                    n++;
                }
    }
    return n;
}

typedef struct run_ctx {
    const options *opt;
    result_list *results;
    size_t next; /* the result the next configuration samples into */
    int want;    /* clean samples per configuration in this round */
    int done, total, tty;
    int warmed[BENCH_NISA];
    double memcpy_gbs, t_start;
} run_ctx;

static void progress(run_ctx *c, const char *scen, const char *what)
{
    if (c->tty)
        fprintf(stderr, "\r[%5d/%5d] %-20s %-34s", c->done, c->total, scen, what);
}

/* Round 0 creates the configuration's row; every round appends samples to it. */
static void sample_config(void *vctx, workload *w, int op, int wid, int isa)
{
    run_ctx *c = vctx;
    char what[64];
    snprintf(what, sizeof what, "%s w%s %s", bench_isa_name(isa), bench_width_name[wid],
             bench_op_name[op]);
    progress(c, w->name, what);
    result *r;
    if (c->next == c->results->n) {
        r = results_push(c->results);
        if (!r)
            return;
        snprintf(r->scenario, sizeof r->scenario, "%s", w->name);
        snprintf(r->group, sizeof r->group, "%s", w->group);
        snprintf(r->isa, sizeof r->isa, "%s", bench_isa_name(isa));
        snprintf(r->op, sizeof r->op, "%s", bench_op_name[op]);
        r->isa_id = isa;
        r->width_id = wid;
        r->op_id = op;
    }
    r = &c->results->r[c->next++];
    if (r->samples < 0) { /* failed in an earlier round */
        c->done++;
        return;
    }
    int first = !c->warmed[isa];
    c->warmed[isa] = 1;
    if (bench_sample(w, isa, wid, op, c->opt, r, c->want, first) != 0)
        r->samples = -1; /* not runnable (no memory): dropped at the end */
    c->done++;
}

/* After the last round: the statistics, and the error side on the same rays. */
static void finish_config(void *vctx, workload *w, int op, int wid, int isa)
{
    run_ctx *c = vctx;
    result *r = &c->results->r[c->next++];
    (void)op, (void)wid, (void)isa;
    if (r->samples <= 0)
        return;
    bench_summarize(w, r, w->big ? c->want : c->opt->reps);
    if (w->big)
        r->memcpy_gbytes_s = c->memcpy_gbs;
    char what[64];
    snprintf(what, sizeof what, "error side: %s w%s %s", r->isa, bench_width_name[wid], r->op);
    progress(c, w->name, what);
    accuracy_measure(w, isa, wid, op, r);
}

static void drop_failed(result_list *l)
{
    size_t k = 0;
    for (size_t i = 0; i < l->n; i++)
        if (l->r[i].samples > 0)
            l->r[k++] = l->r[i];
    l->n = k;
}

static void note(run_ctx *c, const char *what)
{
    if (!c->tty)
        fprintf(stderr, "cylbench: %s (%d/%d configurations sampled, %.1f s)\n", what, c->done,
                c->total, (clk_ns() - c->t_start) * 1e-9);
}

/* Speedup over the scalar path in the same run: same scenario, width and flag set (the
 * textbook builds against scalar's stream, or its first width measured). */
static void compute_speedups(result_list *l)
{
    for (size_t i = 0; i < l->n; i++) {
        result *r = &l->r[i];
        for (size_t j = 0; j < l->n; j++) {
            const result *s = &l->r[j];
            if (s->isa_id == CYLRAY_ISA_SCALAR && !strcmp(s->scenario, r->scenario) &&
                s->op_id == r->op_id &&
                (s->width_id == r->width_id ||
                 (bench_is_textbook(r->isa_id) && r->speedup == 0)) &&
                r->ns.med > 0) {
                r->speedup = s->ns.med / r->ns.med;
                if (s->width_id == r->width_id)
                    break;
            }
        }
    }
}

int main(int argc, char **argv)
{
    options opt;
    if (parse_options(argc, argv, &opt))
        return 2;
    double t_start = clk_ns();
    if (mkdir_p(opt.out_dir)) {
        fprintf(stderr, "cylbench: cannot create %s\n", opt.out_dir);
        return 1;
    }
    if (opt.flush_subnormals && !clk_flush_subnormals()) {
        fprintf(stderr, "cylbench: --flush-subnormals: not supported on this CPU\n");
        return 2;
    }
    machine_info m;
    machine_probe(&m);
    clk_pin(m.pinned, sizeof m.pinned);

    run_ctx ctx;
    memset(&ctx, 0, sizeof ctx);
    result_list results = {0, 0, 0};
    ctx.opt = &opt;
    ctx.results = &results;
    ctx.tty = isatty(2);
    ctx.t_start = t_start;

    /* The L1-resident workloads are all built first and then sampled in rounds: each
     * round visits every configuration once and takes one sample of it, so a busy spell
     * of this shared machine lands on all configurations alike and the ratios between
     * them stay fair. The big stream (one long pass per sample) comes after. */
    const int rounds = opt.reps; /* one sample per configuration and round */
    int nw = workloads_count();
    workload *ws = calloc((size_t)nw, sizeof *ws);
    int nws = 0, big_idx[8], nbig = 0;
    if (!ws)
        return 1;
    fprintf(stderr, "cylbench: %s, %d cores, %s; paths: %s; reference: %s\n", m.cpu, m.cores,
            m.compiler, m.isas, accuracy_available() ? "exact (tests/ref)" : "none");
    for (int i = 0; i < nw; i++) {
        if (!workloads_selected(i, opt.scenarios))
            continue;
        workload w;
        memset(&w, 0, sizeof w);
        if (!strcmp(workloads_group(i), "stream")) {
            /* the configurations are counted now, the rays drawn when their turn comes */
            if (workloads_build(i, &w, &(options){.big_rays = 16, .quick = 1}) == 0 &&
                nbig < 8) {
                big_idx[nbig++] = i;
                ctx.total += for_configs(&w, &opt, NULL, NULL);
            }
            workloads_free(&w);
            continue;
        }
        progress(&ctx, workloads_name(i), "drawing rays, exact reference");
        if (workloads_build(i, &w, &opt) != 0) {
            fprintf(stderr, "\ncylbench: %s: cannot build this scenario; skipped\n",
                    workloads_name(i));
            workloads_free(&w);
            continue;
        }
        accuracy_reference(&w);
        ws[nws++] = w;
        ctx.total += rounds * for_configs(&w, &opt, NULL, NULL);
    }
    note(&ctx, "workloads built");
    for (int round = 0; round < rounds; round++) {
        ctx.next = 0;
        ctx.want = (opt.reps + rounds - 1 - round) / rounds; /* shares add up to reps */
        for (int k = 0; k < nws; k++)
            for_configs(&ws[k], &opt, sample_config, &ctx);
        if ((round + 1) % 5 == 0 || round + 1 == rounds) {
            char what[48];
            snprintf(what, sizeof what, "round %d of %d done", round + 1, rounds);
            note(&ctx, what);
        }
    }
    ctx.next = 0;
    for (int k = 0; k < nws; k++) {
        for_configs(&ws[k], &opt, finish_config, &ctx);
        workloads_free(&ws[k]);
    }
    note(&ctx, "error side done");
    free(ws);

    for (int k = 0; k < nbig; k++) {
        workload w;
        progress(&ctx, workloads_name(big_idx[k]), "drawing rays, exact reference");
        if (workloads_build(big_idx[k], &w, &opt) != 0) {
            fprintf(stderr, "\ncylbench: %s: cannot build this scenario; skipped\n",
                    workloads_name(big_idx[k]));
            workloads_free(&w);
            continue;
        }
        accuracy_reference(&w);
        progress(&ctx, w.name, "memcpy bound");
        ctx.memcpy_gbs = bench_memcpy_gbs(&w, &opt);
        size_t first = results.n;
        ctx.next = first;
        /* whole passes of 128 or 256 MB: fewer samples */
        ctx.want = opt.reps < 3 ? opt.reps : opt.quick ? 3 : 4;
        for_configs(&w, &opt, sample_config, &ctx);
        ctx.next = first;
        for_configs(&w, &opt, finish_config, &ctx);
        workloads_free(&w);
        note(&ctx, "big stream done");
    }
    drop_failed(&results);

    scene_report sc;
    memset(&sc, 0, sizeof sc);
    if (!opt.scenarios || strstr(opt.scenarios, "scene") || strstr(opt.scenarios, "all")) {
        progress(&ctx, "scene", "rendering");
        scene_run(&opt, &sc, &results);
    }
    leaf_report lr;
    memset(&lr, 0, sizeof lr);
    if (leaf_selected(&opt)) {
        progress(&ctx, "leaf", "leaves against loops");
        leaf_run(&opt, &results, &lr);
        if (!lr.have)
            fprintf(stderr, "%scylbench: leaf: the library has no leaf kernels; skipped\n",
                    ctx.tty ? "\n" : "");
    }
    if (ctx.tty)
        fprintf(stderr, "\r%-80s\r", "");
    compute_speedups(&results);
    m.load_end = machine_load();

    double wall = (clk_ns() - t_start) * 1e-9;
    report_all(&results, &m, &opt, &sc, &lr, wall);
    free(results.r);
    return 0;
}
