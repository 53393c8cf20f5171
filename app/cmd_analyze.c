// SPDX-License-Identifier: MIT
// `granflow analyze [NAME] DIR`: the papers' statistics of a run (SPEC 1.6),
// as CSV files, plots and headline numbers in DIR/analysis/.
#include <getopt.h>
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
    fprintf(stderr, "usage: granflow analyze [NAME] DIR [--set key=value]... [--timestep DT] [--config INI] [-o OUTDIR] "
                    "[--no-plots] [--list] (see granflow analyze --help)\n");
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
    enum { OPT_TIMESTEP = 256, OPT_CONFIG, OPT_NO_PLOTS, OPT_LIST };
    static const struct option longs[] = {
        {"set", required_argument, NULL, 's'},          {"timestep", required_argument, NULL, OPT_TIMESTEP},
        {"config", required_argument, NULL, OPT_CONFIG}, {"output", required_argument, NULL, 'o'},
        {"no-plots", no_argument, NULL, OPT_NO_PLOTS},   {"list", no_argument, NULL, OPT_LIST},
        {"quiet", no_argument, NULL, 'q'},              {"help", no_argument, NULL, 'h'},
        {0},
    };
    optind = 0;
    opterr = 0;
    int c;
    while ((c = getopt_long(argc, argv, ":s:o:qh", longs, NULL)) != -1) {
        switch (c) {
        case 'h': return gf_cli_help("analyze");
        case OPT_LIST: gf_analyze_list(stdout); return GF_EXIT_OK;
        case 's':
            if (gf_analyze_is_config_key(optarg)) { // container.width=..., packing.types=...: the run's config
                if (nsets == sizeof sets / sizeof sets[0]) return gf_analyze_usage("too many --set", NULL);
                sets[nsets++] = optarg;
            } else if (gf_analysis_opts_set(&opts, optarg) != GF_OK) {
                return gf_cli_fail("analyze", GF_ERR_PARAM);
            }
            break;
        case OPT_CONFIG: config = optarg; break;
        case OPT_TIMESTEP: {
            char dt[128];
            snprintf(dt, sizeof dt, "dump.dt=%s", optarg);
            if (gf_analysis_opts_set(&opts, dt) != GF_OK) return gf_cli_fail("analyze", GF_ERR_PARAM);
            break;
        }
        case 'o': outdir = optarg; break;
        case OPT_NO_PLOTS: plots = false; break;
        case 'q': quiet = true; break;
        default: return gf_cli_getopt_error("analyze", c, argv);
        }
    }
    for (int i = optind; i < argc; i++) {
        if (npos == 2) return gf_analyze_usage("unexpected argument", argv[i]);
        pos[npos++] = argv[i];
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
