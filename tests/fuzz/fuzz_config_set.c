// SPDX-License-Identifier: MIT
// Fuzz target: `--set section.key=value` overrides (gf_config_set), one per
// line of the input, then validation.
#include <stdlib.h>
#include <string.h>

#include "fuzz.h"
#include "granflow/granflow.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *text = gf_fuzz_string(data, size);
    gf_config cfg = gf_config_default();
    gf_status st = GF_OK;
    for (char *line = text, *next; st == GF_OK && line; line = next) {
        next = strchr(line, '\n');
        if (next) *next++ = '\0';
        st = gf_config_set(&cfg, line, "--set");
    }
    if (st == GF_OK) gf_config_validate(&cfg);
    free(text);
    return 0;
}
