// SPDX-License-Identifier: MIT
// Mean velocity: the field v(x, z), horizontal profiles v_z(x) (in a
// cylinder: radial, v_z(r)) with Gaussian fits whose variance grows linearly
// with height (thesis Sec. 3.3, DEM: Var = 2.28 z + 1.60), and the profile
// across the depth v_z(y) (2009 paper Fig. 8).
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <string.h>

#include "analysis/motion.h"
#include "analysis/steady_height.h"
#include "core/alloc.h"
#include "core/error.h"
#include "core/stop.h"
#include "geom/container.h"
#include "granflow/analysis.h"
#include "granflow/defs.h"

/// Bin of the depth profile, d. Centres lie within |y| <= D/2 - 0.5 = 3.5 of an
/// 8 d deep silo and the wall-ordered layer sits 0.5 d from each wall, so bins
/// must be well below 0.5 d to show the boundary layer of Fig. 8; 0.25 d still
/// holds ~115 particles of the 20 x 20 d test region per bin per frame pair.
#define GF_VELY_BIN 0.25

/// Accumulators of one measurement over the window's frame pairs.
typedef struct gf_vel_acc {
    gf_vfield field;
    size_t nh;      ///< heights
    bool radial;    ///< cylinder: profiles in r = sqrt(x^2 + y^2), not x
    double ox;      ///< x of the orifice (container.orifice_x): the v_z(y) region is |x - ox| < y_xhalf
    bool mirror;    ///< radial, no central column: fit with the points mirrored to -r
    size_t np;      ///< profile bins: field.nx, or radial bins of field.bin from the axis
    double *prof;   ///< nh x np x 2: sum vz, samples over each height's steady pairs
    size_t npairs;  ///< frame pairs of the window
    double *pp;     ///< npairs x nh x np x 2: the profiles of each pair
    double *band;   ///< npairs x nh x 2: sum vz, samples of each height's band (its steadiness)
    gf_steady_height *verdict; ///< nh: each height's steady pairs
    const gf_frame *frames; ///< the window's frames: pair j is frames j and j + 1
    size_t ny;      ///< depth bins
    double y0;      ///< lower edge of depth bin 0, d
    double *depth;  ///< ny x 2: sum vz, samples
} gf_vel_acc;

static void gf_vel_acc_free(gf_vel_acc *a)
{
    if (a->prof) GF_DELETE(a->prof, 2 * a->nh * a->np + 1);
    if (a->pp) GF_DELETE(a->pp, 2 * a->npairs * a->nh * a->np + 1);
    if (a->band) GF_DELETE(a->band, 2 * a->npairs * a->nh + 1);
    if (a->verdict) GF_DELETE(a->verdict, a->nh);
    if (a->depth) GF_DELETE(a->depth, 2 * a->ny);
    gf_vfield_free(&a->field);
}

/// Adds the steps of frame pair j.
static void gf_vel_acc_add(gf_vel_acc *a, const gf_steps *st, const gf_analysis_opts *o, size_t j)
{
    gf_vfield_add(&a->field, st);
    const gf_vfield *f = &a->field;
    for (size_t i = 0; i < st->n; i++) {
        double x = st->x[i], z = st->z[i];
        double ix = a->radial ? floor(hypot(x, st->y[i]) / f->bin) : floor(x / f->bin) - (double)f->ix0;
        if (ix >= 0.0 && ix < (double)a->np)
            for (size_t h = 0; h < a->nh; h++)
                if (fabs(z - o->vel_heights[h]) < o->vel_band) {
                    double *b = a->pp + 2 * ((j * a->nh + h) * a->np + (size_t)ix), *m = a->band + 2 * (j * a->nh + h);
                    b[0] += st->vz[i];
                    b[1] += 1.0;
                    m[0] += st->vz[i];
                    m[1] += 1.0;
                }
        if (a->ny && fabs(x - a->ox) < o->vely_xhalf && z > o->vely_z0 && z < o->vely_z1) {
            double iy = floor((st->y[i] - a->y0) / GF_VELY_BIN);
            if (iy >= 0.0 && iy < (double)a->ny) {
                a->depth[2 * (size_t)iy] += st->vz[i];
                a->depth[2 * (size_t)iy + 1] += 1.0;
            }
        }
    }
}

static gf_status gf_vel_check(const gf_analysis_opts *o)
{
    if (!(o->vel_bin > 0.0) || !(o->vel_band > 0.0) || o->vel_nheights > 16)
        return gf_error_set(GF_ERR_PARAM, "velocity: bin (%g) and band (%g) must be positive, at most 16 heights",
                            o->vel_bin, o->vel_band);
    return GF_OK;
}

/// Adds table `name` to `out`, returning it (NULL with the status in *st).
static gf_table *gf_vel_table(gf_measure_out *out, const char *name, const char *cols, gf_status *st)
{
    if (*st != GF_OK) return NULL;
    gf_table *t = &out->tables[out->ntables];
    *st = gf_table_init(t, name, cols);
    if (*st != GF_OK) {
        gf_table_free(t);
        return NULL;
    }
    out->ntables++;
    return t;
}

/// Each height's steady frame pairs (velocity.window = height; run: all of
/// them) and its profile summed over those pairs.
static gf_status gf_vel_steady(gf_vel_acc *a, const gf_analysis_opts *o, const gf_series *s)
{
    double *m = GF_NEW(double, a->npairs + 1), *tp = GF_NEW(double, a->npairs + 1);
    if (!m || !tp) {
        if (m) GF_DELETE(m, a->npairs + 1);
        if (tp) GF_DELETE(tp, a->npairs + 1);
        return gf_error_set(GF_ERR_NOMEM, "velocity: out of memory");
    }
    for (size_t j = 0; j < a->npairs; j++) tp[j] = a->frames[j].time;
    // A spot run's own rise time (the papers' walk: up by step_z each move;
    // sfr's drift follows the stress field, so the noise judges there).
    gf_engine_defs ed;
    gf_config_engine_defs(&s->cfg, &ed);
    const bool by_rise = s->spot_run && s->nframes && ed.flow_rule == GF_FLOW_DIFFUSIVE && ed.step_z > 0.0 &&
                         ed.move_rate > 0.0;
    for (size_t h = 0; h < a->nh; h++) {
        for (size_t j = 0; j < a->npairs; j++) {
            const double *b = a->band + 2 * (j * a->nh + h);
            m[j] = b[1] > 0.0 ? b[0] / b[1] : NAN;
        }
        gf_steady_height *v = &a->verdict[h];
        if (o->vel_window == GF_VEL_WINDOW_HEIGHT) {
            *v = gf_steady_height_find(m, a->npairs);
            if (by_rise)
                gf_steady_height_by_rise(v, tp, a->npairs,
                                         s->frames[0].time + gf_steady_height_rise_time(o->vel_heights[h], ed.birth_z,
                                                                                        ed.radius, ed.step_z,
                                                                                        ed.move_rate));
        } else {
            *v = (gf_steady_height){.steady = true};
            snprintf(v->why, sizeof v->why, "all %zu frame pairs of the window (velocity.window = run)", a->npairs);
        }
        if (!v->steady) continue;
        for (size_t j = v->first; j < a->npairs; j++)
            for (size_t i = 0; i < 2 * a->np; i++) a->prof[2 * h * a->np + i] += a->pp[2 * (j * a->nh + h) * a->np + i];
    }
    GF_DELETE(m, a->npairs + 1);
    GF_DELETE(tp, a->npairs + 1);
    return GF_OK;
}

/// The tables, fits and headlines from the accumulated sums.
static gf_status gf_vel_tables(const gf_vel_acc *a, const gf_analysis_opts *o, gf_measure_out *out, double *slope,
                               double *icpt, size_t *nfit)
{
    gf_status st = GF_OK;
    const gf_vfield *f = &a->field;
    gf_table *tf = gf_vel_table(out, "velocity_field", "x_d,z_d,vx_d_per_tau,vz_d_per_tau,samples", &st);
    for (size_t k = 0; st == GF_OK && k < f->nz; k++)
        for (size_t i = 0; st == GF_OK && i < f->nx; i++) {
            const double *b = f->sum + 4 * (k * f->nx + i);
            if (b[3] == 0.0) continue;
            double row[5] = {f->bin * ((double)f->ix0 + (double)i + 0.5), f->bin * ((double)f->iz0 + (double)k + 0.5),
                             b[0] / b[3], b[2] / b[3], b[3]};
            st = gf_table_add(tf, row);
        }

    // Profiles v_z(x) (radial: v_z(r)) at each height, and the Gaussian fit
    // of the downward speed. A radial profile about the axis is fitted with
    // its points mirrored to -r, so the Gaussian is centred on the axis and
    // its Var is the variance along one horizontal axis, as in the box (a
    // spot's walk spreads x and y alike: Var = 2 b_s z + c, thesis Sec. 3.3).
    // Around a central column (inner_radius > 0) the flow peaks on a ring:
    // the points are fitted as they are, the centre mu is the ring's radius.
    gf_table *tp = gf_vel_table(out, "velocity_profiles",
                                a->radial ? "z_d,r_d,vz_d_per_tau,vz_fit" : "z_d,x_d,vz_d_per_tau,vz_fit", &st);
    gf_table *tv = gf_vel_table(out, "velocity_variance",
                                "z_d,variance_d2,amplitude_d_per_tau,centre_d,t0_tau,t1_tau,steady", &st);
    size_t cap = 2 * a->np;
    double *px = cap ? GF_NEW(double, cap) : NULL, *pv = cap ? GF_NEW(double, cap) : NULL;
    double hz[16], hv[16];
    *nfit = 0;
    if (st == GF_OK && cap && (!px || !pv)) st = gf_error_set(GF_ERR_NOMEM, "velocity: out of memory");
    for (size_t h = 0; st == GF_OK && h < a->nh; h++) {
        size_t m = 0;
        for (size_t i = 0; i < a->np; i++) {
            const double *b = a->prof + 2 * (h * a->np + i);
            if (b[1] == 0.0) continue;
            px[m] = a->radial ? f->bin * ((double)i + 0.5) : f->bin * ((double)f->ix0 + (double)i + 0.5);
            pv[m++] = -b[0] / b[1]; // downward speed
        }
        size_t mfit = m;
        if (a->mirror)
            for (size_t i = 0; i < m; i++) {
                px[mfit] = -px[i];
                pv[mfit++] = pv[i];
            }
        double amp = NAN, mu = NAN, var = NAN;
        if (m > 0 && gf_fit_gaussian(px, pv, mfit, &amp, &mu, &var) != GF_OK) {
            gf_error_clear(); // no Gaussian at this height (e.g. no flow yet): NaN
            amp = mu = var = NAN;
        }
        for (size_t r = 0; st == GF_OK && r < m; r++) {
            double u = px[r] - mu;
            double row[4] = {o->vel_heights[h], px[r], -pv[r], -amp * exp(-u * u / (2.0 * var))};
            st = gf_table_add(tp, row);
        }
        const gf_steady_height *v = &a->verdict[h];
        bool timed = v->steady && a->frames;
        double row[7] = {o->vel_heights[h], var, amp, mu, timed ? a->frames[v->first].time : NAN,
                         timed ? a->frames[a->npairs].time : NAN, v->steady ? 1.0 : 0.0};
        if (st == GF_OK) st = gf_table_add(tv, row);
        if (isfinite(var)) {
            hz[*nfit] = o->vel_heights[h];
            hv[(*nfit)++] = var;
        }
    }
    if (px) GF_DELETE(px, cap);
    if (pv) GF_DELETE(pv, cap);
    // Var = s z + c over the fitted heights (thesis Sec. 3.3: linear regression).
    *slope = *icpt = NAN;
    if (st == GF_OK && *nfit >= 2 && gf_fit_linear(hz, hv, *nfit, slope, icpt) != GF_OK) {
        gf_error_clear(); // all at one height
        *slope = *icpt = NAN;
    }

    gf_table *td = gf_vel_table(out, "velocity_depth", "y_d,vz_d_per_tau,samples", &st);
    for (size_t j = 0; st == GF_OK && j < a->ny; j++) {
        if (a->depth[2 * j + 1] == 0.0) continue;
        double row[3] = {a->y0 + GF_VELY_BIN * ((double)j + 0.5), a->depth[2 * j] / a->depth[2 * j + 1], a->depth[2 * j + 1]};
        st = gf_table_add(td, row);
    }
    return st;
}

/// An empty panel saying so (gnuplot stops on a plot with no valid points).
static gf_status gf_vel_nodata(gf_measure_out *out, const char *title)
{
    return gf_measure_gnuplot(out,
                              "set title '%s: no data'\nunset xlabel\nunset ylabel\n"
                              "plot [0:1] [0:1] 2 notitle\n",
                              title);
}

static gf_status gf_vel_plot(const gf_measure_out *tabs, const gf_analysis_opts *o, double slope, double icpt,
                             const gf_config *cfg, gf_measure_out *out)
{
    const gf_table *tp = &tabs->tables[1], *tv = &tabs->tables[2], *td = &tabs->tables[3], *tf = &tabs->tables[0];
    gf_status st = gf_measure_gnuplot(out, "set datafile separator ','\nset multiplot layout 2,2\n");
    // Profiles with their fits.
    const char *name = gf_velocity_profile_name(cfg), *c = gf_velocity_radial(cfg) ? "r" : "x";
    char nodata[32];
    snprintf(nodata, sizeof nodata, "%s profiles", name);
    if (st == GF_OK && tp->nrow == 0) st = gf_vel_nodata(out, nodata);
    else if (st == GF_OK) {
        st = gf_measure_gnuplot(out,
                                "set title '%s at heights z, Gaussian fits'\n"
                                "set xlabel '%s (d)'\nset ylabel 'v_z (d/tau)'\nset key bottom right font ',7'\nplot ",
                                name, c);
        for (size_t h = 0; st == GF_OK && h < o->vel_nheights; h++) {
            double z = o->vel_heights[h];
            st = gf_measure_gnuplot(out,
                                    "%s'velocity_profiles.csv' skip 1 using 2:(abs($1-(%.10g))<1e-6?$3:1/0) "
                                    "with points pt 7 ps 0.4 lc %zu title 'z = %g', \\\n"
                                    "  'velocity_profiles.csv' skip 1 using 2:(abs($1-(%.10g))<1e-6?$4:1/0) "
                                    "with lines lc %zu notitle",
                                    h ? ", \\\n  " : "", z, h + 1, z, z, h + 1);
        }
        if (st == GF_OK) st = gf_measure_gnuplot(out, "\n");
    }
    // Var vs z with the regression and the paper's DEM line.
    if (st == GF_OK) {
        st = gf_measure_gnuplot(out,
                                "set title 'Gaussian variance of %s'\n"
                                "set xlabel 'z (d)'\nset ylabel 'Var (d^2)'\nset key top left font ',8'\n"
                                "plot 2.28*x+1.60 with lines dt 2 lc 'black' title 'DEM: 2.28 z + 1.60'",
                                name);
        if (st == GF_OK && isfinite(slope))
            st = gf_measure_gnuplot(out, ", \\\n  (%.10g)*x+(%.10g) with lines lc 2 title 'fit: %.3g z %c %.3g'", slope,
                                    icpt, slope, icpt < 0.0 ? '-' : '+', fabs(icpt));
        if (st == GF_OK && tv->nrow)
            st = gf_measure_gnuplot(out, ", \\\n  'velocity_variance.csv' skip 1 using 1:2 with points pt 7 lc 2 "
                                         "title 'measured'");
        if (st == GF_OK) st = gf_measure_gnuplot(out, "\n");
    }
    // v_z(y) across the depth, above the orifice (|x - orifice_x| < y_xhalf).
    char xs[48] = "|x|";
    gf_container_defs cd;
    gf_config_container_defs(cfg, &cd);
    if (cd.orifice.x != 0.0) snprintf(xs, sizeof xs, "|x - %g|", cd.orifice.x);
    if (st == GF_OK && td->nrow == 0) st = gf_vel_nodata(out, "v_z(y)");
    else if (st == GF_OK)
        st = gf_measure_gnuplot(out,
                                "set title 'v_z(y), %s < %g, %g < z < %g'\n"
                                "set xlabel 'y (d)'\nset ylabel 'v_z (d/tau)'\nunset key\n"
                                "plot 'velocity_depth.csv' skip 1 using 1:2 with linespoints pt 7 ps 0.5\n",
                                xs, o->vely_xhalf, o->vely_z0, o->vely_z1);
    // The mean field, coloured by v_z.
    if (st == GF_OK && tf->nrow == 0) st = gf_vel_nodata(out, "mean v_z(x, z)");
    else if (st == GF_OK)
        st = gf_measure_gnuplot(out,
                                "set title 'mean v_z(x, z)'\n"
                                "set xlabel 'x (d)'\nset ylabel 'z (d)'\nset cblabel 'v_z (d/tau)'\nunset key\nset size ratio -1\nset xtics 25\n"
                                "set style fill solid noborder\n"
                                "plot 'velocity_field.csv' skip 1 using 1:2:(%g):(%g):4 with boxxyerror lc palette\n",
                                0.5 * o->vel_bin, 0.5 * o->vel_bin);
    if (st == GF_OK) st = gf_measure_gnuplot(out, "unset multiplot\n");
    return st;
}

bool gf_velocity_radial(const gf_config *cfg)
{
    const gf_container c = gf_container_make(cfg);
    return gf_container_profile_radial(&c) && gf_container_outer_radius(&c) > 0.0;
}

const char *gf_velocity_profile_name(const gf_config *cfg) { return gf_velocity_radial(cfg) ? "v_z(r)" : "v_z(x)"; }

gf_status gf_measure_velocity(const gf_series *s, const gf_analysis_opts *o, gf_measure_out *out)
{
    gf_status st = gf_vel_check(o);
    if (st != GF_OK) return st;
    double t0, t1;
    gf_analysis_window(o, s, &t0, &t1);
    size_t k0, k1;
    gf_window_frames(s, t0, t1, &k0, &k1);

    gf_vel_acc a = {0};
    st = gf_vfield_init(&a.field, s, k0, k1, o->vel_bin, false);
    a.nh = o->vel_nheights;
    a.np = a.field.nx;
    gf_container_defs cd;
    gf_config_container_defs(&s->cfg, &cd);
    a.ox = cd.orifice.x;
    if (gf_velocity_radial(&s->cfg)) {
        a.radial = true; // bins of r out to the wall
        const gf_container c = gf_container_make(&s->cfg);
        a.mirror = !(gf_container_inner_radius(&c) > 0.0);
        a.np = (size_t)ceil(gf_container_outer_radius(&c) / o->vel_bin);
    }
    double depth = cd.depth;
    a.frames = k1 > k0 ? s->frames + k0 : NULL; // NULL: no frame in the window
    a.npairs = k1 > k0 + 1 ? k1 - k0 - 1 : 0;
    if (st == GF_OK && a.nh) {
        a.prof = GF_NEW(double, 2 * a.nh * a.np + 1);
        a.pp = GF_NEW(double, 2 * a.npairs * a.nh * a.np + 1);
        a.band = GF_NEW(double, 2 * a.npairs * a.nh + 1);
        a.verdict = GF_NEW(gf_steady_height, a.nh);
        if (!a.prof || !a.pp || !a.band || !a.verdict)
            st = gf_error_set(GF_ERR_NOMEM, "velocity: out of memory for the profiles of %zu frame pairs", a.npairs);
    }
    if (st == GF_OK && depth > 0.0) {
        a.ny = (size_t)ceil(depth / GF_VELY_BIN - 1e-9);
        a.y0 = -0.5 * depth;
        a.depth = GF_NEW(double, 2 * a.ny);
        if (!a.depth) st = gf_error_set(GF_ERR_NOMEM, "velocity: out of memory for the depth profile");
    }
    // v = (r2 - r1) / (t2 - t1) at the midpoint, for each pair of consecutive
    // frames in the window and each particle present in both.
    gf_steps steps = {0};
    for (size_t k = k0; st == GF_OK && k + 1 < k1; k++) {
        if ((st = gf_stop_check(o->stop, "velocity")) != GF_OK) break;
        st = gf_steps_between(&s->frames[k], &s->frames[k + 1], &steps);
        if (st == GF_OK) gf_vel_acc_add(&a, &steps, o, k - k0);
    }
    gf_steps_free(&steps);
    if (st == GF_OK && a.nh) st = gf_vel_steady(&a, o, s);
    size_t unsteady = 0;
    for (size_t h = 0; st == GF_OK && h < a.nh; h++) unsteady += !a.verdict[h].steady;

    double slope = NAN, icpt = NAN;
    size_t nfit = 0;
    if (st == GF_OK) st = gf_vel_tables(&a, o, out, &slope, &icpt, &nfit);
    gf_vel_acc_free(&a);
    if (st == GF_OK) st = gf_measure_value(out, "velocity_variance_slope", slope);
    if (st == GF_OK) st = gf_measure_value(out, "velocity_variance_intercept", icpt);
    if (st == GF_OK) st = gf_measure_value(out, "velocity_unsteady_heights", (double)unsteady);
    if (st == GF_OK) st = gf_vel_plot(out, o, slope, icpt, &s->cfg, out);
    return st;
}
