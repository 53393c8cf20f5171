// SPDX-License-Identifier: MIT
// Recirculation (run.recirculate, src/spot/recirculate.c): every exit is put
// back on the free surface, so particles are conserved (in = out +
// re-inserted); a re-inserted particle overlaps nothing and lies in the
// container (and in its zone); each exit of a particle ends the pass after
// the one before; max_passes retires particles; the parallel engine gives
// the same result on any thread count; a resumed run keeps passes exact.
#include "support.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "granflow/granflow.h"
#include "spot/sim_internal.h"

// A shallow 8 x 6 silo of 300 spheres (~5 d deep) draining through a 5 d
// hole: a particle passes through in a couple of tau, so 5 tau give many
// passes. The free surface is the 2009 paper's (Sec. 3: biased walk and
// influence weighting), without which the top loosens pass after pass.
static gf_config shallow(uint64_t seed)
{
    gf_config c = gf_config_default();
    c.container_width = 8;
    c.container_depth = 6;
    c.packing_particles = 300;
    c.run_seed = seed;
    c.orifice_diameter = 5;
    c.spot_bias_exponent = 3;
    c.spot_weighting = 1;
    c.spot_weighting_zmin = 0;
    c.run_recirculate = 1;
    c.run_duration = 5.0;
    c.output_snapshot_interval = 2.5;
    assert_int_equal(gf_config_validate(&c), GF_OK);
    return c;
}

static int cmp_exit_id_time(const void *a, const void *b)
{
    const gf_exit *x = a, *y = b;
    if (x->id != y->id) return x->id < y->id ? -1 : 1;
    return (x->time > y->time) - (x->time < y->time);
}

// Per particle, its exits in time order end passes 1, 2, 3, ...; each pass
// after the first began when the one before ended, at a radius inside the
// container. Returns the number of exits that ended a pass >= 2.
static size_t check_passes(const gf_exit *e, size_t n, int64_t max_pass)
{
    gf_exit *s = malloc(sizeof *s * (n ? n : 1));
    assert_non_null(s);
    if (n) memcpy(s, e, sizeof *s * n);
    qsort(s, n, sizeof *s, cmp_exit_id_time);
    size_t later = 0;
    for (size_t k = 0; k < n; k++) {
        bool first = k == 0 || s[k - 1].id != s[k].id;
        if (first) {
            assert_int_equal(s[k].pass, 1);
            assert_true(s[k].entry_time == 0.0);
        } else {
            assert_int_equal(s[k].pass, s[k - 1].pass + 1);
            assert_true(s[k].entry_time == s[k - 1].time);
            assert_true(s[k].time > s[k].entry_time);
            later++;
        }
        assert_true(s[k].pass <= max_pass);
        assert_true(s[k].entry_r >= 0.0 && s[k].entry_r <= hypot(4.0, 3.0));
    }
    free(s);
    return later;
}

static void counts_balance_and_passes_step_by_one(void **state)
{
    (void)state;
    gf_config c = shallow(3);
    gf_sim *sim = gf_test_generated_sim(&c);
    assert_int_equal(gf_sim_run(sim, c.run_duration, NULL), GF_OK);
    gf_sim_stats st = gf_sim_get_stats(sim);
    size_t n;
    const gf_exit *e = gf_sim_exits(sim, &n);
    size_t later = check_passes(e, n, INT64_MAX);
    print_message("recirculation: %zu exits, %zu of them ending a second or later pass\n", n, later);
    assert_true(n > 200); // it flowed
    assert_true(later > 10);
    assert_int_equal(st.particles_exited, n);
    assert_int_equal(st.particles_reinserted, n); // every exit went back
    assert_int_equal(st.particles_remaining, st.particles_initial);
    assert_int_equal(st.particles_initial, st.particles_remaining + st.particles_exited - st.particles_reinserted);
    gf_packing pk = {0};
    assert_int_equal(gf_sim_particles(sim, &pk), GF_OK);
    assert_int_equal(pk.n, 300);
    int32_t pass[300];
    assert_int_equal(gf_sim_passes(sim, pass, pk.n), GF_OK);
    // A particle's pass now is one more than the passes it has ended.
    for (size_t k = 0; k < pk.n; k++) {
        int32_t ended = 0;
        for (size_t j = 0; j < n; j++) ended += e[j].id == pk.id[k];
        assert_int_equal(pass[k], ended + 1);
    }
    gf_packing_free(&pk);
    gf_sim_destroy(sim);
}

// The particles put back in the step just made: each inside the container
// (its own test, tol 0) and clear of every other particle (centre distance
// >= r_i + r_j); `extra` checks more of each (its zone). Returns how many.
static size_t check_reinserted_now(const gf_sim *sim, void (*extra)(const gf_sim *sim, const gf_pos *a))
{
    size_t checked = 0;
    for (size_t i = 0; i < sim->n; i++) {
        if (!sim->alive[i] || sim->hist[i].pass < 2 || sim->hist[i].t_entry != sim->t) continue;
        const gf_pos *a = &sim->p[i];
        assert_true(gf_container_contains(&sim->box, a->x, a->y, a->z, a->r, 0.0));
        assert_true(sim->hist[i].r_entry == hypot(a->x, a->y));
        extra(sim, a);
        for (size_t j = 0; j < sim->n; j++) {
            if (j == i || !sim->alive[j]) continue;
            const gf_pos *b = &sim->p[j];
            double dx = a->x - b->x, dy = a->y - b->y, dz = a->z - b->z;
            assert_true(sqrt(dx * dx + dy * dy + dz * dz) >= a->r + b->r);
        }
        checked++;
    }
    return checked;
}

// Steps `sim` until `want` re-insertions have been checked (check_reinserted_now).
static void check_reinsertions(gf_sim *sim, size_t want, void (*extra)(const gf_sim *sim, const gf_pos *a))
{
    size_t checked = 0, done = 0;
    while (checked < want) {
        assert_int_equal(gf_sim_step(sim), GF_OK);
        assert_true(sim->t < 30.0);
        if (sim->st.particles_reinserted == done) continue;
        done = sim->st.particles_reinserted;
        checked += check_reinserted_now(sim, extra);
    }
}

static void in_zone_1_to_2_5(const gf_sim *sim, const gf_pos *a)
{
    (void)sim;
    double rho = hypot(a->x, a->y);
    assert_true(rho >= 1.0 && rho < 2.5);
}

// Step by step: right after each re-insertion, the particle put back is
// clear of every other particle and of the walls, and in its zone.
static void reinserted_particles_do_not_overlap(void **state)
{
    (void)state;
    gf_config c = shallow(4);
    c.run_reinsert = GF_REINSERT_ZONE;
    c.run_reinsert_rmin = 1.0;
    c.run_reinsert_rmax = 2.5;
    gf_sim *sim = gf_test_generated_sim(&c);
    check_reinsertions(sim, 100, in_zone_1_to_2_5);
    assert_int_equal(sim->n_alive, 300);
    gf_sim_destroy(sim);
}

// run.max_passes = 2: second passes end for good. Nothing ends a third pass,
// every first-pass exit went back, every second-pass exit left.
static void max_passes_retires_particles(void **state)
{
    (void)state;
    gf_config c = shallow(5);
    c.run_max_passes = 2;
    gf_sim *sim = gf_test_generated_sim(&c);
    assert_int_equal(gf_sim_run(sim, 6.0, NULL), GF_OK);
    gf_sim_stats st = gf_sim_get_stats(sim);
    size_t n;
    const gf_exit *e = gf_sim_exits(sim, &n);
    size_t second = check_passes(e, n, 2);
    assert_true(second > 10);
    assert_int_equal(st.particles_reinserted, n - second);
    assert_int_equal(st.particles_remaining, 300 - second);
    assert_int_equal(st.particles_initial, st.particles_remaining + st.particles_exited - st.particles_reinserted);
    gf_sim_destroy(sim);
}

// A run stopped half way and resumed gives the same exits (passes, entry
// times and radii) and the same final snapshot, pass column included.
static void resume_keeps_passes_exact(void **state)
{
    (void)state;
    char whole[512], part[512], a[600], b[600];
    snprintf(whole, sizeof whole, "%s/rc_whole", gf_test_tmpdir());
    snprintf(part, sizeof part, "%s/rc_part", gf_test_tmpdir());
    gf_config c = shallow(6), h = shallow(6);
    h.run_duration = 2.9;
    gf_run_opts o = {.dir = whole, .force = 1};
    assert_int_equal(gf_run_dir(&c, &o, NULL), GF_OK);
    o.dir = part;
    assert_int_equal(gf_run_dir(&h, &o, NULL), GF_OK);
    gf_run_opts r = {.dir = part, .resume = 1, .force = 1};
    assert_int_equal(gf_run_dir(&c, &r, NULL), GF_OK);
    assert_true(gf_test_same_snapshot(whole, part, 2));
    snprintf(a, sizeof a, "%s/exits.csv", whole);
    snprintf(b, sizeof b, "%s/exits.csv", part);
    assert_true(gf_test_same_file(a, b));
    snprintf(a, sizeof a, "%s/snapshots/snap_000002.dump", whole);
    size_t len;
    char *text = gf_test_read_file(a, &len);
    assert_non_null(strstr(text, "ITEM: ATOMS id type x y z pass\n"));
    free(text);
}

// Beside the column (radius 1.5) and inside the wall (radius 5), or under
// the column once the surface is below it; on or above the funnel.
static void in_hopper_annulus(const gf_sim *sim, const gf_pos *a)
{
    double rho = hypot(a->x, a->y);
    assert_true(rho <= 5.0 - a->r + 1e-9); // may touch the wall
    if (a->z >= sim->box.z_col) assert_true(rho >= 1.5 + a->r - 1e-9);
    assert_true(a->z >= gf_container_floor_z(&sim->box, a->x, a->y, a->r));
}

// A 60 degree hopper with a central column (the annular core of the 2006
// pebble-bed paper) recirculating: every particle put back is inside, clear
// of the others and in the annulus; the count stays.
static void hopper_with_column_reinserts_inside(void **state)
{
    (void)state;
    gf_config c = shallow(7);
    c.container_shape = GF_SHAPE_CYLINDER;
    c.container_radius = 5;
    c.hopper_angle = 60;
    c.outlet_diameter = 5;
    c.inner_radius = 1.5;
    c.packing_particles = 400;
    assert_int_equal(gf_config_validate(&c), GF_OK);
    gf_sim *sim = gf_test_generated_sim(&c);
    const size_t n0 = sim->n_alive;
    check_reinsertions(sim, 60, in_hopper_annulus);
    assert_int_equal(sim->n_alive, n0);
    gf_sim_stats st = gf_sim_get_stats(sim);
    assert_int_equal(st.particles_exited, st.particles_reinserted);
    gf_sim_destroy(sim);
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(hopper_with_column_reinserts_inside),
    cmocka_unit_test(counts_balance_and_passes_step_by_one),
    cmocka_unit_test(reinserted_particles_do_not_overlap),
    cmocka_unit_test(max_passes_retires_particles),
    cmocka_unit_test(resume_keeps_passes_exact),
};

GF_TEST_MAIN("recirculate", tests)
