/* SPDX-License-Identifier: MIT */
/* errors.c - the tables of error on stdout: p99 ulps and disagreements per scenario and
 * path, and cylray against the textbook peer (time and error side by side). */
#include "report.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

/* ---- cylray against the textbook peer ------------------------------------------------- */

/* The textbook build of the same ISA: TB_* follows the order of cylray_isa. */
_Static_assert(TB_SCALAR == (int)CYLRAY_ISA_SCALAR && TB_SSE41 == (int)CYLRAY_ISA_SSE41 &&
                   TB_AVX2 == (int)CYLRAY_ISA_AVX2 && TB_AVX512 == (int)CYLRAY_ISA_AVX512 &&
                   TB_NEON == (int)CYLRAY_ISA_NEON,
               "the textbook builds pair with the cylray ISAs by index");

static const char *disagree_cell(const result *r, char *buf, size_t n)
{
    char u[16];
    if (!r || !r->have_err) {
        snprintf(buf, n, "-");
        return buf;
    }
    size_t d = r->extra_hits + r->lost_hits + r->part_diff;
    int k = snprintf(buf, n, "%s", fmt_ulps(r->ulp_p99, u, sizeof u));
    if (d && k > 0 && (size_t)k < n)
        k += snprintf(buf + k, n - (size_t)k, " d%zu", d);
    if (r->unexcused && k > 0 && (size_t)k < n)
        snprintf(buf + k, n - (size_t)k, "!%zu", r->unexcused);
    return buf;
}

/* The groups whose scenarios pit cylray against the peer in this table. */
static int peer_group(const char *group)
{
    return !strcmp(group, "main") || !strcmp(group, "spheres") || !strcmp(group, "cones");
}

void report_peer(FILE *f, const result_list *l)
{
    int any = 0;
    for (size_t i = 0; i < l->n && !any; i++)
        any = is_auto(l->r[i].isa_id) && peer_group(l->r[i].group);
    if (!any)
        return;
    fprintf(f,
            "\n== cylray against the textbook loop a user would write (naive.c, built per ISA "
            "and auto-vectorized): same rays,\n   same capped cylinder (sphere-*, cone-*: "
            "same sphere, cone), normals, calls of %d rays in L1 ==\n",
            BENCH_BATCH);
    fprintf(f, "   M rays/s; x peer: the peer's time over cylray's (>= 1: accuracy for free); "
               "error: p99 ulps, dN hit/miss or part\n   disagreements with the exact "
               "answer, !M of them unexcused by the tolerance band\n");
    fprintf(f, "%-17s %-7s %9s %9s %-6s %-12s %9s %7s %7s | %-15s %-15s\n", "scenario", "isa",
            "stream", "packet", "width", "peer", "peer", "x peer", "x peer", "cylray error",
            "peer error");
    fprintf(f, "%-17s %-7s %9s %9s %-6s %-12s %9s %7s %7s |\n", "", "", "", "(best)", "", "",
            "", "stream", "packet");
    for (size_t i = 0; i < l->n; i++) {
        const result *pr = &l->r[i];
        if (!bench_is_textbook(pr->isa_id) || !peer_group(pr->group))
            continue;
        int isa = pr->isa_id - BENCH_ISA_TEXTBOOK;
        const result *st = find_result(l, pr->scenario, isa, BW_STREAM, OP_NORMAL);
        const result *pk = NULL;
        for (int w = BW_4; w < BW_STREAM; w++) {
            const result *q = find_result(l, pr->scenario, isa, w, OP_NORMAL);
            if (q && (!pk || q->ns.med < pk->ns.med))
                pk = q;
        }
        char e1[32], e2[32];
        fprintf(f, "%-17s %-7s ", pr->scenario, bench_isa_name(isa));
        if (st)
            fprintf(f, "%9.1f ", st->mrays);
        else
            fprintf(f, "%9s ", "-");
        if (pk)
            fprintf(f, "%9.1f %-6s ", pk->mrays, bench_width_name[pk->width_id]);
        else
            fprintf(f, "%9s %-6s ", "-", "");
        fprintf(f, "%-12s %8.1f%c %6.2fx %6.2fx | %-15s %-15s\n", pr->isa, pr->mrays,
                pr->cpu_timed ? '~' : ' ', st ? pr->ns.med / st->ns.med : 0,
                pk ? pr->ns.med / pk->ns.med : 0, disagree_cell(st, e1, sizeof e1),
                disagree_cell(pr, e2, sizeof e2));
    }
}

/* ---- error table --------------------------------------------------------------------- */

/* Do the error figures of (scenario, op, isa) differ between widths? */
static int err_varies(const result_list *l, const result *r)
{
    for (size_t i = 0; i < l->n; i++) {
        const result *q = &l->r[i];
        if (q == r || q->isa_id != r->isa_id || q->op_id != r->op_id ||
            strcmp(q->scenario, r->scenario) || !q->have_err)
            continue;
        if (q->ulp_p99 != r->ulp_p99 || q->ulp_max != r->ulp_max ||
            q->extra_hits != r->extra_hits || q->lost_hits != r->lost_hits)
            return 1;
    }
    return 0;
}

void report_errors(FILE *f, const result_list *l)
{
    int cols[NCOLS], nc = isas_in(l, NULL, cols);
    int have = 0;
    for (size_t i = 0; i < l->n; i++)
        have |= l->r[i].have_err;
    if (!have) {
        fprintf(f, "\n(no exact reference in this build: no error figures)\n");
        return;
    }
    fprintf(f, "\n== t error against the exact reference, on the timed rays (widest width "
               "measured) ==\n"
               "   cell: p99/max of |t - t_exact| in ulps at t_exact; dN: N hit/miss or part "
               "disagreements, !M of them outside the\n   reference's tolerance band "
               "(unexcused); *: differs between widths. med: worst median; >band: worst "
               "p99/max of\n   the error beyond the band (what input rounding cannot "
               "explain). textbook: the textbook formulas in plain float (naive.c)\n");
    fprintf(f, "%-19s %-8s", "scenario", "flags");
    for (int c = 0; c < nc; c++)
        fprintf(f, "| %-20s", bench_isa_name(cols[c]));
    fprintf(f, "| %5s %s\n", "med", ">band");
    for (size_t i = 0; i < l->n; i++) {
        const result *r = &l->r[i];
        if (!r->have_err || r->op_id == OP_OCC || is_auto(r->isa_id))
            continue;
        /* one row per (scenario, flags), opened by its first result */
        int seen = 0;
        for (size_t j = 0; j < l->n && !seen; j++)
            seen = j != i && l->r[j].have_err && !is_auto(l->r[j].isa_id) &&
                   !strcmp(l->r[j].scenario, r->scenario) && l->r[j].op_id == r->op_id &&
                   (j < i ? 1
                          : r->isa_id == BENCH_ISA_TEXTBOOK &&
                                l->r[j].isa_id != BENCH_ISA_TEXTBOOK);
        if (seen)
            continue;
        fprintf(f, "%-19s %-8s", r->scenario, r->op);
        double med = 0, xp = 0, xm = 0;
        for (int c = 0; c < nc; c++) {
            /* the widest width of this ISA, scenario and flag set */
            const result *q = NULL;
            for (int w = BW_16; w >= BW_4 && !q; w--)
                q = find_result(l, r->scenario, cols[c], w, r->op_id);
            if (!q)
                q = find_result(l, r->scenario, cols[c], -1, r->op_id);
            if (!q || !q->have_err) {
                fprintf(f, "| %-20s", "");
                continue;
            }
            char a[16], b[16], cell[64];
            size_t d = q->extra_hits + q->lost_hits + q->part_diff;
            int k = snprintf(cell, sizeof cell, "%s/%s", fmt_ulps(q->ulp_p99, a, sizeof a),
                             fmt_ulps(q->ulp_max, b, sizeof b));
            if (d && k > 0 && (size_t)k < sizeof cell)
                k += snprintf(cell + k, sizeof cell - (size_t)k, " d%zu", d);
            if (q->unexcused && k > 0 && (size_t)k < sizeof cell)
                k += snprintf(cell + k, sizeof cell - (size_t)k, "!%zu", q->unexcused);
            if (err_varies(l, q) && k > 0 && (size_t)k < sizeof cell)
                snprintf(cell + k, sizeof cell - (size_t)k, "*");
            fprintf(f, "| %-20s", cell);
            if (cols[c] != BENCH_ISA_TEXTBOOK) {
                med = fmax(med, q->ulp_med);
                xp = fmax(xp, q->xs_p99);
                xm = fmax(xm, q->xs_max);
            }
        }
        char a[16], b[16], c[16];
        fprintf(f, "| %5s %s/%s\n", fmt_ulps(med, a, sizeof a), fmt_ulps(xp, b, sizeof b),
                fmt_ulps(xm, c, sizeof c));
    }
}
