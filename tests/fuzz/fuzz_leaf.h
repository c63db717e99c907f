/* SPDX-License-Identifier: MIT */
/* fuzz_leaf.h - the fuzzer's checks of the leaf kernels (fuzz_leaf.c). */
#ifndef FUZZ_LEAF_H
#define FUZZ_LEAF_H

#include <stddef.h>

#include "cylray.h"
#include "fuzz_input.h"

/* 0: every check held; 1: one failed, and `why` says which. */
int fz_leaf(const fz_case *c, const cylray_kernels *const *isas, int nisa, char *why,
            size_t whylen);

#endif
