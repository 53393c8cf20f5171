// SPDX-License-Identifier: MIT
// `granflow analyze [NAME] DIR`: the papers' statistics of a run (SPEC 1.6),
// as CSV files, plots and headline numbers in DIR/analysis/.
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "granflow/analysis.h"

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
    fprintf(stderr, "usage: granflow analyze [NAME] DIR [--set key=value]... [-o OUTDIR] [--no-plots] [--list]\n");
    return GF_EXIT_USAGE;
}

int gf_cmd_analyze(int argc, char **argv)
{
    gf_analysis_opts opts;
    gf_analysis_opts_default(&opts);
    const char *pos[2] = {NULL, NULL};
    int npos = 0;
    const char *outdir = NULL;
    bool plots = true, quiet = false;
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "--list")) {
            gf_analyze_list(stdout);
            return GF_EXIT_OK;
        } else if (!strcmp(a, "--set") || !strcmp(a, "-s")) {
            if (i + 1 >= argc) return gf_analyze_usage("--set needs key=value", NULL);
            if (gf_analysis_opts_set(&opts, argv[++i]) != GF_OK) return gf_cli_fail("analyze", GF_ERR_PARAM);
        } else if (!strncmp(a, "--set=", 6)) {
            if (gf_analysis_opts_set(&opts, a + 6) != GF_OK) return gf_cli_fail("analyze", GF_ERR_PARAM);
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
    char outbuf[4096];
    if (!outdir) {
        snprintf(outbuf, sizeof outbuf, "%s/analysis", dir);
        outdir = outbuf;
    }
    gf_series s = {0};
    if (!quiet) fprintf(stderr, "granflow analyze: reading %s...\n", dir);
    gf_status st = gf_series_load(dir, opts.dump_dt, &s);
    if (st != GF_OK) return gf_cli_fail("analyze", st);
    if (!quiet) {
        double t0, t1;
        gf_analysis_window(&opts, &s, &t0, &t1);
        fprintf(stderr, "granflow analyze: %zu snapshots from t = %g to %g tau, %zu exits; window %g..%g tau\n",
                s.nframes, s.nframes ? s.frames[0].time : 0.0, s.nframes ? s.frames[s.nframes - 1].time : 0.0,
                s.nexits, t0, t1);
    }
    st = gf_analyze(&s, &opts, name, outdir, plots);
    gf_series_free(&s);
    if (st != GF_OK) return gf_cli_fail("analyze", st);
    if (!quiet) fprintf(stderr, "granflow analyze: results in %s (summary.json, *.csv, *.png)\n", outdir);
    return GF_EXIT_OK;
}
