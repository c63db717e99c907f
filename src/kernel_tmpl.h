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

#ifndef CYLRAY_KERNEL_ONCE_
#define CYLRAY_KERNEL_ONCE_
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

/* What an instantiation's flags decide. Every field but the run-time ones (cull, ff)
 * is a compile-time constant where a kernel is specialised, and its branches fold. */
typedef struct {
    unsigned kind;
    int leaf, capped, finite, one_end, aligned, scaled, occ, normal, cull, ff, refine, fast;
    int scratch;
} cylray_kflags_;

CYLRAY_INLINE cylray_kflags_ cylray_kflags_of_(unsigned FL, unsigned rt)
{
    cylray_kflags_ F;
    F.kind = (FL >> CYLRAY_KF_KIND_SHIFT) & 3u;
    F.leaf = F.kind == CYLRAY_KIND_LEAF;
    /* A leaf's lanes are cylinders of any kind: each runs the capped solid's logic with
     * its own discs (an open tube has none, an infinite one an infinite slab). */
    F.capped = F.kind == CYLRAY_KIND_CAPPED || F.leaf;
    F.finite = F.kind != CYLRAY_KIND_INFINITE;
    F.one_end = F.leaf || (FL & CYLRAY_KF_ONE_END) != 0;
    F.aligned = (FL & CYLRAY_KF_ALIGNED) != 0;
    F.scaled = (FL & CYLRAY_KF_SCALED) != 0;
    F.occ = (FL & CYLRAY_KF_OCCLUDED) != 0;
    F.normal = (FL & CYLRAY_NORMAL) && !F.occ;
    F.cull = ((FL | rt) & CYLRAY_CULL_BACK) != 0;
    F.ff = (rt & CYLRAY_FACE_FORWARD) != 0;
    F.refine = (FL & CYLRAY_REFINE) != 0;
    F.fast = (FL & CYLRAY_FAST) != 0;
    F.scratch = F.leaf || (FL & CYLRAY_KF_SCRATCH) != 0;
    return F;
}

/* Where one vector's lanes come from and go to: the cylinder (P) or the leaf (L, lm
 * lanes), the rays and hits, the first lane i and the active lanes. An aligned
 * cylinder comes with its rays' coordinates already renamed by the drivers
 * (cylray_internal.h), so that its axis is the third one; c3 is its center renamed
 * the same way. */
typedef struct {
    const cylray_prepared *P;
    const cylray_rays *R;
    const cylray_hits *H;
    const float *L;
    size_t lm, i;
    uint32_t bits;
    const float *c3;
} cylray_kat_;

CYLRAY_INLINE const float *cylray_kcenter_(const cylray_prepared *P, const cylray_kflags_ F)
{
    return F.leaf ? NULL : F.aligned ? P->cr : P->c;
}
#endif

#ifndef KPAIRS
/* KPAIRS(F): whether the stream kernel of flags F keeps two vectors in flight; one at
 * a time unless the ISA file says otherwise. KGROUP(F), below: after how many vectors
 * in a row that pass the rejection such a stream resumes its pairs. */
#define KPAIRS(F) 0
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

/* The kernel for one vector of rays, in stages. KFN(block) below runs them in order;
 * each stage reads what the ones before it left in the lane state (KFN(lanes)) and
 * adds its own, and the stages that can end the work for the whole vector say so.
 * They are always inlined: the state lives in registers, and the flags fold. */

/* The state of one vector's lanes, in the order the stages fill it in. */
typedef struct {
    /* load_ray: the ray (with an aligned axis, its coordinates already renamed) */
    vf ox, oy, oz, dx, dy, dz, dd, tscale;
    vm act; /* the lanes still in play */
    /* reject: the cylinder, w = o - c rounded (wh), the shift s and 1 / d.d */
    vf cx, cy, cz, vx, vy, vz, rad, rr, rr_vv;
    vm fin, infl; /* a leaf's finite and infinite lanes */
    vf whx, why, whz, rdd, s, ex, ey, ez, A, g;
    /* shift: w's rounding error wl and the shifted origin p = w + s d */
    vf wlx, wly, wlz, px, py, pz;
    /* side: the quadratic A t^2 - 2 nB t + C, f = v x p, and its discriminant */
    vf fx, fy, fz, nB, C, D, AR2;
    vm side, inpar; /* the side's roots exist; parallel inside the tube */
    /* roots, ends: the side's roots, and entry and exit relative to p */
    vf tn, tf, z0, dv, side_lo, side_hi, t_in, t_out;
    vm ok_in, ok_out;
    /* decide: the hit lanes and their t */
    vf tr, T, t_to_user;
    vm hit, front, back;
} KFN(lanes);

/* Packets read the ray per lane and broadcast the cylinder; a leaf broadcasts its one
 * ray and reads a cylinder per lane (its fields at L[f lm + lane]). */
#define KR_(f) (F.leaf ? vset1(*k->R->f) : vloadu(k->R->f + k->i))
#define KL_(f) vloadu(k->L + (size_t)CYLRAY_LF_##f * k->lm + k->i)
#define KC_(pf, lf) (F.leaf ? (lf) : vset1(k->P->pf))
#define KCEN_(c, f) (F.leaf ? KL_(f) : vset1(k->c3[c]))
/* Inactive lanes may hold anything, and subnormals there would cost microcode assists
 * in every operation (20x on some cores): they take a ray that the packet rejection
 * drops, a line 2^40 from the origin. */
#define KSANE_(f, dead) st->f = vsel(mfrom_bits(k->bits), st->f, dead)
#define KPARTIAL_ (!F.leaf && k->bits != VFULL)
#define KLOAD_O_()                                                                     \
    do {                                                                               \
        st->ox = KR_(ox), st->oy = KR_(oy), st->oz = KR_(oz);                          \
        if (KPARTIAL_)                                                                 \
            KSANE_(ox, vset1(0x1p40f)), KSANE_(oy, vzero()), KSANE_(oz, vzero());       \
        st->cx = KCEN_(0, CX), st->cy = KCEN_(1, CY), st->cz = KCEN_(2, CZ);            \
    } while (0)

/* Stage 1, the ray: A (aligned), d.d and the lanes in play. An Inf or NaN anywhere but
 * in d turns C or D into NaN later, which takes the lane out there. Returns
 * CYLRAY_RARE_ for a vector that the rare instance must take, else 0. */
CYLRAY_INLINE uint32_t KFN(load_ray)(KFN(lanes) *st, const cylray_kat_ *k,
                                     const cylray_kflags_ F)
{
    const vf zero = vzero(), one = vset1(1.0f), inf = vset1(INFINITY);
    KLOAD_O_();
    st->dx = KR_(dx), st->dy = KR_(dy), st->dz = KR_(dz);
    if (KPARTIAL_)
        KSANE_(dx, zero), KSANE_(dy, one), KSANE_(dz, zero);
    vf dx = st->dx, dy = st->dy, dz = st->dz;
    vf A = F.aligned ? vfma(dx, dx, vmul(dy, dy)) : zero; /* the side's |d_perp|^2 */
    vf dd = F.aligned ? vfma(dz, dz, A) : KDOT(dx, dy, dz, dx, dy, dz);
    vm act = mand(vge(dd, vset1(KM_DD_LO)), vle(dd, vset1(KM_DD_HI)));
    /* A direction far from unit length makes A, D and their products under- or
     * overflow (|d| = 2^-56 loses a tiny radius, 2^64 overflows d.d). A vector with
     * such an active lane (or a bad one) goes to the rare instance, where every lane
     * takes d times an exact power of two m, so that its largest component lies in
     * [2^-29, 2^20]: the line is the same, and t = m t'. Everything after works in t'
     * but the range test and T itself. A zero, infinite or NaN direction never hits. */
    vf tscale = one;
    if (F.scaled) {
        vf M = vmax(vabs(dx), vmax(vabs(dy), vabs(dz)));
        tscale = vsel(vlt(M, vset1(0x1p-20f)), vset1(0x1p40f), tscale);
        tscale = vsel(vlt(M, vset1(0x1p-60f)), vset1(0x1p80f), tscale);
        tscale = vsel(vlt(M, vset1(0x1p-100f)), vset1(0x1p120f), tscale);
        tscale = vsel(vgt(M, vset1(0x1p20f)), vset1(0x1p-40f), tscale);
        tscale = vsel(vgt(M, vset1(0x1p60f)), vset1(0x1p-80f), tscale);
        tscale = vsel(vgt(M, vset1(0x1p100f)), vset1(0x1p-120f), tscale);
        dx = vmul(dx, tscale), dy = vmul(dy, tscale), dz = vmul(dz, tscale);
        st->dx = dx, st->dy = dy, st->dz = dz;
        A = F.aligned ? vfma(dx, dx, vmul(dy, dy)) : zero;
        dd = F.aligned ? vfma(dz, dz, A) : KDOT(dx, dy, dz, dx, dy, dz);
        act = mand(mand(vgt(dd, zero), vlt(dd, inf)), vlt(M, inf));
    }
    st->A = A, st->dd = dd, st->act = act, st->tscale = tscale;
    if (!F.scaled && (mbits(act) & k->bits) != k->bits)
        return CYLRAY_RARE_; /* the driver calls KFN(block_rare) */
    return 0;
}

/* Stage 2, the cheap rejections: the sphere around a finite cylinder and the tube
 * around the axis, from w = o - c rounded. Returns whether any lane is left. */
CYLRAY_INLINE int KFN(reject)(KFN(lanes) *st, const cylray_kat_ *k, const cylray_kflags_ F)
{
    const vf zero = vzero(), inf = vset1(INFINITY);
    const vf dx = st->dx, dy = st->dy, dz = st->dz, dd = st->dd;
    vf vx = zero, vy = zero;
    if (!F.aligned)
        vx = KC_(v[0], KL_(VX)), vy = KC_(v[1], KL_(VY));
    const vf vz = F.leaf ? KL_(VZ) : vset1(F.aligned ? k->P->vr : k->P->v[2]);
    st->vx = vx, st->vy = vy, st->vz = vz;
    /* A leaf derives what it does not store from what it does (64 bytes a lane). */
    st->rad = F.leaf ? KL_(R) : zero;
    st->rr = KC_(rr, vmul(st->rad, st->rad)), st->rr_vv = KC_(rr_vv, KL_(RRVV));
    st->fin = F.leaf ? vlt(KL_(HV), inf) : vle(zero, zero);
    st->infl = F.leaf ? vge(KL_(HV), inf) : vlt(vset1(1.0f), zero);

    /* w = o - c, rounded here; its rounding error wl is recovered by the shift stage
     * (two-sum), once the cheap whole-vector rejections are behind. */
    vf whx = vsub(st->ox, st->cx), why = vsub(st->oy, st->cy), whz = vsub(st->oz, st->cz);
    st->whx = whx, st->why = why, st->whz = whz;
    vf ww = KDOT(whx, why, whz, whx, why, whz), wd = KDOT(whx, why, whz, dx, dy, dz);
    vm act = st->act;

    /* Shift to the closest approach to the center. s need not be accurate: any s is
     * exact as long as w' is formed from the same s, and t = s + t'. So a refined
     * reciprocal estimate serves, and the divider is kept for the roots. */
    const vf rdd = vrcp_fast(dd);
    vf s = vmul(vneg(wd), rdd);
    if (F.finite) {
        /* ww + s wd = ww - wd^2 / dd is the squared distance of the closest approach
         * to the center; a finite cylinder lies in a sphere, and a ray that passes
         * outside it misses. The slack (KM_SPHERE) covers the cancellation of a far
         * origin. */
        vf wd2 = vmul(vmul(wd, wd), rdd); /* wd^2 / dd; wd^2 is formed beside rdd */
        act = mand(act, vle(vfnma(ww, vset1(KM_SPHERE), vsub(ww, wd2)), KC_(bound2, KL_(BOUND2))));
        /* A shift that brings the origin less than a factor sqrt(2) closer gains less
         * than it costs: a small t would lose its low bits in s + t'. (ww > 2 pp.) */
        s = F.leaf ? vsel(st->fin, vkeep(vgt(vadd(wd2, wd2), ww), s), s)
                   : vkeep(vgt(vadd(wd2, wd2), ww), s);
    }
    st->rdd = rdd, st->s = s;

    /* e = d x v to a relative accuracy that survives a ray almost along the axis.
     * With an aligned axis v = (0, 0, +-1) and e = (dy, -dx, 0) up to the sign of v,
     * which no product below sees. */
    vf g0, A = st->A;
    st->ex = st->ey = st->ez = zero;
    if (F.aligned) {
        g0 = vfms(whx, dy, vmul(why, dx)); /* plain: within the margin below */
    } else {
        st->ex = vdop_x(dy, vz, dz, vy), st->ey = vdop_x(dz, vx, dx, vz);
        st->ez = vdop_x(dx, vy, dy, vx);
        A = KDOT(st->ex, st->ey, st->ez, st->ex, st->ey, st->ez);
        g0 = KDOT(st->ex, st->ey, st->ez, whx, why, whz);
    }
    st->A = A;
    /* The ray's line passes at |g| / sqrt(A) from the axis (g = e.w moves neither with
     * the shift nor along the axis). g0 is off from the exact g by less than
     * 2^-21 sqrt(A ww); beyond that margin the line misses the tube. A vector whose
     * rays all miss the sphere or the tube ends here, before the exact work, at one
     * branch (two would mispredict on a mix of the two kinds of miss). */
    act = mandn(act, vgt(vmul(g0, g0),
                         vmul(vmul(A, vset1(KM_TUBE_A)), vfma(ww, vset1(KM_TUBE_WW), st->rr))));
    st->act = act;
    return many(act);
}

/* Stage 3, the shift: w's rounding error, and the origin moved by s along the ray
 * with the product s d exact. The inputs are read again rather than kept across the
 * rejection (the caller's CYLRAY_REREAD): a rejected vector then spills nothing, and
 * the rest loses nothing (it would reload them from the stack instead). */
CYLRAY_INLINE void KFN(shift)(KFN(lanes) *st, const cylray_kat_ *k, const cylray_kflags_ F)
{
    KLOAD_O_();
    vf bx = vsub(st->whx, st->ox), by = vsub(st->why, st->oy), bz = vsub(st->whz, st->oz);
    st->wlx = vsub(vsub(st->ox, vsub(st->whx, bx)), vadd(st->cx, bx));
    st->wly = vsub(vsub(st->oy, vsub(st->why, by)), vadd(st->cy, by));
    st->wlz = vsub(vsub(st->oz, vsub(st->whz, bz)), vadd(st->cz, bz));
    st->px = vfma_x2(st->s, st->dx, st->whx, st->wlx);
    st->py = vfma_x2(st->s, st->dy, st->why, st->wly);
    st->pz = vfma_x2(st->s, st->dz, st->whz, st->wlz);
}

/* An infinite cylinder has no center: c may slide along the axis (any slide u is
 * exact when the product u v is, as in the FMA). The error of a root t' grows with
 * its distance from the shifted point: a far origin aimed near c wants the point near
 * c, an origin near the surface far along the axis wants c slid to the origin's
 * level. |C / B| estimates the near root's distance; each lane keeps the shift that
 * makes it smaller. */
CYLRAY_INLINE void KFN(slide)(KFN(lanes) *st, const cylray_kat_ *k, const cylray_kflags_ F)
{
    const vf vx = st->vx, vy = st->vy, vz = st->vz, dx = st->dx, dy = st->dy, dz = st->dz;
    /* u need not be accurate (the slide is exact for any u): a leaf takes an estimate
     * of 1 / v.v. */
    vf u = vmul(KDOT(st->whx, st->why, st->whz, vx, vy, vz),
                KC_(inv_vv, vrcp_fast(KDOT(vx, vy, vz, vx, vy, vz))));
    vf hx = vfma_x(vneg(u), vx, st->whx), hy = vfma_x(vneg(u), vy, st->why),
       hz = vfma_x(vneg(u), vz, st->whz);
    vf s2 = vfnma(KDOT(hx, hy, hz, dx, dy, dz), st->rdd, vzero());
    vf qx = vfma_x2(s2, dx, hx, st->wlx);
    vf qy = vfma_x2(s2, dy, hy, st->wly);
    vf qz = vfma_x2(s2, dz, hz, st->wlz);
    vf nB2, C2, g2 = st->g, fx2, fy2, fz2;
    KFN(side_coefs)(st->rr_vv, F.aligned, dx, dy, st->ex, st->ey, st->ez, vx, vy, vz, qx, qy,
                    qz, &fx2, &fy2, &fz2, &nB2, &C2, &g2);
    vm slide = vlt(vabs(vmul(C2, st->nB)), vabs(vmul(st->C, nB2)));
    if (F.leaf)
        slide = mand(slide, st->infl);
    st->s = vsel(slide, s2, st->s);
    st->px = vsel(slide, qx, st->px), st->py = vsel(slide, qy, st->py);
    st->pz = vsel(slide, qz, st->pz);
    st->fx = vsel(slide, fx2, st->fx), st->fy = vsel(slide, fy2, st->fy);
    st->fz = vsel(slide, fz2, st->fz);
    st->nB = vsel(slide, nB2, st->nB), st->C = vsel(slide, C2, st->C);
    st->g = vsel(slide, g2, st->g);
}

/* Stage 4, the side's quadratic and its discriminant, in Lagrange's form. Returns
 * whether any lane can still hit. */
CYLRAY_INLINE int KFN(side)(KFN(lanes) *st, const cylray_kat_ *k, const cylray_kflags_ F)
{
    const vf zero = vzero(), dx = st->dx, dy = st->dy;
    st->g = zero;
    if (F.aligned) {
        /* g = w x d, in the plane: it does not change along the ray, and Kahan's
         * difference of products is accurate relative to g itself (2 eps), so g is
         * taken from the unshifted w = wh + wl, and the discriminant need not wait
         * for the shift. */
        st->g = vadd(vdop_x(st->whx, dy, st->why, dx), vfms(st->wlx, dy, vmul(st->wly, dx)));
    }
    KFN(side_coefs)(st->rr_vv, F.aligned, dx, dy, st->ex, st->ey, st->ez, st->vx, st->vy,
                    st->vz, st->px, st->py, st->pz, &st->fx, &st->fy, &st->fz, &st->nB, &st->C,
                    &st->g);
    if (!F.finite || (F.leaf && many(st->infl)))
        KFN(slide)(st, k, F);

    /* Lagrange's form of B^2 - A C, over v.v, with both products exact. AR2, the
     * larger term of D, sets its rounding. */
    const vf A = st->A, g = st->g;
    if (!F.scaled && !F.leaf) { /* a radius in [2^-20, 2^21): j = 0 */
        st->D = vdop_x(A, st->rr, g, g);
        st->AR2 = vmul(A, st->rr);
    } else { /* scaled by 2^-2j (cylray_prepared.rr_d), and sqrt_vv has 2^j */
        const vf gs = KC_(g_s, KL_(GS));
        const vf rs = vmul(st->rad, gs); /* a leaf's R 2^-j, exact */
        const vf rr_d = KC_(rr_d, vmul(rs, rs));
        vf gd = vmul(g, gs);
        st->D = vdop_x(A, rr_d, gd, gd);
        st->AR2 = vmul(A, rr_d);
    }
    vm act = mand(st->act, veq(vfma(st->C, zero, vmul(st->D, zero)), zero));

    /* A ray within about one ulp of the axis direction is parallel: it meets the side
     * nowhere, and no division by its tiny A may make a hit. */
    const vf par_eps = KC_(par_eps, vmul(KDOT(st->vx, st->vy, st->vz, st->vx, st->vy, st->vz),
                                         vset1(CYLRAY_PAR_EPS)));
    vm par = vle(A, vmul(st->dd, par_eps));
    st->side = mand(act, mandn(vge(st->D, zero), par));
    st->inpar = mand(act, mand(par, vle(st->C, zero))); /* parallel and inside the tube */
    return F.capped ? many(mor(st->side, st->inpar)) : many(st->side);
}

/* Stage 5, the side's roots tn <= tf (relative to p), polished with CYLRAY_REFINE. */
CYLRAY_INLINE void KFN(roots)(KFN(lanes) *st, const cylray_kat_ *k, const cylray_kflags_ F)
{
    const vm side = st->side;
    const vf A = st->A, C = st->C, D = st->D, nB = st->nB;
    /* The estimates see subnormal inputs as zero: below 2^-100 (rare where the
     * coordinates are near 1, and D = 0 at a tangency) the exact operation serves. */
    const vf tiny = vset1(KM_TINY);
    vf sq;
    if (F.fast) {
        sq = vmul(D, vrsqrt_fast(vmax(D, tiny)));
        vm small = mand(side, vlt(D, tiny));
        if (many(small))
            sq = vsel(small, vsqrt(D), sq);
    } else {
        sq = vsqrt(D);
    }
    if (!F.aligned) /* |v| = 1 there, and j = 0 */
        sq = vmul(sq, F.leaf ? KL_(SQS)
                             : vset1(F.scaled ? k->P->sqrt_vv / k->P->g_s : k->P->sqrt_vv));
    vf q = vadd(nB, vxorsign(sq, nB)); /* -(B + sign(B) sqrt(disc)); sq >= 0 */
    vf r1 = F.fast ? vmul(q, vrcp_fast(A)) : vdiv(q, A);
    vf r2;
    if (F.fast) {
        r2 = vmul(C, vrcp_fast(q));
        vm small = mand(side, vlt(vabs(q), tiny));
        if (many(small))
            r2 = vsel(small, vdiv(C, q), r2);
    } else {
        r2 = vdiv(C, q);
    }
    /* By construction q^2 >= A C. Where rounding of C (a point on the surface, or a
     * tangent ray) breaks that, C / q is no root: the two coincide at q / A. */
    r2 = vsel(mor(veq(q, vzero()), vlt(vmul(q, q), vmul(C, A))), r1, r2);
    /* Near a tangency D is known only to a few ulps of A R^2 (the rounding of A, R^2
     * and g), and C, at a point near the surface, only to a few ulps of R^2: C / q then
     * divides one rounding error by another and can put the root anywhere, even past
     * the origin (a ray leaving the surface reported as hitting it from inside). The
     * direct form (nB - sign sq) / A errs by the error of sq alone. */
    vm tangent = mand(side, vlt(D, vmul(st->AR2, vset1(KM_TANGENT))));
    if (many(tangent))
        r2 = vsel(tangent, vdiv(vsub(nB, vxorsign(sq, nB)), A), r2);
    st->tn = vmin(r1, r2), st->tf = vmax(r1, r2);
    if (F.refine && many(side)) {
        /* Both roots are polished before anything is decided from them, so that the
         * entry test, the clip and the range test all see the t that is reported: a
         * call with tmax set to a reported t then reports it again. */
        st->tn = KFN(polish)(st->rr_vv, st->rr, F.aligned, side, st->tn, A, st->dx, st->dy,
                             st->dz, st->ex, st->ey, st->ez, st->vx, st->vy, st->vz, st->px,
                             st->py, st->pz);
        st->tf = KFN(polish)(st->rr_vv, st->rr, F.aligned, side, st->tf, A, st->dx, st->dy,
                             st->dz, st->ex, st->ey, st->ez, st->vx, st->vy, st->vz, st->px,
                             st->py, st->pz);
    }
}

/* Where a disc is not part of the surface, the solid is still what decides entry and
 * exit (so the other rim stays watertight), but a bound made by that disc is no hit:
 * the ray passes through the open end. Going up the axis (dv > 0) it enters by the low
 * disc and leaves by the high one. */
CYLRAY_INLINE void KFN(open_ends)(KFN(lanes) *st, const cylray_kat_ *k, const cylray_kflags_ F,
                                  vf slab_in, vf slab_out)
{
    vm lo_on, hi_on;
    if (F.leaf) {
        const uint32_t *meta = (const uint32_t *)(const void *)(k->L + CYLRAY_LF_COUNT * k->lm);
        lo_on = mfrom_bits(meta[CYLRAY_LM_LO] >> k->i);
        hi_on = mfrom_bits(meta[CYLRAY_LM_HI] >> k->i);
    } else {
        lo_on = mfrom_bits(k->P->caps & CYLRAY_CAPPED_LO ? VFULL : 0u);
        hi_on = mfrom_bits(k->P->caps & CYLRAY_CAPPED_HI ? VFULL : 0u);
    }
    vm up = vgt(st->dv, vzero());
    vm in_disc = vgt(slab_in, st->side_lo), out_disc = vlt(slab_out, st->side_hi);
    vm in_open = mandn(in_disc, mor(mand(up, lo_on), mandn(hi_on, up)));
    vm out_open = mandn(out_disc, mor(mand(up, hi_on), mandn(lo_on, up)));
    st->ok_in = mandn(st->ok_in, in_open);
    st->ok_out = mandn(st->ok_out, out_open);
}

/* Stage 6, the ends: entry and exit relative to p, and whether each is on the
 * surface (the slab and the caps of a finite cylinder). */
CYLRAY_INLINE void KFN(ends)(KFN(lanes) *st, const cylray_kat_ *k, const cylray_kflags_ F)
{
    const vf zero = vzero(), inf = vset1(INFINITY), tn = st->tn, tf = st->tf;
    st->side_lo = tn, st->side_hi = tf;
    /* The axial coordinate z0 + t dv, over |v|. An aligned axis is measured along the
     * third coordinate itself, whatever its sign: the slab is symmetric, and the sign
     * only names the caps. */
    vf z0 = zero, dv = zero;
    if (F.finite) {
        z0 = F.aligned ? st->pz : KDOT(st->px, st->py, st->pz, st->vx, st->vy, st->vz);
        dv = F.aligned ? st->dz : KDOT(st->dx, st->dy, st->dz, st->vx, st->vy, st->vz);
    }
    st->z0 = z0, st->dv = dv;
    if (F.capped) {
        /* The solid is the infinite one cut by the slab |z| <= H: inside on [max of the
         * entries, min of the exits]. The rim is then shared, not tested twice. A ray
         * parallel to the axis inside the tube is inside the side everywhere. */
        st->side_lo = vsel(st->inpar, vneg(inf), tn), st->side_hi = vsel(st->inpar, inf, tf);
        const vf hv = KC_(h_v, KL_(HV));
        /* Two divisions rather than one reciprocal: a cap hit is then as exact as
         * the plane's offset, and dv = 0 gives the infinities the slab wants. */
        vf na = vsub(vneg(hv), z0), nb = vsub(hv, z0);
        vf ta, tb;
        if (F.fast) {
            vf rdv = vdiv(vset1(1.0f), dv);
            ta = vmul(na, rdv), tb = vmul(nb, rdv);
        } else {
            ta = vdiv(na, dv), tb = vdiv(nb, dv);
        }
        vf slab_in = vmin(ta, tb), slab_out = vmax(ta, tb);
        st->t_in = vmax(st->side_lo, slab_in);
        st->t_out = vmin(st->side_hi, slab_out);
        st->ok_in = mand(mor(st->side, st->inpar), vle(st->t_in, st->t_out));
        st->ok_out = st->ok_in;
        if (F.one_end)
            KFN(open_ends)(st, k, F, slab_in, slab_out);
    } else {
        st->t_in = tn, st->t_out = tf;
        st->ok_in = st->ok_out = st->side;
        if (F.kind == CYLRAY_KIND_OPEN) {
            const vf hv = vset1(k->P->h_v);
            st->ok_in = mand(st->ok_in, vle(vabs(vfma(tn, dv, z0)), hv));
            st->ok_out = mand(st->ok_out, vle(vabs(vfma(tf, dv, z0)), hv));
        }
    }
}

/* Stage 7, the decision: the entry if it is not before tmin, else the exit (a hit from
 * inside); then one range test for whichever it is. Rounding s + t is monotonic, so the
 * entry test decides correctly which of the two can be the first in [tmin, tmax]. The
 * bounds are clamped to finite values, so that no infinite t ever hits. Returns the
 * hit lanes. */
CYLRAY_INLINE uint32_t KFN(decide)(KFN(lanes) *st, const cylray_kat_ *k, const cylray_kflags_ F)
{
    const vf one = vset1(1.0f);
    vf tmin = vmax(vset1(-FLT_MAX), KR_(tmin)); /* a NaN bound stays */
    vf tmax = vmin(vset1(FLT_MAX), KR_(tmax));
    /* (min, max and comparisons take subnormals without an assist) */
    vf T_in = vadd(st->s, st->t_in), T_out = vadd(st->s, st->t_out);
    /* With a scaled direction the range test is made where no scaling rounds: a
     * shrunk d (m < 1) moves the bounds to t' (exact, or overflowing as it should), a
     * grown one moves T to t (the same): t_to_test takes t' there, t_to_user takes
     * that to t. */
    st->t_to_user = one;
    if (F.scaled) {
        vm shrunk = vlt(st->tscale, one);
        vf rs = vdiv(one, st->tscale);
        tmin = vsel(shrunk, vmul(tmin, rs), tmin);
        tmax = vsel(shrunk, vmul(tmax, rs), tmax);
        vf t_to_test = vsel(shrunk, one, st->tscale);
        st->t_to_user = vsel(shrunk, st->tscale, one);
        T_in = vmul(T_in, t_to_test), T_out = vmul(T_out, t_to_test);
    }
    vm front = mand(st->ok_in, vge(T_in, tmin));
    vm cand = F.cull ? front : mor(front, st->ok_out);
    st->tr = vsel(front, st->t_in, st->t_out); /* relative to the shifted origin */
    st->T = vsel(front, T_in, T_out);
    vm hit = mand(cand, mand(vge(st->T, tmin), vle(st->T, tmax)));
    if (k->bits != VFULL) /* a whole vector is the common case, and needs no mask */
        hit = mand(hit, mfrom_bits(k->bits));
    st->back = mandn(hit, front);
    st->front = mand(hit, front);
    st->hit = hit;
    return mbits(hit);
}

/* A hit point that rounding moved well off the surface (a radius far below the
 * coordinates' ulp) gets a true normalisation, divided by its largest component
 * first, so that a length whose square underflows or overflows still normalises. */
CYLRAY_INLINE void KFN(renormalize)(const KFN(lanes) *st, const cylray_kflags_ F, vm off,
                                    vf *nx, vf *ny, vf *nz, vf *corr)
{
    const vf zero = vzero(), inf = vset1(INFINITY);
    vf m = vmax(vabs(*nx), vmax(vabs(*ny), vabs(*nz)));
    vm lost = mandn(off, mand(vgt(m, zero), vlt(m, inf)));
    if (many(lost)) {
        /* A hit point that rounds onto the axis (a radius far below the coordinates'
         * ulp), or one so far from it that the offset is not finite (an origin far
         * beyond the documented 2^62), has no direction of its own: the side then
         * faces the ray, along -d_perp (v x e = v.v d_perp) on entry. */
        vf ux = st->dx, uy = st->dy, uz = zero;
        if (!F.aligned) {
            ux = vfms(st->vy, st->ez, vmul(st->vz, st->ey));
            uy = vfms(st->vz, st->ex, vmul(st->vx, st->ez));
            uz = vfms(st->vx, st->ey, vmul(st->vy, st->ex));
        }
        *nx = vsel(lost, vsel(st->front, vneg(ux), ux), *nx);
        *ny = vsel(lost, vsel(st->front, vneg(uy), uy), *ny);
        *nz = vsel(lost, vsel(st->front, vneg(uz), uz), *nz);
        m = vmax(vabs(*nx), vmax(vabs(*ny), vabs(*nz)));
    }
    /* n / m by division: 1 / m overflows where m is subnormal. */
    vf sx = vdiv(*nx, m), sy = vdiv(*ny, m), sz = vdiv(*nz, m);
    vf kk = vdiv(vset1(1.0f), vsqrt(KDOT(sx, sy, sz, sx, sy, sz)));
    vm ok = mand(off, mand(vgt(m, zero), vlt(m, inf)));
    *nx = vsel(ok, vmul(sx, kk), *nx), *ny = vsel(ok, vmul(sy, kk), *ny);
    *nz = vsel(ok, vmul(sz, kk), *nz);
    *corr = vsel(ok, vset1(1.0f), *corr);
}

#ifndef vstore_hits
/* The fields of a hit vector, each stored at the hit lanes (the ISA header may store
 * them together instead). */
#define vstore_hits(m, normal, pt, ptmax, ppart, pnx, pny, pnz, t, part, nx, ny, nz)      \
    do {                                                                               \
        vstore_m(pt, m, t);                                                            \
        vstore_m(ptmax, m, t);                                                         \
        vstore_part_m(ppart, m, part);                                                 \
        if (normal) {                                                                  \
            vstore_m(pnx, m, nx);                                                      \
            vstore_m(pny, m, ny);                                                      \
            vstore_m(pnz, m, nz);                                                      \
        }                                                                              \
    } while (0)
#endif

/* Stage 8b, the unit normal at the hit lanes. */
CYLRAY_INLINE void KFN(normals)(const KFN(lanes) *st, const cylray_kat_ *k,
                                const cylray_kflags_ F, vm on_side, vm cap_hi, vf *onx,
                                vf *ony, vf *onz)
{
    const vf zero = vzero(), one = vset1(1.0f), tr = st->tr;
    const vm hit = st->hit;
    vf nx, ny, nz;
    if (F.aligned) {
        const vf kn = vset1(k->P->nscale);
        nx = vmul(vfma(tr, st->dx, st->px), kn);
        ny = vmul(vfma(tr, st->dy, st->py), kn);
        nz = zero;
    } else {
        /* v x (p x v) = v.v p_perp, with p x v = f + t e already perpendicular, so
         * no axial magnitude leaks in; vk = v / (R v.v) makes it unit length. */
        const vf ns = F.leaf ? KL_(NSCALE) : zero;
        const vf kx = KC_(vk[0], vmul(st->vx, ns)), ky = KC_(vk[1], vmul(st->vy, ns)),
                 kz = KC_(vk[2], vmul(st->vz, ns));
        vf ux = vfms(tr, st->ex, st->fx), uy = vfms(tr, st->ey, st->fy),
           uz = vfms(tr, st->ez, st->fz);
        nx = vfms(ky, uz, vmul(kz, uy));
        ny = vfms(kz, ux, vmul(kx, uz));
        nz = vfms(kx, uy, vmul(ky, ux));
    }
    if (F.capped) {
        vm cap = mandn(hit, on_side);
        vf sgn = vsel(cap_hi, one, vset1(-1.0f));
        if (F.leaf) /* 1 / |v| = R |v| / (R v.v) */
            sgn = vmul(sgn, vmul(vmul(KL_(NSCALE), st->rad), vmul(KL_(SQS), KL_(GS))));
        nx = vsel(cap, F.aligned ? zero : vmul(sgn, KC_(n[0], st->vx)), nx);
        ny = vsel(cap, F.aligned ? zero : vmul(sgn, KC_(n[1], st->vy)), ny);
        nz = vsel(cap, F.aligned ? sgn : vmul(sgn, KC_(n[2], st->vz)), nz);
    }
    /* One Newton step of 1/sqrt(n.n) around 1 removes what rounding left of the
     * length error, whatever the hit point's distance from the axis. */
    vf l2 = KDOT(nx, ny, nz, nx, ny, nz);
    vf corr = vfnma(vset1(0.5f), l2, vset1(1.5f));
    vm off = mand(hit, vgt(vabs(vsub(l2, one)), vset1(KM_NORMAL_OFF)));
    if (many(off)) /* rare enough to branch */
        KFN(renormalize)(st, F, off, &nx, &ny, &nz, &corr);
    if (F.ff)
        corr = vsel(st->back, vneg(corr), corr);
    *onx = vmul(nx, corr), *ony = vmul(ny, corr), *onz = vmul(nz, corr);
}

/* Stage 8, the store: t, the part and (with CYLRAY_NORMAL) the normal of the hit
 * lanes. On a capped cylinder, the chosen t is the side's or a cap's; which cap
 * follows from the direction: entering upwards (or leaving downwards) is the low one.
 * An aligned axis pointing down the third coordinate swaps the names (P->cap_up). */
CYLRAY_INLINE void KFN(store)(const KFN(lanes) *st, const cylray_kat_ *k, const cylray_kflags_ F)
{
    const vf one = vset1(1.0f);
    const vm hit = st->hit;
    vm on_side = hit, cap_hi = hit;
    vf part = one;
    if (F.capped) {
        on_side = mand(hit, veq(st->tr, vsel(st->front, st->side_lo, st->side_hi)));
        cap_hi = mxor(vgt(st->dv, vzero()), st->front);
        part = vsel(on_side, one,
                    F.aligned ? vsel(cap_hi, vset1(k->P->cap_up), vset1(k->P->cap_down))
                              : vsel(cap_hi, vset1(CYLRAY_CAP_HI), vset1(CYLRAY_CAP_LO)));
    }
    part = vadd(part, vkeep(st->back, vset1(CYLRAY_BACKFACE)));
    vf T = F.scaled ? vmul(st->T, st->t_to_user) : st->T;
    vf nx = one, ny = one, nz = one;
    if (F.normal)
        KFN(normals)(st, k, F, on_side, cap_hi, &nx, &ny, &nz);
    const size_t i = k->i;
    if (F.scratch) {
        /* The driver reads the hit lanes of its scratch back and no other: whole
         * vectors there. (A leaf's driver sets tmax once, from the closest lane.) */
        vstoreu(k->H->t + i, T);
        if (!F.leaf)
            vstoreu(k->R->tmax + i, T);
        vstoreu_part(k->H->part + i, part);
        if (F.normal)
            vstoreu(k->H->nx + i, nx), vstoreu(k->H->ny + i, ny), vstoreu(k->H->nz + i, nz);
        return;
    }
    float *const pnx = F.normal ? k->H->nx + i : NULL, *const pny = F.normal ? k->H->ny + i : NULL,
                 *const pnz = F.normal ? k->H->nz + i : NULL;
    vstore_hits(hit, F.normal, k->H->t + i, k->R->tmax + i, k->H->part + i, pnx, pny, pnz, T,
                part, nx, ny, nz);
}

/* The stages after the rejection, for one vector. Returns the hit lanes. */
CYLRAY_INLINE uint32_t KFN(finish)(KFN(lanes) *st, const cylray_kat_ *k, const cylray_kflags_ F)
{
    KFN(shift)(st, k, F);
    if (!KFN(side)(st, k, F))
        return 0;
    KFN(roots)(st, k, F);
    KFN(ends)(st, k, F);
    uint32_t hit = KFN(decide)(st, k, F);
    if (!F.occ && hit)
        KFN(store)(st, k, F);
    return hit;
}

/* One vector of rays: lanes [i, i + VW) of R, active where `bits` is set. Returns the
 * hit lanes; writes H and R->tmax only there. FL is a compile-time constant. Where the
 * cheap rejections end the work, *rejected (if given) is set.
 *
 * With CYLRAY_KF_ALIGNED the axis is a coordinate axis (P->axis_id) and exactly a unit
 * vector: the coordinates are renamed so that it is the third one, and the side is a
 * 2D quadratic without cross products. */
CYLRAY_INLINE uint32_t KFN(block_r)(const cylray_prepared *P, const cylray_rays *R,
                                    const cylray_hits *H, size_t i, uint32_t bits,
                                    unsigned rt, const unsigned FL, const float *L, size_t lm,
                                    int *rejected)
{
    const cylray_kflags_ F = cylray_kflags_of_(FL, rt);
    const cylray_kat_ at = {P, R, H, L, lm, i, bits, cylray_kcenter_(P, F)};
    KFN(lanes) st;
    if (KFN(load_ray)(&st, &at, F))
        return CYLRAY_RARE_;
    if (!KFN(reject)(&st, &at, F)) {
        if (rejected)
            *rejected = 1;
        return 0;
    }
    CYLRAY_REREAD();
    return KFN(finish)(&st, &at, F);
}

CYLRAY_INLINE uint32_t KFN(block)(const cylray_prepared *P, const cylray_rays *R,
                                  const cylray_hits *H, size_t i, uint32_t bits,
                                  unsigned rt, const unsigned FL, const float *L, size_t lm)
{
    return KFN(block_r)(P, R, H, i, bits, rt, FL, L, lm, NULL);
}

/* Two vectors in flight: lanes [i0, i0 + VW) active where bits0 is set and
 * [i1, i1 + VW) where bits1 is. One vector's work is a chain of dependent operations
 * longer than the out-of-order window; with the stages of two vectors alternating, the
 * core has independent work while one waits on a division or a square root. A vector
 * that the rejection drops takes its partner's place as a twin. Returns how many of
 * the two the rejection dropped, with the hit lanes in m[0] and m[1]; or CYLRAY_RARE_,
 * having written nothing, when either vector needs the rare instance (the driver then
 * takes them one at a time). */
CYLRAY_INLINE uint32_t KFN(block2)(const cylray_prepared *P, const cylray_rays *R,
                                   const cylray_hits *H, size_t i0, size_t i1, uint32_t bits0,
                                   uint32_t bits1, unsigned rt, const unsigned FL,
                                   uint32_t m[2])
{
    const cylray_kflags_ F = cylray_kflags_of_(FL, rt);
    cylray_kat_ k0 = {P, R, H, NULL, 0, i0, bits0, cylray_kcenter_(P, F)};
    cylray_kat_ k1 = {P, R, H, NULL, 0, i1, bits1, cylray_kcenter_(P, F)};
    KFN(lanes) a, b;
    m[0] = m[1] = 0;
    if (KFN(load_ray)(&a, &k0, F) | KFN(load_ray)(&b, &k1, F))
        return CYLRAY_RARE_;
    const int la = KFN(reject)(&a, &k0, F), lb = KFN(reject)(&b, &k1, F);
    const uint32_t dropped = (uint32_t)(!la + !lb);
    if (dropped == 2)
        return dropped;
    CYLRAY_REREAD();
    /* A vector that the rejection drops takes the other's place: the pair then runs
     * one vector twice, at the latency of one, and the kernel stays one copy. */
    if (!la)
        a = b, k0 = k1;
    else if (!lb)
        b = a, k1 = k0;
    KFN(shift)(&a, &k0, F), KFN(shift)(&b, &k1, F);
    /* A vector that the side drops runs on with no lane in play: a branch here would
     * cost more than the work it saves, on rays that hit. */
    if (!(KFN(side)(&a, &k0, F) | KFN(side)(&b, &k1, F)))
        return dropped;
    KFN(roots)(&a, &k0, F), KFN(roots)(&b, &k1, F);
    KFN(ends)(&a, &k0, F), KFN(ends)(&b, &k1, F);
    m[0] = KFN(decide)(&a, &k0, F), m[1] = KFN(decide)(&b, &k1, F);
    if (!F.occ) {
        if (m[0])
            KFN(store)(&a, &k0, F);
        if (m[1] && la && lb) /* a twin stores nothing new */
            KFN(store)(&b, &k1, F);
    }
    m[0] = la ? m[0] : 0u, m[1] = lb ? m[1] : 0u;
    return dropped;
}
#undef KR_
#undef KL_
#undef KC_
#undef KCEN_
#undef KSANE_
#undef KPARTIAL_
#undef KLOAD_O_

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

/* The last lanes of a stream, fewer than two vectors, through a local copy: nothing
 * beyond the caller's arrays is read or written. One instance per ISA and width, with
 * the flags read at run time: it runs once per stream call. */
CYLRAY_NOINLINE size_t KFN(stream_tail)(const cylray_prepared *P, const cylray_rays *R,
                                        const cylray_hits *H, uint8_t *occluded, size_t n,
                                        size_t i, unsigned rt, unsigned FL)
{
    const int occ = (FL & CYLRAY_KF_OCCLUDED) != 0;
    const int normal = (FL & CYLRAY_NORMAL) && !occ;
    const size_t rest = n - i;
    float in[8][2 * VW] = {{0}}, out[4][2 * VW] = {{0}};
    int32_t part[2 * VW] = {0};
    const float *src[8] = {R->ox, R->oy, R->oz, R->dx, R->dy, R->dz, R->tmin, R->tmax};
    for (int f = 0; f < 8; f++)
        for (size_t j = 0; j < rest; j++)
            in[f][j] = src[f][i + j];
    const cylray_rays lr = {in[0], in[1], in[2], in[3], in[4], in[5], in[6], in[7]};
    const cylray_hits lh = {out[0], out[1], out[2], out[3], part};
    size_t count = 0;
    for (size_t b = 0; b < rest; b += VW) {
        const uint32_t bits = rest - b >= VW ? VFULL : (uint32_t)((1u << (rest - b)) - 1u);
        uint32_t m = KFN(block)(P, &lr, &lh, b, bits, rt, FL | CYLRAY_KF_SCRATCH, NULL, 0);
        if (m == CYLRAY_RARE_)
            m = KFN(block_rare)(P, &lr, &lh, b, bits, rt, FL | CYLRAY_KF_SCRATCH, NULL, 0);
        count += CYLRAY_POPCOUNT(m);
        for (; m; m &= m - 1) {
            const size_t j = b + CYLRAY_CTZ(m);
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

/* A packet of several vectors, one vector at a time. Two in flight, as the streams
 * run them, did not pay here (docs/performance.md): a packet has no further vectors
 * to pair a survivor with, and a pair that the rejection drops costs more than two
 * single vectors do. */
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

/* A stream of any length: whole vectors in place, then the last lanes through
 * KFN(stream_tail). Where the ISA file sets KPAIRS (the widths and kernels on which it
 * was measured to pay), a stream keeps two vectors in flight (KFN(block2)) while the
 * rejection drops none; once a pair sees a vector rejected, the vectors go one at a time
 * until KGROUP_ in a row pass it (a rejected vector would otherwise run beside one that
 * hits, as its twin, and cost what the pair saves). Occlusion streams run the same way. */
#ifndef KGROUP
#define KGROUP(F) 2 /* coherent rays come in runs: two that pass say the next pair will */
#endif
#define KGROUP_ KGROUP(cylray_kflags_of_(FL, rt))
CYLRAY_INLINE size_t KFN(stream)(const cylray_prepared *P, const cylray_rays *R0,
                                 const cylray_hits *H0, uint8_t *occluded, size_t n,
                                 unsigned rt, const unsigned FL)
{
    const int occ = (FL & CYLRAY_KF_OCCLUDED) != 0;
    const int aligned = (FL & CYLRAY_KF_ALIGNED) != 0;
    const cylray_rays Rv = aligned ? cylray_rays_renamed_(P, R0) : *R0;
    const cylray_hits Hv = occ ? KFN(no_hits) : aligned ? cylray_hits_renamed_(P, H0) : *H0;
    const cylray_rays *R = &Rv;
    const cylray_hits *H = &Hv;
    const size_t whole = n - n % VW;
    size_t count = 0;
    const int pairs = KPAIRS(cylray_kflags_of_(FL, rt));
    /* The occluded bytes without a branch per hit lane: a loop over the set bits
     * mispredicts on a mix of hits and misses. A lane that missed keeps its byte. */
#define KOCC_MARK_(i, m)                                                               \
    do {                                                                               \
        if (occ && (m))                                                                \
            for (size_t j_ = 0; j_ < VW; j_++)                                         \
                occluded[(i) + j_] = ((m) >> j_) & 1u ? (uint8_t)1 : occluded[(i) + j_]; \
    } while (0)
    for (size_t i = 0; i < whole;) {
        /* Each phase is a loop of its own: in one loop body with a branch between
         * them, the single vectors of streams that the rejection mostly ends ran 5-10 %
         * slower than in a driver without pairs. Two vectors at a time until a pair
         * sees one rejected... */
        for (uint32_t r = 0; pairs && !r && i + 2 * VW <= whole; i += 2 * VW) {
            uint32_t m[2] = {0u, 0u};
            r = KFN(block2)(P, R, H, i, i + VW, VFULL, VFULL, rt, FL, m);
            if (r == CYLRAY_RARE_) {
                m[0] = KFN(block_rare)(P, R, H, i, VFULL, rt, FL, NULL, 0);
                m[1] = KFN(block_rare)(P, R, H, i + VW, VFULL, rt, FL, NULL, 0);
                r = 0;
            }
            count += (size_t)CYLRAY_POPCOUNT(m[0]) + (size_t)CYLRAY_POPCOUNT(m[1]);
            KOCC_MARK_(i, m[0]);
            KOCC_MARK_(i + VW, m[1]);
        }
        /* ...then one at a time until KGROUP_ in a row pass the rejection (or one is
         * left over); without pairs, to the end. */
        for (int passed = 0;
             i < whole && (!pairs || passed < KGROUP_ || i + 2 * VW > whole); i += VW) {
            int rejected = 0;
            uint32_t m = KFN(block_r)(P, R, H, i, VFULL, rt, FL, NULL, 0, &rejected);
            if (m == CYLRAY_RARE_)
                m = KFN(block_rare)(P, R, H, i, VFULL, rt, FL, NULL, 0);
            count += CYLRAY_POPCOUNT(m);
            KOCC_MARK_(i, m);
            passed = rejected ? 0 : passed + 1;
        }
    }
#undef KOCC_MARK_
    if (whole < n)
        count += KFN(stream_tail)(P, R, H, occluded, n, whole, rt, FL);
    return count;
}
#undef KGROUP_
#undef KGROUP

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
CYLRAY_MAYBE_UNUSED CYLRAY_NOINLINE size_t KFN(stream_any)(const cylray_prepared *P,
                                                           const cylray_rays *R,
                                                           const cylray_hits *H,
                                                           uint8_t *occluded, size_t n,
                                                           unsigned rt, unsigned FL)
{
    return KFN(stream)(P, R, H, occluded, n, rt, FL);
}

CYLRAY_MAYBE_UNUSED CYLRAY_NOINLINE uint32_t KFN(packet_any)(const cylray_prepared *P, float *ray,
                                                             float *hit, size_t n,
                                                             uint32_t active, unsigned rt,
                                                             unsigned FL)
{
    return n == VW ? KFN(packet1)(P, ray, hit, active, rt, FL)
                   : KFN(packet)(P, ray, hit, n, active, rt, FL);
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
#define KSLOT_(kind, b, pk1_call, pk_body, st_call)                                    \
    static size_t KFN(st_##kind##_##b)(const cylray_prepared *P, const cylray_rays *R,  \
                                       const cylray_hits *H, uint8_t *o, size_t n,       \
                                       unsigned rt)                                     \
    {                                                                                  \
        return st_call;                                                                \
    }                                                                                  \
    static uint32_t KFN(pk1_##kind##_##b)(const cylray_prepared *P, float *R, float *H,  \
                                          size_t n, uint32_t a, unsigned rt)            \
    {                                                                                  \
        (void)n;                                                                       \
        return pk1_call;                                                               \
    }                                                                                  \
    static uint32_t KFN(pk_##kind##_##b)(const cylray_prepared *P, float *R, float *H,   \
                                         size_t n, uint32_t a, unsigned rt)             \
    {                                                                                  \
        pk_body;                                                                       \
    }
/* A packet of several vectors runs through its slot's stream driver. */
#define KSPEC_(kind, b, fl)                                                            \
    KSLOT_(kind, b, KFN(packet1)(P, R, H, a, rt, fl),                                   \
           return KFN(packet)(P, R, H, n, a, rt, fl), KFN(stream)(P, R, H, o, n, rt, fl))
#define KANY_(kind, b, fl)                                                             \
    KSLOT_(kind, b, KFN(packet_any)(P, R, H, n, a, rt, fl),                             \
           return KFN(packet_any)(P, R, H, n, a, rt, fl),                              \
           KFN(stream_any)(P, R, H, o, n, rt, fl))
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
