// SPDX-License-Identifier: MIT
// The modules' small defs (granflow/defs.h, issue 24): each builder copies its
// keys and works out the derived values in one place (r_e, the insertion
// margin and radius, the birth height, the thread count, the exit plane,
// the DEM's auto stiffness and damping), and the typed setters change only
// their keys.
#include "support.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "granflow/defs.h"
#include "spot/sim_internal.h"

// relax.radius auto is spot.radius + 1, insertion_margin auto is spot.radius;
// both resolved by the builder whether or not the config was validated, and
// an explicit value is kept.
static void r_e_and_margin_follow_the_spot_radius(void **state)
{
    (void)state;
    gf_config c = gf_config_default();
    assert_true(isnan(c.relax_radius) && isnan(c.spot_insertion_margin)); // auto before validation
    c.spot_radius = 3.0;
    gf_engine_defs d;
    gf_config_engine_defs(&c, &d);
    gf_assert_near(d.r_e, 4.0, 0);
    gf_assert_near(d.insertion_margin, 3.0, 0);
    assert_int_equal(gf_config_validate(&c), GF_OK);
    gf_engine_defs v;
    gf_config_engine_defs(&c, &v);
    assert_true(v.r_e == d.r_e && v.insertion_margin == d.insertion_margin); // validate resolves them the same way
    c.relax_radius = 5.5;
    gf_config_engine_defs(&c, &d);
    gf_assert_near(d.r_e, 5.5, 0);
    gf_spot_params sp;
    gf_config_spot_params(&c, &sp);
    assert_true(sp.r_e == 5.5 && sp.radius == 3.0 && sp.insertion_margin == 3.0);
}

// run.threads 0 is every core (gf_cpu_count), once, here; a count is kept.
static void threads_zero_is_every_core(void **state)
{
    (void)state;
    gf_config c = gf_config_default();
    gf_engine_defs d;
    assert_int_equal(c.run_threads, 0);
    gf_config_engine_defs(&c, &d);
    assert_int_equal(d.threads, gf_cpu_count());
    assert_true(d.threads_auto);
    assert_false(d.spatial); // the event engine
    gf_config_set_threads(&c, 3);
    c.run_mode = GF_MODE_FIXED;
    c.run_order = GF_ORDER_DOMAINS;
    gf_config_engine_defs(&c, &d);
    assert_int_equal(d.threads, 3);
    assert_false(d.threads_auto);
    assert_true(d.spatial);
    gf_config_set_threads(&c, -2); // no count: back to every core
    assert_int_equal(c.run_threads, 0);
}

// The birth disc and height, and the container's exit plane (a pipe's end).
static void birth_and_exit_plane(void **state)
{
    (void)state;
    gf_config c = gf_config_default();
    c.orifice_diameter = 8;
    c.spot_radius = 2.5;
    c.exit_z = -1;
    assert_int_equal(gf_config_validate(&c), GF_OK);
    gf_engine_defs d;
    gf_config_engine_defs(&c, &d);
    gf_assert_near(d.insertion_radius, 4.0 - 2.5, 0);
    gf_assert_near(d.birth_z, -1.0 - 2.5, 0);
    c.spot_insertion_margin = 9; // wider than the hole: born on its axis
    gf_config_engine_defs(&c, &d);
    gf_assert_near(d.insertion_radius, 0.0, 0);

    gf_config y = gf_config_default();
    y.container_shape = GF_SHAPE_CYLINDER;
    y.outlet_length = 3;
    y.exit_z = -0.5;
    assert_int_equal(gf_config_validate(&y), GF_OK);
    gf_container_defs cd;
    gf_config_container_defs(&y, &cd);
    gf_assert_near(cd.exit_level, -0.5, 0);
    gf_assert_near(cd.exit_plane, -3.5, 0);
    gf_assert_near(cd.exit_plane, gf_config_exit_plane(&y), 0);
    gf_assert_near(cd.outlet.length, 3, 0);
    gf_assert_near(cd.radius, y.container_radius, 0);
    gf_config_engine_defs(&y, &d);
    gf_assert_near(d.birth_z, -3.5 - y.spot_radius, 0);
}

// The engine reads what the builder made: a sim's defs are its config's.
static void the_engine_reads_its_defs(void **state)
{
    (void)state;
    gf_config c = gf_config_default();
    c.packing_particles = 300;
    c.container_width = 12;
    c.orifice_diameter = 5;
    c.spot_radius = 2.2;
    gf_sim *sim = NULL;
    assert_int_equal(gf_sim_create_from_config(&c, NULL, &sim), GF_OK);
    gf_assert_near(sim->d.r_e, 3.2, 1e-15);
    gf_assert_near(sim->re, 3.2, 1e-15);
    gf_assert_near(sim->spot_ins_r, 2.5 - 2.2, 1e-15);
    gf_sim_set_threads(sim, 2);
    assert_int_equal(sim->d.threads, 2);
    assert_int_equal(gf_sim_config(sim)->run_threads, 2);
    gf_sim_destroy(sim);
}

// The other builders copy their keys and resolve theirs.
static void packing_rundir_dem_lga(void **state)
{
    (void)state;
    gf_config c = gf_config_default();
    c.dem_kn = 7e4;
    snprintf(c.packing_file, sizeof c.packing_file, "%s", "in.dump");
    c.dump_diameter = 0.004;
    c.run_seed = 42;
    c.lga_p = 0.3;
    gf_dem_defs dd;
    gf_config_dem_defs(&c, &dd);
    gf_assert_near(dd.kt, 2.0 / 7.0 * 7e4, 1e-9); // auto before validation too
    gf_assert_near(dd.gammat, 0.5 * c.dem_gamman, 0);
    assert_true(dd.seed == 42);
    gf_packing_defs pd;
    gf_config_packing_defs(&c, &pd);
    assert_string_equal(pd.file, "in.dump");
    assert_true(pd.unit_diameter == 0.004 && pd.seed == 42);
    gf_rundir_defs rd;
    gf_config_rundir_defs(&c, &rd);
    assert_string_equal(rd.packing, "in.dump");
    assert_true(rd.format == c.output_format && rd.duration == c.run_duration);
    gf_lga_defs ld;
    gf_config_lga_defs(&c, &ld);
    assert_true(ld.p == 0.3 && ld.seed == 42 && isnan(ld.angle));
}

// The setters change their keys and nothing else.
static void setters_touch_only_their_keys(void **state)
{
    (void)state;
    gf_config c = gf_config_default();
    assert_int_equal(gf_config_validate(&c), GF_OK);
    gf_config before = c;
    gf_config_set_spot_fit(&c, 2.0, 300, 200, 20, 0.5);
    assert_true(c.spot_radius == 2.0 && c.spot_w == 300 && c.spot_insertion_rate == 200 && c.spot_move_rate == 20 &&
                c.spot_step_xy == 0.5);
    assert_true(isnan(c.relax_radius) && isnan(c.spot_insertion_margin)); // back to auto: they follow the radius
    gf_spot_params sp;
    gf_config_spot_params(&c, &sp);
    gf_assert_near(sp.r_e, 3.0, 0);
    assert_true(c.spot_step_z == before.spot_step_z && c.run_seed == before.run_seed);
    gf_config_set_extent(&c, 30, 10);
    gf_config_set_dump_units(&c, 2, 9.81);
    gf_config_set_mesh_path(&c, "a.stl");
    assert_true(c.container_width == 30 && c.container_depth == 10 && c.dump_diameter == 2 && c.dump_gravity == 9.81);
    assert_string_equal(c.container_mesh, "a.stl");
    c.run_duration = 5;
    c.run_stall_time = 1;
    c.run_checkpoint_interval = 3;
    c.run_threads = 4;
    gf_config_reset_run_keys(&c);
    assert_true(c.run_duration == before.run_duration && c.run_stall_time == before.run_stall_time &&
                c.run_checkpoint_interval == before.run_checkpoint_interval && c.run_threads == 0);
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(r_e_and_margin_follow_the_spot_radius),
    cmocka_unit_test(threads_zero_is_every_core),
    cmocka_unit_test(birth_and_exit_plane),
    cmocka_unit_test(the_engine_reads_its_defs),
    cmocka_unit_test(packing_rundir_dem_lga),
    cmocka_unit_test(setters_touch_only_their_keys),
};

GF_TEST_MAIN("defs", tests)
