/* SPDX-License-Identifier: MIT */
/* report.h - the outputs: tables on stdout, CSV, JSON, a long text table, SVG plots. */
#ifndef CYLBENCH_REPORT_H
#define CYLBENCH_REPORT_H

#include "bench.h"
#include "machine.h"
#include "leaf.h"
#include "scene.h"

#include <stdio.h>

#define NCOLS BENCH_NISA

void report_all(const result_list *l, const machine_info *m, const options *opt,
                const scene_report *sc, const leaf_report *lr, double wall_s);

/* tables.c: the tables on stdout; files.c: results.csv, results.json, table.txt. */
void report_tables(FILE *f, const result_list *l, const scene_report *sc,
                   const leaf_report *lr);
void report_files(const result_list *l, const machine_info *m, const options *opt,
                  const scene_report *sc, double wall_s);
/* errors.c: the error table, and cylray against the textbook peer (for report_tables). */
void report_errors(FILE *f, const result_list *l);
void report_peer(FILE *f, const result_list *l);

/* svg.c */
int svg_time_vs_error(const char *path, const result_list *l, const machine_info *m);
int svg_speedup(const char *path, const result_list *l, const machine_info *m);

/* fmt.c: small formatting and lookup helpers shared by the writers. */
const char *fmt_ulps(double u, char *buf, size_t n); /* "0.5", "12", "3.4k", "2e+06" */
const result *find_result(const result_list *l, const char *scenario, int isa, int width_id,
                          int op);
/* The one-line machine description used in every output. */
void machine_line(const machine_info *m, char *buf, size_t n);
/* The auto-vectorized builds of the textbook, which have a table of their own. */
int is_auto(int isa);
/* The ISAs (and the scalar textbook) that have rows among the results of one group. */
int isas_in(const result_list *l, const char *group, int cols[NCOLS]);
/* "-", "occ" or the p99 error in ulps. */
const char *err_cell(const result *r, char *buf, size_t n);
/* a's median time over b's; 0 when either is missing. */
double ratio(const result *a, const result *b);
/* A row by its path's name (the loops have no ISA id); width_id < 0: any. */
const result *find_named(const result_list *l, const char *scenario, const char *isa,
                         int width_id, int op);

#endif
