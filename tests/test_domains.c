// SPDX-License-Identifier: MIT
// The domain engine (run.order = domains, src/spot/domains.c): its result
// depends on the seed and the parallel keys, never on the number of threads
// (bit for bit, resume included); sectors of one index really run side by
// side; the decomposition follows parallel.domain_size, parallel.sectors and
// parallel.cut and refuses domains too small to keep sectors independent.
// ctest: nosan-case thread_count_does_not_change_the_result
// ctest: nosan-case resume_under_another_thread_count
#include "support.h"
#include "run_outcome.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "granflow/granflow.h"
#include "spot/sim_internal.h"

// A 12 x 6 silo of 4000 spheres (~50 d tall). Spots climb twice as fast as
// the papers' (step_z = 0.2) so that within 6 tau they fill the column; with
// 4 sectors per axis (sectors ~6 d) the column holds several sectors of one
// index, so phases run two or more side by side.
static gf_config tall_silo(int64_t threads)
{
    gf_config c = gf_test_silo_config(12, 4000, 5);
    c.container_depth = 6;
    c.spot_step_z = 0.2;
    c.spot_insertion_rate = 150;
    c.run_mode = GF_MODE_FIXED;
    c.run_order = GF_ORDER_DOMAINS;
    c.parallel_sectors = 4;
    c.parallel_window = 0.1;
    c.run_threads = threads;
    c.run_duration = 6.0;
    c.output_snapshot_interval = 3.0;
    assert_int_equal(gf_config_validate(&c), GF_OK);
    return c;
}

static gf_test_outcome run_config(gf_config c) { return gf_test_run_outcome(c); }

// 1, 2 and 3 threads (3 on a 2-core machine: oversubscribed) give the same
// particles, exits and counters to the last bit; the run did flow, and many
// phases had two or more sectors with spots, run side by side.
static void thread_count_does_not_change_the_result(void **state)
{
    (void)state;
    gf_test_outcome o1 = run_config(tall_silo(1)), o2 = run_config(tall_silo(2)), o3 = run_config(tall_silo(3));
    print_message("domains: %d x %d x %d sectors, %d indices, %zu domains; %zu exited, %llu moves, %llu shared phases\n",
                  o1.prof.blocks_along[0], o1.prof.blocks_along[1], o1.prof.blocks_along[2], o1.prof.colours,
                  o1.prof.domains, o1.nex, (unsigned long long)o1.st.spot_moves,
                  (unsigned long long)o2.shared_phases);
    assert_true(o1.nex > 50);
    assert_true(o2.shared_phases > 50);
    assert_true(o1.prof.blocks_along[2] > 4); // more sectors up the column than indices
    gf_test_same_outcome(&o1, &o2);
    gf_test_same_outcome(&o1, &o3);
    gf_test_outcome_free(&o1);
    gf_test_outcome_free(&o2);
    gf_test_outcome_free(&o3);
}

// Exits carry the time of the move that let them out, within the run, in
// time order; every spot move made falls inside the cycles run.
static void exits_are_timed_and_ordered(void **state)
{
    (void)state;
    gf_test_outcome o = run_config(tall_silo(2));
    assert_true(o.nex > 50);
    for (size_t k = 0; k < o.nex; k++) {
        assert_true(o.ex[k].time > 0.0 && o.ex[k].time <= 6.0 + 1e-12);
        if (k > 0) assert_true(o.ex[k].time >= o.ex[k - 1].time);
    }
    // Not all on the cycle boundaries (each exit has its move's own time).
    size_t off = 0;
    for (size_t k = 0; k < o.nex; k++) {
        double c = o.ex[k].time / 0.1;
        off += fabs(c - (double)llround(c)) > 1e-6;
    }
    assert_true(off > o.nex / 2);
    gf_test_outcome_free(&o);
}

// Recirculation: exits are put back after the cycle in id order, so 1 and 2
// threads still agree to the last bit, and every exit went back.
static void recirculation_does_not_depend_on_threads(void **state)
{
    (void)state;
    gf_config c1 = tall_silo(1), c2 = tall_silo(2);
    c1.run_recirculate = c2.run_recirculate = 1;
    gf_test_outcome o1 = run_config(c1), o2 = run_config(c2);
    assert_true(o1.nex > 50);
    assert_int_equal(o1.pk.n, 4000);
    assert_int_equal(o1.st.particles_reinserted, o1.nex);
    gf_test_same_outcome(&o1, &o2);
    gf_test_outcome_free(&o1);
    gf_test_outcome_free(&o2);
}

// The decomposition depends on the keys: another window or sector count
// gives another (valid) result; a domain smaller than two reaches per sector
// is refused with a message naming the key and the smallest size.
static void keys_set_the_decomposition(void **state)
{
    (void)state;
    gf_config a = tall_silo(2), b = tall_silo(2);
    b.parallel_sectors = 2;
    a.run_duration = b.run_duration = 3.0;
    gf_test_outcome oa = run_config(a), ob = run_config(b);
    assert_int_equal(oa.prof.colours, 4 * 4); // cut in y? no: 6 d deep holds one sector; x and z cut
    assert_true(ob.prof.colours <= 4);
    assert_true(oa.nex > 0 && ob.nex > 0);
    gf_test_outcome_free(&oa);
    gf_test_outcome_free(&ob);

    gf_config c = tall_silo(1);
    c.parallel_domain_size = 4.0;
    gf_sim *sim = gf_test_generated_sim(&c);
    gf_status st = gf_sim_run(sim, 0.5, NULL);
    assert_int_equal(st, GF_ERR_PARAM);
    assert_non_null(strstr(gf_last_error(), "parallel.domain_size = 4"));
    assert_non_null(strstr(gf_last_error(), "smallest domain"));
    gf_sim_destroy(sim);
}

// parallel.cut = z: horizontal slabs only, none across x or y, whatever
// their length; S sector indices; still the same result on 1 and 2 threads,
// and another result than the cut across x and z (the decomposition is part
// of the keys). A cut set that names an unknown axis is refused by name.
static void a_z_cut_makes_slabs(void **state)
{
    (void)state;
    gf_config a = tall_silo(1), b = tall_silo(2), x = tall_silo(2);
    assert_int_equal(gf_config_set_key(&a, "parallel.cut", "z"), GF_OK);
    assert_int_equal(gf_config_set_key(&b, "parallel.cut", "z"), GF_OK);
    assert_int_equal(a.parallel_cut, 1 << 2);
    a.run_duration = b.run_duration = x.run_duration = 4.0;
    gf_test_outcome oa = run_config(a), ob = run_config(b), ox = run_config(x);
    assert_int_equal(oa.prof.blocks_along[0], 1);
    assert_int_equal(oa.prof.blocks_along[1], 1);
    assert_true(oa.prof.blocks_along[2] > 4);
    assert_int_equal(oa.prof.colours, 4);
    assert_int_equal(ox.prof.colours, 16);
    assert_true(oa.nex > 20);
    gf_test_same_outcome(&oa, &ob);
    assert_true(oa.nex != ox.nex || memcmp(oa.pk.z, ox.pk.z, sizeof(double) * oa.pk.n) != 0);
    gf_test_outcome_free(&oa);
    gf_test_outcome_free(&ob);
    gf_test_outcome_free(&ox);

    gf_config c = tall_silo(1);
    assert_int_equal(gf_config_set_key(&c, "parallel.cut", "all"), GF_OK);
    assert_int_equal(c.parallel_cut, 7);
    assert_int_equal(gf_config_set_key(&c, "parallel.cut", "z,w"), GF_ERR_PARAM);
    assert_non_null(strstr(gf_last_error(), "parallel.cut"));
    assert_non_null(strstr(gf_last_error(), "'w'"));
}

// A run stopped at 4.1 tau with 1 thread and resumed with 2 writes the same
// snapshots (byte for byte) as one run straight through with 3.
static void resume_under_another_thread_count(void **state)
{
    (void)state;
    gf_test_resume_matches("dom", tall_silo(3), tall_silo(1), tall_silo(2), 4.1);
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(thread_count_does_not_change_the_result),
    cmocka_unit_test(exits_are_timed_and_ordered),
    cmocka_unit_test(recirculation_does_not_depend_on_threads),
    cmocka_unit_test(keys_set_the_decomposition),
    cmocka_unit_test(resume_under_another_thread_count),
    cmocka_unit_test(a_z_cut_makes_slabs),
};

GF_TEST_MAIN("domains", tests)
