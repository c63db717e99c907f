/* SPDX-License-Identifier: MIT */
/* machine.h - naming the machine a run was measured on, for every output file. */
#ifndef CYLBENCH_MACHINE_H
#define CYLBENCH_MACHINE_H

typedef struct machine_info {
    char cpu[128];     /* model name from /proc/cpuinfo */
    char cpuid[64];    /* "family 6 model 143 stepping 8" */
    char compiler[96]; /* the compiler that built the harness and the library */
    char buildtype[32];
    char os[224];  /* uname: system, release */
    char isas[64]; /* the cylray paths this CPU runs, e.g. "scalar sse41 avx2 avx512" */
    char pinned[48];
    char date[32];  /* UTC, ISO 8601 */
    int cores;      /* online logical CPUs */
    int hypervisor; /* 1 when /proc/cpuinfo lists the hypervisor flag */
    double tsc_ghz;
    double core_ghz; /* the core's clock while busy, from a dependent add chain; 0 if
                            unknown. TSC ticks run at tsc_ghz whatever the core does. */
    double load_start, load_end; /* 1-minute load average when the run began and ended */
} machine_info;

void machine_probe(machine_info *m);

/* The 1-minute load average (-1 if unknown): other processes share these cores. */
double machine_load(void);

#endif
