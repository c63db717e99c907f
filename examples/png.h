/* SPDX-License-Identifier: MIT */
/* png.h - a minimal PNG writer (8-bit RGB, uncompressed deflate blocks), no dependency. */
#ifndef EXAMPLE_PNG_H
#define EXAMPLE_PNG_H

#include <stddef.h>
#include <stdint.h>

/* Writes w x h pixels of 3 bytes each (row by row, top first) to path; 0 on success. */
int png_write_rgb(const char *path, const uint8_t *rgb, uint32_t w, uint32_t h);

#endif
