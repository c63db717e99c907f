/* SPDX-License-Identifier: MIT */
/* spawn/forms.h - the batched forms and, at one lane, the scalar entry points */

/* ---- the batched forms ---------------------------------------------------------- */

/* Packets of n lanes (a multiple of DW): ray and hit as n-lane field arrays; normals:
 * the hit's nx, ny, nz are the kernel's normals (the normal forms). */
CYLRAY_MAYBE_UNUSED static void DFN(hit_points_packet)(const cylray_prepared *P,
                                                       const float *ray, const float *hit,
                                                       size_t n, uint32_t mask, int normals,
                                                       float *pts)
{
    DFN(geo) g;
    DFN(geo_prepared)(&g, P);
    const int32_t *part = (const int32_t *)(const void *)(hit + 4 * n);
    for (size_t b = 0; b < n; b += DW) {
        const uint32_t bits = (mask >> b) & DFULL;
        if (!bits)
            continue;
        const float *const in[10] = {
            ray + b,         ray + n + b,     ray + 2 * n + b, ray + 3 * n + b,
            ray + 4 * n + b, ray + 5 * n + b, hit + b,         normals ? hit + n + b : NULL,
            hit + 2 * n + b, hit + 3 * n + b};
        float *const out[4] = {pts + b, pts + n + b, pts + 2 * n + b, pts + 3 * n + b};
        DFN(hp_lanes)(&g, in, part + b, out, bits);
    }
}

/* The sides asked for, as +1 or -1 a lane (bits of a mask, or bytes), for sp_lanes. */
static inline void DFN(sides_bits)(float side[DW], uint32_t outward)
{
    for (int i = 0; i < DW; i++)
        side[i] = outward >> i & 1u ? 1.0f : -1.0f;
}

CYLRAY_MAYBE_UNUSED static void DFN(spawn_rays_packet)(const cylray_prepared *P,
                                                       const float *pts, const float *hit,
                                                       size_t n, uint32_t mask,
                                                       const uint32_t *outward, float *ray)
{
    DFN(geo) g;
    DFN(geo_prepared)(&g, P);
    const int32_t *part = (const int32_t *)(const void *)(hit + 4 * n);
    float side[DW];
    for (size_t b = 0; b < n; b += DW) {
        const uint32_t bits = (mask >> b) & DFULL;
        if (!bits)
            continue;
        if (outward)
            DFN(sides_bits)(side, *outward >> b);
        const float *const in[10] = {pts + b,         pts + n + b,          pts + 2 * n + b,
                                     pts + 3 * n + b, ray + 3 * n + b,      ray + 4 * n + b,
                                     ray + 5 * n + b, outward ? side : NULL};
        float *const out[3] = {ray + b, ray + n + b, ray + 2 * n + b};
        DFN(sp_lanes)(&g, in, part + b, out, bits);
        DFN(store)(ray + 6 * n + b, dset1(0.0), bits);
    }
}

/* The lanes of DW parts that are not CYLRAY_MISS. */
static inline uint32_t DFN(hit_bits)(const int32_t *part)
{
    return dmbits(dgt(dload_bits(part, CYLRAY_PART_MASK), dset1(0.0)));
}

CYLRAY_MAYBE_UNUSED static size_t DFN(hit_points_stream)(const cylray_prepared *P,
                                                         const cylray_rays *rays,
                                                         const cylray_hits *hits,
                                                         const cylray_points *pts, size_t n,
                                                         int normals)
{
    DFN(geo) g;
    DFN(geo_prepared)(&g, P);
    size_t count = 0;
    for (size_t b = 0; b < n; b += DW) {
        const float *const in[10] = {rays->ox + b,
                                     rays->oy + b,
                                     rays->oz + b,
                                     rays->dx + b,
                                     rays->dy + b,
                                     rays->dz + b,
                                     hits->t + b,
                                     normals ? hits->nx + b : NULL,
                                     normals ? hits->ny + b : NULL,
                                     normals ? hits->nz + b : NULL};
        float *const out[4] = {pts->x + b, pts->y + b, pts->z + b,
                               pts->err ? pts->err + b : NULL};
        if (b + DW > n) {
            uint32_t bits = 0;
            for (size_t i = 0; b + i < n; i++)
                bits |= (uint32_t)((hits->part[b + i] & CYLRAY_PART_MASK) != CYLRAY_MISS) << i;
            if (bits) {
                count += CYLRAY_POPCOUNT(bits);
                DFN(tail)(DFN(hp_fn), &g, in, hits->part + b, out, 4, n - b, bits);
            }
            break;
        }
        const uint32_t bits = DFN(hit_bits)(hits->part + b);
        if (!bits)
            continue;
        count += CYLRAY_POPCOUNT(bits);
        DFN(hp_lanes)(&g, in, hits->part + b, out, bits);
    }
    return count;
}

/* The spawn's inputs and outputs for the vector of lanes [b, b + cnt) of the batched
 * forms: points (with err), directions, and with outward the sides as +-1 in side. */
static inline void DFN(sp_args)(const cylray_points *pts, const uint8_t *outward,
                                const cylray_points *dirs, const cylray_points *origins,
                                size_t b, size_t cnt, float side[DW], const float *in[10],
                                float *out[3])
{
    if (outward)
        for (size_t i = 0; i < DW; i++)
            side[i] = outward[b + (i < cnt ? i : 0)] ? 1.0f : -1.0f;
    const float *const a[10] = {
        pts->x + b,  pts->y + b,  pts->z + b,  pts->err ? pts->err + b : NULL,
        dirs->x + b, dirs->y + b, dirs->z + b, outward ? side : NULL};
    for (int k = 0; k < 10; k++)
        in[k] = a[k];
    out[0] = origins->x + b, out[1] = origins->y + b, out[2] = origins->z + b;
}

/* outward: NULL (w's side), or a byte a ray (nonzero: the part's outward side). */
CYLRAY_MAYBE_UNUSED static void DFN(spawn_stream)(const cylray_prepared *P,
                                                  const cylray_points *pts, const int32_t *part,
                                                  const uint8_t *outward,
                                                  const cylray_points *dirs,
                                                  const cylray_points *origins, size_t n)
{
    DFN(geo) g;
    DFN(geo_prepared)(&g, P);
    float side[DW];
    for (size_t b = 0; b < n; b += DW) {
        const size_t cnt = n - b < DW ? n - b : DW;
        const float *in[10];
        float *out[3];
        DFN(sp_args)(pts, outward, dirs, origins, b, cnt, side, in, out);
        if (cnt < DW) {
            uint32_t bits = 0;
            for (size_t i = 0; i < cnt; i++)
                bits |= (uint32_t)((part[b + i] & CYLRAY_PART_MASK) != CYLRAY_MISS) << i;
            if (bits)
                DFN(tail)(DFN(sp_fn), &g, in, part + b, out, 3, cnt, bits);
            break;
        }
        const uint32_t bits = DFN(hit_bits)(part + b);
        if (bits)
            DFN(sp_lanes)(&g, in, part + b, out, bits);
    }
}

/* Leaves in bulk: hit i of a query of leaf[i] (its geom_ array, m lanes a field). The
 * lanes' cylinders are gathered into vectors; so are the AoS rays and hits. */
CYLRAY_MAYBE_UNUSED CYLRAY_ONE_COPY void DFN(leaf_geo)(DFN(geo) *g, const float *const *leaf,
                                                       const cylray_hit1 *hit, size_t m,
                                                       size_t cnt)
{
    float f[8][DW], lo[DW], hi[DW], sp[DW], co[DW], kap[DW];
    for (size_t i = 0; i < DW; i++) {
        const size_t j = i < cnt ? i : 0;
        const float *geom = leaf[j];
        const uint32_t *meta = (const uint32_t *)(const void *)(geom + CYLRAY_LF_COUNT * m);
        const cylray_shape_ s = cylray_leaf_shape_(geom, meta, m, hit[j].lane % m);
        for (int k = 0; k < 3; k++)
            f[k][i] = s.c[k], f[3 + k][i] = s.v[k];
        f[6][i] = s.r, f[7][i] = s.h;
        lo[i] = s.caps & CYLRAY_CAPPED_LO ? 1.0f : 0.0f;
        hi[i] = s.caps & CYLRAY_CAPPED_HI ? 1.0f : 0.0f;
        sp[i] = s.shape == CYLRAY_SHAPE_SPHERE ? 1.0f : 0.0f;
        co[i] = s.shape == CYLRAY_SHAPE_CONE ? 1.0f : 0.0f;
        kap[i] = s.kap;
    }
    vd c[3], v[3];
    for (int k = 0; k < 3; k++) {
        c[k] = dloadu_f(f[k]);
        v[k] = dloadu_f(f[3 + k]);
    }
    const vd zero = dset1(0.0);
    DFN(geo_make)
    (g, c, v, dloadu_f(f[6]), dloadu_f(f[7]), dgt(dloadu_f(lo), zero), dgt(dloadu_f(hi), zero),
     dgt(dloadu_f(sp), zero), dgt(dloadu_f(co), zero), dloadu_f(kap));
}

CYLRAY_MAYBE_UNUSED static void DFN(leaf_hit_points)(const float *const *leaf, size_t m,
                                                     const cylray_ray1 *ray,
                                                     const cylray_hit1 *hit,
                                                     const cylray_points *pts, size_t n,
                                                     int normals)
{
    for (size_t b = 0; b < n; b += DW) {
        const size_t cnt = n - b < DW ? n - b : DW;
        DFN(geo) g;
        DFN(leaf_geo)(&g, leaf + b, hit + b, m, cnt);
        float ib[10][DW], ob[4][DW];
        int32_t pb[DW];
        for (size_t i = 0; i < DW; i++) {
            const size_t j = b + (i < cnt ? i : 0);
            for (int k = 0; k < 3; k++) {
                ib[k][i] = ray[j].o[k];
                ib[3 + k][i] = ray[j].d[k];
                ib[7 + k][i] = hit[j].n[k];
            }
            ib[6][i] = hit[j].t;
            pb[i] = hit[j].part;
        }
        const float *const in[10] = {ib[0], ib[1], ib[2], ib[3],
                                     ib[4], ib[5], ib[6], normals ? ib[7] : NULL,
                                     ib[8], ib[9]};
        float *const out[4] = {ob[0], ob[1], ob[2], ob[3]};
        DFN(hp_lanes)(&g, in, pb, out, DFULL);
        for (size_t i = 0; i < cnt; i++) {
            pts->x[b + i] = ob[0][i];
            pts->y[b + i] = ob[1][i];
            pts->z[b + i] = ob[2][i];
            if (pts->err)
                pts->err[b + i] = ob[3][i];
        }
    }
}

CYLRAY_MAYBE_UNUSED static void DFN(leaf_spawn_origins)(
    const float *const *leaf, size_t m, const cylray_hit1 *hit, const cylray_points *pts,
    const uint8_t *outward, const cylray_points *dirs, const cylray_points *origins, size_t n)
{
    float side[DW];
    for (size_t b = 0; b < n; b += DW) {
        const size_t cnt = n - b < DW ? n - b : DW;
        DFN(geo) g;
        DFN(leaf_geo)(&g, leaf + b, hit + b, m, cnt);
        const float *in[10];
        float *out[3];
        DFN(sp_args)(pts, outward, dirs, origins, b, cnt, side, in, out);
        int32_t pb[DW];
        for (size_t i = 0; i < DW; i++)
            pb[i] = hit[b + (i < cnt ? i : 0)].part;
        if (cnt == DW)
            DFN(sp_lanes)(&g, in, pb, out, DFULL);
        else
            DFN(tail)(DFN(sp_fn), &g, in, pb, out, 3, cnt, (1u << cnt) - 1u);
    }
}

#if DW == 1
/* The scalar entry points: one lane; n, the kernel's normal or NULL; side as in spawn. */
CYLRAY_MAYBE_UNUSED static void DFN(hit_point1)(const DFN(geo) *g, const float o[3],
                                                const float d[3], float t, int32_t part,
                                                const float *n, float p[3], float *err)
{
    const float *const in[10] = {&o[0],
                                 &o[1],
                                 &o[2],
                                 &d[0],
                                 &d[1],
                                 &d[2],
                                 &t,
                                 n ? &n[0] : NULL,
                                 n ? &n[1] : NULL,
                                 n ? &n[2] : NULL};
    float *const out[4] = {&p[0], &p[1], &p[2], err};
    DFN(hp_lanes)(g, in, &part, out, 1u);
}

CYLRAY_MAYBE_UNUSED static void DFN(spawn1)(const DFN(geo) *g, const float p[3], float err,
                                            int32_t part, int side, const float w[3],
                                            float out[3])
{
    const float sd = (float)side;
    const float *const in[10] = {&p[0], &p[1], &p[2], &err,
                                 &w[0], &w[1], &w[2], side ? &sd : NULL};
    float *const o[3] = {&out[0], &out[1], &out[2]};
    DFN(sp_lanes)(g, in, &part, o, 1u);
}
#endif
