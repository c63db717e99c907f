/* SPDX-License-Identifier: MIT */
/* guarded.h - rays through any ISA at any width, inside canaries and poison, with every
 * check of docs/design.md section 3 that needs no geometry.
 *
 * Each call copies a batch of rays into freshly allocated packets (or stream arrays at
 * a chosen misalignment), surrounds every array with canary bytes (also poisoned for
 * AddressSanitizer, so a stray read is caught too), fills every output with poison,
 * runs one kernel and then checks, for every lane:
 *   - nothing before or after any array was written, no input field changed;
 *   - a hit only on an active lane; on a hit, tmax == t bit for bit, t in the ray's
 *     [tmin, tmax], a valid part, no BACKFACE under CYLRAY_CULL_BACK, normals written
 *     exactly when CYLRAY_NORMAL is set;
 *   - a miss or an inactive lane: every output still poison, tmax unchanged;
 *   - the returned count equals the lanes written.
 * Violations are reported through CHECK (tcheck.h) and counted in the return value,
 * so every test that runs rays checks the memory contract as a side effect. */
#ifndef GUARDED_H
#define GUARDED_H

#include <stddef.h>
#include <stdint.h>

#include "cylray.h"

#define G_MAX 64   /* rays in one batch: a 16-packet, or a stream up to 3*16+16 */
#define G_STREAM 0 /* width value that selects the stream entry points */

enum { G_OX, G_OY, G_OZ, G_DX, G_DY, G_DZ, G_TMIN, G_TMAX, G_NFIELD };

/* Rays in structure-of-arrays form, fields in cylray_ray order. */
typedef struct gbatch {
    float f[G_NFIELD][G_MAX];
} gbatch;

typedef struct gresult {
    float t[G_MAX], nx[G_MAX], ny[G_MAX], nz[G_MAX];
    int32_t part[G_MAX];
    float tmax[G_MAX]; /* the ray's tmax after the call */
    uint64_t hit;      /* bit i: ray i reported a hit */
    size_t count;      /* the kernel's return value, as a number of hits */
} gresult;

/* What unwritten outputs hold: a signalling NaN with a payload no kernel computes,
 * and an impossible part code. */
#define G_POISON_BITS 0x7fa5c3e1u
#define G_POISON_PART ((int32_t)0x5a5a5a5a)
#define G_POISON_OCC 0xa5u

/* The ISAs cylray_kernels_for offers here, scalar first; returns how many. */
int g_isas(const cylray_kernels *out[CYLRAY_ISA_COUNT]);

/* "4", "8", "16" or "stream". */
const char *g_width_name(int width);

/* Runs intersect (width 4, 8, 16: n must equal width; G_STREAM: any n <= G_MAX, with
 * the arrays starting `misalign` floats past a 64-byte boundary, `active` ignored).
 * Returns the number of contract violations found (already reported). */
int g_intersect(const cylray_kernels *k, int width, const cylray_prepared *P, const gbatch *in,
                size_t n, uint32_t active, unsigned flags, unsigned misalign, gresult *out);

/* The same for occluded; fills out->hit and out->count only. */
int g_occluded(const cylray_kernels *k, int width, const cylray_prepared *P, const gbatch *in,
               size_t n, uint32_t active, unsigned flags, unsigned misalign, gresult *out);

/* Lane i of a and lane j of b, bit for bit: hit, tmax, and on a hit t, part and (if
 * `normal`) the normal. */
int g_same_lane(const gresult *a, size_t i, const gresult *b, size_t j, int normal);

/* "o=(..) d=(..) t=[..]" in %a, for failure messages. */
const char *g_ray_str(const gbatch *b, size_t i, char *buf, size_t len);
const char *g_cyl_str(const cylray_cylinder *c, char *buf, size_t len);

/* A float with the given bits, and the output poison as a float. */
float g_bits(uint32_t bits);
float g_poison(void);

#endif
