/* SPDX-License-Identifier: MIT */
/* frame.h - an orthonormal frame around a cylinder's axis, for placing test rays. */
#ifndef FRAME_H
#define FRAME_H

/* u: the unit axis, in double; e1, e2: unit vectors perpendicular to it and to each
 * other (u, e1, e2 right-handed). e1 is built from the first coordinate axis that is
 * well away from u, so the frame is a pure function of the axis: fuzz inputs decode to
 * the same rays wherever they run. An axis that is zero or not finite (a fuzz input
 * may give one) is taken as +z, so that callers still get a frame. */
void axis_frame(const float axis[3], double u[3], double e1[3], double e2[3]);

#endif
