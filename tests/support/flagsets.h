/* SPDX-License-Identifier: MIT */
/* flagsets.h - the kernel flag combinations the tests run their cases under.
 *
 * Every flag is exercised alone (with CYLRAY_NORMAL where it acts on the normal), next
 * to the flags that act on the same decision, and all together; each combination
 * selects its own specialised kernel, so each is a separate path to test. The list is
 * ordered so that a prefix serves a test whose cases are costly:
 *   the first FLAG_SETS_QUICK   no flag and every flag (quick runs: sanitizers, qemu)
 *   the first FLAG_SETS_FEW     those, plus normals alone and with culling, face-forward
 *                               normals, and culling with refinement
 *   all FLAG_SETS_ALL           every combination listed */
#ifndef FLAGSETS_H
#define FLAGSETS_H

#define FLAG_SETS_QUICK 2
#define FLAG_SETS_FEW 6
#define FLAG_SETS_ALL 10

extern const unsigned flag_sets[FLAG_SETS_ALL];

#endif
