/* SPDX-License-Identifier: MIT */
/* pending.h - the secondary-ray helpers, declared in cylray.h but not necessarily built
 * into the library this harness links against. They are weak references: a missing one
 * is NULL at run time, and the harness says what stood in, instead of failing to link. */
#ifndef EB_PENDING_H
#define EB_PENDING_H

#include "cylray.h"

#pragma weak cylray_hit_point
#pragma weak cylray_spawn_origin

#endif
