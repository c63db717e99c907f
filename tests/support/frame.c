/* SPDX-License-Identifier: MIT */
/* frame.c - the axis frame of frame.h. */
#include "frame.h"

#include <math.h>

void axis_frame(const float axis[3], double u[3], double e1[3], double e2[3])
{
    double l = 0;
    for (int k = 0; k < 3; k++)
        l += (double)axis[k] * axis[k];
    l = sqrt(l);
    if (!(l > 0) || !isfinite(l)) {
        u[0] = 0, u[1] = 0, u[2] = 1;
    } else {
        for (int k = 0; k < 3; k++)
            u[k] = axis[k] / l;
    }
    /* e_m is then at least 45 degrees from u (60 unless |u_0|, |u_1| >= 0.5), so
     * a x u is not small. */
    const int m = fabs(u[0]) < 0.5 ? 0 : fabs(u[1]) < 0.5 ? 1 : 2;
    double a[3] = {0, 0, 0};
    a[m] = 1;
    e1[0] = a[1] * u[2] - a[2] * u[1];
    e1[1] = a[2] * u[0] - a[0] * u[2];
    e1[2] = a[0] * u[1] - a[1] * u[0];
    l = sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
    for (int k = 0; k < 3; k++)
        e1[k] /= l;
    e2[0] = u[1] * e1[2] - u[2] * e1[1];
    e2[1] = u[2] * e1[0] - u[0] * e1[2];
    e2[2] = u[0] * e1[1] - u[1] * e1[0];
}
