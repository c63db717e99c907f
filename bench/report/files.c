/* SPDX-License-Identifier: MIT */
/* files.c - the files of a run: results.csv, results.json and table.txt, every
 * configuration one per line, all written from one list of columns. */
#include "report.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

/* One column of the per-configuration outputs. results.csv, results.json and table.txt
 * are all written from the list below, so a new figure is one line there. */
typedef enum col_kind {
    K_TEXT,  /* a string */
    K_COUNT, /* an integer */
    K_REAL,  /* a real number, printed with fmt */
    K_ULPS,  /* a real number of ulps: fmt in CSV, fmt_ulps in table.txt */
    K_MARK   /* yes or no: 0/1 in CSV, true/false in JSON, fmt in table.txt when yes */
} col_kind;

typedef enum col_when {
    ON_ALL,
    ON_ERR, /* only with an error side (an exact reference in the build) */
    ON_BIG  /* only for big streams */
} col_when;

/* Where a column's value lives: a field of the result, or a function of the result and
 * the machine. */
typedef enum col_type { T_STR, T_WIDTH, T_INT, T_SIZE, T_DBL, T_FN } col_type;
typedef double (*col_fn)(const result *r, const machine_info *m);

typedef struct column {
    const char *name; /* the CSV heading and the JSON key */
    const char *unit; /* "" for names and plain counts */
    col_kind kind;
    col_when when;
    const char *fmt;
    const char *head; /* the table.txt heading; NULL: not in table.txt */
    int width;        /* its table.txt width; negative: left-aligned */
    col_type type;
    size_t off;
    col_fn fn;
} column;

#define STR(f) T_STR, offsetof(result, f), NULL
#define INT(f) T_INT, offsetof(result, f), NULL
#define SIZE(f) T_SIZE, offsetof(result, f), NULL
#define DBL(f) T_DBL, offsetof(result, f), NULL
#define FN(f) T_FN, 0, f

static double core_cycles(const result *r, const machine_info *m)
{
    return r->ns.med * m->core_ghz;
}

static const column columns[] = {
    {"scenario", "", K_TEXT, ON_ALL, "%s", "scenario", -19, STR(scenario)},
    {"group", "", K_TEXT, ON_ALL, "%s", NULL, 0, STR(group)},
    {"isa", "", K_TEXT, ON_ALL, "%s", "isa", -14, STR(isa)},
    {"width", "rays per packet", K_TEXT, ON_ALL, "%s", "width", -6, T_WIDTH, 0, NULL},
    {"flags", "", K_TEXT, ON_ALL, "%s", "flags", -8, STR(op)},
    {"rays_per_pass", "rays", K_COUNT, ON_ALL, NULL, NULL, 0, SIZE(rays_timed)},
    {"tests_per_ray", "cylinders", K_COUNT, ON_ALL, NULL, NULL, 0, INT(ncyl)},
    {"reps", "samples", K_COUNT, ON_ALL, NULL, NULL, 0, INT(reps)},
    {"ns_med", "ns per ray and cylinder", K_REAL, ON_ALL, "%.4f", "ns/ray", 8, DBL(ns.med)},
    {"cpu_timed", "", K_MARK, ON_ALL, "~", "~", 1, INT(cpu_timed)},
    {"ns_min", "ns per ray and cylinder", K_REAL, ON_ALL, "%.4f", "min", 8, DBL(ns.min)},
    {"ns_max", "ns per ray and cylinder", K_REAL, ON_ALL, "%.4f", "max", 8, DBL(ns.max)},
    {"ns_q1", "ns per ray and cylinder", K_REAL, ON_ALL, "%.4f", NULL, 0, DBL(ns.q1)},
    {"ns_q3", "ns per ray and cylinder", K_REAL, ON_ALL, "%.4f", NULL, 0, DBL(ns.q3)},
    {"mrays_s", "M rays/s", K_REAL, ON_ALL, "%.2f", "M rays/s", 9, DBL(mrays)},
    {"tsc_ticks", "TSC ticks per ray", K_REAL, ON_ALL, "%.3f", "ticks", 8, DBL(ticks)},
    {"core_cycles", "core cycles per ray", K_REAL, ON_ALL, "%.2f", "cycles", 8,
     FN(core_cycles)},
    {"speedup_vs_scalar", "x", K_REAL, ON_ALL, "%.3f", "xscalar", 8, DBL(speedup)},
    {"hit_frac", "share of rays", K_REAL, ON_ALL, "%.4f", "hit", 6, DBL(hit_frac)},
    {"samples", "samples", K_COUNT, ON_ALL, NULL, NULL, 0, INT(samples)},
    {"clean_samples", "samples", K_COUNT, ON_ALL, NULL, NULL, 0, INT(clean)},
    {"err_compared", "rays", K_COUNT, ON_ERR, NULL, NULL, 0, SIZE(n_cmp)},
    {"ref_hits", "rays", K_COUNT, ON_ERR, NULL, NULL, 0, SIZE(n_hits_ref)},
    {"ulp_med", "ulps", K_ULPS, ON_ERR, "%.4g", "med", 6, DBL(ulp_med)},
    {"ulp_p99", "ulps", K_ULPS, ON_ERR, "%.4g", "p99", 6, DBL(ulp_p99)},
    {"ulp_max", "ulps", K_ULPS, ON_ERR, "%.4g", "max ulp", 7, DBL(ulp_max)},
    {"beyond_band_p99", "ulps", K_ULPS, ON_ERR, "%.4g", NULL, 0, DBL(xs_p99)},
    {"beyond_band_max", "ulps", K_ULPS, ON_ERR, "%.4g", NULL, 0, DBL(xs_max)},
    {"extra_hits", "rays", K_COUNT, ON_ERR, NULL, "extra", 5, SIZE(extra_hits)},
    {"lost_hits", "rays", K_COUNT, ON_ERR, NULL, "lost", 5, SIZE(lost_hits)},
    {"part_diff", "rays", K_COUNT, ON_ERR, NULL, "part", 5, SIZE(part_diff)},
    {"unexcused", "rays", K_COUNT, ON_ERR, NULL, "unexc", 5, SIZE(unexcused)},
    {"gbytes_s", "GB/s", K_REAL, ON_BIG, "%.3f", NULL, 0, DBL(gbytes_s)},
    {"memcpy_gbytes_s", "GB/s", K_REAL, ON_BIG, "%.3f", NULL, 0, DBL(memcpy_gbytes_s)},
};
#define NCOLUMNS (sizeof columns / sizeof columns[0])

#undef STR
#undef INT
#undef SIZE
#undef DBL
#undef FN

static int col_present(const column *c, const result *r)
{
    return c->when == ON_ALL || (c->when == ON_ERR && r->have_err) ||
           (c->when == ON_BIG && r->gbytes_s > 0);
}

static const char *col_text(const column *c, const result *r)
{
    if (c->type == T_WIDTH)
        return bench_width_name[r->width_id];
    return (const char *)r + c->off;
}

static double col_num(const column *c, const result *r, const machine_info *m)
{
    const char *p = (const char *)r + c->off;
    int i;
    size_t z;
    double d;
    switch (c->type) {
    case T_INT:
        memcpy(&i, p, sizeof i);
        return i;
    case T_SIZE:
        memcpy(&z, p, sizeof z);
        return (double)z;
    case T_DBL:
        memcpy(&d, p, sizeof d);
        return d;
    case T_FN:
        return c->fn(r, m);
    default:
        return 0;
    }
}

/* The value as CSV shows it (and table.txt, except for ulps and marks). */
static const char *col_format(const column *c, const result *r, const machine_info *m,
                              char *buf, size_t n)
{
    double x = c->kind == K_TEXT ? 0 : col_num(c, r, m);
    switch (c->kind) {
    case K_TEXT:
        snprintf(buf, n, "%s", col_text(c, r));
        break;
    case K_COUNT:
    case K_MARK:
        snprintf(buf, n, "%.0f", x);
        break;
    default:
        snprintf(buf, n, c->fmt, x);
    }
    return buf;
}

static FILE *open_out(const options *opt, const char *name, char *path, size_t n)
{
    snprintf(path, n, "%s/%s", opt->out_dir, name);
    FILE *f = fopen(path, "w");
    if (!f)
        fprintf(stderr, "cylbench: cannot write %s\n", path);
    return f;
}

static void write_csv(const result_list *l, const machine_info *m, const options *opt)
{
    char path[1024], ml[512], cell[64];
    FILE *f = open_out(opt, "results.csv", path, sizeof path);
    if (!f)
        return;
    machine_line(m, ml, sizeof ml);
    fprintf(f, "# cylbench %s; %s; %s%s\n# units:", m->date, ml, m->pinned,
            opt->flush_subnormals ? "; subnormals flushed to zero (--flush-subnormals)" : "");
    for (size_t c = 0; c < NCOLUMNS; c++)
        if (*columns[c].unit)
            fprintf(f, " %s: %s;", columns[c].name, columns[c].unit);
    fprintf(f, "\n");
    for (size_t c = 0; c < NCOLUMNS; c++)
        fprintf(f, "%s%s", columns[c].name, c + 1 < NCOLUMNS ? "," : "\n");
    for (size_t i = 0; i < l->n; i++)
        for (size_t c = 0; c < NCOLUMNS; c++) {
            const column *col = &columns[c];
            if (col_present(col, &l->r[i]))
                fputs(col_format(col, &l->r[i], m, cell, sizeof cell), f);
            fputs(c + 1 < NCOLUMNS ? "," : "\n", f);
        }
    fclose(f);
}

static void json_str(FILE *f, const char *s)
{
    fputc('"', f);
    for (; *s; s++) {
        if (*s == '"' || *s == '\\')
            fputc('\\', f);
        if ((unsigned char)*s >= 0x20)
            fputc(*s, f);
    }
    fputc('"', f);
}

static void json_num(FILE *f, double x)
{
    if (isfinite(x))
        fprintf(f, "%.6g", x);
    else
        fprintf(f, "null");
}

static void write_json(const result_list *l, const machine_info *m, const options *opt,
                       const scene_report *sc, double wall)
{
    char path[1024];
    FILE *f = open_out(opt, "results.json", path, sizeof path);
    if (!f)
        return;
    const struct {
        const char *key, *val;
    } mtext[] = {{"cpu", m->cpu},
                 {"cpuid", m->cpuid},
                 {"compiler", m->compiler},
                 {"buildtype", m->buildtype},
                 {"os", m->os},
                 {"paths", m->isas},
                 {"pinning", m->pinned},
                 {"date", m->date}};
    fprintf(f, "{\n  \"machine\": {\"cores\": %d, \"virtual\": %s, \"tsc_ghz\": ", m->cores,
            m->hypervisor ? "true" : "false");
    json_num(f, m->tsc_ghz);
    fprintf(f, ", \"core_ghz\": ");
    json_num(f, m->core_ghz);
    fprintf(f, ", \"load_start\": ");
    json_num(f, m->load_start);
    fprintf(f, ", \"load_end\": ");
    json_num(f, m->load_end);
    for (size_t k = 0; k < sizeof mtext / sizeof mtext[0]; k++) {
        fprintf(f, ", \"%s\": ", mtext[k].key);
        json_str(f, mtext[k].val);
    }
    fprintf(f,
            "},\n  \"settings\": {\"quick\": %s, \"reps\": %d, \"sample_ms\": %.3f, "
            "\"batch_rays\": %d, \"big_stream_rays\": %zu, \"exact_reference\": %s, "
            "\"flush_subnormals\": %s, \"wall_s\": %.1f},\n",
            opt->quick ? "true" : "false", opt->reps, opt->sample_ns * 1e-6, BENCH_BATCH,
            opt->big_rays, accuracy_available() ? "true" : "false",
            opt->flush_subnormals ? "true" : "false", wall);
    if (sc->have) {
        fprintf(f,
                "  \"scene\": {\"width\": %d, \"height\": %d, \"cylinders\": %d, "
                "\"primary_rays\": %zu, \"shadow_rays\": %zu, \"image\": ",
                sc->w, sc->h, sc->ncyl, sc->primary, sc->shadow);
        json_str(f, sc->image);
        fprintf(f, "},\n");
    }
    fprintf(f, "  \"units\": {");
    const char *sep = "";
    for (size_t c = 0; c < NCOLUMNS; c++)
        if (*columns[c].unit) {
            fprintf(f, "%s\"%s\": ", sep, columns[c].name);
            json_str(f, columns[c].unit);
            sep = ", ";
        }
    fprintf(f, "},\n  \"results\": [\n");
    for (size_t i = 0; i < l->n; i++) {
        const result *r = &l->r[i];
        fprintf(f, "    {");
        sep = "";
        for (size_t c = 0; c < NCOLUMNS; c++) {
            const column *col = &columns[c];
            if (!col_present(col, r))
                continue; /* absent, not null: null is a figure that is not finite */
            fprintf(f, "%s\"%s\": ", sep, col->name);
            sep = ", ";
            if (col->kind == K_TEXT)
                json_str(f, col_text(col, r));
            else if (col->kind == K_MARK)
                fputs(col_num(col, r, m) != 0 ? "true" : "false", f);
            else if (col->kind == K_COUNT)
                fprintf(f, "%.0f", col_num(col, r, m));
            else
                json_num(f, col_num(col, r, m));
        }
        fprintf(f, "}%s\n", i + 1 < l->n ? "," : "");
    }
    fprintf(f, "  ]\n}\n");
    fclose(f);
}

/* Every configuration on its own line, the columns that have a heading: the long form
 * of the stdout tables. */
static void write_long(const result_list *l, const machine_info *m, const options *opt)
{
    char path[1024], ml[512], cell[64];
    FILE *f = open_out(opt, "table.txt", path, sizeof path);
    if (!f)
        return;
    machine_line(m, ml, sizeof ml);
    fprintf(f, "cylbench %s\n%s; %s%s\n\n", m->date, ml, m->pinned,
            opt->flush_subnormals ? "; subnormals flushed to zero (--flush-subnormals)" : "");
    fprintf(f,
            "ticks: TSC ticks per ray (%.3f GHz); cycles: ns x the measured core clock "
            "(%.2f GHz); ~: CPU-timed (busy machine); -: not measured\n\n",
            m->tsc_ghz, m->core_ghz);
    const char *sep = "";
    for (size_t c = 0; c < NCOLUMNS; c++)
        if (columns[c].head) {
            fprintf(f, "%s%*s", sep, columns[c].width, columns[c].head);
            sep = " ";
        }
    fprintf(f, "\n");
    for (size_t i = 0; i < l->n; i++) {
        const result *r = &l->r[i];
        sep = "";
        for (size_t c = 0; c < NCOLUMNS; c++) {
            const column *col = &columns[c];
            if (!col->head)
                continue;
            const char *s = "-";
            if (col->kind == K_MARK)
                s = col_num(col, r, m) != 0 ? col->fmt : "";
            else if (col->kind == K_ULPS && col_present(col, r))
                s = fmt_ulps(col_num(col, r, m), cell, sizeof cell);
            else if (col_present(col, r))
                s = col_format(col, r, m, cell, sizeof cell);
            fprintf(f, "%s%*s", sep, col->width, s);
            sep = " ";
        }
        fprintf(f, "\n");
    }
    fclose(f);
}

void report_files(const result_list *l, const machine_info *m, const options *opt,
                  const scene_report *sc, double wall)
{
    write_csv(l, m, opt);
    write_json(l, m, opt, sc, wall);
    write_long(l, m, opt);
}
