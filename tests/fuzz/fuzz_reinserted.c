// SPDX-License-Identifier: MIT
// Fuzz target: reinserted.txt, the record a recirculating DEM drain writes
// (src/dem/lammps_recirculate.c), as `granflow dem` turns it into exits.csv
// (gf_dem_write_exits, src/dem/reinserted.c). What it writes must read back
// through gf_exits_read, sorted by time, every pass >= 1.
#include <stdio.h>
#include <stdlib.h>

#include "core/alloc.h"
#include "dem/dem_internal.h"
#include "fuzz.h"
#include "granflow/granflow.h"
#include "io/exits_read.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *dir = gf_fuzz_dir();
    if (!dir || gf_fuzz_dir_file(dir, GF_DEM_REINSERTED, data, size) != 0) return 0;
    if (gf_dem_write_exits(dir) != GF_OK) return 0;
    char path[4096];
    snprintf(path, sizeof path, "%s/exits.csv", dir);
    gf_exit *e = NULL;
    size_t n = 0;
    if (gf_exits_read(path, &e, &n) != GF_OK) abort(); // what it wrote, it must read
    for (size_t k = 0; k < n; k++)
        if (e[k].pass < 1 || (k > 0 && e[k].time < e[k - 1].time)) abort();
    if (e) GF_DELETE(e, n);
    return 0;
}
