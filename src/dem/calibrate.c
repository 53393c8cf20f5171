// SPDX-License-Identifier: MIT
// Calibration of the five spot parameters from a DEM run (thesis Sec. 3.3,
// SPEC 1.7): r_s from the velocity-correlation length, b_s (and so the spot
// step) from the growth of the Gaussian profile variance with height, w from
// the particle diffusion length, lambda from the outflow and the particles a
// spot ball holds, mu from the density drop in a slice. The derivations are
// in docs/dem.md. Every value is measured over the window and over K
// sub-windows; the uncertainty is the scatter of the sub-window values over
// sqrt(K) (the standard error of their mean).
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "core/rng.h"
#include "core/stop.h"
#include "geom/container.h"
#include "granflow/defs.h"
#include "granflow/dem.h"
#include "dem/dem_internal.h"

#define GF_CAL_PI 3.14159265358979323846
#define GF_CAL_MAXPARTS 64 // window.parts at most
#define GF_CAL_BALLS 400   // spot balls placed per frame for p
#define GF_CAL_WALLSD 5.0  // a profile is fitted only where its sd is below W / this (tails inside the walls)

/// Width of the container's cross-section, d: a box's width, a cylinder's
/// diameter (the scale of the regions and of the widest profile fitted).
static double gf_cal_width(const gf_config *cfg)
{
    const gf_container c = gf_container_make(cfg);
    return gf_container_width(&c);
}

/// Volume inside the container between heights z0 < z1, d^3: a box's
/// W D (z1 - z0); otherwise its cross-sections integrated.
static double gf_cal_volume(const gf_config *cfg, double z0, double z1)
{
    const gf_container c = gf_container_make(cfg);
    return gf_container_slice_volume(&c, z0, z1);
}

/// Top of the packing in a frame: the mean of its 20 highest centres with
/// |x - xc| < xhalf (above the orifice at x = xc a draining silo is lower than at its sides).
static double gf_cal_top(const gf_packing *p, double xc, double xhalf)
{
    double top[20];
    size_t m = 0;
    for (size_t i = 0; i < p->n; i++) {
        if (fabs(p->x[i] - xc) >= xhalf) continue;
        double z = p->z[i];
        if (m < 20) {
            top[m++] = z;
        } else {
            size_t lo = 0;
            for (size_t k = 1; k < 20; k++)
                if (top[k] < top[lo]) lo = k;
            if (z > top[lo]) top[lo] = z;
        }
    }
    double s = 0.0;
    for (size_t k = 0; k < m; k++) s += top[k];
    return m ? s / (double)m : 0.0;
}

void gf_dem_calibration_opts(const gf_series *s, const gf_analysis_opts *keep, gf_analysis_opts *o)
{
    gf_analysis_opts d = gf_analysis_opts_default();
    gf_analysis_opts k = keep ? *keep : d;
    *o = k;
    if (s->nframes == 0) return;
    double t0, t1;
    gf_analysis_window(o, s, &t0, &t1);
    size_t k0, k1;
    gf_window_frames(s, t0, t1, &k0, &k1);
    double W = gf_cal_width(&s->cfg);
    gf_container_defs cd;
    gf_config_container_defs(&s->cfg, &cd);
    // h1: the lowest the surface gets in the window, above the orifice (a
    // crater forms there), so that no region leaves the packing.
    double h0 = gf_cal_top(&s->frames[0].pk, 0.0, INFINITY), xo = cd.orifice.x;
    const gf_packing *last = &s->frames[k1 > 0 ? k1 - 1 : 0].pk;
    double h1 = fmin(gf_cal_top(last, 0.0, INFINITY), gf_cal_top(last, xo, fmax(2.0, 0.25 * W)));
    // The papers' regions belong to a fill of 110 d: scaled to this one, and
    // kept below the surface at the end of the window.
    if (k.vel_nheights == d.vel_nheights && !memcmp(k.vel_heights, d.vel_heights, sizeof d.vel_heights)) {
        double lo = fmax(5.0, cd.orifice.diameter), hi = fmin(0.6 * h1, h1 - 8.0);
        size_t n = 8;
        if (hi < lo + 2.0) hi = lo + 2.0;
        for (size_t j = 0; j < n; j++) o->vel_heights[j] = lo + (hi - lo) * (double)j / (double)(n - 1);
        o->vel_nheights = n;
    }
    if (k.corr_size == d.corr_size) o->corr_size = fmax(4.0, fmin(16.0, fmin(W - 4.0, 0.4 * h1)));
    // Never below the base (nor in the orifice's jet) nor above the surface.
    if (k.corr_zc == d.corr_zc)
        o->corr_zc = fmax(0.5 * o->corr_size + 2.0, fmin(0.55 * h0, h1 - 0.5 * o->corr_size - 4.0));
    // Diffusion: particles starting above the orifice (|x - orifice_x| < 5, or W/4), from the
    // slice's bottom up (the papers: z > 60 of 110), followed as they drop.
    if (k.diff_xhalf == d.diff_xhalf) o->diff_xhalf = fmin(5.0, 0.25 * W);
    if (k.dens_z0 == d.dens_z0) o->dens_z0 = fmax(2.0, fmin(0.45 * h0, h1 - 6.0));
    if (k.dens_z1 == d.dens_z1) o->dens_z1 = fmax(o->dens_z0 + 2.0, fmin(0.64 * h0, h1 - 4.0));
    if (k.diff_z0 == d.diff_z0) o->diff_z0 = o->dens_z0;
    // g(r) and g3: the papers' -15 < x < 15, 15 < z < 45 of 110, scaled.
    if (k.gr_x0 == d.gr_x0 && k.gr_x1 == d.gr_x1) {
        o->gr_x1 = fmax(2.0, fmin(15.0, 0.5 * W - 2.0));
        o->gr_x0 = -o->gr_x1;
    }
    if (k.gr_z0 == d.gr_z0) o->gr_z0 = fmax(2.0, 0.14 * h0);
    if (k.gr_z1 == d.gr_z1) o->gr_z1 = fmax(o->gr_z0 + 2.0, fmin(0.41 * h0, h1 - 3.0));
}

gf_status gf_dem_window(const gf_series *s, gf_analysis_opts *o, gf_steady *w)
{
    gf_steady tmp;
    gf_steady *win = w ? w : &tmp;
    gf_status st = gf_analysis_opts_check(o);
    if (st == GF_OK) st = gf_steady_window(s, win);
    if (st != GF_OK) return st;
    if (!isnan(o->t0) && !isnan(o->t1)) {
        win->t0 = o->t0;
        win->t1 = o->t1;
        snprintf(win->reason, sizeof win->reason, "the window given (window.t0, window.t1)");
        return GF_OK;
    }
    if (!isnan(o->t0) || !isnan(o->t1)) {
        if (!isnan(o->t0)) win->t0 = o->t0;
        if (!isnan(o->t1)) win->t1 = o->t1;
        size_t len = strlen(win->reason);
        snprintf(win->reason + len, sizeof win->reason - len, "; %s given", !isnan(o->t0) ? "window.t0" : "window.t1");
        // One end given, the other automatic: the two must still make a window.
        if (!(win->t0 < win->t1))
            return gf_error_set(GF_ERR_PARAM,
                                "%s = %.6g leaves no window: the automatic %s is %.6g tau (the run's snapshots span "
                                "%.6g..%.6g tau)",
                                !isnan(o->t0) ? "window.t0" : "window.t1", !isnan(o->t0) ? o->t0 : o->t1,
                                !isnan(o->t0) ? "window.t1" : "window.t0", !isnan(o->t0) ? win->t1 : win->t0,
                                s->nframes ? s->frames[0].time : 0.0, s->nframes ? s->frames[s->nframes - 1].time : 0.0);
    }
    o->t0 = win->t0;
    o->t1 = win->t1;
    return GF_OK;
}

#define GF_CAL_RS_FALLBACK 2.6 // thesis Sec. 3.3

/// Records what could not be measured and the fallback used.
static void gf_cal_note(gf_dem_calibration *c, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void gf_cal_note(gf_dem_calibration *c, const char *fmt, ...)
{
    if (c->nnotes >= sizeof c->notes / sizeof c->notes[0]) return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(c->notes[c->nnotes++], sizeof c->notes[0], fmt, ap);
    va_end(ap);
}

// ---------------------------------------------------------------------------
// One estimate of every measured quantity over one window.

typedef struct gf_cal_est {
    double q, beta, slope, icpt, bp, p, slice;
    size_t nheights;
} gf_cal_est;

static double gf_cal_value(const gf_measure_out *m, const char *key)
{
    for (size_t k = 0; k < m->nvalues; k++)
        if (!strcmp(m->values[k].key, key)) return m->values[k].value;
    return NAN;
}

static const gf_table *gf_cal_table(const gf_measure_out *m, const char *name)
{
    for (size_t k = 0; k < m->ntables; k++)
        if (!strcmp(m->tables[k].name, name)) return &m->tables[k];
    return NULL;
}

/// Var = slope z + icpt over the heights whose Gaussian fits are trustworthy:
/// finite, and narrow enough (sd < W / 5) that the tails stay inside the walls.
static void gf_cal_variance(const gf_measure_out *m, double width, gf_cal_est *e)
{
    const gf_table *t = gf_cal_table(m, "velocity_variance");
    double z[16], v[16];
    size_t n = 0;
    for (size_t r = 0; t && r < t->nrow && n < 16; r++) {
        double zz = t->v[r * t->ncol], var = t->v[r * t->ncol + 1];
        if (isfinite(var) && var > 0 && sqrt(var) < width / GF_CAL_WALLSD) {
            z[n] = zz;
            v[n++] = var;
        }
    }
    e->nheights = n;
    e->slope = e->icpt = NAN;
    if (n >= 2 && gf_fit_linear(z, v, n, &e->slope, &e->icpt) != GF_OK) e->slope = e->icpt = NAN;
}

/// The particles in a spot ball of radius rs, averaged over balls placed where
/// spots go: heights in the slice, x Gaussian with the spot spread there (the
/// profile variance less the ball's own r_s^2 / 5), y uniform, both no closer
/// than d_w to a wall, in every frame of the window. Walls cut these balls.
/// In a cylinder x and y are both Gaussian with that per-axis spread (the
/// radial profile's), redrawn until the centre clears the wall by d_w.
static double gf_cal_balls(const gf_series *s, const gf_analysis_opts *o, const gf_cal_est *e, double rs, double dw,
                           size_t k0, size_t k1)
{
    gf_rng rng;
    gf_rng_seed(&rng, 20090701u, 3);
    gf_container_defs cd;
    gf_config_container_defs(&s->cfg, &cd);
    double hw = 0.5 * cd.width - dw, hd = 0.5 * cd.depth - dw;
    gf_container ctr = gf_container_make(&s->cfg);
    const bool cyl = gf_container_profile_radial(&ctr); // radial profiles: x and y both Gaussian
    double sum = 0.0, n = 0.0, r2 = rs * rs;
    for (size_t k = k0; k < k1; k++) {
        const gf_packing *p = &s->frames[k].pk;
        for (int b = 0; b < GF_CAL_BALLS; b++) {
            double z = o->dens_z0 + (o->dens_z1 - o->dens_z0) * gf_rng_uniform(&rng);
            double var = isfinite(e->slope) ? e->slope * z + e->icpt - r2 / 5.0 : 1.0;
            double sd = sqrt(fmax(var, 1.0)), x, y;
            if (cyl) {
                int tries = 0;
                do { // both Box-Muller normals, redrawn outside the walk's room
                    double u = gf_rng_uniform_pos(&rng), v = gf_rng_uniform(&rng), g = sd * sqrt(-2.0 * log(u));
                    x = g * cos(2.0 * GF_CAL_PI * v);
                    y = g * sin(2.0 * GF_CAL_PI * v);
                } while (!ctr.ops->inside_xy(&ctr, x, y, dw) && ++tries < 1000);
                if (tries >= 1000) x = y = 0.0; // a spread far wider than the container: the axis
            } else {
                do { // Box-Muller, redrawn outside the walk's room
                    double u = gf_rng_uniform_pos(&rng), v = gf_rng_uniform(&rng);
                    x = sd * sqrt(-2.0 * log(u)) * cos(2.0 * GF_CAL_PI * v);
                } while (fabs(x) > hw);
                y = hd * (2.0 * gf_rng_uniform(&rng) - 1.0);
            }
            size_t c = 0;
            for (size_t i = 0; i < p->n; i++) {
                double dz = p->z[i] - z;
                if (dz * dz >= r2) continue;
                double dx = p->x[i] - x, dy = p->y[i] - y;
                c += dx * dx + dy * dy + dz * dz < r2;
            }
            sum += (double)c;
            n += 1.0;
        }
    }
    return n > 0 ? sum / n : NAN;
}

/// All the measured quantities over [t0, t1].
static gf_status gf_cal_measure(const gf_series *s, const gf_analysis_opts *base, double t0, double t1, double rs,
                                double dw, gf_cal_est *e)
{
    gf_analysis_opts o = *base;
    o.t0 = t0;
    o.t1 = t1;
    gf_measure_out m;
    gf_status st;
    memset(e, 0, sizeof *e);
#define GF_CAL_RUN(fn, body)                                                                                           \
    do {                                                                                                               \
        memset(&m, 0, sizeof m);                                                                                       \
        st = fn(s, &o, &m);                                                                                            \
        if (st == GF_OK) {                                                                                             \
            body;                                                                                                      \
        }                                                                                                              \
        gf_measure_free(&m);                                                                                           \
        if (st != GF_OK) return st;                                                                                    \
    } while (0)
    GF_CAL_RUN(gf_measure_outflow, e->q = gf_cal_value(&m, "flow_rate"));
    GF_CAL_RUN(gf_measure_correlation, e->beta = gf_cal_value(&m, "correlation_length"));
    GF_CAL_RUN(gf_measure_velocity, gf_cal_variance(&m, gf_cal_width(&s->cfg), e));
    GF_CAL_RUN(gf_measure_density, e->slice = gf_cal_value(&m, "density_steady"));
    GF_CAL_RUN(gf_measure_diffusion, e->bp = gf_cal_value(&m, "diffusion_length"));
#undef GF_CAL_RUN
    size_t k0, k1;
    gf_window_frames(s, t0, t1, &k0, &k1);
    if (!(rs > 0)) rs = e->beta / GF_DEM_BETA_PER_RS;
    if ((st = gf_stop_check(o.stop, "calibration")) != GF_OK) return st;
    e->p = isfinite(rs) ? gf_cal_balls(s, &o, e, rs, dw, k0, k1) : NAN;
    return GF_OK;
}

/// Mean and standard error of the finite values among n.
static gf_dem_value gf_cal_stat(const double *v, size_t n, double full)
{
    double s = 0.0, s2 = 0.0;
    size_t m = 0;
    for (size_t k = 0; k < n; k++)
        if (isfinite(v[k])) {
            s += v[k];
            m++;
        }
    if (m < 2) return (gf_dem_value){full, NAN};
    double mean = s / (double)m;
    for (size_t k = 0; k < n; k++)
        if (isfinite(v[k])) s2 += (v[k] - mean) * (v[k] - mean);
    return (gf_dem_value){full, sqrt(s2 / (double)(m - 1) / (double)m)};
}

/// Relative uncertainty, treating an unknown one as 0 (so that others still show).
static double gf_cal_rel(gf_dem_value v) { return isfinite(v.err) && v.value != 0 ? v.err / fabs(v.value) : 0.0; }

gf_status gf_dem_calibrate(const gf_series *s, const gf_analysis_opts *o, const gf_config *cfg, gf_dem_calibration *c)
{
    memset(c, 0, sizeof *c);
    if (s->nframes < 3) return gf_error_set(GF_ERR_PARAM, "calibration needs at least 3 snapshots, got %zu", s->nframes);
    double t0, t1;
    gf_analysis_window(o, s, &t0, &t1);
    size_t k0, k1;
    size_t nf = gf_window_frames(s, t0, t1, &k0, &k1);
    if (nf < 3)
        return gf_error_set(GF_ERR_PARAM, "the window %g..%g tau holds %zu snapshots; calibration needs at least 3", t0,
                            t1, nf);
    c->t0 = t0;
    c->t1 = t1;
    gf_spot_params sp;
    gf_config_spot_params(cfg, &sp);
    double dw = sp.wall_distance, dz = sp.step_z;
    gf_cal_est full;
    gf_status st = gf_cal_measure(s, o, t0, t1, 0.0, dw, &full);
    if (st != GF_OK) return st;
    double rs_full = full.beta / GF_DEM_BETA_PER_RS;
    // window.parts sub-windows of equal length (each with at least 3 frames when possible).
    size_t K = gf_dem_window_parts(o, nf, GF_CAL_MAXPARTS);
    c->nparts = K;
    double v[7][GF_CAL_MAXPARTS];
    for (size_t j = 0; j < K; j++) {
        double a = t0 + (t1 - t0) * (double)j / (double)K, b = t0 + (t1 - t0) * (double)(j + 1) / (double)K;
        gf_cal_est e;
        if ((st = gf_stop_check(o->stop, "calibration")) != GF_OK) return st;
        if ((st = gf_cal_measure(s, o, a, b, rs_full, dw, &e)) != GF_OK) return st;
        v[0][j] = e.q;
        v[1][j] = e.beta;
        v[2][j] = e.slope;
        v[3][j] = e.bp;
        v[4][j] = e.p;
        v[5][j] = e.slice;
        v[6][j] = e.nheights >= 2 ? 1.0 : 0.0;
    }
    c->flow_rate = gf_cal_stat(v[0], K, full.q);
    c->corr_length = gf_cal_stat(v[1], K, full.beta);
    c->var_slope = gf_cal_stat(v[2], K, full.slope);
    c->var_heights = full.nheights;
    c->diff_length = gf_cal_stat(v[3], K, full.bp);
    c->ball_count = gf_cal_stat(v[4], K, full.p);
    c->slice_steady = gf_cal_stat(v[5], K, full.slice);
    c->slice_z0 = o->dens_z0;
    c->slice_z1 = o->dens_z1;
    const gf_packing *p0 = &s->frames[0].pk;
    size_t n0 = 0;
    for (size_t i = 0; i < p0->n; i++) n0 += p0->z[i] > o->dens_z0 && p0->z[i] < o->dens_z1;
    c->slice_initial = (gf_dem_value){(double)n0, sqrt((double)n0) * 0.0};
    double h = o->dens_z1 - o->dens_z0;
    double phi = c->slice_steady.value * (GF_CAL_PI / 6.0) / gf_cal_volume(&s->cfg, o->dens_z0, o->dens_z1);

    if (!(c->flow_rate.value > 0))
        return gf_error_set(GF_ERR_PARAM,
                            "no outflow in the window %g..%g tau (flow rate %g): nothing to calibrate on; check the "
                            "window (window.t0, window.t1) and the container (orifice, exit_z)",
                            t0, t1, c->flow_rate.value);
    // r_s = beta / 0.72 (thesis Sec. 3.3). A beta beyond half the region is
    // no measurement (the fit ran off), nor one below the fit's first
    // distance: the thesis' r_s, left to refinement.
    double rs = rs_full;
    if (!isfinite(full.beta) || full.beta < GF_DEM_BETA_MIN || full.beta > 0.5 * o->corr_size) {
        gf_cal_note(c, "velocity correlation length not measurable (beta = %.3g d in a %.3g d region): spot.radius = "
                       "%.3g d (the thesis' value)", full.beta, o->corr_size, GF_CAL_RS_FALLBACK);
        rs = GF_CAL_RS_FALLBACK;
        c->radius = (gf_dem_value){rs, NAN};
    } else {
        c->radius = (gf_dem_value){rs, c->corr_length.err / GF_DEM_BETA_PER_RS};
    }
    // Var(x_s) grows by Var(dx_s) per step of dz: d Var / dz = 2 b_s (thesis Sec. 3.3).
    c->b_s = (gf_dem_value){0.5 * c->var_slope.value, 0.5 * c->var_slope.err};
    if (!isfinite(c->b_s.value) || !(c->b_s.value > 0)) {
        double bs = sp.step_xy * sp.step_xy / (4.0 * dz);
        gf_cal_note(c, "the %s profile variance does not grow with height (slope %.3g over %zu heights): b_s = %.3g "
                       "from the configured spot.step_xy = %.3g", gf_velocity_profile_name(&s->cfg), c->var_slope.value,
                    c->var_heights, bs, sp.step_xy);
        c->b_s = (gf_dem_value){bs, NAN};
    }
    // BCC walk: dx_s = +-dx with probability 1/2, so Var(dx_s) = dx^2 / 2 = 2 b_s dz.
    double dx = sqrt(4.0 * c->b_s.value * dz);
    c->step_xy = (gf_dem_value){dx, 0.5 * dx * gf_cal_rel(c->b_s)};
    // b_p = Var(dx_s / w) / (2 dz_s / w) = b_s / w with w the displacement ratio.
    double w = c->b_s.value / c->diff_length.value;
    if (!isfinite(w) || !(w > 1.0)) {
        gf_cal_note(c, "particle diffusion not measurable (b_p = %.3g d): spot.w = %.4g (configured)",
                    c->diff_length.value, sp.w);
        c->w = (gf_dem_value){sp.w, NAN};
    } else {
        c->w = (gf_dem_value){w, w * hypot(gf_cal_rel(c->b_s), gf_cal_rel(c->diff_length))};
    }
    w = c->w.value;
    // Mass balance: each spot carries p / w particle volumes, so Q = lambda p / w.
    c->ball_count_bulk = phi * 8.0 * rs * rs * rs; // phi (4/3 pi r^3) / (pi / 6)
    double p = c->ball_count.value;
    if (rs != rs_full || !isfinite(p) || !(p > 0)) {
        p = isfinite(c->ball_count_bulk) && c->ball_count_bulk > 0 ? c->ball_count_bulk
                                                                   : 0.6 * 8.0 * rs * rs * rs;
        if (rs == rs_full)
            gf_cal_note(c, "particles in a spot ball not measurable: p = %.4g (phi V_ball / V_p)", p);
        c->ball_count = (gf_dem_value){p, NAN};
    }
    double lam = c->flow_rate.value * w / p;
    c->insertion_rate = (gf_dem_value){lam, lam * sqrt(pow(gf_cal_rel(c->flow_rate), 2) + pow(gf_cal_rel(c->w), 2) +
                                                      pow(gf_cal_rel(c->ball_count), 2))};
    // Spots cross the slice at mu dz, each carrying p / w of free volume, so the
    // slice holds Q h / (mu dz) particles fewer than the packing at rest.
    double dn = c->slice_initial.value - c->slice_steady.value;
    double mu = c->flow_rate.value * h / (dz * dn);
    double rel_dn = isfinite(c->slice_steady.err) && dn != 0 ? c->slice_steady.err / fabs(dn) : 0.0;
    // A drop within 2 of its uncertainties (or none) is no measurement.
    double dn_err = isfinite(c->slice_steady.err) ? c->slice_steady.err : 0.0;
    if (!isfinite(mu) || !(dn > 2.0 * dn_err) || !(mu > 0)) {
        gf_cal_note(c, "no measurable density drop in the slice %.3g < z < %.3g (%.4g particles at rest, %.4g +- %.2g in "
                       "flow): spot.move_rate = %.4g (configured)", o->dens_z0, o->dens_z1, c->slice_initial.value,
                    c->slice_steady.value, c->slice_steady.err, sp.move_rate);
        c->move_rate = (gf_dem_value){sp.move_rate, NAN};
    } else {
        c->move_rate = (gf_dem_value){mu, mu * hypot(gf_cal_rel(c->flow_rate), rel_dn)};
    }
    if (!isfinite(lam) || !(lam > 0))
        return gf_error_set(GF_ERR_PARAM, "calibration failed: lambda = %g from Q = %g, w = %g, p = %g", lam,
                            c->flow_rate.value, w, p);
    return GF_OK;
}

gf_status gf_dem_calibration_apply(const gf_dem_calibration *c, gf_config *cfg)
{
    // The insertion margin and r_e go back to auto: they follow the new radius.
    gf_config_set_spot_fit(cfg, c->radius.value, c->w.value, c->insertion_rate.value, c->move_rate.value,
                           c->step_xy.value);
    return gf_config_validate(cfg);
}

static void gf_cal_line(FILE *f, const char *name, gf_dem_value v, const char *unit, const char *thesis)
{
    char err[32] = "?";
    if (isfinite(v.err)) snprintf(err, sizeof err, "%.3g", v.err);
    fprintf(f, "  %-34s %12.5g +- %-10s %-8s %s\n", name, v.value, err, unit, thesis);
}

void gf_dem_calibration_print(const gf_dem_calibration *c, FILE *f)
{
    fprintf(f, "measured over %.4g..%.4g tau (uncertainties from %zu sub-windows):\n", c->t0, c->t1, c->nparts);
    gf_cal_line(f, "flow rate Q", c->flow_rate, "1/tau", "(DEM of the papers: 131.1)");
    gf_cal_line(f, "velocity correlation length beta", c->corr_length, "d", "(thesis: 1.87)");
    char h[64];
    snprintf(h, sizeof h, "(%zu heights; thesis: 2.28)", c->var_heights);
    gf_cal_line(f, "d Var(v_z profile) / dz", c->var_slope, "d", h);
    gf_cal_line(f, "particle diffusion length b_p", c->diff_length, "d", "(thesis: 2.86e-3)");
    char p[64];
    snprintf(p, sizeof p, "(bulk phi V_ball / V_p: %.4g)", c->ball_count_bulk);
    gf_cal_line(f, "particles in a spot ball p", c->ball_count, "", p);
    char sl[64];
    snprintf(sl, sizeof sl, "slice %.4g < z < %.4g", c->slice_z0, c->slice_z1);
    gf_cal_line(f, "particles in the slice at rest", c->slice_initial, "", sl);
    gf_cal_line(f, "particles in the slice in flow", c->slice_steady, "", "(thesis: 9400 -> 8850)");
    fprintf(f, "the five spot parameters:\n");
    gf_cal_line(f, "spot.radius r_s = beta / 0.72", c->radius, "d", "(thesis: 2.60)");
    gf_cal_line(f, "b_s = slope / 2", c->b_s, "d", "(thesis: 1.14)");
    gf_cal_line(f, "spot.step_xy = sqrt(4 b_s dz)", c->step_xy, "d", "(thesis: 0.68)");
    gf_cal_line(f, "spot.w = b_s / b_p", c->w, "", "(thesis: 1 / 2.50e-3 = 400)");
    gf_cal_line(f, "spot.insertion_rate = Q w / p", c->insertion_rate, "1/tau", "(2009 paper: 375)");
    gf_cal_line(f, "spot.move_rate = Q h / (dz dN)", c->move_rate, "1/tau", "(2009 paper: 28)");
    for (size_t k = 0; k < c->nnotes; k++) fprintf(f, "note: %s\n", c->notes[k]);
}
