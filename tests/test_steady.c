// SPDX-License-Identifier: MIT
// The steady-flow window from the outflow (gf_steady_window_curve): on
// synthetic drainages that ramp up from rest, flow steadily, then empty, the
// window must be the linear part, and its rate the steady one.
#include "support.h"

#include <math.h>
#include <string.h>

#include "core/alloc.h"
#include "core/rng.h"
#include "granflow/analysis.h"

#define NF 121 // snapshots every 0.25 tau over 30 tau

/// Particles exited by time t: rate ramping linearly from 0 to R over
/// [0, ta], R until tb, then falling linearly to 0 at te.
static double exited(double t, double R, double ta, double tb, double te)
{
    if (t <= ta) return 0.5 * R * t * t / ta;
    double c = 0.5 * R * ta;
    if (t <= tb) return c + R * (t - ta);
    c += R * (tb - ta);
    double u = fmin(t, te) - tb, T = te - tb;
    return c + R * (u - 0.5 * u * u / T);
}

static void curve(double *t, double *c, double R, double ta, double tb, double te)
{
    for (size_t k = 0; k < NF; k++) {
        t[k] = 0.25 * (double)k;
        c[k] = exited(t[k], R, ta, tb, te);
    }
}

static void ramp_linear_emptying(void **state)
{
    (void)state;
    double t[NF], c[NF];
    curve(t, c, 50.0, 4.0, 24.0, 30.0);
    gf_steady w;
    assert_int_equal(gf_steady_window_curve(t, c, NF, &w), GF_OK);
    assert_true(w.found);
    print_message("window %g..%g: %s\n", w.t0, w.t1, w.reason);
    // The linear part [4, 24], give or take the 0.5% of rate an edge chunk
    // (here 2.5 tau) may differ by: its first 0.3 tau of ramp, 0.4 tau of
    // emptying (R dt^2 / (2 T) / 2.5 tau < 0.5% R), so one frame either side.
    assert_true(w.t0 >= 3.5 && w.t0 <= 4.5);
    assert_true(w.t1 >= 23.5 && w.t1 <= 24.5);
    gf_assert_near(w.rate, 50.0, 0.005 * 50.0);
    assert_non_null(strstr(w.reason, "start-up"));
    assert_non_null(strstr(w.reason, "emptying"));
}

static void steady_to_the_end(void **state)
{
    (void)state;
    // A silo that never empties within the run: the window reaches the end.
    double t[NF], c[NF];
    curve(t, c, 30.0, 2.0, 1e9, 2e9);
    gf_steady w;
    assert_int_equal(gf_steady_window_curve(t, c, NF, &w), GF_OK);
    assert_true(w.found);
    print_message("window %g..%g: %s\n", w.t0, w.t1, w.reason);
    assert_true(w.t0 >= 1.5 && w.t0 <= 2.5);
    gf_assert_near(w.t1, 30.0, 1e-12);
    gf_assert_near(w.rate, 30.0, 0.005 * 30.0);
    assert_non_null(strstr(w.reason, "to the end of the run"));
}

// Exits of a Poisson process with the same time-dependent rate (thinning):
// the edges are found as far as the noise lets the transients be seen (an
// edge chunk of ~3 tau has a rate noise of ~4% here, so up to ~2 tau of a
// slow ramp look steady), over 20 seeds, and the rate is within 4 standard
// errors (+ 3% for those edges) of the steady one.
static void noisy_exits(void **state)
{
    (void)state;
    const double R = 200.0, ta = 4.0, tb = 24.0, te = 30.0;
    for (uint64_t seed = 1; seed <= 20; seed++) {
        gf_rng rng;
        gf_rng_seed(&rng, seed, 0);
        double t[NF], c[NF];
        for (size_t k = 0; k < NF; k++) {
            t[k] = 0.25 * (double)k;
            c[k] = 0.0;
        }
        double now = 0.0;
        for (;;) {
            now += gf_rng_exp(&rng, R);
            if (now > 30.0) break;
            double rate = now < ta ? R * now / ta : now < tb ? R : R * (te - now) / (te - tb);
            if (gf_rng_uniform(&rng) * R >= rate) continue;
            for (size_t k = (size_t)ceil(now / 0.25); k < NF; k++) c[k] += 1.0;
        }
        gf_steady w;
        assert_int_equal(gf_steady_window_curve(t, c, NF, &w), GF_OK);
        if (!w.found) print_error("seed %llu: %s\n", (unsigned long long)seed, w.reason);
        assert_true(w.found);
        if (!(w.t0 >= ta - 2.0 && w.t0 <= ta + 2.0 && w.t1 >= tb - 2.0 && w.t1 <= tb + 2.5))
            print_error("seed %llu: window %g..%g (%s)\n", (unsigned long long)seed, w.t0, w.t1, w.reason);
        assert_true(w.t0 >= ta - 2.0 && w.t0 <= ta + 2.0);
        assert_true(w.t1 >= tb - 2.0 && w.t1 <= tb + 2.5);
        double se = sqrt(R * (w.t1 - w.t0)) / (w.t1 - w.t0); // Poisson count over the window
        gf_assert_near(w.rate, R, 4.0 * se + 0.03 * R); // + the bias of edges inside the transients
    }
}

static void no_flow_falls_back(void **state)
{
    (void)state;
    double t[NF], c[NF];
    for (size_t k = 0; k < NF; k++) {
        t[k] = 0.25 * (double)k;
        c[k] = k > 100 ? 3.0 : 0.0;
    }
    gf_steady w;
    assert_int_equal(gf_steady_window_curve(t, c, NF, &w), GF_OK);
    assert_false(w.found);
    gf_assert_near(w.t0, 7.5, 1e-12); // the default: a quarter in, to the end
    gf_assert_near(w.t1, 30.0, 1e-12);
    assert_true(isnan(w.rate));
    assert_non_null(strstr(w.reason, "only 3 particles exited"));
    // Three snapshots cannot show a transient.
    assert_int_equal(gf_steady_window_curve(t, c, 3, &w), GF_OK);
    assert_false(w.found);
    assert_non_null(strstr(w.reason, "too few snapshots"));
}

// A recirculating run (run.recirculate = on): every exited particle is put
// back, so each frame holds the same count; the outflow curve is read from
// exits.csv instead (it used to be flat: "only 0 particles exited", fallback).
// Exits every 0.02 tau from t = 2 (rate 50), frames every 0.25 tau over 30 tau.
static void recirculating_run_uses_the_exits(void **state)
{
    (void)state;
    gf_series s = gf_test_series(NF, 20, 20);
    for (size_t k = 0; k < NF; k++) {
        s.frames[k].time = 0.25 * (double)k;
        assert_int_equal(gf_packing_push(&s.frames[k].pk, 1, 1, 0.0, 0.0, 5.0, 0.5), GF_OK);
    }
    s.n_initial = 1;
    s.cfg.run_recirculate = 1;
    const size_t ne = 1400; // t = 2.01 .. 29.99
    s.exits = GF_NEW(gf_exit, ne);
    assert_non_null(s.exits);
    for (size_t e = 0; e < ne; e++) s.exits[e] = (gf_exit){.id = 1, .time = 2.01 + 0.02 * (double)e, .pass = (int64_t)e + 1};
    s.nexits = ne;
    s.has_exits = true;
    gf_steady w;
    assert_int_equal(gf_steady_window(&s, &w), GF_OK);
    print_message("window %g..%g: %s\n", w.t0, w.t1, w.reason);
    assert_true(w.found);
    assert_true(w.t0 >= 1.75 && w.t0 <= 2.75);
    gf_assert_near(w.rate, 50.0, 0.01 * 50.0);
    gf_series_free(&s);
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(ramp_linear_emptying),
    cmocka_unit_test(steady_to_the_end),
    cmocka_unit_test(noisy_exits),
    cmocka_unit_test(no_flow_falls_back),
    cmocka_unit_test(recirculating_run_uses_the_exits),
};

GF_TEST_MAIN("steady", tests)
