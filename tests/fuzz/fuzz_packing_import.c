// SPDX-License-Identifier: MIT
// Fuzz target: the import of packing.file as a run's initial packing
// (gf_packing_import: packing.types filter, the particles below the base
// dropped, radii and shared centres checked), then the relaxation it is fed
// to. The input's first line is `FORMAT TYPES`: FORMAT dump, xyz or csv
// (the file's suffix; anything else is a dump), the rest packing.types; the
// lines after it are the file.
#include <stdlib.h>
#include <string.h>

#include "fuzz.h"
#include "granflow/granflow.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const uint8_t *nl = memchr(data, '\n', size);
    size_t head = nl ? (size_t)(nl - data) : size;
    char *first = gf_fuzz_string(data, head);
    const char *suffix = !strncmp(first, "xyz", 3) ? ".xyz" : !strncmp(first, "csv", 3) ? ".csv" : ".dump";
    const char *types = strchr(first, ' ') ? strchr(first, ' ') + 1 : "";
    gf_config cfg = gf_config_default();
    size_t body = nl ? size - head - 1 : 0;
    const char *path = gf_fuzz_file(suffix, nl ? nl + 1 : data, body);
    if (path && strlen(path) < sizeof cfg.packing_file && strlen(types) < sizeof cfg.packing_types) {
        memcpy(cfg.packing_file, path, strlen(path) + 1);
        memcpy(cfg.packing_types, types, strlen(types) + 1);
        gf_packing pk = {0};
        gf_packing_import_report rep;
        if (gf_packing_import(&cfg, &pk, &rep) == GF_OK) {
            if (pk.n == 0 || pk.n + rep.other_types + rep.below_base != rep.read) abort();
            for (size_t i = 0; i < pk.n; i++)
                if (!(pk.z[i] >= gf_config_exit_plane(&cfg)) || !(pk.r[i] >= 0.25 && pk.r[i] <= 0.75)) abort();
        }
        gf_packing_free(&pk);
    }
    free(first);
    return 0;
}
