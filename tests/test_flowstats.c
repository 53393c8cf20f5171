// SPDX-License-Identifier: MIT
// Outflow, density slice, free-surface angle and residence times on series
// built in memory whose answers are known exactly or bounded by hand.
#include "support.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "granflow/analysis.h"
#include "granflow/granflow.h"

static const double deg_per_rad = 57.295779513082320876798154814105;

/// A series of n empty frames at the given times, with the default config.
static void series_init(gf_series *s, size_t n, const double *times)
{
    memset(s, 0, sizeof *s);
    s->frames = GF_NEW(gf_frame, n);
    assert_non_null(s->frames);
    s->nframes = n;
    for (size_t k = 0; k < n; k++) s->frames[k].time = times[k];
    s->cfg = gf_config_default();
}

static void series_exits(gf_series *s, const gf_exit *e, size_t n)
{
    s->exits = GF_NEW(gf_exit, n);
    assert_non_null(s->exits);
    memcpy(s->exits, e, sizeof *e * n);
    s->nexits = n;
    s->has_exits = true;
}

static void push(gf_packing *p, int64_t id, int32_t layer, double x, double z)
{
    assert_int_equal(gf_packing_push(p, id, layer, x, 0.0, z, 0.5), GF_OK);
}

static double cell(const gf_table *t, size_t row, size_t col)
{
    assert_true(row < t->nrow && col < t->ncol);
    return t->v[row * t->ncol + col];
}

/// Writes the tables as CSV next to the gnuplot script and runs gnuplot on it
/// (dumb terminal): the script must run without a single message. Skipped
/// where gnuplot is not installed.
static void gnuplot_runs(const gf_measure_out *o, const char *name)
{
    if (system("gnuplot --version >/dev/null 2>&1") != 0) {
        print_message("gnuplot not installed: plot script of %s not run\n", name);
        return;
    }
    char dir[1200], path[1300], cmd[2800];
    snprintf(dir, sizeof dir, "%s/plot_%s", gf_test_tmpdir(), name);
    snprintf(cmd, sizeof cmd, "mkdir -p '%s'", dir);
    assert_int_equal(system(cmd), 0);
    for (size_t k = 0; k < o->ntables; k++) {
        snprintf(path, sizeof path, "%s/%s.csv", dir, o->tables[k].name);
        assert_int_equal(gf_table_write_csv(&o->tables[k], path), GF_OK);
    }
    assert_non_null(o->gnuplot);
    snprintf(path, sizeof path, "%s/plot.gp", dir);
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fprintf(f, "set terminal dumb\nset output '/dev/null'\n%s", o->gnuplot);
    fclose(f);
    snprintf(cmd, sizeof cmd, "cd '%s' && gnuplot plot.gp >out.txt 2>&1", dir);
    int rc = system(cmd);
    snprintf(path, sizeof path, "%s/out.txt", dir);
    size_t len = 0;
    char *msg = gf_test_read_file(path, &len);
    if (rc != 0 || len != 0) fail_msg("gnuplot on the %s script: exit %d, said: %s", name, rc, msg ? msg : "?");
    free(msg);
}

// ---------------------------------------------------------------------------
// Outflow.

// Exits every 1/R tau from t = 1: the fit over exit events (t_k, k) is exact,
// so the rate equals R up to rounding of t_k (relative 1e-16 per time, far
// below the 1e-9 R allowed). Exits before the first frame (t = 2) are not counted.
static void outflow_from_exits(void **state)
{
    (void)state;
    const double R = 130.0;
    const size_t N = 1800;
    double times[8];
    for (int k = 0; k < 8; k++) times[k] = 2.0 * (k + 1); // 2 .. 16
    gf_series s;
    series_init(&s, 8, times);
    gf_exit *e = GF_NEW(gf_exit, N);
    for (size_t k = 0; k < N; k++) e[k] = (gf_exit){.id = (int64_t)k + 1, .time = 1.0 + (double)k / R, .pass = 1};
    series_exits(&s, e, N);
    GF_DELETE(e, N);
    gf_analysis_opts o = gf_analysis_opts_default();
    gf_measure_out out = {0};
    assert_int_equal(gf_measure_outflow(&s, &o, &out), GF_OK);
    gf_assert_near(gf_test_value(&out, "flow_rate"), R, 1e-9 * R);
    // k = 0..129 leave before t = 2 (k = 130 leaves exactly at 2 and counts).
    assert_true(gf_test_value(&out, "particles_exited") == (double)(N - 130));
    const gf_table *t = gf_test_table(&out, "outflow");
    assert_int_equal(t->ncol, 3);
    assert_int_equal(t->nrow, 1 + (N - 130) + 1); // start, one row per exit, held to t = 16
    assert_true(cell(t, 0, 0) == 2.0 && cell(t, 0, 1) == 0.0);
    assert_true(isnan(cell(t, 0, 2)));                        // window auto: 5.5 .. 16
    assert_true(cell(t, 1, 0) == 2.0 && cell(t, 1, 1) == 1.0); // the exit at t = 2
    assert_true(cell(t, t->nrow - 1, 0) == 16.0 && cell(t, t->nrow - 1, 1) == (double)(N - 130));
    gf_assert_near(cell(t, t->nrow - 1, 2) - cell(t, t->nrow - 2, 2), R * (16.0 - cell(t, t->nrow - 2, 0)), 1e-6);
    assert_non_null(strstr(out.gnuplot, "'outflow.csv'"));
    gnuplot_runs(&out, "outflow");
    gf_measure_free(&out);

    // A window set by hand: still the same rate, from fewer points.
    assert_int_equal(gf_analysis_opts_set(&o, "window.t0=3"), GF_OK);
    assert_int_equal(gf_analysis_opts_set(&o, "window.t1=4"), GF_OK);
    assert_int_equal(gf_measure_outflow(&s, &o, &out), GF_OK);
    gf_assert_near(gf_test_value(&out, "flow_rate"), R, 1e-9 * R);
    gf_measure_free(&out);
    gf_series_free(&s);
}

// Without exits: n_initial - n per frame. 600 - 50 k particles at t = 2 k
// drain at exactly 25 per tau (integers: the least-squares slope is exact).
static void outflow_from_counts(void **state)
{
    (void)state;
    const double times[6] = {0, 2, 4, 6, 8, 10};
    gf_series s;
    series_init(&s, 6, times);
    for (int k = 0; k < 6; k++)
        for (int i = 0; i < 600 - 50 * k; i++) push(&s.frames[k].pk, i + 1, 1, 0.0, 1.0 + i);
    s.n_initial = 600;
    gf_analysis_opts o = gf_analysis_opts_default();
    gf_measure_out out = {0};
    assert_int_equal(gf_measure_outflow(&s, &o, &out), GF_OK);
    gf_assert_near(gf_test_value(&out, "flow_rate"), 25.0, 1e-12);
    assert_true(gf_test_value(&out, "particles_exited") == 250.0);
    const gf_table *t = gf_test_table(&out, "outflow");
    assert_int_equal(t->nrow, 6);
    for (size_t k = 0; k < 6; k++) {
        assert_true(cell(t, k, 0) == 2.0 * (double)k && cell(t, k, 1) == 50.0 * (double)k);
        if (cell(t, k, 0) >= 2.5) gf_assert_near(cell(t, k, 2), cell(t, k, 1), 1e-9); // on the line
        else assert_true(isnan(cell(t, k, 2)));
    }
    gnuplot_runs(&out, "outflow_counts");
    gf_measure_free(&out);
    // One frame: no rate (NaN), not an error.
    s.nframes = 1;
    assert_int_equal(gf_measure_outflow(&s, &o, &out), GF_OK);
    assert_true(isnan(gf_test_value(&out, "flow_rate")));
    gf_measure_free(&out);
    s.nframes = 6;
    gf_series_free(&s);
}

// ---------------------------------------------------------------------------
// Density.

// Frame k holds c_k particles strictly inside 50 < z < 70 plus particles on
// and beyond the bounds, which must not count: exact counts and means.
static void density_counts_the_slice(void **state)
{
    (void)state;
    const double times[5] = {0, 1, 2, 3, 4};
    const int c[5] = {9, 7, 6, 8, 5};
    gf_series s;
    series_init(&s, 5, times);
    for (int k = 0; k < 5; k++) {
        gf_packing *p = &s.frames[k].pk;
        int id = 1;
        for (int i = 0; i < c[k]; i++) push(p, id++, 1, 0.0, 50.0 + 19.99 * (i + 0.5) / c[k]);
        const double outside[] = {50.0, 70.0, 49.999, 70.001, 10.0, 90.0};
        for (int i = 0; i < 6; i++) push(p, id++, 1, 1.0, outside[i]);
    }
    s.n_initial = s.frames[0].pk.n;
    gf_analysis_opts o = gf_analysis_opts_default();
    gf_measure_out out = {0};
    assert_int_equal(gf_measure_density(&s, &o, &out), GF_OK);
    const gf_table *t = gf_test_table(&out, "density");
    assert_int_equal(t->nrow, 5);
    for (size_t k = 0; k < 5; k++) assert_true(cell(t, k, 0) == times[k] && cell(t, k, 1) == c[k]);
    assert_true(gf_test_value(&out, "density_initial") == 9.0);
    // Auto window 1 .. 4: frames 1-4.
    assert_true(gf_test_value(&out, "density_steady") == (7.0 + 6.0 + 8.0 + 5.0) / 4.0);
    gnuplot_runs(&out, "density");
    gf_measure_free(&out);
    // Another slice, by option: 0 < z < 50.0005 holds z = 50, 49.999 and 10.
    assert_int_equal(gf_analysis_opts_set(&o, "density.z0=0"), GF_OK);
    assert_int_equal(gf_analysis_opts_set(&o, "density.z1=50.0005"), GF_OK);
    assert_int_equal(gf_measure_density(&s, &o, &out), GF_OK);
    assert_true(gf_test_value(&out, "density_initial") == 3.0);
    gf_measure_free(&out);
    // A slice above every particle (a hopper filled to 40 d, the paper's
    // 50 < z < 70): nothing measured, NaN rather than a density of 0.
    assert_int_equal(gf_analysis_opts_set(&o, "density.z0=100"), GF_OK);
    assert_int_equal(gf_analysis_opts_set(&o, "density.z1=120"), GF_OK);
    assert_int_equal(gf_measure_density(&s, &o, &out), GF_OK);
    assert_true(isnan(gf_test_value(&out, "density_initial")));
    assert_true(isnan(gf_test_value(&out, "density_steady")));
    assert_non_null(strstr(out.gnuplot, "empty in the first frame"));
    gnuplot_runs(&out, "density");
    gf_measure_free(&out);
    gf_series_free(&s);
}

// ---------------------------------------------------------------------------
// Free surface.

/// Adds particles on z = z0 + sign tan(theta) |x| at |x| = (k + u_k) h, both
/// sides, for |x| < xmax, skipping column `skip` (1-based, 0: none), with
/// filler particles 1.5 and 3 d below the surface. u_k = 0.5 when !jitter,
/// else pseudo-random in [0.05, 0.95].
static void surface_frame(gf_packing *p, double theta_deg, double sign, double h, double xmax, double dx, int skip,
                          int jitter)
{
    double t = tan(theta_deg / deg_per_rad);
    uint64_t lcg = 12345;
    int64_t id = (int64_t)p->n + 1;
    for (int k = 0;; k++) {
        lcg = lcg * 6364136223846793005u + 1442695040888963407u;
        double u = jitter ? 0.05 + 0.9 * (double)(lcg >> 11) / 9007199254740992.0 : 0.5;
        double ax = (k + u) * h;
        if (ax >= xmax) break;
        if (skip && floor(ax / dx) == skip - 1) continue;
        double z = 40.0 + sign * t * ax;
        for (int side = -1; side <= 1; side += 2) {
            push(p, id++, 1, side * ax, z);
            push(p, id++, 1, side * ax, z - 1.5);
            push(p, id++, 1, side * ax, z - 3.0);
        }
    }
}

// The paper's regression (dx = 2.5, 10 columns). With samples at
// |x| = (k + 1/2) h, h = dx/8, every column's top sample sits the same
// distance from its column edge, so z_j is an exact straight line in x_j and
// the angle comes out exact (rounding only): +theta for a surface rising to
// the walls (a draining silo), -theta for a heap.
//
// Jittered samples: the top of column j is at |x| = j dx - e_j with e_j in
// [0.05 h, 0.95 h], so z_j = (exact line) - t e_j and the slope is off by
// t |sum (x_j - xbar)(e_j - ebar)| / Sxx <= t 0.9 h sum|x_j - xbar| / Sxx,
// with sum|x_j - xbar| = 25 dx and Sxx = 82.5 dx^2 for 10 columns. The angle
// error is at most the slope error (d atan/ds <= 1), in radians.
static void surface_angle_regression(void **state)
{
    (void)state;
    const double dx = 2.5, h_fine = dx / 40.0;
    const double times[6] = {0, 1, 2, 3, 4, 5};
    gf_series s;
    series_init(&s, 6, times);
    surface_frame(&s.frames[0].pk, 30.0, +1.0, dx / 8, 25.0, dx, 0, 0);  // crater, 30 degrees
    surface_frame(&s.frames[1].pk, 20.0, -1.0, dx / 8, 25.0, dx, 0, 0);  // heap, -20 degrees
    surface_frame(&s.frames[2].pk, 35.0, +1.0, h_fine, 25.0, dx, 0, 1); // jittered, 35 degrees
    surface_frame(&s.frames[3].pk, 25.0, +1.0, dx / 8, 7 * dx, dx, 4, 0); // columns 4, 8-10 empty
    push(&s.frames[4].pk, 1, 1, 3.0, 10.0);                                 // one column: no angle
    surface_frame(&s.frames[5].pk, 30.0, +1.0, dx / 8, 30.0, dx, 0, 0); // beyond column 10: ignored
    // Particles right on the column edges |x| = j dx belong to no column: a
    // tall one at x = 2.5 must not change frame 0's answer.
    push(&s.frames[0].pk, 99999, 1, 2.5, 1000.0);
    push(&s.frames[0].pk, 99998, 1, 0.0, 1000.0);
    s.n_initial = s.frames[0].pk.n;
    gf_analysis_opts o = gf_analysis_opts_default();
    gf_measure_out out = {0};
    assert_int_equal(gf_measure_surface(&s, &o, &out), GF_OK);
    const gf_table *t = gf_test_table(&out, "surface");
    assert_int_equal(t->nrow, 6);
    gf_assert_near(cell(t, 0, 2), 30.0, 1e-9);
    gf_assert_near(cell(t, 0, 1), tan(30.0 / deg_per_rad), 1e-12);
    gf_assert_near(cell(t, 1, 2), -20.0, 1e-9);
    double tj = tan(35.0 / deg_per_rad);
    double tol = tj * 0.9 * h_fine * 25.0 * dx / (82.5 * dx * dx) * deg_per_rad;
    gf_assert_near(cell(t, 2, 2), 35.0, tol);
    assert_true(fabs(cell(t, 2, 2) - 35.0) > 1e-6); // the jitter does move it: a real bound, not rounding
    gf_assert_near(cell(t, 3, 2), 25.0, 1e-9);
    assert_true(isnan(cell(t, 4, 1)) && isnan(cell(t, 4, 2)));
    gf_assert_near(cell(t, 5, 2), 30.0, 1e-9);
    // Window auto: 1.25 .. 5 -> frames 2, 3, 5 (frame 4 has no angle).
    double mean = (cell(t, 2, 2) + cell(t, 3, 2) + cell(t, 5, 2)) / 3.0;
    gf_assert_near(gf_test_value(&out, "surface_angle"), mean, 1e-12);
    gf_assert_near(gf_test_value(&out, "surface_angle"), 30.0, tol / 3.0 + 1e-9);
    gnuplot_runs(&out, "surface");
    gf_measure_free(&out);
    gf_series_free(&s);
}

// ---------------------------------------------------------------------------
// Residence times.

/// The residence times of rtd_series' first exits (layer 1 {1, 3, 8}, layer
/// 2 {4, 6}: see rtd_per_layer).
static void assert_rtd_layers(const gf_measure_out *out)
{
    const gf_table *t = gf_test_table(out, "rtd");
    assert_int_equal(t->nrow, 2);
    const double want[2][6] = {{1, 3, 4, sqrt(13.0), 3, 1}, {2, 2, 5, sqrt(2.0), 5, 4}};
    for (size_t r = 0; r < 2; r++)
        for (size_t c = 0; c < 6; c++) gf_assert_near(cell(t, r, c), want[r][c], 1e-12);
    gf_assert_near(gf_test_value(out, "rtd_mean"), 4.4, 1e-12);
}

/// Frames at t = 2 and 12: ids 1-3 in layer 1 and 4-6 in layer 2 at z = 5 i
/// in the first; only id 6 (z = 1) in the last.
static void rtd_series(gf_series *s)
{
    const double times[2] = {2, 12};
    series_init(s, 2, times);
    for (int i = 1; i <= 6; i++) push(&s->frames[0].pk, i, i <= 3 ? 1 : 2, 0.0, 5.0 * i);
    push(&s->frames[1].pk, 6, 2, 0.0, 1.0);
    s->n_initial = 6;
}

// First frame at t = 2: ids 1-3 in layer 1, ids 4-6 in layer 2. Exits (hand
// placed): 1 at 3, 2 at 5, 3 at 10, 4 at 6, 5 at 8; id 99 was not in the
// first frame and id 6 left before it: neither counts. Residence times:
// layer 1 {1, 3, 8}: mean 4, median 3, sd sqrt(((-3)^2 + (-1)^2 + 4^2)/2) =
// sqrt(13); layer 2 {4, 6}: mean 5, median 5, sd sqrt(2); all {1,3,4,6,8}:
// mean 4.4, median 4. Histogram bin = run length / 40 = 10/40 = 0.25 tau.
static void rtd_per_layer(void **state)
{
    (void)state;
    gf_series s;
    rtd_series(&s);
    const gf_exit e[] = {{.id = 6, .time = 1.0}, {.id = 1, .time = 3.0}, {.id = 99, .time = 4.0}, {.id = 2, .time = 5.0},
                         {.id = 4, .time = 6.0}, {.id = 5, .time = 8.0}, {.id = 3, .time = 10.0}};
    series_exits(&s, e, sizeof e / sizeof e[0]);
    gf_analysis_opts o = gf_analysis_opts_default();
    gf_measure_out out = {0};
    assert_int_equal(gf_measure_rtd(&s, &o, &out), GF_OK);
    assert_rtd_layers(&out);
    gf_assert_near(gf_test_value(&out, "rtd_median"), 4.0, 0.0);
    assert_true(gf_test_value(&out, "rtd_exited") == 5.0);
    // Histogram: per layer, pdf = count / (n bw) in bins of 0.25 tau.
    const gf_table *hg = gf_test_table(&out, "rtd_hist");
    double integral[3] = {0, 0, 0};
    size_t rows[3] = {0, 0, 0};
    for (size_t r = 0; r < hg->nrow; r++) {
        int layer = (int)cell(hg, r, 1);
        assert_true(layer == 1 || layer == 2);
        integral[layer] += cell(hg, r, 2) * 0.25;
        rows[layer]++;
        double centre = cell(hg, r, 0);
        gf_assert_near(fmod(centre - 0.125, 0.25), 0.0, 1e-12);
        // Non-empty bins: exactly those holding a residence time.
        const double *res = layer == 1 ? (const double[]){1, 3, 8} : (const double[]){4, 6};
        size_t nres = layer == 1 ? 3 : 2, in = 0;
        for (size_t i = 0; i < nres; i++) in += res[i] >= centre - 0.125 && res[i] < centre + 0.125;
        gf_assert_near(cell(hg, r, 2), (double)in / ((double)nres * 0.25), 1e-12);
    }
    gf_assert_near(integral[1], 1.0, 1e-12);
    gf_assert_near(integral[2], 1.0, 1e-12);
    assert_int_equal(rows[1], rows[2]);
    assert_int_equal(rows[1], 33); // bins up to the longest residence, 8 tau: [8, 8.25) is bin 33
    gnuplot_runs(&out, "rtd");
    gf_measure_free(&out);
    gf_series_free(&s);
}

// A recirculating run puts an exited particle back on the surface under the
// same id, and it exits again (exits.csv then holds several rows per id, one
// per pass). Its residence time ends at its first exit: as rtd_per_layer,
// plus later passes of ids 1 (at 9 and 11) and 4 (at 11.5), which must not
// count (the old code counted them: 8 exits, mean 5.94).
static void rtd_counts_the_first_exit(void **state)
{
    (void)state;
    gf_series s;
    rtd_series(&s);
    const gf_exit e[] = {{.id = 6, .time = 1.0, .pass = 1},  {.id = 1, .time = 3.0, .pass = 1},
                         {.id = 99, .time = 4.0, .pass = 1}, {.id = 2, .time = 5.0, .pass = 1},
                         {.id = 4, .time = 6.0, .pass = 1},  {.id = 5, .time = 8.0, .pass = 1},
                         {.id = 1, .time = 9.0, .pass = 2},  {.id = 3, .time = 10.0, .pass = 1},
                         {.id = 1, .time = 11.0, .pass = 3}, {.id = 4, .time = 11.5, .pass = 2}};
    series_exits(&s, e, sizeof e / sizeof e[0]);
    s.cfg.run_recirculate = true;
    gf_analysis_opts o = gf_analysis_opts_default();
    gf_measure_out out = {0};
    assert_int_equal(gf_measure_rtd(&s, &o, &out), GF_OK);
    assert_rtd_layers(&out);
    assert_true(gf_test_value(&out, "rtd_exited") == 5.0);
    gf_measure_free(&out);
    gf_series_free(&s);
}

static void rtd_needs_exits(void **state)
{
    (void)state;
    const double times[1] = {0};
    gf_series s;
    series_init(&s, 1, times);
    push(&s.frames[0].pk, 1, 1, 0.0, 1.0);
    gf_analysis_opts o = gf_analysis_opts_default();
    gf_measure_out out = {0};
    assert_int_equal(gf_measure_rtd(&s, &o, &out), GF_ERR_PARAM);
    assert_non_null(strstr(gf_last_error(), "rtd: needs the exit time of every particle"));
    gf_measure_free(&out);
    // Exits, but none yet: a valid, empty result.
    series_exits(&s, (const gf_exit[]){{.id = 1, .time = -1.0}}, 1); // before the first frame
    assert_int_equal(gf_measure_rtd(&s, &o, &out), GF_OK);
    assert_true(gf_test_value(&out, "rtd_exited") == 0.0 && isnan(gf_test_value(&out, "rtd_mean")));
    gnuplot_runs(&out, "rtd_empty");
    gf_measure_free(&out);
    gf_series_free(&s);
}

// Exits read off the frames (gf_series_derive_exits), by hand. Frames at
// t = 0, 0.5, 1.5, 2 (intervals 0.5, 1, 0.5); ids 1..6. Id 3 is gone from
// the second frame: exit at 0.25; ids 1, 5 and 6 from the third: 1.0; id 4
// from the fourth: 1.75. Id 6 comes back in the fourth frame and is not
// counted again. Each exit sits where the particle was in its last frame
// (x = 10 id + frame), enters at the first frame (entry_r its first |x|).
// Resolution: half the longest interval with an exit, 0.5.
static void exits_read_off_frames(void **state)
{
    (void)state;
    const double times[4] = {0, 0.5, 1.5, 2};
    const int present[4][6] = {{1, 1, 1, 1, 1, 1}, {1, 1, 0, 1, 1, 1}, {0, 1, 0, 1, 0, 0}, {0, 1, 0, 0, 0, 1}};
    gf_series s;
    series_init(&s, 4, times);
    for (int k = 0; k < 4; k++)
        for (int id = 1; id <= 6; id++)
            if (present[k][id - 1]) push(&s.frames[k].pk, id, 1, 10.0 * id + k, 5.0);
    s.n_initial = 6;
    assert_int_equal(gf_series_derive_exits(&s), GF_OK);
    assert_true(s.has_exits && s.exits_derived);
    gf_assert_near(s.exit_resolution, 0.5, 0.0);
    const struct { int64_t id; double t, x; } want[] = {{3, 0.25, 30}, {1, 1.0, 11}, {5, 1.0, 51}, {6, 1.0, 61}, {4, 1.75, 42}};
    assert_int_equal(s.nexits, 5);
    for (size_t e = 0; e < 5; e++) {
        assert_true(s.exits[e].id == want[e].id);
        gf_assert_near(s.exits[e].time, want[e].t, 0.0);
        gf_assert_near(s.exits[e].x, want[e].x, 0.0);
        assert_true(s.exits[e].pass == 1 && s.exits[e].entry_time == 0.0);
        gf_assert_near(s.exits[e].entry_r, 10.0 * (double)want[e].id, 0.0);
    }
    // A second call keeps them; the outflow still counts the snapshots
    // (6 - 2 = 4 by the last frame: id 6 is back), not the derived exits.
    assert_int_equal(gf_series_derive_exits(&s), GF_OK);
    assert_int_equal(s.nexits, 5);
    gf_analysis_opts o = gf_analysis_opts_default();
    gf_measure_out out = {0};
    assert_int_equal(gf_measure_outflow(&s, &o, &out), GF_OK);
    assert_true(gf_test_value(&out, "particles_exited") == 4.0);
    assert_non_null(strstr(out.gnuplot, "from snapshot counts"));
    gf_measure_free(&out);
    gf_series_free(&s);
    // An id twice in one frame is refused, naming the frame's time.
    series_init(&s, 2, times);
    push(&s.frames[0].pk, 1, 1, 0, 1);
    push(&s.frames[1].pk, 2, 1, 0, 1);
    push(&s.frames[1].pk, 2, 1, 1, 1);
    assert_int_equal(gf_series_derive_exits(&s), GF_ERR_PARAM);
    assert_non_null(strstr(gf_last_error(), "t = 0.5 tau"));
    assert_non_null(strstr(gf_last_error(), "id 2"));
    assert_true(!s.has_exits && s.exits == NULL);
    gf_series_free(&s);
}

// Residence times from the snapshots of a drain whose true exit times are
// known: 400 particles in 4 layers, particle i leaves at T_i = 0.37 + 0.0213 i
// (up to 8.9 tau), snapshots every 0.5 tau to 10 tau. Every derived exit is
// within the stated resolution (0.25 tau) of T_i, so is every layer's mean,
// and rtd says so (rtd_resolution; err_mean_tau at least 0.25 / sqrt 3).
// rtd.tmax = 4 counts only the exits up to 4 tau after the first frame.
static void derived_rtd_within_resolution(void **state)
{
    (void)state;
    enum { N = 400, F = 21 };
    double times[F], truth[N + 1];
    for (int k = 0; k < F; k++) times[k] = 0.5 * k;
    for (int i = 1; i <= N; i++) truth[i] = 0.37 + 0.0213 * i;
    gf_series s;
    series_init(&s, F, times);
    for (int k = 0; k < F; k++)
        for (int i = 1; i <= N; i++)
            if (times[k] < truth[i]) push(&s.frames[k].pk, i, 1 + (i - 1) / 100, 0.1 * i, 1.0);
    s.n_initial = N;
    assert_int_equal(gf_series_derive_exits(&s), GF_OK);
    assert_int_equal(s.nexits, N);
    gf_assert_near(s.exit_resolution, 0.25, 0.0);
    for (size_t e = 0; e < s.nexits; e++)
        assert_true(fabs(s.exits[e].time - truth[s.exits[e].id]) <= s.exit_resolution + 1e-12);
    gf_analysis_opts o = gf_analysis_opts_default();
    gf_measure_out out = {0};
    assert_int_equal(gf_measure_rtd(&s, &o, &out), GF_OK);
    gf_assert_near(gf_test_value(&out, "rtd_resolution"), 0.25, 0.0);
    const gf_table *t = gf_test_table(&out, "rtd");
    assert_int_equal(t->nrow, 4);
    for (size_t r = 0; r < 4; r++) {
        double mean = 0.0;
        for (int i = 1 + 100 * (int)r; i <= 100 * ((int)r + 1); i++) mean += truth[i] / 100.0;
        assert_true(cell(t, r, 1) == 100.0);
        assert_true(fabs(cell(t, r, 2) - mean) <= 0.25);
        assert_true(cell(t, r, 6) >= 0.25 / sqrt(3.0) && cell(t, r, 6) < 0.25);
    }
    gnuplot_runs(&out, "rtd_derived");
    gf_measure_free(&out);
    // Cut at 4 tau: the exits at midpoints up to 4 (T_i < 4: i <= 170).
    assert_int_equal(gf_analysis_opts_set(&o, "rtd.tmax=4"), GF_OK);
    memset(&out, 0, sizeof out);
    assert_int_equal(gf_measure_rtd(&s, &o, &out), GF_OK);
    assert_true(gf_test_value(&out, "rtd_exited") == 170.0 && gf_test_value(&out, "rtd_tmax") == 4.0);
    gf_measure_free(&out);
    gf_series_free(&s);
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(outflow_from_exits),
    cmocka_unit_test(outflow_from_counts),
    cmocka_unit_test(density_counts_the_slice),
    cmocka_unit_test(surface_angle_regression),
    cmocka_unit_test(rtd_per_layer),
    cmocka_unit_test(rtd_counts_the_first_exit),
    cmocka_unit_test(rtd_needs_exits),
    cmocka_unit_test(exits_read_off_frames),
    cmocka_unit_test(derived_rtd_within_resolution),
};

GF_TEST_MAIN("flowstats", tests)
