// SPDX-License-Identifier: MIT
// The slabs of the domain engine across MPI ranks (src/spot/slabs.c, issue
// 23): which layers each rank owns, its region (slab and halo), who exchanges
// with whom, and which moves take a particle into or out of a region. No MPI:
// the geometry is the same in every build.
#include "support.h"

#include "spot/slabs.h"

// 5 domains of 16 layers (the last 14: 78 layers) on 4 ranks, halo 7.
static void slabs_cut_whole_domains_and_add_a_halo(void **state)
{
    (void)state;
    gf_slabs s;
    assert_int_equal(gf_slabs_make(&s, 2, 78, 10, 3, 5, 16, 4, 7), GF_OK);
    // r 5 / 4 rounded down: domains [0,1), [1,2), [2,3), [3,5)
    const int lo[4] = {0, 16, 32, 48}, hi[4] = {16, 32, 48, 78};
    const int rlo[4] = {0, 9, 25, 41}, rhi[4] = {23, 39, 55, 78};
    for (int r = 0; r < 4; r++) {
        assert_int_equal(s.lo[r], lo[r]);
        assert_int_equal(s.hi[r], hi[r]);
        assert_int_equal(s.rlo[r], rlo[r]);
        assert_int_equal(s.rhi[r], rhi[r]);
    }
    for (int L = 0; L < 78; L++) {
        int r = gf_slabs_owner(&s, L);
        assert_true(L >= lo[r] && L < hi[r]);
        assert_true(gf_slabs_holds(&s, r, L)); // a rank's region holds its slab
    }
    // Neighbour slabs exchange; slabs two apart do not (their regions are apart).
    assert_true(gf_slabs_partners(&s, 0, 1) && gf_slabs_partners(&s, 1, 0));
    assert_true(gf_slabs_partners(&s, 2, 3));
    assert_false(gf_slabs_partners(&s, 0, 2));
    assert_false(gf_slabs_partners(&s, 1, 3));
    assert_false(gf_slabs_partners(&s, 1, 1));
    gf_slabs_free(&s);
}

// A cell's layer is its index along the axis; a move crosses a region's edge
// exactly when the regions holding the two layers differ.
static void moves_across_a_region_edge_are_seen(void **state)
{
    (void)state;
    gf_slabs s;
    const int nx = 10, ny = 3;
    assert_int_equal(gf_slabs_make(&s, 2, 78, nx, ny, 5, 16, 4, 7), GF_OK);
    for (int a = 0; a < 78; a++)
        for (int b = 0; b < 78; b++) {
            bool same = true;
            for (int r = 0; r < 4; r++) same = same && gf_slabs_holds(&s, r, a) == gf_slabs_holds(&s, r, b);
            uint32_t ca = (uint32_t)(a * nx * ny + 7), cb = (uint32_t)(b * nx * ny + 2 * nx + 1);
            assert_int_equal(gf_slabs_layer(&s, ca), a);
            assert_int_equal(gf_slabs_crosses(&s, ca, cb) != 0, !same);
        }
    gf_slabs_free(&s);
    // Along x and y the layer is the cell's column index.
    assert_int_equal(gf_slabs_make(&s, 0, nx, nx, ny, 2, 5, 2, 1), GF_OK);
    assert_int_equal(gf_slabs_layer(&s, (uint32_t)(4 * nx * ny + 2 * nx + 7)), 7);
    gf_slabs_free(&s);
    assert_int_equal(gf_slabs_make(&s, 1, ny, nx, ny, 1, 3, 2, 1), GF_OK);
    assert_int_equal(gf_slabs_layer(&s, (uint32_t)(4 * nx * ny + 2 * nx + 7)), 2);
    gf_slabs_free(&s);
}

// Fewer domains than ranks: the last ranks own nothing, hold nothing and
// exchange with no one (they still run every collective).
static void ranks_beyond_the_domains_own_nothing(void **state)
{
    (void)state;
    gf_slabs s;
    assert_int_equal(gf_slabs_make(&s, 0, 34, 34, 1, 3, 16, 4, 7), GF_OK);
    assert_int_equal(s.hi[0], 16);
    assert_int_equal(s.hi[1], 32);
    assert_int_equal(s.lo[2], 32);
    assert_int_equal(s.hi[2], 34);
    assert_int_equal(s.lo[3], s.hi[3]);
    assert_int_equal(s.rlo[3], s.rhi[3]);
    for (int r = 0; r < 3; r++) assert_false(gf_slabs_partners(&s, r, 3));
    for (int L = 0; L < 34; L++) assert_true(gf_slabs_owner(&s, L) < 3);
    gf_slabs_free(&s);
    assert_int_equal(gf_slabs_make(&s, 3, 34, 34, 1, 3, 16, 4, 7), GF_ERR_PARAM); // no such axis
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(slabs_cut_whole_domains_and_add_a_halo),
    cmocka_unit_test(moves_across_a_region_edge_are_seen),
    cmocka_unit_test(ranks_beyond_the_domains_own_nothing),
};

GF_TEST_MAIN("slabs", tests)
