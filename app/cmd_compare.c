// SPDX-License-Identifier: MIT
// `granflow compare DEM_DIR SPOT_DIR`: the two runs side by side (thesis
// Sec. 3.5): flow rate, velocity profiles, diffusion, g(r), g3, density drop,
// central-slice pictures at the same times; CSV, plots and summary.md.
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "granflow/dem.h"

int gf_cmd_compare(int argc, char **argv)
{
    gf_demargs a;
    int rc = gf_demargs_parse("compare", argc, argv, &a);
    if (rc != GF_EXIT_OK) return rc;
    if (a.npos != 2) {
        fprintf(stderr, "granflow compare: error: give the DEM run and the spot run\n"
                        "usage: granflow compare DEM_DIR SPOT_DIR [--timestep DT] [--config INI] [--set key=value]... "
                        "[-o OUTDIR] [--no-plots]\n");
        return GF_EXIT_USAGE;
    }
    gf_series dem, spot;
    gf_status st = gf_demargs_load("compare", &a, a.pos[0], true, &dem);
    if (st != GF_OK) return gf_cli_fail("compare", st);
    st = gf_demargs_load("compare", &a, a.pos[1], false, &spot);
    if (st != GF_OK) {
        gf_series_free(&dem);
        return gf_cli_fail("compare", st);
    }
    char outbuf[4096];
    const char *out = a.out;
    if (!out) {
        snprintf(outbuf, sizeof outbuf, "%s/compare", a.pos[1]);
        out = outbuf;
    }
    gf_analysis_opts o;
    gf_dem_calibration_opts(&dem, &a.opts, &o);
    st = gf_dem_compare(&dem, &spot, &o, out, a.plots);
    gf_series_free(&dem);
    gf_series_free(&spot);
    if (st != GF_OK) return gf_cli_fail("compare", st);
    if (!a.quiet) fprintf(stderr, "granflow compare: results in %s (summary.md, summary.csv, dem_*.csv, spot_*.csv, compare.png, slices_*.png)\n", out);
    return GF_EXIT_OK;
}
