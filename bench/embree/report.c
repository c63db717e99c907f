/* SPDX-License-Identifier: MIT */
/* report.c - the Embree comparison's tables: speed, scaling, error. */
#include "run.h"

#include <math.h>
#include <string.h>

const int eb_packets[EB_NPACKETS] = {1, 4, 8, 16};

const char *eb_set_name(int set)
{
    static const char *const n[EB_NSETS] = {"camera", "rim", "axis"};
    return set >= 0 && set < EB_NSETS ? n[set] : "?";
}

static const char *const phase_name[EB_NPHASES] = {"primary", "shadow", "bounce"};

/* A column is shown when some row measured it. */
static int col_on(const eb_row *r, size_t n, int p, int k)
{
    for (size_t i = 0; i < n; i++)
        if (!r[i].skipped && !isnan(r[i].mrays[p][k]))
            return 1;
    return 0;
}

/* What the table and the CSV print of one ray set's errors. */
typedef struct err_summary {
    double t_med, t_p99, t_max, beyond_max, n_p99;
} err_summary;

static err_summary summarize(eb_err *e)
{
    err_summary q;
    double med, max, p99;
    eb_quantiles(e->t_ulps, e->nt, &q.t_med, &q.t_p99, &q.t_max);
    eb_quantiles(e->t_beyond, e->nt, &med, &p99, &q.beyond_max);
    eb_quantiles(e->n_rad, e->nn, &med, &q.n_p99, &max);
    return q;
}

static void speed(FILE *f, const eb_row *r, size_t n)
{
    fprintf(f,
            "\nM rays/s (%d threads; median of %d runs, each the best of %d passes; packet "
            "= rays per Embree call; cylray-leaf: %d cylinders or spheres a leaf, grouped by "
            "Embree's SAH builder; embree-curve: Embree's curves, and its sphere points for "
            "spheres)\n",
            r[0].threads, r[0].runs, r[0].reps, r[EB_LEAF < n ? EB_LEAF : 0].leaf_m);
    fprintf(f, "%-7s %-14s %-16s %8s", "isa", "scene", "variant", "build s");
    for (int p = 0; p < EB_NPHASES; p++)
        for (int k = 0; k < EB_NPACKETS; k++) {
            if (!col_on(r, n, p, k))
                continue;
            char h[24];
            snprintf(h, sizeof h, "%s/%d", phase_name[p], eb_packets[k]);
            fprintf(f, " %10s", h);
        }
    fprintf(f, "\n");
    for (size_t i = 0; i < n; i++) {
        fprintf(f, "%-7s %-14s %-16s", r[i].isa, r[i].scene, r[i].variant);
        if (r[i].skipped) {
            fprintf(f, " skipped: %s\n", r[i].why);
            continue;
        }
        fprintf(f, " %8.2f", r[i].build_s);
        for (int p = 0; p < EB_NPHASES; p++)
            for (int k = 0; k < EB_NPACKETS; k++)
                if (col_on(r, n, p, k)) {
                    if (isnan(r[i].mrays[p][k]))
                        fprintf(f, " %10s", "-");
                    else
                        fprintf(f, " %10.2f", r[i].mrays[p][k]);
                }
        fprintf(f, "\n");
    }
}

/* The row of Embree's curves on row i's scene and ISA, NULL if none was run. */
static const eb_row *base_of(const eb_row *r, size_t n, size_t i)
{
    const eb_row *base = NULL;
    for (size_t j = 0; j < n; j++)
        if (!strcmp(r[j].variant, "embree-curve") && !strcmp(r[j].scene, r[i].scene) &&
            !strcmp(r[j].isa, r[i].isa) && !r[j].skipped)
            base = &r[j];
    return base;
}

/* Over the runs, each run's time of `row` over the time of `base` in that run (the
 * base's M rays/s over the row's). */
static eb_spread relative(const eb_row *base, const eb_row *row, int p, int k)
{
    double x[EB_MAXRUNS];
    for (int run = 0; run < row->runs; run++) {
        double a = base->mrays_run[p][k][run], b = row->mrays_run[p][k][run];
        x[run] = b > 0 ? a / b : NAN;
    }
    return eb_spread_of(x, row->runs);
}

/* Each cylray row's time relative to Embree's curves on the same scene and ISA: below 1
 * is faster. */
static void ratios(FILE *f, const eb_row *r, size_t n)
{
    int runs = r[0].runs;
    if (runs > 1)
        fprintf(f,
                "\nTime relative to embree-curve (same scene and ISA; < 1: faster): the median "
                "over %d runs of each run's ratio\n(the variant's time over the curves' time "
                "in that run), in brackets the lowest and highest ratio of the runs\n",
                runs);
    else
        fprintf(f, "\nTime relative to embree-curve (same scene, ISA and run; < 1: faster)\n");
    int w = runs > 1 ? 16 : 10;
    fprintf(f, "%-7s %-14s %-16s", "isa", "scene", "variant");
    for (int p = 0; p < EB_NPHASES; p++)
        for (int k = 0; k < EB_NPACKETS; k++)
            if (col_on(r, n, p, k)) {
                char h[24];
                snprintf(h, sizeof h, "%s/%d", phase_name[p], eb_packets[k]);
                fprintf(f, " %*s", w, h);
            }
    fprintf(f, "\n");
    for (size_t i = 0; i < n; i++) {
        const eb_row *base = base_of(r, n, i);
        if (!base || base == &r[i] || r[i].skipped)
            continue;
        fprintf(f, "%-7s %-14s %-16s", r[i].isa, r[i].scene, r[i].variant);
        for (int p = 0; p < EB_NPHASES; p++)
            for (int k = 0; k < EB_NPACKETS; k++)
                if (col_on(r, n, p, k)) {
                    eb_spread q = relative(base, &r[i], p, k);
                    char c[48] = "-";
                    if (!isnan(q.med) && runs > 1)
                        snprintf(c, sizeof c, "%.2f (%.2f-%.2f)", q.med, q.lo, q.hi);
                    else if (!isnan(q.med))
                        snprintf(c, sizeof c, "%.2f", q.med);
                    fprintf(f, " %*s", w, c);
                }
        fprintf(f, "\n");
    }
}

static void scaling(FILE *f, const eb_row *r, size_t n)
{
    int T = r[0].threads;
    fprintf(f,
            "\nScaling: primary rays, one ray a call, M rays/s at 1..%d threads, median of %d "
            "runs (in\nbrackets the cores the process got: CPU time over wall time)\n",
            T, r[0].runs);
    fprintf(f, "%-7s %-14s %-16s", "isa", "scene", "variant");
    for (int t = 1; t <= T; t++)
        fprintf(f, "   T=%-9d", t);
    fprintf(f, " speedup\n");
    for (size_t i = 0; i < n; i++) {
        if (r[i].skipped)
            continue;
        fprintf(f, "%-7s %-14s %-16s", r[i].isa, r[i].scene, r[i].variant);
        for (int t = 1; t <= T; t++)
            fprintf(f, " %6.2f (%.1f)", r[i].scaling[t], r[i].cores[t]);
        fprintf(f, " %7.2fx\n", r[i].scaling[T] / r[i].scaling[1]);
    }
}

static void errors(FILE *f, const eb_row *r, size_t n)
{
    fprintf(f, "\nError against the exact reference (binary128) on sampled rays:\n"
               "wrong = unexcused wrong hit/miss or wrong object (leak: went past the true\n"
               "first surface; phantom: a hit where there is none); excused = inside the\n"
               "tolerance band; t in float ulps (beyond: outside the band), normal in\n"
               "radians (up to sign); self =\n"
               "secondary rays from a front face that hit their own cylinder or sphere\n");
    fprintf(f, "%-7s %-14s %-16s %-6s %6s %5s %5s %5s %5s %8s %8s %8s %8s %8s %11s\n", "isa",
            "scene", "variant", "set", "rays", "wrong", "leak", "phant", "exc", "t med",
            "t p99", "t max", "beyond", "n p99", "self/sec");
    for (size_t i = 0; i < n; i++) {
        if (r[i].skipped)
            continue;
        for (int s = 0; s < EB_NSETS; s++) {
            eb_err e = r[i].err[s];
            const err_summary q = summarize(&e);
            fprintf(f,
                    "%-7s %-14s %-16s %-6s %6zu %5zu %5zu %5zu %5zu %8.3g %8.3g %8.3g %8.3g "
                    "%8.2g",
                    r[i].isa, r[i].scene, r[i].variant, eb_set_name(s), e.rays, e.wrong, e.leak,
                    e.phantom, e.excused, q.t_med, q.t_p99, q.t_max, q.beyond_max, q.n_p99);
            if (s == EB_SET_CAMERA)
                fprintf(f, " %5zu/%-5zu", e.self, e.sec);
            fprintf(f, "\n");
        }
    }
}

void eb_report(FILE *f, const eb_row *rows, size_t n, const char *machine)
{
    if (!n)
        return;
    fprintf(f, "Machine: %s\n", machine);
    speed(f, rows, n);
    scaling(f, rows, n);
    errors(f, rows, n);
    ratios(f, rows, n);
}

/* A cell's median, min and max over the runs, or three nan. */
static void csv_spread(FILE *f, eb_spread q)
{
    fprintf(f, ",%.4g,%.4g,%.4g", q.med, q.lo, q.hi);
}

void eb_report_csv(FILE *f, const eb_row *r, size_t n)
{
    fprintf(f, "isa,scene,variant,leaf_m,threads,runs,reps,cylinders,spheres,build_s");
    for (int p = 0; p < EB_NPHASES; p++)
        for (int k = 0; k < EB_NPACKETS; k++)
            fprintf(f, ",%s_%d_mrays,%s_%d_mrays_min,%s_%d_mrays_max", phase_name[p],
                    eb_packets[k], phase_name[p], eb_packets[k], phase_name[p], eb_packets[k]);
    fprintf(f, ",primary_1thread_mrays");
    for (int s = 0; s < EB_NSETS; s++)
        fprintf(f,
                ",%s_rays,%s_wrong,%s_leak,%s_phantom,%s_excused,%s_t_p99_ulps,"
                "%s_t_beyond_max_ulps,%s_n_p99_rad",
                eb_set_name(s), eb_set_name(s), eb_set_name(s), eb_set_name(s), eb_set_name(s),
                eb_set_name(s), eb_set_name(s), eb_set_name(s));
    fprintf(f, ",secondary,self_intersections,diff_pixels");
    for (int p = 0; p < EB_NPHASES; p++)
        for (int k = 0; k < EB_NPACKETS; k++)
            fprintf(f, ",%s_%d_rel,%s_%d_rel_min,%s_%d_rel_max", phase_name[p], eb_packets[k],
                    phase_name[p], eb_packets[k], phase_name[p], eb_packets[k]);
    fprintf(f, "\n");
    for (size_t i = 0; i < n; i++) {
        if (r[i].skipped)
            continue;
        fprintf(f, "%s,%s,%s,%d,%d,%d,%d,%zu,%zu,%.4f", r[i].isa, r[i].scene, r[i].variant,
                r[i].leaf_m, r[i].threads, r[i].runs, r[i].reps, r[i].ns, r[i].nsph,
                r[i].build_s);
        for (int p = 0; p < EB_NPHASES; p++)
            for (int k = 0; k < EB_NPACKETS; k++)
                csv_spread(f, eb_spread_of(r[i].mrays_run[p][k], r[i].runs));
        fprintf(f, ",%.4g", r[i].scaling[1]);
        for (int s = 0; s < EB_NSETS; s++) {
            eb_err e = r[i].err[s];
            const err_summary q = summarize(&e);
            fprintf(f, ",%zu,%zu,%zu,%zu,%zu,%.4g,%.4g,%.4g", e.rays, e.wrong, e.leak,
                    e.phantom, e.excused, q.t_p99, q.beyond_max, q.n_p99);
        }
        fprintf(f, ",%zu,%zu,%zu", r[i].err[0].sec, r[i].err[0].self, r[i].diff_pixels);
        const eb_row *base = base_of(r, n, i);
        for (int p = 0; p < EB_NPHASES; p++)
            for (int k = 0; k < EB_NPACKETS; k++)
                csv_spread(f, base ? relative(base, &r[i], p, k) : (eb_spread){NAN, NAN, NAN});
        fprintf(f, "\n");
    }
}
