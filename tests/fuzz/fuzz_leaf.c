/* SPDX-License-Identifier: MIT */
/* fuzz_leaf.c - the fuzzer's leaf checks: the decoded cylinder and variants of it
 * (moved by fractions of its radius, with the caps changed) make a leaf of up to 8;
 * each of the first rays of the case is traced through it on every ISA:
 *   - a lane's answer does not depend on the other lanes: the full leaf reports the
 *     minimum of the one-cylinder leaves, bit for bit, on the lowest lane of equal t,
 *     with that lane's id;
 *   - a one-cylinder leaf agrees with the packet kernel of the same ISA for that
 *     cylinder (agree.h: differences only near a decision boundary);
 *   - occluded agrees with intersect; nothing beside the hit is written. */
#include "fuzz_leaf.h"

#include <stdio.h>
#include <string.h>

#include "agree.h"

#define LEAF_RAYS 4

static int leaf_call(const cylray_kernels *k, const cylray_leaf8 *leaf, const float r[G_NFIELD],
                     unsigned flags, cylray_hit1 *hit, char *why, size_t whylen)
{
    struct {
        cylray_hit1 h;
        uint32_t guard[4];
    } io;
    memset(&io, 0xa5, sizeof io);
    cylray_ray1 ray = {
        {r[G_OX], r[G_OY], r[G_OZ]}, {r[G_DX], r[G_DY], r[G_DZ]}, r[G_TMIN], r[G_TMAX]};
    const cylray_ray1 orig = ray;
    int got = k->leaf_intersect8(leaf, &ray, &io.h, flags);
    int occ = k->leaf_occluded8(leaf, &orig, flags);
    for (int q = 0; q < 4; q++)
        if (io.guard[q] != 0xa5a5a5a5u)
            return snprintf(why, whylen, "%s: wrote beside the hit", k->name), -1;
    if (occ != got)
        return snprintf(why, whylen, "%s: occluded %d, intersect %d", k->name, occ, got), -1;
    if (got && memcmp(&ray.tmax, &io.h.t, 4) != 0)
        return snprintf(why, whylen, "%s: tmax %a, t %a", k->name, (double)ray.tmax,
                        (double)io.h.t),
               -1;
    if (!got && memcmp(&ray, &orig, sizeof ray) != 0)
        return snprintf(why, whylen, "%s: a miss wrote the ray", k->name), -1;
    *hit = io.h;
    return got;
}

int fz_leaf(const fz_case *c, const cylray_kernels *const *isas, int nisa, char *why,
            size_t whylen)
{
    cylray_cylinder cyl[8];
    uint32_t ids[8];
    const size_t n = 1 + c->active % 8;
    cylray_prepared P;
    if (cylray_prepare(&P, &c->cyl) != CYLRAY_OK)
        return 0;
    for (size_t j = 0; j < n; j++) {
        cyl[j] = c->cyl;
        cyl[j].center[j % 3] += (float)j * 0.7f * c->cyl.radius;
        if (j & 1)
            cyl[j].flags ^= CYLRAY_CAPPED_LO;
        if (j & 2)
            cyl[j].flags ^= CYLRAY_CAPPED_HI;
        ids[j] = 0x9e3779b9u * (uint32_t)(j + 1);
    }
    cylray_leaf8 full, one[8];
    if (cylray_leaf_prepare8(&full, cyl, ids, n) != CYLRAY_OK)
        return 0; /* a moved center beyond prepare's limits */
    for (size_t j = 0; j < n; j++)
        if (cylray_leaf_prepare8(&one[j], &cyl[j], &ids[j], 1) != CYLRAY_OK)
            return 0;
    const size_t nr = c->n < LEAF_RAYS ? c->n : LEAF_RAYS;
    for (int ii = 0; ii < nisa; ii++) {
        const cylray_kernels *k = isas[ii];
        for (size_t i = 0; i < nr; i++) {
            float r[G_NFIELD];
            for (int f = 0; f < G_NFIELD; f++)
                r[f] = c->rays.f[f][i];
            cylray_hit1 h, hj;
            int got = leaf_call(k, &full, r, c->flags, &h, why, whylen);
            if (got < 0)
                return 1;
            int best = -1;
            float bt = 0;
            for (size_t j = 0; j < n; j++) {
                int gj = leaf_call(k, &one[j], r, c->flags, &hj, why, whylen);
                if (gj < 0)
                    return 1;
                if (gj && (best < 0 || hj.t < bt))
                    best = (int)j, bt = hj.t;
                /* the one-cylinder leaf against the packet kernel of this ISA */
                cylray_prepared Pj;
                cylray_prepare(&Pj, &cyl[j]);
                cylray_ray4 q;
                cylray_hit4 qh;
                for (int l = 0; l < 4; l++) {
                    q.ox[l] = r[G_OX], q.oy[l] = r[G_OY], q.oz[l] = r[G_OZ];
                    q.dx[l] = r[G_DX], q.dy[l] = r[G_DY], q.dz[l] = r[G_DZ];
                    q.tmin[l] = r[G_TMIN], q.tmax[l] = r[G_TMAX];
                }
                int gp = (int)(k->intersect4(&Pj, &q, &qh, 1u, c->flags) & 1u);
                const fz_answer a = {gj, gj ? hj.t : 0, gj ? hj.part : 0};
                const fz_answer b = {gp, gp ? qh.t[0] : 0, gp ? qh.part[0] : 0};
                char w2[512];
                if (fz_agree(&cyl[j], r, c->flags, &a, &b, w2, sizeof w2))
                    return snprintf(why, whylen, "%s ray %zu lane %zu: leaf and packet: %s",
                                    k->name, i, j, w2),
                           1;
            }
            if (got != (best >= 0) || (got && (h.lane != (uint32_t)best ||
                                               memcmp(&h.t, &bt, 4) != 0 || h.id != ids[best])))
                return snprintf(
                           why, whylen,
                           "%s ray %zu: leaf of %zu gives %s t %a lane %u, the lanes alone "
                           "give %s t %a lane %d",
                           k->name, i, n, got ? "hit" : "miss", got ? (double)h.t : 0.0,
                           got ? h.lane : 0u, best >= 0 ? "hit" : "miss", (double)bt, best),
                       1;
        }
    }
    return 0;
}
