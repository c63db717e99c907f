/* SPDX-License-Identifier: MIT */
/* kernel/kernel.h - the ray/cylinder kernel, written once against the vector vocabulary.
 *
 * Included once per ISA and width, after a simd/ header, with:
 *   KFN(name)  the name with this instantiation's suffix (e.g. name_avx2_8)
 *   VW         lanes per vector
 *   KPAIRS(F)  optional: whether the stream kernel of flags F keeps two vectors in
 *              flight (KFN(block2)); one at a time unless the ISA file says otherwise
 *   KGROUP(F)  optional: after how many vectors in a row that pass the rejection such
 *              a stream resumes its pairs; 2 unless the ISA file says otherwise
 * It defines KFN(block), the kernel for one vector of rays, and the flag-specialised
 * packet and stream drivers with their lookup tables: KFN(isect1_table) and
 * KFN(occ1_table) for packets of one vector, KFN(isect_table) and KFN(occ_table) for
 * packets of several, KFN(isect_stream_table) and KFN(occ_stream_table); KFN(vw) = VW.
 *
 * The files below read in the order a vector flows: the margins and where a vector's
 * lanes come from (shared by every instantiation), the math, the lane state, a
 * slender shape's frame, each shape's own work (kernel/shape.h), the stages from the
 * ray to the store, the block that runs them, the packet, stream and
 * leaf drivers, the drivers with the flags read at run time, and the tables.
 *
 * The math is docs/design.md section 2. Coordinates are cylinder-relative: w = o - c is
 * formed exactly as a two-term sum, then the origin is moved along the ray to its
 * closest approach to the center (with the product s*d exact inside an FMA), so that
 * the error of everything after grows with the distance from there, not from o. The
 * axis v is the user's, scaled by a power of two, never normalised: v.v is carried
 * through instead. With e = d x v, f = w' x v, the side is A t^2 + 2 B t + C = 0 with
 *   A = e.e,  B = e.f,  C = f.f - R^2 v.v,  disc = v.v (A R^2 - g^2),  g = e.w'.
 */

#include "margins.h"
#include "io.h"

#ifndef KPAIRS
#define KPAIRS(F) 0
#endif
#ifndef KGROUP
#define KGROUP(F) 2 /* coherent rays come in runs: two that pass say the next pair will */
#endif

typedef uint32_t (*KFN(packet_fn))(const cylray_prepared *, float *, float *, size_t, uint32_t,
                                   unsigned);
typedef size_t (*KFN(stream_fn))(const cylray_prepared *, const cylray_rays *,
                                 const cylray_hits *, uint8_t *, size_t, unsigned);
typedef int (*KFN(leaf_fn))(const float *, size_t, cylray_ray1 *, cylray_hit1 *, unsigned);

#include "kmath.h"
#include "state.h"
#include "anchor.h"
#include "shape.h"
#include "front.h"
#include "solve.h"
#include "ends.h"
#include "store.h"
#include "block.h"
#include "packet.h"
#include "stream.h"
#include "leaf.h"
#include "runtime.h"
#include "tables.h"

#undef KGROUP
