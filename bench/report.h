/* SPDX-License-Identifier: MIT */
/* report.h - the outputs: tables on stdout, CSV, JSON, a long text table, SVG plots. */
#ifndef CYLBENCH_REPORT_H
#define CYLBENCH_REPORT_H

#include "bench.h"
#include "machine.h"
#include "leaf.h"
#include "scene.h"

void report_all(const result_list *l, const machine_info *m, const options *opt,
                const scene_report *sc, const leaf_report *lr, double wall_s);

/* svg.c */
int svg_time_vs_error(const char *path, const result_list *l, const machine_info *m);
int svg_speedup(const char *path, const result_list *l, const machine_info *m);

/* report_fmt.c: small formatting helpers shared by the writers. */
const char *fmt_ulps(double u, char *buf, size_t n);   /* "0.5", "12", "3.4k", "2e+06" */
const result *find_result(const result_list *l, const char *scenario, int isa, int width_id,
                          int op);
/* The one-line machine description used in every output. */
void machine_line(const machine_info *m, char *buf, size_t n);

#endif
