// SPDX-License-Identifier: MIT
// The numbers a spot run must match a DEM run on (thesis Sec. 3.5): flow
// rate, variance of the Gaussian v_z(x) profiles (v_z(r) in a cylinder) at
// each height, particle diffusion length b_p, velocity correlation length
// beta and packing fraction in the flowing slice, each over the window with
// an uncertainty from the scatter over sub-windows; the mean residence time
// per initial layer (SPEC 1.6), over the whole run; and the table of DEM vs
// spot with a within-tolerance verdict for each.
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "core/error.h"
#include "core/stop.h"
#include "geom/container.h"
#include "granflow/dem.h"
#include "dem/dem_internal.h"

#define GF_FS_PI 3.14159265358979323846
#define GF_FS_PARTS_MAX 64 // window.parts at most

static double gf_fs_value(const gf_measure_out *m, const char *key)
{
    for (size_t k = 0; k < m->nvalues; k++)
        if (!strcmp(m->values[k].key, key)) return m->values[k].value;
    return NAN;
}

/// One estimate of everything over [t0, t1].
static gf_status gf_fs_once(const gf_series *s, const gf_analysis_opts *base, double t0, double t1, bool corr,
                            gf_dem_flowstats *fs)
{
    gf_analysis_opts o = *base;
    o.t0 = t0;
    o.t1 = t1;
    gf_measure_out m;
    gf_status st;
    memset(&m, 0, sizeof m);
    if ((st = gf_measure_outflow(s, &o, &m)) == GF_OK) fs->flow.value = gf_fs_value(&m, "flow_rate");
    gf_measure_free(&m);
    if (st != GF_OK) return st;
    memset(&m, 0, sizeof m);
    if ((st = gf_measure_velocity(s, &o, &m)) == GF_OK) {
        for (size_t k = 0; k < m.ntables; k++) {
            const gf_table *t = &m.tables[k];
            if (strcmp(t->name, "velocity_variance") != 0) continue;
            fs->nz = 0;
            for (size_t r = 0; r < t->nrow && fs->nz < GF_DEM_FS_MAXZ; r++) {
                fs->z[fs->nz] = t->v[r * t->ncol];
                fs->var_t0[fs->nz] = t->ncol > 6 && t->v[r * t->ncol + 6] != 0.0 ? t->v[r * t->ncol + 4] : NAN;
                fs->var[fs->nz++].value = t->v[r * t->ncol + 1];
            }
        }
    }
    gf_measure_free(&m);
    if (st != GF_OK) return st;
    memset(&m, 0, sizeof m);
    if ((st = gf_measure_diffusion(s, &o, &m)) == GF_OK) fs->bp.value = gf_fs_value(&m, "diffusion_length");
    gf_measure_free(&m);
    if (st != GF_OK) return st;
    memset(&m, 0, sizeof m);
    if ((st = gf_measure_density(s, &o, &m)) == GF_OK) {
        gf_container box = gf_container_make(&s->cfg); // a cylinder's slice is a disc (less its column)
        double vol = gf_container_slice_volume(&box, o.dens_z0, o.dens_z1);
        fs->phi.value = gf_fs_value(&m, "density_steady") * (GF_FS_PI / 6.0) / vol;
        fs->drop.value = gf_fs_value(&m, "density_initial") - gf_fs_value(&m, "density_steady");
    }
    gf_measure_free(&m);
    if (st != GF_OK) return st;
    fs->beta.value = NAN;
    if (corr) {
        memset(&m, 0, sizeof m);
        if ((st = gf_measure_correlation(s, &o, &m)) == GF_OK) fs->beta.value = gf_fs_value(&m, "correlation_length");
        gf_measure_free(&m);
    }
    return st;
}

/// The residence times of gf_measure_rtd: the mean over all layers and per
/// layer, each with the uncertainty of its mean (err_mean_tau).
static gf_status gf_fs_rtd(const gf_series *s, const gf_analysis_opts *o, gf_dem_flowstats *fs)
{
    fs->rtd = (gf_dem_value){NAN, NAN};
    fs->rtd_tmax = fs->rtd_resolution = NAN;
    fs->nlayer = 0;
    if (!s->has_exits) return GF_OK; // a series made without gf_dem_series_load: no residence times
    gf_measure_out m;
    memset(&m, 0, sizeof m);
    gf_status st = gf_measure_rtd(s, o, &m);
    if (st == GF_OK) {
        fs->rtd = (gf_dem_value){gf_fs_value(&m, "rtd_mean"), gf_fs_value(&m, "rtd_mean_err")};
        fs->rtd_tmax = gf_fs_value(&m, "rtd_tmax");
        fs->rtd_resolution = gf_fs_value(&m, "rtd_resolution");
        const gf_table *t = m.ntables ? &m.tables[0] : NULL; // "rtd": layer, count, mean, sd, median, first, err
        for (size_t r = 0; t && r < t->nrow && fs->nlayer < GF_DEM_FS_MAXL; r++) {
            const double *row = &t->v[r * t->ncol];
            fs->layer[fs->nlayer] = (int32_t)row[0];
            fs->rtd_layer[fs->nlayer++] = (gf_dem_value){row[2], row[6]};
        }
    }
    gf_measure_free(&m);
    return st;
}

/// Mean of the finite values among v[0..n) and its standard error (NaN with fewer than 2).
static void gf_fs_mean_se(const double *v, size_t n, double *mean, double *se)
{
    double s = 0.0, s2 = 0.0;
    size_t m = 0;
    for (size_t k = 0; k < n; k++)
        if (isfinite(v[k])) {
            s += v[k];
            m++;
        }
    *mean = m ? s / (double)m : NAN;
    *se = NAN;
    if (m < 2) return;
    for (size_t k = 0; k < n; k++)
        if (isfinite(v[k])) s2 += (v[k] - *mean) * (v[k] - *mean);
    *se = sqrt(s2 / (double)(m - 1) / (double)m);
}

size_t gf_dem_window_parts(const gf_analysis_opts *o, size_t nframes, size_t most)
{
    size_t parts = o->window_parts < 2 ? 2 : o->window_parts > most ? most : o->window_parts;
    return nframes >= 3 * parts ? parts : nframes >= 6 ? 2 : 1;
}

/// Standard error of the mean of the finite values among v[0..n).
static double gf_fs_err(const double *v, size_t n)
{
    double mean, se;
    gf_fs_mean_se(v, n, &mean, &se);
    return se;
}

gf_status gf_dem_flowstats_measure(const gf_series *s, const gf_analysis_opts *o, bool correlation,
                                   gf_dem_flowstats *fs)
{
    memset(fs, 0, sizeof *fs);
    double t0, t1;
    gf_analysis_window(o, s, &t0, &t1);
    gf_status st = gf_fs_once(s, o, t0, t1, correlation, fs);
    if (st != GF_OK) return st;
    size_t k0, k1, nf = gf_window_frames(s, t0, t1, &k0, &k1);
    size_t K = gf_dem_window_parts(o, nf, GF_FS_PARTS_MAX);
    double v[5 + GF_DEM_FS_MAXZ][GF_FS_PARTS_MAX];
    // The parts take each height's steadiness from the whole window: a
    // height's Var counts in the parts that start once its flow is steady
    // (var_t0), each averaging all its pairs (a part is too short to judge).
    gf_analysis_opts op = *o;
    op.vel_window = GF_VEL_WINDOW_RUN;
    for (size_t j = 0; j < K; j++) {
        gf_dem_flowstats e;
        memset(&e, 0, sizeof e);
        double a = t0 + (t1 - t0) * (double)j / (double)K, b = t0 + (t1 - t0) * (double)(j + 1) / (double)K;
        if ((st = gf_stop_check(o->stop, "flow statistics")) != GF_OK) return st;
        if ((st = gf_fs_once(s, &op, a, b, correlation, &e)) != GF_OK) return st;
        v[0][j] = e.flow.value;
        v[1][j] = e.bp.value;
        v[2][j] = e.phi.value;
        v[3][j] = e.drop.value;
        v[4][j] = e.beta.value;
        for (size_t z = 0; z < GF_DEM_FS_MAXZ; z++) {
            bool steady = z < fs->nz && a >= fs->var_t0[z] - 1e-9 * fmax(1.0, fabs(a)); // false for NaN
            v[5 + z][j] = z < e.nz && steady ? e.var[z].value : NAN;
        }
    }
    if (K < 2) {
        fs->flow.err = fs->bp.err = fs->phi.err = fs->drop.err = fs->beta.err = NAN;
        for (size_t z = 0; z < fs->nz; z++) fs->var[z].err = NAN;
    } else {
        fs->flow.err = gf_fs_err(v[0], K);
        fs->bp.err = gf_fs_err(v[1], K);
        fs->phi.err = gf_fs_err(v[2], K);
        fs->drop.err = gf_fs_err(v[3], K);
        fs->beta.err = gf_fs_err(v[4], K);
        for (size_t z = 0; z < fs->nz; z++) fs->var[z].err = gf_fs_err(v[5 + z], K);
    }
    // Whether each height's width drifts over the window: the later half of
    // the sub-windows against the earlier (a reference still widening, as
    // docs/dem.md's long references do for about one residence time).
    for (size_t z = 0; z < GF_DEM_FS_MAXZ; z++) fs->var_drift[z] = fs->var_drift_se[z] = NAN;
    for (size_t z = 0; z < fs->nz && K >= 4; z++) {
        double m1, e1, m2, e2;
        gf_fs_mean_se(v[5 + z], K / 2, &m1, &e1);
        gf_fs_mean_se(v[5 + z] + K / 2, K - K / 2, &m2, &e2);
        double e = hypot(e1, e2);
        if (!isfinite(m1) || !isfinite(m2) || !(fs->var[z].value > 0)) continue;
        fs->var_drift[z] = (m2 - m1) / fs->var[z].value;
        fs->var_drift_se[z] = e > 0 ? (m2 - m1) / e : NAN;
    }
    fs->t0 = t0;
    fs->t1 = t1;
    fs->parts = K;
    fs->profile = gf_velocity_profile_name(&s->cfg);
    return gf_fs_rtd(s, o, fs);
}

void gf_dem_compare_opts(const gf_series *dem, const gf_series *spot, gf_analysis_opts *o)
{
    if (!isnan(o->rtd_tmax) || !dem->nframes || !spot->nframes) return;
    double a = dem->frames[dem->nframes - 1].time - dem->frames[0].time;
    double b = spot->frames[spot->nframes - 1].time - spot->frames[0].time;
    o->rtd_tmax = fmax(0.0, fmin(a, b));
}

static bool gf_fs_within(gf_dem_value d, gf_dem_value s, double tol)
{
    return isfinite(d.value) && isfinite(s.value) && fabs(s.value - d.value) <= tol * fabs(d.value);
}

bool gf_dem_flowstats_measured(gf_dem_value v, double tol)
{
    return isfinite(v.value) && v.value > 0 && (!isfinite(v.err) || v.err <= tol * v.value);
}

bool gf_dem_flowstats_match(const gf_dem_flowstats *dem, const gf_dem_flowstats *spot, double flow_tol,
                            double var_tol)
{
    if (!gf_fs_within(dem->flow, spot->flow, flow_tol)) return false;
    size_t used = 0;
    for (size_t z = 0; z < dem->nz && z < spot->nz; z++) {
        if (!gf_dem_flowstats_measured(dem->var[z], var_tol)) continue; // too noisy in the DEM to test
        used++;
        if (!gf_fs_within(dem->var[z], spot->var[z], var_tol)) return false;
    }
    return used > 0;
}

static void gf_fs_num(char *buf, size_t n, gf_dem_value v)
{
    if (!isfinite(v.value)) snprintf(buf, n, "-");
    else if (isfinite(v.err)) snprintf(buf, n, "%.4g +- %.2g", v.value, v.err);
    else snprintf(buf, n, "%.4g", v.value);
}

/// One row; `gate`: a DEM value too noisy for the tolerance gets no verdict
/// (the Var rows; the flow rate is always judged).
static void gf_fs_row(FILE *f, const char *name, gf_dem_value d, gf_dem_value s, double tol, bool gate)
{
    char a[48], b[48], diff[64], verdict[64];
    gf_fs_num(a, sizeof a, d);
    gf_fs_num(b, sizeof b, s);
    double delta = s.value - d.value;
    double err = hypot(isfinite(d.err) ? d.err : 0.0, isfinite(s.err) ? s.err : 0.0);
    if (isfinite(delta) && d.value != 0)
        snprintf(diff, sizeof diff, "%+.1f%% +- %.1f%%", 100.0 * delta / fabs(d.value), 100.0 * err / fabs(d.value));
    else snprintf(diff, sizeof diff, "-");
    if (gate && tol > 0 && isfinite(delta) && !gf_dem_flowstats_measured(d, tol))
        snprintf(verdict, sizeof verdict, "DEM too noisy to test %.0f%%", 100.0 * tol);
    else if (tol > 0 && isfinite(delta))
        snprintf(verdict, sizeof verdict, "%s (tolerance %.0f%%)", gf_fs_within(d, s, tol) ? "within" : "OUTSIDE",
                 100.0 * tol);
    else if (isfinite(delta)) snprintf(verdict, sizeof verdict, "(no tolerance)");
    else snprintf(verdict, sizeof verdict, "not measurable");
    fprintf(f, "  %-34s %-20s %-20s %-20s %s\n", name, a, b, diff, verdict);
}

/// Which frames each height's profile averaged, in either run (velocity.window).
static void gf_fs_windows(FILE *f, const gf_dem_flowstats *dem, const gf_dem_flowstats *spot)
{
    fprintf(f, "  %-34s", "profile frames (tau), DEM / spot:");
    const gf_dem_flowstats *run[2] = {dem, spot};
    for (size_t z = 0; z < dem->nz && z < spot->nz; z++) {
        fprintf(f, "%s z = %.3g:", z ? ";" : "", dem->z[z]);
        for (int r = 0; r < 2; r++) {
            if (isfinite(run[r]->var_t0[z])) fprintf(f, "%s %.4g-%.4g", r ? " /" : "", run[r]->var_t0[z], run[r]->t1);
            else fprintf(f, "%s no steady frames", r ? " /" : "");
        }
    }
    fputc('\n', f);
}

/// The heights whose DEM width drifts over the window by more than 3
/// standard errors (later half of the sub-windows against the earlier).
static void gf_fs_drift(FILE *f, const gf_dem_flowstats *dem)
{
    bool any = false;
    for (size_t z = 0; z < dem->nz; z++) {
        if (!(fabs(dem->var_drift_se[z]) > 3.0)) continue;
        if (!any) fprintf(f, "  %-34s", "DEM widths drifting (later half of the window against the earlier):");
        fprintf(f, "%s z = %.3g: %+.0f%% (%.1f se)", any ? ";" : "", dem->z[z], 100.0 * dem->var_drift[z],
                dem->var_drift_se[z]);
        any = true;
    }
    if (any) fprintf(f, "; a later window.t0 measures the steady widths\n");
}

void gf_dem_flowstats_table(const gf_dem_flowstats *dem, const gf_dem_flowstats *spot, double flow_tol,
                            double var_tol, FILE *f)
{
    fprintf(f, "  %-34s %-20s %-20s %-20s %s\n", "quantity", "DEM", "spot", "spot - DEM", "verdict");
    gf_fs_row(f, "flow rate Q (1/tau)", dem->flow, spot->flow, flow_tol, false);
    const char *profile = dem->profile ? dem->profile : spot->profile ? spot->profile : "the profile";
    for (size_t z = 0; z < dem->nz && z < spot->nz; z++) {
        char name[64];
        snprintf(name, sizeof name, "Var of %s at z = %.3g (d^2)", profile, dem->z[z]);
        gf_fs_row(f, name, dem->var[z], spot->var[z], var_tol, true);
    }
    gf_fs_windows(f, dem, spot);
    gf_fs_drift(f, dem);
    gf_fs_row(f, "diffusion length b_p (d)", dem->bp, spot->bp, 0.0, false);
    gf_fs_row(f, "packing fraction in flow", dem->phi, spot->phi, 0.0, false);
    gf_fs_row(f, "density drop in the slice", dem->drop, spot->drop, 0.0, false);
    if (isfinite(dem->beta.value) || isfinite(spot->beta.value))
        gf_fs_row(f, "correlation length beta (d)", dem->beta, spot->beta, 0.0, false);
    if (!isfinite(dem->rtd.value) && !isfinite(spot->rtd.value)) return;
    // Residence times: how they were measured, the mean over all layers, then
    // each initial layer either run has.
    char how[2][64];
    const gf_dem_flowstats *run[2] = {dem, spot};
    for (int r = 0; r < 2; r++)
        if (run[r]->rtd_resolution > 0)
            snprintf(how[r], sizeof how[r], "read off the snapshots, +- %.3g tau", run[r]->rtd_resolution);
        else snprintf(how[r], sizeof how[r], "exits.csv");
    // Means over different spans are not comparable (a longer run adds late exits).
    double ta = dem->rtd_tmax, tb = spot->rtd_tmax;
    if (!(fabs(ta - tb) <= 1e-9 * fmax(1.0, fmax(fabs(ta), fabs(tb))))) {
        fprintf(f, "  residence times not compared: counted up to %.4g tau in the DEM, %.4g tau in the spot run "
                   "(rtd.tmax sets one span)\n",
                ta, tb);
        return;
    }
    fprintf(f, "  residence times of the first snapshot's particles exiting within %.4g tau (exit times: DEM %s, "
               "spot %s; uncertainty: standard error of the mean and that resolution):\n",
            ta, how[0], how[1]);
    gf_fs_row(f, "mean residence time (tau)", dem->rtd, spot->rtd, 0.0, false);
    int32_t lo = INT32_MAX, hi = INT32_MIN;
    for (int r = 0; r < 2; r++)
        for (size_t k = 0; k < run[r]->nlayer; k++) {
            if (run[r]->layer[k] < lo) lo = run[r]->layer[k];
            if (run[r]->layer[k] > hi) hi = run[r]->layer[k];
        }
    for (int64_t l = lo; l <= hi; l++) {
        gf_dem_value d = {NAN, NAN}, s = {NAN, NAN};
        for (size_t k = 0; k < dem->nlayer; k++)
            if (dem->layer[k] == l) d = dem->rtd_layer[k];
        for (size_t k = 0; k < spot->nlayer; k++)
            if (spot->layer[k] == l) s = spot->rtd_layer[k];
        if (!isfinite(d.value) && !isfinite(s.value)) continue;
        char name[64];
        snprintf(name, sizeof name, "  of layer %lld (tau)", (long long)l);
        gf_fs_row(f, name, d, s, 0.0, false);
    }
}
