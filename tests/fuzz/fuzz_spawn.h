/* SPDX-License-Identifier: MIT */
/* fuzz_spawn.h - the secondary-ray properties on a fuzz input's hits (fuzz_spawn.c). */
#ifndef FUZZ_SPAWN_H
#define FUZZ_SPAWN_H

#include "cylray.h"
#include "fuzz_input.h"
#include "guarded.h"

#include <stddef.h>

/* Nonzero with a description in why when a property fails for the hits of res (the
 * scalar path's answers to c, whose cylinder P is prepared). */
int fz_spawn(const fz_case *c, const cylray_prepared *P, const gresult *res,
             const cylray_kernels *const *isas, int nisa, char *why, size_t whylen);

/* Hits that went through the helpers, and spawned rays traced under the guarantee. */
extern unsigned long fz_spawn_hits, fz_spawn_traced;

#endif
