// SPDX-License-Identifier: MIT
// A DEM run and a spot run side by side (thesis Sec. 3.5): the same
// measurements on both (flow rate, velocity profiles and their spreading,
// diffusion, velocity correlation, g(r) and g3, density drop, residence
// times per initial layer up to the shorter run's length), their tables
// as dem_NAME.csv / spot_NAME.csv, one figure overlaying them, central-slice
// pictures at the same times, and summary.md with the differences.
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/fs.h"
#include "core/gnuplot.h"
#include "core/stop.h"
#include "granflow/defs.h"
#include "granflow/dem.h"
#include "granflow/render.h"

/// Residence times when the series has exits (gf_dem_series_load reads them
/// off the snapshots of dumps without exits.csv); none, not an error, else.
static gf_status gf_cmp_rtd(const gf_series *s, const gf_analysis_opts *o, gf_measure_out *out)
{
    return s->has_exits ? gf_measure_rtd(s, o, out) : GF_OK;
}

/// The compared measurements, in figure order.
static const struct {
    const char *name;
    gf_status (*run)(const gf_series *, const gf_analysis_opts *, gf_measure_out *);
} gf_cmp_measures[] = {
    {"outflow", gf_measure_outflow},         {"velocity", gf_measure_velocity}, {"diffusion", gf_measure_diffusion},
    {"correlation", gf_measure_correlation}, {"gr", gf_measure_gr},             {"density", gf_measure_density},
    {"rtd", gf_cmp_rtd},
};
#define GF_CMP_N (sizeof gf_cmp_measures / sizeof gf_cmp_measures[0])

/// Headline values compared in summary.md: key, what (followed by the
/// profile's name, gf_velocity_profile_name, when `of_profile`), unit, the
/// papers' DEM value.
static const struct {
    const char *key, *what, *unit, *papers;
    bool of_profile;
} gf_cmp_keys[] = {
    {"flow_rate", "flow rate Q", "1/tau", "131.1 (2009 paper)", false},
    {"velocity_variance_slope", "spreading d Var / dz of", "d", "2.28 (thesis)", true},
    {"velocity_variance_intercept", "its intercept", "d^2", "1.60 (thesis)", false},
    {"diffusion_length", "particle diffusion length b_p", "d", "2.86e-3 (thesis)", false},
    {"correlation_length", "velocity correlation length beta", "d", "1.87 (thesis)", false},
    {"gr_first_peak_r", "first peak of g(r)", "d", "1", false},
    {"coordination", "neighbours closer than the g3 bond", "", "-", false},
    {"density_initial", "particles in the slice at rest", "", "9400 (thesis)", false},
    {"density_steady", "particles in the slice in flow", "", "8850 (thesis)", false},
    {"rtd_mean", "mean residence time of the first snapshot's particles", "tau", "-", false},
    {"rtd_median", "median residence time", "tau", "-", false},
};
#define GF_CMP_K (sizeof gf_cmp_keys / sizeof gf_cmp_keys[0])

static double gf_cmp_value(const gf_measure_out *m, size_t n, const char *key)
{
    for (size_t k = 0; k < n; k++)
        for (size_t v = 0; v < m[k].nvalues; v++)
            if (!strcmp(m[k].values[v].key, key)) return m[k].values[v].value;
    return NAN;
}

static const gf_table *gf_cmp_table(const gf_measure_out *m, size_t n, const char *name)
{
    for (size_t k = 0; k < n; k++)
        for (size_t t = 0; t < m[k].ntables; t++)
            if (!strcmp(m[k].tables[t].name, name)) return &m[k].tables[t];
    return NULL;
}

/// sqrt(sum (b - a)^2 dx) of two curves on the same grid (column 1 against column 0).
static double gf_cmp_l2(const gf_table *a, const gf_table *b)
{
    if (!a || !b || a->nrow != b->nrow || a->nrow < 2) return NAN;
    double s = 0.0, dx = a->v[a->ncol] - a->v[0];
    for (size_t r = 0; r < a->nrow; r++) {
        double d = b->v[r * b->ncol + 1] - a->v[r * a->ncol + 1];
        if (isfinite(d)) s += d * d * dx;
    }
    return sqrt(s);
}

// The profile and Var panels also draw the line 0: a height with no steady
// frames has no profile and no Var, and a panel whose every point is
// undefined would stop gnuplot ("x range is invalid").
static gf_status gf_cmp_figure(const char *outdir, const gf_config *cfg, const gf_analysis_opts *o, bool plots)
{
    const char *profile = gf_velocity_profile_name(cfg);
    char path[GF_PATH_MAX + 32], tmp[GF_PATH_MAX + 48];
    snprintf(path, sizeof path, "%s/compare.gp", outdir);
    FILE *f;
    gf_status st = gf_atomic_open(path, tmp, sizeof tmp, &f);
    if (st != GF_OK) return st;
    fprintf(f,
            "# Draws compare.png from the CSV files beside it: gnuplot compare.gp\n"
            "set terminal pngcairo size 1800,950 font 'sans,10'\n"
            "set output 'compare.png'\n"
            "set datafile separator ','\n"
            "set grid\nset key font ',8'\n"
            "D = 'lc rgb \"#c0392b\"'\nS = 'lc rgb \"#2471a3\"'\n"
            "set multiplot layout 2,4 title 'DEM (red) and spot model (blue)'\n"
            "set title 'particles exited'\nset xlabel 't (tau)'\nset ylabel 'exited'\nset key top left\n"
            "plot 'dem_outflow.csv' skip 1 u 1:2 w steps lw 2 @D t 'DEM', "
            "'spot_outflow.csv' skip 1 u 1:2 w steps lw 2 @S t 'spot'\n"
            "set title '%s at z = %g .. %g'\nset xlabel '%s (d)'\nset ylabel 'v_z (d/tau)'\nset key bottom right\n"
            "plot 'dem_velocity_profiles.csv' skip 1 u 2:3 w p pt 7 ps 0.3 @D t 'DEM', "
            "'spot_velocity_profiles.csv' skip 1 u 2:3 w p pt 6 ps 0.3 @S t 'spot', 0 w l lc 'grey' notitle\n"
            "set title 'Gaussian variance of %s'\nset xlabel 'z (d)'\nset ylabel 'Var (d^2)'\nset key top left\n"
            "plot 'dem_velocity_variance.csv' skip 1 u 1:2 w lp pt 7 @D t 'DEM', "
            "'spot_velocity_variance.csv' skip 1 u 1:2 w lp pt 6 @S t 'spot', 0 w l lc 'grey' notitle\n"
            "set title 'diffusion'\nset xlabel 'mean drop |dz| (d)'\nset ylabel 'Var(dx) (d^2)'\n"
            "plot 'dem_diffusion.csv' skip 1 u 2:3 w lp pt 7 @D t 'DEM', "
            "'spot_diffusion.csv' skip 1 u 2:3 w lp pt 6 @S t 'spot'\n"
            "set title 'velocity correlation C(r)'\nset xlabel 'r (d)'\nset ylabel 'C'\nset key top right\n"
            "plot 'dem_correlation.csv' skip 1 u 1:2 w l lw 2 @D t 'DEM', "
            "'spot_correlation.csv' skip 1 u 1:2 w l lw 2 @S t 'spot'\n"
            "set title 'g(r)'\nset xlabel 'r (d)'\nset ylabel 'g'\n"
            "plot 'dem_gr.csv' skip 1 u 1:2 w l lw 2 @D t 'DEM', 'spot_gr.csv' skip 1 u 1:2 w l lw 2 @S t 'spot'\n"
            "set title 'bond angles g_3'\nset xlabel 'theta (degrees)'\nset ylabel 'g_3'\n"
            "plot 'dem_g3.csv' skip 1 u 1:2 w l lw 2 @D t 'DEM', 'spot_g3.csv' skip 1 u 1:2 w l lw 2 @S t 'spot'\n"
            "set title 'particles in %g < z < %g'\nset xlabel 't (tau)'\nset ylabel 'count'\nset key bottom left\n"
            "plot 'dem_density.csv' skip 1 u 1:2 w lp pt 7 @D t 'DEM', "
            "'spot_density.csv' skip 1 u 1:2 w lp pt 6 @S t 'spot'\n"
            "unset multiplot\nunset output\n",
            profile, o->vel_heights[0], o->vel_heights[o->vel_nheights ? o->vel_nheights - 1 : 0],
            gf_velocity_radial(cfg) ? "r" : "x", profile, o->dens_z0, o->dens_z1);
    if ((st = gf_atomic_commit(f, tmp, path)) != GF_OK) return st;
    if (!plots) return GF_OK;
    char why[512];
    int r = gf_gnuplot_run(outdir, "compare.gp", why, sizeof why);
    if (r < 0) return gf_error_set(GF_ERR_IO, "gnuplot failed on %s: %s", path, why);
    return GF_OK; // r == 1: no gnuplot; the script is there
}

/// The frame of `s` nearest to time t.
static const gf_frame *gf_cmp_at(const gf_series *s, double t)
{
    const gf_frame *best = &s->frames[0];
    for (size_t k = 1; k < s->nframes; k++)
        if (fabs(s->frames[k].time - t) < fabs(best->time - t)) best = &s->frames[k];
    return best;
}

/// Contact sheets of the central slice of both runs at the same 4 times.
static gf_status gf_cmp_slices(const gf_series *dem, const gf_series *spot, const char *outdir, double times[4])
{
    double T = fmin(dem->frames[dem->nframes - 1].time, spot->frames[spot->nframes - 1].time);
    double t0 = fmax(dem->frames[0].time, spot->frames[0].time);
    gf_frame fd[4], fs[4];
    double zmax = 0.0;
    for (int j = 0; j < 4; j++) {
        times[j] = t0 + (T - t0) * j / 3.0;
        fd[j] = *gf_cmp_at(dem, times[j]);
        fs[j] = *gf_cmp_at(spot, times[j]);
    }
    for (size_t i = 0; i < dem->frames[0].pk.n; i++) zmax = fmax(zmax, dem->frames[0].pk.z[i] + 0.5);
    for (size_t i = 0; i < spot->frames[0].pk.n; i++) zmax = fmax(zmax, spot->frames[0].pk.z[i] + 0.5);
    gf_render_opts ro = gf_render_opts_default();
    ro.zmax = zmax;
    gf_container_defs cd;
    gf_config_container_defs(&dem->cfg, &cd);
    ro.px_per_d = fmax(2.0, fmin(10.0, 1200.0 / (4.0 * (cd.width + 4.0))));
    char path[GF_PATH_MAX + 32];
    ro.title = "DEM";
    snprintf(path, sizeof path, "%s/slices_dem.png", outdir);
    gf_status st = gf_render_sheet(fd, 4, &dem->cfg, NULL, &ro, path);
    if (st != GF_OK) return st;
    ro.title = "spot model";
    snprintf(path, sizeof path, "%s/slices_spot.png", outdir);
    return gf_render_sheet(fs, 4, &spot->cfg, NULL, &ro, path);
}

static void gf_cmp_num(FILE *f, double v)
{
    if (isfinite(v)) fprintf(f, " %.5g |", v);
    else fprintf(f, " - |");
}

/// The frames row r of a velocity_variance table averaged: "t0-t1", or that
/// its height had no steady frames (not fitted).
static void gf_cmp_frames(FILE *f, const gf_table *t, size_t r)
{
    const double *row = t->v + r * t->ncol;
    if (t->ncol < 7) fprintf(f, " - |");
    else if (row[6] == 0.0) fprintf(f, " no steady frames |");
    else fprintf(f, " %.4g-%.4g |", row[4], row[5]);
}

static gf_status gf_cmp_summary(const char *outdir, const gf_series *dem, const gf_series *spot,
                                const gf_measure_out *md, const gf_measure_out *ms, const gf_analysis_opts *o,
                                const double times[4])
{
    char path[GF_PATH_MAX + 32], tmp[GF_PATH_MAX + 48];
    FILE *f, *c;
    snprintf(path, sizeof path, "%s/summary.csv", outdir);
    gf_status st = gf_atomic_open(path, tmp, sizeof tmp, &c);
    if (st != GF_OK) return st;
    fprintf(c, "key,dem,spot,difference,relative_difference\n");
    for (size_t k = 0; k < GF_CMP_K; k++) {
        double a = gf_cmp_value(md, GF_CMP_N, gf_cmp_keys[k].key), b = gf_cmp_value(ms, GF_CMP_N, gf_cmp_keys[k].key);
        fprintf(c, "%s,%.10g,%.10g,%.10g,%.10g\n", gf_cmp_keys[k].key, a, b, b - a, (b - a) / fabs(a));
    }
    if ((st = gf_atomic_commit(c, tmp, path)) != GF_OK) return st;

    snprintf(path, sizeof path, "%s/summary.md", outdir);
    if ((st = gf_atomic_open(path, tmp, sizeof tmp, &f)) != GF_OK) return st;
    const char *profile = gf_velocity_profile_name(&dem->cfg);
    double t0d, t1d, t0s, t1s;
    gf_analysis_window(o, dem, &t0d, &t1d);
    gf_analysis_window(o, spot, &t0s, &t1s);
    gf_container_defs cd;
    gf_config_container_defs(&dem->cfg, &cd);
    fprintf(f,
            "# DEM and spot model side by side\n\n"
            "DEM: %zu snapshots, t = %g..%g tau, %zu particles, window %g..%g tau.  \n"
            "Spot model: %zu snapshots, t = %g..%g tau, %zu particles, window %g..%g tau.  \n"
            "Container %g x %g d, %s orifice of %g d. Regions: velocity profiles at z = %g..%g, correlation "
            "%g x %g d at z = %g, g(r) in %g < x < %g, %g < z < %g, density slice %g < z < %g.\n\n"
            "![the measurements of both runs](compare.png)\n\n"
            "| quantity | unit | DEM | spot | spot - DEM | relative | papers' DEM |\n|---|---|---|---|---|---|---|\n",
            dem->nframes, dem->frames[0].time, dem->frames[dem->nframes - 1].time, dem->n_initial, t0d, t1d,
            spot->nframes, spot->frames[0].time, spot->frames[spot->nframes - 1].time, spot->n_initial, t0s, t1s,
            cd.width, cd.depth,
            cd.orifice.shape == GF_ORIFICE_SLIT ? "slit" : "circular", cd.orifice.diameter,
            o->vel_heights[0], o->vel_heights[o->vel_nheights ? o->vel_nheights - 1 : 0], o->corr_size, o->corr_size,
            o->corr_zc, o->gr_x0, o->gr_x1, o->gr_z0, o->gr_z1, o->dens_z0, o->dens_z1);
    for (size_t k = 0; k < GF_CMP_K; k++) {
        double a = gf_cmp_value(md, GF_CMP_N, gf_cmp_keys[k].key), b = gf_cmp_value(ms, GF_CMP_N, gf_cmp_keys[k].key);
        fprintf(f, "| %s%s%s (`%s`) | %s |", gf_cmp_keys[k].what, gf_cmp_keys[k].of_profile ? " " : "",
                gf_cmp_keys[k].of_profile ? profile : "", gf_cmp_keys[k].key,
                *gf_cmp_keys[k].unit ? gf_cmp_keys[k].unit : "-");
        gf_cmp_num(f, a);
        gf_cmp_num(f, b);
        gf_cmp_num(f, b - a);
        if (isfinite((b - a) / fabs(a))) fprintf(f, " %+.1f%% |", 100.0 * (b - a) / fabs(a));
        else fprintf(f, " - |");
        fprintf(f, " %s |\n", gf_cmp_keys[k].papers);
    }
    double dd = gf_cmp_value(md, GF_CMP_N, "density_initial") - gf_cmp_value(md, GF_CMP_N, "density_steady");
    double ds = gf_cmp_value(ms, GF_CMP_N, "density_initial") - gf_cmp_value(ms, GF_CMP_N, "density_steady");
    fprintf(f, "| density drop in the slice | - |");
    gf_cmp_num(f, dd);
    gf_cmp_num(f, ds);
    gf_cmp_num(f, ds - dd);
    if (isfinite((ds - dd) / fabs(dd))) fprintf(f, " %+.1f%% |", 100.0 * (ds - dd) / fabs(dd));
    else fprintf(f, " - |");
    fprintf(f, " 550 (thesis) |\n");
    fprintf(f, "\nShape differences (L2 norm of spot - DEM over the curve, as the thesis measures g(r)):\n\n"
               "| curve | L2 difference |\n|---|---|\n");
    const char *curves[] = {"gr", "g3", "correlation"};
    for (size_t k = 0; k < 3; k++) {
        double l2 = gf_cmp_l2(gf_cmp_table(md, GF_CMP_N, curves[k]), gf_cmp_table(ms, GF_CMP_N, curves[k]));
        fprintf(f, "| %s |", curves[k]);
        gf_cmp_num(f, l2);
        fputc('\n', f);
    }
    fprintf(f, "\nVelocity profiles (Gaussian fits of %s, each over the frames where the flow at its height is steady, "
               "velocity.window = %s):\n\n"
               "| z (d) | DEM variance | spot variance | DEM peak v_z | spot peak v_z | DEM frames (tau) | spot frames (tau) "
               "|\n|---|---|---|---|---|---|---|\n",
            profile, o->vel_window == GF_VEL_WINDOW_RUN ? "run" : "height");
    const gf_table *vd = gf_cmp_table(md, GF_CMP_N, "velocity_variance"),
                   *vs = gf_cmp_table(ms, GF_CMP_N, "velocity_variance");
    for (size_t r = 0; vd && vs && r < vd->nrow && r < vs->nrow; r++) {
        fprintf(f, "| %g |", vd->v[r * vd->ncol]);
        gf_cmp_num(f, vd->v[r * vd->ncol + 1]);
        gf_cmp_num(f, vs->v[r * vs->ncol + 1]);
        gf_cmp_num(f, vd->v[r * vd->ncol + 2]);
        gf_cmp_num(f, vs->v[r * vs->ncol + 2]);
        gf_cmp_frames(f, vd, r);
        gf_cmp_frames(f, vs, r);
        fputc('\n', f);
    }
    const gf_table *rd = gf_cmp_table(md, GF_CMP_N, "rtd"), *rs = gf_cmp_table(ms, GF_CMP_N, "rtd");
    if (rd || rs) {
        fprintf(f,
                "\nResidence times by initial layer (the first snapshot's particles that exit within %.4g tau of it; "
                "DEM exit times %s; +- the uncertainty of the mean: standard error and exit-time resolution):\n\n"
                "| layer | DEM exited | DEM mean (tau) | spot exited | spot mean (tau) |\n|---|---|---|---|---|\n",
                o->rtd_tmax, dem->exits_derived ? "read off the snapshots" : "from exits.csv");
        double lo = INFINITY, hi = -INFINITY;
        const gf_table *both[2] = {rd, rs};
        for (int r = 0; r < 2; r++)
            for (size_t i = 0; both[r] && i < both[r]->nrow; i++) {
                lo = fmin(lo, both[r]->v[i * both[r]->ncol]);
                hi = fmax(hi, both[r]->v[i * both[r]->ncol]);
            }
        for (double l = lo; l <= hi; l += 1.0) {
            fprintf(f, "| %g |", l);
            for (int r = 0; r < 2; r++) {
                const double *row = NULL;
                for (size_t i = 0; both[r] && i < both[r]->nrow; i++)
                    if (both[r]->v[i * both[r]->ncol] == l) row = &both[r]->v[i * both[r]->ncol];
                if (!row) fprintf(f, " 0 | - |");
                else if (isfinite(row[6])) fprintf(f, " %g | %.4g +- %.2g |", row[1], row[2], row[6]);
                else fprintf(f, " %g | %.4g |", row[1], row[2]);
            }
            fputc('\n', f);
        }
    }
    fprintf(f,
            "\nThe central slice (y > 0) at t = %.3g, %.3g, %.3g and %.3g tau, coloured by initial layer:\n\n"
            "![DEM](slices_dem.png)\n\n![spot model](slices_spot.png)\n\n"
            "Files: `dem_NAME.csv` and `spot_NAME.csv` (the tables of `granflow analyze`, see docs/analysis.md), "
            "`summary.csv` (the table above), `compare.gp` (draws compare.png).\n",
            times[0], times[1], times[2], times[3]);
    return gf_atomic_commit(f, tmp, path);
}

// Snapshots of `s` within t0..t1 (a hair of rounding either side).
static size_t gf_cmp_frames_in(const gf_series *s, double t0, double t1)
{
    const double eps = 1e-9 * fmax(1.0, fabs(t1));
    size_t n = 0;
    for (size_t k = 0; k < s->nframes; k++)
        if (!(s->frames[k].time < t0 - eps) && !(s->frames[k].time > t1 + eps)) n++;
    return n;
}

gf_status gf_dem_compare(const gf_series *dem, const gf_series *spot, const gf_analysis_opts *o, const char *outdir,
                         bool plots)
{
    if (dem->nframes < 2 || spot->nframes < 2)
        return gf_error_set(GF_ERR_PARAM, "compare needs two snapshots or more of each run (DEM %zu, spot %zu)",
                            dem->nframes, spot->nframes);
    // The velocities, profiles and their fits take pairs of snapshots inside
    // the window: with one, every row was NaN and the figure failed in
    // gnuplot (issue 26). Refused before anything is written.
    const size_t in_dem = gf_cmp_frames_in(dem, o->t0, o->t1), in_spot = gf_cmp_frames_in(spot, o->t0, o->t1);
    if (in_dem < 2 || in_spot < 2)
        return gf_error_set(GF_ERR_PARAM,
                            "too few snapshots to compare: the window %g..%g tau holds %zu of the DEM run's and %zu "
                            "of the spot run's, and each needs two or more (snapshots more often, a longer run, or "
                            "a wider window.t0..window.t1)",
                            o->t0, o->t1, in_dem, in_spot);
    gf_status st = gf_fs_mkdirs(outdir);
    if (st != GF_OK) return st;
    gf_analysis_opts oc = *o;
    gf_dem_compare_opts(dem, spot, &oc); // both residence-time distributions cut at one time
    o = &oc;
    gf_measure_out md[GF_CMP_N], ms[GF_CMP_N];
    memset(md, 0, sizeof md);
    memset(ms, 0, sizeof ms);
    for (size_t k = 0; st == GF_OK && k < GF_CMP_N; k++) {
        if ((st = gf_stop_check(o->stop, "compare")) != GF_OK) break;
        st = gf_cmp_measures[k].run(dem, o, &md[k]);
        if (st == GF_OK) st = gf_cmp_measures[k].run(spot, o, &ms[k]);
        for (size_t t = 0; st == GF_OK && t < md[k].ntables; t++) {
            char path[GF_PATH_MAX + 64];
            snprintf(path, sizeof path, "%s/dem_%s.csv", outdir, md[k].tables[t].name);
            st = gf_table_write_csv(&md[k].tables[t], path);
        }
        for (size_t t = 0; st == GF_OK && t < ms[k].ntables; t++) {
            char path[GF_PATH_MAX + 64];
            snprintf(path, sizeof path, "%s/spot_%s.csv", outdir, ms[k].tables[t].name);
            st = gf_table_write_csv(&ms[k].tables[t], path);
        }
    }
    double times[4] = {0, 0, 0, 0};
    if (st == GF_OK) st = gf_stop_check(o->stop, "compare");
    if (st == GF_OK) st = gf_cmp_slices(dem, spot, outdir, times);
    if (st == GF_OK) st = gf_cmp_summary(outdir, dem, spot, md, ms, o, times);
    if (st == GF_OK) st = gf_cmp_figure(outdir, &dem->cfg, o, plots);
    for (size_t k = 0; k < GF_CMP_N; k++) {
        gf_measure_free(&md[k]);
        gf_measure_free(&ms[k]);
    }
    return st;
}
