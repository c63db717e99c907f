#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""make_corpus.py - writes the seed corpus (corpus/*) of the fuzz target.

The byte layout is documented in fuzz_input.h. Each seed is one typical call, so the
fuzzer starts from inputs that reach the kernels' interesting branches instead of
having to discover the layout. Run it from tests/fuzz/ after changing the layout."""
import os
import struct

def special(i):            # tag < 32: the special-value table in fuzz_input.c
    return bytes([i])

ZERO, NEG0, ONE, MONE, HALF, TWO, THREE, MTWO, NAN, MNAN, INF, MINF = range(12)

def num(v, scale=0):       # 32 <= tag < 224: int16 * 2^(scale)
    tag = 32 + ((scale + 20) % 24)
    return bytes([tag]) + struct.pack('<h', int(v))

def raw(f):                # tag >= 224: four raw bytes
    return bytes([0xe0]) + struct.pack('<f', f)

def header(width, flags, active, capped=False, infinite=False, misalign=0, sphere=False,
           cone=False):
    mode = {4: 0, 8: 1, 16: 2, 'stream': 3}[width] | misalign << 2
    mode |= 0x10 if capped else 0
    mode |= 0x20 if infinite else 0
    mode |= 0xc0 if sphere else 0
    mode |= 0xa0 if cone else 0
    return bytes([mode, flags]) + struct.pack('<H', active)

def cyl(center, axis, radius, half_height=None):
    b = b''.join(center) + b''.join(axis) + radius
    return b + (half_height if half_height is not None else b'')

def aimed(origin, angle, axial, radial, length, window=0, extra=b''):
    return (bytes([0x80 | window]) + b''.join(origin) +
            bytes([angle & 255, axial & 255, radial & 255, length & 255]) + extra)

def raw_ray(fields):
    return bytes([0]) + b''.join(fields)

seeds = {}

# a unit capped cylinder along z, 8 rays aimed from all around, normals
s = header(8, 0x01, 0xff, capped=True)
s += cyl([special(ZERO)] * 3, [special(ZERO), special(ZERO), special(ONE)], special(ONE), special(TWO))
for i in range(8):
    s += aimed([num(-5 + i), num(3 - i), num(2 * i - 7)], 32 * i, 20 * i - 70, 10 + 15 * i, 12)
seeds['capped8'] = s

# an oblique infinite cylinder, 4 raw rays: one NaN, one from inside, one parallel
s = header(4, 0x01 | 0x02, 0xf, infinite=True)
s += cyl([num(1), num(-2), num(3)], [num(3), num(4), num(0)], num(5))
s += raw_ray([num(-7), num(8), num(3), num(4), num(-3), num(0), special(ZERO), special(INF)])
s += raw_ray([special(NAN)] * 8)
s += raw_ray([num(1), num(-2), num(3), num(1), num(1), num(1), special(MINF), special(INF)])
s += raw_ray([num(2), num(-2), num(3), num(3), num(4), num(0), special(ZERO), special(INF)])
seeds['oblique4'] = s

# an open tube, a misaligned stream of 19 aimed rays with every flag
s = header('stream', 0x1f, 19, misalign=1)
s += cyl([num(0)] * 3, [num(1), num(0), num(1)], special(HALF), special(THREE))
for i in range(19):
    s += aimed([num(i - 9, -2), num(30 - 3 * i, -2), num(7, -1)], 13 * i, 7 * i - 60, 9 * i, 10 + i % 5,
               window=i % 4, extra=num(40) + num(2) + num(60))
seeds['tube_stream'] = s

# a 16-packet on a far, small cylinder; some lanes inactive
s = header(16, 0x01 | 0x08, 0xbeef, capped=True)
s += cyl([num(1000), num(-1000), num(500)], [raw(-0.2), raw(0.9), raw(0.1)], raw(1e-2), raw(0.5))
for i in range(16):
    s += aimed([num(i, -4), num(-i, -4), num(3, -4)], 16 * i, 8 * i - 64, 4 * i, 12)
seeds['far16'] = s

seeds['empty'] = b''

# a sphere (center, radius; the axis and half height only aim the rays), 8 aimed
# rays from all around and one from inside, normals facing forward
s = header(8, 0x01 | 0x02, 0xff, sphere=True)
s += cyl([num(1), num(-2), num(3)], [special(ZERO), special(ZERO), special(ONE)], special(TWO),
         special(ONE))
for i in range(7):
    s += aimed([num(-6 + 2 * i), num(5 - i), num(3 * i - 9)], 36 * i, 30 * i - 90, 20 * i, 12)
s += aimed([num(0), num(1, -2), num(0)], 200, 0, 40, 12, window=1)
seeds['sphere8'] = s

# a small sphere far from the world origin, a misaligned stream of 21 aimed rays with
# every flag and every window
s = header('stream', 0x1f, 21, misalign=2, sphere=True)
s += cyl([num(1000), num(-1000), num(500)], [raw(0.3), raw(-0.2), raw(0.9)], raw(1e-3), raw(1.0))
for i in range(21):
    s += aimed([num(i - 10, -3), num(5 - i, -3), num(2, -3)], 12 * i, 6 * i - 60, 6 * i, 8 + i % 7,
               window=i % 4, extra=num(40) + num(2) + num(60))
seeds['sphere_stream'] = s

# a tip cone (p0 = center, p1 = center + axis, r0 the radius, r1 in the half height's
# place), capped, 8 aimed rays from all around (some at the apex) and one from inside
s = header(8, 0x01, 0xff, capped=True, cone=True)
s += cyl([num(1), num(-2), num(3)], [num(0), num(0), special(TWO)], special(ONE), special(ZERO))
for i in range(7):
    s += aimed([num(-6 + 2 * i), num(5 - i), num(3 * i - 9)], 36 * i, 30 * i - 90, 20 * i, 12)
s += aimed([num(0), num(1, -2), num(0)], 200, 0, 40, 12, window=1)
seeds['cone8'] = s

# a nearly cylindrical cone far from the world origin, a misaligned stream of 21 aimed
# rays with every flag and every window
s = header('stream', 0x1f, 21, misalign=2, cone=True)
s += cyl([num(1000), num(-1000), num(500)], [raw(0.3), raw(-0.2), raw(0.9)], raw(1e-2),
         raw(1.0001e-2))
for i in range(21):
    s += aimed([num(i - 10, -3), num(5 - i, -3), num(2, -3)], 12 * i, 6 * i - 60, 6 * i, 8 + i % 7,
               window=i % 4, extra=num(40) + num(2) + num(60))
seeds['cone_stream'] = s

os.makedirs('corpus', exist_ok=True)
for name, data in seeds.items():
    with open(os.path.join('corpus', name), 'wb') as f:
        f.write(data)
