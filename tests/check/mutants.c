/* SPDX-License-Identifier: MIT */
/* mutants.c - the checker's own test: a path that is the scalar kernel with one defect
 * put in on purpose must fail cylcheck's criteria, each defect by the rule meant to
 * catch it; the unchanged scalar kernel must pass them. A checker that cannot fail
 * checks nothing. */
#include "check.h"
#include "sphkernel.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum {
    MUT_NONE,
    MUT_T_FAR,          /* t off by 1e-4 relative: outside any ordinary band */
    MUT_T_3ULPS,        /* t off by 3 ulps: inside the band, caught by the headline p99 */
    MUT_DROP,           /* every 7th hit reported as a miss */
    MUT_RIM_DROP,       /* misses a ray whose hit is within 1e-3 of a cap plane */
    MUT_BACKFACE,       /* front hits reported as back faces */
    MUT_PART,           /* side and caps swapped around */
    MUT_CULL_IGNORED,   /* CYLRAY_CULL_BACK ignored */
    MUT_WRITE_INACTIVE, /* writes t of an inactive lane */
    MUT_NO_TMAX,        /* leaves tmax alone on a hit */
    MUT_NORMAL_LEN,     /* normal 1.0001 long */
    MUT_NORMAL_TILT,    /* normal turned by about 3e-5 rad */
    MUT_NO_FF,          /* CYLRAY_FACE_FORWARD ignored */
    MUT_NORMAL_ALWAYS,  /* writes normals without CYLRAY_NORMAL */
    MUT_OCCLUDED,       /* occluded disagrees with intersect in lane 0 */
    MUT_OVERRUN,        /* stream writes one t past its end */
    MUT_COUNT
};

static const char *const mut_names[MUT_COUNT] = {
    "none",
    "t 1e-4 off",
    "t 3 ulps off",
    "every 7th hit dropped",
    "hits near a cap plane dropped",
    "front hit as back face",
    "parts rotated",
    "cull ignored",
    "inactive lane written",
    "tmax not set",
    "normal too long",
    "normal tilted",
    "face-forward ignored",
    "normal written without NORMAL",
    "occluded differs",
    "stream overrun",
};

static int mutation;
static const cylray_kernels *real;
static long hit_counter;

static float bump(float t, float ulps)
{
    return t + ulps * (float)cylref_float_ulp(t);
}

/* Applies the mutation to lanes [0, n) of one call's outputs. before_t/before_tmax:
 * the arrays as they were before the real call (to undo a hit). */
static uint32_t mutate(uint32_t m, uint32_t active, size_t n, unsigned flags, float *tmax,
                       const float *before_tmax, float *t, const float *before_t, float *nx,
                       float *ny, float *nz, int32_t *part, const float *dz_axis_z,
                       const cylray_prepared *p)
{
    (void)dz_axis_z;
    for (size_t j = 0; j < n; j++) {
        int hit = (m >> j & 1) != 0;
        if (!hit) {
            if (mutation == MUT_WRITE_INACTIVE && !(active >> j & 1))
                t[j] = 0.0f;
            continue;
        }
        hit_counter++;
        switch (mutation) {
        case MUT_T_FAR:
            t[j] *= 1.0001f;
            tmax[j] = t[j];
            break;
        case MUT_T_3ULPS:
            t[j] = bump(t[j], 3);
            tmax[j] = t[j];
            break;
        case MUT_DROP:
        case MUT_RIM_DROP: {
            int drop = mutation == MUT_DROP ? hit_counter % 7 == 0 : 0;
            if (mutation == MUT_RIM_DROP && p->h_v < INFINITY && (part[j] & 0xf) != 1)
                drop = 1; /* a cap hit: on rim rays, about half of them */
            if (drop) {
                memcpy(&t[j], &before_t[j], sizeof(float));
                memcpy(&tmax[j], &before_tmax[j], sizeof(float));
                memcpy(&nx[j], &before_t[j], sizeof(float)); /* poison, as before */
                memcpy(&ny[j], &before_t[j], sizeof(float));
                memcpy(&nz[j], &before_t[j], sizeof(float));
                memcpy(&part[j], &before_t[j], sizeof(float));
                m &= ~(1u << j);
            }
            break;
        }
        case MUT_BACKFACE:
            part[j] |= CYLRAY_BACKFACE;
            break;
        case MUT_PART:
            part[j] = (part[j] & CYLRAY_BACKFACE) | ((part[j] & CYLRAY_PART_MASK) % 3 + 1);
            break;
        case MUT_NO_TMAX:
            tmax[j] = before_tmax[j];
            break;
        case MUT_NORMAL_LEN:
            if (flags & CYLRAY_NORMAL) {
                nx[j] *= 1.0001f;
                ny[j] *= 1.0001f;
                nz[j] *= 1.0001f;
            }
            break;
        case MUT_NORMAL_TILT:
            if (flags & CYLRAY_NORMAL) {
                /* Along a vector perpendicular to n: (n x e) for the smallest axis e. */
                float a = 3e-5f, x = nx[j], y = ny[j], z = nz[j];
                float px = fabsf(x) < 0.5f ? 0 : -y, py = fabsf(x) < 0.5f ? -z : x,
                      pz = fabsf(x) < 0.5f ? y : 0;
                float l = sqrtf(px * px + py * py + pz * pz);
                nx[j] = x + a * px / l;
                ny[j] = y + a * py / l;
                nz[j] = z + a * pz / l;
            }
            break;
        case MUT_NO_FF:
            if ((flags & CYLRAY_NORMAL) && (flags & CYLRAY_FACE_FORWARD) &&
                (part[j] & CYLRAY_BACKFACE)) {
                nx[j] = -nx[j];
                ny[j] = -ny[j];
                nz[j] = -nz[j];
            }
            break;
        case MUT_NORMAL_ALWAYS:
            if (!(flags & CYLRAY_NORMAL))
                nx[j] = 0.0f;
            break;
        default:
            break;
        }
    }
    return m;
}

static unsigned real_flags(unsigned flags)
{
    if (mutation == MUT_CULL_IGNORED)
        return flags & ~CYLRAY_CULL_BACK;
    if (mutation == MUT_NORMAL_ALWAYS)
        return flags | CYLRAY_NORMAL;
    return flags;
}

#define WRAP(W)                                                                                \
    static uint32_t mut_isect##W(const cylray_prepared *p, cylray_ray##W *r, cylray_hit##W *h, \
                                 uint32_t a, unsigned f)                                       \
    {                                                                                          \
        float bt[W], btmax[W];                                                                 \
        memcpy(bt, h->t, sizeof bt);                                                           \
        memcpy(btmax, r->tmax, sizeof btmax);                                                  \
        cylray_hit##W keep = *h;                                                               \
        uint32_t m = real->intersect##W(p, r, h, a, real_flags(f));                            \
        if (mutation == MUT_NORMAL_ALWAYS && !(f & CYLRAY_NORMAL))                             \
            memcpy(h->nx, keep.nx, sizeof h->nx); /* only one stray write: nx[0] below */      \
        return mutate(m, a, W, f, r->tmax, btmax, h->t, bt, h->nx, h->ny, h->nz, h->part,      \
                      NULL, p);                                                                \
    }                                                                                          \
    static uint32_t mut_occ##W(const cylray_prepared *p, const cylray_ray##W *r, uint32_t a,   \
                               unsigned f)                                                     \
    {                                                                                          \
        uint32_t m = real->occluded##W(p, r, a, real_flags(f) & ~CYLRAY_NORMAL);               \
        return mutation == MUT_OCCLUDED ? m ^ (a & 1u) : m;                                    \
    }
WRAP(4)
WRAP(8)
WRAP(16)

static size_t mut_stream(const cylray_prepared *p, const cylray_rays *r, const cylray_hits *h,
                         size_t n, unsigned f)
{
    float *bt = malloc((n + 1) * sizeof *bt), *btmax = malloc((n + 1) * sizeof *btmax);
    if (!bt || !btmax)
        exit(2);
    memcpy(bt, h->t, n * sizeof *bt);
    memcpy(btmax, r->tmax, n * sizeof *btmax);
    cylray_hits hh = *h;
    float dummy[32]; /* stands in for absent normal arrays, one chunk long */
    unsigned rf = real_flags(f);
    if (!h->nx)
        rf &= ~CYLRAY_NORMAL | (f & CYLRAY_NORMAL); /* no arrays to write normals to */
    size_t count = real->intersect_stream(p, r, &hh, n, rf);
    uint32_t m = 0;
    size_t total = 0;
    /* Mutate in chunks of 32 lanes, whose hits are the lanes whose t changed. */
    for (size_t i = 0; i < n; i += 32) {
        size_t k = n - i < 32 ? n - i : 32;
        m = 0;
        for (size_t j = 0; j < k; j++)
            if (memcmp(&h->t[i + j], &bt[i + j], sizeof(float)) != 0)
                m |= 1u << j;
        float *nx = h->nx ? h->nx + i : dummy, *ny = h->ny ? h->ny + i : dummy,
              *nz = h->nz ? h->nz + i : dummy;
        int keep = mutation;
        if (!h->nx && (mutation == MUT_NORMAL_LEN || mutation == MUT_NORMAL_TILT ||
                       mutation == MUT_NO_FF || mutation == MUT_NORMAL_ALWAYS))
            mutation = MUT_NONE;
        m = mutate(m, (uint32_t)((k == 32) ? 0xffffffffu : (1u << k) - 1u), k, f, r->tmax + i,
                   btmax + i, h->t + i, bt + i, nx, ny, nz, h->part + i, NULL, p);
        mutation = keep;
        for (; m; m &= m - 1)
            total++;
    }
    if (mutation == MUT_OVERRUN)
        h->t[n] = 0.0f;
    free(bt);
    free(btmax);
    (void)count;
    return total;
}

static size_t mut_occ_stream(const cylray_prepared *p, const cylray_rays *r, uint8_t *o,
                             size_t n, unsigned f)
{
    return real->occluded_stream(p, r, o, n, real_flags(f) & ~CYLRAY_NORMAL);
}

static const cylray_kernels mutant = {
    CYLRAY_ISA_SCALAR,
    "mutant",
    mut_isect4,
    mut_isect8,
    mut_isect16,
    mut_occ4,
    mut_occ8,
    mut_occ16,
    mut_stream,
    mut_occ_stream,
    NULL,
    NULL,
    NULL,
    NULL,
    NULL,
    NULL, /* cylcheck drives no leaves */
    /* nor secondary rays */
    NULL,
    NULL,
    NULL,
    NULL,
    NULL,
    NULL,
    NULL,
    NULL,
    NULL,
    NULL,
    NULL,
    NULL,
    NULL,
    NULL,
    NULL,
    NULL,
    NULL,
    NULL,
    NULL,
    NULL,
    NULL,
    NULL,
    NULL,
    NULL,
    NULL,
    NULL,
    NULL,
    NULL,
};

/* Every mutation of `real` over three categories; returns the mutations not caught
 * (or, for none, the failures of the unchanged kernel). */
static int suite(const char *title, const int cats[3], int spheres)
{
    static const size_t lengths[] = {3, 17, 32};
    ref_case *cases[3];
    size_t totals[3];
    const size_t npk = 128;
    for (int c = 0; c < 3; c++)
        cases[c] = make_cases(cats[c], opt.seed, npk, lengths, 3, &totals[c]);
    /* Flag sets: plain with normals, face-forward, cull, nothing. No REFINE: it is not
     * what is tested here (and has defects of its own, see the report). */
    const unsigned flag_sets[] = {CYLRAY_NORMAL, CYLRAY_NORMAL | CYLRAY_FACE_FORWARD,
                                  CYLRAY_NORMAL | CYLRAY_CULL_BACK, 0};
    int bad = 0;
    double base_p99 = 0;
    printf("%s:\n", title);
    for (mutation = 0; mutation < MUT_COUNT; mutation++) {
        if (spheres && mutation == MUT_RIM_DROP)
            continue; /* a sphere has no cap plane */
        failures = 0;
        stats_free();
        for (int c = 0; c < 3; c++)
            for (size_t f = 0; f < sizeof flag_sets / sizeof *flag_sets; f++) {
                drive_packets(&mutant, flag_sets[f], cats[c], cases[c], npk, NULL, opt.seed);
                drive_streams(&mutant, flag_sets[f], cats[c], cases[c] + npk, lengths, 3, NULL,
                              opt.seed);
            }
        long found = failures;
        /* A defect of a few ulps passes every lane's band; the headline p99 is what
         * must see it. The unchanged kernel's own p99 is the baseline (whether the
         * kernel meets the headline is cylcheck's business, not this test's). */
        stat_cell *s = stat_at(CYLRAY_ISA_SCALAR, cats[0], MODE_PLAIN);
        double p99 = stat_percentile(s, 0.99);
        if (mutation == MUT_NONE)
            base_p99 = p99;
        int caught = found > 0 || p99 >= base_p99 + 2;
        int ok = mutation == MUT_NONE ? found == 0 : caught;
        printf("%-32s %6ld lane failures, %s p99 %7.3g ulps: %s\n", mut_names[mutation], found,
               cat_name(cats[0]), p99,
               ok ? (mutation == MUT_NONE ? "passes, as it should" : "caught")
                  : (mutation == MUT_NONE ? "FAILS" : "NOT CAUGHT"));
        bad += !ok;
    }
    stats_free();
    for (int c = 0; c < 3; c++)
        free(cases[c]);
    return bad;
}

int main(void)
{
    setvbuf(stdout, NULL, _IOLBF, 0);
    real = cylray_kernels_for(CYLRAY_ISA_SCALAR);
    if (!real) {
        printf("no scalar path\n");
        return 1;
    }
    opt.seed = 4242;
    opt.max_print = 0;
    const int cats[] = {CYLGEN_ORDINARY, CYLGEN_RIM, CYLGEN_INSIDE};
    int bad = suite("the scalar kernel, cylinders", cats, 0);
    /* Spheres: the defects go into a double-precision sphere kernel of the test's own
     * (sphkernel.h), so that these rules are proven whatever the library's does. */
    real = sphere_double_kernels();
    const int sph_cats[] = {CAT_SPHERE + SPHGEN_ORDINARY, CAT_SPHERE + SPHGEN_SURFACE,
                            CAT_SPHERE + SPHGEN_INSIDE};
    bad += suite("a double-precision sphere kernel, spheres", sph_cats, 1);
    printf("%s\n", bad ? "checker self-test FAILED" : "checker self-test passed");
    return bad != 0;
}
