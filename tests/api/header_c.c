/* SPDX-License-Identifier: MIT */
/* header_c.c - include/cylray.h compiles alone as C11 (it is the only include, twice,
 * and this file is built with -Werror at warning level 3), and its packets have the
 * layout the contract promises: SoA, aligned to their width, no padding. */
#include "cylray.h"
#include "cylray.h" /* the include guard holds */

#define LAYOUT_(n, al)                                                                         \
    _Static_assert(_Alignof(cylray_ray##n) == al && _Alignof(cylray_hit##n) == al,             \
                   "packet " #n " alignment");                                                 \
    _Static_assert(sizeof(cylray_ray##n) == 8 * n * sizeof(float), "ray" #n " size");          \
    _Static_assert(offsetof(cylray_ray##n, oy) == 1 * n * sizeof(float) &&                     \
                       offsetof(cylray_ray##n, dx) == 3 * n * sizeof(float) &&                 \
                       offsetof(cylray_ray##n, tmin) == 6 * n * sizeof(float) &&               \
                       offsetof(cylray_ray##n, tmax) == 7 * n * sizeof(float),                 \
                   "ray" #n " fields");                                                        \
    _Static_assert(sizeof(cylray_hit##n) == 5 * n * sizeof(float) &&                           \
                       offsetof(cylray_hit##n, nz) == 3 * n * sizeof(float) &&                 \
                       offsetof(cylray_hit##n, part) == 4 * n * sizeof(float),                 \
                   "hit" #n " layout");
LAYOUT_(4, 16)
LAYOUT_(8, 32)
LAYOUT_(16, 64)

_Static_assert(_Alignof(cylray_prepared) == 64, "prepared is cache-line aligned");
_Static_assert(CYLRAY_FLAGS_ALL == (CYLRAY_NORMAL | CYLRAY_FACE_FORWARD | CYLRAY_CULL_BACK |
                                    CYLRAY_REFINE | CYLRAY_FAST),
               "FLAGS_ALL is every kernel flag");
_Static_assert(CYLRAY_MISS == 0 && CYLRAY_SIDE == 1 && CYLRAY_CAP_LO == 2 &&
                   CYLRAY_CAP_HI == 3 && CYLRAY_BACKFACE == 0x10 &&
                   (CYLRAY_PART_MASK & CYLRAY_BACKFACE) == 0,
               "part codes as in docs/design.md");
_Static_assert(CYLRAY_ISA_SCALAR == 0 && CYLRAY_ISA_NEON == 4 && CYLRAY_ISA_COUNT == 5,
               "ISA enum order");

/* Every function the header declares must link, with the declared type. */
static cylray_intersect4_fn const i4 = cylray_intersect4;
static cylray_intersect8_fn const i8 = cylray_intersect8;
static cylray_intersect16_fn const i16 = cylray_intersect16;
static cylray_occluded4_fn const o4 = cylray_occluded4;
static cylray_occluded8_fn const o8 = cylray_occluded8;
static cylray_occluded16_fn const o16 = cylray_occluded16;
static cylray_intersect_stream_fn const is = cylray_intersect_stream;
static cylray_occluded_stream_fn const os = cylray_occluded_stream;

int main(void)
{
    cylray_status (*const prep)(cylray_prepared *, const cylray_cylinder *) = cylray_prepare;
    const char *(*const err)(cylray_status) = cylray_strerror;
    const cylray_kernels *(*const kf)(cylray_isa) = cylray_kernels_for;
    const cylray_kernels *(*const kb)(void) = cylray_kernels_best;
    const char *(*const nm)(cylray_isa) = cylray_isa_name;
    int linked =
        i4 && i8 && i16 && o4 && o8 && o16 && is && os && prep && err && kf && kb && nm;
    const char *s = cylray_isa_name(CYLRAY_ISA_SCALAR);
    int named = s && s[0] == 's' && s[1] == 'c' && s[6] == '\0';
    return linked && named ? 0 : 1;
}
