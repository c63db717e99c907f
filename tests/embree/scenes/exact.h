/* SPDX-License-Identifier: MIT */
/* exact.h - the exact answer for a ray against a whole scene (every cylinder, nearest
 * first, through the binary128 reference of tests/ref). */
#ifndef EB_EXACT_H
#define EB_EXACT_H

#include "cylref.h"
#include "ebscene.h"

#include <cylray_embree.h>

/* A collecting scene: every cylinder's box, so that one traversal lists every cylinder
 * a ray may meet. */
typedef struct eb_ref {
    const eb_scene *s;
    RTCScene collect;
} eb_ref;

int eb_ref_init(eb_ref *r, RTCDevice dev, const eb_scene *s);
void eb_ref_free(eb_ref *r);

/* The exact first hit over the scene: 1 with *id and *h, or 0. */
int eb_ref_closest(const eb_ref *r, const float o[3], const float d[3], float tmin, float tmax,
                   uint32_t *id, cylref_hit *h);

#endif
