/* SPDX-License-Identifier: MIT */
/* clocks.h - the two clocks behind the build and trace times that geom.c and trace.c
 * report: this library is linked by a test too, so it keeps to plain POSIX clocks of
 * its own rather than the bench's (which pin threads and read the TSC). */
#ifndef EB_CLOCKS_H
#define EB_CLOCKS_H

/* Monotonic wall time in seconds. */
double eb_wall_s(void);

/* CPU time of the whole process in seconds: beside the wall time of a threaded trace
 * it shows how many cores a shared machine actually gave. */
double eb_cpu_s(void);

#endif
