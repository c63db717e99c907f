/* SPDX-License-Identifier: MIT */
/* kernel/store.h - stage 8: t, the part and the normal of the hit lanes. */

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
         * faces the ray, along -d_perp (v x e = v.v d_perp) on entry (a sphere's
         * along -d). */
        vf ux, uy, uz;
        KFN(shape_facing)(st, F, &ux, &uy, &uz);
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
 * them together instead, by the store policy, knowing which lanes are active). */
#define vstore_hits(m, active, stores, normal, pt, ptmax, ppart, pnx, pny, pnz, t, part, nx,   \
                    ny, nz)                                                                    \
    do {                                                                                       \
        vstore_m(pt, m, t);                                                                    \
        vstore_m(ptmax, m, t);                                                                 \
        vstore_part_m(ppart, m, part);                                                         \
        if (normal) {                                                                          \
            vstore_m(pnx, m, nx);                                                              \
            vstore_m(pny, m, ny);                                                              \
            vstore_m(pnz, m, nz);                                                              \
        }                                                                                      \
    } while (0)
#endif

/* Stage 8b, the unit normal at the hit lanes. */
CYLRAY_INLINE void KFN(normals)(const KFN(lanes) *st, const cylray_kat_ *k,
                                const cylray_kflags_ F, vm on_side, vm cap_hi, vf *onx, vf *ony,
                                vf *onz)
{
    const vf zero = vzero(), one = vset1(1.0f);
    const vm hit = st->hit;
    vf nx, ny, nz;
    KFN(shape_normal)(st, k, F, &nx, &ny, &nz);
    if (F.capped) {
        vm cap = mandn(hit, on_side);
        vf sgn = vsel(cap_hi, one, vset1(-1.0f));
        if (F.leaf) /* 1 / |v| from the leaf's rows */
            sgn = KFN(shape_cap_scale)(st, k, F, sgn);
        const vf n0 = KFN(cyl_in)(k, F, offsetof(cylray_prepared, n[0]), st->vx),
                 n1 = KFN(cyl_in)(k, F, offsetof(cylray_prepared, n[1]), st->vy),
                 n2 = KFN(cyl_in)(k, F, offsetof(cylray_prepared, n[2]), st->vz);
        nx = vsel(cap, F.aligned ? zero : vmul(sgn, n0), nx);
        ny = vsel(cap, F.aligned ? zero : vmul(sgn, n1), ny);
        nz = vsel(cap, F.aligned ? sgn : vmul(sgn, n2), nz);
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
CYLRAY_INLINE void KFN(store)(const KFN(lanes) *st, const cylray_kat_ *k,
                              const cylray_kflags_ F)
{
    const vf one = vset1(1.0f);
    const vm hit = st->hit;
    vm on_side = hit, cap_hi = hit;
    vf part = one;
    if (KFN(shape_part)(st, k, F, &part)) {
        /* (its discs are never on the surface) */
    } else if (F.capped) {
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
    float *const pnx = F.normal ? k->H->nx + i : NULL,
                 *const pny = F.normal ? k->H->ny + i : NULL,
                 *const pnz = F.normal ? k->H->nz + i : NULL;
    vstore_hits(hit, k->bits, F.stores, F.normal, k->H->t + i, k->R->tmax + i, k->H->part + i,
                pnx, pny, pnz, T, part, nx, ny, nz);
}
