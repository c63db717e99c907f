/* SPDX-License-Identifier: MIT */
/* fmt.c - formatting and lookup helpers shared by the text, CSV, JSON and SVG
 * writers. */
#include "report.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

const char *fmt_ulps(double u, char *buf, size_t n)
{
    if (!isfinite(u))
        snprintf(buf, n, "inf");
    else if (u < 10)
        snprintf(buf, n, "%.1f", u);
    else if (u < 1e3)
        snprintf(buf, n, "%.0f", u);
    else if (u < 1e5)
        snprintf(buf, n, "%.1fk", u / 1e3);
    else
        snprintf(buf, n, "%.0e", u);
    return buf;
}

const result *find_result(const result_list *l, const char *scenario, int isa, int width_id,
                          int op)
{
    for (size_t i = 0; i < l->n; i++) {
        const result *r = &l->r[i];
        if (r->isa_id == isa && r->op_id == op && !strcmp(r->scenario, scenario) &&
            (width_id < 0 || r->width_id == width_id))
            return r;
    }
    return NULL;
}

void machine_line(const machine_info *m, char *buf, size_t n)
{
    snprintf(buf, n, "%s (%s), %d cores%s, core ~%.2f GHz, TSC %.3f GHz; %s, %s; load %.1f",
             m->cpu, m->cpuid, m->cores, m->hypervisor ? " (virtual machine)" : "", m->core_ghz,
             m->tsc_ghz, m->compiler, m->buildtype, m->load_start);
}

/* The auto-vectorized builds of the textbook have a table of their own (print_peer);
 * the others show the scalar textbook only, beside the paths. */
int is_auto(int isa)
{
    return bench_is_textbook(isa) && isa != BENCH_ISA_TEXTBOOK;
}

/* The ISAs (and the scalar textbook) that have rows among the results of one group. */
int isas_in(const result_list *l, const char *group, int cols[NCOLS])
{
    int n = 0;
    for (int isa = 0; isa <= BENCH_ISA_TEXTBOOK; isa++)
        for (size_t i = 0; i < l->n; i++)
            if (l->r[i].isa_id == isa && (!group || !strcmp(l->r[i].group, group))) {
                cols[n++] = isa;
                break;
            }
    return n;
}

const char *err_cell(const result *r, char *buf, size_t n)
{
    char u[16];
    if (!r || !r->have_err)
        snprintf(buf, n, "-");
    else if (r->op_id == OP_OCC)
        snprintf(buf, n, "occ");
    else
        snprintf(buf, n, "%su", fmt_ulps(r->ulp_p99, u, sizeof u));
    return buf;
}

double ratio(const result *a, const result *b)
{
    return a && b && b->ns.med > 0 ? a->ns.med / b->ns.med : 0;
}

/* A row by its path's name (the loops have no ISA id); width_id < 0: any. */
const result *find_named(const result_list *l, const char *scenario, const char *isa,
                         int width_id, int op)
{
    for (size_t i = 0; i < l->n; i++) {
        const result *r = &l->r[i];
        if (r->op_id == op && !strcmp(r->isa, isa) && !strcmp(r->scenario, scenario) &&
            (width_id < 0 || r->width_id == width_id))
            return r;
    }
    return NULL;
}
