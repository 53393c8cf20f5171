// SPDX-License-Identifier: MIT
// Fuzz target: a configuration file (gf_config_load: INI through libinih,
// line checks, key table), then validation and writing it back out.
#include <stdio.h>

#include "fuzz.h"
#include "granflow/granflow.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *path = gf_fuzz_file(".ini", data, size);
    if (!path) return 0;
    gf_config cfg = gf_config_default();
    if (gf_config_load(&cfg, path) == GF_OK && gf_config_validate(&cfg) == GF_OK) {
        FILE *f = fopen("/dev/null", "w");
        if (f) {
            gf_config_write(&cfg, f);
            fclose(f);
        }
    }
    return 0;
}
