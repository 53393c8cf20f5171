// SPDX-License-Identifier: MIT
// The orifice off the centre of the base (container.orifice_x, orifice_y):
// the box's rim and exit test around it, spots born over it and kept over it
// below the base, a run that drains through it and nowhere else, and the
// checks that keep it inside the base (docs/config.md, docs/geometry.md).
// ctest: nosan-case off_centre_circle_drains_through_it
#include "support.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geom/container.h"
#include "geom/mesh.h"
#include "granflow/granflow.h"
#include "spot/sim_internal.h"

// A 24 x 8 box (x = -12..12) with a circular orifice of diameter 5 at x = 7:
// the hole spans x = 4.5..9.5, well clear of the centre's disc of radius 2.5.
static gf_config off_centre(void)
{
    gf_config c = gf_config_default();
    c.container_width = 24;
    c.container_depth = 8;
    c.orifice_diameter = 5;
    c.orifice_x = 7;
    c.packing_particles = 2000;
    return c;
}

static void rim_and_exit_follow_the_centre(void **state)
{
    (void)state;
    gf_config cfg = off_centre();
    cfg.orifice_y = 1;
    assert_int_equal(gf_config_validate(&cfg), GF_OK);
    gf_container c = gf_container_make(&cfg);
    assert_true(gf_container_over_hole(&c, 7, 1));
    assert_true(gf_container_over_hole(&c, 9.4, 1));
    assert_false(gf_container_over_hole(&c, 0, 0)); // the centre of the base is plate now
    assert_false(gf_container_over_hole(&c, 7, 3.6));
    assert_true(gf_container_exited(&c, 7.5, 0.5, -0.1));
    assert_false(gf_container_exited(&c, 0, 0, -0.1));
    // (9.2, 1, 0): over the hole, 0.3 inside its rim at x = 9.5: the rim pushes it back towards the centre.
    gf_wall_hit hit[GF_WALL_HITS];
    const double p[3] = {9.2, 1, 0};
    assert_int_equal(gf_container_walls(&c, p, 0.5, hit), 1);
    gf_assert_near(hit[0].gap, 0.3, 1e-12);
    gf_assert_near(hit[0].n[0], -1, 1e-12);
    gf_assert_near(hit[0].n[1], 0, 1e-12);
    double dx = 0, dy = 0, dz = 0;
    gf_container_push(&c, 9.2, 1, 0, 0.5, 1.0, &dx, &dy, &dz);
    gf_assert_near(dx, -0.2, 1e-12);
    // (0, 0, 0.4): on the plate where a centred orifice would be.
    const double q[3] = {0, 0, 0.4};
    assert_int_equal(gf_container_walls(&c, q, 0.5, hit), 1);
    gf_assert_near(hit[0].gap, 0.4, 1e-12);
    gf_assert_near(hit[0].n[2], 1, 1e-12);
    assert_false(gf_container_contains(&c, 0, 0, 0.2, 0.5, 0));
    assert_true(gf_container_contains(&c, 7, 1, 0.2, 0.5, 0));
    // A slit at x = -5: |x + 5| < 2.
    gf_config s = off_centre();
    s.orifice_shape = GF_ORIFICE_SLIT;
    s.orifice_diameter = 4;
    s.orifice_x = -5;
    assert_int_equal(gf_config_validate(&s), GF_OK);
    c = gf_container_make(&s);
    assert_true(gf_container_over_hole(&c, -6.9, 3.9));
    assert_false(gf_container_over_hole(&c, 0, 0));
    assert_false(gf_container_over_hole(&c, -7.1, 0));
}

// Spots are born uniformly on the orifice around (orifice_x, orifice_y),
// shrunk by the margin, one spot radius below the exit plane.
static void spots_are_born_over_it(void **state)
{
    (void)state;
    gf_config cfg = off_centre();
    cfg.orifice_y = -1;
    cfg.spot_insertion_margin = 1; // born within 1.5 of the centre
    cfg.packing_particles = 300;
    assert_int_equal(gf_config_validate(&cfg), GF_OK);
    gf_sim *sim = gf_test_generated_sim(&cfg);
    const double R = 2.5 - cfg.spot_insertion_margin + 1e-12;
    double mx = 0, my = 0;
    for (int k = 0; k < 2000; k++) assert_int_equal(gf_spot_insert(sim), GF_OK);
    assert_true(sim->ns >= 2000);
    for (size_t k = sim->ns - 2000; k < sim->ns; k++) {
        assert_true(hypot(sim->sx[k] - 7, sim->sy[k] + 1) <= R);
        gf_assert_near(sim->sz[k], -cfg.spot_radius, 1e-12);
        mx += sim->sx[k] / 2000;
        my += sim->sy[k] / 2000;
    }
    gf_assert_near(mx, 7, 0.05); // centred on the orifice, not merely inside it
    gf_assert_near(my, -1, 0.05);
    gf_sim_destroy(sim);
}

// A few tau of drainage: every exit lies over the orifice around (7, 0),
// none over where a centred orifice would be, and spots below the base stay
// over the region they are born in.
static void off_centre_circle_drains_through_it(void **state)
{
    (void)state;
    gf_config cfg = off_centre();
    cfg.spot_insertion_margin = 1; // spots born on a disc, not at its centre
    assert_int_equal(gf_config_validate(&cfg), GF_OK);
    gf_sim *sim = gf_test_generated_sim(&cfg);
    double below = 0;
    for (int step = 0; step < 20; step++) {
        assert_int_equal(gf_sim_run(sim, 0.15 * (step + 1), NULL), GF_OK);
        for (size_t k = 0; k < sim->ns; k++)
            if (sim->sz[k] < 0) {
                assert_true(hypot(sim->sx[k] - 7, sim->sy[k]) <= sim->spot_ins_r + 1e-9);
                below++;
            }
    }
    size_t ne;
    const gf_exit *e = gf_sim_exits(sim, &ne);
    print_message("%zu exits, %g spot sightings below the base\n", ne, below);
    assert_true(ne > 30);
    assert_true(below > 0);
    for (size_t i = 0; i < ne; i++) {
        assert_true(hypot(e[i].x - 7, e[i].y) < 2.5);
        assert_true(hypot(e[i].x, e[i].y) >= 2.5);
    }
    gf_sim_destroy(sim);
}

// An error naming `part` from validating c.
static void rejected(gf_config c, const char *part)
{
    assert_int_equal(gf_config_validate(&c), GF_ERR_PARAM);
    if (!strstr(gf_last_error(), part)) fail_msg("'%s' lacks '%s'", gf_last_error(), part);
}

static void orifice_outside_the_base_is_rejected(void **state)
{
    (void)state;
    gf_config c = off_centre();
    c.orifice_x = 10; // 10 + 2.5 > 12
    rejected(c, "container.orifice_x = 10");
    rejected(c, "partly outside the base");
    c.orifice_x = -9.6;
    rejected(c, "container.orifice_x = -9.6");
    c.orifice_x = 9.4; // 9.4 + 2.5 < 12
    assert_int_equal(gf_config_validate(&c), GF_OK);
    c = off_centre();
    c.orifice_y = 1.6; // 1.6 + 2.5 > 4
    rejected(c, "container.orifice_y = 1.6");
    c.orifice_y = -1.5; // touching the wall y = -4 is allowed
    assert_int_equal(gf_config_validate(&c), GF_OK);
    // A slit has no y position; a cylinder's outlet is on its axis.
    c = off_centre();
    c.orifice_shape = GF_ORIFICE_SLIT;
    c.orifice_y = 1;
    rejected(c, "container.orifice_y = 1");
    rejected(c, "a slit spans the whole depth");
    c = gf_config_default();
    c.container_shape = GF_SHAPE_CYLINDER;
    c.orifice_x = 2;
    rejected(c, "container.orifice_x = 2");
    rejected(c, "a cylinder's outlet is on its axis");
    // From a file and from --set, the key is named too.
    gf_config f = gf_config_default();
    const char *ini = gf_test_write_file(gf_test_tmpdir(), "orifice.ini",
                                         "[container]\nwidth = 20\norifice_diameter = 6\norifice_x = 8\n");
    assert_int_equal(gf_config_load(&f, ini), GF_OK);
    rejected(f, "orifice.ini:4: container.orifice_x = 8 puts the orifice");
    rejected(f, "less than half of container.width = 20 (");
    rejected(f, "orifice.ini:2)");
    f = gf_config_default();
    assert_int_equal(gf_config_set(&f, "container.orifice_y=-3", "--set"), GF_OK);
    rejected(f, "--set: container.orifice_y = -3");
}

// `granflow dem`'s LAMMPS input: the hole in the base wall is a cylinder
// about the orifice centre, and every frozen rim bead lies on its edge.
static void dem_input_cuts_the_hole_there(void **state)
{
    (void)state;
    gf_config c = off_centre();
    c.orifice_y = 1;
    c.packing_particles = 300;
    assert_int_equal(gf_config_validate(&c), GF_OK);
    char dir[900], path[1000];
    snprintf(dir, sizeof dir, "%s/dem", gf_test_tmpdir());
    gf_dem_plan plan;
    assert_int_equal(gf_dem_write_inputs(&c, dir, NULL, &plan), GF_OK);
    snprintf(path, sizeof path, "%s/in.drain", dir);
    char *text = gf_test_read_file(path, NULL);
    assert_non_null(text);
    if (!strstr(text, "region hole cylinder z 7 1 2.5 ")) fail_msg("in.drain lacks the hole at (7, 1):\n%s", text);
    assert_non_null(strstr(text, "orifice of 5 d at x = 7, y = 1 on the base"));
    free(text);
    snprintf(path, sizeof path, "%s/in.fill", dir);
    text = gf_test_read_file(path, NULL);
    assert_non_null(text);
    size_t beads = 0;
    for (const char *p = strstr(text, "create_atoms 2 single "); p; p = strstr(p + 1, "create_atoms 2 single ")) {
        double x, y;
        assert_int_equal(sscanf(p, "create_atoms 2 single %lf %lf", &x, &y), 2);
        gf_assert_near(hypot(x - 7, y - 1), 2.5, 1e-5);
        beads++;
    }
    assert_int_equal(beads, plan.rim_beads);
    assert_true(beads > 100);
    free(text);
    // A slit at x = -5 of width 4: the hole is the block -7 < x < -3.
    gf_config s = off_centre();
    s.orifice_shape = GF_ORIFICE_SLIT;
    s.orifice_diameter = 4;
    s.orifice_x = -5;
    s.packing_particles = 300;
    assert_int_equal(gf_config_validate(&s), GF_OK);
    assert_int_equal(gf_dem_write_inputs(&s, dir, NULL, &plan), GF_OK);
    snprintf(path, sizeof path, "%s/in.drain", dir);
    text = gf_test_read_file(path, NULL);
    assert_non_null(text);
    assert_non_null(strstr(text, "region hole block -7 -3 INF INF "));
    free(text);
}

// The container mesh (container.vtk): the base plate at z = 0 has the area
// of the base less the hole's, and every plate vertex lies outside the hole
// around (7, 1) (on its rim at most), none inside the disc where a centred
// orifice would be cut.
static void mesh_cuts_the_hole_there(void **state)
{
    (void)state;
    gf_config cfg = off_centre();
    cfg.orifice_y = 1;
    assert_int_equal(gf_config_validate(&cfg), GF_OK);
    gf_container c = gf_container_make(&cfg);
    gf_mesh m;
    assert_int_equal(gf_container_mesh(&c, 10.0, 256, &m), GF_OK);
    double area = 0;
    bool touches_rim = false;
    for (size_t k = 0; k < m.nt; k++) {
        const double *a = m.v[m.t[k][0]], *b = m.v[m.t[k][1]], *d = m.v[m.t[k][2]];
        if (a[2] != 0.0 || b[2] != 0.0 || d[2] != 0.0) continue; // a side wall
        area += 0.5 * fabs((b[0] - a[0]) * (d[1] - a[1]) - (b[1] - a[1]) * (d[0] - a[0]));
        for (int j = 0; j < 3; j++) {
            const double *v = m.v[m.t[k][j]];
            double r = hypot(v[0] - 7, v[1] - 1);
            assert_true(r >= 2.5 - 1e-9);
            touches_rim |= r < 2.5 + 1e-9;
        }
    }
    assert_true(touches_rim);
    // The hole is a polygon of ~256 sides inscribed in the circle: pi R^2 less ~1e-4 of it.
    gf_assert_near(area, 24.0 * 8.0 - 3.14159265358979323846 * 2.5 * 2.5, 0.01);
    gf_mesh_free(&m);
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(rim_and_exit_follow_the_centre),
    cmocka_unit_test(spots_are_born_over_it),
    cmocka_unit_test(off_centre_circle_drains_through_it),
    cmocka_unit_test(orifice_outside_the_base_is_rejected),
    cmocka_unit_test(dem_input_cuts_the_hole_there),
    cmocka_unit_test(mesh_cuts_the_hole_there),
};

GF_TEST_MAIN("orifice", tests)
