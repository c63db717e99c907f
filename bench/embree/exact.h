/* exact.h - the exact answer for a ray against a whole scene, and the judgment of a
 * variant's answer against it. */
#ifndef EB_EXACT_H
#define EB_EXACT_H

#include "cylref.h"
#include "ebscene.h"

#include <embree3/rtcore.h>

/* A collecting scene: every cylinder's box, so that one traversal lists every cylinder
 * a ray may meet. */
typedef struct eb_ref {
    const eb_scene *s;
    RTCScene collect;
} eb_ref;

int eb_ref_init(eb_ref *r, RTCDevice dev, const eb_scene *s);
void eb_ref_free(eb_ref *r);

/* The exact first hit of one cylinder, one-end caps included (cylref knows closed and
 * open cylinders; a cylinder closed at one end is the open tube plus that disc). */
int eb_ref_one(const cylray_cylinder *c, const float o[3], const float d[3], float tmin,
               float tmax, cylref_hit *h);

/* The exact first hit over the scene: 1 with *id and *h, or 0. */
int eb_ref_closest(const eb_ref *r, const float o[3], const float d[3], float tmin,
                   float tmax, uint32_t *id, cylref_hit *h);

/* The tolerance band of cylinder c for that ray (one-end caps judged as the open tube
 * for side hits and as the closed cylinder for cap hits). */
void eb_ref_band(const cylray_cylinder *c, int part, const float o[3], const float d[3],
                 float tmin, float tmax, cylref_band *b);

#endif
