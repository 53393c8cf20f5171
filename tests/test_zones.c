// SPDX-License-Identifier: MIT
// The reactor outputs (gf_measure_zones, src/analysis/zones.c) on hand-made
// exits and snapshots whose answers are computed by hand: flow shares, mean
// transit times, exit shares and the mixing matrix per radial zone, residence
// times per pass, v_z(r) and v_r(r), and the streamlines of surface particles.
#include "support.h"

#include <math.h>
#include <string.h>

#include "core/alloc.h"
#include "granflow/granflow.h"

static double cell(const gf_table *t, size_t row, size_t col)
{
    assert_true(row < t->nrow && col < t->ncol);
    return t->v[row * t->ncol + col];
}

// Zones [0, 1), [1, 2), [2, wall). Four exits:
//   id 1 pass 1: entered r = 0.5 at t = 0, left at x = 0.2 at t = 4  (zone 0 -> 0, 4 tau)
//   id 2 pass 1: entered r = 1.5 at t = 0, left at x = 1.5 at t = 6  (zone 1 -> 1, 6 tau)
//   id 1 pass 2: entered r = 2.5 at t = 4, left at x = 0.5 at t = 12 (zone 2 -> 0, 8 tau)
//   id 3 pass 1: entered r = 1.2 at t = 0, left at y = 0.3 at t = 8  (zone 1 -> 0, 8 tau)
static void zone_tables_from_exits(void **state)
{
    (void)state;
    gf_series s = gf_test_series(2, 8, 8);
    for (size_t k = 0; k < 2; k++)
        assert_int_equal(gf_packing_push(&s.frames[k].pk, 9, 1, 3.0, 0.0, 5.0 - k, 0.5), GF_OK);
    const gf_exit e[] = {
        {.id = 1, .time = 4, .x = 0.2, .y = 0, .pass = 1, .entry_time = 0, .entry_r = 0.5},
        {.id = 2, .time = 6, .x = 1.5, .y = 0, .pass = 1, .entry_time = 0, .entry_r = 1.5},
        {.id = 3, .time = 8, .x = 0, .y = 0.3, .pass = 1, .entry_time = 0, .entry_r = 1.2},
        {.id = 1, .time = 12, .x = 0.5, .y = 0, .pass = 2, .entry_time = 4, .entry_r = 2.5},
    };
    s.exits = GF_NEW(gf_exit, 4);
    memcpy(s.exits, e, sizeof e);
    s.nexits = 4;
    s.has_exits = true;
    gf_analysis_opts o = gf_analysis_opts_default();
    assert_int_equal(gf_analysis_opts_set(&o, "zones.radii=1,2"), GF_OK);
    gf_measure_out out = {0};
    assert_int_equal(gf_measure_zones(&s, &o, &out), GF_OK);
    const gf_table *z = gf_test_table(&out, "zones");
    assert_int_equal(z->nrow, 3);
    // zone, r_inner, r_outer, exits, flow_share, mean, sd, exit_share
    assert_true(cell(z, 0, 3) == 1 && cell(z, 1, 3) == 2 && cell(z, 2, 3) == 1);
    gf_assert_near(cell(z, 0, 4), 0.25, 1e-12);
    gf_assert_near(cell(z, 1, 4), 0.5, 1e-12);
    gf_assert_near(cell(z, 0, 5), 4.0, 1e-12);
    gf_assert_near(cell(z, 1, 5), 7.0, 1e-12);
    gf_assert_near(cell(z, 1, 6), sqrt(2.0), 1e-12);
    gf_assert_near(cell(z, 2, 5), 8.0, 1e-12);
    gf_assert_near(cell(z, 0, 7), 0.75, 1e-12);
    gf_assert_near(cell(z, 1, 7), 0.25, 1e-12);
    gf_assert_near(cell(z, 2, 2), hypot(4.0, 4.0), 1e-12); // the last zone reaches the wall
    const gf_table *m = gf_test_table(&out, "zones_matrix");
    assert_int_equal(m->nrow, 9);
    const double count[3][3] = {{1, 0, 0}, {1, 1, 0}, {1, 0, 0}}, frac[3][3] = {{1, 0, 0}, {0.5, 0.5, 0}, {1, 0, 0}};
    for (size_t a = 0; a < 3; a++)
        for (size_t b = 0; b < 3; b++) {
            assert_true(cell(m, 3 * a + b, 2) == count[a][b]);
            gf_assert_near(cell(m, 3 * a + b, 3), frac[a][b], 1e-12);
        }
    const gf_table *p = gf_test_table(&out, "rtd_pass");
    assert_int_equal(p->nrow, 2);
    // pass 1: 4, 6, 8 tau -> mean 6, sd 2, median 6; pass 2: one of 8 tau
    assert_true(cell(p, 0, 1) == 3);
    gf_assert_near(cell(p, 0, 2), 6.0, 1e-12);
    gf_assert_near(cell(p, 0, 3), 2.0, 1e-12);
    gf_assert_near(cell(p, 0, 4), 6.0, 1e-12);
    assert_true(cell(p, 1, 0) == 2 && cell(p, 1, 1) == 1);
    gf_assert_near(cell(p, 1, 2), 8.0, 1e-12);
    // The pdf of each entry zone integrates to 1.
    const gf_table *h = gf_test_table(&out, "rtd_zone_hist");
    double sum[3] = {0}, bw = 8.0 / 40.0;
    for (size_t r = 0; r < h->nrow; r++) sum[(size_t)cell(h, r, 1)] += cell(h, r, 2) * bw;
    for (size_t k = 0; k < 3; k++) gf_assert_near(sum[k], 1.0, 1e-12);
    gf_assert_near(gf_test_value(&out, "transit_mean"), 6.5, 1e-12);
    assert_true(gf_test_value(&out, "passes_max") == 2);
    gf_measure_free(&out);
    gf_series_free(&s);
}

// Particles on circles r = 0.25, 1.25, 2.75 falling at v_z = -(1 + r), plus
// one that drifts outward at v_r = 0.5 and one put back on the surface
// between frames 1 and 2 (a rise of 10 d: no velocity, a new streamline).
static void velocity_and_streamlines_from_frames(void **state)
{
    (void)state;
    gf_series s = gf_test_series(3, 8, 8);
    const double rad[3] = {0.25, 1.25, 2.75};
    for (size_t k = 0; k < 3; k++) {
        gf_packing *pk = &s.frames[k].pk;
        for (int i = 0; i < 3; i++) {
            double r = rad[i], z = 20.0 - (1.0 + r) * (double)k;
            assert_int_equal(gf_packing_push(pk, 1 + i, 1, r * cos(i), r * sin(i), z, 0.5), GF_OK);
        }
        assert_int_equal(gf_packing_push(pk, 4, 1, 3.0 + 0.5 * (double)k, 0.0, 10.0, 0.5), GF_OK);
        double z5 = k < 2 ? 2.0 - 0.5 * (double)k : 12.0;
        assert_int_equal(gf_packing_push(pk, 5, 1, 0.6, 0.0, z5, 0.5), GF_OK);
    }
    gf_analysis_opts o = gf_analysis_opts_default();
    assert_int_equal(gf_analysis_opts_set(&o, "zones.radii=1,2"), GF_OK);
    assert_int_equal(gf_analysis_opts_set(&o, "window.t0=0"), GF_OK);
    gf_measure_out out = {0};
    assert_int_equal(gf_measure_zones(&s, &o, &out), GF_OK);
    const gf_table *v = gf_test_table(&out, "vz_r");
    // bins of 0.5: r = 0.25 -> bin 0, 0.6 -> 1, 1.25 -> 2, 2.75 -> 5, 3.25 and 3.75 -> 6, 7
    size_t seen = 0;
    for (size_t r = 0; r < v->nrow; r++) {
        double rm = cell(v, r, 0), vz = cell(v, r, 1), vr = cell(v, r, 2), n = cell(v, r, 3);
        if (fabs(rm - 0.25) < 1e-9 || fabs(rm - 1.25) < 1e-9 || fabs(rm - 2.75) < 1e-9) {
            gf_assert_near(vz, -(1.0 + rm), 1e-9);
            gf_assert_near(vr, 0.0, 1e-9);
            assert_true(n == 2); // two frame pairs
            seen++;
        } else if (fabs(rm - 0.75) < 1e-9) { // particle 5 falling at 0.5, first pair only (then it jumps)
            gf_assert_near(vz, -0.5, 1e-9);
            assert_true(n == 1);
            seen++;
        } else {
            gf_assert_near(vz, 0.0, 1e-9); // particle 4 drifting outward
            gf_assert_near(vr, 0.5, 1e-9);
        }
    }
    assert_int_equal(seen, 4);
    // Streamlines: the top zones.dz (2 d) of frame 0 are particles 1-3 (z = 20);
    // particle 5 starts one when it is put back at r = 0.6 (zone 0).
    const gf_table *t = gf_test_table(&out, "streamlines");
    double zone0_count = 0.0;
    for (size_t r = 0; r < t->nrow; r++) {
        size_t k = (size_t)cell(t, r, 0);
        double rm = cell(t, r, 2);
        if (k == 0) zone0_count += cell(t, r, 3);
        if (k == 1) gf_assert_near(rm, 1.25, 1e-9);
        if (k == 2) gf_assert_near(rm, 2.75, 1e-9);
        assert_true(k < 3);
    }
    assert_true(zone0_count == 4.0); // particle 1 in three frames, particle 5 in the last
    gf_measure_free(&out);
    gf_series_free(&s);
}

static void zone_radii_must_increase(void **state)
{
    (void)state;
    gf_analysis_opts o = gf_analysis_opts_default();
    assert_int_equal(gf_analysis_opts_set(&o, "zones.radii=2,1"), GF_ERR_PARAM);
    assert_non_null(strstr(gf_last_error(), "zones.radii"));
    assert_int_equal(gf_analysis_opts_set(&o, "zones.radii=1,2,3"), GF_OK);
    assert_int_equal(o.zone_nradii, 3);
}

// A cylinder of radius 4 (its bounding box 8 x 8): the default four zones of
// equal area end at the wall r = 4, not at the box's corner 4 sqrt(2), so an
// exit at r = 3.9 falls in the last zone and none lies outside the vessel.
// With only two snapshots (none inside the steady window) v(r) is empty and
// the plot script must not ask gnuplot to draw the empty vz_r.csv.
static void cylinder_zones_end_at_the_wall(void **state)
{
    (void)state;
    gf_series s = gf_test_series(2, 8, 8);
    s.cfg.container_shape = GF_SHAPE_CYLINDER;
    s.cfg.container_radius = 4.0;
    for (size_t k = 0; k < 2; k++)
        assert_int_equal(gf_packing_push(&s.frames[k].pk, 9, 1, 3.0, 0.0, 5.0 - k, 0.5), GF_OK);
    const gf_exit e[] = {{.id = 1, .time = 4, .x = 3.9, .y = 0, .pass = 1, .entry_time = 0, .entry_r = 3.9}};
    s.exits = GF_NEW(gf_exit, 1);
    memcpy(s.exits, e, sizeof e);
    s.nexits = 1;
    s.has_exits = true;
    gf_analysis_opts o = gf_analysis_opts_default();
    gf_measure_out out = {0};
    assert_int_equal(gf_measure_zones(&s, &o, &out), GF_OK);
    const gf_table *z = gf_test_table(&out, "zones");
    assert_int_equal(z->nrow, 4);
    for (size_t k = 0; k < 4; k++) gf_assert_near(cell(z, k, 2), 4.0 * sqrt((double)(k + 1) / 4.0), 1e-12);
    assert_true(cell(z, 3, 3) == 1); // r = 3.9 is in the outermost zone [2 sqrt 3, 4)
    assert_int_equal(gf_test_table(&out, "vz_r")->nrow, 0);
    assert_non_null(out.gnuplot);
    assert_null(strstr(out.gnuplot, "'vz_r.csv'"));
    gf_measure_free(&out);
    gf_series_free(&s);
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(zone_tables_from_exits),
    cmocka_unit_test(velocity_and_streamlines_from_frames),
    cmocka_unit_test(zone_radii_must_increase),
    cmocka_unit_test(cylinder_zones_end_at_the_wall),
};

GF_TEST_MAIN("zones", tests)
