/* SPDX-License-Identifier: MIT */
/* icount.c - cylicount: one configuration of the harness run for a fixed number of
 * passes and nothing else, to be counted under valgrind (bench/tools/icount.sh).
 *
 *   cylicount --isa=scalar|sse41|avx2|avx512|neon --driver=4|8|16|stream|textbook
 *             --flags=t|normal|occluded|refine|fast --scenario=NAME --passes=N
 *             [--batch=B]
 *
 * Without hardware counters, instructions can only be counted by a simulator, and a
 * simulator counts the whole process. The scenario, the packing and the pass are the
 * harness's own code (the cylbench_core library), so what is counted is what cylbench
 * times, bookkeeping of the pass included (the tmax restore, the hit count); set-up
 * cancels when two runs that differ only in N are subtracted. Exit status 2: the
 * path or build is not available here (valgrind hides AVX-512 from the CPU it
 * reports); 3: the harness does not measure that combination. */
#include "bench.h"
#include "timing_run.h"
#include "workloads.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static volatile uint64_t sink; /* every pass's hit count, so no pass is dead code */

static void usage(void)
{
    fprintf(stderr, "usage: cylicount --isa=scalar|sse41|avx2|avx512|neon\n"
                    "                 --driver=4|8|16|stream|textbook\n"
                    "                 --flags=t|normal|occluded|refine|fast\n"
                    "                 --scenario=coherent|incoherent|... --passes=N\n"
                    "                 [--batch=B]  (default: the batches in turn)\n");
}

/* The index of `s` in names[0..n), or -1. */
static int lookup(const char *s, const char *const *names, int n)
{
    for (int i = 0; i < n; i++)
        if (names[i] && !strcmp(s, names[i]))
            return i;
    return -1;
}

static int scenario_index(const char *s)
{
    for (int i = 0; i < workloads_count(); i++)
        if (!strcmp(s, workloads_name(i)))
            return i;
    return -1;
}

int main(int argc, char **argv)
{
    const char *isa_names[CYLRAY_ISA_COUNT];
    for (int i = 0; i < CYLRAY_ISA_COUNT; i++)
        isa_names[i] = cylray_isa_name((cylray_isa)i);
    /* the textbook peer's builds, by the cylray path whose instructions they may use */
    static const int tb_of[CYLRAY_ISA_COUNT] = {[CYLRAY_ISA_SCALAR] = TB_SCALAR,
                                                [CYLRAY_ISA_SSE41] = TB_SSE41,
                                                [CYLRAY_ISA_AVX2] = TB_AVX2,
                                                [CYLRAY_ISA_AVX512] = TB_AVX512,
                                                [CYLRAY_ISA_NEON] = TB_NEON};
    int isa = -1, width = -1, textbook = 0, op = -1, scen = -1, batch = -1;
    long passes = -1;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = strchr(a, '=');
        v = v ? v + 1 : "";
        if (!strncmp(a, "--isa=", 6)) {
            isa = lookup(v, isa_names, CYLRAY_ISA_COUNT);
        } else if (!strncmp(a, "--driver=", 9)) {
            textbook = !strcmp(v, "textbook");
            width = textbook ? BW_STREAM : lookup(v, bench_width_name, BW_COUNT);
        } else if (!strncmp(a, "--flags=", 8)) {
            op = lookup(v, bench_op_name, OP_COUNT);
        } else if (!strncmp(a, "--scenario=", 11)) {
            scen = scenario_index(v);
        } else if (!strncmp(a, "--passes=", 9)) {
            passes = strtol(v, NULL, 10);
        } else if (!strncmp(a, "--batch=", 8)) {
            batch = atoi(v);
        } else {
            usage();
            return 1;
        }
    }
    const char *bad = isa < 0      ? "--isa"
                      : width < 0  ? "--driver"
                      : op < 0     ? "--flags"
                      : scen < 0   ? "--scenario"
                      : passes < 1 ? "--passes"
                                   : NULL;
    if (bad) {
        fprintf(stderr, "cylicount: %s missing or not known\n", bad);
        usage();
        return 1;
    }

    options opt;
    memset(&opt, 0, sizeof opt);
    workload w;
    if (workloads_build(scen, &w, &opt)) {
        fprintf(stderr, "cylicount: could not build scenario %s\n", workloads_name(scen));
        return 1;
    }
    const size_t nb = w.rays.n / w.batch;
    if (w.big || !(w.ops >> op & 1u) || !(w.widths >> width & 1u) ||
        (textbook && (!w.textbook || op != OP_NORMAL)) || batch >= (int)nb) {
        fprintf(stderr, "cylicount: the harness does not measure this combination\n");
        return 3;
    }
    int id = isa;
    if (textbook) {
        id = BENCH_ISA_TEXTBOOK + tb_of[isa];
        if (!tb_variant(tb_of[isa])) {
            fprintf(stderr, "cylicount: no %s build of the textbook peer runs here\n",
                    tb_variant_name(tb_of[isa]));
            return 2;
        }
    } else if (!cylray_kernels_for((cylray_isa)isa)) {
        fprintf(stderr, "cylicount: the %s path is not built or not available on this CPU\n",
                isa_names[isa]);
        return 2;
    }
    runner x;
    if (runner_init(&x, &w, id, width, op)) {
        fprintf(stderr, "cylicount: out of memory\n");
        return 1;
    }

    uint64_t hits = 0;
    for (long p = 0; p < passes; p++)
        hits += x.pass(&x, batch >= 0 ? (size_t)batch : (size_t)p % nb);
    sink = sink + hits;
    printf("%s %s %s %s: %ld passes, %zu rays, %zu tests a ray, %llu hits\n",
           workloads_name(scen), isa_names[isa],
           textbook ? "textbook" : bench_width_name[width], bench_op_name[op], passes,
           (size_t)passes * w.batch, (size_t)bench_tests_per_ray(&w), (unsigned long long)hits);
    runner_free(&x);
    workloads_free(&w);
    return 0;
}
