/* SPDX-License-Identifier: MIT */
/* tables.c - what a person reads on stdout, in its order: time per ISA, the rates, the
 * skips, the inactive lanes, the leaves, the big stream, the scene; the peer and the
 * errors are errors.c's. */
#include "report.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

/* ---- the per-group time table ------------------------------------------------- */

static void print_group(FILE *f, const result_list *l, const char *group, const char *title)
{
    int cols[NCOLS], nc = isas_in(l, group, cols);
    if (!nc)
        return;
    fprintf(f, "\n== %s ==\n", title);
    fprintf(f, "   cell: ns per ray (median; ~: timed by CPU time, the machine was busy) | "
               "speedup over scalar | p99 t error, ulps\n");
    fprintf(f, "%-19s %-8s %-6s", "scenario", "flags", "width");
    for (int c = 0; c < nc; c++)
        fprintf(f, "| %-19s", bench_isa_name(cols[c]));
    fprintf(f, "| hit%%  dis\n");
    const char *last = "";
    for (size_t i = 0; i < l->n; i++) {
        const result *r = &l->r[i];
        if (strcmp(r->group, group) || is_auto(r->isa_id))
            continue;
        /* The textbook shares the rows of the paths; it opens one only when it ran
         * alone (--isa=textbook). */
        if (r->isa_id == BENCH_ISA_TEXTBOOK) {
            int alone = 1;
            for (size_t j = 0; j < l->n && alone; j++)
                alone = l->r[j].isa_id == BENCH_ISA_TEXTBOOK ||
                        strcmp(l->r[j].scenario, r->scenario) || l->r[j].op_id != r->op_id;
            if (!alone)
                continue;
        }
        /* one row per (scenario, flags, width): its first result opens it */
        int seen = 0;
        for (size_t j = 0; j < i && !seen; j++) {
            const result *q = &l->r[j];
            seen = q->isa_id != BENCH_ISA_TEXTBOOK && !strcmp(q->scenario, r->scenario) &&
                   q->op_id == r->op_id && q->width_id == r->width_id;
        }
        if (seen)
            continue;
        if (strcmp(last, r->scenario) && *last)
            fprintf(f, "\n");
        last = r->scenario;
        fprintf(f, "%-19s %-8s %-6s", r->scenario, r->op, bench_width_name[r->width_id]);
        size_t dis = 0, unexc = 0;
        double hit = -1;
        for (int c = 0; c < nc; c++) {
            const result *q =
                find_result(l, r->scenario, cols[c],
                            cols[c] == BENCH_ISA_TEXTBOOK ? -1 : r->width_id, r->op_id);
            /* the textbook has one row per flag set: show it on the first width's row */
            if (q && cols[c] == BENCH_ISA_TEXTBOOK && r->isa_id != BENCH_ISA_TEXTBOOK) {
                const result *first = NULL;
                for (size_t j = 0; j < l->n && !first; j++)
                    if (!strcmp(l->r[j].scenario, r->scenario) && l->r[j].op_id == r->op_id &&
                        l->r[j].isa_id != BENCH_ISA_TEXTBOOK)
                        first = &l->r[j];
                if (first != r)
                    q = NULL;
            }
            if (!q) {
                fprintf(f, "| %-19s", "");
                continue;
            }
            char e[16];
            char sp[16];
            snprintf(sp, sizeof sp, q->speedup > 0 ? "%5.1fx" : "     -", q->speedup);
            fprintf(f, "| %7.2f%c%s %5s", q->ns.med, q->cpu_timed ? '~' : ' ', sp,
                    err_cell(q, e, sizeof e));
            if (cols[c] != BENCH_ISA_TEXTBOOK || r->isa_id == BENCH_ISA_TEXTBOOK) {
                dis += q->extra_hits + q->lost_hits;
                unexc += q->unexcused;
                if (hit < 0)
                    hit = q->hit_frac;
            }
        }
        fprintf(f, "| %4.1f %3zu", 100 * (hit < 0 ? 0 : hit), dis);
        if (unexc)
            fprintf(f, " (%zu unexcused)", unexc);
        fprintf(f, "\n");
    }
}

/* ---- M rays/s per ISA and width ------------------------------------------------------ */

static void print_rates(FILE *f, const result_list *l)
{
    if (!find_result(l, "incoherent", CYLRAY_ISA_SCALAR, -1, OP_NORMAL) &&
        !find_result(l, "incoherent", CYLRAY_ISA_AVX2, -1, OP_NORMAL))
        return;
    fprintf(f, "\n== M rays/s: ordinary (incoherent) rays, capped cylinder, normals, batches "
               "in L1, one core ==\n");
    fprintf(f, "%-9s", "isa");
    for (int w = 0; w < BW_COUNT; w++)
        fprintf(f, " %9s", bench_width_name[w]);
    fprintf(f, "   | speedup over scalar:");
    for (int w = 0; w < BW_COUNT; w++)
        fprintf(f, " %6s", bench_width_name[w]);
    fprintf(f, "\n");
    for (int isa = 0; isa < CYLRAY_ISA_COUNT; isa++) {
        if (!find_result(l, "incoherent", isa, -1, OP_NORMAL))
            continue;
        fprintf(f, "%-9s", bench_isa_name(isa));
        for (int w = 0; w < BW_COUNT; w++) {
            const result *r = find_result(l, "incoherent", isa, w, OP_NORMAL);
            if (r)
                fprintf(f, " %9.1f", r->mrays);
            else
                fprintf(f, " %9s", "-");
        }
        fprintf(f, "   | %20s", "");
        for (int w = 0; w < BW_COUNT; w++) {
            const result *r = find_result(l, "incoherent", isa, w, OP_NORMAL);
            if (r)
                fprintf(f, " %5.1fx", r->speedup);
            else
                fprintf(f, " %6s", "-");
        }
        fprintf(f, "\n");
    }
}

/* ---- what each skip saves ------------------------------------------------------------ */

static void print_skips(FILE *f, const result_list *l)
{
    if (!find_result(l, "general", CYLRAY_ISA_SCALAR, -1, OP_NORMAL) &&
        !find_result(l, "general", CYLRAY_ISA_AVX2, -1, OP_NORMAL))
        return;
    fprintf(f, "\n== what each skip saves: time of the full case / time of the reduced one "
               "(>1: the skip pays) ==\n");
    fprintf(f, "   normal/t, normal/occ: incoherent rays; general/aligned, capped/open, "
               "capped/infinite: the same rays;\n   all-hit/all-miss: packets of 100%% "
               "hits vs 100%% misses (ns/ray of each in brackets)\n");
    fprintf(f, "%-8s %-6s %8s %9s %9s %14s %10s %13s %22s\n", "isa", "width", "normal",
            "normal/t", "norm/occ", "general/align", "capd/open", "capd/infinite",
            "all-hit/all-miss");
    for (int isa = 0; isa < CYLRAY_ISA_COUNT; isa++)
        for (int w = 0; w < BW_COUNT; w++) {
            const result *gen = find_result(l, "general", isa, w, OP_NORMAL);
            const result *inc = find_result(l, "incoherent", isa, w, OP_NORMAL);
            if (!gen && !inc)
                continue;
            const result *ah = find_result(l, "all-hit", isa, w, OP_NORMAL);
            const result *am = find_result(l, "all-miss", isa, w, OP_NORMAL);
            fprintf(f,
                    "%-8s %-6s %8.2f %8.2fx %8.2fx %13.2fx %9.2fx %12.2fx %6.2fx (%.2f/%.2f)\n",
                    bench_isa_name(isa), bench_width_name[w], inc ? inc->ns.med : 0,
                    ratio(inc, find_result(l, "incoherent", isa, w, OP_T)),
                    ratio(inc, find_result(l, "incoherent", isa, w, OP_OCC)),
                    ratio(gen, find_result(l, "aligned", isa, w, OP_NORMAL)),
                    ratio(gen, find_result(l, "open", isa, w, OP_NORMAL)),
                    ratio(gen, find_result(l, "infinite", isa, w, OP_NORMAL)), ratio(ah, am),
                    ah ? ah->ns.med : 0, am ? am->ns.med : 0);
        }
}

/* ---- inactive lanes: zeros against subnormals ------------------------------------------ */

static void print_lanes(FILE *f, const result_list *l)
{
    int any = 0;
    for (size_t i = 0; i < l->n && !any; i++)
        any = !strcmp(l->r[i].scenario, "half-subnormal");
    if (!any)
        return;
    fprintf(
        f, "\n== inactive lanes: packets with every other lane inactive, those lanes all zeros "
           "or all subnormals (1e-40) ==\n");
    fprintf(f, "   ns per packet call (median; the active lanes hold the same incoherent rays "
               "in both); subnormal/zero: > 1 means the\n   garbage in lanes whose results are "
               "thrown away costs time\n");
    fprintf(f, "%-8s %-6s %12s %16s %15s\n", "isa", "width", "zeros ns", "subnormals ns",
            "subnormal/zero");
    for (int isa = 0; isa < CYLRAY_ISA_COUNT; isa++)
        for (int w = BW_4; w < BW_STREAM; w++) {
            const result *z = find_result(l, "half-zero", isa, w, OP_NORMAL);
            const result *s = find_result(l, "half-subnormal", isa, w, OP_NORMAL);
            if (!z || !s)
                continue;
            double lanes = bench_width_lanes[w];
            fprintf(f, "%-8s %-6s %11.2f%c %15.2f%c %14.2fx\n", bench_isa_name(isa),
                    bench_width_name[w], z->ns.med * lanes, z->cpu_timed ? '~' : ' ',
                    s->ns.med * lanes, s->cpu_timed ? '~' : ' ', ratio(s, z));
        }
}

/* ---- leaves against loops ------------------------------------------------------------- */

static void print_leaf_row(FILE *f, const result_list *l, const char *scen, const char *isa,
                           int wid, const char *m, const char *loop, const char *lane,
                           const char *tbloop)
{
    const int ops[3] = {OP_T, OP_NORMAL, OP_OCC};
    const result *r[3];
    for (int o = 0; o < 3; o++)
        r[o] = find_named(l, scen, isa, wid, ops[o]);
    if (!r[0] && !r[1] && !r[2])
        return;
    /* the shape leaves' tables (with a textbook loop) have a wider first column */
    fprintf(f, "%-*s %-14s %-3s", tbloop ? 11 : 8, scen, isa, m);
    for (int o = 0; o < 3; o++) {
        if (r[o])
            fprintf(f, " %9.1f%c", r[o]->mrays, r[o]->cpu_timed ? '~' : ' ');
        else
            fprintf(f, " %10s", "-");
    }
    /* the same op class of the loops: the ratios of intersect with normals */
    double xl = ratio(find_named(l, scen, loop, -1, OP_NORMAL), r[1]);
    double x1 = ratio(find_named(l, scen, lane, -1, OP_NORMAL), r[1]);
    double oc = ratio(r[1], r[2]);
    fprintf(f, " | %7.2fx %8.2fx %10.2fx", xl, x1, oc);
    if (tbloop)
        fprintf(f, " %8.2fx", ratio(find_named(l, scen, tbloop, -1, OP_NORMAL), r[1]));
    fprintf(f, "\n");
}

static void print_leaf_cyl(FILE *f, const result_list *l, const leaf_report *lr,
                           const char *lane, const char *sizes, const char *diffs)
{
    const char *tag[2] = {"leaf-l1", "leaf-l2"};
    fprintf(f,
            "\n== leaf: one incoherent ray against %d cylinders (molecule bonds, pipes) in "
            "leaves of M; scenes of %s cylinders ==\n",
            lr->run, sizes);
    fprintf(f,
            "   M ray-cylinder tests/s (median) for t, normal, occluded. With normals: x loop "
            "= the scalar loop's time over this\n   one's (scalar-loop: the scalar path, a "
            "4-wide packet call with one active lane per cylinder), x 1-lane = the\n   "
            "same over one-lane intersect8 calls of %s; occ/normal = intersect with normals "
            "over occluded.\n   Leaf bytes per cylinder: %d (M = 4), %d (8), %d (16); "
            "answers that differ from the scalar loop's: %s\n",
            lr->best, lr->bytes_per_cyl[0], lr->bytes_per_cyl[1], lr->bytes_per_cyl[2], diffs);
    fprintf(f, "%-8s %-14s %-3s %10s %10s %10s | %8s %9s %11s\n", "data", "path", "M", "t",
            "normal", "occluded", "x loop", "x 1-lane", "occ/normal");
    for (int s = 0; s < 2; s++) {
        for (int isa = 0; isa < CYLRAY_ISA_COUNT; isa++)
            for (int w = BW_4; w < BW_STREAM; w++)
                print_leaf_row(f, l, tag[s], bench_isa_name(isa), w, bench_width_name[w],
                               "scalar-loop", lane, NULL);
        print_leaf_row(f, l, tag[s], "scalar-loop", -1, "1", "scalar-loop", lane, NULL);
        print_leaf_row(f, l, tag[s], lane, -1, "1", "scalar-loop", lane, NULL);
    }
}

/* sphere-leaf or cone-leaf: the table of leaf-l1 with the textbook loop beside it. */
static void print_shape_leaf(FILE *f, const result_list *l, const leaf_report *lr,
                             const char *lane, int sz, const char *tag, const char *shapes,
                             const char *scene)
{
    fprintf(f,
            "\n== %s: one incoherent ray against %d %s (%s) in leaves of M; %d %s, in L1 ==\n",
            tag, lr->run, shapes, scene, lr->ncyl[sz], shapes);
    fprintf(f,
            "   as for the cylinders; x tb-loop = the textbook %.*s formula in a plain "
            "scalar loop over the same %s\n   (textbook-loop), its time over this one's. "
            "Answers that differ from the scalar loop's: %zu\n",
            (int)strlen(shapes) - 1, shapes, shapes, lr->diff[sz]);
    fprintf(f, "%-11s %-14s %-3s %10s %10s %10s | %8s %9s %11s %9s\n", "data", "path", "M", "t",
            "normal", "occluded", "x loop", "x 1-lane", "occ/normal", "x tb-loop");
    for (int isa = 0; isa < CYLRAY_ISA_COUNT; isa++)
        for (int w = BW_4; w < BW_STREAM; w++)
            print_leaf_row(f, l, tag, bench_isa_name(isa), w, bench_width_name[w],
                           "scalar-loop", lane, "textbook-loop");
    print_leaf_row(f, l, tag, "scalar-loop", -1, "1", "scalar-loop", lane, "textbook-loop");
    print_leaf_row(f, l, tag, lane, -1, "1", "scalar-loop", lane, "textbook-loop");
    print_leaf_row(f, l, tag, "textbook-loop", -1, "1", "scalar-loop", lane, "textbook-loop");
}

static void print_leaf(FILE *f, const result_list *l, const leaf_report *lr)
{
    if (!lr->have)
        return;
    char lane[32];
    snprintf(lane, sizeof lane, "1-lane:%s", lr->best);
    /* the scene sizes run (a size not selected has no cylinders) */
    char sizes[96] = "", diffs[96] = "";
    const char *tag[2] = {"leaf-l1", "leaf-l2"};
    for (int s = 0, ks = 0, kd = 0; s < 2; s++) {
        if (!lr->ncyl[s])
            continue;
        ks += snprintf(sizes + ks, sizeof sizes - (size_t)ks, "%s%d (%s)", ks ? ", " : "",
                       lr->ncyl[s], tag[s]);
        kd += snprintf(diffs + kd, sizeof diffs - (size_t)kd, "%s%zu (%s)", kd ? ", " : "",
                       lr->diff[s], tag[s]);
    }
    if (lr->ncyl[0] || lr->ncyl[1])
        print_leaf_cyl(f, l, lr, lane, sizes, diffs);
    if (lr->sphere)
        print_shape_leaf(f, l, lr, lane, 2, "sphere-leaf", "spheres",
                         "atoms on a jittered lattice");
    if (lr->cone)
        print_shape_leaf(f, l, lr, lane, 3, "cone-leaf", "cones",
                         "leaf-l1's bonds and pipes tapered, a quarter of them tips");
}

/* ---- the big stream -------------------------------------------------------------- */

static void print_stream(FILE *f, const result_list *l)
{
    int any = 0;
    for (size_t i = 0; i < l->n; i++)
        any |= !strcmp(l->r[i].scenario, "big-stream");
    if (!any)
        return;
    size_t n = 0;
    for (size_t i = 0; i < l->n; i++)
        if (!strcmp(l->r[i].scenario, "big-stream"))
            n = l->r[i].rays_timed;
    fprintf(f,
            "\n== big stream: %zu rays (%.0f MB of ray input) through the stream API, one "
            "pass per sample ==\n",
            n, 32e-6 * (double)n);
    fprintf(f, "   GB/s: the 32 bytes of ray input per ray over the time; memcpy: a plain "
               "memcpy of the same bytes (GB/s copied,\n   and its time per ray); x memcpy: "
               "the kernel's time per ray over memcpy's (1 = as fast as copying the rays)\n");
    fprintf(f, "%-8s %-9s %8s %9s %7s %11s %13s %9s\n", "isa", "flags", "ns/ray", "M rays/s",
            "GB/s", "memcpy GB/s", "memcpy ns/ray", "x memcpy");
    for (size_t i = 0; i < l->n; i++) {
        const result *r = &l->r[i];
        if (strcmp(r->scenario, "big-stream"))
            continue;
        double mc = r->memcpy_gbytes_s > 0 ? 32.0 / r->memcpy_gbytes_s : 0;
        fprintf(f, "%-8s %-9s %8.2f %9.1f %7.2f %11.2f %13.2f %8.2fx%s\n", r->isa, r->op,
                r->ns.med, r->mrays, r->gbytes_s, r->memcpy_gbytes_s, mc,
                mc > 0 ? r->ns.med / mc : 0, r->cpu_timed ? " ~" : "");
    }
}

/* ---- the scene ------------------------------------------------------------------------ */

static void print_scene(FILE *f, const result_list *l, const scene_report *sc)
{
    if (!sc->have)
        return;
    fprintf(f,
            "\n== scene: %d capped cylinders, %dx%d, 16-ray packets against every cylinder, "
            "%zu primary + %zu shadow rays per frame ==\n",
            sc->ncyl, sc->w, sc->h, sc->primary, sc->shadow);
    fprintf(f, "%-14s %10s %10s %12s %9s %14s\n", "path", "ms/frame", "M rays/s", "M tests/s",
            "xscalar", "pixels != plain");
    for (size_t i = 0; i < l->n; i++) {
        const result *r = &l->r[i];
        if (strcmp(r->scenario, "scene"))
            continue;
        double ms = r->ns.med * (double)r->rays_timed * 1e-6;
        fprintf(f, "%-14s %9.1f%c %10.1f %12.0f %8.1fx ", r->isa, ms, r->cpu_timed ? '~' : ' ',
                r->mrays, r->mrays * r->ncyl, r->speedup);
        if (r->isa_id >= 0 && r->isa_id < BENCH_NISA)
            fprintf(f, "%14ld\n", sc->pix_diff[r->isa_id]);
        else
            fprintf(f, "%14s\n", "(the image)");
    }
    if (sc->image[0])
        fprintf(f, "   image: %s\n", sc->image);
}

void report_tables(FILE *f, const result_list *l, const scene_report *sc, const leaf_report *lr)
{
    print_group(f, l, "main", "main scenarios: packets of 4, 8, 16 and the stream API");
    print_group(f, l, "skips", "skips: the same work with less to do");
    print_group(f, l, "spheres",
                "spheres: one sphere, packets of 4, 8, 16 and the stream API (textbook: the "
                "textbook sphere in plain float)");
    print_group(f, l, "cones",
                "cones: one capped cone, packets of 4, 8, 16 and the stream API (textbook: "
                "the textbook cone in plain float)");
    print_group(f, l, "stress",
                "stress categories of tests/ref/gen.h (16 rays per cylinder; "
                "textbook: the textbook formulas in plain float)");
    print_rates(f, l);
    report_peer(f, l);
    print_skips(f, l);
    print_lanes(f, l);
    print_leaf(f, l, lr);
    print_stream(f, l);
    report_errors(f, l);
    print_scene(f, l, sc);
}
