// SPDX-License-Identifier: MIT
// The MPI exchange's received messages are checked before they are applied
// (issue 26: ranks out of step sent indices that were written through
// unchecked and corrupted the heap). The checks need no MPI: every build runs
// them here, on messages made by hand against a small simulation.
#include "support.h"

#include <string.h>

#include "core/error.h"
#include "granflow/granflow.h"
#include "spot/mpi_records.h"

enum { NBLOCK = 4, BLOCK = 16 };

typedef struct msg {
    unsigned char b[4096];
    size_t len;
    gf_mpi_head h;
} msg;

// A message of one record of kind k (rec bytes from r; the rest zero).
static void msg_one(msg *m, const gf_sim *sim, int k, const void *r, size_t rbytes)
{
    size_t limit[GF_TOUCH_KINDS], rec[GF_TOUCH_KINDS];
    gf_mpi_records_kinds(sim, NBLOCK, BLOCK, limit, rec);
    memset(m, 0, sizeof *m);
    m->h.v[1 + k] = 1;
    m->len = sizeof m->h + rec[k];
    assert_true(m->len <= sizeof m->b && rbytes <= rec[k]);
    m->h.v[0] = (uint32_t)m->len;
    memcpy(m->b, &m->h, sizeof m->h);
    memcpy(m->b + sizeof m->h, r, rbytes);
}

static gf_status check(const gf_sim *sim, const msg *m)
{
    return gf_mpi_records_check(sim, m->b, m->len, NBLOCK, BLOCK, 1);
}

static gf_sim *small_sim(void)
{
    gf_config c = gf_test_silo_config(10, 300, 3);
    c.run_mode = GF_MODE_FIXED;
    c.run_order = GF_ORDER_SPATIAL;
    return gf_test_generated_sim(&c);
}

// Records whose indices are in range pass, and applying them writes them.
static void records_in_range_are_applied(void **state)
{
    (void)state;
    gf_sim *sim = small_sim();
    const uint32_t n = (uint32_t)sim->n;
    msg m;
    gf_mpi_pos pos = {n - 1, 0, 1.5, -0.5, 7.0};
    msg_one(&m, sim, GF_TOUCH_MOVED, &pos, sizeof pos);
    assert_int_equal(check(sim, &m), GF_OK);
    uint8_t dead[1] = {0};
    unsigned char blocks[NBLOCK * BLOCK];
    uint64_t parts = 0, cells = 0;
    gf_mpi_records_apply(sim, m.b, dead, blocks, NBLOCK, BLOCK, false, &parts, &cells);
    assert_true(sim->p[n - 1].x == 1.5 && sim->p[n - 1].z == 7.0);
    assert_int_equal(parts, 1);
    gf_mpi_cell cell = {(uint32_t)sim->grid.ncell - 1, 2};
    unsigned char cr[sizeof cell + 2 * sizeof(uint32_t)];
    uint32_t who[2] = {0, n - 1};
    memcpy(cr, &cell, sizeof cell);
    memcpy(cr + sizeof cell, who, sizeof who);
    msg_one(&m, sim, GF_TOUCH_CELL, cr, sizeof cr);
    assert_int_equal(check(sim, &m), GF_OK);
    gf_sim_destroy(sim);
}

// Every index a record carries, out of range: refused with a message naming
// the rank, the kind and the value, before anything is written.
static void records_out_of_range_are_refused(void **state)
{
    (void)state;
    gf_sim *sim = small_sim();
    const uint32_t n = (uint32_t)sim->n, nc = (uint32_t)sim->grid.ncell;
    msg m;
    gf_mpi_pos pos = {n, 0, 1, 2, 3};
    msg_one(&m, sim, GF_TOUCH_MOVED, &pos, sizeof pos);
    assert_int_equal(check(sim, &m), GF_ERR_STATE);
    assert_non_null(strstr(gf_last_error(), "rank 1 sent moved-particle record 0 with index"));
    assert_non_null(strstr(gf_last_error(), "out of step"));

    gf_mpi_part part = {.i = 0, .cell = nc, .slot = 0, .alive = 1};
    msg_one(&m, sim, GF_TOUCH_PARTICLE, &part, sizeof part);
    assert_int_equal(check(sim, &m), GF_ERR_STATE);
    assert_non_null(strstr(gf_last_error(), "particle record 0 with cell"));
    part = (gf_mpi_part){.i = 0, .cell = 0, .slot = 1000, .alive = 1};
    msg_one(&m, sim, GF_TOUCH_PARTICLE, &part, sizeof part);
    assert_int_equal(check(sim, &m), GF_ERR_STATE);
    part = (gf_mpi_part){.i = 0, .cell = UINT32_MAX, .slot = 1000, .alive = 0}; // out of the grid: slot unused
    msg_one(&m, sim, GF_TOUCH_PARTICLE, &part, sizeof part);
    assert_int_equal(check(sim, &m), GF_OK);

    gf_mpi_cell cell = {nc, 0};
    msg_one(&m, sim, GF_TOUCH_CELL, &cell, sizeof cell);
    assert_int_equal(check(sim, &m), GF_ERR_STATE);
    cell = (gf_mpi_cell){0, 1000};
    msg_one(&m, sim, GF_TOUCH_CELL, &cell, sizeof cell);
    assert_int_equal(check(sim, &m), GF_ERR_STATE);
    assert_non_null(strstr(gf_last_error(), "with count 1000"));
    unsigned char cr[sizeof cell + sizeof(uint32_t)];
    cell = (gf_mpi_cell){0, 1};
    uint32_t who = n + 5;
    memcpy(cr, &cell, sizeof cell);
    memcpy(cr + sizeof cell, &who, sizeof who);
    msg_one(&m, sim, GF_TOUCH_CELL, cr, sizeof cr);
    assert_int_equal(check(sim, &m), GF_ERR_STATE);

    gf_mpi_spot spot = {.k = (uint32_t)sim->ns};
    msg_one(&m, sim, GF_TOUCH_SPOT, &spot, sizeof spot);
    assert_int_equal(check(sim, &m), GF_ERR_STATE);
    assert_non_null(strstr(gf_last_error(), "spot record 0 with spot"));

    uint32_t block = NBLOCK;
    msg_one(&m, sim, GF_TOUCH_BLOCK, &block, sizeof block);
    assert_int_equal(check(sim, &m), GF_ERR_STATE);

    assert_true(sim->use_nlist && sim->nl);
    { // a list row: its length, then neighbours
        uint32_t row[3] = {0, 1, n};
        msg_one(&m, sim, GF_TOUCH_ROW, row, sizeof row);
        assert_int_equal(check(sim, &m), GF_ERR_STATE);
        assert_non_null(strstr(gf_last_error(), "neighbour-list record 0 with neighbour"));
        row[1] = UINT32_MAX;
        msg_one(&m, sim, GF_TOUCH_ROW, row, sizeof row);
        assert_int_equal(check(sim, &m), GF_ERR_STATE);
    }
    gf_sim_destroy(sim);
}

// A message whose length does not match its head or its counts: refused.
static void messages_of_the_wrong_length_are_refused(void **state)
{
    (void)state;
    gf_sim *sim = small_sim();
    msg m;
    gf_mpi_pos pos = {0, 0, 1, 2, 3};
    msg_one(&m, sim, GF_TOUCH_MOVED, &pos, sizeof pos);
    assert_int_equal(gf_mpi_records_check(sim, m.b, m.len - 1, NBLOCK, BLOCK, 2), GF_ERR_STATE);
    assert_non_null(strstr(gf_last_error(), "rank 2 sent a message of"));
    assert_int_equal(gf_mpi_records_check(sim, m.b, 3, NBLOCK, BLOCK, 2), GF_ERR_STATE);
    m.h.v[1 + GF_TOUCH_MOVED] = UINT32_MAX; // counts far beyond the bytes
    memcpy(m.b, &m.h, sizeof m.h);
    assert_int_equal(check(sim, &m), GF_ERR_STATE);
    gf_sim_destroy(sim);
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(records_in_range_are_applied),
    cmocka_unit_test(records_out_of_range_are_refused),
    cmocka_unit_test(messages_of_the_wrong_length_are_refused),
};

GF_TEST_MAIN("mpi_records", tests)
