// SPDX-License-Identifier: MIT
// The domain engine (run.order = domains) drains like the event-driven
// engine (2009 paper Sec. 2.1: reordering spot motions "while still
// achieving similar results"), and this test sees an engine that drops the
// spots whose moves cross a sector boundary (gf_dom_test_drop_crossing):
// it must pass on the engine and fail on that one.
// ctest: nosan
#include "support.h"

#include <math.h>
#include <stdio.h>

#include "granflow/granflow.h"
#include "spot/sim_internal.h"

#define NBATCH 12

// How the domain engine cuts the silo.
typedef enum cut {
    CUT_XZ,       ///< 2 x 1 x 2 sectors of ~16 d, a window of 0.2 tau (the table of docs/performance.md)
    CUT_DEFAULTS, ///< the keys' defaults (parallel.cut, parallel.sectors, parallel.window)
} cut;

// A 20 x 8 silo of 4000 spheres (~21 d tall) with the papers' spots, in
// steady flow after ~6 tau. CUT_XZ: cut along x and z into 2 x 1 x 2
// sectors of ~16 d (two per cut axis), with a window of 0.2 tau (5.6 moves
// per spot, 40 times the default): every spot rising from the orifice
// crosses a sector boundary. CUT_DEFAULTS: the defaults' decomposition.
static gf_config flow_silo(gf_run_mode mode, cut how)
{
    gf_config c = gf_test_silo_config(20, 4000, 1);
    c.run_mode = mode;
    if (mode == GF_MODE_FIXED) {
        c.run_order = GF_ORDER_DOMAINS;
        c.run_threads = 2;
        if (how == CUT_XZ) {
            c.parallel_cut = 7;
            c.parallel_sectors = 2;
            c.parallel_window = 0.2;
        }
    }
    assert_int_equal(gf_config_validate(&c), GF_OK);
    return c;
}

typedef struct drainage {
    double rate, rate_se;   ///< drainage per tau: summed particle z displacement, d^4/tau, and its standard error
    double move, move_se;   ///< drainage per spot move, and its standard error
    double moves;           ///< spot moves per tau
    size_t exits;           ///< particles that left in the window
} drainage;

static void batch_mean(const double *v, int n, double *mean, double *se)
{
    double m = 0.0, var = 0.0;
    for (int b = 0; b < n; b++) m += v[b] / n;
    for (int b = 0; b < n; b++) var += (v[b] - m) * (v[b] - m) / (n - 1);
    *mean = m;
    *se = sqrt(var / n);
}

// Drainage per tau and per spot move over NBATCH windows of 0.5 tau from
// t = 6 tau (steady flow). In steady flow the summed z displacement per tau
// is the flow rate times the column height: the flow rate without the
// Poisson noise of single exits. Standard errors from the batches' spread.
static drainage drain(gf_run_mode mode, cut how, bool broken)
{
    gf_config c = flow_silo(mode, how);
    gf_sim *sim = gf_test_generated_sim(&c);
    if (broken) assert_int_equal(gf_dom_test_drop_crossing(sim), GF_OK);
    double t = 6.0, f[NBATCH], g[NBATCH], m = 0.0;
    assert_int_equal(gf_sim_run(sim, t, NULL), GF_OK);
    gf_sim_stats a = gf_sim_get_stats(sim), first = a;
    for (int b = 0; b < NBATCH; b++) {
        t += 0.5;
        assert_int_equal(gf_sim_run(sim, t, NULL), GF_OK);
        gf_sim_stats z = gf_sim_get_stats(sim);
        double dz = -((z.spot_dz - a.spot_dz) + (z.relax_dz - a.relax_dz));
        f[b] = dz / 0.5;
        g[b] = dz / (double)(z.spot_moves - a.spot_moves);
        m += (double)(z.spot_moves - a.spot_moves) / (0.5 * NBATCH);
        a = z;
    }
    drainage d = {.exits = a.particles_exited - first.particles_exited, .moves = m};
    gf_sim_destroy(sim);
    batch_mean(f, NBATCH, &d.rate, &d.rate_se);
    batch_mean(g, NBATCH, &d.move, &d.move_se);
    return d;
}

static double zscore(const drainage *a, const drainage *b)
{
    return (b->rate - a->rate) / sqrt(a->rate_se * a->rate_se + b->rate_se * b->rate_se);
}

// The event engine's drainage, run once for both cases.
static drainage event_drainage(void)
{
    static drainage ev;
    static bool done;
    if (!done) ev = drain(GF_MODE_EVENT, CUT_XZ, false);
    done = true;
    return ev;
}

// The engine's drainage per tau and per move agree with the event engine's
// within 3 standard errors of the difference, the outflow within 4 Poisson
// standard deviations. In steady flow the flow rate is lambda times the
// drainage of a spot's life, and a spot makes as many moves in its life in
// both engines (it rises step_z a move), so the drainage per move carries
// the flow rate's comparison free of the insertions' Poisson noise; its
// standard error resolves a 3% difference (3 se < 3%). The engine that
// drops crossing spots is more than 3 standard errors off.
static void drains_like_the_event_engine(cut how)
{
    drainage ev = event_drainage(), dm = drain(GF_MODE_FIXED, how, false), bad = drain(GF_MODE_FIXED, how, true);
    double se_move = sqrt(ev.move_se * ev.move_se + dm.move_se * dm.move_se);
    print_message("%s: drainage per tau: event %.1f +- %.1f, domains %.1f +- %.1f (%+.2f%%, z = %+.2f), dropping "
                  "crossings %.1f +- %.1f (%+.2f%%, z = %+.2f); per move %.5f +- %.5f, %.5f +- %.5f; moves per tau "
                  "%.0f, %.0f, %.0f; exits %zu, %zu, %zu\n",
                  how == CUT_XZ ? "x and z cut, W = 0.2" : "defaults", ev.rate, ev.rate_se, dm.rate, dm.rate_se,
                  100.0 * (dm.rate / ev.rate - 1.0), zscore(&ev, &dm), bad.rate, bad.rate_se,
                  100.0 * (bad.rate / ev.rate - 1.0), zscore(&ev, &bad), ev.move, ev.move_se, dm.move, dm.move_se,
                  ev.moves, dm.moves, bad.moves, ev.exits, dm.exits, bad.exits);
    assert_true(ev.rate > 0.0 && ev.exits > 200);
    assert_true(3.0 * se_move < 0.03 * ev.move);
    assert_true(fabs(zscore(&ev, &dm)) < 3.0);
    assert_true(fabs(dm.move - ev.move) < 3.0 * se_move);
    assert_true(fabs((double)dm.exits - (double)ev.exits) < 4.0 * sqrt((double)(dm.exits + ev.exits)));
    assert_true(fabs(zscore(&ev, &bad)) > 3.0 || fabs(bad.move - ev.move) > 3.0 * se_move);
}

static void domain_engine_drains_like_the_event_engine(void **state)
{
    (void)state;
    drains_like_the_event_engine(CUT_XZ);
}

// The same with the decomposition and window a run gets by default.
static void default_decomposition_drains_like_the_event_engine(void **state)
{
    (void)state;
    drains_like_the_event_engine(CUT_DEFAULTS);
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(domain_engine_drains_like_the_event_engine),
    cmocka_unit_test(default_decomposition_drains_like_the_event_engine),
};

GF_TEST_MAIN("domains_flow", tests)
