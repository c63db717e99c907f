/* SPDX-License-Identifier: MIT */
/* molecule.c - a ball-and-stick molecule as a molecular viewer draws it: atoms are
 * cylray spheres, bonds cylray cylinders, each shape in a BVH of cylray leaves of its
 * own (bvh.c); camera rays, one shadow ray and a few ambient-occlusion rays a hit, the
 * secondary rays started by the library (cylray_leaf_spawn_origin_side) on the side the
 * tracer shaded; a PNG out.
 *
 *   molecule [-o out.png] [-s WxH] [-n atoms] [-a ao-rays] [-t repeats]
 *
 * Copy it and change what you need. The leaf width is LEAF_WIDTH (4, 8 or 16). With -t
 * it renders the image that many times and prints the time per ray. */
#include "bvh.h"
#include "cylray.h"
#include "png.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* ---- the scene: a folded chain with side chains ----------------------------------- */

enum { CARBON, OXYGEN, NITROGEN, HYDROGEN };
static const float element_colour[4][3] = {
    {0.50f, 0.50f, 0.52f}, {0.88f, 0.12f, 0.10f}, {0.15f, 0.30f, 0.92f}, {0.93f, 0.93f, 0.90f}};
static const float element_radius[4] = {0.40f, 0.36f, 0.37f, 0.25f};
#define BOND_RADIUS 0.12f

typedef struct molecule {
    cylray_sphere *atoms;
    int *element;
    cylray_cylinder *bonds;
    int (*bonded)[2]; /* the atoms at u = 0 and u = 1 of each bond */
    int natoms, nbonds;
} molecule;

static uint64_t rng_state;
static double rnd(void) /* [0, 1): splitmix64 */
{
    uint64_t z = (rng_state += 0x9e3779b97f4a7c15u);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9u;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebu;
    return (double)((z ^ (z >> 31)) >> 11) * 0x1p-53;
}

static int add_bond(molecule *m, int a, int b)
{
    if (cylray_cylinder_from_endpoints(&m->bonds[m->nbonds], m->atoms[a].center,
                                       m->atoms[b].center, BOND_RADIUS, 0) != CYLRAY_OK)
        return -1;
    m->bonded[m->nbonds][0] = a, m->bonded[m->nbonds][1] = b;
    m->nbonds++;
    return 0;
}

/* Whether c keeps 1.25 units from the atoms before it. */
static int clear_of(const molecule *m, const double c[3])
{
    for (int j = 0; j < m->natoms; j++) {
        const float *q = m->atoms[j].center;
        const double e[3] = {q[0] - c[0], q[1] - c[1], q[2] - c[2]};
        if (e[0] * e[0] + e[1] * e[1] + e[2] * e[2] < 1.25 * 1.25)
            return 0;
    }
    return 1;
}

/* A step of 1.45 units from `from` in a random direction, pulled toward `bias`; the
 * new atom's center in c. Returns 0 when none of a few tries keeps clear. */
static int step(const molecule *m, const float from[3], const double bias[3], double c[3])
{
    for (int attempt = 0; attempt < 30; attempt++) {
        const double z = 2 * rnd() - 1, phi = 6.283185307179586 * rnd(), r = sqrt(1 - z * z);
        double d[3] = {r * cos(phi) + bias[0], r * sin(phi) + bias[1], z + bias[2]};
        const double l = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        for (int k = 0; k < 3; k++)
            c[k] = from[k] + 1.45 * d[k] / l;
        if (clear_of(m, c))
            return 1;
    }
    return 0;
}

static int add_atom(molecule *m, const double c[3], int element)
{
    const int i = m->natoms++;
    for (int k = 0; k < 3; k++)
        m->atoms[i].center[k] = (float)c[k];
    m->atoms[i].radius = element_radius[element];
    m->element[i] = element;
    return i;
}

/* n atoms, folded as a small protein is: a backbone that wanders with some persistence
 * inside a ball, every backbone atom carrying a side chain of one to three atoms. The
 * bonds are open tubes, each end inside an atom. */
static int make_molecule(int n, molecule *m)
{
    memset(m, 0, sizeof *m);
    m->atoms = malloc((size_t)n * sizeof *m->atoms);
    m->element = malloc((size_t)n * sizeof *m->element);
    m->bonds = malloc((size_t)n * sizeof *m->bonds);
    m->bonded = malloc((size_t)n * sizeof *m->bonded);
    if (!m->atoms || !m->element || !m->bonds || !m->bonded)
        return -1;
    const double ball = 1.3 * cbrt((double)n);
    double c[3] = {0, 0, 0}, dir[3] = {1, 0, 0};
    int prev = add_atom(m, c, CARBON);
    for (int k = 1; m->natoms < n; k++) {
        const float *p = m->atoms[prev].center;
        const double bias[3] = {0.8 * dir[0] - 0.6 * p[0] / ball,
                                0.8 * dir[1] - 0.6 * p[1] / ball,
                                0.8 * dir[2] - 0.6 * p[2] / ball};
        if (!step(m, p, bias, c)) { /* boxed in: go back along the chain */
            prev = prev > 0 ? prev - 1 : 0;
            if (k > 50 * n)
                return -1;
            continue;
        }
        const int b = add_atom(m, c, k % 3 == 2 ? NITROGEN : CARBON);
        for (int j = 0; j < 3; j++)
            dir[j] = (c[j] - p[j]) / 1.45;
        if (add_bond(m, prev, b))
            return -1;
        prev = b;
        int from = b;
        const double none[3] = {0, 0, 0};
        for (int s = 0, len = 1 + (int)(3 * rnd()); s < len && m->natoms < n; s++) {
            if (!step(m, m->atoms[from].center, none, c))
                break;
            const int e = s + 1 == len ? (rnd() < 0.5 ? HYDROGEN : OXYGEN) : CARBON;
            const int a = add_atom(m, c, e);
            if (add_bond(m, from, a))
                return -1;
            from = a;
        }
    }
    return 0;
}

static cylray_status atom_leaf(void *ctx, leaf_t *leaf, const uint32_t *ids, size_t n)
{
    const molecule *m = ctx;
    cylray_sphere s[LEAF_WIDTH];
    for (size_t i = 0; i < n; i++)
        s[i] = m->atoms[ids[i]];
    return LW(cylray_leaf_prepare_spheres)(leaf, s, ids, n);
}

static cylray_status bond_leaf(void *ctx, leaf_t *leaf, const uint32_t *ids, size_t n)
{
    const molecule *m = ctx;
    cylray_cylinder c[LEAF_WIDTH];
    for (size_t i = 0; i < n; i++)
        c[i] = m->bonds[ids[i]];
    return LW(cylray_leaf_prepare)(leaf, c, ids, n);
}

/* A BVH over the n shapes, each boxed by cylray_bounds of its prepared form. */
static int build_tree(bvh *t, const molecule *m, int spheres)
{
    const int n = spheres ? m->natoms : m->nbonds;
    bvh_item *items = malloc((size_t)n * sizeof *items);
    int rc = items ? 0 : -1;
    for (int i = 0; !rc && i < n; i++) {
        cylray_prepared p;
        cylray_status st = spheres ? cylray_prepare_sphere(&p, &m->atoms[i])
                                   : cylray_prepare(&p, &m->bonds[i]);
        rc = st != CYLRAY_OK || cylray_bounds(&p, items[i].lo, items[i].hi) != CYLRAY_OK;
        items[i].id = (uint32_t)i;
    }
    if (!rc)
        rc = bvh_build(t, items, (size_t)n, spheres ? atom_leaf : bond_leaf, (void *)m);
    free(items);
    return rc;
}

/* ---- tracing and shading ---------------------------------------------------------- */

typedef struct scene {
    molecule m;
    bvh atoms, bonds;
    float light[3];
    int ao_rays;
    long rays[3]; /* camera, shadow, ambient occlusion */
} scene;

/* The closest hit over both trees (the second sees the first's hit as ray->tmax), or
 * whether anything is hit (hit NULL). *leaf and *sphere tell which shape was hit. */
static int trace(const scene *s, cylray_ray1 *ray, cylray_hit1 *hit, const leaf_t **leaf,
                 int *sphere)
{
    if (!hit)
        return bvh_trace(&s->atoms, ray, NULL, 0, NULL) ||
               bvh_trace(&s->bonds, ray, NULL, 0, NULL);
    int found = 0;
    if (bvh_trace(&s->atoms, ray, hit, CYLRAY_NORMAL, leaf))
        found = 1, *sphere = 1;
    if (bvh_trace(&s->bonds, ray, hit, CYLRAY_NORMAL, leaf))
        found = 1, *sphere = 0;
    return found;
}

static float dot3(const float a[3], const float b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void normalize(float v[3])
{
    float l = sqrtf(dot3(v, v));
    for (int k = 0; k < 3; k++)
        v[k] /= l;
}

/* A direction around the unit n with density cos(theta) / pi. */
static void cosine_dir(const float n[3], float w[3])
{
    const double r1 = rnd(), r2 = rnd(), phi = 6.283185307179586 * r1, sr = sqrt(r2);
    float a[3] = {fabsf(n[0]) > 0.5f ? 0.0f : 1.0f, fabsf(n[0]) > 0.5f ? 1.0f : 0.0f, 0};
    float b1[3] = {n[1] * a[2] - n[2] * a[1], n[2] * a[0] - n[0] * a[2],
                   n[0] * a[1] - n[1] * a[0]};
    normalize(b1);
    const float b2[3] = {n[1] * b1[2] - n[2] * b1[1], n[2] * b1[0] - n[0] * b1[2],
                         n[0] * b1[1] - n[1] * b1[0]};
    const float x = (float)(sr * cos(phi)), y = (float)(sr * sin(phi)), z = (float)sqrt(1 - r2);
    for (int k = 0; k < 3; k++)
        w[k] = x * b1[k] + y * b2[k] + z * n[k];
}

static void shade(scene *s, const float o[3], const float d[3], float c[3])
{
    cylray_ray1 ray = {{o[0], o[1], o[2]}, {d[0], d[1], d[2]}, 0.0f, INFINITY};
    cylray_hit1 hit;
    const leaf_t *leaf = NULL;
    int sphere = 0;
    s->rays[0]++;
    if (!trace(s, &ray, &hit, &leaf, &sphere)) {
        const float k = 0.5f + 0.5f * d[1] / sqrtf(dot3(d, d));
        c[0] = 0.12f + 0.2f * k, c[1] = 0.14f + 0.22f * k, c[2] = 0.20f + 0.30f * k;
        return;
    }
    /* the hit point at the kernel's normal (shading and spawning then agree with it),
     * and how far it may lie from the surface */
    float p[3], err;
    LW(cylray_leaf_hit_point_normal)(leaf, &ray, &hit, p, &err);
    int atom = (int)hit.id;
    if (!sphere) { /* each half of a bond takes the colour of its own atom */
        float uv[2];
        LW(cylray_leaf_surface)(leaf, &hit, p, uv, NULL, NULL);
        atom = s->m.bonded[hit.id][uv[0] < 0.5f ? 0 : 1];
    }
    const float *alb = element_colour[s->m.element[atom]];
    float n[3] = {hit.n[0], hit.n[1], hit.n[2]};
    const int outward = dot3(n, d) <= 0; /* the side seen, shaded and spawned from */
    if (!outward)
        for (int k = 0; k < 3; k++)
            n[k] = -n[k];

    float l[3] = {s->light[0] - p[0], s->light[1] - p[1], s->light[2] - p[2]};
    const float dist = sqrtf(dot3(l, l));
    for (int k = 0; k < 3; k++)
        l[k] /= dist;
    float direct = 0;
    const float cosl = dot3(n, l);
    if (cosl > 0) {
        cylray_ray1 sh = {{0, 0, 0}, {l[0], l[1], l[2]}, 0.0f, dist};
        LW(cylray_leaf_spawn_origin_side)(leaf, &hit, p, err, outward, l, sh.o);
        s->rays[1]++;
        if (!trace(s, &sh, NULL, NULL, NULL))
            direct = cosl;
    }
    /* ambient occlusion: the share of short cosine-weighted rays that escape */
    int open = 0;
    for (int i = 0; i < s->ao_rays; i++) {
        cylray_ray1 ao = {{0, 0, 0}, {0, 0, 0}, 0.0f, 2.5f};
        cosine_dir(n, ao.d);
        LW(cylray_leaf_spawn_origin_side)(leaf, &hit, p, err, outward, ao.d, ao.o);
        s->rays[2]++;
        open += !trace(s, &ao, NULL, NULL, NULL);
    }
    const float ambient = s->ao_rays ? (float)open / (float)s->ao_rays : 1.0f;
    for (int k = 0; k < 3; k++)
        c[k] = alb[k] * (0.75f * direct + 0.45f * ambient);
}

/* Processor time, so that other programs on a busy machine do not count. */
static double now(void)
{
    return (double)clock() / CLOCKS_PER_SEC;
}

int main(int argc, char **argv)
{
    const char *out = "molecule.png";
    int w = 320, h = 240, natoms = 400, repeats = 0;
    scene s;
    memset(&s, 0, sizeof s);
    s.ao_rays = 4;
    for (int i = 1; i + 1 < argc; i += 2) {
        if (!strcmp(argv[i], "-o"))
            out = argv[i + 1];
        else if (!strcmp(argv[i], "-s"))
            sscanf(argv[i + 1], "%dx%d", &w, &h);
        else if (!strcmp(argv[i], "-n"))
            natoms = atoi(argv[i + 1]);
        else if (!strcmp(argv[i], "-a"))
            s.ao_rays = atoi(argv[i + 1]);
        else if (!strcmp(argv[i], "-t"))
            repeats = atoi(argv[i + 1]);
    }
    if (w < 1 || h < 1 || natoms < 2 || s.ao_rays < 0 || argc % 2 == 0) {
        fprintf(stderr, "usage: molecule [-o out.png] [-s WxH] [-n atoms>=2] [-a ao-rays] "
                        "[-t repeats]\n");
        return 2;
    }
    rng_state = 0x243f6a8885a308d3u;
    if (make_molecule(natoms, &s.m) || build_tree(&s.atoms, &s.m, 1) ||
        build_tree(&s.bonds, &s.m, 0)) {
        fprintf(stderr, "molecule: the scene cannot be built\n");
        return 1;
    }
    /* the camera outside the molecule's box, looking at its middle; the light above */
    float lo[3] = {FLT_MAX, FLT_MAX, FLT_MAX}, hi[3] = {-FLT_MAX, -FLT_MAX, -FLT_MAX};
    for (int i = 0; i < s.m.natoms; i++)
        for (int k = 0; k < 3; k++) {
            lo[k] = fminf(lo[k], s.m.atoms[i].center[k]);
            hi[k] = fmaxf(hi[k], s.m.atoms[i].center[k]);
        }
    float ctr[3], size = 0;
    for (int k = 0; k < 3; k++) {
        ctr[k] = 0.5f * (lo[k] + hi[k]);
        size = fmaxf(size, hi[k] - lo[k]);
    }
    const float eye[3] = {ctr[0] + 0.8f * size, ctr[1] + 0.2f * size, ctr[2] + 0.3f * size};
    float fwd[3] = {ctr[0] - eye[0], ctr[1] - eye[1], ctr[2] - eye[2]};
    normalize(fwd);
    float up[3] = {0, 0, 1}, right[3] = {fwd[1], -fwd[0], 0};
    normalize(right);
    up[0] = right[1] * fwd[2] - right[2] * fwd[1];
    up[1] = right[2] * fwd[0] - right[0] * fwd[2];
    up[2] = right[0] * fwd[1] - right[1] * fwd[0];
    for (int k = 0; k < 3; k++)
        s.light[k] = eye[k] + size * (k == 2 ? 1.0f : 0.3f);
    uint8_t *img = malloc((size_t)w * (size_t)h * 3);
    if (!img)
        return 1;
    const double t0 = now();
    const int passes = repeats > 0 ? repeats : 1;
    for (int pass = 0; pass < passes; pass++) {
        rng_state = 0x9e3779b97f4a7c15u; /* the same image every pass */
        for (int y = 0; y < h; y++)
            for (int x = 0; x < w; x++) {
                const float sx = (2 * (x + 0.5f) / w - 1) * 0.55f * w / h;
                const float sy = (1 - 2 * (y + 0.5f) / h) * 0.55f;
                float d[3], c[3];
                for (int k = 0; k < 3; k++)
                    d[k] = fwd[k] + sx * right[k] + sy * up[k];
                shade(&s, eye, d, c);
                for (int k = 0; k < 3; k++) {
                    const float v = c[k] <= 0 ? 0 : c[k] >= 1 ? 1 : sqrtf(c[k]);
                    img[((size_t)y * w + x) * 3 + k] = (uint8_t)(v * 255 + 0.5f);
                }
            }
    }
    const double dt = now() - t0;
    uint64_t fnv = 0xcbf29ce484222325u; /* a fingerprint, to compare runs and paths */
    for (size_t i = 0; i < (size_t)w * h * 3; i++)
        fnv = (fnv ^ img[i]) * 0x100000001b3u;
    const long total = s.rays[0] + s.rays[1] + s.rays[2];
    printf("molecule: leaf%d, isa %s, %d atoms, %d bonds; %dx%d; rays: %ld camera, %ld "
           "shadow, %ld ambient occlusion; image fnv %016llx\n",
           LEAF_WIDTH, cylray_kernels_best()->name, s.m.natoms, s.m.nbonds, w, h,
           s.rays[0] / passes, s.rays[1] / passes, s.rays[2] / passes, (unsigned long long)fnv);
    if (repeats > 0)
        printf("time: %.1f ns per ray (%d passes, %.3f s of processor time)\n",
               1e9 * dt / (double)total, passes, dt);
    const int rc = png_write_rgb(out, img, (uint32_t)w, (uint32_t)h);
    if (rc)
        fprintf(stderr, "molecule: cannot write %s\n", out);
    free(img);
    bvh_free(&s.atoms);
    bvh_free(&s.bonds);
    free(s.m.atoms);
    free(s.m.element);
    free(s.m.bonds);
    free(s.m.bonded);
    return rc ? 1 : 0;
}
