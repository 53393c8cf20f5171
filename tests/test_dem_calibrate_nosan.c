// SPDX-License-Identifier: MIT
// Calibration recovers known parameters (SPEC 1.7): granflow drains a small
// silo with chosen, non-default spot parameters; gf_dem_calibrate measures
// its snapshots as it would a DEM run and must give the five parameters back.
// About 15 s optimised; "nosan" in the suite name keeps it out of the
// sanitizer run (make test-san runs ctest -LE nosan), where it takes minutes.
#include "support.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "granflow/dem.h"
#include "granflow/run.h"

// The chosen model: none of the five is at its default (2.6, 0.676, 399,
// 375, 28). relax.method = none: the thesis' relations (beta = 0.72 r_s,
// b_p = b_s / w, Q = lambda p / w, dN = Q h / (mu dz)) are those of the
// basic spot model; the elastic relaxation widens the velocity
// correlation (beta ~1.4x) and adds particle diffusion (b_p ~2x) in a silo
// this small, which docs/dem.md reports. 30 tau, a snapshot a tau.
static gf_config chosen_model(void)
{
    gf_config c = gf_config_default();
    c.orifice_diameter = 6;
    c.spot_radius = 2.2;
    c.spot_step_xy = 0.55;
    c.spot_w = 300;
    c.spot_insertion_rate = 300;
    c.spot_move_rate = 40;
    c.relax_method = GF_RELAX_NONE;
    c.run_duration = 30;
    c.run_seed = 11;
    c.output_snapshot_interval = 1;
    return c;
}

// Runs c into the test's directory NAME and reads it back as a DEM run.
static void run_and_load(const gf_config *c, const char *name, gf_series *s, gf_dem_load_report *rep)
{
    char dir[1024];
    snprintf(dir, sizeof dir, "%s/%s", gf_test_tmpdir(), name);
    gf_run_opts ro = {.dir = dir};
    assert_int_equal(gf_run_dir(c, &ro, NULL), GF_OK);
    assert_int_equal(gf_dem_series_load(dir, NULL, s, rep), GF_OK);
}

// The calibration of s over the regions calibrate would choose, printed.
static gf_dem_calibration calibrate_series(const gf_series *s)
{
    gf_analysis_opts o;
    gf_dem_calibration_opts(s, NULL, &o);
    gf_dem_calibration cal;
    if (gf_dem_calibrate(s, &o, &s->cfg, &cal) != GF_OK) fail_msg("%s", gf_last_error());
    gf_dem_calibration_print(&cal, stdout);
    return cal;
}

static void recovers_chosen_parameters(void **state)
{
    (void)state;
    gf_config c = chosen_model();
    c.container_width = 24;
    c.packing_particles = 9000;
    gf_series s;
    gf_dem_load_report rep;
    run_and_load(&c, "run", &s, &rep);
    assert_int_equal(s.nframes, 31);
    // Without relaxation nothing holds particles above the base away from
    // the orifice, so a few sink below z = 0 there: counted as exited (~1% of
    // the outflow), as a DEM run's particles below the base are.
    assert_true(rep.below_base < 0.02 * 31 * 9000);
    gf_dem_calibration cal = calibrate_series(&s);

    // Tolerances. Statistical: the sub-window scatter gives 2-5% (printed
    // above). Systematic (this silo, seed 11: -2%, +5%, +6%, +9%, +3%; see
    // docs/dem.md): the velocity profiles near the orifice carry the birth
    // spread and the walls 12 d away flatten their tails (d Var/dz about +9%,
    // so step_xy +4.5%); tracked particles keep a little of the converging
    // mean flow in Var(dx) (b_p +3%); w = b_s / b_p and lambda = Q w / p
    // inherit these. So: r_s, step_xy and mu within 10%, w within 20%,
    // lambda (the product of three measured factors) within 25%.
    struct {
        const char *name;
        double got, err, want, tol;
    } v[] = {
        {"spot.radius", cal.radius.value, cal.radius.err, c.spot_radius, 0.10},
        {"spot.step_xy", cal.step_xy.value, cal.step_xy.err, c.spot_step_xy, 0.10},
        {"spot.w", cal.w.value, cal.w.err, c.spot_w, 0.20},
        {"spot.insertion_rate", cal.insertion_rate.value, cal.insertion_rate.err, c.spot_insertion_rate, 0.25},
        {"spot.move_rate", cal.move_rate.value, cal.move_rate.err, c.spot_move_rate, 0.10},
    };
    for (size_t k = 0; k < sizeof v / sizeof v[0]; k++) {
        double rel = (v[k].got - v[k].want) / v[k].want;
        print_message("%-20s chosen %8.4g  recovered %8.4g +- %-8.3g (%+.1f%%, tolerance %.0f%%)\n", v[k].name,
                      v[k].want, v[k].got, v[k].err, 100 * rel, 100 * v[k].tol);
        if (!(fabs(rel) <= v[k].tol)) fail_msg("%s: recovered %g, chosen %g", v[k].name, v[k].got, v[k].want);
        // The stated uncertainty is an uncertainty: finite and a few percent at most.
        assert_true(isfinite(v[k].err) && v[k].err > 0 && v[k].err < 0.2 * v[k].got);
    }
    // The calibrated config runs as it is.
    gf_config out = s.cfg;
    assert_int_equal(gf_dem_calibration_apply(&cal, &out), GF_OK);
    assert_true(out.spot_radius == cal.radius.value && out.spot_move_rate == cal.move_rate.value);
    gf_series_free(&s);
}

// A cylinder (radius 12 d, the chosen parameters above, 30 tau): what the
// calibration measures that depends on the container's shape. The profiles
// are radial (per-axis Var), so d Var/dz comes from >= 5 heights and gives
// step_xy back within 10% (+4.3% measured); the density slice's volume is the
// disc's and the spot balls are placed about the axis, so the particles a
// ball holds agree with phi V_ball / V_p within 3% (0.4% measured; with the
// box's 50 x 8 section the slice's phi came out 12% high) and phi is a
// packing's. The correlation and diffusion estimators subtract the
// axisymmetric mean flow (before: a mean of (x, z) averaged over y, which
// gave beta +37% and b_p ~4x here).
static void calibration_measures_a_cylinder(void **state)
{
    (void)state;
    gf_config c = chosen_model();
    c.container_shape = GF_SHAPE_CYLINDER;
    c.container_radius = 12;
    c.packing_particles = 12500;
    gf_series s;
    gf_dem_load_report rep;
    run_and_load(&c, "cylinder", &s, &rep);
    gf_dem_calibration cal = calibrate_series(&s);
    print_message("cylinder: %zu heights, step_xy %.4g (chosen 0.55), p %.4g, bulk %.4g\n", cal.var_heights,
                  cal.step_xy.value, cal.ball_count.value, cal.ball_count_bulk);
    assert_true(cal.var_heights >= 5);
    gf_assert_near(cal.step_xy.value, c.spot_step_xy, 0.10 * c.spot_step_xy);
    gf_assert_near(cal.ball_count.value, cal.ball_count_bulk, 0.03 * cal.ball_count_bulk);
    double rs = cal.radius.value, phi = cal.ball_count_bulk / (8.0 * rs * rs * rs); // p = phi (2 r_s / d)^3
    assert_true(phi > 0.55 && phi < 0.64);
    // The correlation and diffusion lengths with the axisymmetric mean flow
    // taken out (fluctuations about v(r, z); tangential displacements). r_s
    // within the box test's 10% (old estimator: 3.02, +37%; now 2.03). The
    // converging flow no longer leaks into b_p: it must not exceed b_s / w by
    // more than 20%, so w is not under-read (old: b_p 2.7x b_s / w, w 113).
    // Not asserted within 20%: this spot run's tracked particles diffuse at
    // ~0.6 b_s / w even at small dz (docs/dem.md), so w reads ~580.
    print_message("cylinder: spot.radius %.4g (chosen 2.2, beta %.4g), spot.w %.4g (chosen 300, b_p %.4g, b_s / w %.4g)\n",
                  cal.radius.value, cal.corr_length.value, cal.w.value, cal.diff_length.value,
                  cal.b_s.value / c.spot_w);
    gf_assert_near(cal.radius.value, c.spot_radius, 0.10 * c.spot_radius);
    assert_true(cal.diff_length.value < 1.2 * cal.b_s.value / c.spot_w);
    assert_true(cal.w.value > 0.8 * c.spot_w);
    gf_series_free(&s);
}

static void show_refine(void *ctx, int iter, int max_iter, const gf_config *c, const gf_dem_flowstats *dem,
                        const gf_dem_flowstats *spot, bool match)
{
    (void)ctx;
    print_message("refine %d/%d: step_xy %.4g w %.4g lambda %.4g mu %.4g r_s %.4g -> Q %.4g (DEM %.4g)%s\n", iter,
                  max_iter, c->spot_step_xy, c->spot_w, c->spot_insertion_rate, c->spot_move_rate, c->spot_radius,
                  spot->flow.value, dem->flow.value, match ? " matched" : "");
    for (size_t z = 0; z < dem->nz && z < spot->nz; z++) // Var spot / DEM at each height (nan: not steady)
        print_message("  z %.3g: Var %.4g / %.4g (%+.1f%%)\n", dem->z[z], spot->var[z].value, dem->var[z].value,
                      100.0 * (spot->var[z].value / dem->var[z].value - 1.0));
}

// Closed loop: a granflow reference with chosen parameters (lambda 250 and
// step_xy 0.5, not the defaults); the refinement starts from the defaults
// (lambda 375, step_xy 0.676: flow +45%, Var +80%) and must bring the spot
// run within 5% of the reference's flow and 10% of its Var(z), and the
// parameters that set them back near the chosen ones. The other three
// start right (the test is of the loop, not of the thesis relations, which
// recovers_chosen_parameters tests). About 10 s of CPU.
/// The refinement tests' granflow reference: a 20 x 8 box, orifice 6,
/// 5,000 spheres, no relaxation, 16 tau, snapshots every 0.5 tau, with the
/// chosen step_xy, lambda and r_s, run into NAME and loaded with the
/// calibration's options.
static gf_config reference(const char *name, double step_xy, double lambda, double r_s, gf_series *s,
                           gf_analysis_opts *o)
{
    gf_config c = gf_config_default();
    c.container_width = 20;
    c.container_depth = 8;
    c.orifice_diameter = 6;
    c.packing_particles = 5000;
    c.spot_step_xy = step_xy;
    c.spot_insertion_rate = lambda;
    c.spot_radius = r_s;
    c.relax_method = GF_RELAX_NONE;
    c.run_duration = 16;
    c.run_seed = 5;
    c.output_snapshot_interval = 0.5;
    char dir[1024];
    snprintf(dir, sizeof dir, "%s/%s", gf_test_tmpdir(), name);
    gf_run_opts ro = {.dir = dir};
    assert_int_equal(gf_run_dir(&c, &ro, NULL), GF_OK);
    assert_int_equal(gf_dem_series_load(dir, NULL, s, NULL), GF_OK);
    *o = gf_analysis_opts_default();
    assert_int_equal(gf_dem_window(s, o, NULL), GF_OK);
    gf_dem_calibration_opts(s, o, o);
    // One window for every height. With the window per height (issue 27) this
    // short draining reference has heights near the orifice judged "still
    // speeding up" in some spot runs and not in others with the same
    // parameters (z = 7.4 and 8.8 at step_xy 0.50), and its Var varies by
    // ~15% from run to run at the top, against errors of 1-2% from the
    // sub-windows: no loop can meet 10% at every height there.
    o->vel_window = GF_VEL_WINDOW_RUN;
    return c;
}

static void refine_recovers_flow_and_width(void **state)
{
    (void)state;
    gf_series s;
    gf_analysis_opts o;
    gf_config c = reference("ref", 0.5, 250, 2.6, &s, &o);

    gf_config start = s.cfg;
    start.spot_step_xy = 0.676;
    start.spot_insertion_rate = 375;
    start.run_seed = 77; // not the reference's own noise
    gf_dem_refine_opts opts = {.progress = show_refine, .max_iter = 6};
    gf_dem_refine_result res;
    if (gf_dem_refine(&s, &o, &start, &opts, &res) != GF_OK) fail_msg("%s", gf_last_error());
    gf_dem_flowstats_table(&res.dem, &res.first, GF_DEM_FLOW_TOL, GF_DEM_VAR_TOL, stdout);
    gf_dem_flowstats_table(&res.dem, &res.last, GF_DEM_FLOW_TOL, GF_DEM_VAR_TOL, stdout);
    // The first guess is off by far more than the tolerances; the end is within.
    assert_false(gf_dem_flowstats_match(&res.dem, &res.first, GF_DEM_FLOW_TOL, GF_DEM_VAR_TOL));
    assert_true(res.matched);
    assert_true(gf_dem_flowstats_match(&res.dem, &res.last, GF_DEM_FLOW_TOL, GF_DEM_VAR_TOL));
    gf_assert_near(res.last.flow.value, res.dem.flow.value, GF_DEM_FLOW_TOL * res.dem.flow.value);
    // The parameters: the flow fixes lambda / w (Q = lambda p / w), within
    // 10% (the flow's 5% plus its noise); step_xy within 10% (Var ~ dx^2:
    // the 10% of Var is 5% of dx, plus noise); w, mu and r_s, right from the
    // start, stay within 20% (they move only on a 2-sigma difference).
    print_message("recovered lambda %.4g, w %.4g (lambda / w %.4g, chosen %.4g), step_xy %.4g (chosen 0.5) in %d runs\n",
                  start.spot_insertion_rate, start.spot_w, start.spot_insertion_rate / start.spot_w,
                  c.spot_insertion_rate / c.spot_w, start.spot_step_xy, res.runs);
    double ratio = c.spot_insertion_rate / c.spot_w;
    gf_assert_near(start.spot_insertion_rate / start.spot_w, ratio, 0.10 * ratio);
    gf_assert_near(start.spot_step_xy, 0.5, 0.05);
    gf_assert_near(start.spot_w, c.spot_w, 0.2 * c.spot_w);
    gf_assert_near(start.spot_move_rate, c.spot_move_rate, 0.2 * c.spot_move_rate);
    gf_assert_near(start.spot_radius, c.spot_radius, 0.2 * c.spot_radius);
    gf_series_free(&s);
}

// Issue 27 item 3: the three parameters that set the flow and the Var(z)
// line, recovered together. A granflow reference with lambda 250, step_xy
// 0.5 and r_s 2.2 (none the defaults); the refinement starts from the
// defaults (375, 0.676, 2.6) with the correlation length out of reach (the
// region of 3 d holds no beta), so r_s is left to the widths' level; it
// must match, and give the three back (below). w and mu start right and
// stay within 20%.
static void refine_recovers_three_parameters(void **state)
{
    (void)state;
    gf_series s;
    gf_analysis_opts o;
    gf_config c = reference("ref3", 0.5, 250, 2.2, &s, &o);
    o.corr_size = 3.0; // beta > 1.5 d: not measurable here, r_s free

    gf_config start = s.cfg;
    start.spot_step_xy = 0.676;
    start.spot_insertion_rate = 375;
    start.spot_radius = 2.6;
    start.spot_insertion_margin = NAN;
    start.relax_radius = NAN;
    start.run_seed = 77;
    assert_int_equal(gf_config_validate(&start), GF_OK);
    gf_dem_refine_opts opts = {.progress = show_refine, .max_iter = 6};
    gf_dem_refine_result res;
    if (gf_dem_refine(&s, &o, &start, &opts, &res) != GF_OK) fail_msg("%s", gf_last_error());
    gf_dem_flowstats_table(&res.dem, &res.last, GF_DEM_FLOW_TOL, GF_DEM_VAR_TOL, stdout);
    gf_dem_refine_print(&res, stdout);
    assert_false(gf_dem_flowstats_match(&res.dem, &res.first, GF_DEM_FLOW_TOL, GF_DEM_VAR_TOL));
    assert_true(res.matched);
    assert_string_equal(res.unreached, "");
    // Each fitted, with its error. step_xy within twice its error (plus the
    // 10% of Var's share, 5%); the flow fixes lambda r_s^3 / w (Q = lambda p
    // / w, p ~ r_s^3): within 10%; r_s within 0.5 d. lambda alone is not
    // asserted within its error: the Var(z) line holds r_s loosely and
    // lambda follows r_s^3, and the errors, from the sub-windows' noise,
    // understate the noise between runs (measured: lambda 194 +- 15 and r_s
    // 2.35 +- 0.06 for 250 and 2.2; lambda r_s^3 / w -5%).
    assert_true(isfinite(res.insertion_rate.err) && isfinite(res.step_xy.err) && isfinite(res.radius.err));
    gf_assert_near(res.step_xy.value, 0.5, 2.0 * res.step_xy.err + 0.05 * 0.5);
    double q = c.spot_insertion_rate * pow(c.spot_radius, 3) / c.spot_w;
    gf_assert_near(res.insertion_rate.value * pow(res.radius.value, 3) / start.spot_w, q, 0.10 * q);
    gf_assert_near(res.radius.value, 2.2, 0.5);
    assert_true(res.radius.value == start.spot_radius && res.step_xy.value == start.spot_step_xy);
    gf_assert_near(start.spot_w, c.spot_w, 0.2 * c.spot_w);
    gf_assert_near(start.spot_move_rate, c.spot_move_rate, 0.2 * c.spot_move_rate);
    gf_series_free(&s);
}

// Issue 28: a hopper's reference must not drive the loop's parameters away.
// The 60-degree cone of docs/stress.md in DEM flows as a plug over its
// funnel (Var of v_z(r) 60-67 d^2 there); calibrated with the papers' walk
// it needs step_xy ~2.8 (4x the thesis'). A granflow reference made that
// way (a cylinder of radius 8 over a 60-degree cone to a 6 d outlet,
// step_xy 2.5, 10 tau) is calibrated and refined as `granflow calibrate`
// does: before the refinement fitted lambda, step_xy and r_s together it
// drove w from 1,470 to 11,170 and lambda from 90 to 1,820 on such a
// hopper; now every run's w and lambda must stay within 3x of the first
// guess, and the flow must match.
typedef struct bounds_seen {
    double w0, lambda0, worst;
} bounds_seen;

static void track_bounds(void *ctx, int iter, int max_iter, const gf_config *c, const gf_dem_flowstats *dem,
                         const gf_dem_flowstats *spot, bool match)
{
    bounds_seen *b = ctx;
    show_refine(NULL, iter, max_iter, c, dem, spot, match);
    double rw = c->spot_w / b->w0, rl = c->spot_insertion_rate / b->lambda0;
    b->worst = fmax(b->worst, fmax(fmax(rw, 1.0 / rw), fmax(rl, 1.0 / rl)));
}

static void refine_keeps_a_hoppers_parameters_bounded(void **state)
{
    (void)state;
    gf_config c = gf_config_default();
    const char *set[] = {"container.shape=cylinder", "container.radius=8", "container.hopper_angle=60",
                         "container.outlet_diameter=6", "container.outlet_length=1", "packing.fill_height=17",
                         "spot.step_xy=2.5", "spot.insertion_rate=211", "run.duration=10",
                         "output.snapshot_interval=0.5", "run.seed=3", NULL};
    for (int i = 0; set[i]; i++) assert_int_equal(gf_config_set(&c, set[i], "--set"), GF_OK);
    assert_int_equal(gf_config_validate(&c), GF_OK);
    char dir[1024];
    snprintf(dir, sizeof dir, "%s/hopper", gf_test_tmpdir());
    gf_run_opts ro = {.dir = dir};
    assert_int_equal(gf_run_dir(&c, &ro, NULL), GF_OK);
    gf_series s;
    assert_int_equal(gf_dem_series_load(dir, NULL, &s, NULL), GF_OK);
    gf_analysis_opts o = gf_analysis_opts_default();
    assert_int_equal(gf_dem_window(&s, &o, NULL), GF_OK);
    gf_dem_calibration_opts(&s, &o, &o);
    gf_dem_calibration cal;
    if (gf_dem_calibrate(&s, &o, &s.cfg, &cal) != GF_OK) fail_msg("%s", gf_last_error());
    gf_config start = s.cfg;
    start.spot_step_xy = 0.676; // calibrate's first guess of step_xy from b_p is not what is tested
    start.run_seed = 77;
    assert_int_equal(gf_dem_calibration_apply(&cal, &start), GF_OK);
    start.spot_step_xy = 0.676;
    bounds_seen b = {.w0 = start.spot_w, .lambda0 = start.spot_insertion_rate, .worst = 1.0};
    gf_dem_refine_opts opts = {.progress = track_bounds, .ctx = &b, .max_iter = 6, .start = &s.frames[0].pk};
    gf_dem_refine_result res;
    if (gf_dem_refine(&s, &o, &start, &opts, &res) != GF_OK) fail_msg("%s", gf_last_error());
    gf_dem_flowstats_table(&res.dem, &res.last, GF_DEM_FLOW_TOL, GF_DEM_VAR_TOL, stdout);
    print_message("first guess w %.4g lambda %.4g; refined w %.4g lambda %.4g step_xy %.4g r_s %.4g; "
                  "largest factor from the first guess over the runs %.3g\n",
                  b.w0, b.lambda0, start.spot_w, start.spot_insertion_rate, start.spot_step_xy, start.spot_radius,
                  b.worst);
    assert_true(b.worst <= 3.0);
    // The flow within twice the loop's tolerance (10 tau of this small cone
    // leave the flow's error at 7%): it is what the bounded lambda must give.
    gf_assert_near(res.last.flow.value, res.dem.flow.value, 2.0 * GF_DEM_FLOW_TOL * res.dem.flow.value);
    assert_true(start.spot_step_xy > 1.5); // the width came from the step, not from w or lambda
    gf_series_free(&s);
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(recovers_chosen_parameters),
    cmocka_unit_test(calibration_measures_a_cylinder),
    cmocka_unit_test(refine_recovers_flow_and_width),
    cmocka_unit_test(refine_recovers_three_parameters),
    cmocka_unit_test(refine_keeps_a_hoppers_parameters_bounded),
};

GF_TEST_MAIN("dem_calibrate_nosan", tests)
