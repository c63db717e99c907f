/* SPDX-License-Identifier: MIT */
/* tmax_protocol.c - the closed interval [tmin, tmax] is one contract for every path,
 * flag set, width and kind of cylinder, so that a tracer can walk cylinders in any
 * order through tmax and keep the closest hit:
 *   - a reported hit t* comes back bit for bit (t, part, normal) from the same call
 *     with tmax = t*, and with tmin = tmax = t*;
 *   - with tmax one float below t*, no hit of the same part comes back (no root
 *     "moved" below the bound);
 *   - occluded agrees with intersect on every one of those calls;
 *   - a ray traced through a cluster of cylinders (duplicates, near copies, nested and
 *     tilted ones, capped and open twins), forwards and backwards, ends with the
 *     minimum t over separate calls, and with a record one of the minimal cylinders
 *     reports on its own.
 * The rays are the stress generators' (tests/ref/gen.h), every category. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cylray.h"
#include "gen.h"
#include "guarded.h"
#include "tcheck.h"

#define CLUSTER 8
#define STREAM_N 37 /* odd: whole vectors and a tail */

static int widths[] = {4, 8, 16, G_STREAM};
#define NWIDTH (int)(sizeof widths / sizeof widths[0])

static size_t lanes_of(int w)
{
    return w == G_STREAM ? STREAM_N : (size_t)w;
}

static uint32_t full_mask(int w)
{
    return w == G_STREAM ? 0 : (uint32_t)((1ull << w) - 1u);
}

/* The cluster around one cylinder: itself, an exact duplicate, the center a few ulps
 * away, the radius a few ulps larger, a nested one, a tilted one, and the same one
 * with the caps toggled (both, none, one end) when it is finite. */
static int make_cluster(const cylray_cylinder *c, cylray_cylinder out[CLUSTER])
{
    int n = 0;
    out[n++] = *c;
    out[n++] = *c;
    cylray_cylinder m = *c;
    for (int k = 0; k < 3; k++)
        m.center[k] = nextafterf(nextafterf(m.center[k], INFINITY), INFINITY);
    out[n++] = m;
    m = *c;
    m.radius = nextafterf(nextafterf(m.radius, INFINITY), INFINITY);
    out[n++] = m;
    m = *c;
    m.radius *= 0.999f;
    out[n++] = m;
    m = *c;
    m.axis[0] += 1e-6f * (fabsf(m.axis[1]) + fabsf(m.axis[2]) + fabsf(m.axis[0]));
    out[n++] = m;
    if (isfinite(c->half_height)) {
        m = *c;
        m.flags = c->flags ^ CYLRAY_CAPPED;
        out[n++] = m;
        m = *c;
        m.flags = c->flags == CYLRAY_CAPPED_LO ? CYLRAY_CAPPED_HI : CYLRAY_CAPPED_LO;
        out[n++] = m;
    }
    return n;
}

static void run(const cylray_kernels *k, int w, const cylray_prepared *P, const gbatch *b,
                unsigned flags, gresult *r)
{
    g_intersect(k, w, P, b, lanes_of(w), full_mask(w), flags, 1, r);
    gresult o;
    g_occluded(k, w, P, b, lanes_of(w), full_mask(w), flags, 1, &o);
    CHECK(o.hit == r->hit, "%s width %s flags %#x: occluded %#llx, intersect %#llx", k->name,
          g_width_name(w), flags, (unsigned long long)o.hit, (unsigned long long)r->hit);
}

static void describe(const cylray_cylinder *c, const gbatch *b, size_t i)
{
    char cb[256], rb[256];
    fprintf(stderr, "    cylinder %s\n    ray %s\n", g_cyl_str(c, cb, sizeof cb),
            g_ray_str(b, i, rb, sizeof rb));
}

/* The same call again with tmax = t*, with tmin = tmax = t*, and with tmax below t*. */
static void closed_interval(const cylray_kernels *k, int w, const cylray_cylinder *c,
                            const cylray_prepared *P, const gbatch *b, unsigned flags)
{
    const int normal = (flags & CYLRAY_NORMAL) != 0;
    const size_t n = lanes_of(w);
    gresult first;
    run(k, w, P, b, flags, &first);
    if (!first.hit)
        return;
    gbatch at = *b, pin = *b, below = *b;
    for (size_t i = 0; i < n; i++) {
        if (!((first.hit >> i) & 1u))
            continue;
        at.f[G_TMAX][i] = first.t[i];
        pin.f[G_TMIN][i] = pin.f[G_TMAX][i] = first.t[i];
        below.f[G_TMAX][i] = nextafterf(first.t[i], -INFINITY);
    }
    gresult r_at, r_pin, r_below;
    run(k, w, P, &at, flags, &r_at);
    run(k, w, P, &pin, flags, &r_pin);
    run(k, w, P, &below, flags, &r_below);
    for (size_t i = 0; i < n; i++) {
        if (!((first.hit >> i) & 1u))
            continue;
        int ok_at = g_same_lane(&first, i, &r_at, i, normal);
        int ok_pin = g_same_lane(&first, i, &r_pin, i, normal);
        int hit_below = (int)((r_below.hit >> i) & 1u);
        /* The same root must not come back below tmax; another part or face,
         * genuinely earlier, may. */
        int ok_below =
            !hit_below || (r_below.part[i] != first.part[i] && r_below.t[i] < first.t[i]);
        CHECK(ok_at && ok_pin && ok_below,
              "%s width %s flags %#x lane %zu: hit t %a part %d; with tmax = t: %s; with "
              "tmin = tmax = t: %s; with tmax one below: %s %a",
              k->name, g_width_name(w), flags, i, (double)first.t[i], first.part[i],
              ok_at ? "same" : "differs", ok_pin ? "same" : "differs",
              hit_below ? "hit" : "miss", hit_below ? (double)r_below.t[i] : 0.0);
        if (!(ok_at && ok_pin && ok_below))
            describe(c, b, i);
    }
}

/* The cluster walked through tmax in both orders against separate calls. */
static void walk(const cylray_kernels *k, int w, const cylray_cylinder *cyl, int nc,
                 const cylray_prepared *P, const gbatch *b, unsigned flags)
{
    const int normal = (flags & CYLRAY_NORMAL) != 0;
    const size_t n = lanes_of(w);
    static gresult alone[CLUSTER];
    for (int j = 0; j < nc; j++)
        run(k, w, &P[j], b, flags, &alone[j]);
    for (int dir = 0; dir < 2; dir++) {
        gbatch cur = *b;
        uint64_t any = 0;
        int last[G_MAX];
        gresult r, rec;
        memset(&rec, 0, sizeof rec);
        for (int s = 0; s < nc; s++) {
            int j = dir ? nc - 1 - s : s;
            run(k, w, &P[j], &cur, flags, &r);
            for (size_t i = 0; i < n; i++) {
                if ((r.hit >> i) & 1u) {
                    cur.f[G_TMAX][i] = r.t[i];
                    last[i] = j;
                    rec.t[i] = r.t[i], rec.part[i] = r.part[i];
                    rec.nx[i] = r.nx[i], rec.ny[i] = r.ny[i], rec.nz[i] = r.nz[i];
                    rec.tmax[i] = r.tmax[i];
                }
            }
            any |= r.hit;
        }
        rec.hit = any;
        for (size_t i = 0; i < n; i++) {
            float best = INFINITY;
            int hits = 0;
            for (int j = 0; j < nc; j++)
                if ((alone[j].hit >> i) & 1u) {
                    hits = 1;
                    if (alone[j].t[i] < best)
                        best = alone[j].t[i];
                }
            int got = (int)((any >> i) & 1u);
            int ok = got == hits && (!hits || tc_same(rec.t[i], best));
            /* The record is the last cylinder's that hit, which alone gives it too. */
            if (ok && hits)
                ok = g_same_lane(&rec, i, &alone[last[i]], i, normal);
            CHECK(ok,
                  "%s width %s flags %#x lane %zu, %s walk: %s t %a, separate calls: %s "
                  "minimum %a",
                  k->name, g_width_name(w), flags, i, dir ? "backward" : "forward",
                  got ? "hit" : "miss", got ? (double)rec.t[i] : 0.0, hits ? "hit" : "miss",
                  (double)best);
            if (!ok) {
                describe(&cyl[0], b, i);
                for (int j = 0; j < nc; j++)
                    fprintf(stderr, "    cylinder %d alone: %s t %a part %d\n", j,
                            (alone[j].hit >> i) & 1u ? "hit" : "miss",
                            (alone[j].hit >> i) & 1u ? (double)alone[j].t[i] : 0.0,
                            (alone[j].hit >> i) & 1u ? alone[j].part[i] : 0);
            }
        }
    }
}

/* The far cylinder whose polished root once lay below the unpolished one that the
 * range test saw: with tmax just below the reported t, a hit one ulp lower came back. */
static void known_case(const cylray_kernels *k)
{
    const cylray_cylinder c = {{0x1.00af06p+11f, -0x1.3c79a4p+9f, 0x1.da4aep+8f},
                               {0x1.0e37ccp-2f, -0x1.7b8c7ap+0f, 0x1.0c3a88p+0f},
                               0x1.8d2c7ap-1f,
                               INFINITY,
                               0};
    const float ray[G_NFIELD] = {
        0x1.008bc6p+11f, -0x1.3bf5aap+9f, 0x1.d9c5bcp+8f, 0x1.947abp+0f,
        0x1.d9182ap-3f,  0x1.67af4ap-2f,  0.0f,           INFINITY};
    cylray_prepared P;
    CHECK(cylray_prepare(&P, &c) == CYLRAY_OK, "prepare");
    gbatch b;
    for (int f = 0; f < G_NFIELD; f++)
        for (int i = 0; i < G_MAX; i++)
            b.f[f][i] = ray[f];
    for (int wi = 0; wi < NWIDTH; wi++)
        for (unsigned flags = 0; flags <= CYLRAY_FLAGS_ALL; flags++) {
            gresult r;
            run(k, widths[wi], &P, &b, flags, &r);
            CHECK(r.hit & 1u, "%s: the known case misses (flags %#x)", k->name, flags);
            closed_interval(k, widths[wi], &c, &P, &b, flags);
        }
}

int main(void)
{
    const cylray_kernels *isas[CYLRAY_ISA_COUNT];
    const int nisa = g_isas(isas);
    const int batches = tc_quick() ? 1 : 3;
    const size_t ncase = (size_t)batches * CYLGEN_BATCH;
    cylgen_case *cases = malloc(ncase * sizeof *cases);
    if (!cases)
        return 1;
    for (int ii = 0; ii < nisa; ii++) {
        const cylray_kernels *k = isas[ii];
        known_case(k);
        for (int cat = 0; cat < CYLGEN_COUNT; cat++) {
            cylgen_make(cat, 0x7a3c0ffeeull + (uint64_t)cat, ncase, cases);
            for (int bi = 0; bi < batches; bi++) {
                const cylgen_case *cs = &cases[bi * CYLGEN_BATCH];
                cylray_cylinder cyl[CLUSTER];
                cylray_prepared P[CLUSTER];
                const int nc = make_cluster(&cs[0].cyl, cyl);
                int ok = 1;
                for (int j = 0; j < nc; j++)
                    ok &= cylray_prepare(&P[j], &cyl[j]) == CYLRAY_OK;
                CHECK(ok, "%s: a cluster cylinder was refused", cylgen_category_name(cat));
                if (!ok)
                    continue;
                for (int wi = 0; wi < NWIDTH; wi++) {
                    const int w = widths[wi];
                    gbatch b;
                    for (size_t i = 0; i < lanes_of(w); i++) {
                        const cylgen_case *c = &cs[i % CYLGEN_BATCH];
                        const float f[G_NFIELD] = {c->o[0], c->o[1], c->o[2], c->d[0],
                                                   c->d[1], c->d[2], c->tmin, c->tmax};
                        for (int q = 0; q < G_NFIELD; q++)
                            b.f[q][i] = f[q];
                    }
                    for (unsigned flags = 0; flags <= CYLRAY_FLAGS_ALL; flags++) {
                        for (int j = 0; j < nc; j++)
                            closed_interval(k, w, &cyl[j], &P[j], &b, flags);
                        walk(k, w, cyl, nc, P, &b, flags);
                    }
                }
            }
        }
    }
    free(cases);
    return tc_report("robust-tmax-protocol");
}
