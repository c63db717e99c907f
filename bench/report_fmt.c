/* SPDX-License-Identifier: MIT */
/* report_fmt.c - formatting and lookup helpers shared by the text, CSV, JSON and SVG
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
