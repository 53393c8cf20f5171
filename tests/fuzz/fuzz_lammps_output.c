// SPDX-License-Identifier: MIT
// Fuzz target: LAMMPS' output as gf_dem_run reads it while LAMMPS runs
// (gf_dem_line: phase markers, thermo lines, ERROR lines), one line of the
// input at a time; every progress report must name a known phase.
#include <stdlib.h>
#include <string.h>

#include "dem/lammps_output.h"
#include "fuzz.h"

static void gf_fuzz_progress(void *ctx, const gf_dem_progress *p)
{
    if (p->phase < GF_DEM_PHASE_FILL || p->phase > GF_DEM_PHASE_DONE) abort();
    ++*(size_t *)ctx;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *text = gf_fuzz_string(data, size);
    size_t reports = 0;
    gf_dem_run_opts o = {.ranks = 1, .progress = gf_fuzz_progress, .ctx = &reports};
    gf_dem_reader r = {.o = &o, .t_phase = __builtin_nan("")};
    for (char *line = text, *next; line; line = next) {
        next = strchr(line, '\n');
        if (next) *next++ = '\0';
        gf_dem_line(&r, line);
    }
    if (!memchr(r.error, '\0', sizeof r.error)) abort();
    free(text);
    return 0;
}
