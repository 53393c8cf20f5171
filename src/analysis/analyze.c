// SPDX-License-Identifier: MIT
// The analysis driver: runs measurements on a series and writes their CSV
// files, gnuplot plots and headline numbers (analysis/summary.json).
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include "core/alloc.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/fs.h"
#include "core/gnuplot.h"
#include "core/stop.h"
#include "analysis/summary.h"
#include "granflow/analysis.h"
#include "granflow/defs.h"

static const gf_measure_def gf_measure_table[] = {
    {"outflow", "particles exited vs time, steady flow rate", gf_measure_outflow},
    {"velocity", "mean velocity field, v_z(x) profiles with Gaussian fits, Var(z), v_z(y)", gf_measure_velocity},
    {"diffusion", "particle diffusion length b_p = Var(dx)/(2 dz)", gf_measure_diffusion},
    {"correlation", "spatial correlation of velocity fluctuations, exponential fit", gf_measure_correlation},
    {"gr", "pair correlation g(r) and bond angles g3(theta)", gf_measure_gr},
    {"voronoi", "local packing fraction from Voronoi cells, 2.2 d-averaged field", gf_measure_voronoi},
    {"density", "particles in the slice 50 < z < 70 over time", gf_measure_density},
    {"surface", "free-surface angle by regression, over time", gf_measure_surface},
    {"badness", "packing badness B over a region and window", gf_measure_badness},
    {"rtd", "residence-time distribution by initial layer", gf_measure_rtd},
    {"zones", "reactor outputs: residence times per pass and radial zone, flow shares, mixing matrix, streamlines, v_z(r)",
     gf_measure_zones},
};

const gf_measure_def *gf_measures(size_t *n)
{
    *n = sizeof gf_measure_table / sizeof gf_measure_table[0];
    return gf_measure_table;
}

static gf_status gf_write_plot(const char *outdir, const char *name, const gf_measure_out *out, int *gnuplot_state)
{
    char path[4096], tmp[4096], gp[128];
    snprintf(gp, sizeof gp, "%s.gp", name);
    snprintf(path, sizeof path, "%s/%s", outdir, gp);
    FILE *f;
    gf_status st = gf_atomic_open(path, tmp, sizeof tmp, &f);
    if (st != GF_OK) return st;
    fprintf(f, "# Draws %s.png from the CSV files beside it: gnuplot %s\n"
               "set terminal pngcairo size 1100,800 font 'sans,11'\n"
               "set output '%s.png'\n"
               "set datafile separator ','\n"
               "set grid\n",
            name, gp, name);
    fputs(out->gnuplot, f);
    fputs("\nunset output\n", f);
    if ((st = gf_atomic_commit(f, tmp, path)) != GF_OK) return st;
    if (*gnuplot_state == 1) return GF_OK; // known missing: said once
    char why[512];
    int r = gf_gnuplot_run(outdir, gp, why, sizeof why);
    if (r == 1) {
        gf_warn("gnuplot not found, plots not drawn (scripts/deps.sh installs it; the .gp scripts are in %s)",
                outdir);
        *gnuplot_state = 1;
    } else if (r < 0) {
        return gf_error_set(GF_ERR_IO, "gnuplot failed on %s: %s", path, why);
    }
    return GF_OK;
}

// The measurements read a drain: particles leave and none arrive. A series
// whose count grows (frames of two runs, a pour) would give negative flow
// rates and wrong fields, so it is refused. A recirculating run
// (run.recirculate = on) puts the particles back: a DEM's snapshot can catch
// some below the exit plane (dropped from the frame as exited) before
// LAMMPS puts them back on top, so its count dips and grows again.
static gf_status gf_analyze_check_drain(const gf_series *s)
{
    gf_rundir_defs rd;
    gf_config_rundir_defs(&s->cfg, &rd);
    if (rd.recirculate) return GF_OK;
    for (size_t f = 1; f < s->nframes; f++)
        if (s->frames[f].pk.n > s->frames[f - 1].pk.n)
            return gf_error_set(GF_ERR_FORMAT,
                                "the particle count grows from %zu at t = %.6g tau to %zu at t = %.6g tau: "
                                "a draining silo only loses particles (frames of two runs mixed?)",
                                s->frames[f - 1].pk.n, s->frames[f - 1].time, s->frames[f].pk.n, s->frames[f].time);
    return GF_OK;
}

gf_status gf_analyze(const gf_series *s, const gf_analysis_opts *o, const char *name, const char *outdir, bool plots)
{
    gf_status st0 = gf_analyze_check_drain(s);
    if (st0 != GF_OK) return st0;
    size_t nm;
    const gf_measure_def *defs = gf_measures(&nm);
    const gf_measure_def *only = NULL;
    if (name) {
        for (size_t k = 0; k < nm; k++)
            if (!strcmp(defs[k].name, name)) only = &defs[k];
        if (!only) return gf_error_set(GF_ERR_PARAM, "unknown measurement '%s'", name);
    }
    gf_status st = gf_fs_mkdirs(outdir);
    if (st != GF_OK) return st;
    char path[4096];
    snprintf(path, sizeof path, "%s/summary.json", outdir);
    gf_summary *sum = GF_NEW(gf_summary, 1);
    if (!sum) return gf_error_set(GF_ERR_NOMEM, "out of memory");
    // One measurement again: keep the others' numbers. A summary.json that
    // cannot be read stops here rather than be overwritten without them.
    st = only ? gf_summary_read(sum, path) : GF_OK;
    if (st != GF_OK) {
        GF_DELETE(sum, 1);
        return st;
    }
    double t0, t1;
    gf_analysis_window(o, s, &t0, &t1);
    gf_summary_num(sum, "frames", (double)s->nframes);
    gf_summary_num(sum, "window_t0", t0);
    gf_summary_num(sum, "window_t1", t1);
    int gnuplot_state = 0;
    gf_status first_err = GF_OK;
    for (size_t k = 0; k < nm; k++) {
        const gf_measure_def *d = &defs[k];
        if (only && d != only) continue;
        gf_measure_out out = {0};
        char note[GF_TABLE_NAME + 16];
        snprintf(note, sizeof note, "skipped_%s", d->name);
        st = gf_stop_check(o->stop, "analysis");
        if (st == GF_OK) st = d->run(s, o, &out);
        for (size_t t = 0; st == GF_OK && t < out.ntables; t++) {
            snprintf(path, sizeof path, "%s/%s.csv", outdir, out.tables[t].name);
            st = gf_table_write_csv(&out.tables[t], path);
        }
        if (st == GF_OK && plots && out.gnuplot) st = gf_write_plot(outdir, d->name, &out, &gnuplot_state);
        if (st == GF_OK) {
            for (size_t v = 0; v < out.nvalues; v++) gf_summary_num(sum, out.values[v].key, out.values[v].value);
            gf_summary_item *it = gf_summary_slot(sum, note);
            if (it) it->key[0] = '\0'; // a previous skip no longer holds
        } else if (only || st == GF_ERR_INTERRUPTED) {
            first_err = st; // interrupted: summary.json is not written (the CSVs so far are whole files)
        } else {
            // One measurement that cannot be made (no exits, too few frames)
            // does not stop the others; the reason goes into summary.json.
            gf_warn("%s skipped: %s", d->name, gf_last_error());
            gf_summary_text(sum, note, gf_last_error());
        }
        gf_measure_free(&out);
        if (first_err != GF_OK) break;
    }
    // Drop the entries blanked above.
    size_t w = 0;
    for (size_t k = 0; k < sum->n; k++)
        if (sum->item[k].key[0]) sum->item[w++] = sum->item[k];
    sum->n = w;
    if (first_err == GF_OK) {
        snprintf(path, sizeof path, "%s/summary.json", outdir);
        first_err = gf_summary_write(sum, path);
    }
    GF_DELETE(sum, 1);
    return first_err;
}
