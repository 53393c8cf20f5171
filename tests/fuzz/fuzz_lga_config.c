// SPDX-License-Identifier: MIT
// Fuzz target: an LGA configuration: the INI file, then the scenario it
// builds (lattice, walls, hopper, initial particles) and a few iterations.
// Lattices above 20,000 sites are skipped (size limits are tested elsewhere;
// here they would only make each input slow).
#include "fuzz.h"
#include "granflow/granflow.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *path = gf_fuzz_file(".ini", data, size);
    if (!path) return 0;
    gf_config cfg = gf_config_default();
    if (gf_config_load(&cfg, path) != GF_OK || gf_config_validate(&cfg) != GF_OK) return 0;
    if ((double)cfg.lga_width * (double)cfg.lga_height > 20000.0 || cfg.lga_particles > 20000) return 0;
    if (cfg.lga_width == 0 || cfg.lga_height == 0) return 0; // the scenarios' defaults are large
    gf_lga *l = NULL;
    if (gf_lga_create(&cfg, &l) != GF_OK) return 0;
    gf_lga_run(l, 3, NULL);
    gf_lga_destroy(l);
    return 0;
}
