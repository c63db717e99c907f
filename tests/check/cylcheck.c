/* SPDX-License-Identifier: MIT */
/* cylcheck.c - checkasm for cylray: every ISA the CPU has, every width, every flag
 * combination, every category of stress ray, against the scalar path and the exact
 * reference (tests/ref). Prints its seed; a failure prints the lane's inputs in %a.
 *
 *   cylcheck [--isa=NAME] [--category=NAME] [--seed=N] [--quick] [--report]
 *            [--n=N] [--flags=F] [--fast] [--case=I] [--max-print=N] [--no-headline]
 *            [--show-ulps=X]
 *
 * Exit status: 0 all passed, 1 failures, 2 usage, 77 the requested ISA is not here
 * (meson's "skipped"). CYLRAY_TEST_QUICK=1 in the environment implies --quick (for
 * sanitizer and qemu runs). */
#define _POSIX_C_SOURCE 200809L /* clock_gettime, for a fresh seed */
#include "check.h"
#include "tcheck.h"

#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static const size_t stream_full[] = {1,  2,  3,  5,  7,  8,  9,  13,  15,  16,
                                     17, 23, 31, 33, 47, 64, 65, 100, 257, 700};
static const size_t stream_quick[] = {1, 3, 5, 7, 13, 17, 31, 129};
/* Spheres and cones run a quarter of the packet rays and fewer streams: their kernels
 * share the cylinder's drivers and stores, and CI's time is shared. */
static const size_t sphere_full[] = {1, 3, 7, 9, 16, 17, 33, 65, 100};
static const size_t sphere_quick[] = {1, 5, 17, 33};

static void usage(FILE *f)
{
    fprintf(f, "usage: cylcheck [options]\n"
               "  --isa=NAME       only this path (scalar, sse41, avx2, avx512, neon)\n"
               "  --category=NAME  only this category of rays:");
    for (int c = 0; c < CAT_COUNT; c++)
        fprintf(f, " %s", cat_name(c));
    fprintf(f, "\n"
               "  --seed=N         the generators' seed (default: from the clock, printed)\n"
               "  --quick          small counts (sanitizers, qemu); also CYLRAY_TEST_QUICK=1\n"
               "  --report         the accuracy table per ISA x category x mode\n"
               "  --n=N            packet rays per category (16k; spheres and cones N/4)\n"
               "  --flags=F        only this kernel flag combination (0..31)\n"
               "  --fast           only the combinations with CYLRAY_FAST (run them with\n"
               "                   CYLRAY_ESTIMATES=on to check the estimates on any CPU)\n"
               "  --case=I         only this case of the category (from a failure's repro)\n"
               "  --max-print=N    failures printed in full (default 12)\n"
               "  --no-headline    do not assert the headline accuracy numbers\n"
               "  --show-ulps=X    print each hit whose t is over X ulps from the exact t\n");
}

static int parse_isa(const char *s)
{
    for (int i = 0; i < CYLRAY_ISA_COUNT; i++)
        if (strcmp(s, cylray_isa_name((cylray_isa)i)) == 0)
            return i;
    return -2;
}

static void parse_args(int argc, char **argv)
{
    int have_seed = 0;
    if (tc_quick())
        opt.quick = 1;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (strncmp(a, "--isa=", 6) == 0) {
            opt.isa = parse_isa(a + 6);
            if (opt.isa < 0) {
                fprintf(stderr, "cylcheck: unknown ISA '%s'\n", a + 6);
                exit(2);
            }
        } else if (strncmp(a, "--category=", 11) == 0) {
            opt.category = cat_find(a + 11);
            if (opt.category < 0) {
                fprintf(stderr, "cylcheck: unknown category '%s'\n", a + 11);
                usage(stderr);
                exit(2);
            }
        } else if (strncmp(a, "--seed=", 7) == 0) {
            opt.seed = strtoull(a + 7, NULL, 0);
            have_seed = 1;
        } else if (strcmp(a, "--quick") == 0) {
            opt.quick = 1;
        } else if (strcmp(a, "--report") == 0) {
            opt.report = 1;
        } else if (strncmp(a, "--n=", 4) == 0) {
            opt.n = (size_t)strtoull(a + 4, NULL, 0);
            opt.n = (opt.n + CYLGEN_BATCH - 1) / CYLGEN_BATCH * CYLGEN_BATCH;
        } else if (strncmp(a, "--flags=", 8) == 0) {
            opt.flags_only = (int)strtol(a + 8, NULL, 0);
            if (opt.flags_only < 0 || opt.flags_only > (int)CYLRAY_FLAGS_ALL) {
                fprintf(stderr, "cylcheck: flags must be 0..31\n");
                exit(2);
            }
        } else if (strcmp(a, "--fast") == 0) {
            opt.fast_only = 1;
        } else if (strncmp(a, "--case=", 7) == 0) {
            opt.only_case = atoi(a + 7);
        } else if (strncmp(a, "--max-print=", 12) == 0) {
            opt.max_print = atoi(a + 12);
        } else if (strncmp(a, "--show-ulps=", 12) == 0) {
            opt.show_ulps = strtod(a + 12, NULL);
        } else if (strcmp(a, "--no-headline") == 0) {
            opt.headline = 0;
        } else if (strcmp(a, "--verbose") == 0 || strcmp(a, "-v") == 0) {
            opt.verbose = 1;
        } else if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            usage(stdout);
            exit(0);
        } else {
            fprintf(stderr, "cylcheck: unknown option '%s'\n", a);
            usage(stderr);
            exit(2);
        }
    }
    if (!have_seed) {
        struct timespec ts;
        clock_gettime(CLOCK_REALTIME, &ts);
        opt.seed = (uint64_t)ts.tv_sec * 1000003u ^ (uint64_t)ts.tv_nsec;
        opt.seed &= 0xffffffffu;
    }
    if (!opt.n)
        opt.n = opt.quick ? 64 : 1024;
}

int main(int argc, char **argv)
{
    setvbuf(stdout, NULL, _IOLBF, 0);
    parse_args(argc, argv);
    printf("cylcheck: seed %" PRIu64 " (--seed=%" PRIu64 " repeats this run)%s\n", opt.seed,
           opt.seed, opt.quick ? ", quick" : "");

    const cylray_kernels *isas[CYLRAY_ISA_COUNT];
    int n_isas = 0;
    for (int i = 0; i < CYLRAY_ISA_COUNT; i++) {
        if (opt.isa >= 0 && i != opt.isa)
            continue;
        const cylray_kernels *k = cylray_kernels_for((cylray_isa)i);
        if (k)
            isas[n_isas++] = k;
    }
    if (!n_isas) {
        printf("cylcheck: %s is not available on this CPU or not built: skipped\n",
               cylray_isa_name((cylray_isa)opt.isa));
        return 77;
    }
    const cylray_kernels *scalar = cylray_kernels_for(CYLRAY_ISA_SCALAR);
    printf("cylcheck: paths");
    for (int i = 0; i < n_isas; i++)
        printf(" %s", isas[i]->name);
    printf("\n");

    const size_t *lengths = opt.quick ? stream_quick : stream_full;
    size_t n_lengths = opt.quick ? sizeof stream_quick / sizeof *stream_quick
                                 : sizeof stream_full / sizeof *stream_full;
    long lanes_before = 0;
    for (int cat = 0; cat < CAT_COUNT; cat++) {
        if (opt.category >= 0 && cat != opt.category)
            continue;
        size_t total, npk = opt.n, nl = n_lengths;
        const size_t *ls = lengths;
        if (cat_is_sphere(cat) || cat_is_cone(cat) || cat_is_round(cat)) {
            npk = opt.n / 4 / CYLGEN_BATCH * CYLGEN_BATCH;
            npk = npk ? npk : CYLGEN_BATCH;
            ls = opt.quick ? sphere_quick : sphere_full;
            nl = opt.quick ? sizeof sphere_quick / sizeof *sphere_quick
                           : sizeof sphere_full / sizeof *sphere_full;
        }
        ref_case *rc = cat == CAT_REGRESS ? make_regress_cases(&npk, &ls, &nl, &total)
                                          : make_cases(cat, opt.seed, npk, ls, nl, &total);
        /* Segments for the scalar answers: packet batches, then the streams. */
        size_t n_seg = npk / CYLGEN_BATCH + nl;
        size_t *segs = malloc(n_seg * sizeof *segs);
        lane_out *sc = malloc(total * sizeof *sc);
        if (!segs || !sc)
            return 2;
        for (size_t i = 0; i < npk / CYLGEN_BATCH; i++)
            segs[i] = CYLGEN_BATCH;
        for (size_t i = 0; i < nl; i++)
            segs[npk / CYLGEN_BATCH + i] = ls[i];
        for (unsigned flags = 0; flags <= CYLRAY_FLAGS_ALL; flags++) {
            if ((opt.flags_only >= 0 && flags != (unsigned)opt.flags_only) ||
                (opt.fast_only && !(flags & CYLRAY_FAST)))
                continue;
            if (scalar)
                scalar_answers(scalar, flags, rc, segs, n_seg, sc);
            for (int i = 0; i < n_isas; i++) {
                const cylray_kernels *k = isas[i];
                const lane_out *cmp = scalar && k != scalar ? sc : NULL;
                drive_packets(k, flags, cat, rc, npk, cmp, opt.seed);
                drive_streams(k, flags, cat, rc + npk, ls, nl, cmp ? cmp + npk : NULL,
                              opt.seed);
            }
        }
        long lanes = 0;
        for (int i = 0; i < n_isas; i++)
            for (int m = 0; m < MODE_COUNT; m++)
                lanes += stat_at(isas[i]->isa, cat, m)->lanes;
        if (opt.verbose || opt.report)
            printf("cylcheck: %-13s %ld lanes checked, %ld failures so far\n", cat_name(cat),
                   lanes, failures);
        lanes_before += lanes;
        free(segs);
        free(sc);
        free(rc);
    }

    if (opt.report)
        stats_report();
    int headline_bad = 0;
    if (opt.headline && opt.only_case < 0 && !opt.fast_only &&
        (opt.flags_only < 0 || mode_of((unsigned)opt.flags_only) == MODE_PLAIN)) {
        printf("\n");
        for (int i = 0; i < n_isas; i++)
            headline_bad += stats_headline(isas[i]->isa);
    }
    stats_free();
    if (failures > opt.max_print)
        printf("(%ld more failures not printed; --max-print=N)\n", failures - opt.max_print);
    printf("cylcheck: %ld lanes checked, %ld failures, %d headline numbers missed: %s\n",
           lanes_before, failures, headline_bad, failures || headline_bad ? "FAILED" : "ok");
    return failures || headline_bad ? 1 : 0;
}
