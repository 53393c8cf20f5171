// SPDX-License-Identifier: MIT
// A rank's window of packing.file (src/spot/window.c, issue 23 item 3): rank
// r of R of the domain engine reads the file keeping its region's particles
// and a margin, at the indices one process gives them, and holds nothing
// else: its records equal the single process's, its region's neighbour
// lists are whole, and the other particles' records were never written; its
// re-sort of its window is one process's. No MPI: rank and ranks are
// numbers here.
#include "support.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "granflow/packing.h"
#include "spot/sim_internal.h"

// A tall silo of 6,000 spheres (156 d: 6 domains along z), cut along z by the domain engine's slabs,
// packed once and written where packing.file points.
static gf_config window_config(void)
{
    gf_config c = gf_config_default();
    assert_int_equal(gf_config_set_key(&c, "container.width", "8"), GF_OK);
    assert_int_equal(gf_config_set_key(&c, "container.depth", "4"), GF_OK);
    assert_int_equal(gf_config_set_key(&c, "container.orifice_diameter", "5"), GF_OK);
    assert_int_equal(gf_config_set_key(&c, "packing.particles", "6000"), GF_OK);
    assert_int_equal(gf_config_set_key(&c, "run.mode", "fixed"), GF_OK);
    assert_int_equal(gf_config_set_key(&c, "run.order", "domains"), GF_OK);
    assert_int_equal(gf_config_set_key(&c, "parallel.sectors", "4"), GF_OK);
    gf_packing pk = {0};
    assert_int_equal(gf_packing_for_config(&c, NULL, &pk, NULL), GF_OK);
    char path[512];
    snprintf(path, sizeof path, "%s/tall.dump", gf_test_tmpdir());
    assert_int_equal(gf_packing_write(&pk, path, GF_FORMAT_LAMMPS, &c), GF_OK);
    gf_packing_free(&pk);
    assert_int_equal(gf_config_set_key(&c, "packing.file", path), GF_OK);
    return c;
}

// Rank me's window against the whole sim: same count and radii, every
// particle of the window as one process has it, the rows of its region
// whole, nothing written outside it.
static size_t window_matches(const gf_sim *all, const gf_sim *w, int R, int me)
{
    assert_int_equal(w->n, all->n);
    assert_true(w->part);
    assert_true(w->win_lo <= w->win_hi && w->win_hi <= all->n);
    assert_true(w->rmax == all->rmax && w->contact2 == all->contact2 && w->nl_shift == all->nl_shift);
    assert_true(w->grid.nz == all->grid.nz && w->grid_ztop == all->grid_ztop);
    int rlo, rhi;
    assert_int_equal(gf_dom_window_layers(w, R, me, 0, &rlo, &rhi), GF_OK);
    const size_t row = sizeof(uint32_t) << all->nl_shift, layer = (size_t)all->grid.nx * (size_t)all->grid.ny;
    for (size_t i = 0; i < all->n; i++) {
        if (i < w->win_lo || i >= w->win_hi) {
            assert_true(w->id[i] == 0 && w->alive[i] == 0); // never written
            continue;
        }
        assert_memory_equal(&w->p[i], &all->p[i], sizeof all->p[i]);
        assert_memory_equal(&w->p0[i], &all->p0[i], sizeof all->p0[i]);
        assert_true(w->id[i] == all->id[i] && w->layer[i] == all->layer[i] && w->alive[i] == all->alive[i]);
        assert_memory_equal(&w->hist[i], &all->hist[i], sizeof all->hist[i]);
        assert_int_equal(w->grid.cell_of[i], all->grid.cell_of[i]);
        assert_int_equal(w->grid.slot_of[i], all->grid.slot_of[i]);
        int L = (int)(all->grid.cell_of[i] / layer);
        if (L >= rlo && L < rhi) assert_memory_equal((const char *)w->nl + i * row, (const char *)all->nl + i * row, row);
    }
    assert_int_equal(gf_sim_held_particles(w), w->win_hi - w->win_lo);
    return w->win_hi - w->win_lo;
}

static void a_rank_holds_its_window_at_the_single_process_indices(void **state)
{
    (void)state;
    gf_config c = window_config();
    gf_sim *all = NULL;
    assert_int_equal(gf_sim_create_from_config(&c, NULL, &all), GF_OK);
    assert_int_equal(gf_sim_held_particles(all), all->n);
    const int R = 4;
    size_t covered = 0, most = 0;
    size_t next = 0; // windows overlap and together cover every index
    for (int me = 0; me < R; me++) {
        gf_sim *w = NULL;
        assert_int_equal(gf_sim_create_part(&c, R, me, &w), GF_OK);
        size_t held = window_matches(all, w, R, me);
        assert_true(w->win_lo <= next);
        next = w->win_hi;
        covered += held;
        if (held > most) most = held;
        gf_sim_destroy(w);
    }
    assert_int_equal(next, all->n);
    assert_true(covered >= all->n);
    // Each rank holds well under the whole (4 slabs with halos and margins).
    assert_true(most < all->n / 2);
    gf_sim_destroy(all);
}

// One rank: its window is the whole packing, as one process makes it.
static void one_rank_holds_everything(void **state)
{
    (void)state;
    gf_config c = window_config();
    gf_sim *all = NULL, *w = NULL;
    assert_int_equal(gf_sim_create_from_config(&c, NULL, &all), GF_OK);
    assert_int_equal(gf_sim_create_part(&c, 1, 0, &w), GF_OK);
    assert_int_equal(window_matches(all, w, 1, 0), all->n);
    gf_sim_destroy(w);
    gf_sim_destroy(all);
}

// A window's re-sort (gf_window_resort, what each MPI rank does at a
// re-sort) is one process's: after particles left, a window of every cell
// gives the indices, grid, references and rows of gf_nlist_build's re-sort.
static void a_window_resorts_as_one_process(void **state)
{
    (void)state;
    gf_config c = window_config();
    assert_int_equal(gf_config_set_key(&c, "run.reorder_interval", "1000000000"), GF_OK);
    assert_int_equal(gf_config_set_key(&c, "container.orifice_diameter", "6"), GF_OK);
    gf_sim *all = NULL, *w = NULL;
    assert_int_equal(gf_sim_create_from_config(&c, NULL, &all), GF_OK);
    assert_int_equal(gf_sim_create_part(&c, 1, 0, &w), GF_OK);
    assert_int_equal(gf_sim_run(all, 3.0, NULL), GF_OK);
    assert_int_equal(gf_sim_run(w, 3.0, NULL), GF_OK);
    assert_true(all->n_alive < all->n); // particles left: the re-sort drops them
    double rmin = INFINITY, rmax = 0.0;
    for (size_t i = 0; i < w->n; i++)
        if (w->alive[i]) {
            rmin = fmin(rmin, w->p[i].r);
            rmax = fmax(rmax, w->p[i].r);
        }
    assert_int_equal(gf_nlist_build(all, true), GF_OK);
    assert_int_equal(gf_window_resort(w, 0, w->grid.ncell, 0, w->n_alive, rmin, rmax), GF_OK);
    assert_int_equal(w->n, all->n);
    assert_true(w->win_lo == 0 && w->win_hi == all->n);
    assert_true(w->hmax == all->hmax && w->contact2 == all->contact2);
    const size_t row = sizeof(uint32_t) << all->nl_shift;
    for (size_t i = 0; i < all->n; i++) {
        assert_memory_equal(&w->p[i], &all->p[i], sizeof all->p[i]);
        assert_memory_equal(&w->p0[i], &all->p0[i], sizeof all->p0[i]);
        assert_true(w->id[i] == all->id[i] && w->layer[i] == all->layer[i] && w->alive[i] == 1 && all->alive[i] == 1);
        assert_memory_equal(&w->hist[i], &all->hist[i], sizeof all->hist[i]);
        assert_int_equal(w->grid.cell_of[i], all->grid.cell_of[i]);
        assert_int_equal(w->grid.slot_of[i], all->grid.slot_of[i]);
        assert_memory_equal((const char *)w->nl + i * row, (const char *)all->nl + i * row, row);
    }
    assert_memory_equal(w->grid.count, all->grid.count, all->grid.ncell * sizeof *all->grid.count);
    gf_sim_destroy(w);
    gf_sim_destroy(all);
}

// Without packing.file there is nothing to read a window of: refused (the
// caller then makes the whole packing, as one process does).
static void a_window_needs_a_packing_file(void **state)
{
    (void)state;
    gf_config c = gf_config_default();
    gf_sim *w = NULL;
    assert_int_equal(gf_sim_create_part(&c, 4, 0, &w), GF_ERR_PARAM);
    assert_null(w);
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(a_rank_holds_its_window_at_the_single_process_indices),
    cmocka_unit_test(one_rank_holds_everything),
    cmocka_unit_test(a_window_resorts_as_one_process),
    cmocka_unit_test(a_window_needs_a_packing_file),
};

GF_TEST_MAIN("window", tests)
