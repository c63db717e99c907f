/* SPDX-License-Identifier: MIT */
/* kernel_tmpl.h - the ray/cylinder kernel, written once against the vector vocabulary.
 *
 * Included once per ISA and width, after a vec_*.h header, with:
 *   KFN(name)  the name with this instantiation's suffix (e.g. name_avx2_8)
 *   VW         lanes per vector
 * It defines KFN(block), the kernel for one vector of rays, and the flag-specialised
 * packet and stream drivers with their lookup tables: KFN(isect1_table) and
 * KFN(occ1_table) for packets of one vector, KFN(isect_table) and KFN(occ_table) for
 * packets of several, KFN(isect_stream_table) and KFN(occ_stream_table); KFN(vw) = VW.
 *
 * The math is docs/design.md section 2. Coordinates are cylinder-relative: w = o - c is
 * formed exactly as a two-term sum, then the origin is moved along the ray to its
 * closest approach to the center (with the product s*d exact inside an FMA), so that
 * the error of everything after grows with the distance from there, not from o. The
 * axis v is the user's, scaled by a power of two, never normalised: v.v is carried
 * through instead. With e = d x v, f = w' x v, the side is A t^2 + 2 B t + C = 0 with
 *   A = e.e,  B = e.f,  C = f.f - R^2 v.v,  disc = v.v (A R^2 - g^2),  g = e.w'.
 */

#ifndef CYLRAY_KERNEL_MARGINS_
#define CYLRAY_KERNEL_MARGINS_
/* The margins the kernel decides with, each with why it is safe.
 *
 * KM_DD_LO, KM_DD_HI: an active lane whose |d|^2 lies outside [2^-40, 2^40] goes to the
 *   rare instance (2^-40 keeps A R^2 clear of underflow for the smallest radius prepare
 *   takes with j = 0, 2^-20 squared twice over; 2^40 keeps d.d times coordinates of
 *   2^62 below the float range after the shift).
 * KM_SPHERE: the slack of the sphere rejection, relative to |w|^2. The rounding of
 *   w, w.w, w.d and the refined reciprocal moves the closest approach's squared
 *   distance by less than 2^-19 |w|^2; 2^-17 leaves a factor 4.
 * KM_TUBE_A, KM_TUBE_WW: the tube rejection. g0 = e.w from the rounded w is off from
 *   g by d <= 2^-21 sqrt(A ww); the line misses when |g| > R sqrt(A), and
 *   (R sqrt(A) + d)^2 <= A R^2 (1 + 2^-9) + 2^9 d^2 + d^2 < A R^2 (1 + 2^-9) + 2^-30 A ww
 *   (2ab <= 2^-9 a^2 + 2^9 b^2), which leaves room for the products' own rounding.
 * KM_TINY: the hardware estimates treat subnormals as zero; below 2^-100 the exact
 *   operation serves (CYLRAY_FAST).
 * KM_TANGENT: D below 2^-18 A R^2, some 32 ulps of its larger term, is near a tangency,
 *   where only the direct form of the second root is safe (see there).
 * KM_NORMAL_OFF: a normal whose squared length is off 1 by more than 2^-10 (a hit point
 *   that rounding moved well off a tiny radius) is normalised exactly; below that one
 *   Newton step of 1/sqrt takes the error to rounding level. */
#define KM_DD_LO 0x1p-40f
#define KM_DD_HI 0x1p40f
#define KM_SPHERE 0x1p-17f
#define KM_TUBE_A (1.0f + 0x1p-9f)
#define KM_TUBE_WW 0x1p-30f
#define KM_TINY 0x1p-100f
#define KM_NORMAL_OFF 0x1p-10f
#define KM_TANGENT 0x1p-18f
#endif

typedef uint32_t (*KFN(packet_fn))(const cylray_prepared *, float *, float *, size_t,
                                   uint32_t, unsigned);
typedef size_t (*KFN(stream_fn))(const cylray_prepared *, const cylray_rays *,
                                 const cylray_hits *, uint8_t *, size_t, unsigned);
typedef int (*KFN(leaf_fn))(const float *, size_t, cylray_ray1 *, cylray_hit1 *, unsigned);

#define KDOT(ax, ay, az, bx, by, bz) vfma(ax, bx, vfma(ay, by, vmul(az, bz)))

/* The side's quadratic from the shifted origin p: f = v x p (so that nB = e.f is -B),
 * C = f.f - R^2 v.v and g = e.p, the triple product of Lagrange's form (with an
 * aligned axis g is the caller's, from the unshifted origin). */
CYLRAY_INLINE void KFN(side_coefs)(vf rr_vv, int aligned, vf dx, vf dy, vf ex,
                                   vf ey, vf ez, vf vx, vf vy, vf vz, vf px, vf py, vf pz,
                                   vf *fx, vf *fy, vf *fz, vf *nB, vf *C, vf *g)
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

/* Root polishing (CYLRAY_REFINE): the side's quadratic again from the point q at the
 * root r, where C is tiny and the small root C / q2 is a correction of a few ulps; the
 * result is then limited by the rounding of q, not by the distance of the shifted
 * origin. Returns the polished root where that helps, r elsewhere. */
CYLRAY_INLINE vf KFN(polish)(vf rr_vv, vf rr, int aligned, vm side, vf r, vf A, vf dx,
                             vf dy, vf dz, vf ex, vf ey, vf ez, vf vx, vf vy, vf vz, vf px,
                             vf py, vf pz)
{
    const vf zero = vzero();
    vf qx = vfma_x(r, dx, px), qy = vfma_x(r, dy, py), qz = vfma_x(r, dz, pz);
    vf B2, C2;
    if (aligned) {
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

/* One vector of rays: lanes [i, i + VW) of R, active where `bits` is set. Returns the
 * hit lanes; writes H and R->tmax only there. FL is a compile-time constant.
 *
 * With CYLRAY_KF_ALIGNED the axis is a coordinate axis (P->axis_id) and exactly a unit
 * vector: the coordinates are renamed so that it is the third one, and the side is a
 * 2D quadratic without cross products. */
CYLRAY_INLINE uint32_t KFN(block)(const cylray_prepared *P, const cylray_rays *R,
                                  const cylray_hits *H, size_t i, uint32_t bits,
                                  unsigned rt, const unsigned FL, const float *L, size_t lm)
{
    const int scaled = (FL & CYLRAY_KF_SCALED) != 0;
    const unsigned kind = (FL >> CYLRAY_KF_KIND_SHIFT) & 3u;
    const int leaf = kind == CYLRAY_KIND_LEAF;
    /* A leaf's lanes are cylinders of any kind: each runs the capped solid's logic with
     * its own discs (an open tube has none, an infinite one an infinite slab). */
    const int capped = kind == CYLRAY_KIND_CAPPED || leaf;
    const int finite = kind != CYLRAY_KIND_INFINITE;
    const int one_end = leaf || (FL & CYLRAY_KF_ONE_END) != 0;
    const int aligned = (FL & CYLRAY_KF_ALIGNED) != 0;
    const int occ = (FL & CYLRAY_KF_OCCLUDED) != 0;
    const int normal = (FL & CYLRAY_NORMAL) && !occ;
    const int cull = ((FL | rt) & CYLRAY_CULL_BACK) != 0;
    const int ff = (rt & CYLRAY_FACE_FORWARD) != 0;
    const int refine = (FL & CYLRAY_REFINE) != 0;
    const int fast = (FL & CYLRAY_FAST) != 0;
    const vf zero = vzero(), one = vset1(1.0f), inf = vset1(INFINITY);
    /* Packets read the ray per lane and broadcast the cylinder; a leaf broadcasts its
     * one ray and reads a cylinder per lane (its fields at L[f lm + lane]). */
#define KR_(f) (leaf ? vset1(*R->f) : vloadu(R->f + i))
#define KL_(f) vloadu(L + (size_t)CYLRAY_LF_##f * lm + i)
#define KC_(pf, lf) (leaf ? (lf) : vset1(P->pf))

    /* An aligned cylinder comes with its coordinates already renamed by the packet and
     * stream drivers (cylray_internal.h), so that its axis is the third one. */
    vf ox = KR_(ox), oy = KR_(oy), oz = KR_(oz);
    vf dx = KR_(dx), dy = KR_(dy), dz = KR_(dz);
    /* Inactive lanes may hold anything, and subnormals there would cost microcode
     * assists in every operation (20x on some cores): they take a ray that the packet
     * rejection drops, a line 2^40 from the origin. */
#define KSANE_(f, dead) f = vsel(mfrom_bits(bits), f, dead)
    const int partial = !leaf && bits != VFULL;
    if (partial) {
        KSANE_(ox, vset1(0x1p40f)), KSANE_(oy, zero), KSANE_(oz, zero);
        KSANE_(dx, zero), KSANE_(dy, one), KSANE_(dz, zero);
    }

    /* An Inf or NaN anywhere but in d turns C or D into NaN below, which takes the
     * lane out there. Inactive lanes are computed like the others (their garbage
     * cannot disturb a lane) and taken out where the hits are decided. */
    vf A = aligned ? vfma(dx, dx, vmul(dy, dy)) : zero; /* the side's |d_perp|^2 */
    vf dd = aligned ? vfma(dz, dz, A) : KDOT(dx, dy, dz, dx, dy, dz);
    vm act = mand(vge(dd, vset1(KM_DD_LO)), vle(dd, vset1(KM_DD_HI)));
    /* A direction far from unit length makes A, D and their products under- or
     * overflow (|d| = 2^-56 loses a tiny radius, 2^64 overflows d.d). A vector with
     * such an active lane (or a bad one) goes to the rare instance, where every lane
     * takes d times an exact power of two m, so that its largest component lies in
     * [2^-29, 2^20]: the line is the same, and t = m t'. Everything below works in t'
     * but the range test and T itself. A zero, infinite or NaN direction never hits. */
    vf tscale = one;
    if (scaled) {
        vf M = vmax(vabs(dx), vmax(vabs(dy), vabs(dz)));
        tscale = vsel(vlt(M, vset1(0x1p-20f)), vset1(0x1p40f), tscale);
        tscale = vsel(vlt(M, vset1(0x1p-60f)), vset1(0x1p80f), tscale);
        tscale = vsel(vlt(M, vset1(0x1p-100f)), vset1(0x1p120f), tscale);
        tscale = vsel(vgt(M, vset1(0x1p20f)), vset1(0x1p-40f), tscale);
        tscale = vsel(vgt(M, vset1(0x1p60f)), vset1(0x1p-80f), tscale);
        tscale = vsel(vgt(M, vset1(0x1p100f)), vset1(0x1p-120f), tscale);
        dx = vmul(dx, tscale), dy = vmul(dy, tscale), dz = vmul(dz, tscale);
        A = aligned ? vfma(dx, dx, vmul(dy, dy)) : zero;
        dd = aligned ? vfma(dz, dz, A) : KDOT(dx, dy, dz, dx, dy, dz);
        act = mand(mand(vgt(dd, zero), vlt(dd, inf)), vlt(M, inf));
    } else if ((mbits(act) & bits) != bits) {
        return CYLRAY_RARE_; /* the driver calls KFN(block_rare) */
    }

    const float *const c3 = leaf ? NULL : aligned ? P->cr : P->c;
#define KCEN_(k, f) (leaf ? KL_(f) : vset1(c3[k]))
    vf cx = KCEN_(0, CX), cy = KCEN_(1, CY), cz = KCEN_(2, CZ);
    const vf vx = aligned ? zero : KC_(v[0], KL_(VX)), vy = aligned ? zero : KC_(v[1], KL_(VY));
    const vf vz = leaf ? KL_(VZ) : vset1(aligned ? P->vr : P->v[2]);
    /* A leaf derives what it does not store from what it does (64 bytes a lane). */
    const vf rad = leaf ? KL_(R) : zero;
    const vf rr = KC_(rr, vmul(rad, rad)), rr_vv = KC_(rr_vv, KL_(RRVV));
    /* A leaf's finite and infinite lanes (h_v = INFINITY). */
    const vm fin = leaf ? vlt(KL_(HV), inf) : vle(zero, zero);
    const vm infl = leaf ? vge(KL_(HV), inf) : vlt(one, zero);

    /* w = o - c, rounded here; its rounding error wl is recovered below (two-sum),
     * once the cheap whole-packet rejections are behind. */
    vf whx = vsub(ox, cx), why = vsub(oy, cy), whz = vsub(oz, cz);
    vf ww = KDOT(whx, why, whz, whx, why, whz), wd = KDOT(whx, why, whz, dx, dy, dz);

    /* Shift to the closest approach to the center. s need not be accurate: any s is
     * exact as long as w' is formed from the same s, and t = s + t'. So a refined
     * reciprocal estimate serves, and the divider is kept for the roots. */
    const vf rdd = vrcp_fast(dd);
    vf s = vmul(vneg(wd), rdd);
    if (finite) {
        /* ww + s wd = ww - wd^2 / dd is the squared distance of the closest approach
         * to the center; a finite cylinder lies in a sphere, and a ray that passes
         * outside it misses. The slack (KM_SPHERE) covers the cancellation of a far
         * origin. */
        vf wd2 = vmul(vmul(wd, wd), rdd); /* wd^2 / dd; wd^2 is formed beside rdd */
        act = mand(act, vle(vfnma(ww, vset1(KM_SPHERE), vsub(ww, wd2)), KC_(bound2, KL_(BOUND2))));
        /* A shift that brings the origin less than a factor sqrt(2) closer gains less
         * than it costs: a small t would lose its low bits in s + t'. (ww > 2 pp.) */
        s = leaf ? vsel(fin, vkeep(vgt(vadd(wd2, wd2), ww), s), s)
                 : vkeep(vgt(vadd(wd2, wd2), ww), s);
    }

    /* e = d x v to a relative accuracy that survives a ray almost along the axis.
     * With an aligned axis v = (0, 0, +-1) and e = (dy, -dx, 0) up to the sign of v,
     * which no product below sees. */
    vf ex = zero, ey = zero, ez = zero, g0;
    if (aligned) {
        g0 = vfms(whx, dy, vmul(why, dx)); /* plain: within the margin below */
    } else {
        ex = vdop_x(dy, vz, dz, vy), ey = vdop_x(dz, vx, dx, vz), ez = vdop_x(dx, vy, dy, vx);
        A = KDOT(ex, ey, ez, ex, ey, ez);
        g0 = KDOT(ex, ey, ez, whx, why, whz);
    }
    /* The ray's line passes at |g| / sqrt(A) from the axis (g = e.w moves neither with
     * the shift nor along the axis). g0 is off from the exact g by less than
     * 2^-21 sqrt(A ww); beyond that margin the line misses the tube. A packet whose
     * rays all miss the sphere or the tube ends here, before the exact work, at one
     * branch (two would mispredict on a mix of the two kinds of miss). */
    act = mandn(act, vgt(vmul(g0, g0),
                         vmul(vmul(A, vset1(KM_TUBE_A)), vfma(ww, vset1(KM_TUBE_WW), rr))));
    if (!many(act))
        return 0;
    /* Past the rejection, the inputs are read again rather than kept across it: a
     * rejected packet then spills nothing, and the rest loses nothing (it would
     * reload them from the stack instead). */
    CYLRAY_REREAD();
    ox = KR_(ox), oy = KR_(oy), oz = KR_(oz);
    if (partial)
        KSANE_(ox, vset1(0x1p40f)), KSANE_(oy, zero), KSANE_(oz, zero);
    cx = KCEN_(0, CX), cy = KCEN_(1, CY), cz = KCEN_(2, CZ);

    vf bx = vsub(whx, ox), by = vsub(why, oy), bz = vsub(whz, oz);
    vf wlx = vsub(vsub(ox, vsub(whx, bx)), vadd(cx, bx));
    vf wly = vsub(vsub(oy, vsub(why, by)), vadd(cy, by));
    vf wlz = vsub(vsub(oz, vsub(whz, bz)), vadd(cz, bz));
    vf px = vfma_x2(s, dx, whx, wlx);
    vf py = vfma_x2(s, dy, why, wly);
    vf pz = vfma_x2(s, dz, whz, wlz);

    vf nB, C, g = zero, fx, fy, fz;
    if (aligned) {
        /* g = w x d, in the plane: it does not change along the ray, and Kahan's
         * difference of products is accurate relative to g itself (2 eps), so g is
         * taken from the unshifted w = wh + wl, and the discriminant need not wait
         * for the shift. */
        g = vadd(vdop_x(whx, dy, why, dx), vfms(wlx, dy, vmul(wly, dx)));
    }
    KFN(side_coefs)(rr_vv, aligned, dx, dy, ex, ey, ez, vx, vy, vz, px, py, pz, &fx, &fy, &fz,
                    &nB, &C, &g);

    if (!finite || (leaf && many(infl))) {
        /* An infinite cylinder has no center: c may slide along the axis (any slide u
         * is exact when the product u v is, as in the FMA). The error of a root t'
         * grows with its distance from the shifted point: a far origin aimed near c
         * wants the point near c, an origin near the surface far along the axis wants
         * c slid to the origin's level. |C / B| estimates the near root's distance;
         * each lane keeps the shift that makes it smaller. */
        /* u need not be accurate (the slide is exact for any u): a leaf takes an
         * estimate of 1 / v.v. */
        vf u = vmul(KDOT(whx, why, whz, vx, vy, vz),
                    KC_(inv_vv, vrcp_fast(KDOT(vx, vy, vz, vx, vy, vz))));
        vf hx = vfma_x(vneg(u), vx, whx), hy = vfma_x(vneg(u), vy, why),
           hz = vfma_x(vneg(u), vz, whz);
        vf s2 = vfnma(KDOT(hx, hy, hz, dx, dy, dz), rdd, zero);
        vf qx = vfma_x2(s2, dx, hx, wlx);
        vf qy = vfma_x2(s2, dy, hy, wly);
        vf qz = vfma_x2(s2, dz, hz, wlz);
        vf nB2, C2, g2 = g, fx2, fy2, fz2;
        KFN(side_coefs)(rr_vv, aligned, dx, dy, ex, ey, ez, vx, vy, vz, qx, qy, qz, &fx2, &fy2,
                        &fz2, &nB2, &C2, &g2);
        vm slide = vlt(vabs(vmul(C2, nB)), vabs(vmul(C, nB2)));
        if (leaf)
            slide = mand(slide, infl);
        s = vsel(slide, s2, s);
        px = vsel(slide, qx, px), py = vsel(slide, qy, py), pz = vsel(slide, qz, pz);
        fx = vsel(slide, fx2, fx), fy = vsel(slide, fy2, fy), fz = vsel(slide, fz2, fz);
        nB = vsel(slide, nB2, nB), C = vsel(slide, C2, C), g = vsel(slide, g2, g);
    }
    /* Lagrange's form of B^2 - A C, over v.v, with both products exact. */
    vf D, AR2; /* AR2: the larger term of D, which sets its rounding */
    if (!scaled && !leaf) { /* a radius in [2^-20, 2^21): j = 0 */
        D = vdop_x(A, rr, g, g);
        AR2 = vmul(A, rr);
    } else { /* scaled by 2^-2j (cylray_prepared.rr_d), and sqrt_vv has 2^j */
        const vf gs = KC_(g_s, KL_(GS));
        const vf rs = vmul(rad, gs); /* a leaf's R 2^-j, exact */
        const vf rr_d = KC_(rr_d, vmul(rs, rs));
        vf gd = vmul(g, gs);
        D = vdop_x(A, rr_d, gd, gd);
        AR2 = vmul(A, rr_d);
    }
    act = mand(act, veq(vfma(C, zero, vmul(D, zero)), zero));

    /* A ray within about one ulp of the axis direction is parallel: it meets the side
     * nowhere, and no division by its tiny A may make a hit. */
    const vf par_eps = KC_(par_eps, vmul(KDOT(vx, vy, vz, vx, vy, vz), vset1(CYLRAY_PAR_EPS)));
    vm par = vle(A, vmul(dd, par_eps));
    vm side = mand(act, mandn(vge(D, zero), par));
    vm inpar = mand(act, mand(par, vle(C, zero))); /* parallel and inside the tube */
    if (capped ? !many(mor(side, inpar)) : !many(side))
        return 0;

    /* The estimates see subnormal inputs as zero: below 2^-100 (rare where the
     * coordinates are near 1, and D = 0 at a tangency) the exact operation serves. */
    const vf tiny = vset1(KM_TINY);
    vf sq;
    if (fast) {
        sq = vmul(D, vrsqrt_fast(vmax(D, tiny)));
        vm small = mand(side, vlt(D, tiny));
        if (many(small))
            sq = vsel(small, vsqrt(D), sq);
    } else {
        sq = vsqrt(D);
    }
    if (!aligned) /* |v| = 1 there, and j = 0 */
        sq = vmul(sq, leaf ? KL_(SQS) : vset1(scaled ? P->sqrt_vv / P->g_s : P->sqrt_vv));
    vf q = vadd(nB, vxorsign(sq, nB)); /* -(B + sign(B) sqrt(disc)); sq >= 0 */
    vf r1 = fast ? vmul(q, vrcp_fast(A)) : vdiv(q, A);
    vf r2;
    if (fast) {
        r2 = vmul(C, vrcp_fast(q));
        vm small = mand(side, vlt(vabs(q), tiny));
        if (many(small))
            r2 = vsel(small, vdiv(C, q), r2);
    } else {
        r2 = vdiv(C, q);
    }
    /* By construction q^2 >= A C. Where rounding of C (a point on the surface, or a
     * tangent ray) breaks that, C / q is no root: the two coincide at q / A. */
    r2 = vsel(mor(veq(q, zero), vlt(vmul(q, q), vmul(C, A))), r1, r2);
    /* Near a tangency D is known only to a few ulps of A R^2 (the rounding of A, R^2
     * and g), and C, at a point near the surface, only to a few ulps of R^2: C / q then
     * divides one rounding error by another and can put the root anywhere, even past
     * the origin (a ray leaving the surface reported as hitting it from inside). The
     * direct form (nB - sign sq) / A errs by the error of sq alone. */
    vm tangent = mand(side, vlt(D, vmul(AR2, vset1(KM_TANGENT))));
    if (many(tangent))
        r2 = vsel(tangent, vdiv(vsub(nB, vxorsign(sq, nB)), A), r2);
    vf tn = vmin(r1, r2), tf = vmax(r1, r2);
    if (refine && many(side)) {
        /* Both roots are polished before anything is decided from them, so that the
         * entry test, the clip and the range test all see the t that is reported: a
         * call with tmax set to a reported t then reports it again. */
        tn = KFN(polish)(rr_vv, rr, aligned, side, tn, A, dx, dy, dz, ex, ey, ez, vx, vy, vz,
                         px, py, pz);
        tf = KFN(polish)(rr_vv, rr, aligned, side, tf, A, dx, dy, dz, ex, ey, ez, vx, vy, vz,
                         px, py, pz);
    }

    /* Entry and exit, relative to the shifted origin, and which part each one is. */
    vf t_in, t_out, side_lo = tn, side_hi = tf;
    vm ok_in, ok_out;
    /* The axial coordinate z0 + t dv, over |v|. An aligned axis is measured along the
     * third coordinate itself, whatever its sign: the slab is symmetric, and the sign
     * only names the caps. */
    vf z0 = zero, dv = zero;
    if (finite) {
        z0 = aligned ? pz : KDOT(px, py, pz, vx, vy, vz);
        dv = aligned ? dz : KDOT(dx, dy, dz, vx, vy, vz);
    }
    if (capped) {
        /* The solid is the infinite one cut by the slab |z| <= H: inside on [max of the
         * entries, min of the exits]. The rim is then shared, not tested twice. A ray
         * parallel to the axis inside the tube is inside the side everywhere. */
        side_lo = vsel(inpar, vneg(inf), tn), side_hi = vsel(inpar, inf, tf);
        const vf hv = KC_(h_v, KL_(HV));
        /* Two divisions rather than one reciprocal: a cap hit is then as exact as
         * the plane's offset, and dv = 0 gives the infinities the slab wants. */
        vf na = vsub(vneg(hv), z0), nb = vsub(hv, z0);
        vf ta, tb;
        if (fast) {
            vf rdv = vdiv(one, dv);
            ta = vmul(na, rdv), tb = vmul(nb, rdv);
        } else {
            ta = vdiv(na, dv), tb = vdiv(nb, dv);
        }
        vf slab_in = vmin(ta, tb), slab_out = vmax(ta, tb);
        t_in = vmax(side_lo, slab_in);
        t_out = vmin(side_hi, slab_out);
        ok_in = mand(mor(side, inpar), vle(t_in, t_out));
        ok_out = ok_in;
        if (one_end) {
            /* Where a disc is not part of the surface, the solid is still what decides
             * entry and exit (so the other rim stays watertight), but a bound made by
             * that disc is no hit: the ray passes through the open end. Going up the
             * axis (dv > 0) it enters by the low disc and leaves by the high one. */
            vm lo_on, hi_on;
            if (leaf) {
                const uint32_t *meta = (const uint32_t *)(const void *)(L + CYLRAY_LF_COUNT * lm);
                lo_on = mfrom_bits(meta[CYLRAY_LM_LO] >> i);
                hi_on = mfrom_bits(meta[CYLRAY_LM_HI] >> i);
            } else {
                lo_on = mfrom_bits(P->caps & CYLRAY_CAPPED_LO ? VFULL : 0u);
                hi_on = mfrom_bits(P->caps & CYLRAY_CAPPED_HI ? VFULL : 0u);
            }
            vm up = vgt(dv, zero);
            vm in_disc = vgt(slab_in, side_lo), out_disc = vlt(slab_out, side_hi);
            vm in_open = mandn(in_disc, mor(mand(up, lo_on), mandn(hi_on, up)));
            vm out_open = mandn(out_disc, mor(mand(up, hi_on), mandn(lo_on, up)));
            ok_in = mandn(ok_in, in_open);
            ok_out = mandn(ok_out, out_open);
        }
    } else {
        t_in = tn;
        t_out = tf;
        ok_in = side;
        ok_out = side;
        if (kind == CYLRAY_KIND_OPEN) {
            const vf hv = vset1(P->h_v);
            ok_in = mand(ok_in, vle(vabs(vfma(tn, dv, z0)), hv));
            ok_out = mand(ok_out, vle(vabs(vfma(tf, dv, z0)), hv));
        }
    }

    /* The entry if it is not before tmin, else the exit (a hit from inside); then
     * one range test for whichever it is. Rounding s + t is monotonic, so the entry
     * test decides correctly which of the two can be the first in [tmin, tmax]. The
     * bounds are clamped to finite values, so that no infinite t ever hits. */
    vf tmin = vmax(vset1(-FLT_MAX), KR_(tmin)); /* a NaN bound stays */
    vf tmax = vmin(vset1(FLT_MAX), KR_(tmax));
    /* (min, max and comparisons take subnormals without an assist) */
    vf T_in = vadd(s, t_in), T_out = vadd(s, t_out);
    /* With a scaled direction the range test is made where no scaling rounds: a
     * shrunk d (m < 1) moves the bounds to t' (exact, or overflowing as it should), a
     * grown one moves T to t (the same): t_to_test takes t' there, t_to_user takes
     * that to t. */
    vf t_to_test = one, t_to_user = one;
    if (scaled) {
        vm shrunk = vlt(tscale, one);
        vf rs = vdiv(one, tscale);
        tmin = vsel(shrunk, vmul(tmin, rs), tmin);
        tmax = vsel(shrunk, vmul(tmax, rs), tmax);
        t_to_test = vsel(shrunk, one, tscale);
        t_to_user = vsel(shrunk, tscale, one);
        T_in = vmul(T_in, t_to_test), T_out = vmul(T_out, t_to_test);
    }
    vm front = mand(ok_in, vge(T_in, tmin));
    vm cand = cull ? front : mor(front, ok_out);
    vf tr = vsel(front, t_in, t_out); /* relative to the shifted origin */
    vf T = vsel(front, T_in, T_out);
    vm hit = mand(cand, mand(vge(T, tmin), vle(T, tmax)));
    if (bits != VFULL) /* a whole packet is the common case, and needs no mask */
        hit = mand(hit, mfrom_bits(bits));
    vm back = mandn(hit, front);
    front = mand(hit, front);
    if (occ || !many(hit))
        return mbits(hit);

    /* On a capped cylinder, the chosen t is the side's or a cap's; which cap follows
     * from the direction: entering upwards (or leaving downwards) is the low one. An
     * aligned axis pointing down the third coordinate swaps the names (P->cap_up). */
    vm on_side = hit, cap_hi = hit;
    vf part = one;
    if (capped) {
        on_side = mand(hit, veq(tr, vsel(front, side_lo, side_hi)));
        cap_hi = mxor(vgt(dv, zero), front);
        part = vsel(on_side, one,
                    aligned ? vsel(cap_hi, vset1(P->cap_up), vset1(P->cap_down))
                            : vsel(cap_hi, vset1(CYLRAY_CAP_HI), vset1(CYLRAY_CAP_LO)));
    }
    part = vadd(part, vkeep(back, vset1(CYLRAY_BACKFACE)));

    if (scaled)
        T = vmul(T, t_to_user);
    vstore_m(H->t + i, hit, T);
    if (!leaf) /* a leaf's driver sets tmax once, from the closest lane */
        vstore_m(R->tmax + i, hit, T);
    vstore_part_m(H->part + i, hit, part);

    if (normal) {
        vf nx, ny, nz;
        if (aligned) {
            const vf k = vset1(P->nscale);
            nx = vmul(vfma(tr, dx, px), k);
            ny = vmul(vfma(tr, dy, py), k);
            nz = zero;
        } else {
            /* v x (p x v) = v.v p_perp, with p x v = f + t e already perpendicular, so
             * no axial magnitude leaks in; vk = v / (R v.v) makes it unit length. */
            const vf ns = leaf ? KL_(NSCALE) : zero;
            const vf kx = KC_(vk[0], vmul(vx, ns)), ky = KC_(vk[1], vmul(vy, ns)),
                     kz = KC_(vk[2], vmul(vz, ns));
            vf ux = vfms(tr, ex, fx), uy = vfms(tr, ey, fy), uz = vfms(tr, ez, fz);
            nx = vfms(ky, uz, vmul(kz, uy));
            ny = vfms(kz, ux, vmul(kx, uz));
            nz = vfms(kx, uy, vmul(ky, ux));
        }
        if (capped) {
            vm cap = mandn(hit, on_side);
            vf sgn = vsel(cap_hi, one, vset1(-1.0f));
            if (leaf) /* 1 / |v| = R |v| / (R v.v) */
                sgn = vmul(sgn, vmul(vmul(KL_(NSCALE), rad), vmul(KL_(SQS), KL_(GS))));
            nx = vsel(cap, aligned ? zero : vmul(sgn, KC_(n[0], vx)), nx);
            ny = vsel(cap, aligned ? zero : vmul(sgn, KC_(n[1], vy)), ny);
            nz = vsel(cap, aligned ? sgn : vmul(sgn, KC_(n[2], vz)), nz);
        }
        /* One Newton step of 1/sqrt(n.n) around 1 removes what rounding left of the
         * length error, whatever the hit point's distance from the axis. */
        vf l2 = KDOT(nx, ny, nz, nx, ny, nz);
        vf corr = vfnma(vset1(0.5f), l2, vset1(1.5f));
        /* A hit point that rounding moved well off the surface (a radius far below the
         * coordinates' ulp) gets a true normalisation; it is rare enough to branch. */
        vm off = mand(hit, vgt(vabs(vsub(l2, one)), vset1(KM_NORMAL_OFF)));
        if (many(off)) {
            /* Divided by its largest component first, so that a length whose square
             * underflows or overflows still normalises. */
            vf m = vmax(vabs(nx), vmax(vabs(ny), vabs(nz)));
            vm lost = mandn(off, mand(vgt(m, zero), vlt(m, inf)));
            if (many(lost)) {
                /* A hit point that rounds onto the axis (a radius far below the
                 * coordinates' ulp), or one so far from it that the offset is not
                 * finite (an origin far beyond the documented 2^62), has no direction
                 * of its own: the side then faces the ray, along -d_perp
                 * (v x e = v.v d_perp) on entry. */
                vf ux = dx, uy = dy, uz = zero;
                if (!aligned) {
                    ux = vfms(vy, ez, vmul(vz, ey));
                    uy = vfms(vz, ex, vmul(vx, ez));
                    uz = vfms(vx, ey, vmul(vy, ex));
                }
                nx = vsel(lost, vsel(front, vneg(ux), ux), nx);
                ny = vsel(lost, vsel(front, vneg(uy), uy), ny);
                nz = vsel(lost, vsel(front, vneg(uz), uz), nz);
                m = vmax(vabs(nx), vmax(vabs(ny), vabs(nz)));
            }
            /* n / m by division: 1 / m overflows where m is subnormal. */
            vf sx = vdiv(nx, m), sy = vdiv(ny, m), sz = vdiv(nz, m);
            vf k = vdiv(one, vsqrt(KDOT(sx, sy, sz, sx, sy, sz)));
            vm ok = mand(off, mand(vgt(m, zero), vlt(m, inf)));
            nx = vsel(ok, vmul(sx, k), nx), ny = vsel(ok, vmul(sy, k), ny);
            nz = vsel(ok, vmul(sz, k), nz);
            corr = vsel(ok, one, corr);
        }
        if (ff)
            corr = vsel(back, vneg(corr), corr);
        vstore_m(H->nx + i, hit, vmul(nx, corr));
        vstore_m(H->ny + i, hit, vmul(ny, corr));
        vstore_m(H->nz + i, hit, vmul(nz, corr));
    }
    return mbits(hit);
#undef KR_
#undef KL_
#undef KC_
#undef KCEN_
#undef KSANE_
}

static const cylray_hits KFN(no_hits) = {NULL, NULL, NULL, NULL, NULL}; /* occlusion */

/* The rare instance, one per ISA and width for every kind and flag set: a vector with
 * an active lane whose direction is far from unit length is rare, and the branches on
 * FL here cost less than more specialised copies would. The drivers call it when
 * KFN(block) returns CYLRAY_RARE_, rather than KFN(block) itself: a call there would
 * make the views escape, and every vector would pay for storing them. */
CYLRAY_NOINLINE uint32_t KFN(block_rare)(const cylray_prepared *P, const cylray_rays *R,
                                         const cylray_hits *H, size_t i, uint32_t bits,
                                         unsigned rt, unsigned FL, const float *L, size_t lm)
{
    return KFN(block)(P, R, H, i, bits, rt, FL | CYLRAY_KF_SCALED, L, lm);
}

/* The same for lanes [b, b + VW) of a packet of n, given as the packet structs. */
CYLRAY_NOINLINE uint32_t KFN(packet_rare)(const cylray_prepared *P, float *ray, float *hit,
                                          size_t n, size_t b, uint32_t bits, unsigned rt,
                                          unsigned FL)
{
    const int aligned = (FL & CYLRAY_KF_ALIGNED) != 0, occ = (FL & CYLRAY_KF_OCCLUDED) != 0;
    const cylray_rays R = cylray_packet_rays_(P, ray, n, aligned);
    const cylray_hits H = occ ? KFN(no_hits) : cylray_packet_hits_(P, hit, n, aligned);
    return KFN(block)(P, &R, &H, b, bits, rt, FL | CYLRAY_KF_SCALED, NULL, 0);
}

/* A packet given as the packet structs themselves: field f of the rays at ray + f n,
 * of the hits at hit + f n. The views are built here, where they stay in registers,
 * rather than by the caller (a struct of pointers passed through memory costs a store
 * and a reload on every call). packet1 is one vector (n = VW), with constant offsets
 * and nothing else to keep in registers; packet any multiple of VW up to 32. (packet
 * with n = VW folds to nearly the same code, but a rejected AVX2 packet then takes 12
 * instructions and 6 % more time.) */

CYLRAY_INLINE uint32_t KFN(packet1)(const cylray_prepared *P, float *ray, float *hit,
                                    uint32_t active, unsigned rt, const unsigned FL)
{
    const int aligned = (FL & CYLRAY_KF_ALIGNED) != 0, occ = (FL & CYLRAY_KF_OCCLUDED) != 0;
    const cylray_rays R = cylray_packet_rays_(P, ray, VW, aligned);
    const cylray_hits H = occ ? KFN(no_hits) : cylray_packet_hits_(P, hit, VW, aligned);
    uint32_t m = KFN(block)(P, &R, &H, 0, active, rt, FL, NULL, 0);
    return m == CYLRAY_RARE_ ? KFN(packet_rare)(P, ray, hit, VW, 0, active, rt, FL) : m;
}

CYLRAY_INLINE uint32_t KFN(packet)(const cylray_prepared *P, float *ray, float *hit, size_t n,
                                   uint32_t active, unsigned rt, const unsigned FL)
{
    const int aligned = (FL & CYLRAY_KF_ALIGNED) != 0, occ = (FL & CYLRAY_KF_OCCLUDED) != 0;
    const cylray_rays R = cylray_packet_rays_(P, ray, n, aligned);
    const cylray_hits H = occ ? KFN(no_hits) : cylray_packet_hits_(P, hit, n, aligned);
    uint32_t hits = 0;
    for (size_t b = 0; b < n; b += VW) {
        uint32_t a = (active >> b) & VFULL;
        if (a) {
            uint32_t m = KFN(block)(P, &R, &H, b, a, rt, FL, NULL, 0);
            if (m == CYLRAY_RARE_)
                m = KFN(packet_rare)(P, ray, hit, n, b, a, rt, FL);
            hits |= m << b;
        }
    }
    return hits;
}

/* A stream of any length: whole vectors in place, then the tail through a local
 * copy, so that nothing before or after the caller's arrays is read or written. */
CYLRAY_INLINE size_t KFN(stream)(const cylray_prepared *P, const cylray_rays *R0,
                                 const cylray_hits *H0, uint8_t *occluded, size_t n,
                                 unsigned rt, const unsigned FL)
{
    const int occ = (FL & CYLRAY_KF_OCCLUDED) != 0;
    const int normal = (FL & CYLRAY_NORMAL) && !occ;
    const int aligned = (FL & CYLRAY_KF_ALIGNED) != 0;
    const cylray_rays Rv = aligned ? cylray_rays_renamed_(P, R0) : *R0;
    const cylray_hits Hv = occ ? KFN(no_hits) : aligned ? cylray_hits_renamed_(P, H0) : *H0;
    const cylray_rays *R = &Rv;
    const cylray_hits *H = &Hv;
    size_t count = 0, i = 0;
    for (; i + VW <= n; i += VW) {
        uint32_t m = KFN(block)(P, R, H, i, VFULL, rt, FL, NULL, 0);
        if (m == CYLRAY_RARE_)
            m = KFN(block_rare)(P, R, H, i, VFULL, rt, FL, NULL, 0);
        count += CYLRAY_POPCOUNT(m);
        if (occ)
            for (; m; m &= m - 1)
                occluded[i + CYLRAY_CTZ(m)] = 1;
    }
    if (i < n) {
        size_t rest = n - i;
        float in[8][VW] = {{0}}, out[4][VW] = {{0}};
        int32_t part[VW] = {0};
        const float *src[8] = {R->ox, R->oy, R->oz, R->dx, R->dy, R->dz, R->tmin, R->tmax};
        for (int f = 0; f < 8; f++)
            for (size_t j = 0; j < rest; j++)
                in[f][j] = src[f][i + j];
        cylray_rays lr = {in[0], in[1], in[2], in[3], in[4], in[5], in[6], in[7]};
        cylray_hits lh = {out[0], out[1], out[2], out[3], part};
        const uint32_t bits = (uint32_t)((1u << rest) - 1u);
        uint32_t m = KFN(block)(P, &lr, &lh, 0, bits, rt, FL, NULL, 0);
        if (m == CYLRAY_RARE_)
            m = KFN(block_rare)(P, &lr, &lh, 0, bits, rt, FL, NULL, 0);
        count += CYLRAY_POPCOUNT(m);
        for (; m; m &= m - 1) {
            size_t j = CYLRAY_CTZ(m);
            if (occ) {
                occluded[i + j] = 1;
                continue;
            }
            H->t[i + j] = out[0][j];
            R->tmax[i + j] = in[7][j];
            H->part[i + j] = part[j];
            if (normal) {
                H->nx[i + j] = out[1][j];
                H->ny[i + j] = out[2][j];
                H->nz[i + j] = out[3][j];
            }
        }
    }
    return count;
}

/* One ray against a leaf of lm cylinders (lm a multiple of VW, at most 16): a vector of
 * lanes at a time, each with tmax lowered to the closest hit so far, so that a farther
 * vector is rejected cheaply; the closest lane wins, the lowest of equal ones. */
CYLRAY_INLINE int KFN(leaf)(const float *L, size_t lm, cylray_ray1 *ray, cylray_hit1 *hit,
                            unsigned rt, const unsigned FL)
{
    const int occ = (FL & CYLRAY_KF_OCCLUDED) != 0;
    const int normal = (FL & CYLRAY_NORMAL) && !occ;
    const uint32_t *meta = (const uint32_t *)(const void *)(L + CYLRAY_LF_COUNT * lm);
    const uint32_t used = meta[CYLRAY_LM_USED];
    float tmax = ray->tmax;
    const cylray_rays R = {&ray->o[0], &ray->o[1], &ray->o[2], &ray->d[0],
                           &ray->d[1], &ray->d[2], &ray->tmin, &tmax};
    float out[4][16];
    int32_t part[16];
    const cylray_hits H = {out[0], out[1], out[2], out[3], part};
    int best = -1;
    for (size_t b = 0; b < lm; b += VW) {
        uint32_t a = (used >> b) & VFULL;
        if (!a)
            continue;
        uint32_t m = KFN(block)(NULL, &R, &H, b, a, rt, FL, L, lm);
        if (m == CYLRAY_RARE_)
            m = KFN(block_rare)(NULL, &R, &H, b, a, rt, FL, L, lm);
        if (occ) {
            if (m)
                return 1;
            continue;
        }
        for (; m; m &= m - 1) {
            int j = (int)(b + CYLRAY_CTZ(m));
            if (best < 0 || out[0][j] < out[0][best])
                best = j;
        }
        if (best >= 0)
            tmax = out[0][best];
    }
    if (best < 0)
        return 0;
    hit->t = out[0][best];
    if (normal) {
        hit->n[0] = out[1][best];
        hit->n[1] = out[2][best];
        hit->n[2] = out[3][best];
    }
    hit->part = part[best];
    hit->id = meta[lm + best]; /* id_ follows meta_ */
    hit->lane = (uint32_t)best;
    ray->tmax = out[0][best];
    return 1;
}

/* The drivers for what the specialisations below leave out: a cylinder whose radius is
 * far from 1 or that has one disc only (variant >= CYLRAY_VARIANT_GENERIC). The flags
 * select the kernel's branches at run time. */
static unsigned KFN(generic_fl)(const cylray_prepared *P, unsigned flags, int occ)
{
    return P->kind << CYLRAY_KF_KIND_SHIFT | (occ ? CYLRAY_KF_OCCLUDED : 0u) |
           (flags & ((occ ? 0u : CYLRAY_NORMAL) | CYLRAY_REFINE | CYLRAY_FAST)) |
           (P->kind == CYLRAY_KIND_CAPPED && P->caps != CYLRAY_CAPPED ? CYLRAY_KF_ONE_END : 0u) |
           CYLRAY_KF_SCALED;
}

/* One instance each of the drivers with the flags read at run time. */
CYLRAY_MAYBE_UNUSED CYLRAY_NOINLINE uint32_t KFN(packet_any)(const cylray_prepared *P, float *ray,
                                                             float *hit, size_t n,
                                                             uint32_t active, unsigned rt,
                                                             unsigned FL)
{
    return KFN(packet)(P, ray, hit, n, active, rt, FL);
}

CYLRAY_MAYBE_UNUSED CYLRAY_NOINLINE size_t KFN(stream_any)(const cylray_prepared *P,
                                                           const cylray_rays *R,
                                                           const cylray_hits *H,
                                                           uint8_t *occluded, size_t n,
                                                           unsigned rt, unsigned FL)
{
    return KFN(stream)(P, R, H, occluded, n, rt, FL);
}

CYLRAY_MAYBE_UNUSED CYLRAY_NOINLINE int KFN(leaf_any)(const float *L, size_t lm, cylray_ray1 *ray,
                                                      cylray_hit1 *hit, unsigned rt, unsigned FL)
{
    return KFN(leaf)(L, lm, ray, hit, rt, FL);
}

CYLRAY_MAYBE_UNUSED static uint32_t KFN(packet_generic)(const cylray_prepared *P, float *ray,
                                                        float *hit, size_t n, uint32_t active,
                                                        unsigned flags)
{
    return KFN(packet_any)(P, ray, hit, n, active, flags & CYLRAY_KF_RUNTIME,
                           KFN(generic_fl)(P, flags, hit == NULL));
}

CYLRAY_MAYBE_UNUSED static size_t KFN(stream_generic)(const cylray_prepared *P,
                                                      const cylray_rays *R, const cylray_hits *H,
                                                      uint8_t *occluded, size_t n, unsigned flags)
{
    return KFN(stream_any)(P, R, H, occluded, n, flags & CYLRAY_KF_RUNTIME,
                           KFN(generic_fl)(P, flags, occluded != NULL));
}

/* The specialisations, where a tracer spends its time: for each kind of cylinder
 * (infinite, open, capped; the same three along a coordinate axis; and a leaf) the
 * intersect kernels with and without normals, each plain, with CYLRAY_FAST or with
 * CYLRAY_REFINE, and the occluded ones likewise. FAST and REFINE together (an odd
 * pair: one trades accuracy away, the other buys it) take the drivers that read their
 * flags at run time, as the rare cylinders do; so do face-forward and culling in every
 * kernel (a select each). b is cylray_spec_'s encoding (cylray_internal.h); the tables
 * are indexed by cylray_isect_index_ / cylray_occ_index_. Half the specialisations of
 * every combination, in build time and size, for the same speed where it counts. */
#define KSPECFL_(b)                                                                    \
    (((b) & 1 ? CYLRAY_NORMAL : 0u) | ((b) & 2 ? CYLRAY_FAST : 0u) |                       \
     ((b) & 4 ? CYLRAY_REFINE : 0u))
#define KFL_(kind, b, extra)                                                           \
    (((kind) % 3u) << CYLRAY_KF_KIND_SHIFT | ((kind) >= 3 ? CYLRAY_KF_ALIGNED : 0u) |     \
     KSPECFL_(b) | (extra))
#define KLFL_(b, extra) (CYLRAY_KIND_LEAF << CYLRAY_KF_KIND_SHIFT | KSPECFL_(b) | (extra))
/* The three drivers of one table slot; the calls are given, as they differ between the
 * specialised drivers and the run-time ones. */
#define KSLOT_(kind, b, pk1_call, pk_call, st_call)                                    \
    static uint32_t KFN(pk1_##kind##_##b)(const cylray_prepared *P, float *R, float *H,  \
                                          size_t n, uint32_t a, unsigned rt)            \
    {                                                                                  \
        (void)n;                                                                       \
        return pk1_call;                                                               \
    }                                                                                  \
    static uint32_t KFN(pk_##kind##_##b)(const cylray_prepared *P, float *R, float *H,   \
                                         size_t n, uint32_t a, unsigned rt)             \
    {                                                                                  \
        return pk_call;                                                                \
    }                                                                                  \
    static size_t KFN(st_##kind##_##b)(const cylray_prepared *P, const cylray_rays *R,  \
                                       const cylray_hits *H, uint8_t *o, size_t n,       \
                                       unsigned rt)                                     \
    {                                                                                  \
        return st_call;                                                                \
    }
#define KSPEC_(kind, b, fl)                                                            \
    KSLOT_(kind, b, KFN(packet1)(P, R, H, a, rt, fl), KFN(packet)(P, R, H, n, a, rt, fl), \
           KFN(stream)(P, R, H, o, n, rt, fl))
#define KANY_(kind, b, fl)                                                             \
    KSLOT_(kind, b, KFN(packet_any)(P, R, H, n, a, rt, fl),                             \
           KFN(packet_any)(P, R, H, n, a, rt, fl), KFN(stream_any)(P, R, H, o, n, rt, fl))
#define KISECT_(kind, b) KSPEC_(kind, b, KFL_(kind, b, 0u))
#define KOCC_(kind, b) KSPEC_(kind, o##b, KFL_(kind, (b) << 1, CYLRAY_KF_OCCLUDED))
#define KISECTANY_(kind, b) KANY_(kind, b, KFL_(kind, b, 0u))
#define KOCCANY_(kind, b) KANY_(kind, o##b, KFL_(kind, (b) << 1, CYLRAY_KF_OCCLUDED))
#define KLEAFDRV_(name, drv, fl)                                                       \
    static int KFN(name)(const float *L, size_t lm, cylray_ray1 *r, cylray_hit1 *h,     \
                         unsigned rt)                                                  \
    {                                                                                  \
        return KFN(drv)(L, lm, r, h, rt, fl);                                          \
    }
#define KLEAF_(b) KLEAFDRV_(lf_##b, leaf, KLFL_(b, 0u))
#define KLEAFOCC_(b) KLEAFDRV_(lo_##b, leaf, KLFL_((b) << 1, CYLRAY_KF_OCCLUDED))
#define KLEAFANY_(b) KLEAFDRV_(lf_##b, leaf_any, KLFL_(b, 0u))
#define KLEAFOCCANY_(b) KLEAFDRV_(lo_##b, leaf_any, KLFL_((b) << 1, CYLRAY_KF_OCCLUDED))
#define K8_(X, k) X(k, 0) X(k, 1) X(k, 2) X(k, 3) X(k, 4) X(k, 5) X(k, 6) X(k, 7)
#define K4_(X, k) X(k, 0) X(k, 1) X(k, 2) X(k, 3)
#define KALL8_(X) K8_(X, 0) K8_(X, 1) K8_(X, 2) K8_(X, 3) K8_(X, 4) K8_(X, 5)
#define KALL4_(X) K4_(X, 0) K4_(X, 1) K4_(X, 2) K4_(X, 3) K4_(X, 4) K4_(X, 5)

/* b = 6, 7 (occluded: 3) are FAST with REFINE. */
#define KKIND_(k)                                                                      \
    KISECT_(k, 0) KISECT_(k, 1) KISECT_(k, 2) KISECT_(k, 3) KISECT_(k, 4) KISECT_(k, 5)    \
    KISECTANY_(k, 6) KISECTANY_(k, 7) KOCC_(k, 0) KOCC_(k, 1) KOCC_(k, 2) KOCCANY_(k, 3)
KKIND_(0) KKIND_(1) KKIND_(2) KKIND_(3) KKIND_(4) KKIND_(5)
KLEAF_(0) KLEAF_(1) KLEAF_(2) KLEAF_(3) KLEAF_(4) KLEAF_(5) KLEAFANY_(6) KLEAFANY_(7)
KLEAFOCC_(0) KLEAFOCC_(1) KLEAFOCC_(2) KLEAFOCCANY_(3)

#define KREF_PK1_(k, b) KFN(pk1_##k##_##b),
#define KREF_PK_(k, b) KFN(pk_##k##_##b),
#define KREF_ST_(k, b) KFN(st_##k##_##b),
#define KREF_PO1_(k, b) KFN(pk1_##k##_o##b),
#define KREF_PO_(k, b) KFN(pk_##k##_o##b),
#define KREF_SO_(k, b) KFN(st_##k##_o##b),
/* The packet tables for one vector (isect1, occ1) and for several (isect, occ); an
 * ISA's entry points take the ones their widths need, the compiler drops the rest. */
enum { KFN(vw) = VW };
_Static_assert(CYLRAY_VARIANT_GENERIC == 6, "six specialised variants");
CYLRAY_MAYBE_UNUSED static const KFN(packet_fn) KFN(isect1_table)[48] = {KALL8_(KREF_PK1_)};
CYLRAY_MAYBE_UNUSED static const KFN(packet_fn) KFN(isect_table)[48] = {KALL8_(KREF_PK_)};
CYLRAY_MAYBE_UNUSED static const KFN(stream_fn) KFN(isect_stream_table)[48] = {KALL8_(KREF_ST_)};
CYLRAY_MAYBE_UNUSED static const KFN(packet_fn) KFN(occ1_table)[24] = {KALL4_(KREF_PO1_)};
CYLRAY_MAYBE_UNUSED static const KFN(packet_fn) KFN(occ_table)[24] = {KALL4_(KREF_PO_)};
CYLRAY_MAYBE_UNUSED static const KFN(stream_fn) KFN(occ_stream_table)[24] = {KALL4_(KREF_SO_)};
CYLRAY_MAYBE_UNUSED static const KFN(leaf_fn) KFN(leaf_table)[8] = {
    KFN(lf_0), KFN(lf_1), KFN(lf_2), KFN(lf_3), KFN(lf_4), KFN(lf_5), KFN(lf_6), KFN(lf_7)};
CYLRAY_MAYBE_UNUSED static const KFN(leaf_fn) KFN(leaf_occ_table)[4] = {
    KFN(lo_0), KFN(lo_1), KFN(lo_2), KFN(lo_3)};

#undef KDOT
#undef KFL_
#undef KLFL_
#undef KSPEC_
#undef KSLOT_
#undef KISECT_
#undef KOCC_
#undef KLEAF_
#undef KLEAFOCC_
#undef KLEAFANY_
#undef KLEAFOCCANY_
#undef KLEAFDRV_
#undef KANY_
#undef KISECTANY_
#undef KOCCANY_
#undef KKIND_
#undef K8_
#undef K4_
#undef KALL8_
#undef KALL4_
#undef KSPECFL_
#undef KREF_PK1_
#undef KREF_PK_
#undef KREF_ST_
#undef KREF_PO1_
#undef KREF_PO_
#undef KREF_SO_
