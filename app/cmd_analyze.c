// SPDX-License-Identifier: MIT
// `granflow analyze [NAME] DIR`: the papers' statistics of a run (SPEC 1.6),
// as CSV files, plots and headline numbers in DIR/analysis/.
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "granflow/analysis.h"
#include "granflow/dem.h"

static void gf_analyze_list(FILE *f)
{
    size_t n;
    const gf_measure_def *d = gf_measures(&n);
    fprintf(f, "measurements:\n");
    for (size_t k = 0; k < n; k++) fprintf(f, "  %-12s %s\n", d[k].name, d[k].what);
}

static int gf_analyze_usage(const char *msg, const char *arg)
{
    fprintf(stderr, "granflow analyze: error: %s%s%s\n", msg, arg ? " " : "", arg ? arg : "");
    fprintf(stderr, "usage: granflow analyze [NAME] DIR [--set key=value]... [--timestep DT] [--config INI] [-o OUTDIR] [--no-plots] [--list]\n");
    return GF_EXIT_USAGE;
}

/// A `section.key` of the run's configuration (a DEM run's container, its
/// atom types), rather than an analysis option.
static bool gf_analyze_is_config_key(const char *kv)
{
    gf_config c = gf_config_default();
    return gf_config_set(&c, kv, "--set") == GF_OK;
}

int gf_cmd_analyze(int argc, char **argv)
{
    const char *sets[64];
    size_t nsets = 0;
    const char *config = NULL;
    gf_analysis_opts opts = gf_analysis_opts_default();
    opts.stop = gf_cli_catch_stop(); // polled while reading and measuring
    const char *pos[2] = {NULL, NULL};
    int npos = 0;
    const char *outdir = NULL;
    bool plots = true, quiet = false;
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "--list")) {
            gf_analyze_list(stdout);
            return GF_EXIT_OK;
        } else if (!strcmp(a, "--set") || !strcmp(a, "-s") || !strncmp(a, "--set=", 6)) {
            const char *kv = a[5] == '=' ? a + 6 : i + 1 < argc ? argv[++i] : NULL;
            if (!kv) return gf_analyze_usage("--set needs key=value", NULL);
            if (gf_analyze_is_config_key(kv)) { // container.width=..., packing.types=...: the run's config
                if (nsets == sizeof sets / sizeof sets[0]) return gf_analyze_usage("too many --set", NULL);
                sets[nsets++] = kv;
            } else if (gf_analysis_opts_set(&opts, kv) != GF_OK) {
                return gf_cli_fail("analyze", GF_ERR_PARAM);
            }
        } else if (!strcmp(a, "--timestep") || !strcmp(a, "--config")) {
            if (i + 1 >= argc) return gf_analyze_usage(a, "needs a value");
            const char *v = argv[++i];
            if (a[2] == 'c') {
                config = v;
            } else {
                char dt[128];
                snprintf(dt, sizeof dt, "dump.dt=%s", v);
                if (gf_analysis_opts_set(&opts, dt) != GF_OK) return gf_cli_fail("analyze", GF_ERR_PARAM);
            }
        } else if (!strcmp(a, "-o") || !strcmp(a, "--output")) {
            if (i + 1 >= argc) return gf_analyze_usage("-o needs a directory", NULL);
            outdir = argv[++i];
        } else if (!strcmp(a, "--no-plots")) {
            plots = false;
        } else if (!strcmp(a, "-q") || !strcmp(a, "--quiet")) {
            quiet = true;
        } else if (a[0] == '-' && a[1]) {
            return gf_analyze_usage("unknown option", a);
        } else if (npos < 2) {
            pos[npos++] = a;
        } else {
            return gf_analyze_usage("unexpected argument", a);
        }
    }
    if (npos == 0) return gf_analyze_usage("which run? give its directory (or a LAMMPS dump)", NULL);
    const char *name = npos == 2 ? pos[0] : NULL;
    const char *dir = pos[npos - 1];
    if (name) {
        size_t n;
        const gf_measure_def *d = gf_measures(&n);
        size_t k = 0;
        while (k < n && strcmp(d[k].name, name)) k++;
        if (k == n) {
            gf_analyze_usage("unknown measurement", name);
            gf_analyze_list(stderr);
            return GF_EXIT_USAGE;
        }
    }
    if (!quiet) fprintf(stderr, "granflow analyze: reading %s...\n", dir);
    // Like gf_series_load, plus the container from --config/--set, packing.types,
    // and DEM particles below the base counted as exited (granflow dem, docs/dem.md);
    // the window: the steady flow of the outflow unless given (window.t0/t1).
    gf_dem_source src = {.config = config, .sets = sets, .nsets = nsets};
    gf_dem_analysis info;
    gf_status st = gf_dem_analyze(dir, &src, &opts, name, outdir, plots, &info);
    if (st == GF_ERR_INTERRUPTED)
        return gf_cli_interrupted("analyze", info.outdir[0] ? "summary.json not written (each CSV file there is whole)"
                                                            : "nothing written");
    if (st != GF_OK) return gf_cli_fail("analyze", st); // an unknown NAME was refused above, with the list
    if (!quiet) {
        char from[96] = "";
        if (info.exits_derived)
            snprintf(from, sizeof from, " (read off the snapshots, times within +- %.3g tau)", info.exit_resolution);
        fprintf(stderr, "granflow analyze: %zu snapshots from t = %g to %g tau, %zu exits%s; window %g..%g tau: %s\n",
                info.nframes, info.t_first, info.t_last, info.nexits, from, info.window.t0, info.window.t1,
                info.window.reason);
        fprintf(stderr, "granflow analyze: %s\n", info.container);
        fprintf(stderr, "granflow analyze: results in %s (summary.json, *.csv, *.png)\n", info.outdir);
    }
    return GF_EXIT_OK;
}
