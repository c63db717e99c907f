/* SPDX-License-Identifier: MIT */
/* ebscene.c - the four scenes of the Embree comparison, built from a seeded generator.
 *
 * Every vertex is rounded to a grid fine enough for the scene and coarse enough that
 * the midpoint and the difference of two vertices are exact in float; where the
 * directions are free (rods, lattice, pipes) they are integer vectors of integer
 * length, so the half height is exact too. Then Embree's curve (made from the
 * vertices) and cylray's cylinder (centre, axis, half height) describe one solid, and
 * one exact reference judges both. */
#include "ebscene.h"

#include "build.h"
#include "gen.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

double eb_unit(eb_rng *g)
{
    return (double)(cylgen_splitmix64(&g->s) >> 11) * 0x1p-53;
}

double eb_range(eb_rng *g, double a, double b)
{
    return a + (b - a) * eb_unit(g);
}

static const char *const names[EB_NSCENES] = {"molecule",       "pipes",    "far-rods",
                                              "lattice",        "balls",    "far-cloud",
                                              "molecule-taper", "reducers", "far-taper"};

const char *eb_scene_name(int which)
{
    return which >= 0 && which < EB_NSCENES ? names[which] : "?";
}

int eb_scene_find(const char *name)
{
    for (int k = 0; k < EB_NSCENES; k++)
        if (!strcmp(name, names[k]))
            return k;
    return -1;
}

static int grow(void **p, size_t *cap, size_t need, size_t elem)
{
    if (need <= *cap)
        return 0;
    size_t n = *cap ? *cap : 1024;
    while (n < need)
        n *= 2;
    void *q = realloc(*p, n * elem);
    if (!q)
        return -1;
    *p = q;
    *cap = n;
    return 0;
}

uint32_t eb_add_vertex(eb_builder *b, const double p[3])
{
    eb_scene *s = b->s;
    if (grow((void **)&s->vert, &b->cap_v, s->nv + 1, sizeof s->vert[0])) {
        b->failed = 1;
        return 0;
    }
    for (int k = 0; k < 3; k++)
        s->vert[s->nv][k] = (float)(nearbyint(p[k] / b->quantum) * b->quantum);
    return (uint32_t)s->nv++;
}

void eb_add_segment(eb_builder *b, uint32_t v0, unsigned caps)
{
    eb_scene *s = b->s;
    if (grow((void **)&s->first, &b->cap_f, s->ns + 1, sizeof s->first[0]) ||
        grow((void **)&s->caps, &b->cap_c, s->ns + 1, sizeof s->caps[0])) {
        b->failed = 1;
        return;
    }
    s->first[s->ns] = v0;
    s->caps[s->ns] = caps;
    s->ns++;
}

/* Vertex v's radius, in a tapered scene (every vertex gets one). */
void eb_set_vrad(eb_builder *b, uint32_t v, float r)
{
    eb_scene *s = b->s;
    if (grow((void **)&s->vrad, &b->cap_r, (size_t)v + 1, sizeof s->vrad[0])) {
        b->failed = 1;
        return;
    }
    s->vrad[v] = r;
}

/* A sphere at p (rounded to the scene's grid) of radius r. */
void eb_add_sphere(eb_builder *b, const double p[3], float r)
{
    eb_scene *s = b->s;
    if (grow((void **)&s->sph, &b->cap_s, s->nsph + 1, sizeof s->sph[0])) {
        b->failed = 1;
        return;
    }
    for (int k = 0; k < 3; k++)
        s->sph[s->nsph].center[k] = (float)(nearbyint(p[k] / b->quantum) * b->quantum);
    s->sph[s->nsph++].radius = r;
}

/* A polyline through pts[0..n): closed at its two ends only; with radii (a tapered
 * scene), radii[i] at pts[i]. */
static void add_polyline_r(eb_builder *b, const double (*pts)[3], const float *radii, int n)
{
    uint32_t v = 0;
    for (int i = 0; i < n; i++) {
        uint32_t w = eb_add_vertex(b, pts[i]);
        if (radii)
            eb_set_vrad(b, w, radii[i]);
        if (i == 0)
            v = w;
    }
    for (int i = 0; i + 1 < n; i++)
        eb_add_segment(b, v + (uint32_t)i,
                       (i == 0 ? CYLRAY_CAPPED_LO : 0) | (i == n - 2 ? CYLRAY_CAPPED_HI : 0));
}

static void add_polyline(eb_builder *b, const double (*pts)[3], int n)
{
    add_polyline_r(b, pts, NULL, n);
}

void eb_set3(float o[3], double x, double y, double z)
{
    o[0] = (float)x, o[1] = (float)y, o[2] = (float)z;
}

/* Ball-and-stick without the balls: atoms on a jittered cubic lattice, a bond to each
 * of the three forward neighbours with probability 0.92 (about 105,000 bonds). With
 * balls, every atom is a sphere of 2.5 bond radii too (39,304 of them), on the bonds'
 * own rounded vertex. Tapered, the same bonds run between atoms of three kinds, each
 * bond the radius of its atom at either end (0.07, 0.1, 0.13; a third of them between
 * atoms of one kind, cylinders). */
static float atom_radius(int i, int j, int k)
{
    static const float r[3] = {0.07f, 0.1f, 0.13f};
    uint32_t h = (uint32_t)i * 73856093u ^ (uint32_t)j * 19349663u ^ (uint32_t)k * 83492791u;
    return r[(h >> 7) % 3];
}

static void molecule(eb_builder *b, eb_rng *g, int balls, int taper)
{
    enum { N = 34 };
    eb_scene *s = b->s;
    b->quantum = 0x1p-12;
    s->radius = 0.1f;
    static double atom[N][N][N][3];
    for (int i = 0; i < N; i++)
        for (int j = 0; j < N; j++)
            for (int k = 0; k < N; k++) {
                double p[3] = {i, j, k};
                for (int c = 0; c < 3; c++)
                    atom[i][j][k][c] = p[c] + eb_range(g, -0.15, 0.15);
            }
    for (int i = 0; i < N; i++)
        for (int j = 0; j < N; j++)
            for (int k = 0; k < N; k++)
                for (int a = 0; a < 3; a++) {
                    int n[3] = {i, j, k};
                    n[a]++;
                    if (n[a] >= N || eb_unit(g) > 0.92)
                        continue;
                    double pts[2][3];
                    memcpy(pts[0], atom[i][j][k], sizeof pts[0]);
                    memcpy(pts[1], atom[n[0]][n[1]][n[2]], sizeof pts[1]);
                    float r[2] = {atom_radius(i, j, k), atom_radius(n[0], n[1], n[2])};
                    add_polyline_r(b, (const double(*)[3])pts, taper ? r : NULL, 2);
                }
    for (int i = 0; balls && i < N; i++)
        for (int j = 0; j < N; j++)
            for (int k = 0; k < N; k++)
                eb_add_sphere(b, atom[i][j][k], 2.5f * s->radius);
    eb_set3(s->eye, -14, 38.5, -21.5);
    eb_set3(s->look, 16.5, 16.5, 16.5);
    eb_set3(s->light, -30, 80, 10);
    s->fov_deg = 40;
    s->scale = N;
}

/* With reducers: the run starts at 0.3 and, at the end of each piece but the last,
 * with probability 0.4 steps down to the next of 0.24, 0.18, 0.12 through a cone one
 * unit long, the piece's last unit; the rest of the piece and the pieces after are
 * cylinders of the radius reached. Decided by their own generator, so that the runs are
 * the pipes scene's. Writes out[0..) and their radii, returns their count. */
static int reduce(eb_rng *g, const double (*pts)[3], int n, double (*out)[3], float *rad)
{
    static const float steps[4] = {0.3f, 0.24f, 0.18f, 0.12f};
    int m = 0, at = 0;
    for (int i = 0; i < n; i++) {
        if (i > 0 && i < n - 1 && at < 3 && eb_unit(g) < 0.4) {
            /* the last unit of piece i - 1 (2 units long at least) narrows */
            for (int c = 0; c < 3; c++) {
                double dlt = pts[i][c] - pts[i - 1][c];
                out[m][c] = pts[i][c] - (dlt > 0 ? 1 : dlt < 0 ? -1 : 0);
            }
            rad[m++] = steps[at++];
        }
        memcpy(out[m], pts[i], sizeof out[m]);
        rad[m++] = steps[at];
    }
    return m;
}

/* A plant's pipe runs: Manhattan polylines on an integer grid in a 60^3 box, 3-11
 * straight pieces of length 2-7 each, never turning back on themselves (two runs may
 * share a stretch of grid line: coincident surfaces, where either answer is right).
 * With reducers, narrowing along the run (reduce). */
static void pipes(eb_builder *b, eb_rng *g, int reducers)
{
    eb_rng gr = {g->s ^ 0x7265647563657273ull};
    eb_scene *s = b->s;
    b->quantum = 1;
    s->radius = 0.3f;
    for (int p = 0; p < 500; p++) {
        double pts[12][3];
        for (int c = 0; c < 3; c++)
            pts[0][c] = floor(eb_range(g, 0, 60));
        int n = 4 + (int)(eb_unit(g) * 8), last = -1;
        for (int i = 1; i < n; i++) {
            int a;
            do
                a = (int)(eb_unit(g) * 3);
            while (a == last);
            last = a;
            memcpy(pts[i], pts[i - 1], sizeof pts[i]);
            const double sign = eb_unit(g) < 0.5 ? -1 : 1;
            double step = sign * floor(eb_range(g, 2, 8));
            if (pts[i][a] + step < 0 || pts[i][a] + step > 60)
                step = -step; /* stay in the plant's box, away from the camera */
            pts[i][a] += step;
        }
        if (reducers) {
            double out[24][3];
            float rad[24];
            int m = reduce(&gr, (const double(*)[3])pts, n, out, rad);
            add_polyline_r(b, (const double(*)[3])out, rad, m);
        } else {
            add_polyline(b, (const double(*)[3])pts, n);
        }
    }
    eb_set3(s->eye, -35, 75, -45);
    eb_set3(s->look, 30, 28, 30);
    eb_set3(s->light, 10, 120, -20);
    s->fov_deg = 45;
    s->scale = 60;
}

/* Integer vectors of integer length (a^2 + b^2 + c^2 = m^2): the coordinate axes, and
 * tilts of 1.1 to 6.4 degrees off them ((m^2 - 1, 2m, m^2 + 1) for m = 100, 60, 30, 18).
 * Rods near an axis keep their boxes slim, so the BVH stays useful for rods this long. */
static const int quads[][4] = {{0, 0, 1, 1},         {0, 0, 1, 1},      {0, 200, 9999, 10001},
                               {0, 120, 3599, 3601}, {0, 60, 899, 901}, {0, 36, 323, 325}};

/* A direction from the table, its coordinates permuted and signed; *len = m. */
static void int_direction(eb_rng *g, double out[3], double *len)
{
    const int *q = quads[(int)(eb_unit(g) * (sizeof quads / sizeof quads[0]))];
    int perm = (int)(eb_unit(g) * 6);
    static const int P[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2},
                                {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    for (int c = 0; c < 3; c++)
        out[c] = q[P[perm][c]] * (eb_unit(g) < 0.5 ? -1 : 1);
    *len = q[3];
}

/* Long thin rods (length 1e4 radii) around a point 48,000 units from the world origin,
 * the camera among them: every coordinate is large, every radius small. Tapered: the
 * same rods, each narrowing from 0.25 at its first end to a radius of 1/16 to 1/4 at
 * its other (steps of 1/64, drawn by their own generator). */
static void far_rods(eb_builder *b, eb_rng *g, int taper)
{
    eb_rng gt = {g->s ^ 0x7461706572656421ull};
    eb_scene *s = b->s;
    b->quantum = 0x1p-6;
    s->radius = 0.25f;
    const double C[3] = {41000, 23000, 11000};
    for (int r = 0; r < 1000; r++) {
        double c[3], u[3], m;
        for (int k = 0; k < 3; k++)
            c[k] = nearbyint((C[k] + eb_range(g, -150, 150)) * 64) / 64;
        /* half length about 1250 = 5e3 radii, exact: a multiple of 1/16 per unit of m */
        int_direction(g, u, &m);
        double sc = nearbyint(1250 / m * 16) / 16;
        double pts[2][3];
        for (int k = 0; k < 3; k++)
            pts[0][k] = c[k] - sc * u[k], pts[1][k] = c[k] + sc * u[k];
        float rad[2] = {0.25f, (float)(4 + (int)(eb_unit(&gt) * 13)) / 64};
        add_polyline_r(b, (const double(*)[3])pts, taper ? rad : NULL, 2);
    }
    eb_set3(s->eye, C[0] - 260, C[1] + 40, C[2] - 190);
    eb_set3(s->look, C[0], C[1], C[2]);
    eb_set3(s->light, C[0] - 300, C[1] + 3000, C[2] + 200);
    s->fov_deg = 30;
    s->scale = 300;
}

/* Dust far away: 100,000 spheres of radius 0.04 in a 60^3 box around a point 1,200
 * units from the origin, seen from 1,500 units (3.75e4 radii) through a narrow lens,
 * each sphere about half a pixel across: grazing and sub-pixel hits, where o - c and
 * the discriminant lose the most. (Not 48,000 away as the far rods: there floats are
 * 0.004 apart, a tenth of the radius, and a spawned origin no longer clears the
 * sphere by the margin cylray_spawn_origin promises under its condition.) */
static void far_cloud(eb_builder *b, eb_rng *g)
{
    eb_scene *s = b->s;
    b->quantum = 0x1p-12;
    s->radius = 0.04f;
    const double C[3] = {1000, 600, 300};
    for (int i = 0; i < 100000; i++) {
        double p[3];
        for (int k = 0; k < 3; k++)
            p[k] = C[k] + eb_range(g, -30, 30);
        eb_add_sphere(b, p, s->radius);
    }
    eb_set3(s->eye, C[0] - 1200, C[1] + 300, C[2] - 840);
    eb_set3(s->look, C[0], C[1], C[2]);
    eb_set3(s->light, C[0] - 300, C[1] + 3000, C[2] + 200);
    s->fov_deg = 3;
    s->scale = 60;
}

/* A jungle gym: rods along x, y and z through every point of a 21^3 grid of spacing 2,
 * each line one polyline, seen from a point on the axis of the middle z rod and in the
 * plane of a layer of x rods: rays run down that rod's axis and edge-on along the
 * layer. */
static void lattice(eb_builder *b)
{
    enum { K = 21 };
    eb_scene *s = b->s;
    b->quantum = 1;
    s->radius = 0.08f;
    for (int a = 0; a < 3; a++)
        for (int i = 0; i < K; i++)
            for (int j = 0; j < K; j++) {
                double pts[K][3];
                for (int t = 0; t < K; t++) {
                    int idx[3];
                    idx[a] = t, idx[(a + 1) % 3] = i, idx[(a + 2) % 3] = j;
                    for (int c = 0; c < 3; c++)
                        pts[t][c] = 2.0 * idx[c];
                }
                add_polyline(b, (const double(*)[3])pts, K);
            }
    eb_set3(s->eye, 20, 20, 75);
    eb_set3(s->look, 20, 20, 0);
    eb_set3(s->light, 55, 70, 90);
    s->fov_deg = 50;
    s->scale = 40;
}

int eb_scene_finish(eb_builder *b)
{
    eb_scene *s = b->s;
    size_t n1 = s->ns ? s->ns : 1;
    if (b->failed || !(s->cyl = malloc(n1 * sizeof *s->cyl)) ||
        !(s->p0 = malloc(n1 * sizeof *s->p0)) || !(s->p1 = malloc(n1 * sizeof *s->p1)))
        return -1;
    for (size_t i = 0; i < s->nsph; i++) {
        cylray_prepared p;
        if (cylray_prepare_sphere(&p, &s->sph[i]) != CYLRAY_OK) {
            fprintf(stderr, "ebscene: %s sphere %zu refused\n", s->name, i);
            return -1;
        }
    }
    for (size_t i = 0; i < s->ns; i++) {
        memcpy(s->p0[i], s->vert[s->first[i]], sizeof s->p0[i]);
        memcpy(s->p1[i], s->vert[s->first[i] + 1], sizeof s->p1[i]);
    }
    if (s->vrad && !(s->cone = malloc(n1 * sizeof *s->cone)))
        return -1;
    for (size_t i = 0; i < s->ns; i++) {
        float r = s->radius;
        if (s->vrad) {
            cylray_cone *c = &s->cone[i];
            memcpy(c->p0, s->p0[i], sizeof c->p0);
            memcpy(c->p1, s->p1[i], sizeof c->p1);
            c->r0 = s->vrad[s->first[i]], c->r1 = s->vrad[s->first[i] + 1];
            c->flags = s->caps[i];
            r = fmaxf(c->r0, c->r1);
            cylray_prepared p;
            if (cylray_prepare_cone(&p, c) != CYLRAY_OK)
                r = -1;
        }
        if (r < 0 || cylray_cylinder_from_endpoints(&s->cyl[i], s->vert[s->first[i]],
                                                    s->vert[s->first[i] + 1], r,
                                                    s->caps[i]) != CYLRAY_OK) {
            fprintf(stderr, "ebscene: %s segment %zu refused\n", s->name, i);
            return -1;
        }
    }
    s->up[0] = 0, s->up[1] = 1, s->up[2] = 0;
    return 0;
}

int eb_scene_make(eb_scene *s, int which, uint64_t seed)
{
    memset(s, 0, sizeof *s);
    snprintf(s->name, sizeof s->name, "%s", eb_scene_name(which));
    eb_builder b = {.s = s};
    eb_rng g = {seed * 0x2545f4914f6cdd1dull + (uint64_t)which};
    switch (which) {
    case EB_MOLECULE:
    case EB_BALLS:
    case EB_MOLECULE_TAPER:
        /* the balls' molecule is the molecule's, bond for bond: the same draws */
        g.s = seed * 0x2545f4914f6cdd1dull + (uint64_t)EB_MOLECULE;
        molecule(&b, &g, which == EB_BALLS, which == EB_MOLECULE_TAPER);
        break;
    case EB_FAR_CLOUD:
        far_cloud(&b, &g);
        break;
    case EB_PIPES:
    case EB_REDUCERS:
        g.s = seed * 0x2545f4914f6cdd1dull + (uint64_t)EB_PIPES;
        pipes(&b, &g, which == EB_REDUCERS);
        break;
    case EB_FAR_RODS:
    case EB_FAR_TAPER:
        g.s = seed * 0x2545f4914f6cdd1dull + (uint64_t)EB_FAR_RODS;
        far_rods(&b, &g, which == EB_FAR_TAPER);
        break;
    case EB_LATTICE:
        lattice(&b);
        break;
    default:
        return -1;
    }
    if (eb_scene_finish(&b)) {
        eb_scene_free(s);
        return -1;
    }
    return 0;
}

void eb_scene_free(eb_scene *s)
{
    free(s->vrad);
    free(s->cone);
    free(s->vert);
    free(s->first);
    free(s->caps);
    free(s->cyl);
    free(s->p0);
    free(s->p1);
    free(s->sph);
    memset(s, 0, sizeof *s);
}
