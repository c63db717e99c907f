/* SPDX-License-Identifier: MIT */
/* skip.c - stands in for a test that cannot be built here (e.g. no C++ compiler):
 * prints why and exits 77, which meson reports as SKIP rather than a silent pass. */
#include <stdio.h>

int main(int argc, char **argv)
{
    printf("skipped: %s\n", argc > 1 ? argv[1] : "not applicable here");
    return 77;
}
