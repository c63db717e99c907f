/* SPDX-License-Identifier: MIT */
/* kernel/kmath.h - the side's quadratic and the root polish, on vectors. */

#define KDOT(ax, ay, az, bx, by, bz) vfma(ax, bx, vfma(ay, by, vmul(az, bz)))
/* c - a*b and a*b - c rounded once, as vfma_x: where they cancel, a product rounded
 * on its own would be the whole result's error (SSE4.1 has no FMA). */
#define vfnma_x(a, b, c) vfma_x(vneg(a), b, c)
#define vfms_x(a, b, c) vfma_x(a, b, vneg(c))
/* KDOT with every step fused, also where there is no FMA (KDOT rounds each product) */
#define KDOTX(ax, ay, az, bx, by, bz) vfma_x(ax, bx, vfma_x(ay, by, vmul(az, bz)))

/* ax bx + ay by + az bz + c where the terms cancel far below themselves: Ogita, Rump
 * and Oishi's Dot2, each product split exactly by vfms (fused, or formed in double) and
 * each sum by a two-sum, so that the result is as good as one formed in twice the
 * precision and rounded (about an ulp of it, and 2^-45 of the terms). An ISA whose
 * vfms is not exact (SSE4.1) defines vdot3_x in double instead, as it forms vsumsq_x:
 * KSUMSQ_CHAINED says whether vsumsq_x is a chain of roundings that vdot3_x betters. */
#ifdef vdot3_x
#define KSUMSQ_CHAINED 0
#else
#define KSUMSQ_CHAINED 1
CYLRAY_INLINE vf KFN(two_sum)(vf a, vf b, vf *err)
{
    const vf s = vadd(a, b), bb = vsub(s, a);
    *err = vadd(vsub(a, vsub(s, bb)), vsub(b, bb));
    return s;
}
CYLRAY_INLINE vf KFN(dot3_x)(vf ax, vf ay, vf az, vf bx, vf by, vf bz, vf c)
{
    const vf px = vmul(ax, bx), py = vmul(ay, by), pz = vmul(az, bz);
    const vf ep = vadd(vadd(vfms(ax, bx, px), vfms(ay, by, py)), vfms(az, bz, pz));
    vf e1, e2, e3;
    const vf s = KFN(two_sum)(KFN(two_sum)(KFN(two_sum)(px, py, &e1), pz, &e2), c, &e3);
    return vadd(s, vadd(ep, vadd(e1, vadd(e2, e3))));
}
#define vdot3_x(ax, ay, az, bx, by, bz, c) KFN(dot3_x)(ax, ay, az, bx, by, bz, c)
#endif

/* 1 / x where the kernel only needs some value near it (a shift, a slide): the
 * divider's correctly rounded quotient, so that every CPU of one ISA gives the same
 * answers; the hardware estimate (rcpps's table differs between vendors) only under
 * CYLRAY_FAST, whose answers are documented to differ. */
#define KRCP(F, x) ((F).fast ? vrcp_fast(x) : vdiv(vset1(1.0f), (x)))

/* The side's quadratic from the shifted origin p: f = v x p (so that nB = e.f is -B),
 * C = f.f - R^2 v.v and g = e.p, the triple product of Lagrange's form (with an
 * aligned axis g is the caller's, from the unshifted origin). */
CYLRAY_INLINE void KFN(side_coefs)(vf rr_vv, int aligned, vf dx, vf dy, vf ex, vf ey, vf ez,
                                   vf vx, vf vy, vf vz, vf px, vf py, vf pz, vf *fx, vf *fy,
                                   vf *fz, vf *nB, vf *C, vf *g)
{
    const vf zero = vzero();
    if (aligned) {
        *fx = *fy = *fz = zero;
        *nB = vfnma(dx, px, vfnma(dy, py, zero));
        *C = vsub(vfma(px, px, vmul(py, py)), rr_vv);
    } else {
        *fx = vfms(vy, pz, vmul(vz, py));
        *fy = vfms(vz, px, vmul(vx, pz));
        *fz = vfms(vx, py, vmul(vy, px));
        *nB = KDOT(ex, ey, ez, *fx, *fy, *fz);
        *C = vsumsq_x(*fx, *fy, *fz, rr_vv);
        *g = KDOT(ex, ey, ez, px, py, pz);
    }
}

/* Root polishing (CYLRAY_REFINE): the side's quadratic (a sphere's) again from the
 * point q at the root r, where C is tiny and the small root C / q2 is a correction of a few ulps; the
 * result is then limited by the rounding of q, not by the distance of the shifted
 * origin. Returns the polished root where that helps, r elsewhere. */
CYLRAY_INLINE vf KFN(polish)(vf rr_vv, vf rr, int aligned, int sphere, vm side, vf r, vf A,
                             vf dx, vf dy, vf dz, vf ex, vf ey, vf ez, vf vx, vf vy, vf vz,
                             vf px, vf py, vf pz)
{
    const vf zero = vzero();
    vf qx = vfma_x(r, dx, px), qy = vfma_x(r, dy, py), qz = vfma_x(r, dz, pz);
    vf B2, C2;
    if (sphere) {
        B2 = KDOT(dx, dy, dz, qx, qy, qz);
        C2 = vsumsq_x(qx, qy, qz, rr_vv);
    } else if (aligned) {
        B2 = vfma(dx, qx, vmul(dy, qy));
        C2 = vsub(vfma(qx, qx, vmul(qy, qy)), rr_vv);
    } else {
        vf gx = vfms(qy, vz, vmul(qz, vy)), gy = vfms(qz, vx, vmul(qx, vz)),
           gz = vfms(qx, vy, vmul(qy, vx));
        B2 = KDOT(ex, ey, ez, gx, gy, gz);
        C2 = vsub(KDOT(gx, gy, gz, gx, gy, gz), rr_vv);
    }
    vf D2 = vmax(vfms(B2, B2, vmul(A, C2)), zero);
    vf q2 = vneg(vadd(B2, vcopysign(vsqrt(D2), B2)));
    vf dt = vdiv(C2, q2);
    /* The polish point carries a rounding error relative to its own distance from c:
     * it only helps where that is not much beyond the shifted origin's. And the small
     * root dt is a correction only while the other one, q2 / A, lies well beyond it:
     * near a tangency the two merge (or, with D2 clamped, dt is a Newton step on a
     * flat quadratic), and the first root is as good as any. */
    vf qq = KDOT(qx, qy, qz, qx, qy, qz);
    vf near = vmul(vset1(4.0f), vmax(KDOT(px, py, pz, px, py, pz), rr));
    vm apart = vle(vmul(vabs(dt), vmul(A, vset1(4.0f))), vabs(q2));
    vm keep = mand(mand(side, mand(vle(qq, near), apart)), vlt(vabs(dt), vset1(INFINITY)));
    return vsel(keep, vadd(r, dt), r);
}
