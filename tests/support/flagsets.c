/* SPDX-License-Identifier: MIT */
/* flagsets.c - the list of flagsets.h. */
#include "flagsets.h"

#include "cylray.h"

const unsigned flag_sets[FLAG_SETS_ALL] = {
    0,
    CYLRAY_FLAGS_ALL,
    CYLRAY_NORMAL,
    CYLRAY_NORMAL | CYLRAY_CULL_BACK,
    CYLRAY_NORMAL | CYLRAY_FACE_FORWARD,
    CYLRAY_CULL_BACK | CYLRAY_REFINE,
    CYLRAY_NORMAL | CYLRAY_REFINE,
    CYLRAY_NORMAL | CYLRAY_FAST,
    CYLRAY_CULL_BACK | CYLRAY_FACE_FORWARD,
    CYLRAY_CULL_BACK | CYLRAY_REFINE | CYLRAY_FAST,
};
