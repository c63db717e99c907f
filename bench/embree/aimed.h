/* SPDX-License-Identifier: MIT */
/* aimed.h - the rim and axis ray sets, aimed where Embree's curves and cylray differ
 * most, apart from the timing and judging that use them (main.c). */
#ifndef EB_AIMED_H
#define EB_AIMED_H

#include "judge.h"
#include "rays.h"

/* One ray of set EB_SET_RIM or EB_SET_AXIS (run.h) at a random end or sphere of sc. */
void eb_aimed(eb_sample *s, const eb_scene *sc, int set, rng *g);

#endif
