/* SPDX-License-Identifier: MIT */
/* spawn_cone.c - secondary rays from cones against exact (binary128) arithmetic.
 *
 *   spawn_cone bounds   hit points (plain and normal forms) of every ISA's kernel hits:
 *                       the bound contains the point's exact distance from the part hit
 *   spawn_cone self     rays spawned from kernel hits away from the solid (reflections
 *                       off the outside, rays leaving it from inside, shadow rays): the
 *                       origin strictly on w's side of the part, and no hit at all (the
 *                       frustum is convex, so none is right); the side form likewise,
 *                       its origin strictly on the side asked for
 *   spawn_cone batched  the stream and leaf forms of every ISA equal the scalar ones bit
 *                       for bit
 *
 * Cones of five kinds: general, tips (one radius 0), nearly cylinders (radii 1e-6 apart),
 * steep (radii far apart against the height) and flat (a height far below the radii).
 * CYLRAY_TEST_QUICK=1 shrinks the counts a hundredfold. */
#include "cylray.h"
#include "cylref.h"
#include "quad.h"
#include "spawn_main.h"
#include "spawnref.h"
#include "tcheck.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void fail(const char *what, const cylray_cone *c, double a, double b)
{
    if (failures++ < 20)
        printf("FAIL %s: cone p0=(%a, %a, %a) p1=(%a, %a, %a) r0=%a r1=%a flags=%u: %a %a\n",
               what, (double)c->p0[0], (double)c->p0[1], (double)c->p0[2], (double)c->p1[0],
               (double)c->p1[1], (double)c->p1[2], (double)c->r0, (double)c->r1, c->flags, a,
               b);
}

enum { K_GENERAL, K_TIP, K_NEARCYL, K_STEEP, K_FLAT, K_COUNT };

static void make_cone(cylgen_rng *r, int kind, cylray_cone *c)
{
    double u[3], m[3];
    sref_unit(r, u);
    const double S = pow(10, uni(r, -2, 2)), D = cylgen_uniform(r) < 0.5 ? 0 : 1e3 * S;
    double w[3];
    sref_unit(r, w);
    for (int k = 0; k < 3; k++)
        m[k] = D * w[k] + S * uni(r, -2, 2);
    double h = S * uni(r, 0.2, 3), r0 = S * uni(r, 0.1, 2), r1 = S * uni(r, 0.1, 2);
    switch (kind) {
    case K_TIP:
        if (cylgen_uniform(r) < 0.5)
            r0 = 0;
        else
            r1 = 0;
        break;
    case K_NEARCYL:
        r1 = r0 * (1 + 1e-6 * uni(r, -1, 1));
        break;
    case K_STEEP:
        h = S * uni(r, 2, 20), r1 = r0 * uni(r, 0.9, 1.1);
        break;
    case K_FLAT:
        h = S * uni(r, 0.001, 0.05);
        break;
    default:
        break;
    }
    for (int k = 0; k < 3; k++) {
        c->p0[k] = (float)(m[k] - 0.5 * h * u[k]);
        c->p1[k] = (float)(m[k] + 0.5 * h * u[k]);
    }
    c->r0 = (float)r0, c->r1 = (float)r1;
    const unsigned caps[4] = {0, CYLRAY_CAPPED_LO, CYLRAY_CAPPED_HI, CYLRAY_CAPPED};
    c->flags = caps[cylgen_next(r) % 4 == 0 ? cylgen_next(r) % 3 : 3];
}

/* ---- the exact cone: the prepared one (c, v, H, r0, r1, kap) in binary128 --------- */

typedef struct {
    cylq c[3], v[3], sv, H, rlo, rhi;
} qcone;

static void qcone_of(const cylray_prepared *P, qcone *q)
{
    cylq vv = 0;
    for (int k = 0; k < 3; k++) {
        q->c[k] = P->c[k], q->v[k] = P->v[k];
        vv += q->v[k] * q->v[k];
    }
    q->sv = q_sqrt(vv);
    q->H = P->half_height;
    /* the kernels' radius, from the narrower end: ra + dk (q - qa) at z = q H |v| */
    const cylq dk = (cylq)P->kap * q->H * q->sv, qa = P->kap > 0 ? -1 : 1;
    const cylq ra = P->kap > 0 ? P->r0 : P->r1;
    q->rlo = q_max(0, ra + dk * (-1 - qa)), q->rhi = q_max(0, ra + dk * (1 - qa));
    if (P->kap == 0) /* prepared as a cylinder: r0 and r1 are not set */
        q->rlo = q->rhi = P->radius;
}

/* x's axial coordinate and distance from the axis */
static void q_coords(const qcone *q, const float x[3], cylq *z, cylq *rho)
{
    cylq a[3], av = 0, aa = 0;
    for (int k = 0; k < 3; k++) {
        a[k] = (cylq)x[k] - q->c[k];
        av += a[k] * q->v[k];
        aa += a[k] * a[k];
    }
    *z = av / q->sv;
    *rho = q_sqrt(q_max(0, aa - *z * *z));
}

/* The exact distance of x from the part */
static double q_dist(const qcone *q, const float x[3], int part)
{
    cylq z, rho, fr, fz;
    q_coords(q, x, &z, &rho);
    if (part == CYLRAY_SIDE) {
        const cylq dR = q->rhi - q->rlo, dZ = 2 * q->H;
        cylq t = ((rho - q->rlo) * dR + (z + q->H) * dZ) / (dR * dR + dZ * dZ);
        t = q_min(1, q_max(0, t));
        fr = q->rlo + t * dR, fz = -q->H + t * dZ;
    } else {
        const int hi = part == CYLRAY_CAP_HI;
        fr = q_min(rho, hi ? q->rhi : q->rlo), fz = hi ? q->H : -q->H;
    }
    return (double)q_sqrt((rho - fr) * (rho - fr) + (z - fz) * (z - fz));
}

/* The sign of x's side of the part's surface (the side's infinite cone, the disc's
 * plane): +1 outside */
static int q_side(const qcone *q, const float x[3], int part)
{
    cylq z, rho;
    q_coords(q, x, &z, &rho);
    cylq s;
    if (part == CYLRAY_SIDE)
        s = rho * 2 * q->H - (q->rlo * (q->H - z) + q->rhi * (q->H + z));
    else
        s = part == CYLRAY_CAP_HI ? z - q->H : -q->H - z;
    return s > 0 ? 1 : s < 0 ? -1 : 0;
}

/* The part's outward normal at x, in double */
static void d_normal(const cylray_prepared *P, const float x[3], int part, double n[3])
{
    double a[3], v[3], vv = 0, av = 0;
    for (int k = 0; k < 3; k++) {
        a[k] = (double)x[k] - P->c[k], v[k] = P->v[k];
        vv += v[k] * v[k], av += a[k] * v[k];
    }
    const double sv = sqrt(vv);
    if (part != CYLRAY_SIDE) {
        for (int k = 0; k < 3; k++)
            n[k] = (part == CYLRAY_CAP_HI ? 1 : -1) * v[k] / sv;
        return;
    }
    double r[3], l = 0;
    for (int k = 0; k < 3; k++) {
        r[k] = a[k] - av / vv * v[k];
        l += r[k] * r[k];
    }
    l = sqrt(l);
    const double kk = (double)P->kap * sv, cn = 1 / sqrt(1 + kk * kk);
    for (int k = 0; k < 3; k++)
        n[k] = (l > 0 ? r[k] / l - kk * v[k] / sv : 0) * cn;
}

/* 16 rays from outside at random points of the cone's surface (or from inside) */
static void make_rays(cylgen_rng *r, const cylray_prepared *P, float o[16][3], float d[16][3])
{
    double v[3], vv = 0;
    for (int k = 0; k < 3; k++)
        v[k] = P->v[k], vv += v[k] * v[k];
    const double sv = sqrt(vv), H = P->half_height, S = P->radius + H;
    double e1[3], e2[3], t[3] = {v[1], -v[0], 0};
    if (fabs(v[2]) > fabs(v[0]))
        t[0] = 0, t[1] = v[2], t[2] = -v[1];
    double l = sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
    for (int k = 0; k < 3; k++)
        e1[k] = t[k] / l;
    e2[0] = (v[1] * e1[2] - v[2] * e1[1]) / sv;
    e2[1] = (v[2] * e1[0] - v[0] * e1[2]) / sv;
    e2[2] = (v[0] * e1[1] - v[1] * e1[0]) / sv;
    for (int i = 0; i < 16; i++) {
        const double zz = uni(r, -1, 1), ph = uni(r, 0, 6.283185307179586);
        double rr = (1 - zz) / 2 * P->r0 + (1 + zz) / 2 * P->r1;
        double z = zz * H;
        const double sel = cylgen_uniform(r);
        const double rd = sel < 0.125 ? P->r0 : P->r1;
        if (sel < 0.25 && rd > 0) /* a disc (a tip's, of radius 0, is the apex: not aimed at) */
            z = sel < 0.125 ? -H : H, rr = rd * sqrt(uni(r, 0, 1));
        double tgt[3], u[3];
        for (int k = 0; k < 3; k++)
            tgt[k] = P->c[k] + z * v[k] / sv + rr * (cos(ph) * e1[k] + sin(ph) * e2[k]);
        sref_unit(r, u);
        const double len = pow(10, uni(r, -2, 2));
        if (cylgen_uniform(r) < 0.8) {
            const double Dd = S * pow(10, uni(r, 0.1, 2));
            double dd[3], dl = 0;
            for (int k = 0; k < 3; k++) {
                o[i][k] = (float)(tgt[k] + Dd * u[k]);
                dd[k] = tgt[k] - o[i][k], dl += dd[k] * dd[k];
            }
            dl = sqrt(dl);
            for (int k = 0; k < 3; k++)
                d[i][k] = (float)(len * dd[k] / dl);
        } else {
            for (int k = 0; k < 3; k++) {
                o[i][k] = (float)(P->c[k] + 0.3 * (tgt[k] - P->c[k]));
                d[i][k] = (float)(len * (tgt[k] - o[i][k]));
            }
        }
    }
}

static uint32_t trace(const cylray_kernels *K, const cylray_prepared *P, const float o[][3],
                      const float d[][3], uint32_t act, float t[16], int32_t part[16],
                      float n[16][3])
{
    cylray_ray16 ray;
    cylray_hit16 hit;
    memset(&ray, 0, sizeof ray);
    memset(&hit, 0, sizeof hit);
    for (int i = 0; i < 16; i++) {
        ray.ox[i] = o[i][0], ray.oy[i] = o[i][1], ray.oz[i] = o[i][2];
        ray.dx[i] = d[i][0], ray.dy[i] = d[i][1], ray.dz[i] = d[i][2];
        ray.tmin[i] = 0, ray.tmax[i] = INFINITY;
    }
    const uint32_t m = K->intersect16(P, &ray, &hit, act, CYLRAY_NORMAL);
    for (int i = 0; i < 16; i++) {
        t[i] = hit.t[i], part[i] = hit.part[i];
        n[i][0] = hit.nx[i], n[i][1] = hit.ny[i], n[i][2] = hit.nz[i];
    }
    return m;
}

static int prepare(cylgen_rng *rng, long g, cylray_cone *c, cylray_prepared *P)
{
    make_cone(rng, (int)(g % K_COUNT), c);
    return cylray_prepare_cone(P, c) == CYLRAY_OK;
}

/* ---- bounds -------------------------------------------------------------------- */

static int run_bounds(void)
{
    const long N = scaled(20000);
    long checked = 0, viol = 0;
    double worst = 0;
    cylgen_rng rng;
    cylgen_seed(&rng, 5101);
    for (long g = 0; g < N; g++) {
        cylray_cone c;
        cylray_prepared P;
        if (!prepare(&rng, g, &c, &P))
            continue;
        qcone q;
        qcone_of(&P, &q);
        float o[16][3], d[16][3], t[16], n[16][3];
        int32_t part[16];
        make_rays(&rng, &P, o, d);
        const uint32_t m = trace(isas[g % nisa], &P, (const float(*)[3])o, (const float(*)[3])d,
                                 0xffffu, t, part, n);
        for (int i = 0; i < 16; i++) {
            if (!(m >> i & 1u))
                continue;
            for (int form = 0; form < 2; form++) {
                float p[3], err;
                hit_point_form(&P, o[i], d[i], t[i], part[i], n[i], form, p, &err);
                const double dist = q_dist(&q, p, part[i] & CYLRAY_PART_MASK);
                checked++;
                if (!(dist <= err)) {
                    viol++;
                    fail("bound", &c, dist, err);
                }
                const double pm = fmax(fabs(p[0]), fmax(fabs(p[1]), fabs(p[2])));
                int e;
                frexp(pm, &e);
                worst = fmax(worst, err / ldexp(1, e - 24));
            }
        }
    }
    printf("bounds: %ld points checked, %ld violations; largest err %.3g ulps of the largest "
           "coordinate\n",
           checked, viol, worst);
    return viol == 0 && checked > 0;
}

/* ---- spawned rays -------------------------------------------------------------- */

static int run_self(void)
{
    const long N = scaled(65000); /* groups of 16 a path: 10^6 spawns */
    long spawns = 0, self = 0, wrong = 0, side_spawns = 0, side_wrong = 0, inward = 0,
         wrong_in = 0, apex = 0;
    cylgen_rng rng;
    cylgen_seed(&rng, 5202);
    for (int ki = 0; ki < nisa; ki++) {
        const cylray_kernels *K = isas[ki];
        long ks = 0, kself = 0;
        for (long g = 0; g < N; g++) {
            cylray_cone c;
            cylray_prepared P;
            if (!prepare(&rng, g, &c, &P))
                continue;
            qcone q;
            qcone_of(&P, &q);
            float o[16][3], d[16][3], t[16], n[16][3];
            int32_t part[16];
            make_rays(&rng, &P, o, d);
            const uint32_t m =
                trace(K, &P, (const float(*)[3])o, (const float(*)[3])d, 0xffffu, t, part, n);
            float x0[16][3], w[16][3], p[16][3];
            uint32_t act = 0;
            for (int i = 0; i < 16; i++) {
                if (!(m >> i & 1u))
                    continue;
                const int pt = part[i] & CYLRAY_PART_MASK;
                float err;
                cylray_hit_point_normal(&P, o[i], d[i], t[i], part[i], n[i], p[i], &err);
                double no[3], u[3], wn = 0, dn = 0, wl = 0;
                d_normal(&P, p[i], pt, no);
                for (int k = 0; k < 3; k++)
                    dn += (double)d[i][k] * no[k];
                const int kind = (int)(cylgen_next(&rng) % 3);
                if (kind == 0 && dn < 0) { /* the mirror direction off the outside */
                    for (int k = 0; k < 3; k++)
                        u[k] = d[i][k] - 2 * dn * no[k];
                } else { /* leaving the solid, at random */
                    sref_unit(&rng, u);
                    double un = u[0] * no[0] + u[1] * no[1] + u[2] * no[2];
                    if (un < 0)
                        for (int k = 0; k < 3; k++)
                            u[k] -= 2 * un * no[k];
                }
                for (int k = 0; k < 3; k++) {
                    w[i][k] = (float)u[k];
                    wn += (double)w[i][k] * no[k];
                    wl += (double)w[i][k] * w[i][k];
                }
                if (!(wn > 1e-7 * sqrt(wl))) /* too near the plane to call it leaving */
                    continue;
                const int sideform = (cylgen_next(&rng) & 3) == 0;
                if (sideform)
                    cylray_spawn_origin_side(&P, p[i], err, part[i], 1, w[i], x0[i]);
                else
                    cylray_spawn_origin(&P, p[i], err, part[i], w[i], x0[i]);
                /* into the solid: the side only (a hit beyond is right) */
                const float wi[3] = {-w[i][0], -w[i][1], -w[i][2]};
                float xi[3];
                if (sideform)
                    cylray_spawn_origin_side(&P, p[i], err, part[i], 0, w[i], xi);
                else
                    cylray_spawn_origin(&P, p[i], err, part[i], wi, xi);
                /* at the apex "inside" is a vanishing cone: docs/secondary-rays.md */
                cylq z, rho;
                q_coords(&q, p[i], &z, &rho);
                const cylq rz = (q.rlo * (q.H - z) + q.rhi * (q.H + z)) / (2 * q.H);
                /* an acute rim of a flat cone (a wedge thinner than 1/100): moving into
                 * it by the margins needs a depth of margin / angle, which may leave the
                 * solid (docs/secondary-rays.md) */
                const cylq rw = q.rlo > q.rhi ? q.rlo : q.rhi, zw = q.rlo > q.rhi ? -q.H : q.H;
                const int sharp = 2 * q.H < (cylq)0.01 * q_abs(q.rhi - q.rlo) &&
                                  q_abs(rho - rw) + q_abs(z - zw) < (cylq)1e-3 * rw;
                /* or a solid (or an apex's cross-section) a few hundred ulps across:
                 * inward margins cross it */
                const double pm = fmax(fabs(p[i][0]), fmax(fabs(p[i][1]), fabs(p[i][2])));
                const int thin = 2 * (double)q.H < 0x1p-13 * pm;
                if (rz < (cylq)1e-4 * (cylq)P.radius || rz < (cylq)(0x1p-13 * pm) || sharp ||
                    thin) {
                    apex++;
                } else if (inward++, q_side(&q, xi, pt) != -1) {
                    wrong_in++;
                    fail("inward origin not inside", &c, (double)p[i][0], (double)xi[0]);
                }
                if (q_side(&q, x0[i], pt) != 1) {
                    *(sideform ? &side_wrong : &wrong) += 1;
                    fail(sideform ? "side form: not outside" : "not on w's side", &c,
                         (double)p[i][0], (double)x0[i][0]);
                }
                side_spawns += sideform;
                act |= 1u << i;
            }
            float t2[16], n2[16][3];
            int32_t part2[16];
            const uint32_t m2 =
                trace(K, &P, (const float(*)[3])x0, (const float(*)[3])w, act, t2, part2, n2);
            ks += __builtin_popcount(act);
            for (int i = 0; i < 16; i++)
                if (m2 >> i & 1u) {
                    kself++;
                    fail("self-intersection", &c, (double)t2[i], (double)part2[i]);
                    printf("  %s: part %d, p=(%a, %a, %a) w=(%a, %a, %a) origin=(%a, %a, %a)\n",
                           K->name, (int)part[i], (double)p[i][0], (double)p[i][1],
                           (double)p[i][2], (double)w[i][0], (double)w[i][1], (double)w[i][2],
                           (double)x0[i][0], (double)x0[i][1], (double)x0[i][2]);
                }
        }
        printf("self %s: %ld spawns, %ld hit their cone\n", K->name, ks, kself);
        spawns += ks, self += kself;
    }
    printf("self: %ld spawns (%ld side form), %ld self-intersections, %ld off w's side, %ld "
           "side form off its side; %ld inward origins, %ld not inside (%ld at an apex "
           "unchecked)\n",
           spawns, side_spawns, self, wrong, side_wrong, inward, wrong_in, apex);
    return spawns > 0 && self == 0 && wrong == 0 && side_wrong == 0 && wrong_in == 0;
}

/* ---- batched forms --------------------------------------------------------------- */

static void batched_group(cylgen_rng *rng, long g, spawn_tally *tally)
{
    cylray_cone cs[16];
    cylray_prepared P[16];
    int ok = 1;
    for (int j = 0; j < 16 && ok; j++)
        ok = prepare(rng, g * 16 + j, &cs[j], &P[j]) && cs[j].r0 != cs[j].r1;
    if (!ok)
        return;
    cylray_leaf16 leaf;
    if (cylray_leaf_prepare_cones16(&leaf, cs, NULL, 16) != CYLRAY_OK)
        return;
    const int j = (int)(g % 16);
    const cylray_kernels *K = isas[g % nisa];
    float o[16][3], d[16][3], t[16], n[16][3];
    int32_t part[16];
    make_rays(rng, &P[j], o, d);
    const uint32_t m =
        trace(K, &P[j], (const float(*)[3])o, (const float(*)[3])d, 0xffffu, t, part, n);
    if (!m)
        return;
    float ox[16], oy[16], oz[16], dx[16], dy[16], dz[16], tt[16], nx[16], ny[16], nz[16];
    float px[16], py[16], pz[16], pe[16], lx[16], ly[16], lz[16], le[16];
    float wx[16], wy[16], wz[16], sx[16], sy[16], sz[16], fx[16], fy[16], fz[16];
    int32_t pp[16];
    cylray_ray1 r1[16];
    cylray_hit1 h1[16];
    const cylray_leaf16 *lv[16];
    int cnt = 0;
    for (int i = 0; i < 16; i++) {
        if (!(m >> i & 1u))
            continue;
        ox[cnt] = o[i][0], oy[cnt] = o[i][1], oz[cnt] = o[i][2];
        dx[cnt] = d[i][0], dy[cnt] = d[i][1], dz[cnt] = d[i][2];
        tt[cnt] = t[i], nx[cnt] = n[i][0], ny[cnt] = n[i][1], nz[cnt] = n[i][2];
        pp[cnt] = part[i];
        double u[3];
        sref_unit(rng, u);
        wx[cnt] = (float)u[0], wy[cnt] = (float)u[1], wz[cnt] = (float)u[2];
        memset(&r1[cnt], 0, sizeof r1[cnt]);
        memcpy(r1[cnt].o, o[i], sizeof o[i]);
        memcpy(r1[cnt].d, d[i], sizeof d[i]);
        memset(&h1[cnt], 0, sizeof h1[cnt]);
        h1[cnt].t = t[i], h1[cnt].part = part[i], h1[cnt].lane = (uint32_t)j;
        memcpy(h1[cnt].n, n[i], sizeof n[i]);
        lv[cnt] = &leaf;
        cnt++;
    }
    const cylray_rays rays = {ox, oy, oz, dx, dy, dz, NULL, NULL};
    const cylray_hits hits = {tt, nx, ny, nz, pp};
    const cylray_points pts = {px, py, pz, pe}, lpts = {lx, ly, lz, le};
    const cylray_points dirs = {wx, wy, wz, NULL}, org = {sx, sy, sz, NULL};
    const cylray_points lorg = {fx, fy, fz, NULL};
    K->hit_points_normal_stream(&P[j], &rays, &hits, &pts, (size_t)cnt);
    K->leaf_hit_points_normal16(lv, r1, h1, &lpts, (size_t)cnt);
    K->spawn_stream(&P[j], &pts, pp, &dirs, &org, (size_t)cnt);
    K->leaf_spawn_origins16(lv, h1, &pts, &dirs, &lorg, (size_t)cnt);
    for (int i = 0; i < cnt; i++) {
        const float oo[3] = {ox[i], oy[i], oz[i]}, dd[3] = {dx[i], dy[i], dz[i]};
        const float nn[3] = {nx[i], ny[i], nz[i]}, ww[3] = {wx[i], wy[i], wz[i]};
        float ps[3], es, xs[3];
        cylray_hit_point_normal(&P[j], oo, dd, tt[i], pp[i], nn, ps, &es);
        cylray_spawn_origin(&P[j], ps, es, pp[i], ww, xs);
        const float a[3] = {px[i], py[i], pz[i]}, b[3] = {lx[i], ly[i], lz[i]};
        const float sa[3] = {sx[i], sy[i], sz[i]}, sb[3] = {fx[i], fy[i], fz[i]};
        tally->compared++;
        if (!sref_same3(a, ps) || !tc_same(pe[i], es) || !sref_same3(b, ps) ||
            !tc_same(le[i], es) || !sref_same3(sa, xs) || !sref_same3(sb, xs)) {
            tally->differ++;
            fail("batched differs from scalar", &cs[j], (double)ps[0], (double)px[i]);
        }
    }
}

static int run_batched(void)
{
    spawn_tally t = {0, 0};
    const int ok = spawn_groups(scaled(3000), 5303, batched_group, &t);
    printf("batched: %ld hits compared (stream, leaf; points and origins), %ld differ\n",
           t.compared, t.differ);
    return ok;
}

static const spawn_mode modes[] = {
    {"bounds", run_bounds}, {"self", run_self}, {"batched", run_batched}};

int main(int argc, char **argv)
{
    return spawn_main(argc, argv, "spawn_cone", modes, sizeof modes / sizeof modes[0]);
}
