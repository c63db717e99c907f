/* SPDX-License-Identifier: MIT */
/* simd/f64_undef.h - takes back every name a simd/f64_*.h header defined, so that another
 * width can be included next in the same translation unit. */
#undef DW
#undef DFULL
#undef vd
#undef vdm
#undef DX
#undef dset1
#undef dadd
#undef dsub
#undef dmul
#undef ddiv
#undef dsqrt
#undef dabs
#undef dmax
#undef dmin
#undef dlt
#undef dle
#undef dgt
#undef deq
#undef dmand
#undef dmor
#undef dmandn
#undef dmnot
#undef dmbits
#undef dsel
#undef dround_f
#undef dexpo
#undef dloadu_f
#undef dstoreu_f
#undef dload_bits
#undef dcmp_
#undef dones_
