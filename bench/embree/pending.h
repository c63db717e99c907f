/* pending.h - the parts of cylray's API that are declared in cylray.h but may not be
 * built into the library this harness links against yet (leaves, the endpoint form, the
 * secondary-ray helpers). They are weak references: a missing one is NULL at run time,
 * and the harness says what it skipped or what stood in, instead of failing to link. */
#ifndef EB_PENDING_H
#define EB_PENDING_H

#include "cylray.h"

#pragma weak cylray_leaf_prepare4
#pragma weak cylray_leaf_prepare8
#pragma weak cylray_leaf_prepare16
#pragma weak cylray_cylinder_from_endpoints
#pragma weak cylray_hit_point
#pragma weak cylray_spawn_origin

#endif
