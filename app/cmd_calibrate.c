// SPDX-License-Identifier: MIT
// `granflow calibrate DEM_DIR -o params.ini`: the five spot parameters fitted
// to a DEM run as the thesis does (Sec. 3.3), printed with their
// uncertainties and written as a config `granflow run` takes directly.
#define _XOPEN_SOURCE 700
#include <getopt.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"
#include "granflow/dem.h"
#include "granflow/defs.h"


static bool gf_demargs_is_config_key(const char *kv)
{
    gf_config c = gf_config_default();
    return gf_config_set(&c, kv, "--set") == GF_OK;
}

/// Parses [positional]... -o OUT --timestep DT --config INI --set k=v -q, and
/// compare's --no-plots, calibrate's --no-refine, with getopt_long.
int gf_demargs_parse(const char *cmd, int argc, char **argv, gf_demargs *a)
{
    memset(a, 0, sizeof *a);
    a->plots = true;
    a->refine = true;
    a->opts = gf_analysis_opts_default();
    enum { OPT_TIMESTEP = 256, OPT_CONFIG, OPT_NO_PLOTS, OPT_NO_REFINE, OPT_RUNS };
    bool calibrate = !strcmp(cmd, "calibrate");
    const struct option longs[] = {
        {"output", required_argument, NULL, 'o'},
        {"set", required_argument, NULL, 's'},
        {"timestep", required_argument, NULL, OPT_TIMESTEP},
        {"config", required_argument, NULL, OPT_CONFIG},
        {"quiet", no_argument, NULL, 'q'},
        {"help", no_argument, NULL, 'h'},
        {calibrate ? "no-refine" : "no-plots", no_argument, NULL, calibrate ? OPT_NO_REFINE : OPT_NO_PLOTS},
        {calibrate ? "runs" : NULL, required_argument, NULL, OPT_RUNS}, // compare: the end
        {0},
    };
    optind = 0;
    opterr = 0;
    int c;
    while ((c = getopt_long(argc, argv, ":o:s:qh", longs, NULL)) != -1) {
        switch (c) {
        case 'h': return gf_cli_help(cmd);
        case 'o': a->out = optarg; break;
        case OPT_CONFIG: a->config = optarg; break;
        case OPT_TIMESTEP: {
            char kv[128];
            snprintf(kv, sizeof kv, "dump.dt=%s", optarg);
            if (gf_analysis_opts_set(&a->opts, kv) != GF_OK) return gf_cli_fail(cmd, GF_ERR_PARAM);
            break;
        }
        case 's':
            if (gf_demargs_is_config_key(optarg)) {
                if (a->nsets == 64) {
                    fprintf(stderr, "granflow %s: error: too many --set\n", cmd);
                    return GF_EXIT_USAGE;
                }
                a->sets[a->nsets++] = optarg;
            } else if (gf_analysis_opts_set(&a->opts, optarg) != GF_OK) {
                return gf_cli_fail(cmd, GF_ERR_PARAM);
            }
            break;
        case 'q': a->quiet = true; break;
        case OPT_NO_PLOTS: a->plots = false; break;
        case OPT_NO_REFINE: a->refine = false; break;
        case OPT_RUNS: {
            char *end = NULL;
            long v = strtol(optarg, &end, 10);
            if (!*optarg || *end || v < 1 || v > 100) {
                fprintf(stderr, "granflow %s: error: --runs %s: a whole number of spot runs from 1 to 100\n", cmd,
                        optarg);
                return GF_EXIT_USAGE;
            }
            a->runs = (int)v;
            break;
        }
        default: return gf_cli_getopt_error(cmd, c, argv);
        }
    }
    for (int i = optind; i < argc; i++) {
        if (a->npos == 4) {
            fprintf(stderr, "granflow %s: error: unexpected argument '%s' (see granflow %s --help)\n", cmd, argv[i], cmd);
            return GF_EXIT_USAGE;
        }
        a->pos[a->npos++] = argv[i];
    }
    return GF_CLI_GO;
}

gf_status gf_demargs_load(const char *cmd, const gf_demargs *a, const char *path, bool dem, gf_series *s)
{
    gf_dem_source src = {.dump_dt = a->opts.dump_dt, .config = dem ? a->config : NULL,
                         .sets = dem ? a->sets : NULL, .nsets = dem ? a->nsets : 0, .stop = a->opts.stop};
    gf_dem_load_report rep;
    if (!a->quiet) fprintf(stderr, "granflow %s: reading %s...\n", cmd, path);
    gf_status st = gf_dem_series_load(path, &src, s, &rep);
    if (st != GF_OK || a->quiet) return st;
    fprintf(stderr,
            "granflow %s: %zu snapshots, t = %g..%g tau, %zu particles at first (%zu particle-frames below the "
            "base counted as exited, %zu of other atom types dropped); %s\n",
            cmd, s->nframes, s->nframes ? s->frames[0].time : 0.0, s->nframes ? s->frames[s->nframes - 1].time : 0.0,
            s->n_initial, rep.below_base, rep.other_types, rep.container);
    return st;
}

static void gf_calibrate_progress(void *ctx, int iter, int max_iter, const gf_config *c, const gf_dem_flowstats *dem,
                                  const gf_dem_flowstats *spot, bool match)
{
    (void)ctx;
    gf_spot_params sp;
    gf_config_spot_params(c, &sp);
    double worst = 0.0;
    int unsteady = 0, seen = 0;
    for (size_t z = 0; z < dem->nz && z < spot->nz; z++)
        if (gf_dem_flowstats_measured(dem->var[z], GF_DEM_VAR_TOL)) {
            double e = fabs(spot->var[z].value / dem->var[z].value - 1.0);
            if (!isfinite(e)) {
                unsteady++;
                continue;
            }
            seen++;
            worst = fmax(worst, e);
        }
    char vs[96];
    if (seen)
        snprintf(vs, sizeof vs, "worst measured Var %.1f%% off", 100.0 * worst);
    else
        snprintf(vs, sizeof vs, "no Var measured");
    if (unsteady)
        snprintf(vs + strlen(vs), sizeof vs - strlen(vs), " (%d height%s not steady)", unsteady,
                 unsteady == 1 ? "" : "s");
    fprintf(stderr,
            "[refine] run %d/%d: r_s %.3g, step_xy %.3g, w %.4g, lambda %.4g, mu %.4g -> Q %.4g (DEM %.4g, %+.1f%%), "
            "%s%s\n",
            iter, max_iter, sp.radius, sp.step_xy, sp.w, sp.insertion_rate, sp.move_rate,
            spot->flow.value, dem->flow.value, 100.0 * (spot->flow.value / dem->flow.value - 1.0), vs,
            match ? ": matched" : "");
}

int gf_cmd_calibrate(int argc, char **argv)
{
    gf_demargs a;
    int rc = gf_demargs_parse("calibrate", argc, argv, &a);
    if (rc != GF_CLI_GO) return rc;
    bool refine = a.refine;
    if (a.npos != 1 || !a.out) {
        fprintf(stderr, "granflow calibrate: error: give one DEM run and -o PARAMS.ini\n"
                        "usage: granflow calibrate DEM_DIR [--timestep DT] [--config INI] [--set key=value]... "
                        "[--no-refine] -o PARAMS.ini\n");
        return GF_EXIT_USAGE;
    }
    a.opts.stop = gf_cli_catch_stop(); // reading, measuring, packing, the spot runs of the refinement
    gf_series s;
    gf_status st = gf_demargs_load("calibrate", &a, a.pos[0], true, &s);
    if (st == GF_ERR_INTERRUPTED) return gf_cli_interrupted("calibrate", "nothing written");
    if (st != GF_OK) return gf_cli_fail("calibrate", st);
    gf_steady win;
    st = gf_dem_window(&s, &a.opts, &win);
    if (st != GF_OK) {
        gf_series_free(&s);
        return gf_cli_fail("calibrate", st);
    }
    if (!a.quiet) fprintf(stderr, "granflow calibrate: window %g..%g tau: %s\n", win.t0, win.t1, win.reason);
    gf_analysis_opts o;
    gf_dem_calibration_opts(&s, &a.opts, &o);
    if (!a.quiet) {
        fprintf(stderr, "granflow calibrate: regions: velocity heights %g..%g, correlation %g x %g at z = %g, slice "
                        "%g < z < %g\n",
                o.vel_heights[0], o.vel_heights[o.vel_nheights - 1], o.corr_size, o.corr_size, o.corr_zc, o.dens_z0,
                o.dens_z1);
    }
    gf_dem_calibration c;
    st = gf_dem_calibrate(&s, &o, &s.cfg, &c);
    if (st == GF_OK || (st != GF_ERR_INTERRUPTED && isfinite(c.flow_rate.value))) gf_dem_calibration_print(&c, stdout);
    gf_config cfg = s.cfg;
    // The spot runs start from the DEM's first snapshot, snapshots as often.
    double span = s.frames[s.nframes - 1].time - s.frames[0].time;
    char num[64];
    gf_status set = GF_OK;
    if (span > 0 && snprintf(num, sizeof num, "%.17g", span) > 0) set = gf_config_set_key(&cfg, "run.duration", num);
    if (set == GF_OK && s.nframes > 1 && snprintf(num, sizeof num, "%.17g", s.frames[1].time - s.frames[0].time) > 0)
        set = gf_config_set_key(&cfg, "output.snapshot_interval", num);
    if (st == GF_OK) st = set;
    if (st == GF_OK) st = gf_dem_calibration_apply(&c, &cfg);
    // params.ini starts from the DEM's first snapshot, written beside it; the
    // refinement starts from that file read back as `granflow run` reads it,
    // so that the run of params.ini repeats the refinement's last run.
    char pk[4096];
    snprintf(pk, sizeof pk, "%s.packing.dump", a.out);
    if (st == GF_OK) st = gf_packing_write(&s.frames[0].pk, pk, GF_FORMAT_LAMMPS, &cfg);
    if (st == GF_OK) {
        char abs[PATH_MAX];
        const char *use = realpath(pk, abs) ? abs : pk;
        char kv[PATH_MAX + 32];
        snprintf(kv, sizeof kv, "packing.file=%s", use);
        st = gf_config_set(&cfg, kv, "calibrate");
        if (st == GF_OK) st = gf_config_set(&cfg, "packing.types=", "calibrate");
    }
    gf_packing start = {0};
    if (st == GF_OK && refine) st = gf_packing_for_config(&cfg, &(gf_packing_opts){.stop = a.opts.stop}, &start, NULL);
    if (st == GF_OK && refine) {
        if (!a.quiet)
            fprintf(stderr,
                    "granflow calibrate: closed-loop refinement: spot runs from the DEM's first snapshot to t = %g "
                    "tau, until the flow rate is within %.0f%% and Var(z) within %.0f%% at every height\n",
                    win.t1, 100.0 * GF_DEM_FLOW_TOL, 100.0 * GF_DEM_VAR_TOL);
        gf_dem_refine_result res;
        gf_dem_refine_opts ro = {.progress = a.quiet ? NULL : gf_calibrate_progress, .stop = a.opts.stop,
                                 .start = &start, .max_iter = a.runs};
        st = gf_dem_refine(&s, &o, &cfg, &ro, &res);
        if (st == GF_OK) {
            printf("DEM vs spot, first guess (thesis relations):\n");
            gf_dem_flowstats_table(&res.dem, &res.first, GF_DEM_FLOW_TOL, GF_DEM_VAR_TOL, stdout);
            printf("DEM vs spot, refined (%d spot run%s, %s):\n", res.runs, res.runs == 1 ? "" : "s",
                   res.matched ? "both tolerances met" : "tolerances NOT met: the closest run kept");
            gf_dem_flowstats_table(&res.dem, &res.last, GF_DEM_FLOW_TOL, GF_DEM_VAR_TOL, stdout);
            gf_spot_params sp;
            gf_config_spot_params(&cfg, &sp);
            printf("refined parameters: spot.radius = %.4g, spot.step_xy = %.4g, spot.w = %.4g, "
                   "spot.insertion_rate = %.4g, spot.move_rate = %.4g\n",
                   sp.radius, sp.step_xy, sp.w, sp.insertion_rate, sp.move_rate);
            gf_dem_refine_print(&res, stdout);
        }
    }
    gf_packing_free(&start);
    if (st == GF_OK) st = gf_config_save(&cfg, a.out);
    gf_series_free(&s);
    if (st == GF_ERR_INTERRUPTED) {
        unlink(pk); // no params.ini: its initial packing goes too
        return gf_cli_interrupted("calibrate", "nothing written");
    }
    if (st != GF_OK) return gf_cli_fail("calibrate", st);
    if (!a.quiet)
        fprintf(stderr, "granflow calibrate: wrote %s (and its initial packing %s); run it with granflow run %s -o DIR\n",
                a.out, pk, a.out);
    return GF_EXIT_OK;
}
