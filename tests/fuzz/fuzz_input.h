/* SPDX-License-Identifier: MIT */
/* fuzz_input.h - turning arbitrary bytes into one kernel call: a cylinder, kernel
 * flags, a width (4, 8, 16 or a stream), an active mask, a stream misalignment and the
 * rays. Every byte string decodes to something; running out of bytes gives zeros.
 *
 * Layout (all optional; missing bytes read as 0):
 *   byte 0      bits 0-1 width (0: 4, 1: 8, 2: 16, 3: stream), bits 2-3 stream
 *               misalignment in floats, bit 4 capped, bit 5 infinite (half height Inf),
 *               bits 6 and 7 both set: a sphere (the center and radius below; the
 *               axis and half height are read and only aim the rays); bits 7 and 5
 *               set, bit 6 clear: a cone from p0 = center to p1 = center + axis, r0
 *               the radius, r1 the half height's value, capped by bit 4
 *   byte 1      kernel flags (the low 5 bits: CYLRAY_FLAGS_ALL)
 *   bytes 2-3   active mask, little endian (streams: byte 2 % 50 is the length)
 *   values      center x y z, axis x y z, radius, half height
 *   per ray     one tag byte: below 0x80 the 8 fields as values; otherwise an aimed
 *               ray: origin (3 values), then bytes angle, axial (int8), radial, and
 *               length, and the window byte (tag & 3: [0, Inf), [-Inf, Inf], [0, v],
 *               [v, v] with values)
 * A value is a tag byte and its payload: tag < 32 a special value (0, -0, 1, NaN, Inf,
 * FLT_MAX, FLT_MIN, denormals, 1e30, ...); 32 <= tag < 224 a 16-bit integer scaled by
 * a power of two from 2^-20 to 2^3; tag >= 224 four raw bytes of a float. Aimed rays
 * make most lanes hit, so the fuzzer spends its time where the answers are decided. */
#ifndef FUZZ_INPUT_H
#define FUZZ_INPUT_H

#include <stddef.h>
#include <stdint.h>

#include "cylray.h"
#include "guarded.h"

typedef struct fz_case {
    cylray_cylinder cyl;
    int sphere; /* the shape is sph; cyl only aims the rays */
    cylray_sphere sph;
    int cone; /* the shape is con; cyl only aims the rays */
    cylray_cone con;
    unsigned flags;
    int width;         /* 4, 8, 16 or G_STREAM */
    size_t n;          /* rays: the width, or the stream length */
    uint32_t active;   /* packets only */
    unsigned misalign; /* streams only */
    gbatch rays;
} fz_case;

void fz_decode(const uint8_t *data, size_t size, fz_case *c);

#endif
