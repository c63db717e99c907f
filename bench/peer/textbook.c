/* SPDX-License-Identifier: MIT */
/* textbook.c - the textbook peer's setup and its builds: which of the per-ISA builds of
 * naive.c exist in this harness and run on this CPU. */
#include "textbook.h"

#include <math.h>

/* One declaration per build; the meson file defines CYLBENCH_TB_<ISA> for each it made. */
size_t tb_stream_scalar(const tb_cylinder *, const cylray_rays *, const cylray_hits *, size_t);
size_t tb_stream_sse41(const tb_cylinder *, const cylray_rays *, const cylray_hits *, size_t);
size_t tb_stream_avx2(const tb_cylinder *, const cylray_rays *, const cylray_hits *, size_t);
size_t tb_stream_avx512(const tb_cylinder *, const cylray_rays *, const cylray_hits *, size_t);
size_t tb_stream_neon(const tb_cylinder *, const cylray_rays *, const cylray_hits *, size_t);
size_t tb_sphere_stream_scalar(const tb_sphere *, const cylray_rays *, const cylray_hits *,
                               size_t);
size_t tb_sphere_stream_sse41(const tb_sphere *, const cylray_rays *, const cylray_hits *,
                              size_t);
size_t tb_sphere_stream_avx2(const tb_sphere *, const cylray_rays *, const cylray_hits *,
                             size_t);
size_t tb_sphere_stream_avx512(const tb_sphere *, const cylray_rays *, const cylray_hits *,
                               size_t);
size_t tb_sphere_stream_neon(const tb_sphere *, const cylray_rays *, const cylray_hits *,
                             size_t);
size_t tb_cone_stream_scalar(const tb_cone *, const cylray_rays *, const cylray_hits *, size_t);
size_t tb_cone_stream_sse41(const tb_cone *, const cylray_rays *, const cylray_hits *, size_t);
size_t tb_cone_stream_avx2(const tb_cone *, const cylray_rays *, const cylray_hits *, size_t);
size_t tb_cone_stream_avx512(const tb_cone *, const cylray_rays *, const cylray_hits *, size_t);
size_t tb_cone_stream_neon(const tb_cone *, const cylray_rays *, const cylray_hits *, size_t);

void tb_prepare(tb_cylinder *out, const cylray_cylinder *in)
{
    const float *a = in->axis;
    float len = sqrtf(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    for (int k = 0; k < 3; k++) {
        out->c[k] = in->center[k];
        out->v[k] = a[k] / len;
    }
    out->rr = in->radius * in->radius;
    out->inv_r = 1.0f / in->radius;
    out->h = in->half_height;
    out->caps = isinf(in->half_height) ? 0u : in->flags & CYLRAY_CAPPED;
}

void tb_prepare_sphere(tb_sphere *out, const cylray_sphere *in)
{
    for (int k = 0; k < 3; k++)
        out->c[k] = in->center[k];
    out->rr = in->radius * in->radius;
    out->inv_r = 1.0f / in->radius;
}

void tb_prepare_cone(tb_cone *out, const cylray_cone *in)
{
    float a[3];
    for (int k = 0; k < 3; k++) {
        a[k] = in->p1[k] - in->p0[k];
        out->c[k] = 0.5f * (in->p0[k] + in->p1[k]);
    }
    const float len = sqrtf(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    for (int k = 0; k < 3; k++)
        out->v[k] = a[k] / len;
    out->h = 0.5f * len;
    out->rm = 0.5f * (in->r0 + in->r1);
    out->k = (in->r1 - in->r0) / len;
    out->cnrm = 1.0f / sqrtf(1.0f + out->k * out->k);
    out->rr0 = in->r0 * in->r0;
    out->rr1 = in->r1 * in->r1;
    out->caps = in->flags & CYLRAY_CAPPED;
}

#if (defined(__x86_64__) || defined(__i386__)) && defined(__GNUC__)
#define TB_HAS(feature) __builtin_cpu_supports(feature)
#else
#define TB_HAS(feature) 0
#endif

/* Was build v made, and can this CPU run it? */
static int tb_runs(int v)
{
    switch (v) {
    case TB_SCALAR:
        return 1;
#ifdef CYLBENCH_TB_SSE41
    case TB_SSE41:
        return TB_HAS("sse4.1");
#endif
#ifdef CYLBENCH_TB_AVX2
    case TB_AVX2:
        return TB_HAS("avx2") && TB_HAS("fma");
#endif
#ifdef CYLBENCH_TB_AVX512
    case TB_AVX512:
        return TB_HAS("avx512f") && TB_HAS("avx512vl") && TB_HAS("avx512dq");
#endif
#ifdef CYLBENCH_TB_NEON
    case TB_NEON:
        return 1; /* AArch64 always has it */
#endif
    default:
        return 0;
    }
}

/* The functions of build v (declared above; referenced only where the build exists). */
#define TB_PICK(prefix, v)                                                                     \
    do {                                                                                       \
        if (!tb_runs(v))                                                                       \
            return NULL;                                                                       \
        switch (v) {                                                                           \
        case TB_SCALAR:                                                                        \
            return prefix##scalar;                                                             \
            TB_CASE_SSE41(prefix)                                                              \
            TB_CASE_AVX2(prefix)                                                               \
            TB_CASE_AVX512(prefix)                                                             \
            TB_CASE_NEON(prefix)                                                               \
        default:                                                                               \
            return NULL;                                                                       \
        }                                                                                      \
    } while (0)
#ifdef CYLBENCH_TB_SSE41
#define TB_CASE_SSE41(prefix)                                                                  \
    case TB_SSE41:                                                                             \
        return prefix##sse41;
#else
#define TB_CASE_SSE41(prefix)
#endif
#ifdef CYLBENCH_TB_AVX2
#define TB_CASE_AVX2(prefix)                                                                   \
    case TB_AVX2:                                                                              \
        return prefix##avx2;
#else
#define TB_CASE_AVX2(prefix)
#endif
#ifdef CYLBENCH_TB_AVX512
#define TB_CASE_AVX512(prefix)                                                                 \
    case TB_AVX512:                                                                            \
        return prefix##avx512;
#else
#define TB_CASE_AVX512(prefix)
#endif
#ifdef CYLBENCH_TB_NEON
#define TB_CASE_NEON(prefix)                                                                   \
    case TB_NEON:                                                                              \
        return prefix##neon;
#else
#define TB_CASE_NEON(prefix)
#endif

tb_stream_fn tb_variant(int v)
{
    TB_PICK(tb_stream_, v);
}

tb_sphere_fn tb_sphere_variant(int v)
{
    TB_PICK(tb_sphere_stream_, v);
}

tb_cone_fn tb_cone_variant(int v)
{
    TB_PICK(tb_cone_stream_, v);
}

const char *tb_variant_name(int v)
{
    static const char *const names[TB_COUNT] = {"textbook", "auto-sse41", "auto-avx2",
                                                "auto-avx512", "auto-neon"};
    return v >= 0 && v < TB_COUNT ? names[v] : "?";
}
