// SPDX-License-Identifier: MIT
// Fuzz target: a checkpoint (gf_sim_load). The harness repairs what a random
// change almost always breaks first, so that the fuzzer reaches the payload
// parser: the header's payload size and CRC-32 are recomputed, and the
// configuration is read from the checkpoint's own physics text (it must match).
// A checkpoint that loads is stepped a few times and saved again.
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

#include "fuzz.h"
#include "granflow/granflow.h"

enum { GF_FUZZ_HEAD = 8 + 4 + 4 + 8 + 4 };

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size > (1u << 22)) return 0; // a few MB is plenty; larger only slows the search
    uint8_t *buf = malloc(size ? size : 1);
    if (!buf) return 0;
    if (size) memcpy(buf, data, size);
    gf_config cfg = gf_config_default();
    if (size >= GF_FUZZ_HEAD) {
        uint64_t n = size - GF_FUZZ_HEAD;
        memcpy(buf + 16, &n, 8);
        uint32_t crc = (uint32_t)crc32(crc32(0L, Z_NULL, 0), buf + GF_FUZZ_HEAD, (uInt)n);
        memcpy(buf + 24, &crc, 4);
        uint64_t plen;
        if (n >= 8) {
            memcpy(&plen, buf + GF_FUZZ_HEAD, 8);
            if (plen <= n - 8) {
                const char *ini = gf_fuzz_file(".ini", buf + GF_FUZZ_HEAD + 8, (size_t)plen);
                if (ini && gf_config_load(&cfg, ini) != GF_OK) cfg = gf_config_default();
            }
        }
    }
    const char *path = gf_fuzz_file(".bin", buf, size);
    free(buf);
    if (!path) return 0;
    gf_sim *sim = NULL;
    if (gf_config_validate(&cfg) == GF_OK && gf_sim_load(&cfg, path, &sim) == GF_OK) {
        for (int k = 0; k < 8; k++)
            if (gf_sim_step(sim) != GF_OK) break;
        gf_sim_save(sim, path);
        gf_sim_destroy(sim);
    }
    return 0;
}
