/* SPDX-License-Identifier: MIT */
/* accuracy.c - the error side: the configuration run once more on the very rays it was
 * timed on, compared with the exact binary128 reference of tests/ref (cylref).
 *
 * t error is |t - t_exact| in float ulps at t_exact over the rays where both hit. A
 * hit/miss or part disagreement is counted, then judged against the reference's
 * tolerance band (the float inputs perturbed by a few ulps): excused when the exact
 * case is that close to a decision boundary, "unexcused" otherwise. Bands are costly,
 * so they are computed only for rays that disagree, once per ray. Spheres and cones
 * take tests/ref's exact sphere (sphref.h) and cone (conref.h) in the same form. */
#include "bench.h"
#include "timing_run.h"

#include <stdlib.h>
#include <string.h>

#include "conref.h"
#include "cylref.h"
#include "sphref.h"

int accuracy_available(void)
{
    return 1;
}

static size_t stride_of(const workload *w)
{
    return w->ref_stride ? w->ref_stride : 1;
}

static void cyl_range(const workload *w, size_t i, int *c0, int *c1)
{
    if (w->grouped) {
        *c0 = (int)(i / (size_t)w->grouped);
        *c1 = *c0 + 1;
    } else {
        *c0 = 0;
        *c1 = w->ncyl;
    }
}

static int cyl_index(const workload *w, size_t i)
{
    int c0, c1;
    cyl_range(w, i, &c0, &c1);
    return c0;
}

/* Rays in inactive packet lanes hold a fill, not a ray: never compared. */
static int ray_active(const workload *w, size_t i)
{
    return w->lanes >> (i % 32) & 1u;
}

static void ray_of(const workload *w, size_t i, float o[3], float d[3], float *tmin,
                   float *tmax)
{
    raysoa_get(&w->rays, i, o, d);
    *tmin = w->rays.tmin[i];
    *tmax = w->rays.tmax[i];
}

/* The closest exact hit over the cylinders ray i meets. */
static void ref_closest(const workload *w, size_t i, ref_answer *out)
{
    float o[3], d[3], tmin, tmax;
    ray_of(w, i, o, d, &tmin, &tmax);
    int c0, c1;
    cyl_range(w, i, &c0, &c1);
    out->hit = 0;
    out->t = 0;
    out->part = 0;
    for (int c = c0; c < c1; c++) {
        cylref_hit h;
        int got = w->sph   ? sphref_intersect(&w->sph[c], o, d, tmin, tmax, 0, &h)
                  : w->con ? conref_intersect(&w->con[c], o, d, tmin, tmax, 0, &h)
                           : cylref_intersect(&w->cyl[c], o, d, tmin, tmax, 0, &h);
        if (got == 1 && (!out->hit || h.t < out->t)) {
            out->hit = 1;
            out->t = h.t;
            out->part = h.part;
        }
    }
}

void accuracy_reference(workload *w)
{
    size_t n = w->rays.n, st = stride_of(w);
    w->ref = calloc(n, sizeof *w->ref);
    w->bands = calloc(n, sizeof *w->bands);
    if (!w->ref || !w->bands) {
        free(w->ref), free(w->bands);
        w->ref = NULL, w->bands = NULL;
        return;
    }
    for (size_t i = 0; i < n; i += st)
        if (ray_active(w, i))
            ref_closest(w, i, &w->ref[i]);
}

void accuracy_release(workload *w)
{
    size_t n = w->rays.n;
    for (size_t i = 0; w->bands && i < n; i++)
        free(w->bands[i]);
    free(w->ref);
    free(w->bands);
    w->ref = NULL;
    w->bands = NULL;
}

static const cylref_band *band_of(const workload *w, size_t i, int c)
{
    void **cache = w->bands;
    int single = w->grouped || w->ncyl == 1;
    if (single && cache[i])
        return cache[i];
    cylref_band *b = malloc(sizeof *b);
    if (!b)
        return NULL;
    float o[3], d[3], tmin, tmax;
    ray_of(w, i, o, d, &tmin, &tmax);
    if (w->sph)
        sphref_band_eval(&w->sph[c], o, d, tmin, tmax, 0, b);
    else if (w->con)
        conref_band_eval(&w->con[c], o, d, tmin, tmax, 0, b);
    else
        cylref_band_eval(&w->cyl[c], o, d, tmin, tmax, 0, b);
    if (single)
        cache[i] = b;
    return b;
}

/* 0: the kernel's outcome is one the tolerance band allows; 1: an unexcused hit/miss
 * disagreement; 2: an unexcused part disagreement. Occlusion judges hit/miss only. */
static int judge(const workload *w, size_t i, int occ, int hit, int part, float t)
{
    int c0, c1;
    cyl_range(w, i, &c0, &c1);
    if (c1 - c0 == 1) {
        const cylref_band *b = band_of(w, i, c0);
        if (!b)
            return 0;
        if (occ)
            return b->hit_unstable ? 0 : (hit != b->exact.hit);
        double beyond;
        return cylref_judge(b, hit, part, t, &beyond);
    }
    /* Several cylinders (the BVH leaf): excused when any of them is near a decision. */
    int verdict = 1;
    for (int c = c0; c < c1 && verdict; c++) {
        cylref_band *b = (cylref_band *)band_of(w, i, c);
        if (b && b->decision_unstable)
            verdict = 0;
        free(b);
    }
    return verdict;
}

void accuracy_measure(const workload *w, int isa, int width_id, int op, result *r)
{
    size_t n = w->rays.n, st = stride_of(w);
    uint8_t *hit = malloc(n);
    float *t = malloc(n * sizeof *t);
    int32_t *part = malloc(n * sizeof *part);
    double *ulps = malloc(n * sizeof *ulps), *xs = malloc(n * sizeof *xs);
    if (!hit || !t || !part || !ulps || !xs ||
        bench_run_once(w, isa, width_id, op, hit, t, part) != 0)
        goto done;
    size_t nh = 0, na = 0;
    for (size_t i = 0; i < n; i++) {
        nh += hit[i];
        na += (size_t)ray_active(w, i);
    }
    r->hit_frac = (double)nh / (double)na;
    const ref_answer *ref = w->ref;
    if (!ref)
        goto done;
    const int occ = op == OP_OCC;
    size_t nu = 0;
    for (size_t i = 0; i < n; i += st) {
        if (!ray_active(w, i))
            continue;
        const ref_answer *R = &ref[i];
        r->n_hits_ref += (size_t)R->hit;
        if (hit[i] != R->hit) {
            if (hit[i])
                r->extra_hits++;
            else
                r->lost_hits++;
            if (judge(w, i, occ, hit[i], part[i], t[i]))
                r->unexcused++;
            continue;
        }
        if (!hit[i] || occ)
            continue;
        double u = cylref_ulps(t[i], R->t);
        xs[nu] = 0;
        if (u > 1 && (w->grouped || w->ncyl == 1)) {
            /* How far outside what the float inputs' rounding allows: the band of the
             * outcome the kernel chose. Only for rays off by more than 1 ulp (bands
             * are costly); cached per ray, so every configuration shares them. */
            const cylref_band *b = band_of(w, i, cyl_index(w, i));
            double beyond = 0;
            if (b) {
                cylref_judge(b, 1, part[i], t[i], &beyond);
                xs[nu] = beyond;
            }
        } else if (u > 1) {
            xs[nu] = u; /* several cylinders: no band; the raw error stands */
        }
        ulps[nu++] = u;
        if (part[i] != R->part) {
            r->part_diff++;
            if (judge(w, i, occ, hit[i], part[i], t[i]))
                r->unexcused++;
        }
    }
    r->have_err = 1;
    r->n_cmp = nu;
    if (nu) {
        stat_sort(ulps, nu);
        r->ulp_med = stat_quantile(ulps, nu, 0.5);
        r->ulp_p99 = stat_quantile(ulps, nu, 0.99);
        r->ulp_max = ulps[nu - 1];
        stat_sort(xs, nu);
        r->xs_p99 = stat_quantile(xs, nu, 0.99);
        r->xs_max = xs[nu - 1];
    }
done:
    free(hit);
    free(t);
    free(part);
    free(ulps);
    free(xs);
}
