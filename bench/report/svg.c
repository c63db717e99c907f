/* SPDX-License-Identifier: MIT */
/* svg.c - the two plots, as plain SVG text: ns per ray against p99 t error (log-log, one
 * point per ISA x variant), and the speedup over scalar per ISA and width. */
#include "report.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define W 900
#define H 600
#define ML 80 /* margins: left, right, top, bottom */
#define MR 230
#define MT 60
#define MB 70

static void header(FILE *f, const char *title, const machine_info *m)
{
    char ml[512];
    machine_line(m, ml, sizeof ml);
    fprintf(f,
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" height=\"%d\" "
            "viewBox=\"0 0 %d %d\" font-family=\"sans-serif\">\n"
            "<rect width=\"%d\" height=\"%d\" fill=\"white\"/>\n"
            "<text x=\"%d\" y=\"24\" font-size=\"17\" font-weight=\"bold\">%s</text>\n"
            "<text x=\"%d\" y=\"44\" font-size=\"11\" fill=\"#444\">%s</text>\n",
            W, H, W, H, W, H, ML, title, ML, ml);
}

static double lx(double v, double lo, double hi)
{
    return ML + (log10(v) - log10(lo)) / (log10(hi) - log10(lo)) * (W - ML - MR);
}

static double ly(double v, double lo, double hi)
{
    return H - MB - (log10(v) - log10(lo)) / (log10(hi) - log10(lo)) * (H - MT - MB);
}

/* Log axis ticks at 1, 2, 5 times powers of ten inside [lo, hi]. */
static void log_ticks(FILE *f, double lo, double hi, int vertical)
{
    for (int e = (int)floor(log10(lo)) - 1; e <= (int)ceil(log10(hi)); e++)
        for (int k = 0; k < 3; k++) {
            double v = (k == 0 ? 1 : k == 1 ? 2 : 5) * pow(10, e);
            if (v < lo || v > hi)
                continue;
            char lab[32];
            snprintf(lab, sizeof lab, v >= 1e4 || v < 0.01 ? "%.0e" : "%g", v);
            if (vertical) {
                double y = ly(v, lo, hi);
                fprintf(f,
                        "<line x1=\"%d\" x2=\"%d\" y1=\"%.1f\" y2=\"%.1f\" stroke=\"%s\"/>\n",
                        ML, W - MR, y, y, k ? "#f0f0f0" : "#d8d8d8");
                fprintf(f,
                        "<text x=\"%d\" y=\"%.1f\" font-size=\"11\" text-anchor=\"end\">%s"
                        "</text>\n",
                        ML - 6, y + 4, lab);
            } else {
                double x = lx(v, lo, hi);
                fprintf(f,
                        "<line x1=\"%.1f\" x2=\"%.1f\" y1=\"%d\" y2=\"%d\" stroke=\"%s\"/>\n",
                        x, x, MT, H - MB, k ? "#f0f0f0" : "#d8d8d8");
                fprintf(f,
                        "<text x=\"%.1f\" y=\"%d\" font-size=\"11\" text-anchor=\"middle\">"
                        "%s</text>\n",
                        x, H - MB + 16, lab);
            }
        }
}

/* A point's marker by its category: cylinder ordinary (disc), far (square); sphere
 * ordinary (triangle), far (open triangle); cone ordinary (diamond), far (open
 * diamond). */
static void marker(FILE *f, int cat, double x, double y, const char *col)
{
    if (cat == 0)
        fprintf(f,
                "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"5\" fill=\"%s\" fill-opacity=\"0.8\"/>\n",
                x, y, col);
    else if (cat == 1)
        fprintf(f,
                "<rect x=\"%.1f\" y=\"%.1f\" width=\"10\" height=\"10\" fill=\"none\" "
                "stroke=\"%s\" stroke-width=\"2\"/>\n",
                x - 5, y - 5, col);
    else if (cat >= 4)
        fprintf(f,
                "<polygon points=\"%.1f,%.1f %.1f,%.1f %.1f,%.1f %.1f,%.1f\" fill=\"%s\" "
                "fill-opacity=\"%s\" stroke=\"%s\" stroke-width=\"2\"/>\n",
                x, y - 6, x + 6, y, x, y + 6, x - 6, y, cat == 4 ? col : "none",
                cat == 4 ? "0.8" : "1", col);
    else
        fprintf(f,
                "<polygon points=\"%.1f,%.1f %.1f,%.1f %.1f,%.1f\" fill=\"%s\" "
                "fill-opacity=\"%s\" stroke=\"%s\" stroke-width=\"2\"/>\n",
                x, y - 6, x - 6, y + 5, x + 6, y + 5, cat == 2 ? col : "none",
                cat == 2 ? "0.8" : "1", col);
}

typedef struct point {
    double x, y;
    int variant, cat, isa;
} point;

int svg_time_vs_error(const char *path, const result_list *l, const machine_info *m)
{
    /* The cylinder's two stress categories (ordinary and far), the sphere's pair and the
     * cone's, if measured. */
    enum { NCAT = 6 };
    const char *cats[NCAT] = {"stress-ordinary", "stress-far",      "sphere-incoherent",
                              "sphere-far",      "cone-incoherent", "cone-far"};
    const char *cat_label[NCAT] = {"ordinary rays",         "far origins (1e3-1e6 R)",
                                   "sphere, ordinary rays", "sphere, far (1e4-1e6 R)",
                                   "cone, ordinary rays",   "cone, far (1e4-1e6 R)"};
    const int ops[3] = {OP_NORMAL, OP_REFINE, OP_FAST};
    const char *var_name[4] = {"default", "REFINE", "FAST", "textbook"};
    const char *var_col[4] = {"#1f77b4", "#2ca02c", "#d62728", "#111111"};
    point pts[160];
    int np = 0;
    const double floor_ulp = 0.1; /* p99 of 0 ulps is drawn at 0.1 on the log axis */
    for (int c = 0; c < NCAT; c++)
        for (int isa = 0; isa < BENCH_NISA; isa++)
            for (int v = 0; v < 3; v++) {
                const result *r = NULL;
                if (bench_is_textbook(isa)) {
                    if (v == 0)
                        r = find_result(l, cats[c], isa, -1, OP_NORMAL);
                } else {
                    r = find_result(l, cats[c], isa, BW_16, ops[v]);
                }
                if (!r || !r->have_err || np >= 160)
                    continue;
                point p = {r->ns.med, r->ulp_p99 > floor_ulp ? r->ulp_p99 : floor_ulp,
                           bench_is_textbook(isa) ? 3 : v, c, isa};
                pts[np++] = p;
            }
    FILE *f = fopen(path, "w");
    if (!f)
        return -1;
    header(f, "cylray: run time against error (p99 of |t - t_exact| in float ulps)", m);
    if (!np) {
        fprintf(f,
                "<text x=\"%d\" y=\"%d\" font-size=\"14\">no error figures: run the "
                "stress scenarios with the exact reference built</text>\n</svg>\n",
                ML, H / 2);
        fclose(f);
        return 0;
    }
    double x0 = 1e30, x1 = 0, y0 = floor_ulp, y1 = 1;
    for (int i = 0; i < np; i++) {
        x0 = fmin(x0, pts[i].x), x1 = fmax(x1, pts[i].x);
        y1 = fmax(y1, pts[i].y);
    }
    x0 /= 1.5, x1 *= 1.5, y1 *= 3;
    fprintf(f,
            "<rect x=\"%d\" y=\"%d\" width=\"%d\" height=\"%d\" fill=\"none\" "
            "stroke=\"#888\"/>\n",
            ML, MT, W - ML - MR, H - MT - MB);
    log_ticks(f, x0, x1, 0);
    log_ticks(f, y0, y1, 1);
    fprintf(f,
            "<text x=\"%d\" y=\"%d\" font-size=\"13\" text-anchor=\"middle\">ns per ray "
            "(median; 16-wide packets, textbook streams; normals; log)</text>\n",
            (ML + W - MR) / 2, H - MB + 40);
    fprintf(f,
            "<text transform=\"translate(22 %d) rotate(-90)\" font-size=\"13\" "
            "text-anchor=\"middle\">p99 t error, ulps (log; 0 drawn at 0.1)</text>\n",
            (MT + H - MB) / 2);
    for (int i = 0; i < np; i++) {
        const point *p = &pts[i];
        double x = lx(p->x, x0, x1), y = ly(p->y, y0, y1);
        marker(f, p->cat, x, y, var_col[p->variant]);
        /* labels staggered by variant, so points at one error level stay readable; the
         * textbook builds share one error level, so they alternate above and below */
        int stagger =
            p->variant == 3 ? 22 * ((p->isa - BENCH_ISA_TEXTBOOK) % 2) : 10 * p->variant;
        fprintf(f, "<text x=\"%.1f\" y=\"%.1f\" font-size=\"9\" fill=\"%s\">%s%s</text>\n",
                x + 7, y - 8 + stagger, var_col[p->variant], bench_isa_name(p->isa),
                p->variant == 0 || p->variant == 3 ? ""
                : p->variant == 1                  ? " R"
                                                   : " F");
    }
    /* legend */
    int lx0 = W - MR + 20, ly0 = MT + 10;
    for (int v = 0; v < 4; v++)
        fprintf(f,
                "<circle cx=\"%d\" cy=\"%d\" r=\"5\" fill=\"%s\"/><text x=\"%d\" y=\"%d\" "
                "font-size=\"12\">%s</text>\n",
                lx0, ly0 + 20 * v, var_col[v], lx0 + 12, ly0 + 20 * v + 4, var_name[v]);
    for (int c = 0; c < NCAT; c++) {
        marker(f, c, lx0, ly0 + 100 + 18 * c, "#999");
        fprintf(f, "<text x=\"%d\" y=\"%d\" font-size=\"12\">%s</text>\n", lx0 + 12,
                ly0 + 104 + 18 * c, cat_label[c]);
    }
    fprintf(
        f, "<text x=\"%d\" y=\"%d\" font-size=\"10\" fill=\"#444\">R: REFINE, F: FAST</text>\n",
        lx0 - 5, ly0 + 114 + 18 * NCAT);
    fprintf(f,
            "<text x=\"%d\" y=\"%d\" font-size=\"10\" fill=\"#444\">textbook: naive.c, "
            "plain float; scalar</text>\n",
            lx0 - 5, ly0 + 130 + 18 * NCAT);
    fprintf(f,
            "<text x=\"%d\" y=\"%d\" font-size=\"10\" fill=\"#444\">and auto-vectorized "
            "per ISA (streams)</text>\n",
            lx0 - 5, ly0 + 144 + 18 * NCAT);
    fprintf(f, "</svg>\n");
    return fclose(f) ? -1 : 0;
}

int svg_speedup(const char *path, const result_list *l, const machine_info *m)
{
    const char *scen = "incoherent";
    const char *wcol[BW_COUNT] = {"#9ecae1", "#4292c6", "#08519c", "#fd8d3c"};
    int isas[CYLRAY_ISA_COUNT], ni = 0;
    double ymax = 1;
    for (int isa = 0; isa < CYLRAY_ISA_COUNT; isa++) {
        int any = 0;
        for (int w = 0; w < BW_COUNT; w++) {
            const result *r = find_result(l, scen, isa, w, OP_NORMAL);
            if (r) {
                any = 1;
                ymax = fmax(ymax, r->speedup);
            }
        }
        if (any)
            isas[ni++] = isa;
    }
    FILE *f = fopen(path, "w");
    if (!f)
        return -1;
    header(f, "cylray: speedup over the scalar path, per ISA and width", m);
    if (!ni) {
        fprintf(f,
                "<text x=\"%d\" y=\"%d\" font-size=\"14\">no results for the incoherent "
                "scenario</text>\n</svg>\n",
                ML, H / 2);
        fclose(f);
        return 0;
    }
    double top = ceil(ymax * 1.15);
    const int pw = W - ML - MR, ph = H - MT - MB;
    fprintf(f,
            "<rect x=\"%d\" y=\"%d\" width=\"%d\" height=\"%d\" fill=\"none\" "
            "stroke=\"#888\"/>\n",
            ML, MT, pw, ph);
    double step = top <= 10 ? 1 : top <= 25 ? 2 : 5;
    for (double v = 0; v <= top + 1e-9; v += step) {
        double y = H - MB - v / top * ph;
        fprintf(f,
                "<line x1=\"%d\" x2=\"%d\" y1=\"%.1f\" y2=\"%.1f\" stroke=\"%s\"/>\n"
                "<text x=\"%d\" y=\"%.1f\" font-size=\"11\" text-anchor=\"end\">%gx</text>\n",
                ML, W - MR, y, y, v == 1 ? "#888" : "#e4e4e4", ML - 6, y + 4, v);
    }
    double gw = (double)pw / ni, bw = gw * 0.8 / BW_COUNT;
    for (int g = 0; g < ni; g++) {
        double gx = ML + g * gw + gw * 0.1;
        for (int w = 0; w < BW_COUNT; w++) {
            const result *r = find_result(l, scen, isas[g], w, OP_NORMAL);
            if (!r)
                continue;
            double h = r->speedup / top * ph, x = gx + w * bw;
            fprintf(f,
                    "<rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" "
                    "fill=\"%s\"/>\n",
                    x, H - MB - h, bw - 2, h, wcol[w]);
            fprintf(f,
                    "<text x=\"%.1f\" y=\"%.1f\" font-size=\"10\" text-anchor=\"middle\">"
                    "%.1f</text>\n",
                    x + bw / 2 - 1, H - MB - h - 4, r->speedup);
            fprintf(f,
                    "<text x=\"%.1f\" y=\"%.1f\" font-size=\"9\" text-anchor=\"middle\" "
                    "fill=\"#555\">%.0f</text>\n",
                    x + bw / 2 - 1, (double)H - MB + 28, r->mrays);
        }
        fprintf(f,
                "<text x=\"%.1f\" y=\"%d\" font-size=\"13\" text-anchor=\"middle\">%s</text>\n",
                gx + gw * 0.4, H - MB + 15, bench_isa_name(isas[g]));
    }
    fprintf(f,
            "<text x=\"%d\" y=\"%d\" font-size=\"11\" fill=\"#555\">small numbers under the "
            "bars: M rays/s. Ordinary (incoherent) rays, capped cylinder, normals, batches "
            "in L1, one core</text>\n",
            ML, H - MB + 50);
    int lx0 = W - MR + 20, ly0 = MT + 10;
    for (int w = 0; w < BW_COUNT; w++)
        fprintf(f,
                "<rect x=\"%d\" y=\"%d\" width=\"12\" height=\"12\" fill=\"%s\"/><text "
                "x=\"%d\" y=\"%d\" font-size=\"12\">%s%s</text>\n",
                lx0, ly0 + 20 * w, wcol[w], lx0 + 18, ly0 + 20 * w + 11, bench_width_name[w],
                w == BW_STREAM ? "" : " rays per packet");
    fprintf(f, "</svg>\n");
    return fclose(f) ? -1 : 0;
}
