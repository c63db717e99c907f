/* SPDX-License-Identifier: MIT */
// header_cpp.cpp - include/cylray.h compiles alone as C++ (-Werror, warning level 3),
// agrees with C on the packet layout, and declares C linkage (the calls below would not
// link against the C library otherwise).
#include "cylray.h"
#include "cylray.h"

#define LAYOUT_(n, al)                                                                 \
    static_assert(alignof(cylray_ray##n) == al && alignof(cylray_hit##n) == al,        \
                  "packet " #n " alignment");                                          \
    static_assert(sizeof(cylray_ray##n) == 8 * n * sizeof(float), "ray" #n " size");   \
    static_assert(sizeof(cylray_hit##n) == 5 * n * sizeof(float), "hit" #n " size");   \
    static_assert(offsetof(cylray_ray##n, tmax) == 7 * n * sizeof(float), "ray fields"); \
    static_assert(offsetof(cylray_hit##n, part) == 4 * n * sizeof(float), "hit fields");
LAYOUT_(4, 16)
LAYOUT_(8, 32)
LAYOUT_(16, 64)
static_assert(alignof(cylray_prepared) == 64, "prepared alignment");

int main()
{
    cylray_cylinder c = {{0, 0, 0}, {0, 0, 1}, 1.0f, 1.0f, CYLRAY_CAPPED};
    cylray_prepared p;
    if (cylray_prepare(&p, &c) != CYLRAY_OK)
        return 1;
    const cylray_kernels *k = cylray_kernels_for(CYLRAY_ISA_SCALAR);
    if (!k || !cylray_strerror(CYLRAY_EINVAL) || !cylray_isa_name(CYLRAY_ISA_AVX2))
        return 1;
    // one ray straight down onto the upper cap: hit at t = 2
    cylray_ray4 r = {};
    cylray_hit4 h = {};
    r.oz[0] = 3.0f;
    r.dz[0] = -1.0f;
    r.tmax[0] = 100.0f;
    uint32_t m = k->intersect4(&p, &r, &h, 1u, CYLRAY_NORMAL);
    return m == 1u && h.t[0] == 2.0f && h.part[0] == CYLRAY_CAP_HI && h.nz[0] == 1.0f ? 0 : 1;
}
