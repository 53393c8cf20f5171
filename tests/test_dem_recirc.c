// SPDX-License-Identifier: MIT
// granflow dem with run.recirculate = on (issue 27): the drain input puts
// particles back instead of deleting them, what it cannot do is refused
// before anything is written, and reinserted.txt becomes a spot run's
// exits.csv (passes, entry times and radii, exit times by free fall back to
// the exit plane). The LAMMPS run itself: tests/cli/dem_recirc.sh.
#include "support.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "core/alloc.h"
#include "dem/dem_internal.h"
#include "granflow/dem.h"
#include "granflow/granflow.h"
#include "io/exits_read.h"

static gf_config box_config(void)
{
    gf_config c = gf_config_default();
    c.container_width = 8;
    c.container_depth = 6;
    c.orifice_diameter = 4;
    c.packing_particles = 200;
    c.dem_fill_method = GF_DEM_GENERATE;
    c.run_duration = 2.05;
    c.output_snapshot_interval = 0.5;
    return c;
}

static char *drain_text(const char *dir)
{
    char in[1100];
    snprintf(in, sizeof in, "%s/in.drain", dir);
    char *text = gf_test_read_file(in, NULL);
    assert_non_null(text);
    return text;
}

static void drain_input_puts_particles_back(void **state)
{
    (void)state;
    char dir[900];
    gf_config c = box_config();
    snprintf(dir, sizeof dir, "%s/plain", gf_test_tmpdir());
    gf_dem_plan plain, rc;
    assert_int_equal(gf_dem_write_inputs(&c, dir, NULL, &plain), GF_OK);
    assert_int_equal(plain.reinsert_steps, 0);
    char *text = drain_text(dir);
    assert_non_null(strstr(text, "evaporate"));
    assert_null(strstr(text, "rc_"));
    free(text);

    c.run_recirculate = 1;
    snprintf(dir, sizeof dir, "%s/rc", gf_test_tmpdir());
    assert_int_equal(gf_dem_write_inputs(&c, dir, NULL, &rc), GF_OK);
    assert_int_equal(rc.reinsert_steps, 1000); // 0.1 tau of 1e-4
    assert_int_equal(rc.drain_steps, 20500);
    // Room above the packing for the reinsertion slab.
    assert_true(rc.box_zhi >= plain.box_zhi + gf_dem_recirc_headroom(plain.box_zhi - 2.0) - 1e-9);
    text = drain_text(dir);
    assert_null(strstr(text, "evaporate"));
    assert_non_null(strstr(text, "region gone block INF INF INF INF INF -2 units box"));
    assert_non_null(strstr(text, "region pour block -3.45 3.45 -2.45 2.45"));
    assert_non_null(strstr(text, "region rc_in intersect 2 pour rc_slab\n"));
    assert_non_null(strstr(text, "set atom ${rc_id} x ${rc_px} y ${rc_py} z ${rc_pz} vx 0 vy 0 vz 0 omega 0 0 0"));
    assert_non_null(strstr(text, "region rc_ball sphere ${rc_px} ${rc_py} ${rc_pz} 1.01 units box"));
    assert_non_null(strstr(text, "exit plane z = 0\" file reinserted.txt"));
    // 20 chunks of 0.1 tau with a reinsertion after each, then the last 0.05 tau.
    assert_non_null(strstr(text, "variable rc_k loop 20\n"));
    assert_non_null(strstr(text, "run 1000 pre ${rc_pre} post no\n"));
    assert_non_null(strstr(text, "run 500 pre ${rc_pre} post no\n"));
    assert_non_null(strstr(text, "delete_atoms group rc_mark compress no")); // never renumber the ids
    free(text);

    // zone: the annulus reinsert_rmin <= r < reinsert_rmax, cut out of the slab.
    c.run_reinsert = GF_REINSERT_ZONE;
    c.run_reinsert_rmin = 1;
    c.run_reinsert_rmax = 2.5;
    snprintf(dir, sizeof dir, "%s/zone", gf_test_tmpdir());
    assert_int_equal(gf_dem_write_inputs(&c, dir, NULL, NULL), GF_OK);
    text = drain_text(dir);
    assert_non_null(strstr(text, "region rc_zin cylinder z 0 0 1 INF INF side out units box"));
    assert_non_null(strstr(text, "region rc_zout cylinder z 0 0 2.5 INF INF units box"));
    assert_non_null(strstr(text, "region rc_in intersect 4 pour rc_slab rc_zin rc_zout"));
    free(text);
    char cfg[1100];
    snprintf(cfg, sizeof cfg, "%s/config.ini", dir);
    text = gf_test_read_file(cfg, NULL);
    assert_non_null(strstr(text, "recirculate = on"));
    free(text);
}

static void what_dem_cannot_do_is_refused(void **state)
{
    (void)state;
    char dir[900];
    gf_config c = box_config();
    c.run_recirculate = 1;
    c.run_max_passes = 3;
    snprintf(dir, sizeof dir, "%s/passes", gf_test_tmpdir());
    assert_int_equal(gf_dem_write_inputs(&c, dir, NULL, NULL), GF_ERR_PARAM);
    assert_non_null(strstr(gf_last_error(), "run.max_passes"));
    assert_int_not_equal(access(dir, F_OK), 0); // nothing written

    c = gf_config_default();
    c.container_shape = GF_SHAPE_CYLINDER;
    c.container_radius = 5;
    c.hopper_angle = 60;
    c.outlet_diameter = 4;
    c.inner_radius = 1;
    c.packing_particles = 200;
    c.dem_fill_method = GF_DEM_GENERATE;
    c.run_recirculate = 1;
    snprintf(dir, sizeof dir, "%s/column", gf_test_tmpdir());
    assert_int_equal(gf_dem_write_inputs(&c, dir, NULL, NULL), GF_ERR_PARAM);
    assert_non_null(strstr(gf_last_error(), "run.recirculate = on around a central column (container.inner_radius)"));
    assert_int_not_equal(access(dir, F_OK), 0);
    c.run_recirculate = 0; // the same column drains as before
    if (gf_dem_write_inputs(&c, dir, NULL, NULL) != GF_OK) fail_msg("%s", gf_last_error());
}

static void fall_time_back_to_the_exit_plane(void **state)
{
    (void)state;
    assert_float_equal(gf_dem_fall_time(2.5, 3.0), 1.0, 1e-12); // 2.5 = 3 t - t^2 / 2
    assert_float_equal(gf_dem_fall_time(2.5, 2.0), 2.0, 1e-12); // slower than free fall: the vertex
    assert_float_equal(gf_dem_fall_time(0.0, 3.0), 0.0, 0.0);
    assert_float_equal(gf_dem_fall_time(-1.0, 3.0), 0.0, 0.0);
    assert_float_equal(gf_dem_fall_time(2.0, -1.0), 0.0, 0.0);
}

static const char PACKING[] = "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n3\nITEM: BOX BOUNDS ff ff ff\n"
                              "-4 4\n-3 3\n-4 10\nITEM: ATOMS id type x y z radius\n"
                              "1 1 3 4 0.5 0.5\n2 1 0.6 0.8 1.5 0.5\n3 1 -1 0 0.5 0.5\n";

static void exits_from_reinsertions(void **state)
{
    (void)state;
    char dir[900];
    snprintf(dir, sizeof dir, "%s/exits", gf_test_tmpdir());
    assert_int_equal(gf_fs_mkdirs(dir), GF_OK);
    assert_int_equal(gf_dem_write_exits(dir), GF_OK); // no record: nothing to do
    char path[1000];
    snprintf(path, sizeof path, "%s/exits.csv", dir);
    assert_int_not_equal(access(path, F_OK), 0);
    gf_test_write_file(dir, "packing.dump", PACKING);
    // id 2 twice (put back at t = 3 at (0, 2), left again at 8.1), id 1 once;
    // the last line cut short by a stop is dropped.
    gf_test_write_file(dir, GF_DEM_REINSERTED,
                       "# granflow reinsertions, exit plane z = 0\n"
                       "# id time x y z vz x_new y_new z_new\n"
                       "2 3 0.5 -0.5 -2.5 -3 0 2 9\n"
                       "1 3.2 1 1 -2.5 -2 1 -2 8.5\n"
                       "2 8.1 0.1 0.2 -2.5 -3 1 1 9\n"
                       "3 9 0 0");
    assert_int_equal(gf_dem_write_exits(dir), GF_OK);
    char *text = gf_test_read_file(path, NULL);
    assert_non_null(text);
    assert_int_equal(strncmp(text, "id,time,x,y,pass,entry_time,entry_r\n", 36), 0);
    free(text);
    gf_exit *e;
    size_t n;
    assert_int_equal(gf_exits_read(path, &e, &n), GF_OK);
    assert_int_equal(n, 3);
    // Sorted by exit time: 1 at 3.2 - 2 = 1.2, 2 at 3 - 1 = 2, 2 at 8.1 - 1 = 7.1.
    assert_int_equal(e[0].id, 1);
    assert_float_equal(e[0].time, 1.2, 1e-9);
    assert_int_equal(e[0].pass, 1);
    assert_float_equal(e[0].entry_time, 0.0, 0.0);
    assert_float_equal(e[0].entry_r, 5.0, 1e-6); // where it stood in packing.dump
    assert_int_equal(e[1].id, 2);
    assert_float_equal(e[1].time, 2.0, 1e-9);
    assert_float_equal(e[1].x, 0.5, 1e-6);
    assert_float_equal(e[1].y, -0.5, 1e-6);
    assert_int_equal(e[1].pass, 1);
    assert_float_equal(e[1].entry_r, 1.0, 1e-6);
    assert_int_equal(e[2].id, 2);
    assert_float_equal(e[2].time, 7.1, 1e-9);
    assert_int_equal(e[2].pass, 2);
    assert_float_equal(e[2].entry_time, 3.0, 1e-9); // put back at t = 3
    assert_float_equal(e[2].entry_r, 2.0, 1e-6);    // at (0, 2)
    gf_free(e, n * sizeof *e);

    // A bad line in the middle is an error naming the file and line.
    gf_test_write_file(dir, GF_DEM_REINSERTED,
                       "# granflow reinsertions, exit plane z = 0\n2 3 0.5 -0.5 -2.5 oops 0 2 9\n1 3 0 0 -3 -3 0 0 9\n");
    assert_int_equal(gf_dem_write_exits(dir), GF_ERR_FORMAT);
    assert_non_null(strstr(gf_last_error(), "reinserted.txt:2"));
    gf_test_write_file(dir, GF_DEM_REINSERTED, "2 3 0.5 -0.5 -2.5 -3 0 2 9\n");
    assert_int_equal(gf_dem_write_exits(dir), GF_ERR_FORMAT);
    assert_non_null(strstr(gf_last_error(), "exit plane"));
}

// dem.restart_interval: the drain's `restart N drain.a.restart
// drain.b.restart` (what granflow dem --continue goes on from), before its
// first run; recirculating, N a whole number of reinsertion chunks (the
// restart then holds the state before a chunk's reinsertions, which a
// continuation redoes); 0: no restart files.
static void drain_writes_restart_files(void **state)
{
    (void)state;
    char dir[900];
    gf_config c = box_config();
    c.dem_restart_interval = 0.25;
    snprintf(dir, sizeof dir, "%s/restart_plain", gf_test_tmpdir());
    gf_dem_plan plan;
    assert_int_equal(gf_dem_write_inputs(&c, dir, NULL, &plan), GF_OK);
    assert_int_equal(plan.restart_steps, 2500);
    char *text = drain_text(dir);
    const char *line = strstr(text, "\nrestart 2500 drain.a.restart drain.b.restart\n");
    assert_non_null(line);
    assert_true(line < strstr(text, "\nrun 20500\n"));
    free(text);

    c.run_recirculate = 1;
    snprintf(dir, sizeof dir, "%s/restart_rc", gf_test_tmpdir());
    assert_int_equal(gf_dem_write_inputs(&c, dir, NULL, &plan), GF_OK);
    assert_int_equal(plan.restart_steps, 3000); // 2500 up to whole chunks of 1000
    text = drain_text(dir);
    line = strstr(text, "\nrestart 3000 drain.a.restart drain.b.restart\n");
    assert_non_null(line);
    assert_true(line < strstr(text, "\nvariable rc_k loop "));
    free(text);

    c.dem_restart_interval = 0;
    snprintf(dir, sizeof dir, "%s/restart_none", gf_test_tmpdir());
    assert_int_equal(gf_dem_write_inputs(&c, dir, NULL, &plan), GF_OK);
    assert_int_equal(plan.restart_steps, 0);
    text = drain_text(dir);
    assert_null(strstr(text, "\nrestart "));
    free(text);
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(drain_input_puts_particles_back),
    cmocka_unit_test(drain_writes_restart_files),
    cmocka_unit_test(what_dem_cannot_do_is_refused),
    cmocka_unit_test(fall_time_back_to_the_exit_plane),
    cmocka_unit_test(exits_from_reinsertions),
};

GF_TEST_MAIN("dem_recirc", tests)
