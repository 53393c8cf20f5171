// SPDX-License-Identifier: MIT
// Velocity, diffusion and correlation measurements (thesis Sec. 3.3, 2009
// paper Fig. 8) on synthetic series built in memory with known answers.
#include "support.h"

#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "analysis/steady_height.h"
#include "core/rng.h"
#include "granflow/analysis.h"
#include "granflow/dem.h"

static double normal(gf_rng *r)
{
    return sqrt(-2.0 * log(gf_rng_uniform_pos(r))) * cos(6.283185307179586 * gf_rng_uniform(r));
}

/// A series of n empty frames at the given times, default config (50 x 8 silo).
static gf_series make_series(size_t n, const double *times)
{
    gf_series s = {0};
    s.nframes = n;
    s.frames = GF_NEW(gf_frame, n);
    assert_non_null(s.frames);
    for (size_t k = 0; k < n; k++) s.frames[k].time = times[k];
    s.cfg = gf_config_default();
    return s;
}

static void push(gf_frame *f, int64_t id, double x, double y, double z)
{
    assert_int_equal(gf_packing_push(&f->pk, id, 1, x, y, z, 0.5), GF_OK);
}

static double cell(const gf_table *t, size_t row, size_t col) { return t->v[row * t->ncol + col]; }

// ---------------------------------------------------------------------------
// Velocity: v_z(x, z) = -A exp(-x^2 / (2 (2 z + 1))), so Var(z) = 2 z + 1.

#define VEL_A 0.5

static double vz_model(double x, double z) { return -VEL_A * exp(-x * x / (2.0 * (2.0 * z + 1.0))); }

static void velocity_recovers_variance_line(void **state)
{
    (void)state;
    // Frames at t = 0, 2, 4; the default window (a quarter in, to the end) is
    // [1, 4], so only the pair (2, 4) counts and frame 0 holds decoys whose
    // velocity from frame 0 would spoil every profile. Particles sit on a grid
    // of midpoints (x = k + 1/2: one per 1 d bin; integer z; y = -2, 0, 2) and
    // move from z - v dt/2 to z + v dt/2, so each measured velocity is exactly
    // v_z at its bin. Every 7th particle has left by t = 4; frame 4 also holds
    // particles absent at t = 2, and is stored in reverse order.
    const double times[3] = {0.0, 2.0, 4.0}, dt = 2.0;
    gf_series s = make_series(3, times);
    int64_t id = 0;
    size_t pairs = 0;
    gf_packing late = {0}; // frame 2 before it is reversed
    for (int zi = 5; zi <= 65; zi++)
        for (int xi = -25; xi < 25; xi++)
            for (int yi = -1; yi <= 1; yi++) {
                double x = xi + 0.5, y = 2.0 * yi, z = zi, v = vz_model(x, z);
                id++;
                push(&s.frames[0], id, x, y, 30.0 + 0.37 * (double)(id % 11)); // decoy start
                push(&s.frames[1], id, x, y, z - 0.5 * v * dt);
                if (id % 7 == 0) continue; // gone by t = 4
                assert_int_equal(gf_packing_push(&late, id, 1, x, y, z + 0.5 * v * dt, 0.5), GF_OK);
                pairs++;
            }
    for (size_t i = late.n; i-- > 0;) push(&s.frames[2], late.id[i], late.x[i], late.y[i], late.z[i]);
    for (int k = 1; k <= 100; k++) push(&s.frames[2], id + k, 0.0, 0.0, 30.0 + 0.1 * k); // newcomers
    gf_packing_free(&late);
    s.n_initial = s.frames[0].pk.n;

    gf_analysis_opts o = gf_analysis_opts_default();
    gf_measure_out out = {0};
    assert_int_equal(gf_measure_velocity(&s, &o, &out), GF_OK);

    // Every height 10 .. 60 is an exact Gaussian: amplitude A, centre 0,
    // variance 2 h + 1, recovered to the fit's convergence (1e-8).
    const gf_table *tv = gf_test_table(&out, "velocity_variance");
    assert_int_equal(tv->nrow, 6);
    for (size_t r = 0; r < 6; r++) {
        double h = 10.0 * (double)(r + 1);
        gf_assert_near(cell(tv, r, 0), h, 0.0);
        gf_assert_near(cell(tv, r, 1), 2.0 * h + 1.0, 1e-8 * (2.0 * h + 1.0));
        gf_assert_near(cell(tv, r, 2), VEL_A, 1e-8);
        gf_assert_near(cell(tv, r, 3), 0.0, 1e-8);
    }
    gf_assert_near(gf_test_value(&out, "velocity_variance_slope"), 2.0, 1e-8);
    gf_assert_near(gf_test_value(&out, "velocity_variance_intercept"), 1.0, 1e-6);

    // Profiles: 50 bins per height, data and fit both equal to v_z.
    const gf_table *tp = gf_test_table(&out, "velocity_profiles");
    assert_int_equal(tp->nrow, 6 * 50);
    for (size_t r = 0; r < tp->nrow; r++) {
        double v = vz_model(cell(tp, r, 1), cell(tp, r, 0));
        gf_assert_near(cell(tp, r, 2), v, 1e-12);
        gf_assert_near(cell(tp, r, 3), v, 1e-8);
    }

    // The field: one bin per grid row/column, 3 samples (y) less the exits,
    // and its total equals the number of particles present at both times.
    const gf_table *tf = gf_test_table(&out, "velocity_field");
    assert_int_equal(tf->nrow, 61 * 50);
    double total = 0.0;
    for (size_t r = 0; r < tf->nrow; r++) {
        double x = cell(tf, r, 0), z = cell(tf, r, 1) - 0.5; // bin [z, z + 1) holds the grid row z
        gf_assert_near(cell(tf, r, 2), 0.0, 0.0);
        gf_assert_near(cell(tf, r, 3), vz_model(x, z), 1e-12);
        total += cell(tf, r, 4);
    }
    gf_assert_near(total, (double)pairs, 0.0);
    assert_non_null(out.gnuplot);
    assert_non_null(strstr(out.gnuplot, "Var (d^2)"));
    assert_non_null(strstr(out.gnuplot, "2.28*x+1.60"));
    gf_measure_free(&out);
    gf_series_free(&s);
}

// ---------------------------------------------------------------------------
// A spot-like start-up (issue 27): at height z the flow starts narrow and
// weak (40% of the flux, a quarter of the variance) and takes its steady
// Gaussian, Var = 2 z + 1, only after t = z / c. Averaging every frame pair
// at every height mixes the start-up into the upper profiles; the window per
// height recovers the late width, and reports a height still building up at
// the end as having no steady frames.

#define RISE_C 4.0 // d/tau

static double vz_startup(double x, double z, double t)
{
    double var = 2.0 * z + 1.0;
    if (t < z / RISE_C) var *= 0.25;
    double amp = t < z / RISE_C ? 0.8 * VEL_A : VEL_A; // 0.8 A x sqrt(1/4) = 40% of the flux
    return -amp * exp(-x * x / (2.0 * var));
}

// 49 frames, t = 0 .. 24 tau; each pair k has its own particles, present
// in frames k and k + 1 only, at the bin centres of heights 10, 20, ...,
// 10 nh, so that pair measures vz(x, z, t_k + 1/4, arg) exactly.
static gf_series pair_series(int nh, double (*vz)(double x, double z, double t, const void *arg), const void *arg)
{
    enum { NF = 49 };
    double times[NF];
    for (int k = 0; k < NF; k++) times[k] = 0.5 * k;
    gf_series s = make_series(NF, times);
    int64_t id = 0;
    for (int k = 0; k + 1 < NF; k++)
        for (int h = 1; h <= nh; h++)
            for (int xi = -25; xi < 25; xi++) {
                double x = xi + 0.5, z = 10.0 * h, v = vz(x, z, times[k] + 0.25, arg);
                id++;
                push(&s.frames[k], id, x, 0.0, z - 0.25 * v);
                push(&s.frames[k + 1], id, x, 0.0, z + 0.25 * v);
            }
    s.n_initial = s.frames[0].pk.n;
    return s;
}

static double vz_startup_arg(double x, double z, double t, const void *arg)
{
    (void)arg;
    return vz_startup(x, z, t);
}

static void startup_measure(gf_vel_window mode, bool spot_run, gf_measure_out *out)
{
    gf_series s = pair_series(6, vz_startup_arg, NULL);
    if (spot_run) { // the spots rise at mu step_z = 40 x 0.1 = RISE_C
        s.spot_run = true;
        assert_int_equal(gf_config_set_key(&s.cfg, "spot.move_rate", "40"), GF_OK);
        assert_int_equal(gf_config_set_key(&s.cfg, "spot.step_z", "0.1"), GF_OK);
    }
    gf_analysis_opts o = gf_analysis_opts_default();
    o.t0 = 0.0; // the whole run: the outflow's window would start at once
    o.t1 = 24.0;
    o.vel_window = (int)mode;
    assert_int_equal(gf_measure_velocity(&s, &o, out), GF_OK);
    gf_series_free(&s);
}

// A reference still widening (issue 27, docs/dem.md: the DEM's long
// references widen for about one residence time): at every height the
// profile's variance grows linearly in time, 2 z + 1 at t = 0 to 1.5 times
// that at t = 24, its flux held (amplitude times the width). Compare's
// flow statistics flag the drift (later half of the 8 sub-windows against
// the earlier, > 3 standard errors, the right size and sign); the same
// series at a constant width is not flagged.
static double vz_widening(double x, double z, double t, const void *arg)
{
    double var = (2.0 * z + 1.0) * (*(const bool *)arg ? 1.0 + 0.5 * t / 24.0 : 1.0);
    return -VEL_A * sqrt((2.0 * z + 1.0) / var) * exp(-x * x / (2.0 * var));
}

static void widening_series(bool widen, gf_dem_flowstats *fs)
{
    gf_series s = pair_series(4, vz_widening, &widen);
    gf_analysis_opts o = gf_analysis_opts_default();
    o.t0 = 0.0;
    o.t1 = 24.0;
    o.window_parts = 8;
    o.vel_window = GF_VEL_WINDOW_RUN;
    o.vel_nheights = 4;
    for (int h = 0; h < 4; h++) o.vel_heights[h] = 10.0 * (h + 1);
    assert_int_equal(gf_dem_flowstats_measure(&s, &o, false, fs), GF_OK);
    gf_series_free(&s);
}

static void flowstats_flag_a_widening_reference(void **state)
{
    (void)state;
    gf_dem_flowstats w, c;
    widening_series(true, &w);
    widening_series(false, &c);
    assert_int_equal(w.parts, 8);
    assert_int_equal(w.nz, 4);
    for (size_t z = 0; z < 4; z++) {
        // halves at t = 6 and 18 on average: (1.375 - 1.125) / 1.25 = +20%
        print_message("z = %g: drift %+.3f (%.1f se); constant: %+.3f (%.1f se)\n", w.z[z], w.var_drift[z],
                      w.var_drift_se[z], c.var_drift[z], c.var_drift_se[z]);
        gf_assert_near(w.var_drift[z], 0.20, 0.02);
        assert_true(w.var_drift_se[z] > 3.0);
        assert_true(fabs(c.var_drift[z]) < 1e-6);
        assert_false(fabs(c.var_drift_se[z]) > 3.0);
    }
}

static void velocity_window_per_height(void **state)
{
    (void)state;
    gf_measure_out run = {0}, per = {0};
    startup_measure(GF_VEL_WINDOW_RUN, false, &run);
    startup_measure(GF_VEL_WINDOW_HEIGHT, false, &per);
    const gf_table *tr = gf_test_table(&run, "velocity_variance"), *tp = gf_test_table(&per, "velocity_variance");
    assert_int_equal(tr->nrow, 6);
    assert_int_equal(tp->nrow, 6);
    assert_int_equal(tp->ncol, 7);
    // Every pair at every height: the start-up narrows the profiles by more
    // than 5% from z = 20 up (the test fails on the window of before).
    for (size_t r = 1; r < 5; r++) {
        double want = 2.0 * cell(tr, r, 0) + 1.0;
        assert_true(fabs(cell(tr, r, 1) - want) > 0.05 * want);
        assert_true(cell(tr, r, 6) == 1.0);
    }
    // Per height: z = 10 .. 50 within 5% of 2 z + 1, each from the end of
    // its start-up (z / c, to the frame pair: a chunk straddling it may be let in).
    for (size_t r = 0; r < 5; r++) {
        double z = cell(tp, r, 0), want = 2.0 * z + 1.0;
        assert_true(cell(tp, r, 6) == 1.0);
        gf_assert_near(cell(tp, r, 1), want, 0.05 * want);
        assert_true(cell(tp, r, 4) >= z / RISE_C - 3.0 && cell(tp, r, 4) <= z / RISE_C + 0.5);
        gf_assert_near(cell(tp, r, 5), 24.0, 0.0);
    }
    // z = 60 speeds up until t = 15, in the last half of the run: no steady
    // frames, reported and not fitted.
    assert_true(cell(tp, 5, 6) == 0.0);
    assert_true(isnan(cell(tp, 5, 1)) && isnan(cell(tp, 5, 4)));
    gf_assert_near(gf_test_value(&per, "velocity_unsteady_heights"), 1.0, 0.0);
    gf_assert_near(gf_test_value(&run, "velocity_unsteady_heights"), 0.0, 0.0);
    gf_assert_near(gf_test_value(&per, "velocity_variance_slope"), 2.0, 0.1);
    gf_measure_free(&run);
    gf_measure_free(&per);
}

// The same start-up as a spot run's (issue 27 item 2): each height's window
// starts when the spots born at t = 0 have risen there (z + 2 r_s over
// mu step_z, plus 3 sd of the arrival), whatever the noise says; z = 60,
// steady only from t = 15, is then measured from t = 18.2 with its late width.
static void velocity_window_by_spot_rise(void **state)
{
    (void)state;
    gf_measure_out per = {0};
    startup_measure(GF_VEL_WINDOW_HEIGHT, true, &per);
    const gf_table *tp = gf_test_table(&per, "velocity_variance");
    assert_int_equal(tp->nrow, 6);
    for (size_t r = 0; r < 6; r++) {
        double z = cell(tp, r, 0), want = 2.0 * z + 1.0;
        double ready = gf_steady_height_rise_time(z, -2.6, 2.6, 0.1, 40.0);
        gf_assert_near(ready, ((z + 5.2) / 0.1 + 3.0 * sqrt((z + 5.2) / 0.1)) / 40.0, 1e-12);
        assert_true(cell(tp, r, 6) == 1.0);
        gf_assert_near(cell(tp, r, 1), want, 0.05 * want);
        assert_true(cell(tp, r, 4) >= ready && cell(tp, r, 4) < ready + 0.5); // the first pair from then on
    }
    gf_assert_near(gf_test_value(&per, "velocity_unsteady_heights"), 0.0, 0.0);
    gf_measure_free(&per);
}

// The rise's verdict by hand: a spot run's flow at z = 10 d (docs/dem.md
// experiment 4, runs/fs27/tall-s1), steady from ~6 tau with slow swings of
// 5-10% over a few pairs, which the noise test reads as "still speeding up"
// (the last quarter -0.122 against the third's -0.113); the rise time says
// steady from 5.5 tau. A height with no flow, or reached too late, keeps the
// noise's verdict.
static void steady_height_by_rise_cases(void **state)
{
    (void)state;
    const double swing[64] = {0.0,    0.0,    0.0,    0.0,    -0.0,   -0.001, -0.02,  -0.057, -0.082, -0.091, -0.107,
                              -0.113, -0.128, -0.123, -0.114, -0.105, -0.109, -0.111, -0.12,  -0.11,  -0.115, -0.115,
                              -0.111, -0.105, -0.112, -0.111, -0.106, -0.108, -0.107, -0.112, -0.121, -0.12,  -0.116,
                              -0.112, -0.119, -0.12,  -0.113, -0.121, -0.109, -0.108, -0.109, -0.106, -0.104, -0.109,
                              -0.11,  -0.115, -0.123, -0.118, -0.115, -0.128, -0.126, -0.128, -0.126, -0.132, -0.134,
                              -0.123, -0.118, -0.113, -0.112, -0.118, -0.115, -0.119, -0.119, -0.129};
    double t[64];
    for (size_t j = 0; j < 64; j++) t[j] = 0.5 * (double)j;
    gf_steady_height v = gf_steady_height_find(swing, 64);
    assert_false(v.steady);
    assert_non_null(strstr(v.why, "speeding up"));
    gf_steady_height_by_rise(&v, t, 64, 5.3);
    assert_true(v.steady);
    assert_int_equal(v.first, 11); // the pair starting at 5.5 tau
    assert_non_null(strstr(v.why, "risen"));
    // Reached in the last 7 pairs only (fewer than an eighth): the noise's verdict stands.
    v = gf_steady_height_find(swing, 64);
    gf_steady_height_by_rise(&v, t, 64, 28.3);
    assert_false(v.steady);
    assert_non_null(strstr(v.why, "speeding up"));
    // Nothing flows: not steady, however early the spots arrive.
    const double none[8] = {0, 0, 0, 0, 0, 0, 0, 0};
    v = gf_steady_height_find(none, 8);
    gf_steady_height_by_rise(&v, t, 8, 0.0);
    assert_false(v.steady);
    assert_true(v.no_flow);
}

// The verdict on one height, by hand: the first pair of the steady part.
static void steady_height_cases(void **state)
{
    (void)state;
    const double step[8] = {0, 0, 0, -1, -1, -1, -1, -1};
    gf_steady_height v = gf_steady_height_find(step, 8);
    assert_true(v.steady);
    assert_int_equal(v.first, 3); // the chunk [3, 5) is the first at the late value -1
    gf_assert_near(v.late, -1.0, 0.0);
    const double flat[8] = {-1, -1, -1, -1, -1, -1, -1, -1};
    v = gf_steady_height_find(flat, 8);
    assert_true(v.steady);
    assert_int_equal(v.first, 0);
    const double none[8] = {0, 0, 0, 0, 0, 0, 0, 0};
    assert_false(gf_steady_height_find(none, 8).steady); // no downward flow
    const double up[8] = {0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5};
    assert_false(gf_steady_height_find(up, 8).steady);
    const double ramp[8] = {0, 0, 0, 0, -0.2, -0.4, -0.8, -1};
    v = gf_steady_height_find(ramp, 8);
    assert_false(v.steady); // still speeding up at the end
    assert_non_null(strstr(v.why, "speeding up"));
    const double few[3] = {0, -1, -1};
    v = gf_steady_height_find(few, 3);
    assert_true(v.steady);
    assert_int_equal(v.first, 0); // too few pairs to judge: all of them
    const double holes[8] = {NAN, 0, NAN, -1, -1, NAN, -1, -1};
    v = gf_steady_height_find(holes, 8);
    assert_true(v.steady);
    assert_int_equal(v.first, 2); // a chunk of empty pairs and -1 counts as -1
}

static void velocity_depth_profile(void **state)
{
    (void)state;
    // v_z = -(1 + 0.1 y) in the test region |x| < 10, 50 < z < 70, particles at
    // the centres of the 32 depth bins of 0.25 d (x in {-5, 0, 5}, z in {55,
    // 60, 65}: 9 per bin). Particles just outside the region (|x| = 10.5, z =
    // 49.5 or 70.5) move at -5 and must not count. Window set to [0, 1].
    const double times[2] = {0.0, 1.0};
    gf_series s = make_series(2, times);
    int64_t id = 0;
    for (int j = 0; j < 32; j++) {
        double y = -4.0 + 0.25 * (j + 0.5);
        for (int a = -1; a <= 1; a++)
            for (int b = -1; b <= 1; b++) {
                double x = 5.0 * a, z = 60.0 + 5.0 * b, v = -(1.0 + 0.1 * y);
                id++;
                push(&s.frames[0], id, x, y, z - 0.5 * v);
                push(&s.frames[1], id, x, y, z + 0.5 * v);
            }
        const double out_xz[3][2] = {{10.5, 60.0}, {0.0, 49.5}, {-3.0, 70.5}};
        for (int k = 0; k < 3; k++) {
            id++;
            push(&s.frames[0], id, out_xz[k][0], y, out_xz[k][1] + 2.5);
            push(&s.frames[1], id, out_xz[k][0], y, out_xz[k][1] - 2.5);
        }
    }
    gf_analysis_opts o = gf_analysis_opts_default();
    o.t0 = 0.0;
    o.t1 = 1.0;
    gf_measure_out out = {0};
    assert_int_equal(gf_measure_velocity(&s, &o, &out), GF_OK);
    const gf_table *td = gf_test_table(&out, "velocity_depth");
    assert_int_equal(td->nrow, 32);
    for (size_t r = 0; r < 32; r++) {
        double y = -4.0 + 0.25 * ((double)r + 0.5);
        gf_assert_near(cell(td, r, 0), y, 1e-12);
        gf_assert_near(cell(td, r, 1), -(1.0 + 0.1 * y), 1e-12);
        gf_assert_near(cell(td, r, 2), 9.0, 0.0);
    }
    // One height band (z = 60) has uniform flow: no peak, so its fit is NaN,
    // and the others have no particles: too few heights for the line.
    assert_true(isnan(gf_test_value(&out, "velocity_variance_slope")));
    gf_measure_free(&out);
    gf_series_free(&s);
}

// ---------------------------------------------------------------------------
// Cylinder: radial profiles v_z(r). v_z = -A exp(-(r - r0)^2 / (2 (2 z + 1))),
// particles at the centres of the 1 d radial bins (r = i + 1/2), 16 angles
// each, at the profile heights 10 .. 60; one frame pair.

static gf_series cylinder_series(double r0, double inner, double bump)
{
    const double times[2] = {0.0, 1.0};
    gf_series s = make_series(2, times);
    s.cfg.container_shape = GF_SHAPE_CYLINDER;
    s.cfg.container_radius = 12.5;
    s.cfg.container_width = s.cfg.container_depth = 25.0;
    s.cfg.inner_radius = inner;
    int64_t id = 0;
    for (int h = 1; h <= 6; h++)
        for (int i = 0; i < 12; i++)
            for (int k = 0; k < 16; k++) {
                double z = 10.0 * h, r = i + 0.5, th = 6.283185307179586 * (k + 0.25 * (i % 4)) / 16.0;
                double u = r - r0, v = -VEL_A * exp(-u * u / (2.0 * (2.0 * z + 1.0)));
                if (i == 0) v *= bump; // a noisy innermost bin
                id++;
                push(&s.frames[0], id, r * cos(th), r * sin(th), z - 0.5 * v);
                push(&s.frames[1], id, r * cos(th), r * sin(th), z + 0.5 * v);
            }
    s.n_initial = s.frames[0].pk.n;
    return s;
}

static gf_measure_out measure_velocity_01(const gf_series *s)
{
    gf_analysis_opts o;
    o = gf_analysis_opts_default();
    o.t0 = 0.0;
    o.t1 = 1.0;
    gf_measure_out out = {0};
    assert_int_equal(gf_measure_velocity(s, &o, &out), GF_OK);
    return out;
}

static void velocity_radial_in_cylinder(void **state)
{
    (void)state;
    gf_series s = cylinder_series(0.0, 0.0, 1.0);
    gf_measure_out out = measure_velocity_01(&s);
    // Radial profiles: 12 bins of r per height, the data exact at the bin
    // centres, and the Gaussian about the axis recovered (Var = 2 z + 1).
    const gf_table *tp = gf_test_table(&out, "velocity_profiles");
    assert_int_equal(tp->nrow, 6 * 12);
    assert_string_equal(tp->cols[1], "r_d");
    for (size_t r = 0; r < tp->nrow; r++) {
        double x = cell(tp, r, 1), z = cell(tp, r, 0);
        assert_true(x > 0.0 && x < 12.0);
        gf_assert_near(cell(tp, r, 2), -VEL_A * exp(-x * x / (2.0 * (2.0 * z + 1.0))), 1e-12);
    }
    const gf_table *tv = gf_test_table(&out, "velocity_variance");
    assert_int_equal(tv->nrow, 6);
    for (size_t r = 0; r < 6; r++) {
        double h = 10.0 * (double)(r + 1);
        gf_assert_near(cell(tv, r, 1), 2.0 * h + 1.0, 1e-6 * (2.0 * h + 1.0));
        gf_assert_near(cell(tv, r, 2), VEL_A, 1e-8);
        gf_assert_near(cell(tv, r, 3), 0.0, 1e-6);
    }
    gf_assert_near(gf_test_value(&out, "velocity_variance_slope"), 2.0, 1e-6);
    assert_non_null(strstr(out.gnuplot, "Gaussian variance of v_z(r)"));
    assert_null(strstr(out.gnuplot, "v_z(x)"));
    assert_string_equal(gf_velocity_profile_name(&s.cfg), "v_z(r)");
    gf_measure_free(&out);

    // The same particles read as a box: Cartesian v_z(x), each x bin the
    // mean over a chord of the disc, is not that Gaussian (the reason for
    // the radial profiles): its Var is off by more than 10% at some height.
    s.cfg.container_shape = GF_SHAPE_BOX;
    out = measure_velocity_01(&s);
    tv = gf_test_table(&out, "velocity_variance");
    double worst = 0.0;
    for (size_t r = 0; r < tv->nrow; r++) {
        double h = cell(tv, r, 0), rel = fabs(cell(tv, r, 1) / (2.0 * h + 1.0) - 1.0);
        if (!(rel <= worst)) worst = rel; // a NaN counts as off
    }
    print_message("Cartesian profiles of the cylinder's flow: worst Var %.1f%% off\n", 100.0 * worst);
    assert_true(worst > 0.10);
    assert_non_null(strstr(out.gnuplot, "Gaussian variance of v_z(x)"));
    assert_null(strstr(out.gnuplot, "v_z(r)"));
    assert_string_equal(gf_velocity_profile_name(&s.cfg), "v_z(x)");
    gf_measure_free(&out);
    gf_series_free(&s);

    // Around a central column the flow peaks on a ring: the fit is not
    // mirrored and its centre is the ring's radius.
    s = cylinder_series(6.0, 3.0, 1.0);
    out = measure_velocity_01(&s);
    tv = gf_test_table(&out, "velocity_variance");
    gf_assert_near(cell(tv, 0, 3), 6.0, 1e-3);
    gf_assert_near(cell(tv, 0, 1), 21.0, 1e-3 * 21.0);
    gf_measure_free(&out);
    gf_series_free(&s);

    // Noise does not move the Gaussian off the axis: with the innermost
    // bin 20% slow, the points mirrored to -r keep the centre at r = 0 (a
    // free centre on r >= 0 alone moves out, to 1.5 d at z = 10).
    s = cylinder_series(0.0, 0.0, 0.8);
    out = measure_velocity_01(&s);
    tv = gf_test_table(&out, "velocity_variance");
    for (size_t r = 0; r < tv->nrow; r++) gf_assert_near(cell(tv, r, 3), 0.0, 1e-9);
    gf_measure_free(&out);
    gf_series_free(&s);
}

// ---------------------------------------------------------------------------
// Diffusion: a random walk dx ~ N(0, 2 b |dz|) on top of a converging drift.

static void diffusion_recovers_random_walk(void **state)
{
    (void)state;
    // Frames every 2 tau from 0 to 24; the auto window is [6, 24], so particles
    // are selected at t = 6 (frames 0-4 put them elsewhere). N = 16000 start in
    // |x| < 5, 60 < z < 100 and drop 2 d per frame (v_z = -1), with a
    // converging drift dx = -0.004 x0 |dz| and a walk of variance 2 b per d
    // dropped, b = 3e-3. 2000 more start outside the region with a walk 10x
    // wider; 1% of the tracked particles leave at each frame.
    //
    // Tolerance: at each frame Var(dx) about the drift is estimated from n ~
    // 16000 particles with relative sd sqrt(2 / n) = 1.1%; the slope through the
    // origin is a weighted mean of Var_k / |dz|_k, whose sd is at most that
    // (frames fully correlated). 5 sd: 5.6% of b. The drift alone would add
    // 0.004^2 Var(x0) dz^2 = 1.3e-4 dz^2, 40% of 2 b dz at dz = 18: caught.
    enum { NF = 13, N = 16000, NOUT = 2000 };
    const double b = 3e-3, c = 0.004;
    double times[NF];
    for (int k = 0; k < NF; k++) times[k] = 2.0 * k;
    gf_series s = make_series(NF, times);
    gf_rng rng;
    gf_rng_seed(&rng, 2024, 3);
    double *x0 = malloc(sizeof(double) * (N + NOUT)), *z0 = malloc(sizeof(double) * (N + NOUT));
    double *dx = malloc(sizeof(double) * (N + NOUT));
    bool *gone = calloc(N + NOUT, sizeof(bool));
    assert_true(x0 && z0 && dx && gone);
    for (int i = 0; i < N + NOUT; i++) {
        if (i < N) {
            x0[i] = -5.0 + 10.0 * gf_rng_uniform(&rng);
            z0[i] = 60.0 + 40.0 * gf_rng_uniform(&rng) + 1e-9;
        } else {
            x0[i] = i % 2 ? 7.0 + 10.0 * gf_rng_uniform(&rng) : -5.0 + 10.0 * gf_rng_uniform(&rng);
            z0[i] = i % 2 ? 80.0 : 59.0 - 30.0 * gf_rng_uniform(&rng);
        }
        dx[i] = 0.0;
    }
    for (int k = 0; k < NF; k++) {
        int j = k - 3; // frames after the start frame (k = 3, t = 6)
        for (int i = 0; i < N + NOUT; i++) {
            if (j < 0) {
                push(&s.frames[k], i + 1, 20.0 * gf_rng_uniform(&rng) - 10.0, 0.0, 200.0 * gf_rng_uniform(&rng));
                continue;
            }
            if (j > 0) {
                if (i < N && gf_rng_uniform(&rng) < 0.01) gone[i] = true;
                double wide = i < N ? 1.0 : 10.0;
                dx[i] += -c * x0[i] * 2.0 + wide * sqrt(2.0 * b * 2.0) * normal(&rng);
            }
            if (!gone[i]) push(&s.frames[k], i + 1, x0[i] + dx[i], 0.3, z0[i] - 2.0 * j);
        }
    }
    gf_analysis_opts o = gf_analysis_opts_default();
    gf_measure_out out = {0};
    assert_int_equal(gf_measure_diffusion(&s, &o, &out), GF_OK);
    gf_assert_near(gf_test_value(&out, "diffusion_particles"), N, 0.0);
    gf_assert_near(gf_test_value(&out, "diffusion_length"), b, 5.0 * sqrt(2.0 / N) * b);
    const gf_table *t = gf_test_table(&out, "diffusion");
    assert_int_equal(t->nrow, 9);
    for (size_t r = 0; r < t->nrow; r++) {
        double dz = 2.0 * (double)(r + 1);
        gf_assert_near(cell(t, r, 0), 8.0 + 2.0 * (double)r, 1e-12);
        gf_assert_near(cell(t, r, 1), dz, 1e-9);
        assert_true(cell(t, r, 3) < N && cell(t, r, 3) > 0.85 * N);
        // Each frame's variance within 5 sd of 2 b dz; the raw one holds the drift.
        gf_assert_near(cell(t, r, 2), 2.0 * b * dz, 5.0 * sqrt(2.0 / cell(t, r, 3)) * 2.0 * b * dz);
        double drift = c * c * dz * dz * 100.0 / 12.0; // c^2 dz^2 Var(x0), Var(x0) = 10^2 / 12
        gf_assert_near(cell(t, r, 4), 2.0 * b * dz + drift, 5.0 * sqrt(2.0 / cell(t, r, 3)) * (2.0 * b * dz + drift));
    }
    gf_measure_free(&out);
    gf_series_free(&s);
    free(x0);
    free(z0);
    free(dx);
    free(gone);
}

// A cylinder: particles start in r < 5 (uniform disc), drop 2 d per frame,
// with a radial drift that grows faster than r (-c r0 (1 + r0^2 / 4) per d
// dropped, along the start's radius: the mean flow of a silo converges in
// the plane through the axis) and an isotropic walk of variance 2 b per d
// dropped along x and along y. The tangential displacement holds the walk
// only: Var = 2 b |dz|, b recovered (thesis Sec. 3.3's per-axis b_p).
// 2000 decoys start at |x| < 5 but r > 5 with a walk 10x wider: outside the
// region. The old estimator (dx about a regression on x0 and x0 (z0 - zbar),
// particles with |x| < 5) took the decoys and the drift's non-linear part:
// b_p 0.058, 19x. Tolerance as diffusion_recovers_random_walk (5 sd, 5.6%).
// With `recirc` > 0 that fraction of the tracked particles exits at a random
// frame after the start (listed in the series' exits) and is put back on the
// surface (z = 110, anywhere in r < 12) under the same id, as a recirculating
// run does; the others are untouched, so b is recovered as before.
static void diffusion_cylinder_case(double recirc)
{
    enum { NF = 13, N = 16000, NOUT = 2000 };
    const double b = 3e-3, c = 0.004;
    double times[NF];
    for (int k = 0; k < NF; k++) times[k] = 2.0 * k;
    gf_series s = make_series(NF, times);
    s.cfg.container_shape = GF_SHAPE_CYLINDER;
    s.cfg.container_radius = 12.0;
    gf_rng rng;
    gf_rng_seed(&rng, 2025, 5);
    double *p0 = malloc(sizeof(double) * 3 * (N + NOUT)), *d = calloc(2 * (N + NOUT), sizeof(double));
    int *back = calloc(N + NOUT, sizeof(int)); // frame at which a tracked particle is back on the surface (0: never)
    gf_exit *ex = calloc(N + NOUT, sizeof(gf_exit));
    size_t nex = 0;
    assert_true(p0 && d && back && ex);
    for (int i = 0; i < N + NOUT; i++) {
        double *q = p0 + 3 * i;
        if (i < N) {
            double r = 5.0 * sqrt(gf_rng_uniform(&rng)), a = 6.283185307179586 * gf_rng_uniform(&rng);
            q[0] = r * cos(a);
            q[1] = r * sin(a);
        } else {
            q[0] = -5.0 + 10.0 * gf_rng_uniform(&rng);
            q[1] = (i % 2 ? 1.0 : -1.0) * (5.5 + 4.0 * gf_rng_uniform(&rng));
        }
        q[2] = 60.0 + 40.0 * gf_rng_uniform(&rng) + 1e-9;
        if (recirc > 0.0 && i < N && gf_rng_uniform(&rng) < recirc) back[i] = 5 + (int)(7.0 * gf_rng_uniform(&rng));
    }
    // Exited between frames back[i] - 1 and back[i] (times 2 k), in time order.
    for (int k = 1; k < NF; k++)
        for (int i = 0; i < N; i++)
            if (back[i] == k) ex[nex++] = (gf_exit){.id = i + 1, .time = 2.0 * k - 1.0, .pass = 1};
    for (int k = 0; k < NF; k++) {
        int j = k - 3; // frames after the start frame (k = 3, t = 6)
        for (int i = 0; i < N + NOUT; i++) {
            const double *q = p0 + 3 * i;
            if (j < 0) {
                push(&s.frames[k], i + 1, 20.0 * gf_rng_uniform(&rng) - 10.0, 0.0, 200.0 * gf_rng_uniform(&rng));
                continue;
            }
            if (j > 0) {
                double r2 = q[0] * q[0] + q[1] * q[1], wide = i < N ? 1.0 : 10.0;
                for (int a = 0; a < 2; a++)
                    d[2 * i + a] += -c * q[a] * (1.0 + r2 / 4.0) * 2.0 + wide * sqrt(2.0 * b * 2.0) * normal(&rng);
            }
            if (back[i] && k >= back[i]) {
                double r = 12.0 * sqrt(gf_rng_uniform(&rng)), a = 6.283185307179586 * gf_rng_uniform(&rng);
                push(&s.frames[k], i + 1, r * cos(a), r * sin(a), 110.0 - 2.0 * (k - back[i]));
                continue;
            }
            push(&s.frames[k], i + 1, q[0] + d[2 * i], q[1] + d[2 * i + 1], q[2] - 2.0 * j);
        }
    }
    if (nex) {
        s.exits = GF_NEW(gf_exit, nex);
        assert_non_null(s.exits);
        memcpy(s.exits, ex, sizeof *ex * nex);
        s.nexits = nex;
        s.has_exits = true;
        s.cfg.run_recirculate = 1;
    }
    gf_analysis_opts o;
    o = gf_analysis_opts_default();
    gf_measure_out out = {0};
    assert_int_equal(gf_measure_diffusion(&s, &o, &out), GF_OK);
    print_message("cylinder%s: b_p %.4g (walk %.4g), %g particles, %zu put back\n", recirc > 0.0 ? " (recirculating)" : "",
                  gf_test_value(&out, "diffusion_length"), b, gf_test_value(&out, "diffusion_particles"), nex);
    gf_assert_near(gf_test_value(&out, "diffusion_particles"), N, 0.0);
    gf_assert_near(gf_test_value(&out, "diffusion_length"), b, 5.0 * sqrt(2.0 / N) * b);
    gf_measure_free(&out);
    gf_series_free(&s);
    free(p0);
    free(d);
    free(back);
    free(ex);
}

static void diffusion_tangential_in_a_cylinder(void **state)
{
    (void)state;
    diffusion_cylinder_case(0.0);
}

// The tracked particles that a recirculating run put back on the surface
// since the start frame leave the measurement at their exit (the old code
// kept them: their jump to a random surface position made b_p 33x).
static void diffusion_drops_recirculated_particles(void **state)
{
    (void)state;
    diffusion_cylinder_case(0.1);
}

// ---------------------------------------------------------------------------
// Correlation: fluctuations along lines of particles as an AR(1) process.

/// The series below, with the flow's amplitude in frame pair k scaled by
/// 1 + spread (2 U - 1), U uniform: 0 for steady flow.
static void correlation_case(double spread)
{
    // A 32 x 32 d region (correlation.size = 32, r still up to 8 d) holding four
    // lines of 124 particles along x (|x| < 16, spacing s = 0.25807) at z =
    // 49, 58, 65, 74, 7 d or more apart (beyond r = 8 with their 3.5 d offsets
    // in y: no pairs between lines). In each of K frame pairs the y velocity
    // along a line is a stationary AR(1) sequence u_{i+1} = rho u_i + sqrt(1 -
    // rho^2) sigma xi, rho = exp(-s / beta), whose correlation is exactly
    // rho^(r/s) = exp(-r / beta). On top there is a mean flow with a boundary
    // layer: v_z = -0.3 at y = 0.1, -0.18 in the wall layers (y = +-3.6). With
    // velocity.bin = 16 a centre and a wall line share each (x, z) bin of the
    // mean field, which holds their average; only its depth profile makes
    // their du exact (without it du_z = -+0.06, 60 sigma, swamps C). Each frame
    // pair uses its own ids, so positions never drift. Decoys at x = +-20
    // (outside the region) move at random. The spacing keeps every lattice
    // distance m s at least 0.003 d from a bin edge (0.1 d), so each bin holds
    // one distance; the midpoints' y offsets (u dt / 2 < 5 sigma = 0.005) move
    // r by < 1e-4 d.
    //
    // Tolerance: the maximum-likelihood estimate of rho from n = 496 K points
    // has sd sqrt((1 - rho^2) / n), i.e. beta to sd(rho) / (rho |ln rho|) =
    // 0.6% for K = 1000; the unweighted fit of binned C(r) over 1 < r < 8 is
    // less efficient: over 30 seeds its sd was 2.1% for beta and 1.5% for the
    // amplitude, so 5 sd: 10.5% and 7.5%.
    enum { K = 1000, NL = 4, NP = 124 };
    const double beta = 2.0, sp = 0.25807, sigma = 0.001, rho = exp(-sp / beta);
    double times[K + 1];
    for (int k = 0; k <= K; k++) times[k] = (double)k;
    gf_series s = make_series(K + 1, times);
    gf_rng rng;
    gf_rng_seed(&rng, 99, 4);
    const double zl[NL] = {49.0, 58.0, 65.0, 74.0}, yl[NL] = {0.1, 3.6, -3.6, 0.1}, wl[NL] = {-0.3, -0.18, -0.18, -0.3};
    gf_rng brng;
    gf_rng_seed(&brng, 7, 1);
    for (int k = 0; k < K; k++) {
        double amp = 1.0 + spread * (2.0 * gf_rng_uniform(&brng) - 1.0);
        for (int l = 0; l < NL; l++) {
            double u = sigma * normal(&rng);
            for (int i = 0; i < NP; i++) {
                if (i > 0) u = rho * u + sqrt(1.0 - rho * rho) * sigma * normal(&rng);
                int64_t id = 1 + (int64_t)k * 1000 + l * NP + i;
                double x = -16.0 + sp * (i + 0.5);
                push(&s.frames[k], id, x, yl[l], zl[l] - 0.5 * amp * wl[l]);
                push(&s.frames[k + 1], id, x, yl[l] + u, zl[l] + 0.5 * amp * wl[l]);
            }
        }
        for (int d = 0; d < 2; d++) {
            int64_t id = 1 + (int64_t)k * 1000 + 500 + d;
            push(&s.frames[k], id, d ? 20.0 : -20.0, 0.0, 60.0);
            push(&s.frames[k + 1], id, d ? 20.0 : -20.0, normal(&rng), 60.0 + normal(&rng));
        }
    }
    gf_analysis_opts o = gf_analysis_opts_default();
    o.t0 = 0.0;
    o.corr_size = 32.0;
    o.vel_bin = 16.0;
    gf_measure_out out = {0};
    assert_int_equal(gf_measure_correlation(&s, &o, &out), GF_OK);
    gf_assert_near(gf_test_value(&out, "correlation_length"), beta, 0.105 * beta);
    gf_assert_near(gf_test_value(&out, "correlation_amplitude"), 1.0, 0.075);
    // Steady flow: the flow amplitude is the same in every frame pair (only
    // the y fluctuations enter it, through <v_y> ~ sigma / sqrt(K NP) ~ 1e-5).
    // In bursts it is the sd of the uniform amplitudes, spread / sqrt(3),
    // within 3 sd of a sample sd of K (spread / sqrt(3) x 0.022 x 3).
    double us = spread / sqrt(3.0);
    gf_assert_near(gf_test_value(&out, "correlation_unsteadiness"), us, 1e-6 + 0.07 * us);
    // Pairs lie at r = m s: each bin's r is one of them, holding all NL K (NP - m)
    // such pairs, and C(r) = exp(-r / beta) within 5 sd: the sd of a bin's C is
    // at most that of the AR(1) sample autocovariance over NL K lines of NP
    // points, ~ sqrt((1 + rho^2) / (1 - rho^2) / (NL K NP)) = 0.4%, so 0.02.
    const gf_table *t = gf_test_table(&out, "correlation");
    assert_int_equal(t->nrow, 30); // m = 1 .. 30 (31 s = 8.0002 is beyond r = 8)
    for (size_t r = 0; r < t->nrow; r++) {
        double rr = cell(t, r, 0), m = rr / sp;
        gf_assert_near(m, round(m), 1e-3);
        gf_assert_near(cell(t, r, 2), (double)NL * K * (NP - round(m)), 0.0);
        gf_assert_near(cell(t, r, 1), exp(-rr / beta), 0.02);
    }
    gf_measure_free(&out);
    gf_series_free(&s);
}

static void correlation_recovers_length(void **state)
{
    (void)state;
    correlation_case(0.0);
}

// A DEM silo flows in bursts: the whole region speeds up and slows down
// together (here by +-50%, unsteadiness 0.29). That common part, du_z = (a_k
// - 1) v_z ~ 0.09, 90 times the local sigma, would make C(r) ~ 1 at every r
// (as on the LAMMPS runs of docs/dem.md: beta 22 d in an 11 d region); taken
// out frame pair by frame pair, the same length and C(r) come back.
static void correlation_ignores_bursts(void **state)
{
    (void)state;
    correlation_case(0.5);
}

// A cylinder: the four AR(1) lines of correlation_case (here at y = +-1.1,
// +-3.6) in an axisymmetric converging flow, v = (v_r x / r, v_r y / r, v_z),
// v_r = -0.05, v_z = -0.3, 50 and 300 times the fluctuations. The (r, z)
// field holds it exactly (constant in every annulus), so the same length
// comes back. An (x, z) field averaged over y (the box's, before) leaves
// part of v_r y / r and v_r x / r in du, smooth along each line: beta 3.4 d.
// Tolerance as correlation_case.
static void correlation_about_radial_mean_in_a_cylinder(void **state)
{
    (void)state;
    enum { K = 1000, NL = 4, NP = 124 };
    const double beta = 2.0, sp = 0.25807, sigma = 0.001, rho = exp(-sp / beta), vr = -0.05, vz = -0.3;
    double times[K + 1];
    for (int k = 0; k <= K; k++) times[k] = (double)k;
    gf_series s = make_series(K + 1, times);
    s.cfg.container_shape = GF_SHAPE_CYLINDER;
    s.cfg.container_radius = 20.0;
    gf_rng rng;
    gf_rng_seed(&rng, 98, 4);
    const double zl[NL] = {49.0, 58.0, 65.0, 74.0}, yl[NL] = {1.1, 3.6, -3.6, -1.1};
    for (int k = 0; k < K; k++)
        for (int l = 0; l < NL; l++) {
            double u = sigma * normal(&rng);
            for (int i = 0; i < NP; i++) {
                if (i > 0) u = rho * u + sqrt(1.0 - rho * rho) * sigma * normal(&rng);
                int64_t id = 1 + (int64_t)k * 1000 + l * NP + i;
                double x = -16.0 + sp * (i + 0.5), y = yl[l], r = hypot(x, y);
                double v[3] = {vr * x / r, vr * y / r, vz};
                push(&s.frames[k], id, x - 0.5 * v[0], y - 0.5 * v[1], zl[l] - 0.5 * v[2]);
                push(&s.frames[k + 1], id, x + 0.5 * v[0], y + 0.5 * v[1] + u, zl[l] + 0.5 * v[2]);
            }
        }
    gf_analysis_opts o;
    o = gf_analysis_opts_default();
    o.t0 = 0.0;
    o.corr_size = 32.0;
    o.vel_bin = 16.0;
    gf_measure_out out = {0};
    assert_int_equal(gf_measure_correlation(&s, &o, &out), GF_OK);
    print_message("cylinder: beta %.4g (lines %.4g), amplitude %.4g\n", gf_test_value(&out, "correlation_length"),
                  beta, gf_test_value(&out, "correlation_amplitude"));
    gf_assert_near(gf_test_value(&out, "correlation_length"), beta, 0.105 * beta);
    gf_assert_near(gf_test_value(&out, "correlation_amplitude"), 1.0, 0.075);
    gf_measure_free(&out);
    gf_series_free(&s);
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(velocity_recovers_variance_line),
    cmocka_unit_test(velocity_depth_profile),
    cmocka_unit_test(velocity_window_per_height),
    cmocka_unit_test(flowstats_flag_a_widening_reference),
    cmocka_unit_test(steady_height_cases),
    cmocka_unit_test(steady_height_by_rise_cases),
    cmocka_unit_test(velocity_window_by_spot_rise),
    cmocka_unit_test(velocity_radial_in_cylinder),
    cmocka_unit_test(diffusion_recovers_random_walk),
    cmocka_unit_test(correlation_recovers_length),
    cmocka_unit_test(correlation_ignores_bursts),
    cmocka_unit_test(diffusion_tangential_in_a_cylinder),
    cmocka_unit_test(diffusion_drops_recirculated_particles),
    cmocka_unit_test(correlation_about_radial_mean_in_a_cylinder),
};

GF_TEST_MAIN("velocity", tests)
