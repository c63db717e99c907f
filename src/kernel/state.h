/* SPDX-License-Identifier: MIT */
/* kernel/state.h - the state of one vector's lanes, and how the stages read their
 * inputs. */

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
    vf am; /* a slender shape's lanes: the frame's point c + am v (0: the center;
            * kernel/anchor.h) */
    /* side: the quadratic A t^2 - 2 nB t + C, f = v x p, and its discriminant */
    vf fx, fy, fz, nB, C, D, AR2;
    vm side, inpar; /* the side's roots exist; parallel inside the tube (a cone: the
                     * whole line inside its double cone) */
    /* side: the shapes' own (kernel/shape/), set where the shape is not theirs to
     * nothing read (KFN(shape_start)) */
    struct {
        vf cr, ca; /* the radius at the origin's level, and its rate along the ray */
        vm pol;    /* nB cancelled, the roots to be polished */
        vm near;   /* a tiny-ended cone: the lanes measured from that end, */
        vf zn;     /* and its plane's axial coordinate there (shape/cone_frame.h) */
    } cone;
    struct {
        vf pin, pout; /* a round cone: the part of its entry and of its exit */
    } round;
    /* roots, ends: the side's roots, and entry and exit relative to p */
    vf tn, tf, z0, dv, side_lo, side_hi, t_in, t_out;
    vm ok_in, ok_out;
    /* decide: the hit lanes and their t */
    vf tr, T, t_to_user;
    vm hit, front, back;
} KFN(lanes);

/* Where the stages read their inputs. Packets read the ray per lane and broadcast the
 * cylinder; a leaf broadcasts its one ray and reads a cylinder per lane. F folds each
 * choice, and the side not taken is never read (a packet has no L, a leaf no P). */

/* A ray field f (one of k->R's arrays). */
CYLRAY_INLINE vf KFN(ray_in)(const cylray_kat_ *k, const cylray_kflags_ F, const float *f)
{
    return F.leaf ? vset1(*f) : vloadu(f + k->i);
}
/* A leaf's field f (CYLRAY_LF_*) at its lanes, at L[f lm + lane]; zero elsewhere. */
CYLRAY_INLINE vf KFN(leaf_in)(const cylray_kat_ *k, const cylray_kflags_ F, unsigned f)
{
    return F.leaf ? vloadu(k->L + (size_t)f * k->lm + k->i) : vzero();
}
/* A cylinder's value: a leaf's per lane, as given (leaf, computed from its fields), or
 * the prepared cylinder's float at byte offset pf (offsetof(cylray_prepared, ...)). */
CYLRAY_INLINE vf KFN(cyl_in)(const cylray_kat_ *k, const cylray_kflags_ F, size_t pf, vf leaf)
{
    return F.leaf ? leaf : vset1(*(const float *)(const void *)((const char *)k->P + pf));
}
/* A value that both store: the prepared cylinder's at pf, a leaf's field lf. */
CYLRAY_INLINE vf KFN(both_in)(const cylray_kat_ *k, const cylray_kflags_ F, size_t pf,
                              unsigned lf)
{
    return KFN(cyl_in)(k, F, pf, KFN(leaf_in)(k, F, lf));
}
/* Coordinate c of the center (with an aligned axis, renamed). */
CYLRAY_INLINE vf KFN(center_in)(const cylray_kat_ *k, const cylray_kflags_ F, unsigned c)
{
    return F.leaf ? KFN(leaf_in)(k, F, CYLRAY_LF_CX + c) : vset1(k->c3[c]);
}
/* A leaf's meta words (internal/leaf.h: its used lanes, caps and shapes' bits), past
 * its field rows. */
CYLRAY_INLINE const uint32_t *KFN(leaf_meta)(const cylray_kat_ *k)
{
    return (const uint32_t *)(const void *)(k->L + CYLRAY_LF_COUNT * k->lm);
}
/* Whether some lanes of a packet or stream vector are inactive. */
CYLRAY_INLINE int KFN(partial)(const cylray_kat_ *k, const cylray_kflags_ F)
{
    return !F.leaf && k->bits != VFULL;
}
/* Inactive lanes may hold anything, and subnormals there would cost microcode assists
 * in every operation (20x on some cores): they take a ray that the packet rejection
 * drops, a line 2^40 from the origin (x at the active lanes, dead elsewhere). */
CYLRAY_INLINE vf KFN(sane)(const cylray_kat_ *k, vf x, vf dead)
{
    return vsel(mfrom_bits(k->bits), x, dead);
}
/* The origin and the center, loaded by the ray's stage and again by the shift's. */
CYLRAY_INLINE void KFN(load_o)(KFN(lanes) *st, const cylray_kat_ *k, const cylray_kflags_ F)
{
    st->ox = KFN(ray_in)(k, F, k->R->ox), st->oy = KFN(ray_in)(k, F, k->R->oy);
    st->oz = KFN(ray_in)(k, F, k->R->oz);
    if (KFN(partial)(k, F)) {
        st->ox = KFN(sane)(k, st->ox, vset1(0x1p40f)), st->oy = KFN(sane)(k, st->oy, vzero());
        st->oz = KFN(sane)(k, st->oz, vzero());
    }
    st->cx = KFN(center_in)(k, F, 0), st->cy = KFN(center_in)(k, F, 1);
    st->cz = KFN(center_in)(k, F, 2);
}
