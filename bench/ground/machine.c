/* SPDX-License-Identifier: MIT */
/* machine.c - CPU model, core count, compiler and OS, read once for the outputs. */
#define _POSIX_C_SOURCE 200809L /* sysconf, uname */
#include "machine.h"

#include "clock.h"
#include "cylray.h"

#include <stdio.h>
#include <string.h>
#include <sys/utsname.h>
#include <time.h>
#include <unistd.h>

#ifndef CYLBENCH_CC
#define CYLBENCH_CC "unknown compiler " __VERSION__
#endif
#ifndef CYLBENCH_BUILDTYPE
#define CYLBENCH_BUILDTYPE "unknown"
#endif

/* The value after "key<spaces>:" on a /proc/cpuinfo line, without the newline. */
static int cpuinfo_field(const char *line, const char *key, char *out, size_t n)
{
    size_t k = strlen(key);
    if (strncmp(line, key, k) != 0 || (line[k] != ' ' && line[k] != '\t' && line[k] != ':'))
        return 0;
    const char *c = strchr(line, ':');
    if (!c)
        return 0;
    c++;
    while (*c == ' ')
        c++;
    snprintf(out, n, "%s", c);
    out[strcspn(out, "\n")] = 0;
    return 1;
}

/* A chain of dependent 64-bit multiplies takes 3 cycles each on every x86 core of the
 * last fifteen years (dependent adds of an immediate no longer do: newer cores fold them
 * at rename), so timing the chain gives the core's real clock under load, turbo
 * included, which the TSC does not show. Best of five runs of about 10 ms. */
static double core_ghz(void)
{
#if (defined(__x86_64__) || defined(__i386__)) && (defined(__GNUC__) || defined(__clang__))
    double best = 0;
    for (int k = 0; k < 5; k++) {
        unsigned long x = 1, n = 1000000, one = 1;
        double a = clk_cpu_ns(); /* CPU time: a preemption must not look like a slow clock */
        __asm__ volatile("1:\n\t"
                         "imul %2, %0\n\timul %2, %0\n\timul %2, %0\n\timul %2, %0\n\t"
                         "imul %2, %0\n\timul %2, %0\n\timul %2, %0\n\timul %2, %0\n\t"
                         "dec %1\n\tjnz 1b"
                         : "+r"(x), "+r"(n)
                         : "r"(one)
                         : "cc");
        double e = clk_cpu_ns() - a, ghz = 24e6 / e;
        if (ghz > best)
            best = ghz;
    }
    return best;
#else
    return 0;
#endif
}

void machine_probe(machine_info *m)
{
    memset(m, 0, sizeof *m);
    snprintf(m->cpu, sizeof m->cpu, "unknown CPU");
    char fam[12] = "?", model[12] = "?", step[12] = "?";
    FILE *f = fopen("/proc/cpuinfo", "r");
    if (f) {
        char line[4096];
        int got_name = 0, got_flags = 0;
        while (fgets(line, sizeof line, f) && !(got_name && got_flags)) {
            char tmp[12];
            if (!got_name && cpuinfo_field(line, "model name", m->cpu, sizeof m->cpu))
                got_name = 1;
            else if (cpuinfo_field(line, "cpu family", tmp, sizeof tmp))
                memcpy(fam, tmp, sizeof fam);
            else if (cpuinfo_field(line, "model", tmp, sizeof tmp))
                memcpy(model, tmp, sizeof model);
            else if (cpuinfo_field(line, "stepping", tmp, sizeof tmp))
                memcpy(step, tmp, sizeof step);
            else if (strncmp(line, "flags", 5) == 0) {
                m->hypervisor = strstr(line, " hypervisor") != NULL;
                got_flags = 1;
            }
        }
        fclose(f);
    }
    snprintf(m->cpuid, sizeof m->cpuid, "family %s model %s stepping %s", fam, model, step);
    long nc = sysconf(_SC_NPROCESSORS_ONLN);
    m->cores = nc > 0 ? (int)nc : 1;
    snprintf(m->compiler, sizeof m->compiler, "%s", CYLBENCH_CC);
    snprintf(m->buildtype, sizeof m->buildtype, "%s", CYLBENCH_BUILDTYPE);
    struct utsname u;
    if (uname(&u) == 0)
        snprintf(m->os, sizeof m->os, "%s %s %s", u.sysname, u.release, u.machine);
    for (int i = 0; i < CYLRAY_ISA_COUNT; i++)
        if (cylray_kernels_for((cylray_isa)i)) {
            size_t l = strlen(m->isas);
            snprintf(m->isas + l, sizeof m->isas - l, "%s%s", l ? " " : "",
                     cylray_isa_name((cylray_isa)i));
        }
    time_t now = time(NULL);
    struct tm *tm = gmtime(&now);
    if (tm)
        strftime(m->date, sizeof m->date, "%Y-%m-%dT%H:%M:%SZ", tm);
    m->tsc_ghz = clk_tsc_ghz();
    m->core_ghz = core_ghz();
    snprintf(m->pinned, sizeof m->pinned, "not pinned");
    m->load_start = machine_load();
}

double machine_load(void)
{
    double l = -1;
    FILE *f = fopen("/proc/loadavg", "r");
    if (f) {
        if (fscanf(f, "%lf", &l) != 1)
            l = -1;
        fclose(f);
    }
    return l;
}
