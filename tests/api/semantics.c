/* SPDX-License-Identifier: MIT */
/* semantics.c - the per-lane contract of docs/design.md section 3 on varied rays, on every
 * ISA: a lane's answer depends on nothing but its own ray, so
 *   - packets of 4, 8 and 16 and streams of any length give bit-identical answers for
 *     the same ray (same kernel, same operations: a difference would mean a lane sees
 *     its neighbours, or a width computes differently);
 *   - occluded reports exactly the lanes intersect hits;
 *   - the tracer's loop (one packet against many cylinders, tmax shrinking) keeps the
 *     closest hit: a farther cylinder after a nearer one changes nothing.
 * The memory contract (untouched misses and inactive lanes, tmax == t) is checked on
 * every call by the guarded runner. */
#include <math.h>
#include <string.h>

#include "cylray.h"
#include "flagsets.h"
#include "guarded.h"
#include "scene.h"
#include "tcheck.h"


/* Rays [first, first + w) of `all` as lanes [0, w). */
static void slice(const gbatch *all, size_t first, size_t w, gbatch *out)
{
    for (int f = 0; f < G_NFIELD; f++)
        memcpy(out->f[f], all->f[f] + first, w * sizeof(float));
}

static void widths_agree(const cylray_kernels *k, const cylray_prepared *P, const gbatch *all,
                         unsigned flags, const char *cname, uint64_t *seed)
{
    const int normal = (flags & CYLRAY_NORMAL) != 0;
    gresult ref, r;
    /* The reference for this ISA: the whole batch as one stream. */
    g_intersect(k, G_STREAM, P, all, G_MAX, 0, flags, 0, &ref);

    const int widths[] = {4, 8, 16};
    for (int wi = 0; wi < 3; wi++) {
        const size_t w = (size_t)widths[wi];
        for (size_t first = 0; first < G_MAX; first += w) {
            gbatch b;
            slice(all, first, w, &b);
            /* all lanes, then a random subset of them */
            const uint32_t full = (uint32_t)((1u << w) - 1u);
            const uint32_t masks[2] = {full, (uint32_t)cylgen_splitmix64(seed) & full};
            for (int mi = 0; mi < 2; mi++) {
                g_intersect(k, (int)w, P, &b, w, masks[mi], flags, 0, &r);
                for (size_t i = 0; i < w; i++) {
                    if (!((masks[mi] >> i) & 1u))
                        continue;
                    CHECK(g_same_lane(&r, i, &ref, first + i, normal),
                          "%s %s flags=%#x: packet%zu lane %zu (ray %zu) differs from the "
                          "stream: hit %d/%d t %a/%a part %#x/%#x",
                          k->name, cname, flags, w, i, first + i, (int)((r.hit >> i) & 1u),
                          (int)((ref.hit >> (first + i)) & 1u), r.t[i], ref.t[first + i],
                          (unsigned)r.part[i], (unsigned)ref.part[first + i]);
                }
                /* occluded: exactly the lanes intersect hits */
                gresult o;
                g_occluded(k, (int)w, P, &b, w, masks[mi], flags, 0, &o);
                CHECK(o.hit == r.hit, "%s %s flags=%#x: occluded%zu mask %#llx, intersect %#llx",
                      k->name, cname, flags, w, (unsigned long long)o.hit,
                      (unsigned long long)r.hit);
            }
        }
    }
    /* Streams of other lengths and alignments are prefixes of the whole one. */
    const size_t lens[] = {0, 1, 3, 7, 15, 16, 17, 31, 33, 47, 49};
    for (size_t li = 0; li < sizeof lens / sizeof lens[0]; li++) {
        const unsigned mis = (unsigned)(li % 4);
        g_intersect(k, G_STREAM, P, all, lens[li], 0, flags, mis, &r);
        for (size_t i = 0; i < lens[li]; i++)
            CHECK(g_same_lane(&r, i, &ref, i, normal),
                  "%s %s flags=%#x: stream of %zu (misaligned %u) ray %zu differs from the "
                  "stream of %d",
                  k->name, cname, flags, lens[li], mis, i, G_MAX);
        gresult o;
        g_occluded(k, G_STREAM, P, all, lens[li], 0, flags, mis, &o);
        const uint64_t m = lens[li] >= 64 ? ~0ull : (1ull << lens[li]) - 1u;
        CHECK(o.hit == (ref.hit & m) && o.count == r.count,
              "%s %s flags=%#x: occluded stream of %zu: %#llx (%zu), intersect %#llx (%zu)",
              k->name, cname, flags, lens[li], (unsigned long long)o.hit, o.count,
              (unsigned long long)(ref.hit & m), r.count);
    }
}

/* The tracer's loop: a packet against a near cylinder and a far one, in both orders.
 * Near first: the far one finds tmax already shorter and changes nothing. Far first:
 * the near one overwrites. Either way each lane ends with the nearer hit. */
static void closest_hit(const cylray_kernels *k)
{
    const cylray_cylinder near_c = {{0, 0, 0}, {0, 0, 1}, 1, INFINITY, 0};
    const cylray_cylinder far_c = {{10, 0, 0}, {0, 0, 1}, 1, INFINITY, 0};
    cylray_prepared pn, pf;
    cylray_prepare(&pn, &near_c);
    cylray_prepare(&pf, &far_c);
    for (int order = 0; order < 2; order++) {
        cylray_ray8 ray;
        cylray_hit8 hit;
        for (int i = 0; i < 8; i++) {
            ray.ox[i] = -5;
            ray.oy[i] = 0.125f * (float)(i - 4); /* lanes 0..7 at y = -0.5 .. 0.375 */
            ray.oz[i] = (float)i;
            ray.dx[i] = 1;
            ray.dy[i] = 0;
            ray.dz[i] = 0;
            ray.tmin[i] = 0;
            ray.tmax[i] = INFINITY;
        }
        const cylray_prepared *first = order ? &pf : &pn, *second = order ? &pn : &pf;
        uint32_t m1 = k->intersect8(first, &ray, &hit, 0xffu, CYLRAY_NORMAL);
        uint32_t m2 = k->intersect8(second, &ray, &hit, 0xffu, CYLRAY_NORMAL);
        CHECK(m1 == 0xffu, "%s closest-hit order %d: first cylinder mask %#x", k->name, order,
              m1);
        CHECK(m2 == (order ? 0xffu : 0u), "%s closest-hit order %d: second cylinder mask %#x",
              k->name, order, m2);
        for (int i = 0; i < 8; i++) {
            /* the near cylinder's entry: x = -sqrt(1 - y^2) */
            const double y = 0.125 * (i - 4);
            const double want = 5 - sqrt(1 - y * y);
            CHECK(fabs(hit.t[i] - want) <= 4e-6 * want && ray.tmax[i] == hit.t[i] &&
                      hit.nx[i] < 0,
                  "%s closest-hit order %d lane %d: t %a (tmax %a), expected %.9g", k->name,
                  order, i, hit.t[i], ray.tmax[i], want);
        }
    }
}

int main(void)
{
    const cylray_kernels *isas[CYLRAY_ISA_COUNT];
    const int nisa = g_isas(isas);
    cylray_cylinder cyl[SCENE_MAX_CYL];
    const int ncyl = scene_cylinders(cyl);
    const int rounds = tc_quick() ? 1 : 3;
    uint64_t seed = 12345;

    for (int ci = 0; ci < ncyl; ci++) {
        cylray_prepared P;
        if (cylray_prepare(&P, &cyl[ci]) != CYLRAY_OK) {
            CHECK(0, "scene cylinder %d refused", ci);
            continue;
        }
        char cname[32];
        snprintf(cname, sizeof cname, "cylinder %d", ci);
        for (int round = 0; round < rounds; round++) {
            gbatch all;
            scene_rays((uint64_t)(ci * 100 + round), &cyl[ci], &all, 0, G_MAX);
            for (int ii = 0; ii < nisa; ii++)
                for (size_t fi = 0; fi < FLAG_SETS_ALL; fi++)
                    widths_agree(isas[ii], &P, &all, flag_sets[fi], cname, &seed);
        }
    }
    for (int ii = 0; ii < nisa; ii++)
        closest_hit(isas[ii]);
    return tc_report("api-semantics");
}
