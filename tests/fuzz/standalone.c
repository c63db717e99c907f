/* SPDX-License-Identifier: MIT */
/* standalone.c - main() for the fuzz target where libFuzzer is not available (gcc,
 * the aarch64 cross build): replays the files named on the command line (the seed
 * corpus, or a crash file from a long run), and with --random N [SEED] also runs N
 * pseudo-random inputs, so every build exercises the target's checks. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rng.h"
#include "tcheck.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerInitialize(int *argc, char ***argv);

int main(int argc, char **argv)
{
    LLVMFuzzerInitialize(&argc, &argv);
    unsigned long files = 0, randoms = 0;
    for (int a = 1; a < argc; a++) {
        if (strcmp(argv[a], "--random") == 0 && a + 1 < argc) {
            unsigned long n = strtoul(argv[++a], NULL, 10);
            uint64_t seed =
                a + 1 < argc && argv[a + 1][0] != '-' ? strtoull(argv[++a], NULL, 10) : 1;
            if (tc_quick())
                n /= 8;
            uint8_t buf[512];
            for (unsigned long i = 0; i < n; i++) {
                const size_t len = (size_t)(rng_splitmix64(&seed) % sizeof buf);
                for (size_t j = 0; j < len; j++)
                    buf[j] = (uint8_t)rng_splitmix64(&seed);
                /* most inputs aim their rays: set the tag bit often */
                for (size_t j = 40; j < len; j += 29)
                    buf[j] |= 0x80;
                LLVMFuzzerTestOneInput(buf, len);
                randoms++;
            }
            continue;
        }
        FILE *f = fopen(argv[a], "rb");
        if (!f) {
            fprintf(stderr, "cannot open %s\n", argv[a]);
            return 2;
        }
        static uint8_t buf[1 << 16];
        size_t len = fread(buf, 1, sizeof buf, f);
        fclose(f);
        LLVMFuzzerTestOneInput(buf, len);
        files++;
    }
    printf("fuzz target: %lu files and %lu random inputs passed\n", files, randoms);
    return files + randoms ? 0 : 77;
}
