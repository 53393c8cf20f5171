// SPDX-License-Identifier: MIT
// `granflow compare DEM_DIR SPOT_DIR`: the two runs side by side (thesis
// Sec. 3.5): flow rate, velocity profiles, diffusion, g(r), g3, density drop,
// residence times, central-slice pictures at the same times; CSV, plots and summary.md.
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "granflow/dem.h"

int gf_cmd_compare(int argc, char **argv)
{
    gf_demargs a;
    int rc = gf_demargs_parse("compare", argc, argv, &a);
    if (rc != GF_CLI_GO) return rc;
    if (a.npos != 2) {
        fprintf(stderr, "granflow compare: error: give the DEM run and the spot run\n"
                        "usage: granflow compare DEM_DIR SPOT_DIR [--timestep DT] [--config INI] [--set key=value]... "
                        "[-o OUTDIR] [--no-plots]\n");
        return GF_EXIT_USAGE;
    }
    a.opts.stop = gf_cli_catch_stop(); // reading and measuring both runs
    gf_series dem, spot;
    gf_status st = gf_demargs_load("compare", &a, a.pos[0], true, &dem);
    if (st == GF_OK) {
        st = gf_demargs_load("compare", &a, a.pos[1], false, &spot);
        if (st != GF_OK) gf_series_free(&dem);
    }
    if (st == GF_ERR_INTERRUPTED) return gf_cli_interrupted("compare", "nothing written");
    if (st != GF_OK) return gf_cli_fail("compare", st);
    char outbuf[4096];
    const char *out = a.out;
    if (!out) {
        snprintf(outbuf, sizeof outbuf, "%s/compare", a.pos[1]);
        out = outbuf;
    }
    // The DEM's steady window (unless given) for both runs: the spot run
    // starts from the DEM's first snapshot, so their clocks agree.
    gf_steady win;
    st = gf_dem_window(&dem, &a.opts, &win);
    gf_analysis_opts o;
    if (st == GF_OK) {
        if (!a.quiet) fprintf(stderr, "granflow compare: window %g..%g tau: %s\n", win.t0, win.t1, win.reason);
        gf_dem_calibration_opts(&dem, &a.opts, &o);
        gf_dem_compare_opts(&dem, &spot, &o); // both residence-time distributions cut at the shorter run
        st = gf_dem_compare(&dem, &spot, &o, out, a.plots);
    }
    // Each difference with its uncertainty and verdict; the exit code does
    // not depend on the verdicts (a comparison is not a test).
    gf_dem_flowstats fd, fsp;
    if (st == GF_OK) st = gf_dem_flowstats_measure(&dem, &o, false, &fd);
    if (st == GF_OK) st = gf_dem_flowstats_measure(&spot, &o, false, &fsp);
    if (st == GF_OK) {
        printf("DEM vs spot over %g..%g tau (uncertainties: standard errors over %zu sub-windows, window.parts):\n", o.t0,
               o.t1, fd.parts);
        gf_dem_flowstats_table(&fd, &fsp, GF_DEM_FLOW_TOL, GF_DEM_VAR_TOL, stdout);
        printf("%s\n", gf_dem_flowstats_match(&fd, &fsp, GF_DEM_FLOW_TOL, GF_DEM_VAR_TOL)
                          ? "verdict: the spot run matches the DEM (flow rate within 5%, Var within 10% at every "
                            "measured height)"
                          : "verdict: the spot run does NOT match the DEM within the tolerances (flow rate 5%, Var "
                            "10% at every measured height)");
    }
    gf_series_free(&dem);
    gf_series_free(&spot);
    if (st == GF_ERR_INTERRUPTED)
        return gf_cli_interrupted("compare", "summary.md not written (each CSV file written is whole)");
    if (st != GF_OK) return gf_cli_fail("compare", st);
    if (!a.quiet) fprintf(stderr, "granflow compare: results in %s (summary.md, summary.csv, dem_*.csv, spot_*.csv, compare.png, slices_*.png)\n", out);
    return GF_EXIT_OK;
}
