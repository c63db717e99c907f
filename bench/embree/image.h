/* SPDX-License-Identifier: MIT */
/* image.h - the frames as pictures: each variant shaded, and where two variants differ. */
#ifndef EB_IMAGE_H
#define EB_IMAGE_H

#include "trace.h"

#include <stdint.h>

/* Shades a frame (w x h, rgb 3 bytes a pixel): colour by cylinder, a diffuse light
 * with the shadow rays' answer, darkened where the bounce ray meets something near. */
void eb_shade(const eb_scene *s, const eb_rays *prim, const eb_rays *shadow,
              const eb_rays *bounce, int w, int h, uint8_t *rgb);

/* Where frames a and b differ: red, hit against miss; yellow, another cylinder; cyan, the
 * shadow ray's answer; grey, the t difference in float ulps on a log scale (white at
 * 2^10 or more); black, the same. Returns the number of red and yellow pixels. */
size_t eb_diff(const eb_rays *pa, const eb_rays *sa, const eb_rays *pb, const eb_rays *sb,
               int w, int h, uint8_t *rgb);

#endif
