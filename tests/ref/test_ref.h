/* SPDX-License-Identifier: MIT */
/* test_ref.h - what the reference's test files share: the check, which counts into the
 * including file's own `failures`, and the upright cylinder. */
#ifndef TEST_REF_H
#define TEST_REF_H

#include "cylref.h"

#include <stdio.h>

int test_hand(void); /* test_hand.c */

#define CHECK(cond, ...)                                                                       \
    do {                                                                                       \
        if (!(cond)) {                                                                         \
            failures++;                                                                        \
            printf("FAIL %s:%d: %s: ", __FILE__, __LINE__, #cond);                             \
            printf(__VA_ARGS__);                                                               \
            printf("\n");                                                                      \
        }                                                                                      \
    } while (0)

static inline cylray_cylinder cyl_z(float R, float H, unsigned flags)
{
    cylray_cylinder c = {{0, 0, 0}, {0, 0, 1}, R, H, flags};
    return c;
}

#endif
