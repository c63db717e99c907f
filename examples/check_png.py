#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""check_png.py - runs an example renderer (tracer, molecule) and checks its image.

Usage: check_png.py <program> <out.png>

The PNG must parse (signature, chunk CRCs, zlib stream), have the size asked for, and
look like a picture: many distinct colours, neither mostly background nor mostly one
colour, and the colours of more than one kind of atom.
"""
import struct
import subprocess
import sys
import zlib


def read_png(path):
    data = open(path, 'rb').read()
    assert data[:8] == b'\x89PNG\r\n\x1a\n', 'bad signature'
    pos, chunks = 8, []
    while pos < len(data):
        n, = struct.unpack('>I', data[pos:pos + 4])
        kind = data[pos + 4:pos + 8]
        body = data[pos + 8:pos + 8 + n]
        crc, = struct.unpack('>I', data[pos + 8 + n:pos + 12 + n])
        assert zlib.crc32(kind + body) & 0xffffffff == crc, 'bad CRC in ' + kind.decode()
        chunks.append((kind, body))
        pos += 12 + n
    assert chunks[0][0] == b'IHDR' and chunks[-1][0] == b'IEND'
    w, h, depth, ctype = struct.unpack('>IIBB', chunks[0][1][:10])
    assert depth == 8 and ctype == 2, 'not 8-bit RGB'
    raw = zlib.decompress(b''.join(b for k, b in chunks if k == b'IDAT'))
    assert len(raw) == h * (3 * w + 1), 'wrong amount of pixel data'
    rows = [raw[y * (3 * w + 1):(y + 1) * (3 * w + 1)] for y in range(h)]
    assert all(r[0] == 0 for r in rows), 'unexpected filter'
    px = [tuple(r[1 + 3 * x:4 + 3 * x]) for r in rows for x in range(w)]
    return w, h, px


def main():
    tracer, out = sys.argv[1], sys.argv[2]
    w, h = 160, 120
    run = subprocess.run([tracer, '-o', out, '-s', '%dx%d' % (w, h), '-n', '300'],
                         capture_output=True, text=True)
    print(run.stdout, end='')
    if run.returncode:
        print(run.stderr, end='')
        return 1
    gw, gh, px = read_png(out)
    distinct = len(set(px))
    # the background is the sky: blue dominates; the molecule is anything else
    objects = [p for p in px if not (p[2] > p[0] + 20 and p[2] > p[1])]
    reds = sum(1 for p in objects if p[0] > p[1] + 40 and p[0] > p[2] + 40)
    greys = sum(1 for p in objects if max(p) - min(p) < 20 and max(p) > 40)
    print('png %dx%d: %d distinct colours, %d of %d pixels on the molecule (%d red, %d grey)'
          % (gw, gh, distinct, len(objects), len(px), reds, greys))
    ok = (gw, gh) == (w, h) and distinct > 200 and 0.05 * len(px) < len(objects) < 0.95 * len(px) \
        and reds > 50 and greys > 50
    print('OK' if ok else 'FAIL: the image does not look like the scene')
    return 0 if ok else 1


if __name__ == '__main__':
    sys.exit(main())
