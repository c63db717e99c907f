/* SPDX-License-Identifier: MIT */
/* png.c - a minimal PNG writer: the image data goes into "stored" deflate blocks, which
 * every PNG reader accepts; the file is as large as the raw pixels (plus 5 bytes per
 * 64 KiB), which is fine for an example's output. The bench writes its images with it
 * too (the tree's one PNG writer), so it stays free of anything outside examples/. */
#include "png.h"

#include <stdio.h>
#include <stdlib.h>

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

static uint32_t crc_update(uint32_t crc, const uint8_t *p, size_t n)
{
    for (size_t i = 0; i < n; i++)
        crc = crc_table[(crc ^ p[i]) & 0xff] ^ (crc >> 8);
    return crc;
}

static void put32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)(v >> 24), p[1] = (uint8_t)(v >> 16), p[2] = (uint8_t)(v >> 8);
    p[3] = (uint8_t)v;
}

/* One chunk: length, type, data, CRC of type and data. */
static int chunk(FILE *f, const char type[4], const uint8_t *data, uint32_t n)
{
    uint8_t head[8];
    put32(head, n);
    for (int i = 0; i < 4; i++)
        head[4 + i] = (uint8_t)type[i];
    uint32_t crc = crc_update(0xffffffffu, head + 4, 4);
    crc = crc_update(crc, data, n) ^ 0xffffffffu;
    uint8_t tail[4];
    put32(tail, crc);
    return fwrite(head, 1, 8, f) != 8 || (n && fwrite(data, 1, n, f) != n) ||
           fwrite(tail, 1, 4, f) != 4;
}

int png_write_rgb(const char *path, const uint8_t *rgb, uint32_t w, uint32_t h)
{
    crc_init();
    /* the raw scanlines: a filter byte (0, none) before each row */
    size_t row = (size_t)w * 3 + 1, raw_n = row * h;
    size_t blocks = raw_n / 65535 + 1;
    size_t z_n = 2 + raw_n + 5 * blocks + 4;
    uint8_t *z = malloc(z_n);
    if (!z)
        return -1;
    size_t o = 0;
    z[o++] = 0x78, z[o++] = 0x01; /* zlib: deflate, 32 KiB window, no dictionary */
    uint32_t a = 1, b = 0;        /* Adler-32 of the raw data */
    size_t done = 0;
    for (size_t k = 0; k < blocks; k++) {
        size_t len = raw_n - done < 65535 ? raw_n - done : 65535;
        z[o++] = k + 1 == blocks; /* BFINAL on the last block, BTYPE 00: stored */
        z[o++] = (uint8_t)len, z[o++] = (uint8_t)(len >> 8);
        z[o++] = (uint8_t)~len, z[o++] = (uint8_t)(~len >> 8);
        for (size_t i = 0; i < len; i++, done++) {
            size_t y = done / row, x = done % row;
            uint8_t v = x == 0 ? 0 : rgb[y * (size_t)w * 3 + x - 1];
            z[o++] = v;
            a = (a + v) % 65521u;
            b = (b + a) % 65521u;
        }
    }
    put32(z + o, (b << 16) | a);
    o += 4;
    FILE *f = fopen(path, "wb");
    if (!f) {
        free(z);
        return -1;
    }
    static const uint8_t sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    uint8_t ihdr[13];
    put32(ihdr, w);
    put32(ihdr + 4, h);
    ihdr[8] = 8, ihdr[9] = 2, ihdr[10] = ihdr[11] = ihdr[12] = 0; /* 8-bit RGB */
    int bad = fwrite(sig, 1, 8, f) != 8 || chunk(f, "IHDR", ihdr, 13) ||
              chunk(f, "IDAT", z, (uint32_t)o) || chunk(f, "IEND", NULL, 0);
    free(z);
    return fclose(f) != 0 || bad ? -1 : 0;
}
