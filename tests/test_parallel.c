// SPDX-License-Identifier: MIT
// The spatial fixed step (run.order = spatial, src/spot/parallel.c): its
// result does not depend on the number of threads, it resumes exactly under
// another thread count, and blocks of one colour really do run side by side.
#include "support.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "granflow/granflow.h"
#include "spot/sim_internal.h"

// A 12 x 6 silo of 4000 spheres (~50 d tall). Spots climb twice as fast as
// the papers' (step_z = 0.2) so that within 6 tau they fill seven 6 d slabs
// and every colour has two slabs with spots; fewer are born (lambda = 150)
// to keep the run short.
static gf_config tall_silo(int64_t threads)
{
    gf_config c = gf_test_silo_config(12, 4000, 5);
    c.container_depth = 6;
    c.spot_step_z = 0.2;
    c.spot_insertion_rate = 150;
    c.run_mode = GF_MODE_FIXED;
    c.run_order = GF_ORDER_SPATIAL;
    c.run_threads = threads;
    c.run_duration = 6.0;
    c.output_snapshot_interval = 3.0;
    assert_int_equal(gf_config_validate(&c), GF_OK);
    return c;
}

typedef struct outcome {
    gf_packing pk;
    gf_exit *ex;
    size_t nex;
    gf_sim_stats st;
    uint64_t shared_phases;
} outcome;

// A silo 36 d wide and 4 d deep (~30 d tall): wide enough to be cut into
// blocks along x as well as z; a slit orifice 30 d wide sends spots up over
// most of the width, so blocks of one colour 24 d apart in x both have spots.
static gf_config wide_silo(int64_t threads)
{
    gf_config c = tall_silo(threads);
    c.container_width = 36;
    c.container_depth = 4;
    c.orifice_shape = GF_ORIFICE_SLIT;
    c.orifice_diameter = 30;
    c.packing_particles = 5000;
    c.run_duration = 4.0;
    assert_int_equal(gf_config_validate(&c), GF_OK);
    return c;
}

static outcome run_config(gf_config c, gf_par_profile *prof)
{
    gf_sim *sim = gf_test_generated_sim(&c);
    assert_int_equal(gf_sim_run(sim, c.run_duration, NULL), GF_OK);
    outcome o = {.st = gf_sim_get_stats(sim), .shared_phases = gf_par_shared_phases(sim)};
    assert_int_equal(gf_sim_particles(sim, &o.pk), GF_OK);
    const gf_exit *e = gf_sim_exits(sim, &o.nex);
    o.ex = malloc(sizeof *o.ex * (o.nex ? o.nex : 1));
    assert_non_null(o.ex);
    if (o.nex) memcpy(o.ex, e, sizeof *o.ex * o.nex);
    if (prof) *prof = gf_sim_par_profile(sim);
    gf_sim_destroy(sim);
    return o;
}

static outcome run_threads(int64_t threads) { return run_config(tall_silo(threads), NULL); }

static void same_outcome(const outcome *a, const outcome *b)
{
    assert_int_equal(a->pk.n, b->pk.n);
    assert_memory_equal(a->pk.id, b->pk.id, sizeof(int64_t) * a->pk.n);
    assert_memory_equal(a->pk.x, b->pk.x, sizeof(double) * a->pk.n);
    assert_memory_equal(a->pk.y, b->pk.y, sizeof(double) * a->pk.n);
    assert_memory_equal(a->pk.z, b->pk.z, sizeof(double) * a->pk.n);
    assert_int_equal(a->nex, b->nex);
    assert_memory_equal(a->ex, b->ex, sizeof(gf_exit) * a->nex);
    assert_int_equal(a->st.spot_moves, b->st.spot_moves);
    assert_int_equal(a->st.relax_calls, b->st.relax_calls);
    assert_int_equal(a->st.spots_deleted, b->st.spots_deleted);
    // The counters' floating-point sums are made block by block, in block order.
    assert_memory_equal(&a->st.spot_dz, &b->st.spot_dz, sizeof(double));
    assert_memory_equal(&a->st.relax_dz, &b->st.relax_dz, sizeof(double));
}

static void free_outcome(outcome *o)
{
    gf_packing_free(&o->pk);
    free(o->ex);
}

// 1, 2 and 4 threads (4 on a 2-core machine: oversubscribed) give the same
// particles, exits and counters to the last bit; the run did flow, and some
// colours had two slabs with spots, so two threads did work side by side.
static void thread_count_does_not_change_the_result(void **state)
{
    (void)state;
    outcome o1 = run_threads(1), o2 = run_threads(2), o4 = run_threads(4);
    print_message("spatial step: %zu exited, %llu moves, %llu phases with two or more blocks\n", o1.nex,
                  (unsigned long long)o1.st.spot_moves, (unsigned long long)o2.shared_phases);
    assert_true(o1.nex > 50);
    assert_true(o2.shared_phases > 10);
    same_outcome(&o1, &o2);
    same_outcome(&o1, &o4);
    free_outcome(&o1);
    free_outcome(&o2);
    free_outcome(&o4);
}

// Recirculation in the parallel step: exits are put back after the step in
// id order, so 1 and 2 threads still agree to the last bit (passes, entry
// times and radii included), and every exit went back.
static void recirculation_does_not_depend_on_threads(void **state)
{
    (void)state;
    gf_config c1 = tall_silo(1), c2 = tall_silo(2);
    c1.run_recirculate = c2.run_recirculate = 1;
    outcome o1 = run_config(c1, NULL), o2 = run_config(c2, NULL);
    assert_true(o1.nex > 50);
    assert_int_equal(o1.pk.n, 4000);
    assert_int_equal(o1.st.particles_reinserted, o1.nex);
    same_outcome(&o1, &o2);
    free_outcome(&o1);
    free_outcome(&o2);
}

// The wide silo is cut along x too (blocks of one colour side by side in
// x and z): 1, 2 and 3 threads still give the same result to the last bit.
static void blocks_in_x_and_z_do_not_change_the_result(void **state)
{
    (void)state;
    gf_par_profile f;
    outcome o1 = run_config(wide_silo(1), &f), o2 = run_config(wide_silo(2), NULL), o3 = run_config(wide_silo(3), NULL);
    print_message("wide silo: %d x %d x %d blocks, %d colours; %zu exited, %llu phases with two or more blocks\n",
                  f.blocks_along[0], f.blocks_along[1], f.blocks_along[2], f.colours, o1.nex,
                  (unsigned long long)o2.shared_phases);
    assert_true(f.blocks_along[0] > 4); // more blocks along x than colours: two of a colour side by side
    assert_true(f.blocks_along[2] > 4);
    assert_int_equal(f.colours, 16);
    assert_true(o1.nex > 50);
    assert_true(o2.shared_phases > 10);
    same_outcome(&o1, &o2);
    same_outcome(&o1, &o3);
    free_outcome(&o1);
    free_outcome(&o2);
    free_outcome(&o3);
}

// A run stopped at 4.1 tau with 1 thread and resumed with 2 writes the same
// final snapshot (byte for byte) as one run straight through with 4.
static void resume_under_another_thread_count(void **state)
{
    (void)state;
    char whole[512], part[512];
    snprintf(whole, sizeof whole, "%s/par_whole", gf_test_tmpdir());
    snprintf(part, sizeof part, "%s/par_part", gf_test_tmpdir());
    gf_config c4 = tall_silo(4), c1 = tall_silo(1), c2 = tall_silo(2);
    gf_run_opts o = {.dir = whole, .force = 1};
    assert_int_equal(gf_run_dir(&c4, &o, NULL), GF_OK);
    c1.run_duration = 4.1;
    o.dir = part;
    assert_int_equal(gf_run_dir(&c1, &o, NULL), GF_OK);
    gf_run_opts r = {.dir = part, .resume = 1, .force = 1};
    assert_int_equal(gf_run_dir(&c2, &r, NULL), GF_OK);
    assert_true(gf_test_same_snapshot(whole, part, 1));
    assert_true(gf_test_same_snapshot(whole, part, 2));
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(thread_count_does_not_change_the_result),
    cmocka_unit_test(resume_under_another_thread_count),
    cmocka_unit_test(recirculation_does_not_depend_on_threads),
    cmocka_unit_test(blocks_in_x_and_z_do_not_change_the_result),
};

GF_TEST_MAIN("parallel", tests)
