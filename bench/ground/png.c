/* SPDX-License-Identifier: MIT */
/* png.c - PNG without zlib: the image data goes into "stored" deflate blocks (no
 * compression), which every decoder reads; only CRC-32 and Adler-32 are computed. */
#include "png.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static uint32_t crc_table[256];

static void crc_init(void)
{
    for (uint32_t n = 0; n < 256; n++) {
        uint32_t c = n;
        for (int k = 0; k < 8; k++)
            c = c & 1 ? 0xedb88320u ^ (c >> 1) : c >> 1;
        crc_table[n] = c;
    }
}

static uint32_t crc_update(uint32_t c, const uint8_t *p, size_t n)
{
    for (size_t i = 0; i < n; i++)
        c = crc_table[(c ^ p[i]) & 0xff] ^ (c >> 8);
    return c;
}

static void put32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)(v >> 24), p[1] = (uint8_t)(v >> 16), p[2] = (uint8_t)(v >> 8),
    p[3] = (uint8_t)v;
}

/* One chunk: length, type, data, CRC over type and data. */
static int chunk(FILE *f, const char *type, const uint8_t *data, size_t n)
{
    uint8_t head[8];
    put32(head, (uint32_t)n);
    memcpy(head + 4, type, 4);
    uint32_t c = crc_update(0xffffffffu, head + 4, 4);
    c = crc_update(c, data, n) ^ 0xffffffffu;
    uint8_t tail[4];
    put32(tail, c);
    return fwrite(head, 1, 8, f) != 8 || (n && fwrite(data, 1, n, f) != n) ||
           fwrite(tail, 1, 4, f) != 4;
}

int png_write_rgb(const char *path, int w, int h, const uint8_t *rgb)
{
    crc_init();
    /* The raw stream: each row is a filter byte (0, none) and its pixels. */
    size_t row = (size_t)w * 3 + 1, raw_n = row * (size_t)h;
    size_t nblocks = (raw_n + 65534) / 65535;
    size_t z_n = 2 + raw_n + 5 * nblocks + 4;
    uint8_t *z = malloc(z_n);
    if (!z)
        return -1;
    uint8_t *q = z;
    *q++ = 0x78, *q++ = 0x01; /* zlib header: deflate, 32K window, no dictionary */
    uint32_t a = 1, b = 0;    /* Adler-32 of the raw stream */
    size_t done = 0, block_left = 0;
    for (int y = 0; y < h; y++)
        for (size_t x = 0; x < row; x++) {
            if (block_left == 0) {
                size_t len = raw_n - done < 65535 ? raw_n - done : 65535;
                *q++ = (uint8_t)(done + len == raw_n); /* BFINAL on the last; BTYPE 00 */
                *q++ = (uint8_t)len, *q++ = (uint8_t)(len >> 8);
                *q++ = (uint8_t)~len, *q++ = (uint8_t)(~len >> 8);
                block_left = len;
            }
            uint8_t v = x == 0 ? 0 : rgb[(size_t)y * (size_t)w * 3 + x - 1];
            *q++ = v;
            a = (a + v) % 65521u;
            b = (b + a) % 65521u;
            done++;
            block_left--;
        }
    put32(q, b << 16 | a);
    q += 4;

    FILE *f = fopen(path, "wb");
    if (!f) {
        free(z);
        return -1;
    }
    static const uint8_t sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    uint8_t ihdr[13];
    put32(ihdr, (uint32_t)w);
    put32(ihdr + 4, (uint32_t)h);
    ihdr[8] = 8;  /* bit depth */
    ihdr[9] = 2;  /* colour type: RGB */
    ihdr[10] = 0; /* deflate */
    ihdr[11] = 0; /* adaptive filtering */
    ihdr[12] = 0; /* no interlace */
    int err = fwrite(sig, 1, 8, f) != 8 || chunk(f, "IHDR", ihdr, 13) ||
              chunk(f, "IDAT", z, (size_t)(q - z)) || chunk(f, "IEND", NULL, 0);
    err |= fclose(f) != 0;
    free(z);
    return err ? -1 : 0;
}
