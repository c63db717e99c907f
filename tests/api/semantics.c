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
#include "rng.h"
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
            const uint32_t masks[2] = {full, (uint32_t)rng_splitmix64(seed) & full};
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
                CHECK(o.hit == r.hit,
                      "%s %s flags=%#x: occluded%zu mask %#llx, intersect %#llx", k->name,
                      cname, flags, w, (unsigned long long)o.hit, (unsigned long long)r.hit);
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

/* A long stream whose vectors pass and fail the cheap rejections in runs: the stream
 * drivers switch between two vectors in flight and one at a time on what they see, and
 * a vector beside a rejected partner runs as its twin. Whatever the schedule, every ray
 * gets the answer of a 16-ray packet holding it, bit for bit (t, part, normal, tmax).
 * The runs' lengths vary (multiples of 4: the rejected ones 4 to 36 rays, the others 16
 * to 64), so that on every width a pair meets a rejected vector first, second and
 * twice, and a run can end inside a pair. */
enum { LS_N = 1701 };
static float ls_in[G_NFIELD][LS_N], ls_t[LS_N], ls_n[3][LS_N];
static int32_t ls_part[LS_N];
static uint8_t ls_occ[LS_N], ls_seg[LS_N];

static size_t ls_seg_len(size_t seg)
{
    return seg % 4 == 1 ? 4 * (1 + seg * 7 % 9) : 4 * (4 + seg * 5 % 13);
}

static void long_stream_agrees(const cylray_kernels *k, const cylray_prepared *P,
                               const cylray_cylinder *c, unsigned flags, const char *cname,
                               uint64_t seed)
{
    /* Segments in a fixed cycle: the scene's mix of rays; rays parallel to the axis 50
     * radii from it (every vector rejected); the mix again; rays aimed at the center. */
    for (size_t s0 = 0, seg = 0, n = 0; s0 < LS_N; s0 += n, seg++) {
        n = LS_N - s0 < ls_seg_len(seg) ? LS_N - s0 : ls_seg_len(seg);
        gbatch b;
        scene_rays(seed + seg, c, &b, 0, n < G_MAX ? n : G_MAX);
        for (size_t i = 0; i < n; i++) {
            const size_t j = i % G_MAX;
            float o[3], d[3];
            for (int a = 0; a < 3; a++)
                o[a] = b.f[G_OX + a][j], d[a] = b.f[G_DX + a][j];
            const double r = c->radius;
            /* u: a unit vector across the axis */
            double ax[3] = {c->axis[0], c->axis[1], c->axis[2]};
            double u[3] = {ax[1], -ax[0], 0};
            if (fabs(ax[2]) > fabs(ax[0]) && fabs(ax[2]) > fabs(ax[1]))
                u[0] = 0, u[1] = ax[2], u[2] = -ax[1];
            const double lu = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
            if (seg % 4 == 1)
                for (int a = 0; a < 3; a++)
                    o[a] = (float)(c->center[a] + 50 * r * u[a] / lu + (double)(i % 7) * ax[a]),
                    d[a] = (float)ax[a];
            else if (seg % 4 == 3)
                for (int a = 0; a < 3; a++)
                    d[a] = (float)(c->center[a] + 0.25 * r * u[a] / lu - o[a]);
            for (int a = 0; a < 3; a++)
                ls_in[G_OX + a][s0 + i] = o[a], ls_in[G_DX + a][s0 + i] = d[a];
            ls_in[G_TMIN][s0 + i] = b.f[G_TMIN][j];
            ls_in[G_TMAX][s0 + i] = b.f[G_TMAX][j];
            ls_seg[s0 + i] = (uint8_t)seg;
        }
    }
    float tmax[LS_N];
    memcpy(tmax, ls_in[G_TMAX], sizeof tmax);
    memset(ls_part, 0x5a, sizeof ls_part);
    memset(ls_occ, 0, sizeof ls_occ);
    const cylray_rays rays = {ls_in[G_OX], ls_in[G_OY], ls_in[G_OZ],   ls_in[G_DX],
                              ls_in[G_DY], ls_in[G_DZ], ls_in[G_TMIN], tmax};
    const cylray_hits hits = {ls_t, ls_n[0], ls_n[1], ls_n[2], ls_part};
    const size_t count = k->intersect_stream(P, &rays, &hits, LS_N, flags);
    const cylray_rays orays = {ls_in[G_OX], ls_in[G_OY], ls_in[G_OZ],   ls_in[G_DX],
                               ls_in[G_DY], ls_in[G_DZ], ls_in[G_TMIN], ls_in[G_TMAX]};
    const size_t ocount = k->occluded_stream(P, &orays, ls_occ, LS_N, flags);
    size_t hits_seen = 0;
    for (size_t p0 = 0; p0 < LS_N; p0 += 16) {
        const size_t w = LS_N - p0 < 16 ? LS_N - p0 : 16;
        cylray_ray16 ray;
        cylray_hit16 hit;
        memset(&ray, 0, sizeof ray);
        for (size_t i = 0; i < w; i++) {
            ray.ox[i] = ls_in[G_OX][p0 + i], ray.oy[i] = ls_in[G_OY][p0 + i];
            ray.oz[i] = ls_in[G_OZ][p0 + i], ray.dx[i] = ls_in[G_DX][p0 + i];
            ray.dy[i] = ls_in[G_DY][p0 + i], ray.dz[i] = ls_in[G_DZ][p0 + i];
            ray.tmin[i] = ls_in[G_TMIN][p0 + i], ray.tmax[i] = ls_in[G_TMAX][p0 + i];
        }
        const uint32_t m = k->intersect16(P, &ray, &hit, (uint32_t)((1ull << w) - 1u), flags);
        for (size_t i = 0; i < w; i++) {
            const size_t g = p0 + i;
            const int h = (int)((m >> i) & 1u);
            hits_seen += (size_t)h;
            int same = h == (tmax[g] != ls_in[G_TMAX][g] || ls_part[g] != 0x5a5a5a5a) &&
                       h == ls_occ[g];
            if (h) {
                same = same && memcmp(&hit.t[i], &ls_t[g], 4) == 0 &&
                       memcmp(&ray.tmax[i], &tmax[g], 4) == 0 && hit.part[i] == ls_part[g];
                if (flags & CYLRAY_NORMAL)
                    same = same && memcmp(&hit.nx[i], &ls_n[0][g], 4) == 0 &&
                           memcmp(&hit.ny[i], &ls_n[1][g], 4) == 0 &&
                           memcmp(&hit.nz[i], &ls_n[2][g], 4) == 0;
            }
            CHECK(same,
                  "%s %s flags=%#x: long stream ray %zu (segment %zu) differs from its packet: "
                  "hit %d/%d t %a/%a part %#x/%#x occluded %d",
                  k->name, cname, flags, g, (size_t)ls_seg[g], h, ls_part[g] != 0x5a5a5a5a,
                  hit.t[i], ls_t[g], (unsigned)hit.part[i], (unsigned)ls_part[g], ls_occ[g]);
        }
    }
    CHECK(count == hits_seen && ocount == hits_seen,
          "%s %s flags=%#x: long stream counted %zu hits, occluded %zu, packets %zu", k->name,
          cname, flags, count, ocount, hits_seen);
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
        for (int ii = 0; ii < nisa; ii++)
            for (size_t fi = 0; fi < (tc_quick() ? FLAG_SETS_QUICK : FLAG_SETS_ALL); fi++)
                long_stream_agrees(isas[ii], &P, &cyl[ci], flag_sets[fi], cname,
                                   (uint64_t)ci * 1000u);
    }
    for (int ii = 0; ii < nisa; ii++)
        closest_hit(isas[ii]);
    return tc_report("api-semantics");
}
