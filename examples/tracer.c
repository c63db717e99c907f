/* SPDX-License-Identifier: MIT */
/* tracer.c - a small ray tracer over cylray leaves: a molecule of bonds, a binned-SAH
 * BVH whose leaves are cylray leaves, camera, shadow and bounce rays one at a time
 * (started with cylray_leaf_spawn_origin_side8 on the side the tracer shaded),
 * bonds coloured by their surface coordinate u, a PNG out.
 *
 *   tracer [-o out.png] [-s WxH] [-n atoms] [-t repeats] [-c | -p]
 *
 * Copy it and change what you need. The leaf width is LEAF_WIDTH (4, 8 or 16; the
 * build makes one program of each). With -t it renders the image that many times and
 * prints the time per ray. -c traces camera rays only (shaded by u and the normal);
 * -p traces those in packets of eight (4 x 2 pixels) with cylray_intersect8 at the
 * leaves, for comparison with the single-ray leaf path of -c. */
#include "bvh.h"
#include "cylray.h"
#include "png.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* ---- the scene: atoms on a branching chain, a bond between neighbours ------------ */

typedef struct atom {
    float p[3];
    int type; /* index into atom_colour */
} atom;

static const float atom_colour[4][3] = {
    {0.55f, 0.55f, 0.58f}, /* carbon */
    {0.85f, 0.15f, 0.12f}, /* oxygen */
    {0.15f, 0.30f, 0.90f}, /* nitrogen */
    {0.92f, 0.92f, 0.88f}, /* hydrogen */
};

typedef struct bond {
    int a, b; /* the atoms at u = 0 (p0) and u = 1 (p1) */
} bond;

static uint64_t rng_state = 0x9e3779b97f4a7c15u;
static double rnd(void) /* [0, 1): splitmix64 */
{
    uint64_t z = (rng_state += 0x9e3779b97f4a7c15u);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9u;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebu;
    return (double)((z ^ (z >> 31)) >> 11) * 0x1p-53;
}

/* n atoms: each new one 1.5 units from an earlier one, in a random direction that
 * keeps it at least 1.2 units from the others (when a few tries find one). */
static int make_molecule(int n, atom **atoms_out, bond **bonds_out)
{
    atom *at = calloc((size_t)n, sizeof *at);
    bond *bd = calloc((size_t)n, sizeof *bd);
    if (!at || !bd)
        return -1;
    int nb = 0;
    for (int i = 1; i < n; i++) {
        int from = 0;
        for (int attempt = 0; attempt < 20; attempt++) {
            from = (int)(rnd() * i);
            double z = 2 * rnd() - 1, phi = 6.283185307179586 * rnd(), s = sqrt(1 - z * z);
            double d[3] = {s * cos(phi), s * sin(phi), z};
            for (int k = 0; k < 3; k++)
                at[i].p[k] = at[from].p[k] + (float)(1.5 * d[k]);
            int clear = 1;
            for (int j = 0; j < i && clear; j++) {
                float e[3] = {at[j].p[0] - at[i].p[0], at[j].p[1] - at[i].p[1],
                              at[j].p[2] - at[i].p[2]};
                clear = e[0] * e[0] + e[1] * e[1] + e[2] * e[2] >= 1.44f;
            }
            if (clear)
                break;
        }
        at[i].type = rnd() < 0.5 ? 0 : (int)(1 + 3 * rnd());
        bd[nb].a = from, bd[nb].b = i, nb++;
    }
    *atoms_out = at;
    *bonds_out = bd;
    return nb;
}

/* The BVH's leaves: the bonds ids[0..n) of the cylinders ctx. */
static cylray_status bond_leaf(void *ctx, leaf_t *leaf, const uint32_t *ids, size_t n)
{
    const cylray_cylinder *cyl = ctx;
    cylray_cylinder c[LEAF_WIDTH];
    for (size_t i = 0; i < n; i++)
        c[i] = cyl[ids[i]];
    return LW(cylray_leaf_prepare)(leaf, c, ids, n);
}

/* ---- shading ----------------------------------------------------------------------- */

typedef struct scene {
    bvh t;
    cylray_prepared *prep; /* for the packet path only: 192 bytes a cylinder */
    const atom *atoms;
    const bond *bonds;
    float light[3];
    long rays[3]; /* camera, shadow, bounce */
} scene;

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

static void sky(const float d[3], float c[3])
{
    float s = 0.5f + 0.5f * d[1] / sqrtf(dot3(d, d));
    c[0] = 0.20f + 0.35f * s, c[1] = 0.25f + 0.40f * s, c[2] = 0.35f + 0.50f * s;
}

/* A direction around n with density cos(theta) / pi. */
static void cosine_dir(const float n[3], float w[3])
{
    double r1 = rnd(), r2 = rnd(), phi = 6.283185307179586 * r1, s = sqrt(r2);
    /* any frame around n */
    float a[3] = {fabsf(n[0]) > 0.5f ? 0.0f : 1.0f, fabsf(n[0]) > 0.5f ? 1.0f : 0.0f, 0};
    float b1[3] = {n[1] * a[2] - n[2] * a[1], n[2] * a[0] - n[0] * a[2],
                   n[0] * a[1] - n[1] * a[0]};
    normalize(b1);
    float b2[3] = {n[1] * b1[2] - n[2] * b1[1], n[2] * b1[0] - n[0] * b1[2],
                   n[0] * b1[1] - n[1] * b1[0]};
    float x = (float)(s * cos(phi)), y = (float)(s * sin(phi)), z = (float)sqrt(1 - r2);
    for (int k = 0; k < 3; k++)
        w[k] = x * b1[k] + y * b2[k] + z * n[k];
}

static void radiance(scene *s, const float o[3], const float d[3], float c[3])
{
    cylray_ray1 ray = {{o[0], o[1], o[2]}, {d[0], d[1], d[2]}, 0.0f, INFINITY};
    cylray_hit1 hit;
    const leaf_t *leaf = NULL;
    s->rays[0]++;
    if (!bvh_trace(&s->t, &ray, &hit, CYLRAY_NORMAL, &leaf)) {
        sky(d, c);
        return;
    }
    /* where the ray met the surface (at the azimuth of the kernel's normal, so that
     * shading and spawning agree with it), and how far that point may be from it */
    float p[3], err;
    LW(cylray_leaf_hit_point_normal)(leaf, &ray, &hit, p, &err);
    /* u runs from the bond's first atom (p0, u = 0) to its second: each half takes the
     * colour of its own atom */
    float uv[2];
    LW(cylray_leaf_surface)(leaf, &hit, p, uv, NULL, NULL);
    const bond *b = &s->bonds[hit.id];
    const float *alb = atom_colour[s->atoms[uv[0] < 0.5f ? b->a : b->b].type];
    float n[3] = {hit.n[0], hit.n[1], hit.n[2]};
    /* the side we see, and shade, and start the new rays on: the outward normal's side
     * unless the ray came from inside (through an open end) */
    const int outward = dot3(n, d) <= 0;
    if (!outward)
        for (int k = 0; k < 3; k++)
            n[k] = -n[k];
    /* a thin dark seam at the bond's middle, to show u */
    float seam = fabsf(uv[0] - 0.5f) < 0.02f ? 0.3f : 1.0f;

    /* direct light: a shadow ray from the spawned origin, ending at the light */
    float l[3] = {s->light[0] - p[0], s->light[1] - p[1], s->light[2] - p[2]};
    float dist = sqrtf(dot3(l, l)), direct = 0;
    for (int k = 0; k < 3; k++)
        l[k] /= dist;
    float cosl = dot3(n, l);
    if (cosl > 0) {
        cylray_ray1 sh;
        LW(cylray_leaf_spawn_origin_side)(leaf, &hit, p, err, outward, l, sh.o);
        memcpy(sh.d, l, sizeof l);
        sh.tmin = 0.0f;
        sh.tmax = dist;
        s->rays[1]++;
        if (!bvh_trace(&s->t, &sh, NULL, 0, NULL))
            direct = cosl;
    }
    /* one diffuse bounce: sky light unless the bounce meets another bond */
    float w[3], bounce[3] = {0, 0, 0};
    cosine_dir(n, w);
    cylray_ray1 br;
    LW(cylray_leaf_spawn_origin_side)(leaf, &hit, p, err, outward, w, br.o);
    memcpy(br.d, w, sizeof w);
    br.tmin = 0.0f;
    br.tmax = INFINITY;
    s->rays[2]++;
    if (!bvh_trace(&s->t, &br, NULL, 0, NULL))
        sky(w, bounce);
    for (int k = 0; k < 3; k++)
        c[k] = seam * alb[k] * (0.8f * direct + 0.6f * bounce[k]);
}

/* ---- packets: eight camera rays at a time through the same BVH -------------------- */

/* The closest hits of the eight rays of *r (lanes in `active`), cylinder by cylinder
 * with cylray_intersect8 at the leaves: a node is visited when any lane's ray meets its
 * box. id[lane] gets the hit cylinder. */
static uint32_t trace8(const scene *s, cylray_ray8 *r, cylray_hit8 *h, uint32_t active,
                       uint32_t id[8])
{
    float inv[3][8];
    for (int i = 0; i < 8; i++) {
        inv[0][i] = 1.0f / r->dx[i], inv[1][i] = 1.0f / r->dy[i], inv[2][i] = 1.0f / r->dz[i];
    }
    uint32_t stack[64], got = 0;
    int sp = 0;
    stack[sp++] = 0;
    while (sp) {
        const bvh_node *nd = &s->t.nodes[stack[--sp]];
        uint32_t m = 0;
        for (int i = 0; i < 8; i++) {
            const float o[3] = {r->ox[i], r->oy[i], r->oz[i]};
            const float iv[3] = {inv[0][i], inv[1][i], inv[2][i]};
            m |= (uint32_t)bvh_hits_box(nd, o, iv, r->tmin[i], r->tmax[i]) << i;
        }
        m &= active;
        if (!m)
            continue;
        if (nd->count) {
            for (uint32_t j = 0; j < nd->count; j++) {
                uint32_t cid = s->t.leaf_ids[nd->index * LEAF_WIDTH + j];
                uint32_t hm = cylray_intersect8(&s->prep[cid], r, h, m, CYLRAY_NORMAL);
                for (int i = 0; i < 8; i++)
                    if ((hm >> i) & 1u)
                        id[i] = cid;
                got |= hm;
            }
            continue;
        }
        stack[sp++] = nd->index + 1;
        stack[sp++] = nd->index;
    }
    return got;
}

/* Camera rays only, shaded by u and the normal: the single-ray path. */
static void camera_only1(scene *s, const float o[3], const float d[3], float c[3])
{
    cylray_ray1 ray = {{o[0], o[1], o[2]}, {d[0], d[1], d[2]}, 0.0f, INFINITY};
    cylray_hit1 hit;
    const leaf_t *leaf = NULL;
    s->rays[0]++;
    if (!bvh_trace(&s->t, &ray, &hit, CYLRAY_NORMAL, &leaf)) {
        sky(d, c);
        return;
    }
    float p[3], err, uv[2];
    LW(cylray_leaf_hit_point_normal)(leaf, &ray, &hit, p, &err);
    LW(cylray_leaf_surface)(leaf, &hit, p, uv, NULL, NULL);
    const bond *b = &s->bonds[hit.id];
    const float *alb = atom_colour[s->atoms[uv[0] < 0.5f ? b->a : b->b].type];
    float k = fabsf(dot3(hit.n, d)) / sqrtf(dot3(d, d));
    for (int j = 0; j < 3; j++)
        c[j] = alb[j] * (0.2f + 0.8f * k);
}

/* The same eight at a time. */
static void camera_only8(scene *s, const float o[3], float d[8][3], float c[8][3])
{
    cylray_ray8 r;
    cylray_hit8 h;
    uint32_t id[8];
    for (int i = 0; i < 8; i++) {
        r.ox[i] = o[0], r.oy[i] = o[1], r.oz[i] = o[2];
        r.dx[i] = d[i][0], r.dy[i] = d[i][1], r.dz[i] = d[i][2];
        r.tmin[i] = 0.0f, r.tmax[i] = INFINITY;
    }
    s->rays[0] += 8;
    uint32_t m = trace8(s, &r, &h, 0xffu, id);
    for (int i = 0; i < 8; i++) {
        if (!((m >> i) & 1u)) {
            sky(d[i], c[i]);
            continue;
        }
        const cylray_prepared *P = &s->prep[id[i]];
        float p[3], err, uv[2];
        const float oi[3] = {r.ox[i], r.oy[i], r.oz[i]};
        const float ni[3] = {h.nx[i], h.ny[i], h.nz[i]};
        cylray_hit_point_normal(P, oi, d[i], h.t[i], h.part[i], ni, p, &err);
        cylray_surface(P, p, h.part[i], uv, NULL, NULL);
        const bond *b = &s->bonds[id[i]];
        const float *alb = atom_colour[s->atoms[uv[0] < 0.5f ? b->a : b->b].type];
        const float n[3] = {h.nx[i], h.ny[i], h.nz[i]};
        float k = fabsf(dot3(n, d[i])) / sqrtf(dot3(d[i], d[i]));
        for (int j = 0; j < 3; j++)
            c[i][j] = alb[j] * (0.2f + 0.8f * k);
    }
}

/* Processor time, so that other programs on a busy machine do not count. */
static double now(void)
{
    return (double)clock() / CLOCKS_PER_SEC;
}

int main(int argc, char **argv)
{
    const char *out = "tracer.png";
    int w = 320, h = 240, natoms = 400, repeats = 0, camera_only = 0, packets = 0;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "-c")) {
            camera_only = 1;
            continue;
        }
        if (!strcmp(argv[i], "-p")) {
            camera_only = packets = 1;
            continue;
        }
        if (i + 1 == argc)
            break;
        if (!strcmp(argv[i], "-o"))
            out = argv[i + 1];
        else if (!strcmp(argv[i], "-s"))
            sscanf(argv[i + 1], "%dx%d", &w, &h);
        else if (!strcmp(argv[i], "-n"))
            natoms = atoi(argv[i + 1]);
        else if (!strcmp(argv[i], "-t"))
            repeats = atoi(argv[i + 1]);
        i++;
    }
    if (w < 1 || h < 1 || natoms < 2) {
        fprintf(stderr, "usage: tracer [-o out.png] [-s WxH] [-n atoms>=2] [-t repeats] "
                        "[-c | -p]\n");
        return 2;
    }
    atom *atoms;
    bond *bonds;
    int nb = make_molecule(natoms, &atoms, &bonds);
    if (nb < 1)
        return 1;
    /* the bonds in endpoint form: capped, u = 0 at atom a */
    cylray_cylinder *cyl = malloc((size_t)nb * sizeof *cyl);
    float lo[3] = {FLT_MAX, FLT_MAX, FLT_MAX}, hi[3] = {-FLT_MAX, -FLT_MAX, -FLT_MAX};
    for (int i = 0; i < nb; i++) {
        if (cylray_cylinder_from_endpoints(&cyl[i], atoms[bonds[i].a].p, atoms[bonds[i].b].p,
                                           0.18f, CYLRAY_CAPPED) != CYLRAY_OK)
            return 1;
        for (int k = 0; k < 3; k++) {
            lo[k] = fminf(lo[k], atoms[bonds[i].b].p[k]);
            hi[k] = fmaxf(hi[k], atoms[bonds[i].b].p[k]);
        }
    }
    scene s;
    memset(&s, 0, sizeof s);
    s.atoms = atoms, s.bonds = bonds;
    bvh_item *items = malloc((size_t)nb * sizeof *items);
    for (int i = 0; items && i < nb; i++) {
        cylray_prepared p;
        if (cylray_prepare(&p, &cyl[i]) != CYLRAY_OK ||
            cylray_bounds(&p, items[i].lo, items[i].hi))
            return 1;
        items[i].id = (uint32_t)i;
    }
    if (!items || bvh_build(&s.t, items, (size_t)nb, bond_leaf, cyl)) {
        fprintf(stderr, "tracer: BVH build failed\n");
        return 1;
    }
    if (packets) {
        /* the packet calls take one prepared cylinder each: 192 bytes beside the
         * leaves' 64 */
        s.prep = aligned_alloc(_Alignof(cylray_prepared), (size_t)nb * sizeof *s.prep);
        for (int i = 0; s.prep && i < nb; i++)
            cylray_prepare(&s.prep[i], &cyl[i]);
        if (!s.prep)
            return 1;
    }
    /* camera on the molecule's box, looking at its center */
    float ctr[3], size = 0;
    for (int k = 0; k < 3; k++) {
        ctr[k] = 0.5f * (lo[k] + hi[k]);
        size = fmaxf(size, hi[k] - lo[k]);
    }
    float eye[3] = {ctr[0] + 0.2f * size, ctr[1] + 0.3f * size, ctr[2] + 0.9f * size};
    float fwd[3] = {ctr[0] - eye[0], ctr[1] - eye[1], ctr[2] - eye[2]};
    normalize(fwd);
    float right[3] = {-fwd[2], 0, fwd[0]};
    normalize(right);
    float up[3] = {right[1] * fwd[2] - right[2] * fwd[1], right[2] * fwd[0] - right[0] * fwd[2],
                   right[0] * fwd[1] - right[1] * fwd[0]};
    for (int k = 0; k < 3; k++)
        s.light[k] = ctr[k] + size * (k == 1 ? 2.0f : 0.5f);
    uint8_t *img = malloc((size_t)w * (size_t)h * 3);
    if (!img)
        return 1;
    double t0 = now();
    int passes = repeats > 0 ? repeats : 1;
    for (int pass = 0; pass < passes; pass++) {
        rng_state = 0x9e3779b97f4a7c15u; /* the same image every pass */
        /* tiles of 4 x 2 pixels: eight rays that a packet traces together */
        for (int ty = 0; ty < h; ty += 2)
            for (int tx = 0; tx < w; tx += 4) {
                float d[8][3], c[8][3];
                int px[8], py[8];
                for (int i = 0; i < 8; i++) {
                    int x = tx + i % 4, y = ty + i / 4;
                    px[i] = x < w ? x : w - 1, py[i] = y < h ? y : h - 1;
                    float sx = (2 * (px[i] + 0.5f) / w - 1) * 0.6f * w / h;
                    float sy = (1 - 2 * (py[i] + 0.5f) / h) * 0.6f;
                    for (int k = 0; k < 3; k++)
                        d[i][k] = fwd[k] + sx * right[k] + sy * up[k];
                }
                if (packets)
                    camera_only8(&s, eye, d, c);
                for (int i = 0; i < 8 && !packets; i++) {
                    if (camera_only)
                        camera_only1(&s, eye, d[i], c[i]);
                    else
                        radiance(&s, eye, d[i], c[i]);
                }
                for (int i = 0; i < 8; i++)
                    for (int k = 0; k < 3; k++) {
                        float v = c[i][k] <= 0 ? 0 : c[i][k] >= 1 ? 1 : sqrtf(c[i][k]);
                        img[((size_t)py[i] * w + px[i]) * 3 + k] = (uint8_t)(v * 255 + 0.5f);
                    }
            }
    }
    double dt = now() - t0;
    /* a fingerprint of the image, to compare runs and paths */
    uint64_t fnv = 0xcbf29ce484222325u;
    for (size_t i = 0; i < (size_t)w * h * 3; i++)
        fnv = (fnv ^ img[i]) * 0x100000001b3u;
    long total = s.rays[0] + s.rays[1] + s.rays[2];
    printf("tracer: %s, isa %s, %d bonds, %zu nodes, %zu leaves; %dx%d; "
           "rays: %ld camera, %ld shadow, %ld bounce; image fnv %016llx\n",
           packets           ? "packets of 8"
           : LEAF_WIDTH == 4 ? "leaf4"
           : LEAF_WIDTH == 8 ? "leaf8"
                             : "leaf16",
           cylray_kernels_best()->name, nb, s.t.nnodes, s.t.nleaves, w, h, s.rays[0] / passes,
           s.rays[1] / passes, s.rays[2] / passes, (unsigned long long)fnv);
    if (repeats > 0)
        printf("time: %.1f ns per ray (%d passes, %.3f s of processor time)\n",
               1e9 * dt / (double)total, passes, dt);
    int rc = png_write_rgb(out, img, (uint32_t)w, (uint32_t)h);
    if (rc)
        fprintf(stderr, "tracer: cannot write %s\n", out);
    free(img);
    free(cyl);
    free(atoms);
    free(bonds);
    free(items);
    bvh_free(&s.t);
    free(s.prep);
    return rc ? 1 : 0;
}
