/* SPDX-License-Identifier: MIT */
/* kernel/lanes.h - the state of one vector's lanes, and how the stages read their
 * inputs (undefined again at the end of kernel/block.h). */

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
#define KLOAD_O_()                                                                             \
    do {                                                                                       \
        st->ox = KR_(ox), st->oy = KR_(oy), st->oz = KR_(oz);                                  \
        if (KPARTIAL_)                                                                         \
            KSANE_(ox, vset1(0x1p40f)), KSANE_(oy, vzero()), KSANE_(oz, vzero());              \
        st->cx = KCEN_(0, CX), st->cy = KCEN_(1, CY), st->cz = KCEN_(2, CZ);                   \
    } while (0)
