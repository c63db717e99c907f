/* SPDX-License-Identifier: MIT */
/* sphkernel.h - a sphere kernel in double precision, written for the checker's own
 * test: it answers packets and streams with the semantics of cylray.h (NaN lanes miss,
 * missed and inactive lanes untouched, tmax = t on a hit) from the float sphere that
 * cylray_prepare_sphere stored, rounding t and the normal once. mutants.c puts its
 * defects into this kernel, so that the sphere checks are proven to fail on defects
 * whatever the library's own sphere kernel does. */
#ifndef SPHKERNEL_H
#define SPHKERNEL_H

#include "cylray.h"

/* Packets, streams and occluded (no leaves, no secondary rays). */
const cylray_kernels *sphere_double_kernels(void);

#endif
