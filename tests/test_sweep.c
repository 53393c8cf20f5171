// SPDX-License-Identifier: MIT
// The sweep engine (run.order = sweep, src/spot/sweep.c): its result depends
// on the seed and the keys, never on run.threads (bit for bit, resume
// included); it drains, conserves particles, times and orders its exits; its
// profile covers every block; it refuses relax methods it does not have.
// ctest: nosan-case thread_count_does_not_change_the_result
// ctest: nosan-case resume_under_another_thread_count
#include "support.h"
#include "run_outcome.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "granflow/granflow.h"
#include "spot/sim_internal.h"

// A 12 x 6 silo of 4000 spheres (~50 d tall), spots climbing twice as fast
// as the papers' so that within 6 tau they fill the column and particles
// leave; windows of 1/mu (every spot moves about once a window).
static gf_config tall_silo(int64_t threads)
{
    gf_config c = gf_test_silo_config(12, 4000, 5);
    c.container_depth = 6;
    c.spot_step_z = 0.2;
    c.spot_insertion_rate = 150;
    c.run_mode = GF_MODE_FIXED;
    c.run_order = GF_ORDER_SWEEP;
    c.parallel_window = 1.0 / 28.0;
    c.parallel_sweeps = 2;
    c.run_threads = threads;
    c.run_duration = 6.0;
    c.output_snapshot_interval = 3.0;
    assert_int_equal(gf_config_validate(&c), GF_OK);
    return c;
}

// 1, 2 and 3 threads (3 on a 2-core machine: oversubscribed) give the same
// particles, exits and counters to the last bit, and the run did flow.
static void thread_count_does_not_change_the_result(void **state)
{
    (void)state;
    gf_test_outcome o1 = gf_test_run_outcome(tall_silo(1)), o2 = gf_test_run_outcome(tall_silo(2)),
                    o3 = gf_test_run_outcome(tall_silo(3));
    print_message("sweep: %zu exited, %llu moves, %llu sweeps\n", o1.nex, (unsigned long long)o1.st.spot_moves,
                  (unsigned long long)o1.st.relax_calls);
    assert_true(o1.nex > 50);
    gf_test_same_outcome(&o1, &o2);
    gf_test_same_outcome(&o1, &o3);
    gf_test_outcome_free(&o1);
    gf_test_outcome_free(&o2);
    gf_test_outcome_free(&o3);
}

// Every particle is inside or has left, spots move and are removed, each
// window relaxes parallel.sweeps times, and exits carry the time of the
// last move that reached them: within the run, in (time, id) order, and
// mostly off the window boundaries.
static void drains_and_times_its_exits(void **state)
{
    (void)state;
    gf_config c = tall_silo(2);
    c.run_duration = 4.0;
    gf_test_outcome o = gf_test_run_outcome(c);
    assert_true(o.nex > 20);
    assert_int_equal(o.pk.n + o.nex, 4000);
    assert_true(o.st.spot_moves > 1000);
    // Every window after the first spot's first move relaxes twice.
    assert_true(o.st.relax_calls % 2 == 0 && o.st.relax_calls >= 2 * (uint64_t)(3.0 * 28.0));
    assert_true(o.st.spot_dz < 0.0); // the spots moved the packing down
    size_t off = 0;
    for (size_t k = 0; k < o.nex; k++) {
        assert_true(o.ex[k].time > 0.0 && o.ex[k].time <= 4.0 + 1e-12);
        if (k > 0) {
            assert_true(o.ex[k].time >= o.ex[k - 1].time);
            if (o.ex[k].time == o.ex[k - 1].time) assert_true(o.ex[k].id > o.ex[k - 1].id);
        }
        double w = o.ex[k].time * 28.0;
        off += fabs(w - (double)llround(w)) > 1e-6;
    }
    assert_true(off > o.nex / 2);
    gf_test_outcome_free(&o);
}

// More sweeps leave fewer overlaps: the packing after a run with 4 sweeps
// a window overlaps less than with 1 (the sweeps are relax()'s rule).
static double overlap_sum(const gf_packing *pk)
{
    double s = 0.0;
    for (size_t i = 0; i < pk->n; i++)
        for (size_t j = i + 1; j < pk->n; j++) {
            double dx = pk->x[i] - pk->x[j], dy = pk->y[i] - pk->y[j], dz = pk->z[i] - pk->z[j];
            double r = sqrt(dx * dx + dy * dy + dz * dz), d = pk->r[i] + pk->r[j] - r;
            if (d > 0) s += d * d;
        }
    return s;
}

static void sweeps_relax(void **state)
{
    (void)state;
    gf_config a = tall_silo(1), b = tall_silo(1), n = tall_silo(1);
    a.run_duration = b.run_duration = n.run_duration = 2.0;
    a.parallel_sweeps = 1;
    b.parallel_sweeps = 4;
    n.parallel_sweeps = 0;
    gf_test_outcome oa = gf_test_run_outcome(a), ob = gf_test_run_outcome(b), on = gf_test_run_outcome(n);
    double sa = overlap_sum(&oa.pk), sb = overlap_sum(&ob.pk), sn = overlap_sum(&on.pk);
    print_message("sum of overlaps^2: %g (0 sweeps), %g (1 sweep), %g (4 sweeps)\n", sn, sa, sb);
    assert_true(sb < sa);
    assert_true(sa < sn);
    assert_int_equal(on.st.relax_calls, 0);
    gf_test_outcome_free(&oa);
    gf_test_outcome_free(&ob);
    gf_test_outcome_free(&on);
}

// Profiling covers the walk, the gather, the sweeps and the bookkeeping;
// the projected makespans fall with more workers but never below the
// serial part or the longest chunks.
static void profile_projects_the_speedup(void **state)
{
    (void)state;
    gf_config c = tall_silo(1);
    gf_sim *sim = gf_test_generated_sim(&c);
    assert_int_equal(gf_sim_run(sim, 2.0, NULL), GF_OK);
    gf_sim_set_par_profiling(sim, 1);
    assert_int_equal(gf_sim_run(sim, 3.0, NULL), GF_OK);
    gf_par_profile f = gf_sim_par_profile(sim);
    print_message("work %.3g s, serial %.3g s, span %.3g s, speedup on 2/16/64: %.2f %.2f %.2f\n", f.work_seconds,
                  f.serial_seconds, f.span_seconds, f.work_seconds / f.makespan_seconds[0],
                  f.work_seconds / f.makespan_seconds[2], f.work_seconds / f.makespan_seconds[3]);
    assert_true(f.profiled_tau > 0.99 && f.profiled_tau < 1.01);
    assert_true(f.colour_phases >= (uint64_t)(28 * 4)); // walk, gather, bookkeeping, 2 x (sweep, apply, bookkeeping) a window
    assert_true(f.work_seconds > 0.0 && f.serial_seconds > 0.0 && f.serial_seconds < f.work_seconds);
    for (int i = 0; i < GF_PAR_NPROJ; i++) {
        assert_true(f.makespan_seconds[i] <= f.work_seconds * (1 + 1e-12));
        assert_true(f.makespan_seconds[i] >= f.span_seconds * (1 - 1e-12));
        if (i > 0) assert_true(f.makespan_seconds[i] <= f.makespan_seconds[i - 1] * (1 + 1e-12));
    }
    gf_sim_destroy(sim);
}

// relax.method = counter (or random, global) is refused, naming both keys.
static void refuses_other_relax_methods(void **state)
{
    (void)state;
    gf_config c = tall_silo(1);
    c.relax_method = GF_RELAX_COUNTER;
    assert_int_equal(gf_config_validate(&c), GF_ERR_PARAM);
    assert_non_null(strstr(gf_last_error(), "run.order = sweep"));
    assert_non_null(strstr(gf_last_error(), "relax.method"));
    c.relax_method = GF_RELAX_NONE;
    assert_int_equal(gf_config_validate(&c), GF_OK);
}

// A run stopped at 4.1 tau with 1 thread and resumed with 2 writes the same
// snapshots (byte for byte) as one run straight through with 3.
static void resume_under_another_thread_count(void **state)
{
    (void)state;
    gf_test_resume_matches("sweep", tall_silo(3), tall_silo(1), tall_silo(2), 4.1);
}

// After windows whose cell moves, exits and list refreshes ran side by side
// (groups of chunks, removals then insertions, pairs listed per crosser):
// every live particle sits in the grid cell of its position, in the slot the
// grid says; every row lists exactly the live j within the listing distance
// of the references (sim_internal.h's rule), sorted; no particle is past its
// skin.
static void keeps_its_cells_and_lists(void **state)
{
    (void)state;
    gf_config c = tall_silo(2);
    gf_sim *sim = gf_test_generated_sim(&c);
    assert_int_equal(gf_sim_run(sim, 3.0, NULL), GF_OK);
    const gf_grid *g = &sim->grid;
    size_t alive = 0, in_cells = 0;
    for (size_t cell = 0; cell < g->ncell; cell++) in_cells += g->count[cell];
    for (uint32_t i = 0; i < sim->n; i++) {
        if (!sim->alive[i]) continue;
        alive++;
        const gf_pos *p = &sim->p[i];
        uint32_t cell = g->cell_of[i];
        assert_int_equal(cell, gf_grid_cell(g, p->x, p->y, p->z));
        assert_int_equal(g->slot[(size_t)cell * GF_CELL_CAP + g->slot_of[i]], i);
        const gf_ref *a = &sim->p0[i];
        double dx = p->x - a->x, dy = p->y - a->y, dz = p->z - a->z;
        assert_true(sqrt(dx * dx + dy * dy + dz * dz) <= a->h);
        const uint32_t *row = sim->nl + ((size_t)i << sim->nl_shift);
        uint32_t e = 1;
        for (uint32_t j = 0; j < sim->n; j++) {
            if (j == i || !sim->alive[j]) continue;
            const gf_ref *b = &sim->p0[j];
            double ex = (double)a->x - b->x, ey = (double)a->y - b->y, ez = (double)a->z - b->z;
            double cut = (p->r + sim->p[j].r) + ((double)a->h + b->h);
            if (!(ex * ex + ey * ey + ez * ez < cut * cut)) continue;
            assert_true(e <= row[0]);
            assert_int_equal(row[e++], j); // (sorted, nothing missing, nothing extra before it)
        }
        assert_int_equal(e - 1, row[0]);
    }
    assert_int_equal(in_cells, alive);
    assert_true(alive < 4000); // particles left through the orifice
    gf_sim_destroy(sim);
}

// A run's outcome with every window visiting every cell chunk (dense) or
// only those its moves reach: gf_sim_run by hand, the dense switch set first.
static gf_test_outcome sweep_outcome(gf_config c, int dense, size_t *most_chunks)
{
    gf_sim *sim = gf_test_generated_sim(&c);
    gf_sweep_set_dense(sim, dense);
    assert_int_equal(gf_sim_run(sim, c.run_duration, NULL), GF_OK);
    gf_test_outcome o = gf_test_outcome_of(sim);
    *most_chunks = gf_sweep_touched_chunks(sim);
    gf_sim_destroy(sim);
    return o;
}

// Windows of ~1/(64 mu) in a silo 3 times wider: each window's blocks visit
// only the cell chunks within reach of its moves, a small part of the grid,
// and the run is the one whose windows visit every chunk, to the last bit
// (a chunk left out that held a particle within r_e of a move would change
// its displacement, its activity or a neighbour's relaxation).
static void windows_visit_only_what_their_moves_reach(void **state)
{
    (void)state;
    gf_config c = tall_silo(2);
    c.container_width = 36;
    c.packing_particles = 6000;
    c.parallel_window = 1.0 / (64 * 28.0);
    c.run_duration = 2.0;
    assert_int_equal(gf_config_validate(&c), GF_OK);
    size_t touched_sparse = 0, touched_dense = 0;
    gf_test_outcome a = sweep_outcome(c, 0, &touched_sparse), b = sweep_outcome(c, 1, &touched_dense);
    print_message("sweep: last window %zu of %zu chunks; %zu exited\n", touched_sparse, touched_dense, a.nex);
    assert_true(touched_sparse > 0);
    assert_true(touched_sparse * 2 < touched_dense); // (a window of ~2 moves reaches a fraction of the grid)
    assert_true(a.st.spot_moves > 1000);
    gf_test_same_outcome(&a, &b);
    gf_test_outcome_free(&a);
    gf_test_outcome_free(&b);
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(thread_count_does_not_change_the_result),
    cmocka_unit_test(drains_and_times_its_exits),
    cmocka_unit_test(sweeps_relax),
    cmocka_unit_test(profile_projects_the_speedup),
    cmocka_unit_test(refuses_other_relax_methods),
    cmocka_unit_test(resume_under_another_thread_count),
    cmocka_unit_test(keeps_its_cells_and_lists),
    cmocka_unit_test(windows_visit_only_what_their_moves_reach),
};

GF_TEST_MAIN("sweep", tests)
