/* SPDX-License-Identifier: MIT */
/* isa_env.c - CYLRAY_ISA forces the path of the plain entry points: an available
 * choice is used silently; an unavailable or unknown one falls back to the best path
 * with exactly one line on stderr, however many calls follow, which says which of the
 * two it is and, for an unknown name, lists the known ones. The choice is made once
 * per process, so each setting runs in a forked child (fork, not exec: under qemu-user
 * an exec'd foreign binary would not run) with its stderr captured through a pipe. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "cylray.h"
#include "tcheck.h"

/* In the child: force, call the plain entry points several times, check they agree
 * bit for bit with the table cylray_kernels_best() names. Exit status 10 + the ISA
 * chosen, or 1 when the plain entry points disagree with it. */
static void child(const char *value)
{
    if (value)
        setenv("CYLRAY_ISA", value, 1);
    else
        unsetenv("CYLRAY_ISA");
    const cylray_cylinder c = {{0, 0, 0}, {0.25f, 0, 1}, 1, 2, CYLRAY_CAPPED};
    cylray_prepared P;
    if (cylray_prepare(&P, &c) != CYLRAY_OK)
        _exit(1);
    cylray_ray8 r0, r1;
    cylray_hit8 h0, h1;
    for (int i = 0; i < 8; i++) {
        r0.ox[i] = -4;
        r0.oy[i] = 0.1f * (float)i;
        r0.oz[i] = -3 + 0.7f * (float)i;
        r0.dx[i] = 1;
        r0.dy[i] = 0.01f;
        r0.dz[i] = 0.3f;
        r0.tmin[i] = 0;
        r0.tmax[i] = INFINITY;
    }
    int bad = 0;
    for (int rep = 0; rep < 3; rep++) {
        r1 = r0;
        memset(&h0, 0, sizeof h0);
        memset(&h1, 0, sizeof h1);
        cylray_ray8 rk = r0;
        uint32_t m0 = cylray_intersect8(&P, &r1, &h0, 0xffu, CYLRAY_NORMAL);
        const cylray_kernels *k = cylray_kernels_best();
        uint32_t m1 = k->intersect8(&P, &rk, &h1, 0xffu, CYLRAY_NORMAL);
        if (m0 != m1 || memcmp(&h0, &h1, sizeof h0) != 0 || memcmp(&r1, &rk, sizeof rk) != 0 ||
            m0 == 0)
            bad = 1;
        if (cylray_occluded8(&P, &r0, 0xffu, 0) != m0)
            bad = 1;
    }
    _exit(bad ? 1 : 10 + (int)cylray_kernels_best()->isa);
}

/* Runs one setting; returns the chosen ISA (or -1) and the captured stderr. */
static int run(const char *value, char *err, size_t errlen)
{
    int fd[2];
    if (pipe(fd) != 0)
        return -1;
    fflush(NULL);
    pid_t pid = fork();
    if (pid < 0)
        return -1;
    if (pid == 0) {
        close(fd[0]);
        dup2(fd[1], 2);
        close(fd[1]);
        child(value);
    }
    close(fd[1]);
    size_t len = 0;
    ssize_t got;
    while ((got = read(fd[0], err + len, errlen - 1 - len)) > 0)
        len += (size_t)got;
    err[len] = '\0';
    close(fd[0]);
    int status = 0;
    if (waitpid(pid, &status, 0) != pid || !WIFEXITED(status))
        return -1;
    int code = WEXITSTATUS(status);
    return code >= 10 && code < 10 + CYLRAY_ISA_COUNT ? code - 10 : -1;
}

static int lines(const char *s)
{
    int n = 0;
    for (; *s; s++)
        n += *s == '\n';
    return n;
}

int main(void)
{
    /* The automatic choice: the best available, as kernels.c checks in detail. This
     * process never calls a plain entry point itself, so it can fork clean children. */
    int best = CYLRAY_ISA_SCALAR;
    for (int i = 0; i < CYLRAY_ISA_COUNT; i++)
        if (cylray_kernels_for((cylray_isa)i))
            best = i;

    char err[4096];
    int got = run(NULL, err, sizeof err);
    CHECK(got == best, "CYLRAY_ISA unset: chose %d, expected %s", got,
          cylray_isa_name((cylray_isa)best));
    CHECK(err[0] == '\0', "CYLRAY_ISA unset: stderr says \"%s\"", err);

    const char *const values[] = {"scalar", "sse41", "avx2", "avx512",
                                  "neon",   "bogus", "AVX2", "scalar "};
    for (size_t v = 0; v < sizeof values / sizeof values[0]; v++) {
        int isa = -1;
        for (int i = 0; i < CYLRAY_ISA_COUNT; i++)
            if (strcmp(values[v], cylray_isa_name((cylray_isa)i)) == 0)
                isa = i;
        const int available = isa >= 0 && cylray_kernels_for((cylray_isa)isa) != NULL;
        got = run(values[v], err, sizeof err);
        if (available) {
            CHECK(got == isa, "CYLRAY_ISA=%s (available): chose %d", values[v], got);
            CHECK(err[0] == '\0', "CYLRAY_ISA=%s (available): stderr says \"%s\"", values[v],
                  err);
        } else {
            CHECK(got == best, "CYLRAY_ISA=%s (not available): chose %d, expected the best, %s",
                  values[v], got, cylray_isa_name((cylray_isa)best));
            size_t n = strlen(err);
            CHECK(lines(err) == 1 && n > 1 && err[n - 1] == '\n',
                  "CYLRAY_ISA=%s: expected one warning line, stderr has %d lines: \"%s\"",
                  values[v], lines(err), err);
            CHECK(strstr(err, values[v]) != NULL,
                  "CYLRAY_ISA=%s: the warning does not name the request: \"%s\"", values[v],
                  err);
            /* A known name is unavailable here; any other is unknown, and the warning
             * lists the names that would do. */
            const char *says = isa >= 0 ? "not available" : "unknown";
            CHECK(strstr(err, says) != NULL,
                  "CYLRAY_ISA=%s: the warning does not say \"%s\": \"%s\"", values[v], says,
                  err);
            for (int i = 0; i < CYLRAY_ISA_COUNT && isa < 0; i++)
                CHECK(strstr(err, cylray_isa_name((cylray_isa)i)) != NULL,
                      "CYLRAY_ISA=%s: the warning does not list %s: \"%s\"", values[v],
                      cylray_isa_name((cylray_isa)i), err);
        }
    }
    return tc_report("api-isa-env");
}
