/* SPDX-License-Identifier: MIT */
/* tcheck.h - counting test failures, and printing floats so that a failure replays.
 *
 * The test programs of api/, robust/ and fuzz/ report through these: CHECK counts, prints
 * the first failures with file and line, and tc_report() turns the count into the exit
 * status meson reads. Floats are printed with %a (hex) so that a reported input can be
 * pasted back into a test bit for bit. */
#ifndef TCHECK_H
#define TCHECK_H

#include <stdio.h>

#if defined(__GNUC__) || defined(__clang__)
#define TC_PRINTF(f, a) __attribute__((format(printf, f, a)))
#else
#define TC_PRINTF(f, a)
#endif

extern long tc_checks_;
extern long tc_failures_;
extern int tc_silent_; /* nonzero: count failures without printing (harness self-test) */

void tc_fail_(const char *file, int line, const char *fmt, ...) TC_PRINTF(3, 4);

/* CHECK(condition, printf-format, args...): the message says what was expected. */
#define CHECK(cond, ...)                                                                       \
    do {                                                                                       \
        tc_checks_++;                                                                          \
        if (!(cond))                                                                           \
            tc_fail_(__FILE__, __LINE__, __VA_ARGS__);                                         \
    } while (0)

/* Prints "<name>: N checks, M failures" and returns the exit status (0 or 1). A test
 * that made no check at all fails too: it tested nothing. */
int tc_report(const char *name);

/* Nonzero when CYLRAY_TEST_QUICK is set (sanitizer and qemu runs): shrink loops. */
int tc_quick(void);

/* Bit-exact equality of two floats (NaN payloads and signed zeros included). */
int tc_same(float a, float b);

/* Float ulps between a and b (both finite), as a double. */
double tc_ulps(float a, float b);

#endif
