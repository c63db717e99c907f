/* SPDX-License-Identifier: MIT */
/* png.h - a minimal PNG writer: 8-bit RGB, uncompressed (zlib stored blocks). */
#ifndef CYLBENCH_PNG_H
#define CYLBENCH_PNG_H

#include <stdint.h>

/* Writes w x h pixels of 8-bit RGB (rows top to bottom) to path. 0 on success. */
int png_write_rgb(const char *path, int w, int h, const uint8_t *rgb);

#endif
