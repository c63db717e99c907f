/* SPDX-License-Identifier: MIT */
/* judged.c - the batch of judged.h. */
#include "judged.h"

#include "tcheck.h"

void judged_rays(const cylray_prepared *P, judged_band_fn band_of, const void *shape,
                 const gbatch *b, size_t n, size_t distinct, const char *what)
{
    const cylray_kernels *isas[CYLRAY_ISA_COUNT];
    const int nisa = g_isas(isas);
    static const int widths[] = {4, 8, 16, G_STREAM};
    cylref_band bands[2][4];
    for (size_t j = 0; shape && j < distinct && j < 4; j++) {
        const float o3[3] = {b->f[G_OX][j], b->f[G_OY][j], b->f[G_OZ][j]};
        const float d3[3] = {b->f[G_DX][j], b->f[G_DY][j], b->f[G_DZ][j]};
        for (int cull = 0; cull < 2; cull++)
            band_of(shape, o3, d3, b->f[G_TMIN][j], b->f[G_TMAX][j],
                    cull ? CYLRAY_CULL_BACK : 0u, &bands[cull][j]);
    }
    for (int i = 0; i < nisa; i++)
        for (unsigned flags = 0; flags <= CYLRAY_FLAGS_ALL; flags++)
            for (size_t wi = 0; wi < sizeof widths / sizeof widths[0]; wi++) {
                const int w = widths[wi];
                const size_t m = w == G_STREAM ? n : (size_t)w;
                gresult r, o;
                g_intersect(isas[i], w, P, b, m, 0xffffffffu, flags, (unsigned)wi, &r);
                g_occluded(isas[i], w, P, b, m, 0xffffffffu, flags, (unsigned)wi, &o);
                CHECK(o.hit == r.hit, "%s %s w=%s flags %#x: occluded %#llx, intersect %#llx",
                      what, isas[i]->name, g_width_name(w), flags, (unsigned long long)o.hit,
                      (unsigned long long)r.hit);
                for (size_t j = 0; j < m; j++) {
                    const int hit = (int)(r.hit >> j & 1);
                    if (!shape) {
                        CHECK(!hit, "%s %s w=%s flags %#x lane %zu: a zeroed prepared hit",
                              what, isas[i]->name, g_width_name(w), flags, j);
                        continue;
                    }
                    const cylref_band *band =
                        &bands[(flags & CYLRAY_CULL_BACK) != 0][j % distinct];
                    double ub = 0;
                    int v = cylref_judge(band, hit, hit ? r.part[j] : 0, hit ? r.t[j] : 0, &ub);
                    const double tol = (flags & CYLRAY_FAST) ? 8 : 4;
                    char rs[256];
                    CHECK(v == 0 && ub <= tol,
                          "%s %s w=%s flags %#x lane %zu %s: %s t %a part %#x; exact %s t %a "
                          "part %#x (verdict %d, %.3g ulps beyond)",
                          what, isas[i]->name, g_width_name(w), flags, j,
                          g_ray_str(b, j, rs, sizeof rs), hit ? "hit" : "miss",
                          hit ? (double)r.t[j] : 0.0, hit ? (unsigned)r.part[j] : 0u,
                          band->exact.hit ? "hit" : "miss", band->exact.t,
                          (unsigned)band->exact.part, v, ub);
                }
            }
}

void judged_fill(gbatch *b, const float (*rays)[8], size_t k, size_t n)
{
    for (size_t j = 0; j < n; j++)
        for (int f = 0; f < G_NFIELD; f++)
            b->f[f][j] = rays[j % k][f];
}
