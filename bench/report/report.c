/* SPDX-License-Identifier: MIT */
/* report.c - the outputs of a run: the heading, the tables on stdout (tables.c), the
 * files (files.c) and the two plots (svg.c). */
#include "report.h"

#include <stdio.h>
#include <string.h>

void report_all(const result_list *l, const machine_info *m, const options *opt,
                const scene_report *sc, const leaf_report *lr, double wall)
{
    FILE *f = stdout;
    char ml[512];
    machine_line(m, ml, sizeof ml);
    fprintf(f, "cylbench: cylray ray/cylinder kernels, run time against error (%s)\n", m->date);
    fprintf(f, "machine: %s\n", ml);
    fprintf(f, "         %s; cylray paths on this CPU: %s; %s\n", m->os, m->isas, m->pinned);
    fprintf(f,
            "method:  batches of %d rays timed while in L1; per configuration %d samples of "
            ">= %.1f ms each, taken in\n         rounds over all configurations (a busy "
            "spell hits all alike), after a warm-up; median, spread in\n         "
            "results.csv (min, max, quartiles); per-ISA calls through "
            "cylray_kernels_for(isa); tmax restored\n         per packet inside the timed "
            "loop; hit counts summed into a volatile sink%s\n",
            BENCH_BATCH, opt->reps, opt->sample_ns * 1e-6, opt->quick ? "; --quick" : "");
    if (opt->flush_subnormals)
        fprintf(f,
                "         --flush-subnormals: subnormal inputs read as 0 and subnormal results "
                "flushed to 0 throughout\n");
    size_t busy = 0, timed = 0;
    for (size_t i = 0; i < l->n; i++)
        if (strcmp(l->r[i].scenario, "scene")) {
            timed++;
            busy += (size_t)l->r[i].cpu_timed;
        }
    fprintf(f,
            "load:    1-minute load average %.2f at the start, %.2f at the end, on %d cores; "
            "samples interrupted by other\n         processes are retaken; %zu of %zu "
            "configurations had too few clean ones and were timed by thread CPU time (~)\n",
            m->load_start, m->load_end, m->cores, busy, timed);
    fprintf(f, "error:   %s\n",
            accuracy_available()
                ? "exact binary128 reference (tests/ref), same rays as timed (big stream: "
                  "16 Ki of them)"
                : "no reference built: error columns empty");

    report_tables(f, l, sc, lr);
    report_files(l, m, opt, sc, wall);
    char p1[1024], p2[1024];
    snprintf(p1, sizeof p1, "%s/time_vs_error.svg", opt->out_dir);
    snprintf(p2, sizeof p2, "%s/speedup.svg", opt->out_dir);
    int e1 = svg_time_vs_error(p1, l, m), e2 = svg_speedup(p2, l, m);
    fprintf(f, "\noutputs in %s: results.csv results.json table.txt%s%s%s\n", opt->out_dir,
            e1 ? "" : " time_vs_error.svg", e2 ? "" : " speedup.svg",
            sc->have && sc->image[0] ? " scene.png" : "");
    fprintf(f, "harness wall time: %.1f s\n", wall);
}
