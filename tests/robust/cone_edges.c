/* SPDX-License-Identifier: MIT */
/* cone_edges.c - two places where a cone's quadratic degenerates, on every path, leaf
 * width and flag set:
 *   - a lane of a leaf of cones with r0 == r1 (a cylinder there) and a ray exactly
 *     parallel to its axis: A = D = 0, so no side root; the ray inside the tube meets
 *     the caps, outside it meets nothing (as the prepared cone's packet answers);
 *   - a ray into the apex of a tip cone: the side's gradient vanishes there, and the
 *     normal must still be a unit vector (the axis, away from the cone);
 *   - cases found by cylcheck's random seeds and by the fuzzer, each judged against the
 *     exact cone (conref) on every path, packet and leaf: the rims of flat frustums,
 *     where the side's root and the disc's plane lie a fraction of an ulp of t apart
 *     though the point lies many ulps of the radius inside or outside the rim (or far
 *     from the rim, where a flat side runs along the plane), and
 *     rays near an apex or grazing a scaled cone, where SSE4.1 (no FMA) once rounded
 *     the products that cancel, and rays along an end's plane of cones so flat or so
 *     short that their inputs' rounding spans the slab (where the band's samples must
 *     see inside the box, not only its vertices); with normals, each found case's
 *     normal too. The leaf is judged by the same band: its radius is formed as the
 *     prepared cone's, from the narrower end. */
#include "conref.h"
#include "cylray.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static int failures, checks;

static void fail(const char *isa, const char *what, int i, unsigned flags, const char *why)
{
    if (failures++ < 20)
        printf("FAIL %s %s case %d flags 0x%x: %s\n", isa, what, i, flags, why);
}

/* One ray against the leaf (width 4, 8, 16) and the exact answer. */
static void parallel_rays(const cylray_kernels *k)
{
    static const cylray_cone cones[] = {
        {{0, 0, -1}, {0, 0, 1}, 1, 1, CYLRAY_CAPPED},
        {{-1, 0, 0}, {1, 0, 0}, 0.5f, 0.5f, CYLRAY_CAPPED_LO},
        {{1, 2, 3}, {2, 4, 5}, 0.75f, 0.75f, CYLRAY_CAPPED},
        {{0, 0, -1}, {0, 0, 1}, 1, 0.5f, CYLRAY_CAPPED},
    };
    /* offsets across the axis, in units of the radius */
    static const float off[] = {0, 0.5f, 0.999f, 1.001f, 1.2f, 3};
    for (int c = 0; c < 4; c++) {
        const cylray_cone *cn = &cones[c];
        float a[3], n1[3] = {0, 0, 0}, len = 0;
        for (int j = 0; j < 3; j++)
            a[j] = cn->p1[j] - cn->p0[j], len += a[j] * a[j];
        /* a unit vector across the axis: the axis crossed with the coordinate axis it
         * least follows (exact here: the axes are coordinate axes or (1, 2, 2)) */
        if (c == 2)
            n1[0] = 0, n1[1] = 1, n1[2] = -1;
        else if (a[0] != 0)
            n1[1] = 1;
        else
            n1[0] = 1;
        const float nl = sqrtf(n1[0] * n1[0] + n1[1] * n1[1] + n1[2] * n1[2]);
        cylray_cone lanes[16];
        for (int l = 0; l < 16; l++)
            lanes[l] = *cn;
        cylray_leaf4 l4;
        cylray_leaf8 l8;
        cylray_leaf16 l16;
        if (cylray_leaf_prepare_cones4(&l4, lanes, NULL, 4) != CYLRAY_OK ||
            cylray_leaf_prepare_cones8(&l8, lanes, NULL, 8) != CYLRAY_OK ||
            cylray_leaf_prepare_cones16(&l16, lanes, NULL, 16) != CYLRAY_OK) {
            fail(k->name, "leaf prepare", c, 0, "refused");
            continue;
        }
        for (int i = 0; i < (int)(sizeof off / sizeof off[0]); i++)
            for (int dir = -1; dir <= 1; dir += 2) {
                const float r = fmaxf(cn->r0, cn->r1) * off[i] / nl;
                float o[3], d[3];
                for (int j = 0; j < 3; j++) {
                    d[j] = (float)dir * a[j];
                    o[j] = (dir > 0 ? cn->p0[j] : cn->p1[j]) - 3 * d[j] + r * n1[j];
                }
                for (unsigned flags = 0; flags <= CYLRAY_FLAGS_ALL; flags++) {
                    cylref_hit ex;
                    cylref_band band;
                    conref_intersect(cn, o, d, 0, INFINITY, flags, &ex);
                    conref_band_eval(cn, o, d, 0, INFINITY, flags, &band);
                    for (int w = 0; w < 3; w++) {
                        cylray_ray1 ray = {{o[0], o[1], o[2]}, {d[0], d[1], d[2]}, 0, INFINITY};
                        cylray_hit1 h;
                        const int hit = w == 0   ? k->leaf_intersect4(&l4, &ray, &h, flags)
                                        : w == 1 ? k->leaf_intersect8(&l8, &ray, &h, flags)
                                                 : k->leaf_intersect16(&l16, &ray, &h, flags);
                        double beyond = 0;
                        checks++;
                        if (conref_judge(&band, hit, hit ? (int)h.part : 0, hit ? h.t : 0,
                                         &beyond) != 0 ||
                            beyond > 4) {
                            char why[160];
                            snprintf(why, sizeof why,
                                     "leaf%d offset %g dir %d: %s t %g part %u; exact %s t %g",
                                     4 << w, off[i], dir, hit ? "hit" : "miss", hit ? h.t : 0,
                                     hit ? (unsigned)h.part : 0u, ex.hit ? "hit" : "miss",
                                     ex.t);
                            fail(k->name, "parallel", c, flags, why);
                        }
                    }
                }
            }
    }
}

static void apex_normals(const cylray_kernels *k)
{
    /* tips at p1 = (0, 0, 1) and at p0 = (0, 0, -1) */
    static const cylray_cone cones[] = {{{0, 0, -1}, {0, 0, 1}, 1, 0, CYLRAY_CAPPED},
                                        {{0, 0, -1}, {0, 0, 1}, 0, 1, CYLRAY_CAPPED}};
    static const float rays[][6] = {
        {0, 0, 3, 0, 0, -1},  {0, 0, -3, 0, 0, 1}, {-2, 0, 1, 1, 0, 0},
        {2, 0, -1, -1, 0, 0}, {0, -2, 1, 0, 1, 0}, {0, 2, -1, 0, -1, 0},
    };
    for (int c = 0; c < 2; c++) {
        cylray_prepared p;
        if (cylray_prepare_cone(&p, &cones[c]) != CYLRAY_OK) {
            fail(k->name, "prepare", c, 0, "refused");
            continue;
        }
        cylray_ray4 r4;
        for (int l = 0; l < 4; l++) {
            const float *x = rays[(2 * l + c) % 6];
            r4.ox[l] = x[0], r4.oy[l] = x[1], r4.oz[l] = x[2];
            r4.dx[l] = x[3], r4.dy[l] = x[4], r4.dz[l] = x[5];
            r4.tmin[l] = 0, r4.tmax[l] = INFINITY;
        }
        for (unsigned flags = 0; flags <= CYLRAY_FLAGS_ALL; flags++) {
            if (!(flags & CYLRAY_NORMAL))
                continue;
            cylray_hit4 h;
            const uint32_t m = k->intersect4(&p, &r4, &h, 0xfu, flags);
            for (int l = 0; l < 4; l++) {
                if (!((m >> l) & 1u))
                    continue;
                const double n2 = (double)h.nx[l] * h.nx[l] + (double)h.ny[l] * h.ny[l] +
                                  (double)h.nz[l] * h.nz[l];
                checks++;
                if (!(fabs(n2 - 1) < 1e-5)) {
                    char why[120];
                    snprintf(why, sizeof why, "lane %d t %g part %u: n (%g %g %g)", l, h.t[l],
                             h.part[l], h.nx[l], h.ny[l], h.nz[l]);
                    fail(k->name, "apex normal", c, flags, why);
                }
            }
        }
    }
}

/* One ray against a prepared cone (a 4-ray packet, the ray in lane 2) and a leaf of
 * 4 (the cone in every lane), judged against the exact answer. */
typedef struct {
    const char *why;
    cylray_cone cone;
    float o[3], d[3], tmin;
    float tmax; /* 0: INFINITY */
} found_case;

static const found_case found[] = {
    {"flat frustum, passing 43 ulps outside the high rim (was a cap hit)",
     {{-0x1.8f1382p+0f, -0x1.a93a8cp+1f, -0x1.cc4f88p+2f},
      {-0x1.8d6288p+0f, -0x1.a84752p+1f, -0x1.cd19d6p+2f},
      0x1.871696p+2f,
      0x1.c94ac4p+2f,
      CYLRAY_CAPPED_HI},
     {0x1.a5055ap+3f, 0x1.6da7fp+4f, -0x1.a61774p+4f},
     {-0x1.e6c576p-2f, -0x1.95aa72p-1f, 0x1.87a02cp-2f},
     0,
     0},
    {"flat frustum, 40 ulps inside the high rim (was a miss on SSE4.1)",
     {{0x1.4af202p+1f, 0x1.e7651cp-2f, 0x1.017dap+2f},
      {0x1.4b57f4p+1f, 0x1.df20d4p-2f, 0x1.011814p+2f},
      0x1.3a714ap+1f,
      0x1.5158d2p+2f,
      CYLRAY_CAPPED_HI},
     {-0x1.51e06p+3f, -0x1.3311ep+4f, -0x1.656e18p+4f},
     {0x1.ffcd14p-3f, 0x1.186348p-1f, 0x1.98d8bp-1f},
     0,
     0},
    {"flat frustum, inside the low rim (was a miss)",
     {{-0x1.0a7fb2p+3f, -0x1.081b1ap+3f, 0x1.0752f6p+2f},
      {-0x1.0a4fbep+3f, -0x1.084ef6p+3f, 0x1.076bc2p+2f},
      0x1.3c4fep+2f,
      0x1.7906bep-2f,
      CYLRAY_CAPPED},
     {-0x1.ed7ef6p+3f, 0x1.22b2f2p+4f, 0x1.4dcb42p+3f},
     {0x1.96f8f6p-2f, -0x1.cdb2aap-1f, -0x1.5c13f6p-3f},
     0,
     0},
    {"a disc one ulp thick (the fuzzer's): the low disc's middle (was a miss)",
     {{0x1p+0f, -0x0p+0f, 0x1p+0f},
      {0x1.000002p+0f, 0x0p+0f, 0x1p+0f},
      0x1p+8f,
      0,
      CYLRAY_CAPPED},
     {-0x1.8p+1f, 0x1p+2f, -0x1.4p+2f},
     {0x1.ea6a04p-4f, 0x1.9c913ap-1f, -0x1.28f10ep-1f},
     0,
     0},
    {"scaled cone, near a tangency (SSE4.1 was 237 ulps off)",
     {{0x1.5f721p+27f, -0x1.4bbc4p+27f, -0x1.e690eep+29f},
      {0x1.b763a4p+29f, -0x1.aaf37ap+28f, -0x1.d03fa2p+29f},
      0x1.0e5d32p+27f,
      0x1.d7d64cp+26f,
      CYLRAY_CAPPED_LO},
     {0x1.82200ep+31f, -0x1.3a91bcp+29f, -0x1.005386p+31f},
     {-0x1.a6637ep+20f, 0x1.2c9798p+18f, 0x1.7bf1fap+19f},
     0,
     0},
    {"near an apex (SSE4.1 was 38 ulps off)",
     {{0x1.6fbdecp+0f, -0x1.73264ep+0f, 0x1.679aaap+3f},
      {-0x1.f530eep+0f, 0x1.f19872p+0f, 0x1.0b8d8ap+3f},
      0,
      0x1.38e068p+1f,
      CYLRAY_CAPPED},
     {0x1.02338cp-1f, 0x1.9ddd9ap+3f, 0x1.1873d8p+3f},
     {0x1.051884p-4f, -0x1.f79112p-1f, 0x1.5a65a8p-3f},
     0,
     0},
    {"near an apex, far along the ray (SSE4.1 was 14 ulps off)",
     {{-0x1.3a3908p+4f, 0x1.1fc298p+4f, 0x1.0bc79cp+2f},
      {0x1.a1b256p+4f, -0x1.e26a7ep+2f, -0x1.5b268p+0f},
      0x1.7fc7aap+0f,
      0,
      CYLRAY_CAPPED},
     {0x1.61758ap+5f, 0x1.14c4d2p+3f, 0x1.9cf43ap+7f},
     {-0x1.61d8fep-4f, -0x1.3cdbdcp-4f, -0x1.fc8bbcp-1f},
     0,
     0},
    {"a ray along a tip cone's generator line (was 4.6e4 ulps off: the polish refused)",
     {{0x1.37ae66p+2f, -0x1.42406cp-2f, -0x1.8045d2p+3f},
      {0x1.536a14p+1f, -0x1.6712fp+3f, 0x1.422de8p+2f},
      0x1.b97ea4p+2f,
      0,
      CYLRAY_CAPPED},
     {0x1.72f794p+0f, -0x1.dfb4aep+4f, 0x1.42d836p+4f},
     {0x1.99289cp-5f, 0x1.8de8e2p-1f, -0x1.412e9cp-1f},
     0,
     0},
    {"a ray grazing a capped cone's side (scalar and SSE4.1 were 662 ulps off)",
     {{-0x1.c2353ep+2f, 0x1.f78076p+2f, -0x1.1810f8p+1f},
      {-0x1.c27d84p+2f, 0x1.d175p+2f, -0x1.f67018p+0f},
      0x1.20717cp-1f,
      0x1.4adb54p-1f,
      CYLRAY_CAPPED},
     {-0x1.b50176p+2f, 0x1.33956ep+3f, -0x1.77ea3p+0f},
     {0x1.7dc05p-3f, -0x1.df03cp-1f, -0x1.331e9ap-2f},
     0,
     0},
    {"a disc one ulp thick (the fuzzer's): a side entry, whose radius at the hit cancels "
     "below 0 (its normal was inward)",
     {{0x1p+0f, -0x0p+0f, 0x1p+0f},
      {0x1.000002p+0f, 0x0p+0f, 0x1p+0f},
      0x1p+8f,
      0,
      CYLRAY_CAPPED},
     {-0x1.192p+13f, -0x1.192p+13f, -0x1.192p+13f},
     {-0x1.192p+13f, -0x1.192p+13f, -0x1.192p+13f},
     -0x1.049p+14f,
     0},
    {"past an open cone's apex, the two roots close together (REFINE was 5e3 ulps off)",
     {{0x1.3de91cp+3f, 0x1.4f6e76p+1f, 0x1.ac1f02p+2f},
      {-0x1.5e26dp-3f, -0x1.8ebf58p+3f, 0x1.4c8524p+1f},
      0x1.a1c09cp+2f,
      0,
      0},
     {0x1.ccb95p+3f, -0x1.f64802p+2f, 0x1.b197c2p+2f},
     {-0x1.d6d836p-1f, -0x1.2a286ap-2f, -0x1.0dffbep-2f},
     0,
     0},
    {"a flat cone's side by its tiny end's plane (the fuzzer's; was that disc, 0.1 from its "
     "1e-10 rim)",
     {{0x1.b7cdfep-34f, 0x1.b7cdfep-34f, 0x1.b7cdfep-34f},
      {0x1.b7cdfep-33f, 0x1.b7cdfep-33f, 0x1.b7cdfep-33f},
      0x1.b7cdfep-34f,
      0x1.e5ep-2f,
      CYLRAY_CAPPED},
     {0x1.49da7ep-33f, -0x1.8bcp+14f, -0x1.999cp-5f},
     {0x1.ef32d2p-22f, 0x1p-3f, -0x1.5550e6p-26f},
     -INFINITY,
     0},
    {"a flat cone crossed 0.1 degrees off its plane (the fuzzer's; was its 5e-5 disc, or a "
     "miss)",
     {{0x1.a1ap+0f, 0x1.b7cdfep-34f, 0x1.b7cdfep-34f},
      {0x1.a1ap+0f, 0x1.b7cdfep-33f, 0x1.b7cdfep-33f},
      0x1.9p-15f,
      0x1p+1f,
      CYLRAY_CAPPED},
     {-0x1.fe5e6p+8f, 0x1.49da7ep-33f, -0x1p+0f},
     {0x1.ffffacp-13f, -0x1.0f72f2p-24f, 0x1.21eeccp-21f},
     -INFINITY,
     0},
    {"a ray across a flat tip cone's axis, d.v = 0 (the fuzzer's): d.v rounds to a hair "
     "of either sign, and the box of the inputs meets the ends' planes at any t",
     {{0x1.a1ap-7f, 0x1.b7cdfep-34f, 0x1.b7cdfep-34f},
      {0x1.a1ap-7f, 0x1.b7cdfep-33f, 0x1.b7cdfep-33f},
      0x1.e5ep-2f,
      0,
      CYLRAY_CAPPED},
     {0x1.a1ap-7f, 0x1.49da7ep-33f, 0x1.12e0bep-32f},
     {0x1.30ff8p-11f, -0x1.22caccp-11f, 0x1.22caccp-11f},
     0,
     0},
    {"a ray in the low end's plane of a disc one ulp thick (the fuzzer's): the rounded "
     "center moves the cone half its length, within the box's reach along the axis",
     {{0x1p+0f, -0x0p+0f, 0x1p+0f},
      {0x1.000002p+0f, 0x0p+0f, 0x1p+0f},
      0x1p-12f,
      0,
      CYLRAY_CAPPED},
     {0x1p+0f, 0x1.8p-9f, 0x1p+0f},
     {0, -0x1p-12f, 0},
     0,
     0},
    {"a nearly level ray through a flat cone's middle (the fuzzer's): the box of the "
     "inputs takes d.v through 0, where the side is farthest",
     {{0x1.b7cdfep-34f, 0x1.b7cdfep-34f, 0x1.b7cdfep-34f},
      {0x1.b7cdfep-33f, 0x1.b7cdfep-33f, 0x1.b7cdfep-33f},
      0x1.b7cdfep-34f,
      0x1.e5ep-2f,
      CYLRAY_CAPPED},
     {0x1.49da7ep-33f, 0x1.49da7ep-33f, 0x1.49da7ep-33f},
     {-0x1.6a09e6p-10f, 0x1.6a09e6p-10f, 0x1.e1fd9ap-37f},
     -INFINITY,
     0},
    {"a nearly level ray beside a flat cone's slab (the fuzzer's): the box of the inputs "
     "lets it fall onto the wide disc, far along the ray",
     {{0x1.a1ap+0f, 0x1.b7cdfep-34f, 0x1.b7cdfep-34f},
      {0x1.a1ap+0f, 0x1.b7cdfep-33f, 0x1.b7cdfep-33f},
      0x1.9p-15f,
      0x1p+1f,
      CYLRAY_CAPPED},
     {-0x1.798p-2f, 0x1.8p+1f, -0x1.8p+1f},
     {0x1.b4a294p-10f, -0x1.4779eep-9f, 0x1.4779eep-9f},
     0,
     0},
    {"a ray by a flat cone's tiny end (the fuzzer's): its side root, 0.06 % off, falls "
     "before the plane's t; the plane's point, 17 radii outside the disc, was a cap hit",
     {{0x1.b7cdfep-34f, 0x1.b7cdfep-34f, 0x1.b7cdfep-34f},
      {0x1.b7cdfep-33f, 0x1.0c765ap-20f, 0x1.b7cdfep-33f},
      0x1.b7cdfep-34f,
      0x1.e5ep-2f,
      CYLRAY_CAPPED},
     {0, 0, 0x1p-149f},
     {-0x1p+0f, 0x1p+1f, -0x1.fap+4f},
     0,
     0},
    {"a level ray through a flat cone's middle plane (the fuzzer's): the box of the "
     "inputs lets it fall onto the wide disc anywhere along the chord from its origin",
     {{0x1.a5ap+0f, 0x1.b7cdfep-34f, 0x1.b7cdfep-34f},
      {0x1.a5ap+0f, 0x1.b7cdfep-33f, 0x1.b7cdfep-33f},
      0x1.9p-15f,
      0x1p+1f,
      CYLRAY_CAPPED},
     {0x1.4b4p-1f, 0x1.49da7ep-33f, 0x1.49da7ep-33f},
     {0x1.d02e2p+1f, -0x1.318d1ap+0f, 0x1.318d1ap+0f},
     0,
     0},
    {"a level ray from a hair below a flat cone's high plane (the fuzzer's): the box of "
     "the inputs lets it fall onto the wide disc right from its origin",
     {{0x1.a5ap+0f, 0x1.b7cdfep-34f, 0x1.b7cdfep-34f},
      {0x1.a5ap+0f, 0x1.b7cdfep-33f, 0x1.b7cdfep-33f},
      0x1.9p-15f,
      0x1p+1f,
      CYLRAY_CAPPED},
     {0x1.a5a002p+0f, 0x1.49da7ep-33f, 0x1.12e0bep-32f},
     {-0x1.f8765p-13f, -0x1.ef2894p-16f, 0x1.ef2894p-16f},
     0,
     0},
    {"near an apex of an open cone (SSE4.1 was 13 ulps off)",
     {{0x1.44601p+3f, -0x1.e55c7ep+2f, 0x1.366f3ep+1f},
      {0x1.f3788p+1f, 0x1.2f546ap+2f, 0x1.1c0d4cp+3f},
      0,
      0x1.6cdecap+1f,
      0},
     {0x1.3b536ep+5f, -0x1.56a26cp+2f, 0x1.ca8b6ep+3f},
     {-0x1.d91ebep-1f, -0x1.204a6cp-4f, -0x1.80b8d6p-2f},
     0,
     0},
    {"a steep cone's 1e-10 end beside one of 0.47 (the fuzzer's): its radius formed as "
     "rm - kap H|v| came out 7e-9, and the ray, 1.4e-10 off the axis, hit that disc",
     {{0x1.b7cdfep-34f, 0x1.b7cdfep-34f, 0x1.b7cdfep-34f},
      {0x1.b7cdfep-33f, 0x1.0c765ap-20f, 0x1.b7cdfep-33f},
      0x1.b7cdfep-34f,
      0x1.e5ep-2f,
      CYLRAY_CAPPED},
     {0, 0x1.b7cdfep-34f, 0x1.343442p-75f},
     {0x1.b7cdfep-34f, 0x1.b7cdfep-34f, 0x1.b7cdfep-34f},
     0x1.b7cdfep-34f,
     0x1.7998p+0f},
    {"a flat tip cone 1.4e-10 long of radius 0.47, left from its center (the fuzzer's)",
     {{0x1.cp-16f, 0, 0},
      {0x1.c0006ep-16f, 0x1.b7cdfep-34f, 0x1.b7cdfep-34f},
      0x1.e5ep-2f,
      0,
      CYLRAY_CAPPED},
     {0x1.c00038p-16f, 0x1.b7cdfep-35f, 0x1.b7cdfep-35f},
     {-0x1.93c178p+2f, 0x1.b13d4cp+0f, 0x1.27a00ep+2f},
     0,
     0},
    {"a ray from 4e-4 off a cone's 6e-6 end at the origin, 3 from its center: t formed as "
     "s + t' from the center's frame came out 2e4 ulps late (AVX2, AVX-512)",
     {{0, 0, 0},
      {0x1.7debdcp+2f, 0x1.d431a6p-2f, 0x1.f5aa14p-1f},
      0x1.abf534p-18f,
      0x1.2b3832p+2f,
      0},
     {-0x1.1440b6p-12f, -0x1.127dc4p-13f, -0x1.229dfp-12f},
     {0x1.4fc1ccp-1f, 0x1.4421eap-2f, 0x1.5eebdap-1f},
     0,
     0},
    {"a ray passing 1.3e-5 from a cone's 1.4e-9 end at the origin, 9 from its center: the "
     "side's entry, rounded in the center's frame, fell before the plane's (was cap_lo)",
     {{0, 0, 0},
      {-0x1.137c3p+4f, 0x1.ccffacp+2f, 0x1.64873cp-4f},
      0x1.7aa13ep-30f,
      0x1.5e86dap+2f,
      CYLRAY_CAPPED},
     {0x1.b405c2p-12f, -0x1.4b6c5p-12f, 0x1.3e7994p-14f},
     {-0x1.9508aap-1f, 0x1.3324fp-1f, -0x1.ea281p-4f},
     0,
     0},
    {"a tip cone's side 8 from the tip: C = f.f - v.v r0^2 in chained FMAs put t 12 ulps "
     "beyond the band (AVX2, AVX-512)",
     {{0x1.158ff4p+2f, -0x1.5acdbp+2f, 0x1.92c6cep+2f},
      {0x1.1b5fc8p+3f, -0x1.2bbc76p+3f, 0x1.3ae486p+2f},
      0x1.e12e36p+1f,
      0,
      CYLRAY_CAPPED},
     {0x1.ba6358p+3f, -0x1.448f3p+3f, 0x1.b116e8p+1f},
     {-0x1.e3cb58p-1f, 0x1.2e18bp-3f, 0x1.2b385ep-2f},
     0,
     0},
    {"a ray in the plane of a cone's 1.4e-3 disc (d.v 2.7e-9), through it: either facing "
     "of that disc is in the box (the band once had only the falling one)",
     {{0, 0, 0},
      {0x1.36c2a2p+6f, -0x1.1dc5p+5f, 0x1.3289e8p+4f},
      0x1.77be04p-10f,
      0x1.04d674p+3f,
      CYLRAY_CAPPED_LO},
     {-0x1.165be8p+7f, -0x1.478c52p+8f, -0x1.729b9p+5f},
     {0x1.8d1bfep-2f, 0x1.d34834p-1f, 0x1.085964p-3f},
     0,
     0},
    {"a tip cone 1e4 radii long along x, a ray from beside its far end: the center's frame "
     "3400 from the hit kept 10 bits of t (every path; an exact oracle's)",
     {{-0x1.8p+1f, 0x1p+0f, 0x1p+1f},
      {0x1.3868p+13f, 0x1p+0f, 0x1p+1f},
      0x0p+0f,
      0x1p+0f,
      CYLRAY_CAPPED_HI},
     {0x1.0e1ec8p+13f, -0x1.28b43p-1f, 0x1.b82c8cp+1f},
     {-0x1.deba82p-1f, 0x1.3173f8p-2f, -0x1.88af7p-3f},
     0,
     0},
    {"an oblique cone 1e4 radii long, a ray from next to its side (8,323 ulps off in the "
     "center's frame; an exact oracle's)",
     {{0x1.333334p-2f, -0x1.99999ap-3f, 0x1.99999ap-4f},
      {0x1.5686dep+4f, -0x1.5286dep+6f, 0x1.8ad08cp+5f},
      0x1.47ae14p-7f,
      0x1.47ae14p-8f,
      CYLRAY_CAPPED},
     {0x1.bba91cp-1f, -0x1.33dc5cp+1f, 0x1.64d4e4p+0f},
     {-0x1.3ecfb6p-3f, -0x1.e42f48p-1f, 0x1.24473ep-2f},
     0,
     0},
    {"a line along a generator, outside the cone (A = B = 0 exactly, C > 0): A and D "
     "rounded to small negatives read as inside everywhere, and the high disc was hit "
     "outside its rim (an exact oracle's)",
     {{0x1p-2f, -0x1p-1f, 0x1p-3f},
      {0x1p-2f, -0x1p-1f, 0x1.1p+1f},
      0x1.21781p+2f,
      0x1.21781p+1f,
      CYLRAY_CAPPED},
     {0x1.2p+1f, -0x1p-1f, 0x1.08p+2f},
     {0x0p+0f, -0x1.21781p+0f, -0x1p+0f},
     0,
     0},
    {"a ray passing the apex of a tip cone a hair outside it: D rounded below 0 read as "
     "inside everywhere, the entry fell on the tip's open end, and the far disc's exit "
     "was reported from inside (an exact oracle's)",
     {{0x1.4cccccp+0f, -0x1.666666p-1f, 0x1.99999ap-2f},
      {0x1.998812p+0f, -0x1.e6204ap+0f, 0x1.1970b4p+0f},
      0x0p+0f,
      0x1.99999ap-1f,
      CYLRAY_CAPPED},
     {0x1.2050a4p+1f, 0x1.fe9ff8p+0f, -0x1.063908p+1f},
     {-0x1.032722p-2f, -0x1.6e9658p-1f, 0x1.4d1e42p-1f},
     0,
     0},
    {"a ray of a 2^-149 direction 0.47 off the axis of a needle 1e6 long of radius 1e-10 at "
     "its base, outside it (A underflowed to -0, and the side's roots read as its inside; "
     "the fuzzer's)",
     {{0x1.b7cdfep-34f, 0x1.b7cdfep-34f, 0x1.b7cdfep-34f},
      {0x1.b7cdfep-33f, 0x1.b7cdfep-33f, 0x1.e848p+19f},
      0x1.b7cdfep-34f,
      0,
      CYLRAY_CAPPED},
     {0, 0x1.e5ep-2f, -0.0f},
     {0, 0, 0x1p-149f},
     -1,
     2},
};

static void found_cases(const cylray_kernels *k)
{
    for (int c = 0; c < (int)(sizeof found / sizeof found[0]); c++) {
        const found_case *x = &found[c];
        cylray_prepared p;
        cylray_leaf4 l4;
        const cylray_cone lanes[4] = {x->cone, x->cone, x->cone, x->cone};
        if (cylray_prepare_cone(&p, &x->cone) != CYLRAY_OK ||
            cylray_leaf_prepare_cones4(&l4, lanes, NULL, 4) != CYLRAY_OK) {
            fail(k->name, "found: prepare", c, 0, "refused");
            continue;
        }
        for (unsigned flags = 0; flags <= CYLRAY_FLAGS_ALL; flags++) {
            cylref_band band;
            const float tmax = x->tmax > 0 ? x->tmax : INFINITY;
            conref_band_eval(&x->cone, x->o, x->d, x->tmin, tmax, flags, &band);
            const double tol = flags & CYLRAY_FAST ? 8 : 4;
            for (int w = 0; w < 2; w++) {
                int hit;
                float t = 0, n[3] = {0, 0, 0};
                unsigned part = 0;
                if (w == 0) {
                    cylray_ray4 r4;
                    cylray_hit4 h;
                    for (int l = 0; l < 4; l++) {
                        r4.ox[l] = x->o[0], r4.oy[l] = x->o[1], r4.oz[l] = x->o[2];
                        r4.dx[l] = x->d[0], r4.dy[l] = x->d[1], r4.dz[l] = x->d[2];
                        r4.tmin[l] = x->tmin, r4.tmax[l] = tmax;
                    }
                    hit = (k->intersect4(&p, &r4, &h, 0x4u, flags) >> 2) & 1u;
                    t = h.t[2], part = (unsigned)h.part[2];
                    n[0] = h.nx[2], n[1] = h.ny[2], n[2] = h.nz[2];
                } else {
                    cylray_ray1 ray = {{x->o[0], x->o[1], x->o[2]},
                                       {x->d[0], x->d[1], x->d[2]},
                                       x->tmin,
                                       tmax};
                    cylray_hit1 h;
                    hit = k->leaf_intersect4(&l4, &ray, &h, flags);
                    t = h.t, part = (unsigned)h.part;
                    memcpy(n, h.n, sizeof n);
                }
                double beyond = 0;
                checks++;
                if (conref_judge(&band, hit, hit ? (int)part : 0, hit ? t : 0, &beyond) != 0 ||
                    beyond > tol) {
                    char why[200];
                    snprintf(why, sizeof why, "%s, %s: %s t %a part 0x%x, %.3g ulps beyond",
                             x->why, w ? "leaf" : "packet", hit ? "hit" : "miss", hit ? t : 0,
                             hit ? part : 0u, beyond);
                    fail(k->name, "found", c, flags, why);
                }
                /* the normal, where the outcome is the exact one (the rule of
                 * tests/check: unit length, and within the band's spread) */
                if (hit && (flags & CYLRAY_NORMAL) && (int)part == band.exact.part) {
                    const double len = sqrt((double)n[0] * n[0] + (double)n[1] * n[1] +
                                            (double)n[2] * n[2]),
                                 ang = cylref_angle(n, band.exact.n);
                    checks++;
                    if (!(fabs(len - 1) <= 1e-5) || !(ang <= 1e-6 + band.n_spread)) {
                        char why[200];
                        snprintf(why, sizeof why,
                                 "%s, %s: n (%g %g %g), %.3g rad from the exact", x->why,
                                 w ? "leaf" : "packet", n[0], n[1], n[2], ang);
                        fail(k->name, "found normal", c, flags, why);
                    }
                }
            }
        }
    }
}

int main(void)
{
    for (int isa = 0; isa < CYLRAY_ISA_COUNT; isa++) {
        const cylray_kernels *k = cylray_kernels_for((cylray_isa)isa);
        if (!k)
            continue;
        parallel_rays(k);
        apex_normals(k);
        found_cases(k);
    }
    printf("robust-cone-edges: %d checks, %d failures\n", checks, failures);
    return failures != 0;
}
