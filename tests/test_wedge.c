// SPDX-License-Identifier: MIT
// The wedge hopper (src/geom/wedge.c, docs/geometry.md "The wedge hopper"):
// wall distances and normals, the inside test, the spot truncation, floor,
// mirrors, cross-sections and slice volumes at points worked out by hand;
// the checks of its keys; then packings that keep the generator's promises
// and short runs (event and fixed steps) in which every particle and spot
// stays inside and every exit is through the slit.
#include "support.h"
#include "wall_hits.h"

#include <math.h>
#include <string.h>

#include "geom/container.h"
#include "geom/mesh.h"
#include "granflow/granflow.h"
#include "spot/sim_internal.h"

// width 20, depth 6, walls at 45 degrees, a slit 4 wide at x = 0 and a chute
// 3 long: the inclined walls run 8 in x from the slit's edges (x = +-2) to the
// vertical walls (x = +-10), which they meet at z = 8.
static gf_config wedge(double width, double depth, double angle, double slit, double chute)
{
    gf_config c = gf_config_default();
    c.container_shape = GF_SHAPE_WEDGE;
    c.container_width = width;
    c.container_depth = depth;
    c.hopper_angle = angle;
    c.orifice_diameter = slit;
    c.outlet_length = chute;
    c.spot_insertion_margin = 0.5;
    assert_int_equal(gf_config_validate(&c), GF_OK);
    return c;
}

static void wedge_walls_by_hand(void **state)
{
    (void)state;
    gf_config cfg = wedge(20, 6, 45, 4, 3);
    assert_int_equal(cfg.orifice_shape, GF_ORIFICE_SLIT); // validation makes the outlet a slit
    gf_container c = gf_container_make(&cfg);
    const double s = sqrt(0.5);
    assert_true(c.type == &gf_wedge_shape && !gf_container_rectangular(&c));
    gf_assert_near(c.z_col, 8, 1e-12);
    gf_assert_near(c.z_exit, -3, 0);
    gf_assert_near(c.z_bottom, -3, 0);
    // The right inclined wall z = x - 2: (5, 0, 5) is (5 - 3) / sqrt(2) above it.
    gf_test_assert_hit(gf_test_one_hit(&c, 5, 0, 5, 2), sqrt(2.0), -s, 0, s, true);
    // The left one, mirrored.
    gf_test_assert_hit(gf_test_one_hit(&c, -5, 0, 5, 2), sqrt(2.0), s, 0, s, true);
    // The vertical wall above it (z = 12 > 8), and the flat wall y = 3.
    gf_test_assert_hit(gf_test_one_hit(&c, 9.5, 0, 12, 1), 0.5, -1, 0, 0, true);
    gf_test_assert_hit(gf_test_one_hit(&c, 0, 2.8, 20, 1), 0.2, 0, -1, 0, true);
    // The slit's edge (2, 0): a convex edge, not a side wall.
    double d = hypot(0.2, 0.1);
    gf_test_assert_hit(gf_test_one_hit(&c, 1.8, 0, 0.1, 0.5), d, -0.2 / d, 0, 0.1 / d, false);
    // The chute below it.
    gf_test_assert_hit(gf_test_one_hit(&c, 1.7, 0, -1, 0.5), 0.3, -1, 0, 0, true);
    gf_test_assert_hit(gf_test_one_hit(&c, -1.6, 0, -2, 0.5), 0.4, 1, 0, 0, true);
    // The corner of the inclined and vertical walls: both.
    gf_wall_hit hit[GF_WALL_HITS];
    const double corner[3] = {9.6, 0, 8.2};
    assert_int_equal(gf_container_walls(&c, corner, 1.0, hit), 2);
    // In the bulk: nothing, and the cheap test agrees.
    const double bulk[3] = {0, 0, 20};
    assert_int_equal(gf_container_walls(&c, bulk, 2.0, hit), 0);
    assert_true(gf_container_clear(&c, 0, 0, 20, 2.0));
    assert_false(gf_container_clear(&c, 0, 0, 8.5, 1.0));
    // A push moves a sphere off the inclined wall along its normal.
    double dx = 0, dy = 0, dz = 0;
    gf_container_push(&c, 5, 0, 3 + 0.25 * sqrt(2.0), 0.5, 1.0, &dx, &dy, &dz);
    gf_assert_near(dx, -0.25 * s, 1e-12);
    gf_assert_near(dz, 0.25 * s, 1e-12);
    gf_assert_near(dy, 0, 0);
    // Its mirror image in that wall: c - 2 gap n.
    double m[GF_WALL_HITS][3];
    const double ctr[3] = {5, 0, 5};
    assert_int_equal(c.ops->mirrors(&c, ctr, 2.0, m), 1);
    gf_assert_near(m[0][0], 7, 1e-12);
    gf_assert_near(m[0][2], 3, 1e-12);
}

static void wedge_inside_clamp_floor_by_hand(void **state)
{
    (void)state;
    gf_config cfg = wedge(20, 6, 45, 4, 3);
    gf_container c = gf_container_make(&cfg);
    assert_true(gf_container_contains(&c, 0, 0, 5, 0.5, 0));
    assert_false(gf_container_contains(&c, 5, 0, 2.5, 0.5, 0));  // through the right inclined wall
    assert_false(gf_container_contains(&c, -5, 0, 2.5, 0.5, 0)); // the left one
    assert_true(gf_container_contains(&c, 5, 0, 3 + 0.5 * sqrt(2.0), 0.5, 1e-12));
    assert_false(gf_container_contains(&c, 9.7, 0, 20, 0.5, 0)); // the vertical wall
    assert_false(gf_container_contains(&c, 0, 2.9, 20, 0.5, 0)); // the flat wall
    assert_true(gf_container_contains(&c, 0, 0, -2, 0.5, 0));    // in the chute
    assert_false(gf_container_contains(&c, 1.8, 0, -2, 0.5, 0)); // against the chute's wall
    assert_true(gf_container_contains(&c, 1.9, 0, 0.3, 0.5, 0)); // over the slit, at its edge
    assert_false(gf_container_contains(&c, 3, 0, -0.5, 0, 0));   // under the inclined wall
    // Spot truncation d_w = 1 from every wall, square to it: at z = 4 the
    // right inclined wall is at x = 6, so x <= 2 + 4 - sqrt(2).
    double n[3] = {9, 2.9, 4};
    c.ops->spot_clamp(&c, n, 1.0);
    gf_assert_near(n[0], 6 - sqrt(2.0), 1e-12);
    gf_assert_near(n[1], 2, 1e-12);
    n[0] = -9;
    n[2] = 12; // above the inclined walls: the vertical wall
    c.ops->spot_clamp(&c, n, 1.0);
    gf_assert_near(n[0], -9, 1e-12);
    n[0] = -9.5;
    c.ops->spot_clamp(&c, n, 1.0);
    gf_assert_near(n[0], -9, 1e-12);
    double chute[3] = {0, 5, -1}; // in the chute the flat walls still hold
    c.ops->spot_clamp(&c, chute, 1.0);
    gf_assert_near(chute[1], 2, 1e-12);
    // The floor: over the slit z = r; on the wall z = (r + q sin a) / cos a.
    gf_assert_near(gf_container_floor_z(&c, 0.5, 0, 0.5), 0.5, 0);
    gf_assert_near(gf_container_floor_z(&c, 5, 0, 0.5), 3 + 0.5 * sqrt(2.0), 1e-12);
    gf_assert_near(gf_container_floor_z(&c, -5, 0, 0.5), 3 + 0.5 * sqrt(2.0), 1e-12);
    assert_true(gf_container_inside_xy(&c, 9.5, 2.5, 0.5));
    assert_false(gf_container_inside_xy(&c, 9.6, 0, 0.5));
}

static void wedge_sections_and_volumes(void **state)
{
    (void)state;
    gf_config cfg = wedge(20, 6, 45, 4, 3);
    gf_container c = gf_container_make(&cfg);
    gf_assert_near(c.ops->section_area(&c, -1), 4 * 6, 1e-12);  // the chute
    gf_assert_near(c.ops->section_area(&c, 2), 8 * 6, 1e-12);   // 4 + 2 z wide
    gf_assert_near(c.ops->section_area(&c, 10), 20 * 6, 1e-12); // the column
    // (4 + 2 z) 6 integrated over 0..8: 576; the chute 4 * 6 * 3 = 72; 2 d of column 240.
    gf_assert_near(gf_container_slice_volume(&c, 0, 8), 576, 1e-9);
    gf_assert_near(gf_container_slice_volume(&c, -3, 0), 72, 1e-9);
    gf_assert_near(gf_container_slice_volume(&c, 8, 10), 240, 1e-9);
    assert_false(gf_container_profile_radial(&c));
    gf_assert_near(gf_container_width(&c), 20, 0);
    // An off-centre slit: the walls run 6 and 10, meeting the vertical ones at z = 6 and 10.
    cfg = wedge(20, 6, 45, 4, 0);
    cfg.orifice_x = -2;
    assert_int_equal(gf_config_validate(&cfg), GF_OK);
    c = gf_container_make(&cfg);
    gf_assert_near(c.u.wedge.top[0], 6, 1e-12);
    gf_assert_near(c.u.wedge.top[1], 10, 1e-12);
    gf_assert_near(c.z_col, 10, 1e-12);
    gf_assert_near(c.ops->section_area(&c, 7), (7 - -10) * 6, 1e-12); // from the left wall to x = 7
    // The outline: the inside, and each side's wall from the top down to the slit.
    gf_outline o;
    gf_container_outline(&c, 30, &o);
    assert_int_equal(o.n, 6);
    assert_int_equal(o.nwall[0], 3);
    gf_assert_near(o.wall[0][2][0], -4, 1e-12);
    gf_assert_near(o.wall[1][1][1], 10, 1e-12);
    // The mesh: every vertex on the walls' bounding box.
    gf_mesh m;
    assert_int_equal(gf_container_mesh(&c, 30, 16, &m), GF_OK);
    assert_true(m.nt >= 12);
    for (size_t i = 0; i < m.nv; i++) assert_true(fabs(m.v[i][0]) <= 10 && fabs(m.v[i][1]) <= 3);
    gf_mesh_free(&m);
}

static void expect_invalid(gf_config c, const char *needle)
{
    assert_int_equal(gf_config_validate(&c), GF_ERR_PARAM);
    if (!strstr(gf_last_error(), needle)) fail_msg("\"%s\" not in: %s", needle, gf_last_error());
}

static void wedge_config_errors(void **state)
{
    (void)state;
    gf_config c = gf_config_default();
    c.container_shape = GF_SHAPE_WEDGE;
    c.container_width = 20;
    c.container_depth = 6;
    c.orifice_diameter = 4;
    expect_invalid(c, "container.hopper_angle = 0 (default) must be more than 0 with container.shape = wedge"); // a flat base: the box
    c.hopper_angle = 60;
    c.orifice_diameter = 20;
    expect_invalid(c, "container.orifice_diameter = 20"); // no narrower than the width
    c.orifice_diameter = 4;
    c.orifice_x = 8.5;
    expect_invalid(c, "container.orifice_x = 8.5"); // the slit partly beyond a wall
    c.orifice_x = 0;
    c.inner_radius = 2;
    expect_invalid(c, "container.inner_radius");
    c.inner_radius = 0;
    assert_int_equal(gf_config_set(&c, "container.orifice_shape = circle", "w.ini"), GF_OK);
    expect_invalid(c, "container.orifice_shape = circle");
    // From a file: the message names it and the line.
    c = gf_config_default();
    assert_int_equal(gf_config_set(&c, "container.shape = wedge", "w.ini:2"), GF_OK);
    expect_invalid(c, "container.hopper_angle");
    assert_int_equal(gf_config_set(&c, "container.hopper_angle = 95", "w.ini:3"), GF_ERR_PARAM);
    assert_non_null(strstr(gf_last_error(), "out of range"));
}

// The generator's promises in a wedge: no pair closer than 0.99, every
// centre 1/2 inside every wall, the chute filled from its end.
static void wedge_packing_keeps_the_promises(void **state)
{
    (void)state;
    // A square column (as test_pack's bulk_fraction): the layers at the walls
    // are a small part of the bulk region, so counting centres measures it fairly.
    gf_config c = wedge(16, 16, 60, 4, 2);
    c.packing_particles = 8000;
    gf_packing pk = {0};
    assert_int_equal(gf_packing_generate(&c, NULL, &pk), GF_OK);
    assert_int_equal(pk.n, 8000);
    gf_container box = gf_container_make(&c);
    double zmin = INFINITY;
    for (size_t i = 0; i < pk.n; i++) {
        if (!gf_container_contains(&box, pk.x[i], pk.y[i], pk.z[i], 0.5, 1e-9))
            fail_msg("sphere at (%g, %g, %g) crosses a wall", pk.x[i], pk.y[i], pk.z[i]);
        zmin = fmin(zmin, pk.z[i]);
    }
    assert_true(zmin >= box.z_exit + 0.5 - 1e-9 && zmin < box.z_exit + 0.6);
    double dmin = gf_packing_min_distance(&pk), phi = gf_packing_bulk_fraction(&pk, &c);
    print_message("%zu spheres, min distance %.4f, bulk phi %.4f\n", pk.n, dmin, phi);
    assert_true(dmin >= 0.99);
    // 0.646 measured: the bulk region keeps 2 d from the flat walls (as the
    // box's), where the second layer off a wall still counts a little dense.
    assert_true(phi >= 0.58 && phi <= 0.655);
    assert_int_equal(gf_packing_check(&pk, &c), GF_OK);
    gf_packing_free(&pk);
}

// Short runs, event-driven and fixed-step, truncation and reflection: counts
// conserved, the wedge drains, no centre beyond a wall, every exit over the slit.
static void wedge_drains_through_the_slit(void **state)
{
    (void)state;
    for (int v = 0; v < 3; v++) {
        gf_config c = wedge(16, 6, 60, 4, v == 2 ? 2 : 0);
        c.packing_particles = 1500;
        if (v >= 1) c.run_mode = GF_MODE_FIXED;
        if (v == 1) c.spot_walls = GF_WALLS_REFLECT;
        gf_sim *sim = gf_test_generated_sim(&c);
        const gf_container *b = &sim->box;
        double pmin = INFINITY;
        for (int k = 1; k <= 10; k++) {
            assert_int_equal(gf_sim_run(sim, 0.3 * k, NULL), GF_OK);
            for (size_t i = 0; i < sim->n; i++)
                if (sim->alive[i] && !gf_container_contains(b, sim->p[i].x, sim->p[i].y, sim->p[i].z, 0.0, 1e-9))
                    pmin = fmin(pmin, sim->p[i].z);
        }
        gf_sim_stats st = gf_sim_get_stats(sim);
        assert_int_equal(st.particles_remaining + st.particles_exited, st.particles_initial);
        assert_true(st.particles_exited > 20);
        size_t ne;
        const gf_exit *e = gf_sim_exits(sim, &ne);
        for (size_t i = 0; i < ne; i++) assert_true(fabs(e[i].x) < 2.0); // over the slit
        print_message("variant %d: %zu exits\n", v, ne);
        if (isfinite(pmin)) fail_msg("variant %d: a centre beyond a wall (z = %g)", v, pmin);
        gf_sim_destroy(sim);
    }
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(wedge_walls_by_hand),
    cmocka_unit_test(wedge_inside_clamp_floor_by_hand),
    cmocka_unit_test(wedge_sections_and_volumes),
    cmocka_unit_test(wedge_config_errors),
    cmocka_unit_test(wedge_packing_keeps_the_promises),
    cmocka_unit_test(wedge_drains_through_the_slit),
};

GF_TEST_MAIN("wedge", tests)
