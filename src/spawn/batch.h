/* SPDX-License-Identifier: MIT */
/* spawn/batch.h - lanes in memory: loads and stores of the batched forms */

/* ---- lanes in memory ---------------------------------------------------------- */

/* Lane i of x to p[i] where bit i of bits is set. */
static inline void DFN(store)(float *p, vd x, uint32_t bits)
{
    if (bits == DFULL) {
        dstoreu_f(p, x);
        return;
    }
    float tmp[DW];
    dstoreu_f(tmp, x);
    for (int i = 0; i < DW; i++)
        if (bits >> i & 1u)
            p[i] = tmp[i];
}

/* Hit points of DW rays whose fields start at the given pointers (o, d: 3 each, t, then
 * the kernel's normal or NULLs); out: x, y, z, err (err may be NULL). */
CYLRAY_INLINE void DFN(hp_lanes)(const DFN(geo) *g, const float *const in[10],
                                 const int32_t *part, float *const out[4], uint32_t bits)
{
    vd o[3], d[3], p[3], err, n[3];
    for (int k = 0; k < 3; k++) {
        o[k] = dloadu_f(in[k]);
        d[k] = dloadu_f(in[3 + k]);
        n[k] = in[7] ? dloadu_f(in[7 + k]) : dset1(0.0);
    }
    DFN(hit_point)
    (g, o, d, dloadu_f(in[6]), dload_bits(part, CYLRAY_PART_MASK), in[7] ? n : NULL,
     dload_bits(part, CYLRAY_BACKFACE), p, &err);
    for (int k = 0; k < 3; k++)
        DFN(store)(out[k], p[k], bits);
    if (out[3])
        DFN(store)(out[3], err, bits);
}

/* Origins of DW points (x, y, z, err: err may be NULL for 0) with directions w, and the
 * side asked for (+1, -1; NULL: w's side). */
CYLRAY_INLINE void DFN(sp_lanes)(const DFN(geo) *g, const float *const in[10],
                                 const int32_t *part, float *const out[3], uint32_t bits)
{
    vd p[3], w[3], x[3];
    for (int k = 0; k < 3; k++) {
        p[k] = dloadu_f(in[k]);
        w[k] = dloadu_f(in[4 + k]);
    }
    const vd err = in[3] ? dloadu_f(in[3]) : dset1(0.0);
    DFN(spawn)
    (g, p, err, dload_bits(part, CYLRAY_PART_MASK), in[7] ? dloadu_f(in[7]) : dset1(0.0), w, x);
    for (int k = 0; k < 3; k++)
        DFN(store)(out[k], x[k], bits);
}

/* Fewer than DW lanes (a stream's tail): through buffers padded with the first lane. */
CYLRAY_MAYBE_UNUSED static void DFN(tail)(void (*fn)(const DFN(geo) *, const float *const[10],
                                                     const int32_t *, float *const[], uint32_t),
                                          const DFN(geo) *g, const float *const in[10],
                                          const int32_t *part, float *const *out, size_t nout,
                                          size_t cnt, uint32_t bits)
{
    float ib[10][DW], ob[4][DW];
    int32_t pb[DW];
    const float *ip[10];
    float *op[4];
    for (int f = 0; f < 10; f++) {
        ip[f] = in[f] ? ib[f] : NULL;
        for (size_t i = 0; i < DW && in[f]; i++)
            ib[f][i] = in[f][i < cnt ? i : 0];
    }
    for (size_t i = 0; i < DW; i++)
        pb[i] = part[i < cnt ? i : 0];
    for (size_t f = 0; f < 4; f++)
        op[f] = f < nout && out[f] ? ob[f] : NULL;
    fn(g, ip, pb, op, bits);
    for (size_t f = 0; f < nout; f++)
        for (size_t i = 0; i < cnt && out[f]; i++)
            if (bits >> i & 1u)
                out[f][i] = ob[f][i];
}

CYLRAY_MAYBE_UNUSED static void DFN(hp_fn)(const DFN(geo) *g, const float *const in[10],
                                           const int32_t *part, float *const out[],
                                           uint32_t bits)
{
    DFN(hp_lanes)(g, in, part, out, bits);
}

CYLRAY_MAYBE_UNUSED static void DFN(sp_fn)(const DFN(geo) *g, const float *const in[10],
                                           const int32_t *part, float *const out[],
                                           uint32_t bits)
{
    DFN(sp_lanes)(g, in, part, out, bits);
}
