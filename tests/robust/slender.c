/* SPDX-License-Identifier: MIT */
/* slender.c - cylinders, tip cones and truncated cones 10 to 1e6 radii long, along a
 * coordinate axis with exact (dyadic) ends, and rays from beside the whole length: from
 * next to the side, grazing it, from inside, and (tip cones) about the apex. Each answer
 * is judged against the exact cone (conref) with a band of the ray's own floats alone:
 * each of o and d moved by 2 ulps, one at a time, the shape exact. That band does not
 * widen with the shape's length, as one that tilts the axis does, so a kernel that
 * rounds at the size of the shape rather than of the radius where the ray meets it
 * fails here (the center's frame kept 10 bits of t at 1e4 radii). Every path, packets
 * of 8, plain and REFINE; prints the worst |dt| / (kappa + ulp) per length. */
#include "conref.h"
#include "cylray.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

static uint64_t rng = 0x9e3779b97f4a7c15u;
static double uni(double a, double b)
{
    rng = rng * 6364136223846793005u + 1442695040888963407u;
    return a + (b - a) * (double)(rng >> 11) * 0x1p-53;
}

typedef struct {
    float o[3], d[3];
} ray;

/* the exact answer, and how far 2 ulps of each ray float move its t (-1: the outcome
 * itself moves) */
static double kappa_of(const cylray_cone *c, const ray *r, const cylref_hit *ex)
{
    double k = 0;
    for (int i = 0; i < 6; i++)
        for (int sgn = -1; sgn <= 1; sgn += 2) {
            ray q = *r;
            float *x = i < 3 ? &q.o[i] : &q.d[i - 3];
            for (int u = 0; u < 2; u++)
                *x = nextafterf(*x, sgn * INFINITY);
            cylref_hit h;
            conref_intersect(c, q.o, q.d, 0, INFINITY, 0, &h);
            if (h.hit != ex->hit || (h.hit && (h.part & 0xf) != (ex->part & 0xf)))
                return -1;
            if (h.hit && fabs(h.t - ex->t) > k)
                k = fabs(h.t - ex->t);
        }
    return k;
}

/* a ray of the cone along axis ax (0..2) from p0, length L, radii r0 and r1 */
static void make_ray(const double base[3], int ax, double L, double r0, double r1, int tip,
                     ray *out)
{
    const int a1 = (ax + 1) % 3, a2 = (ax + 2) % 3;
    double z = uni(0, 1) * L, rz = r0 + (r1 - r0) * z / L;
    double kind = uni(0, 1), rho, phi = uni(0, 6.283185307179586), zt, rt;
    if (tip && kind < 0.2) { /* about the apex */
        z = (r0 == 0 ? 0 : L) + uni(-3, 3) * (r0 + r1);
        rho = uni(0.01, 3) * (r0 + r1);
        zt = r0 == 0 ? 0 : L, rt = (r0 + r1) * pow(2, uni(-30, -8));
    } else {
        rho = kind < 0.35 ? rz * uni(0, 0.99) : rz * (1 + pow(2, uni(-24, 1)));
        zt = z + uni(-8, 8) * (rz + 1e-3 * (r0 + r1)) * (kind < 0.6 ? 1 : 30);
        const double rzt = r0 + (r1 - r0) * fmin(fmax(zt, 0), L) / L;
        rt = rzt * (kind < 0.8 ? uni(0, 1.05) : 1 - pow(2, uni(-30, -10)));
    }
    const double psi = uni(0, 6.283185307179586);
    double o[3], t[3];
    o[ax] = base[ax] + z, o[a1] = base[a1] + rho * cos(phi), o[a2] = base[a2] + rho * sin(phi);
    t[ax] = base[ax] + zt, t[a1] = base[a1] + rt * cos(psi), t[a2] = base[a2] + rt * sin(psi);
    double d[3] = {t[0] - o[0], t[1] - o[1], t[2] - o[2]};
    const double n = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (int i = 0; i < 3; i++)
        out->o[i] = (float)o[i], out->d[i] = (float)(d[i] / n);
}

int main(void)
{
    static const double aspects[] = {1e1, 1e2, 1e3, 1e4, 1e5, 1e6};
    static const char *const shapes[] = {"cylinder", "tip at p0", "tip at p1", "frustum"};
    static const double rr[4][2] = {{1, 1}, {0, 1}, {1, 0}, {1, 0.5}};
    static const double base[3] = {3, -5, 7};
    enum { NRAY = 96 };
    int failures = 0, checks = 0;
    printf("%-9s %-10s %-7s %8s %8s %6s\n", "L/r", "shape", "path", "worst", "ulps", "lanes");
    for (size_t ai = 0; ai < sizeof aspects / sizeof aspects[0]; ai++)
        for (int si = 0; si < 4; si++) {
            const double L = aspects[ai];
            const int ax = (int)(ai + (size_t)si) % 3;
            cylray_cone c;
            memset(&c, 0, sizeof c);
            for (int i = 0; i < 3; i++)
                c.p0[i] = (float)base[i], c.p1[i] = (float)base[i];
            c.p1[ax] = (float)(base[ax] + L);
            c.r0 = (float)rr[si][0], c.r1 = (float)rr[si][1], c.flags = CYLRAY_CAPPED;
            cylray_prepared P;
            if (cylray_prepare_cone(&P, &c) != CYLRAY_OK) {
                printf("FAIL prepare %g %s\n", L, shapes[si]);
                failures++;
                continue;
            }
            ray rays[NRAY];
            cylref_hit ex[NRAY];
            double kap[NRAY];
            for (int i = 0; i < NRAY; i++) {
                make_ray(base, ax, L, rr[si][0], rr[si][1], si == 1 || si == 2, &rays[i]);
                conref_intersect(&c, rays[i].o, rays[i].d, 0, INFINITY, 0, &ex[i]);
                kap[i] = kappa_of(&c, &rays[i], &ex[i]);
            }
            for (int isa = 0; isa < CYLRAY_ISA_COUNT; isa++) {
                const cylray_kernels *k = cylray_kernels_for((cylray_isa)isa);
                if (!k)
                    continue;
                for (int fl = 0; fl < 2; fl++) {
                    const unsigned flags = fl ? CYLRAY_REFINE | CYLRAY_NORMAL : 0u;
                    double worst = 0, wulps = 0;
                    int lanes = 0;
                    for (int b = 0; b < NRAY; b += 8) {
                        _Alignas(32) cylray_ray8 R;
                        _Alignas(32) cylray_hit8 H;
                        memset(&H, 0, sizeof H);
                        for (int l = 0; l < 8; l++) {
                            const ray *q = &rays[b + l];
                            R.ox[l] = q->o[0], R.oy[l] = q->o[1], R.oz[l] = q->o[2];
                            R.dx[l] = q->d[0], R.dy[l] = q->d[1], R.dz[l] = q->d[2];
                            R.tmin[l] = 0, R.tmax[l] = INFINITY;
                        }
                        const uint32_t m = k->intersect8(&P, &R, &H, 0xffu, flags);
                        for (int l = 0; l < 8; l++) {
                            const int i = b + l, hit = (int)(m >> l) & 1;
                            checks++;
                            if (kap[i] < 0)
                                continue; /* the outcome is the inputs' own */
                            if (hit != ex[i].hit ||
                                (hit && (H.part[l] & 0xf) != (ex[i].part & 0xf))) {
                                if (failures++ < 20)
                                    printf("FAIL %s %g %s ray %d flags 0x%x: hit %d part %d, "
                                           "exact %d part %d\n",
                                           k->name, L, shapes[si], i, flags, hit, H.part[l],
                                           ex[i].hit, ex[i].part);
                                continue;
                            }
                            if (!hit)
                                continue;
                            lanes++;
                            const double ulp = ldexp(1.0, ilogb(ex[i].t) - 23);
                            const double dt = fabs(H.t[l] - ex[i].t);
                            const double ratio = dt / (kap[i] + ulp);
                            if (ratio > worst)
                                worst = ratio;
                            if (dt / ulp > wulps)
                                wulps = dt / ulp;
                            if (dt > kap[i] + 4 * ulp && failures++ < 20)
                                printf("FAIL %s %g %s ray %d flags 0x%x: t %.9g exact %.9g "
                                       "kappa %.3g (%.1f ulps beyond)\n",
                                       k->name, L, shapes[si], i, flags, H.t[l], ex[i].t,
                                       kap[i], (dt - kap[i]) / ulp);
                        }
                    }
                    if (!fl)
                        printf("%-9g %-10s %-7s %8.2f %8.1f %6d\n", L, shapes[si], k->name,
                               worst, wulps, lanes);
                }
            }
        }
    printf("%d checks, %d failures\n", checks, failures);
    return failures != 0;
}
