// SPDX-License-Identifier: MIT
// The spot engine on small silos: invariants of a drainage, the drift of a
// spot move, the mass balance of SPEC 1.3, determinism and exact resumption.
#include "support.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "granflow/granflow.h"
#include "spot/sim_internal.h"



// ---- invariants over a drainage --------------------------------------------

typedef struct inv_ctx {
    gf_packing pk;
    size_t snapshots;
    double worst_wall, worst_pair;
} inv_ctx;

static gf_status check_snapshot(void *ctx, const gf_sim *sim, uint64_t index, double time)
{
    (void)index;
    (void)time;
    inv_ctx *ic = ctx;
    gf_sim_stats s = gf_sim_get_stats(sim);
    // Particles in + exited = particles at the start, at every snapshot.
    assert_int_equal(s.particles_remaining + s.particles_exited, s.particles_initial);
    assert_int_equal(gf_sim_particles(sim, &ic->pk), GF_OK);
    assert_int_equal(ic->pk.n, s.particles_remaining);
    const gf_config *c = gf_sim_config(sim);
    double hw = 0.5 * c->container_width, hd = 0.5 * c->container_depth, R = 0.5 * c->orifice_diameter;
    for (size_t i = 0; i < ic->pk.n; i++) {
        double x = ic->pk.x[i], y = ic->pk.y[i], z = ic->pk.z[i];
        // Nothing is outside the container except over (and falling through) the hole.
        double gap = fmin(fmin(hw - fabs(x), hd - fabs(y)), x * x + y * y < R * R ? INFINITY : z);
        if (gap < ic->worst_wall) ic->worst_wall = gap;
        assert_true(z >= c->exit_z);
    }
    double dmin = gf_packing_min_distance(&ic->pk);
    if (dmin < ic->worst_pair) ic->worst_pair = dmin;
    ic->snapshots++;
    return GF_OK;
}

static void drain_with(gf_config c)
{
    c.output_snapshot_interval = 1.0;
    gf_sim *sim = gf_test_generated_sim(&c);
    inv_ctx ic = {.worst_wall = INFINITY, .worst_pair = INFINITY};
    gf_sim_hooks hooks = {.ctx = &ic, .snapshot = check_snapshot};
    // Spots reach the top (z ~ 17) after ~6 tau: 12 tau is well into steady flow.
    assert_int_equal(gf_sim_run(sim, 12.0, &hooks), GF_OK);
    gf_sim_stats s = gf_sim_get_stats(sim);
    print_message("drain: %zu snapshots, %zu of %zu exited, min pair distance %.4f, min wall gap %.4f\n",
                  ic.snapshots, s.particles_exited, s.particles_initial, ic.worst_pair, ic.worst_wall);
    assert_int_equal(ic.snapshots, 13);
    assert_true(s.particles_exited > 300); // it flows
    assert_true(ic.worst_pair >= 0.98);
    assert_true(ic.worst_wall >= 0.5 - 0.02);
    gf_packing_free(&ic.pk);
    gf_sim_destroy(sim);
}

static void drain_keeps_invariants(void **state)
{
    (void)state;
    drain_with(gf_test_silo_config(16, 2500, 3));
}

// The same for the parallel spatial fixed step, on two threads.
static void spatial_step_keeps_invariants(void **state)
{
    (void)state;
    gf_config c = gf_test_silo_config(16, 2500, 3);
    c.run_mode = GF_MODE_FIXED;
    c.run_order = GF_ORDER_SPATIAL;
    c.run_threads = 2;
    drain_with(c);
}

// ---- mean drift of one spot move --------------------------------------------

typedef struct drift {
    double mean[3], se[3];
} drift;

// Mean displacement of a ball's particles over `trials` spot steps from random
// points in the bulk (|x| < 4, |y| < 1, z0 < z < z0 + 8): sum of all particle
// displacements (spot + relax) divided by the ball's population.
static drift measure_drift(gf_sim *sim, size_t trials, double z0)
{
    double *x0 = malloc(sizeof(double) * 3 * sim->n);
    double sum[3] = {0}, sum2[3] = {0};
    for (size_t t = 0; t < trials; t++) {
        double s[3] = {-4 + 8 * gf_rng_uniform(&sim->rng), -1 + 2 * gf_rng_uniform(&sim->rng),
                       z0 + 8 * gf_rng_uniform(&sim->rng)};
        x0 = realloc(x0, sizeof(double) * 3 * sim->n);
        for (size_t i = 0; i < sim->n; i++) {
            x0[3 * i] = sim->p[i].x;
            x0[3 * i + 1] = sim->p[i].y;
            x0[3 * i + 2] = sim->p[i].z;
        }
        bool deleted;
        long ball;
        uint32_t count = 0;
        assert_int_equal(gf_spot_step(sim, &sim->w0, s, &count, &deleted, &ball), GF_OK);
        assert_false(deleted);
        assert_true(ball > 30);
        double d[3] = {0};
        for (size_t i = 0; i < sim->n; i++) {
            if (!sim->alive[i]) continue;
            d[0] += sim->p[i].x - x0[3 * i];
            d[1] += sim->p[i].y - x0[3 * i + 1];
            d[2] += sim->p[i].z - x0[3 * i + 2];
        }
        for (int k = 0; k < 3; k++) {
            double m = d[k] / (double)ball;
            sum[k] += m;
            sum2[k] += m * m;
        }
    }
    free(x0);
    drift r;
    double n = (double)trials;
    for (int k = 0; k < 3; k++) {
        r.mean[k] = sum[k] / n;
        r.se[k] = sqrt(fmax(sum2[k] / n - r.mean[k] * r.mean[k], 0.0) / n);
    }
    return r;
}

static void spot_move_drift_is_minus_step_over_w(void **state)
{
    (void)state;
    gf_config c = gf_test_silo_config(16, 3000, 5);
    gf_sim *sim = gf_test_generated_sim(&c);
    // spot() alone, through the random walk: E[v] = (0, 0, dz), so the ball's
    // particles drift by (0, 0, -dz / w) on average; horizontally each move
    // is +-dx / w with probability 1/4 each, so SE = dx / (w sqrt(2 n)).
    sim->no_relax = true;
    const size_t n = 4000;
    drift d = measure_drift(sim, n, 6.0);
    double expect[3] = {0, 0, -c.spot_step_z / c.spot_w};
    for (int k = 0; k < 3; k++) {
        print_message("spot drift[%d] = %.5e +- %.1e (expected %.5e)\n", k, d.mean[k], d.se[k], expect[k]);
        if (k < 2) {
            double se = c.spot_step_xy / (c.spot_w * sqrt(2.0 * (double)n));
            assert_true(fabs(d.mean[k]) <= 4 * se);
            gf_assert_near(d.se[k], se, 0.1 * se); // the walk's variance is the BCC one
        } else {
            gf_assert_near(d.mean[2], expect[2], 1e-12 * c.spot_step_z); // every move rises dz
        }
    }
    gf_sim_destroy(sim);
}

// ---- mass balance -------------------------------------------------------------

typedef struct mb_ctx {
    gf_packing pk;
    double t0;
    double ball_sum;
    size_t ball_n;
} mb_ctx;

// Mean number of particle centres in the balls of the spots that are in the
// bulk (4 d above the base to 8 d below the top) at each snapshot: the p of a
// spot as it crosses a bulk plane, walls and all.
static gf_status sample_ball(void *ctx, const gf_sim *sim, uint64_t index, double time)
{
    (void)index;
    mb_ctx *m = ctx;
    if (time < m->t0) return GF_OK;
    assert_int_equal(gf_sim_particles(sim, &m->pk), GF_OK);
    const gf_config *c = gf_sim_config(sim);
    double rs = c->spot_radius, top = 0;
    for (size_t i = 0; i < m->pk.n; i++) top = fmax(top, m->pk.z[i]);
    for (size_t k = 0; k < sim->ns; k++) {
        double p[3] = {sim->sx[k], sim->sy[k], sim->sz[k]};
        if (p[2] < 4.0 || p[2] > top - 8.0) continue;
        size_t cnt = 0;
        for (size_t i = 0; i < m->pk.n; i++) {
            double dx = m->pk.x[i] - p[0], dy = m->pk.y[i] - p[1], dz = m->pk.z[i] - p[2];
            cnt += dx * dx + dy * dy + dz * dz < rs * rs;
        }
        m->ball_sum += (double)cnt;
        m->ball_n++;
    }
    return GF_OK;
}

// ctest: nosan-case outflow_matches_mass_balance
static void outflow_matches_mass_balance(void **state)
{
    (void)state;
    gf_config c = gf_test_silo_config(16, 4000, 7);
    c.output_snapshot_interval = 1.0;
    gf_sim *sim = gf_test_generated_sim(&c);
    // Spots reach the top (z ~ 27) after ~10 tau; measure from 11 to 21 tau.
    mb_ctx m = {.t0 = 11.0};
    gf_sim_hooks hooks = {.ctx = &m, .snapshot = sample_ball};
    assert_int_equal(gf_sim_run(sim, m.t0, &hooks), GF_OK);
    gf_sim_stats a = gf_sim_get_stats(sim);
    const double T = 10.0;
    assert_int_equal(gf_sim_run(sim, m.t0 + T, &hooks), GF_OK);
    gf_sim_stats b = gf_sim_get_stats(sim);
    double exited = (double)(b.particles_exited - a.particles_exited);
    double p = m.ball_sum / (double)m.ball_n, rate = exited / T;
    // A spot carries V_s = p V_p / w. relax() hands part of each step's
    // displacement back (the fixed shell below the ball resists the push), so
    // the volume actually carried is kappa V_s, with kappa the ratio of net
    // (spot + relax) to spot-only vertical displacement over the window.
    double kappa = 1.0 + (b.relax_dz - a.relax_dz) / (b.spot_dz - a.spot_dz);
    double ideal = c.spot_insertion_rate * p / c.spot_w, expect = kappa * ideal;
    // Exits are a sum of ~lambda T spot contributions of p/w particles each
    // plus the discreteness of the count: Var(N) ~ N + lambda T (p/w)^2.
    double sd = sqrt(exited + c.spot_insertion_rate * T * (p / c.spot_w) * (p / c.spot_w)) / T;
    print_message("mass balance: outflow %.2f per tau; lambda p / w = %.2f (p = %.2f); relax keeps kappa = "
                  "%.3f of it: %.2f +- %.2f\n",
                  rate, ideal, p, kappa, expect, sd);
    assert_true(fabs(rate - expect) <= 4 * sd);
    // The thesis: relaxation moves particles by less than 25% of the block motion.
    assert_true(kappa > 0.75 && kappa <= 1.0);
    gf_packing_free(&m.pk);
    gf_sim_destroy(sim);
}

// ---- determinism and resume ---------------------------------------------------

static gf_config tiny(uint64_t seed)
{
    gf_config c = gf_test_silo_config(12, 1200, seed);
    c.run_duration = 3.0;
    c.output_snapshot_interval = 0.5;
    c.run_reorder_interval = 20000; // several full re-sorts within the run, and across each resume
    return c;
}

static void run_into(const gf_config *c, const char *dir, int resume, volatile sig_atomic_t *stop,
                     gf_status expect)
{
    gf_run_opts o = {.dir = dir, .resume = resume, .force = 1, .stop = stop};
    assert_int_equal(gf_run_dir(c, &o, NULL), expect);
}


static bool same_run_file(const char *d1, const char *d2, const char *name)
{
    char a[1024], b[1024];
    snprintf(a, sizeof a, "%s/%s", d1, name);
    snprintf(b, sizeof b, "%s/%s", d2, name);
    return gf_test_same_file(a, b);
}

static void same_seed_same_bytes(void **state)
{
    (void)state;
    char a[512], b[512], d[512];
    snprintf(a, sizeof a, "%s/det_a", gf_test_tmpdir());
    snprintf(b, sizeof b, "%s/det_b", gf_test_tmpdir());
    snprintf(d, sizeof d, "%s/det_d", gf_test_tmpdir());
    gf_config c = tiny(11);
    run_into(&c, a, 0, NULL, GF_OK);
    run_into(&c, b, 0, NULL, GF_OK);
    for (int k = 0; k <= 6; k++) {
        char name[64];
        snprintf(name, sizeof name, "snapshots/snap_%06d.dump", k);
        assert_true(same_run_file(a, b, name));
    }
    assert_true(same_run_file(a, b, "exits.csv"));
    gf_config other = tiny(12);
    run_into(&other, d, 0, NULL, GF_OK);
    assert_false(same_run_file(a, d, "snapshots/snap_000006.dump"));
}

static void resume_extends_exactly(void **state)
{
    (void)state;
    char full[512], part[512];
    snprintf(full, sizeof full, "%s/res_full", gf_test_tmpdir());
    snprintf(part, sizeof part, "%s/res_part", gf_test_tmpdir());
    gf_config c = tiny(21);
    run_into(&c, full, 0, NULL, GF_OK);
    gf_config half = c;
    half.run_duration = 1.3; // ends between snapshots, with an event pending
    run_into(&half, part, 0, NULL, GF_OK);
    run_into(&c, part, 1, NULL, GF_OK);
    assert_true(same_run_file(full, part, "snapshots/snap_000006.dump"));
    assert_true(same_run_file(full, part, "snapshots/snap_000003.dump"));
    assert_true(same_run_file(full, part, "exits.csv"));
}

typedef struct stop_ctx {
    volatile sig_atomic_t *flag;
    int calls, at;
} stop_ctx;

static void stop_after(void *ctx, const gf_run_progress *p)
{
    stop_ctx *s = ctx;
    if (p->phase == GF_RUN_PHASE_RUNNING && ++s->calls == s->at) *s->flag = 1;
}

static void interrupt_and_resume_exactly(void **state)
{
    (void)state;
    char full[512], part[512];
    snprintf(full, sizeof full, "%s/int_full", gf_test_tmpdir());
    snprintf(part, sizeof part, "%s/int_part", gf_test_tmpdir());
    gf_config c = tiny(31);
    c.run_checkpoint_interval = 0.7;
    run_into(&c, full, 0, NULL, GF_OK);
    volatile sig_atomic_t flag = 0;
    stop_ctx sc = {.flag = &flag, .at = 1};
    // Stop after 32768 events, as SIGINT would, then resume.
    gf_run_opts o = {.dir = part, .force = 1, .stop = &flag, .progress = stop_after, .ctx = &sc};
    assert_int_equal(gf_run_dir(&c, &o, NULL), GF_ERR_INTERRUPTED);
    assert_int_equal(sc.calls, 1);
    run_into(&c, part, 1, NULL, GF_OK);
    assert_true(same_run_file(full, part, "snapshots/snap_000006.dump"));
    assert_true(same_run_file(full, part, "exits.csv"));
}

typedef struct phase_log {
    gf_run_phase seen[8];
    int n, running;
} phase_log;

static void log_phase(void *ctx, const gf_run_progress *p)
{
    phase_log *l = ctx;
    if (p->phase == GF_RUN_PHASE_RUNNING) {
        l->running++; // many of these; logged once
        if (l->running > 1) return;
    }
    if (l->n < 8) l->seen[l->n++] = p->phase;
}

// The phases a run reports, in order: packing, running (many times), done;
// each has a name.
static void progress_phases_in_order(void **state)
{
    (void)state;
    char dir[512];
    snprintf(dir, sizeof dir, "%s/phases", gf_test_tmpdir());
    gf_config c = tiny(43); // 3 tau: more than one progress interval (32768 events)
    phase_log l = {.n = 0};
    gf_run_opts o = {.dir = dir, .force = 1, .progress = log_phase, .ctx = &l};
    assert_int_equal(gf_run_dir(&c, &o, NULL), GF_OK);
    assert_int_equal(l.n, 3);
    assert_int_equal(l.seen[0], GF_RUN_PHASE_PACKING);
    assert_int_equal(l.seen[1], GF_RUN_PHASE_RUNNING);
    assert_int_equal(l.seen[2], GF_RUN_PHASE_DONE);
    assert_string_equal(gf_run_phase_name(GF_RUN_PHASE_PACKING), "packing");
    assert_string_equal(gf_run_phase_name(GF_RUN_PHASE_STALLED), "stalled");
    assert_string_equal(gf_run_phase_name((gf_run_phase)-1), "?");
}

static void fresh_run_refuses_to_overwrite(void **state)
{
    (void)state;
    char dir[512];
    snprintf(dir, sizeof dir, "%s/owr", gf_test_tmpdir());
    gf_config c = tiny(41);
    c.run_duration = 0.2;
    run_into(&c, dir, 0, NULL, GF_OK);
    gf_run_opts o = {.dir = dir};
    assert_int_equal(gf_run_dir(&c, &o, NULL), GF_ERR_EXISTS); // the kind the CLI's hint keys on
    assert_non_null(strstr(gf_last_error(), "holds a run"));
    assert_string_equal(gf_status_str(GF_ERR_EXISTS), "output exists");
}

static void corrupt_checkpoint_is_rejected(void **state)
{
    (void)state;
    char dir[512], path[600];
    snprintf(dir, sizeof dir, "%s/corrupt", gf_test_tmpdir());
    snprintf(path, sizeof path, "%s/checkpoint.bin", dir);
    gf_config c = tiny(51);
    c.run_duration = 0.3;
    run_into(&c, dir, 0, NULL, GF_OK);
    size_t n;
    char *data = gf_test_read_file(path, &n);
    assert_non_null(data);
    gf_sim *sim = NULL;
    // One flipped byte in the payload: checksum mismatch.
    data[n / 2] ^= 0x40;
    FILE *f = fopen(path, "wb");
    fwrite(data, 1, n, f);
    fclose(f);
    assert_int_equal(gf_sim_load(&c, path, &sim), GF_ERR_FORMAT);
    assert_non_null(strstr(gf_last_error(), "checksum"));
    // Truncated.
    data[n / 2] ^= 0x40;
    f = fopen(path, "wb");
    fwrite(data, 1, n - 100, f);
    fclose(f);
    assert_int_equal(gf_sim_load(&c, path, &sim), GF_ERR_FORMAT);
    assert_non_null(strstr(gf_last_error(), "truncated"));
    // Not a checkpoint at all.
    f = fopen(path, "wb");
    fputs("hello", f);
    fclose(f);
    assert_int_equal(gf_sim_load(&c, path, &sim), GF_ERR_FORMAT);
    // Physics changed on resume.
    f = fopen(path, "wb");
    fwrite(data, 1, n, f);
    fclose(f);
    gf_config changed = c;
    changed.spot_w = 400;
    assert_int_equal(gf_sim_load(&changed, path, &sim), GF_ERR_PARAM);
    assert_null(sim);
    free(data);
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(drain_keeps_invariants),
    cmocka_unit_test(spatial_step_keeps_invariants),
    cmocka_unit_test(spot_move_drift_is_minus_step_over_w),
    cmocka_unit_test(outflow_matches_mass_balance),
    cmocka_unit_test(same_seed_same_bytes),
    cmocka_unit_test(resume_extends_exactly),
    cmocka_unit_test(interrupt_and_resume_exactly),
    cmocka_unit_test(progress_phases_in_order),
    cmocka_unit_test(fresh_run_refuses_to_overwrite),
    cmocka_unit_test(corrupt_checkpoint_is_rejected),
};

GF_TEST_MAIN("engine", tests)
