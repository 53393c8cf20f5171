// SPDX-License-Identifier: MIT
// The container shapes (src/geom, docs/geometry.md): wall distances, normals,
// mirror images, pushes, inside tests and spot truncation of the box and the
// cylinder (flat base, funnel, pipe, column) at points worked out by hand;
// then invariants of short runs in a hopper: spots and particle centres stay
// inside, the run does not depend on the thread count.
#include "support.h"
#include "wall_hits.h"

#include <math.h>
#include <string.h>

#include "geom/container.h"
#include "granflow/granflow.h"
#include "spot/sim_internal.h"

static const double eps = 1e-12;

// A validated cylinder config: wall radius R, funnel angle (degrees), outlet
// diameter, pipe length, column radius.
static gf_config cylinder(double R, double angle, double outlet, double pipe, double inner)
{
    gf_config c = gf_config_default();
    c.container_shape = GF_SHAPE_CYLINDER;
    c.container_radius = R;
    c.hopper_angle = angle;
    c.outlet_diameter = outlet;
    c.outlet_length = pipe;
    c.inner_radius = inner;
    assert_int_equal(gf_config_validate(&c), GF_OK);
    return c;
}

static void box_walls_by_hand(void **state)
{
    (void)state;
    gf_config cfg = gf_config_default(); // 50 x 8, circular orifice of diameter 8
    assert_int_equal(gf_config_validate(&cfg), GF_OK);
    gf_container c = gf_container_make(&cfg);
    gf_test_assert_hit(gf_test_one_hit(&c, -24.7, 0, 10, 0.5), 0.3, 1, 0, 0, true);
    gf_test_assert_hit(gf_test_one_hit(&c, 0, 3.8, 10, 0.5), 0.2, 0, -1, 0, true);
    gf_test_assert_hit(gf_test_one_hit(&c, 10, 0, 0.4, 0.5), 0.4, 0, 0, 1, false); // the base, off the orifice
    // Over the orifice near its rim (radius 4): the vector from the rim point (4, 0, 0) is (-0.3, 0, 0.4).
    gf_test_assert_hit(gf_test_one_hit(&c, 3.7, 0, 0.4, 0.6), 0.5, -0.6, 0, 0.8, false);
    // The corner: two side walls and the base.
    gf_wall_hit hit[GF_WALL_HITS];
    assert_int_equal(gf_container_walls(&c, (double[3]){24.8, -3.9, 0.2}, 0.5, hit), 3);
    // Mirrors (2009 paper Sec. 4): in the x = 25 wall only.
    double m[GF_WALL_HITS][3];
    assert_int_equal(c.ops->mirrors(&c, (double[3]){24, 0, 10}, 2.6, m), 1);
    gf_assert_near(m[0][0], 26, eps);
    gf_assert_near(m[0][2], 10, eps);
}

static void cylinder_flat_base_by_hand(void **state)
{
    (void)state;
    gf_config cfg = cylinder(10, 0, 6, 0, 0);
    assert_true(cfg.container_width == 20 && cfg.container_depth == 20 && cfg.orifice_diameter == 6);
    gf_container c = gf_container_make(&cfg);
    assert_true(c.type == &gf_cylinder_shape && c.z_col == 0.0);
    gf_test_assert_hit(gf_test_one_hit(&c, 9.7, 0, 5, 0.5), 0.3, -1, 0, 0, true);
    const double s = sqrt(0.5); // at 45 degrees of azimuth
    gf_test_assert_hit(gf_test_one_hit(&c, 9.6 * s, 9.6 * s, 5, 0.5), 0.4, -s, -s, 0, true);
    gf_test_assert_hit(gf_test_one_hit(&c, 0, 6, 0.2, 0.5), 0.2, 0, 0, 1, false); // the base plate
    gf_test_assert_hit(gf_test_one_hit(&c, 0, -2.7, 0.4, 0.6), 0.5, 0, 0.6, 0.8, false); // the rim at radius 3
    assert_int_equal(gf_container_walls(&c, (double[3]){0, 0, 5}, 2.6, (gf_wall_hit[GF_WALL_HITS]){0}), 0);
    // Push (SPEC 1.3): alpha (r - gap) along the normal.
    double d[3] = {0, 0, 0};
    gf_container_push(&c, 9.7, 0, 5, 0.5, 0.8, &d[0], &d[1], &d[2]);
    gf_assert_near(d[0], -0.16, eps);
    gf_assert_near(d[2], 0, eps);
    d[0] = d[1] = d[2] = 0;
    gf_container_push(&c, 0, 6, 0.2, 0.5, 0.8, &d[0], &d[1], &d[2]);
    gf_assert_near(d[2], 0.24, eps);
    // Inside tests: within the wall and above the base, or anywhere over the outlet.
    assert_true(gf_container_contains(&c, 9.4, 0, 3, 0.5, 0));
    assert_false(gf_container_contains(&c, 9.6, 0, 3, 0.5, 0));
    assert_false(gf_container_contains(&c, 7.2, 7.2, 3, 0, 0)); // in the bounding box, outside the wall
    assert_false(gf_container_contains(&c, 5, 0, 0.3, 0.5, 0));
    assert_true(gf_container_contains(&c, 1, 0, -2, 0.5, 0));
    // Mirrors: the wall only (the base plate is not a side wall).
    double m[GF_WALL_HITS][3];
    assert_int_equal(c.ops->mirrors(&c, (double[3]){8.5, 0, 1}, 2.6, m), 1);
    gf_assert_near(m[0][0], 11.5, eps);
    gf_assert_near(m[0][2], 1, eps);
}

static void cylinder_funnel_pipe_column_by_hand(void **state)
{
    (void)state;
    // 45 degrees from radius 10 down to the outlet radius 3: the funnel's top is at z = 7.
    gf_config cfg = cylinder(10, 45, 6, 4, 2);
    gf_container c = gf_container_make(&cfg);
    gf_assert_near(c.z_col, 7, 1e-12);
    gf_assert_near(c.z_exit, -4, 0);
    const double s = sqrt(0.5);
    // (rho, z) = (5, 2.5) is 0.5 / sqrt(2) off the funnel line z = rho - 3.
    gf_test_assert_hit(gf_test_one_hit(&c, 5, 0, 2.5, 0.5), 0.5 * s, -s, 0, s, true);
    gf_test_assert_hit(gf_test_one_hit(&c, 0, 5, 2.5, 0.5), 0.5 * s, 0, -s, s, true);
    gf_test_assert_hit(gf_test_one_hit(&c, 0, -2.7, -2, 0.5), 0.3, 0, 1, 0, true);           // the pipe
    gf_test_assert_hit(gf_test_one_hit(&c, 2.3, 0, 10, 0.5), 0.3, 1, 0, 0, true);            // the column's side
    gf_test_assert_hit(gf_test_one_hit(&c, 0, 1, 6.6, 0.5), 0.4, 0, 0, -1, false);           // its bottom
    gf_test_assert_hit(gf_test_one_hit(&c, 2.3, 0, 6.6, 0.6), 0.5, 0.6, 0, -0.8, false);     // its bottom rim
    gf_test_assert_hit(gf_test_one_hit(&c, 9.7, 0, 20, 0.5), 0.3, -1, 0, 0, true);           // the wall above the funnel
    // Mirrors: reflecting (5, 2.5) in the line z = rho - 3 gives (5.5, 2).
    double m[GF_WALL_HITS][3];
    assert_int_equal(c.ops->mirrors(&c, (double[3]){5, 0, 2.5}, 1.0, m), 1);
    gf_assert_near(m[0][0], 5.5, 1e-12);
    gf_assert_near(m[0][1], 0, 1e-12);
    gf_assert_near(m[0][2], 2, 1e-12);
    // The push of the funnel on a sphere of radius 0.5 at gap 0.5/sqrt(2), alpha = 1.
    double d[3] = {0, 0, 0};
    gf_container_push(&c, 5, 0, 2.5, 0.5, 1.0, &d[0], &d[1], &d[2]);
    double f = 0.5 - 0.5 * s;
    gf_assert_near(d[0], -f * s, 1e-12);
    gf_assert_near(d[2], f * s, 1e-12);
    // Inside tests.
    assert_true(gf_container_contains(&c, 5, 0, 3, 0.5, 0)); // 0.707 off the funnel
    assert_false(gf_container_contains(&c, 5, 0, 2.5, 0.5, 0));
    assert_false(gf_container_contains(&c, 1, 0, 10, 0.5, 0)); // in the column
    assert_false(gf_container_contains(&c, 2.8, 0, -2, 0.5, 0)); // through the pipe wall
    assert_true(gf_container_contains(&c, 2.4, 0, -2, 0.5, 0));
    assert_false(gf_container_contains(&c, 5, 0, -1, 0, 0)); // under the funnel, beside the pipe
    // Spot truncation (d_w = 1): square to the funnel, off the wall, round the column.
    double n[3] = {5, 0, 2};
    c.ops->spot_clamp(&c, n, 1.0);
    gf_assert_near(n[0], 5 - sqrt(2.0), 1e-12); // rho <= 3 + z - d_w / sin 45
    n[0] = 0, n[1] = 9.5, n[2] = 20;
    c.ops->spot_clamp(&c, n, 1.0);
    gf_assert_near(n[1], 9, 1e-12);
    n[0] = 0.5, n[1] = 0, n[2] = 10;
    c.ops->spot_clamp(&c, n, 1.0);
    gf_assert_near(n[0], 3, 1e-12);
    n[0] = 0.5, n[1] = 0, n[2] = -1; // below the outlet: left to the birth disc
    c.ops->spot_clamp(&c, n, 1.0);
    gf_assert_near(n[0], 0.5, 0);
    // Re-insertion (recirculation): in the annulus 2 + r <= rho <= 10 - r.
    assert_true(gf_container_inside_xy(&c, 0, 5, 0.5));
    assert_true(gf_container_inside_xy(&c, 9.5, 0, 0.5));
    assert_false(gf_container_inside_xy(&c, 9.6, 0, 0.5));
    assert_false(gf_container_inside_xy(&c, 0, 2.4, 0.5));
    // Resting on the funnel: (rho, z) = (5, 2 + 0.5 sqrt 2) is 0.5 off z = rho - 3.
    gf_assert_near(gf_container_floor_z(&c, 5, 0, 0.5), 2 + 0.5 / s, 1e-12);
    gf_assert_near(gf_container_floor_z(&c, 0, 1, 0.5), 0.5, 0); // over the outlet
    gf_assert_near(gf_container_outer_radius(&c), 10, 0);
    // Slice volumes: above the funnel a disc of radius 10 less the column of
    // radius 2; in the funnel (radius 3 + z) a frustum pi h (a^2 + ab + b^2) / 3.
    const double pi = 3.14159265358979323846;
    gf_assert_near(gf_container_slice_volume(&c, 8, 10), 2 * pi * (100 - 4), 1e-9);
    gf_assert_near(gf_container_slice_volume(&c, 1, 3), pi * 2 * (16 + 24 + 36) / 3.0, 1e-4);
    gf_config bc = gf_config_default(); // the papers' silo: 50 x 8
    gf_container box = gf_container_make(&bc);
    gf_assert_near(gf_container_slice_volume(&box, 50, 70), 20 * 50 * 8, 1e-9);
}

static void cylinder_config_errors(void **state)
{
    (void)state;
    gf_config c = gf_config_default();
    c.container_shape = GF_SHAPE_CYLINDER;
    c.container_radius = 4;
    c.outlet_diameter = 8;
    assert_int_equal(gf_config_validate(&c), GF_ERR_PARAM);
    assert_non_null(strstr(gf_last_error(), "container.outlet_diameter"));
    c = gf_config_default();
    c.container_shape = GF_SHAPE_CYLINDER;
    c.inner_radius = 2;
    assert_int_equal(gf_config_validate(&c), GF_ERR_PARAM); // a column on a flat base
    assert_non_null(strstr(gf_last_error(), "container.hopper_angle"));
    c = gf_config_default();
    c.container_shape = GF_SHAPE_CYLINDER;
    c.orifice_shape = GF_ORIFICE_SLIT;
    assert_int_equal(gf_config_validate(&c), GF_ERR_PARAM);
    c = gf_config_default();
    c.container_shape = GF_SHAPE_CYLINDER;
    c.hopper_angle = 30;
    c.inner_radius = 12;
    assert_int_equal(gf_config_validate(&c), GF_ERR_PARAM);
    assert_non_null(strstr(gf_last_error(), "container.inner_radius"));
}

// ---- packings -----------------------------------------------------------

// granflow pack's promises (SPEC 1.2) in a cylinder: no pair closer than
// 0.99, every centre 1/2 inside every wall, the bulk at 0.58-0.64.
static void cylinder_packings_keep_the_promises(void **state)
{
    (void)state;
    const struct {
        double R, angle, outlet, pipe, inner;
        int64_t n;
    } cases[] = {{8, 0, 6, 0, 0, 6000}, {8, 60, 6, 3, 0, 6000}, {10, 30, 6, 2, 2, 8000}};
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        gf_config c = cylinder(cases[k].R, cases[k].angle, cases[k].outlet, cases[k].pipe, cases[k].inner);
        c.packing_particles = cases[k].n;
        gf_packing pk = {0};
        assert_int_equal(gf_packing_generate(&c, NULL, &pk), GF_OK);
        assert_int_equal(pk.n, (size_t)cases[k].n);
        gf_container box = gf_container_make(&c);
        double zmin = INFINITY;
        for (size_t i = 0; i < pk.n; i++) {
            if (!gf_container_contains(&box, pk.x[i], pk.y[i], pk.z[i], 0.5, 1e-9))
                fail_msg("case %zu: sphere at (%g, %g, %g) crosses a wall", k, pk.x[i], pk.y[i], pk.z[i]);
            zmin = fmin(zmin, pk.z[i]);
        }
        assert_true(zmin >= box.z_exit + 0.5 - 1e-9); // the pipe is filled from its end
        assert_true(zmin < box.z_exit + 0.6);
        double dmin = gf_packing_min_distance(&pk), phi = gf_packing_bulk_fraction(&pk, &c);
        print_message("case %zu: %zu spheres, min distance %.4f, bulk phi %.4f\n", k, pk.n, dmin, phi);
        assert_true(dmin >= 0.99);
        assert_true(phi >= 0.58 && phi <= 0.64);
        assert_int_equal(gf_packing_check(&pk, &c), GF_OK);
        gf_packing_free(&pk);
    }
}

// An exit plane far below the outlet (issue 26: exit_z = -100 failed the
// generator's own final check, and at -60 half the spheres hung below the
// outlet, where there is no wall): the packing rests on the funnel, or fills
// the pipe from its end, never the open space under it.
static void cylinder_packing_ignores_a_deep_exit_plane(void **state)
{
    (void)state;
    const double exits[] = {-100, -60, -1}, pipes[] = {0, 3};
    for (size_t e = 0; e < 3; e++)
        for (size_t k = 0; k < 2; k++) {
            gf_config c = cylinder(6, 0, 4, pipes[k], 0);
            c.exit_z = exits[e];
            c.packing_particles = 1500;
            assert_int_equal(gf_config_validate(&c), GF_OK);
            gf_packing pk = {0};
            assert_int_equal(gf_packing_generate(&c, NULL, &pk), GF_OK);
            assert_int_equal(pk.n, 1500);
            gf_container box = gf_container_make(&c);
            double zmin = INFINITY, floor = fmax(box.z_exit, -pipes[k]) + 0.5;
            for (size_t i = 0; i < pk.n; i++) {
                if (!gf_container_contains(&box, pk.x[i], pk.y[i], pk.z[i], 0.5, 1e-9))
                    fail_msg("exit_z %g, pipe %g: sphere at (%g, %g, %g) crosses a wall", exits[e], pipes[k],
                             pk.x[i], pk.y[i], pk.z[i]);
                zmin = fmin(zmin, pk.z[i]);
            }
            if (!(zmin >= floor - 1e-9 && zmin < floor + 0.1))
                fail_msg("exit_z %g, pipe %g: lowest centre at %g, not on %g", exits[e], pipes[k], zmin, floor);
            gf_packing_free(&pk);
        }
}

// An imported packing (e.g. a DEM dump) in a cylinder with a pipe: a centre
// in the pipe stays, one below its end has already left (dropped and
// counted), one outside the wall is an error naming it.
static void cylinder_import_checks(void **state)
{
    (void)state;
    gf_config c = cylinder(8, 45, 6, 3, 0);
    const char *dir = gf_test_tmpdir();
    const char *path = gf_test_write_file(dir, "cyl.xyz", "3\nthree\nC 0 0 5\nC 0.5 0 -2\nC 0 0.5 -3.5\n");
    snprintf(c.packing_file, sizeof c.packing_file, "%s", path);
    gf_packing pk = {0};
    gf_packing_import_report rep;
    assert_int_equal(gf_packing_import(&c, &pk, &rep), GF_OK);
    assert_int_equal(pk.n, 2);
    assert_int_equal(rep.below_base, 1);
    assert_int_equal(gf_packing_check(&pk, &c), GF_OK);
    assert_int_equal(gf_packing_push(&pk, 9, 1, 6, 6, 10, 0.5), GF_OK); // rho = 8.5 > 8
    assert_int_equal(gf_packing_check(&pk, &c), GF_ERR_PARAM);
    assert_non_null(strstr(gf_last_error(), "id 9"));
    gf_packing_free(&pk);
}

// ---- runs ---------------------------------------------------------------

// Smallest distance of a live particle centre to a wall (negative: crossed),
// and the smallest margin of a spot to its allowed region (negative: left it).
static void margins(const gf_sim *sim, double *pmin, double *smin)
{
    const gf_container *c = &sim->box;
    gf_wall_hit hit[GF_WALL_HITS];
    for (size_t i = 0; i < sim->n; i++) {
        if (!sim->alive[i]) continue;
        const double p[3] = {sim->p[i].x, sim->p[i].y, sim->p[i].z};
        int nh = gf_container_walls(c, p, 0.5, hit);
        for (int k = 0; k < nh; k++)
            if (hit[k].side && hit[k].gap < *pmin) *pmin = hit[k].gap;
        if (!gf_container_contains(c, p[0], p[1], p[2], 0.0, 0.0)) *pmin = fmin(*pmin, -1.0);
    }
    double dw = sim->cfg.spot_walls == GF_WALLS_REFLECT ? 0.0 : sim->cfg.spot_wall_distance;
    for (size_t k = 0; k < sim->ns; k++) {
        const double q[3] = {sim->sx[k], sim->sy[k], sim->sz[k]};
        double m = INFINITY;
        if (q[2] < 0.0) {
            m = sim->spot_ins_r - hypot(q[0], q[1]);
        } else {
            int nh = gf_container_walls(c, q, dw + 1.0, hit);
            for (int h = 0; h < nh; h++)
                if (hit[h].side) m = fmin(m, hit[h].gap - dw);
        }
        if (m < *smin) *smin = m;
    }
}

// A hopper small enough for seconds: wall radius 6, 60 degree funnel,
// outlet 6 with a pipe of 2, about 1500 spheres.
static gf_config small_hopper(double inner)
{
    gf_config c = cylinder(6, 60, 6, 2, inner);
    c.packing_particles = 1500;
    return c;
}

static void hopper_keeps_spots_and_particles_inside(void **state)
{
    (void)state;
    const double inner[] = {0, 1.5};
    for (int v = 0; v < 2; v++) {
        gf_config c = small_hopper(inner[v]);
        c.spot_walls = v ? GF_WALLS_REFLECT : GF_WALLS_TRUNCATE;
        gf_sim *sim = gf_test_generated_sim(&c);
        double pmin = INFINITY, smin = INFINITY;
        for (int k = 1; k <= 10; k++) {
            assert_int_equal(gf_sim_run(sim, 0.2 * k, NULL), GF_OK);
            margins(sim, &pmin, &smin);
        }
        gf_sim_stats st = gf_sim_get_stats(sim);
        // Count conservation, and the hopper drained.
        assert_int_equal(st.particles_remaining + st.particles_exited, st.particles_initial);
        assert_true(st.particles_exited > 20);
        size_t ne;
        const gf_exit *e = gf_sim_exits(sim, &ne);
        for (size_t i = 0; i < ne; i++) assert_true(hypot(e[i].x, e[i].y) < 3.0); // through the outlet
        print_message("inner %g: %zu exits, closest centre to a wall %.3f, closest spot margin %.3g\n", inner[v],
                      ne, pmin, smin);
        assert_true(pmin >= 0.0); // no centre ever beyond a wall
        assert_true(smin >= -1e-9);
        gf_sim_destroy(sim);
    }
}

// The spatial fixed step in a cylinder gives the same state on 1 and 2 threads.
static void hopper_parallel_matches_serial(void **state)
{
    (void)state;
    gf_config c = small_hopper(0);
    c.run_mode = GF_MODE_FIXED;
    c.run_order = GF_ORDER_SPATIAL;
    gf_packing out[2] = {{0}, {0}};
    size_t nexit[2];
    for (int t = 0; t < 2; t++) {
        gf_sim *sim = gf_test_generated_sim(&c);
        gf_sim_set_threads(sim, t + 1);
        assert_int_equal(gf_sim_run(sim, 1.5, NULL), GF_OK);
        gf_sim_exits(sim, &nexit[t]);
        double pmin = INFINITY, smin = INFINITY;
        margins(sim, &pmin, &smin);
        assert_true(pmin >= 0.0 && smin >= -1e-9);
        assert_int_equal(gf_sim_particles(sim, &out[t]), GF_OK);
        gf_sim_destroy(sim);
    }
    assert_true(nexit[0] > 0);
    assert_int_equal(nexit[0], nexit[1]);
    assert_int_equal(out[0].n, out[1].n);
    assert_memory_equal(out[0].z, out[1].z, out[0].n * sizeof(double));
    gf_packing_free(&out[0]);
    gf_packing_free(&out[1]);
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(box_walls_by_hand),
    cmocka_unit_test(cylinder_flat_base_by_hand),
    cmocka_unit_test(cylinder_funnel_pipe_column_by_hand),
    cmocka_unit_test(cylinder_config_errors),
    cmocka_unit_test(cylinder_packings_keep_the_promises),
    cmocka_unit_test(cylinder_packing_ignores_a_deep_exit_plane),
    cmocka_unit_test(cylinder_import_checks),
    cmocka_unit_test(hopper_keeps_spots_and_particles_inside),
    cmocka_unit_test(hopper_parallel_matches_serial),
};

GF_TEST_MAIN("geometry", tests)
