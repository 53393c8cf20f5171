// SPDX-License-Identifier: MIT
// Fuzz target: `granflow analyze --set section.key=value` options
// (gf_analysis_opts_set), one per line of the input: the only user of the
// list (velocity.heights, zones.radii: increasing, `auto`) and size key types.
// After the lines, every option must pass its own check and read back to the
// same text through gf_analysis_opts_get and set (a failure aborts).
#include <stdlib.h>
#include <string.h>

#include "analysis/options.h"
#include "fuzz.h"
#include "granflow/granflow.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *text = gf_fuzz_string(data, size);
    gf_analysis_opts o = gf_analysis_opts_default();
    for (char *line = text, *next; line; line = next) {
        next = strchr(line, '\n');
        if (next) *next++ = '\0';
        gf_analysis_opts_set(&o, line); // a bad line leaves the options as they were
    }
    free(text);
    for (size_t i = 0; i < gf_analysis_keys.count; i++) {
        const gf_key *k = &gf_analysis_keys.keys[i];
        char why[160], name[128], value[1024], again[1024], assign[1200];
        if (!gf_keys_check(k, &o, why, sizeof why)) abort(); // a stored value the key refuses
        gf_analysis_opts_key_name(i, name, sizeof name);
        if (gf_analysis_opts_get(&o, name, value, sizeof value) != GF_OK) abort();
        gf_analysis_opts back = o;
        snprintf(assign, sizeof assign, "%s=%s", name, value);
        if (gf_analysis_opts_set(&back, assign) != GF_OK) abort(); // what get writes, set reads
        if (gf_analysis_opts_get(&back, name, again, sizeof again) != GF_OK || strcmp(value, again) != 0) abort();
    }
    return 0;
}
