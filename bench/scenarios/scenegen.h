/* SPDX-License-Identifier: MIT */
/* scenegen.h - the harness's cylinder sets, built from a seed: cylinders from their
 * endpoints, molecule bonds and pipe runs (the leaf scenario's clusters) sorted along a
 * Morton curve, and the rendered scene (a fence, pipes, molecules on a floor). */
#ifndef CYLBENCH_SCENEGEN_H
#define CYLBENCH_SCENEGEN_H

#include "cylray.h"
#include "rays.h"

/* A cylinder around the segment p0 -> p1 (the endpoint form, built in double). */
cylray_cylinder sg_segment(const double p0[3], const double p1[3], double r, unsigned caps);

/* Bonds of a molecule: atoms on a jittered lattice of spacing 1.4, a bond between
 * lattice neighbours kept with probability 1/2 (about three bonds an atom), radius
 * 0.1-0.2 of the bond's length. Fills out[0..n) from the box corner `base`; returns how
 * many it made. */
int sg_molecule(cylray_cylinder *out, int n, const double base[3], rng *g);
/* Pipes: runs of 4-9 straight segments turning by right angles in a box of `size` from
 * `base`, capped only at the two ends of a run, radius 0.15-0.3. Fills out[0..n). */
int sg_pipes(cylray_cylinder *out, int n, const double base[3], double size, rng *g);
/* Atoms: spheres on a jittered lattice of spacing 1.4, one a lattice point, radius
 * 0.3-0.5 (neighbours may touch, as space-filling atoms do). Fills out[0..n) from the
 * box corner `base`. */
void sg_atoms(cylray_sphere *out, int n, const double base[3], rng *g);
/* Cones on the cylinders' axes and ends, with their flags: a quarter tips (one radius 0,
 * the other 1.3 R), the rest tapered (radii (1 + u) R and (1 - u) R, u in 0.1-0.5, the
 * wide end drawn at random); each cylinder's radius becomes its cone's larger one, so
 * that the cylinders bound the cones for aiming. */
void sg_taper(cylray_cylinder *cyl, cylray_cone *out, int n, rng *g);
/* Sorts the cylinders along a Morton curve of their centers, as a BVH groups them
 * into leaves; -1 when out of memory. */
int sg_morton_sort(cylray_cylinder *c, int n);

/* A scene whose cylinders have a colour and a material: up to max of them. */
enum { SG_MATTE, SG_FLOOR, SG_SHINY };
typedef struct sg_painted {
    int n, max;
    cylray_cylinder *cyl;
    float (*albedo)[3];
    int *mat;
} sg_painted;
/* The rendered scene: a floor, a fence at the back, a pipe run with flanges, a benzene
 * ring and a double helix, all capped (120 cylinders). */
void sg_fence_scene(sg_painted *s);

#endif
