// SPDX-License-Identifier: MIT
// The spatial fixed step (run.order = spatial, src/spot/parallel.c): its
// result does not depend on the number of threads, it resumes exactly under
// another thread count, and blocks of one colour really do run side by side.
#include "support.h"
#include "run_outcome.h"

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

static gf_test_outcome run_config(gf_config c, gf_par_profile *prof)
{
    gf_test_outcome o = gf_test_run_outcome(c);
    if (prof) *prof = o.prof;
    return o;
}

static gf_test_outcome run_threads(int64_t threads) { return run_config(tall_silo(threads), NULL); }

// 1, 2 and 4 threads (4 on a 2-core machine: oversubscribed) give the same
// particles, exits and counters to the last bit; the run did flow, and some
// colours had two slabs with spots, so two threads did work side by side.
static void thread_count_does_not_change_the_result(void **state)
{
    (void)state;
    gf_test_outcome o1 = run_threads(1), o2 = run_threads(2), o4 = run_threads(4);
    print_message("spatial step: %zu exited, %llu moves, %llu phases with two or more blocks\n", o1.nex,
                  (unsigned long long)o1.st.spot_moves, (unsigned long long)o2.shared_phases);
    assert_true(o1.nex > 50);
    assert_true(o2.shared_phases > 10);
    gf_test_same_outcome(&o1, &o2);
    gf_test_same_outcome(&o1, &o4);
    gf_test_outcome_free(&o1);
    gf_test_outcome_free(&o2);
    gf_test_outcome_free(&o4);
}

// Recirculation in the parallel step: exits are put back after the step in
// id order, so 1 and 2 threads still agree to the last bit (passes, entry
// times and radii included), and every exit went back.
static void recirculation_does_not_depend_on_threads(void **state)
{
    (void)state;
    gf_config c1 = tall_silo(1), c2 = tall_silo(2);
    c1.run_recirculate = c2.run_recirculate = 1;
    gf_test_outcome o1 = run_config(c1, NULL), o2 = run_config(c2, NULL);
    assert_true(o1.nex > 50);
    assert_int_equal(o1.pk.n, 4000);
    assert_int_equal(o1.st.particles_reinserted, o1.nex);
    gf_test_same_outcome(&o1, &o2);
    gf_test_outcome_free(&o1);
    gf_test_outcome_free(&o2);
}

// The wide silo is cut along x too (blocks of one colour side by side in
// x and z): 1, 2 and 3 threads still give the same result to the last bit.
static void blocks_in_x_and_z_do_not_change_the_result(void **state)
{
    (void)state;
    gf_par_profile f;
    gf_test_outcome o1 = run_config(wide_silo(1), &f), o2 = run_config(wide_silo(2), NULL), o3 = run_config(wide_silo(3), NULL);
    print_message("wide silo: %d x %d x %d blocks, %d colours; %zu exited, %llu phases with two or more blocks\n",
                  f.blocks_along[0], f.blocks_along[1], f.blocks_along[2], f.colours, o1.nex,
                  (unsigned long long)o2.shared_phases);
    assert_true(f.blocks_along[0] > 4); // more blocks along x than colours: two of a colour side by side
    assert_true(f.blocks_along[2] > 4);
    assert_int_equal(f.colours, 16);
    assert_true(o1.nex > 50);
    assert_true(o2.shared_phases > 10);
    gf_test_same_outcome(&o1, &o2);
    gf_test_same_outcome(&o1, &o3);
    gf_test_outcome_free(&o1);
    gf_test_outcome_free(&o2);
    gf_test_outcome_free(&o3);
}

// A run stopped at 4.1 tau with 1 thread and resumed with 2 writes the same
// final snapshot (byte for byte) as one run straight through with 4.
static void resume_under_another_thread_count(void **state)
{
    (void)state;
    gf_test_resume_matches("par", tall_silo(4), tall_silo(1), tall_silo(2), 4.1);
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(thread_count_does_not_change_the_result),
    cmocka_unit_test(resume_under_another_thread_count),
    cmocka_unit_test(recirculation_does_not_depend_on_threads),
    cmocka_unit_test(blocks_in_x_and_z_do_not_change_the_result),
};

GF_TEST_MAIN("parallel", tests)
