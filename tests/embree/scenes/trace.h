/* SPDX-License-Identifier: MIT */
/* trace.h - ray sets and their tracing through an Embree scene: one ray or packets of
 * 4, 8, 16, over image tiles, on plain threads. */
#ifndef EB_TRACE_H
#define EB_TRACE_H

#include "ebscene.h"

#include "query.h"
#include <stddef.h>
#include <stdint.h>

/* Rays in SoA. tfar is the input's end and the output's hit t (or -INFINITY for an
 * occluded ray after an occlusion query); ng, u, v and prim are the hit (prim is
 * RTC_INVALID_GEOMETRY_ID on a miss). A ray with valid[i] == 0 is not traced. */
typedef struct eb_rays {
    size_t n;
    float *ox, *oy, *oz, *dx, *dy, *dz, *tnear, *tfar;
    float *ngx, *ngy, *ngz, *u, *v;
    uint32_t *prim; /* an answer's id (ebscene.h) */
    uint8_t *valid;
    int incoherent; /* tells Embree whether neighbouring rays travel alike */
} eb_rays;

int eb_rays_alloc(eb_rays *r, size_t n); /* 0 on success */
void eb_rays_free(eb_rays *r);
void eb_rays_get(const eb_rays *r, size_t i, float o[3], float d[3]);

/* Rays are stored tile by tile (16 x 16 pixels), and inside a tile in 4 x 4 blocks, so
 * that a packet of 4, 8 or 16 consecutive rays is a compact patch of pixels. w and h
 * are multiples of 16. */
void eb_pixel_of(size_t idx, int w, int h, int *x, int *y);

/* The pinhole camera's rays of s, w x h pixels, tnear 0, tfar INFINITY. */
void eb_camera_rays(eb_rays *r, const eb_scene *s, int w, int h);
/* One camera ray, in double until the final rounding. */
void eb_camera_ray(const eb_scene *s, int w, int h, double x, double y, float o[3], float d[3]);

/* Traces the valid rays of r through scene: rtcIntersect (occluded = 0) or rtcOccluded
 * (occluded = 1), `packet` rays to a call (1, 4, 8 or 16), on `threads` threads that take
 * 256 rays (one tile) at a time. Returns the wall time in seconds; *cpu_s (if not NULL)
 * gets the CPU time the process got meanwhile, which shows how many cores a shared
 * machine actually gave. */
double eb_trace(RTCScene scene, eb_rays *r, int packet, int threads, int occluded,
                double *cpu_s);
/* The same with filter as the query's filter function (query.h: Embree 3's context
 * filter; Embree 4's argument filter, and the adapter's extended context's). */
double eb_trace_filtered(RTCScene scene, eb_rays *r, int packet, int threads, int occluded,
                         double *cpu_s, RTCFilterFunctionN filter);

/* One ray, rtcIntersect1 on the calling thread: the hit's id (ebscene.h: the primID,
 * with EB_SPHERE_BIT on a sphere; or RTC_INVALID_GEOMETRY_ID), with *t and ng on a
 * hit. */
uint32_t eb_trace1(RTCScene scene, const float o[3], const float d[3], float tnear, float tfar,
                   float *t, float ng[3]);

/* ---- secondary rays ------------------------------------------------------------ */

struct eb_geom;

/* From the primary hits in `prim` (traced through g), fills shadow and bounce (both
 * allocated with prim->n rays), each started as that variant's user would start it:
 * Embree's curves at the hit point with Embree's path-tracer epsilon as tnear;
 * cylray's at cylray_embree_spawn_origin with tnear 0. The bounce directions depend
 * only on the pixel, so every variant draws the same. */
void eb_spawn(const struct eb_geom *g, const eb_rays *prim, eb_rays *shadow, eb_rays *bounce);

/* The unit normal facing the incoming direction d, from a hit's Ng. */
void eb_facing_normal(const float ng[3], const float d[3], float n[3]);

#endif
