// SPDX-License-Identifier: MIT
// The flat-array API bindings use for notebooks (issue 25): one frame of a
// dump (gf_snapshot_*: radius, pass, frames, .gz), a simulation from arrays
// (gf_sim_create_from_arrays) and its state as files (gf_sim_write_*).
#include "support.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "granflow/granflow.h"

// Two frames; the second has radius and pass columns in another order.
static const char TWO_FRAMES[] = "ITEM: TIME\n0.5\nITEM: TIMESTEP\n10\nITEM: NUMBER OF ATOMS\n2\n"
                                 "ITEM: BOX BOUNDS ff ff ff\n-6 6\n-3 3\n0 20\n"
                                 "ITEM: ATOMS id type x y z\n7 2 1 2 3\n3 1 -1 0 1.5\n"
                                 "ITEM: TIME\n1.5\nITEM: TIMESTEP\n20\nITEM: NUMBER OF ATOMS\n3\n"
                                 "ITEM: BOX BOUNDS ff ff ff\n-6 6\n-3 3\n0 20\n"
                                 "ITEM: ATOMS pass id x y z radius type\n2 7 1 2 3 0.45 2\n1 3 -1 0 1.5 0.5 1\n"
                                 "3 9 0 0 4 0.55 4\n";

static void snapshot_frames_radius_pass_and_gz(void **state)
{
    (void)state;
    const char *dir = gf_test_tmpdir();
    char plain[512], gz[512];
    snprintf(plain, sizeof plain, "%s", gf_test_write_file(dir, "two.dump", TWO_FRAMES));
    snprintf(gz, sizeof gz, "%s/two.dump.gz", dir);
    assert_true(gf_test_gzip(plain, gz, 0) > 0);
    for (int k = 0; k < 2; k++) {
        gf_snapshot *s;
        assert_int_equal(gf_snapshot_read(k ? gz : plain, -1, &s), GF_OK);
        assert_int_equal(gf_snapshot_count(s), 3);
        assert_int_equal(gf_snapshot_frames(s), 2);
        assert_true(gf_snapshot_time(s) == 1.5);
        assert_int_equal(gf_snapshot_step(s), 20);
        double lo[3], hi[3];
        assert_int_equal(gf_snapshot_box(s, lo, hi), 1);
        assert_true(lo[1] == -3 && hi[2] == 20);
        int64_t id[3];
        int32_t type[3], pass[3];
        double xyz[9], r[3];
        size_t n;
        assert_int_equal(gf_snapshot_copy(s, id, type, xyz, r, pass, 2, &n), GF_ERR_PARAM); // no room
        assert_int_equal(gf_snapshot_copy(s, id, type, xyz, r, pass, 3, &n), GF_OK);
        assert_int_equal(n, 3);
        assert_true(id[0] == 7 && id[1] == 3 && id[2] == 9);
        assert_true(type[0] == 2 && type[2] == 4);
        assert_true(pass[0] == 2 && pass[1] == 1 && pass[2] == 3);
        assert_true(r[0] == 0.45 && r[2] == 0.55);
        assert_true(xyz[6] == 0 && xyz[8] == 4);
        gf_snapshot_destroy(s);
    }
    // The first frame: no radius or pass column -> 0.5 and 1.
    gf_snapshot *s;
    assert_int_equal(gf_snapshot_read(plain, 0, &s), GF_OK);
    assert_int_equal(gf_snapshot_count(s), 2);
    assert_true(gf_snapshot_time(s) == 0.5);
    double r[2];
    int32_t pass[2];
    assert_int_equal(gf_snapshot_copy(s, NULL, NULL, NULL, r, pass, 2, NULL), GF_OK);
    assert_true(r[0] == 0.5 && r[1] == 0.5 && pass[0] == 1 && pass[1] == 1);
    gf_snapshot_destroy(s);
    // No frame 2; no file; a bad pass value names file and line.
    assert_int_equal(gf_snapshot_read(plain, 2, &s), GF_ERR_PARAM);
    assert_non_null(strstr(gf_last_error(), "has 2 frames: there is no frame 2"));
    assert_null(s);
    char missing[512];
    snprintf(missing, sizeof missing, "%s/none.dump", dir);
    assert_int_equal(gf_snapshot_read(missing, -1, &s), GF_ERR_IO);
    const char *bad = gf_test_write_file(dir, "bad.dump",
                                         "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n1\nITEM: ATOMS id x y z pass\n"
                                         "1 0 0 1 0\n");
    assert_int_equal(gf_snapshot_read(bad, -1, &s), GF_ERR_FORMAT);
    assert_non_null(strstr(gf_last_error(), "bad.dump:6: column 'pass'"));
}

static void sim_from_arrays_checks_every_value(void **state)
{
    (void)state;
    gf_config c = gf_test_silo_config(12, 100, 1);
    double xyz[9] = {0, 0, 0.5, 2, 0, 0.5, 0, 2, 12.5};
    double r[3] = {0.5, 0.5, 0.5};
    int64_t id[3] = {5, 6, 5};
    gf_sim *sim;
    assert_int_equal(gf_sim_create_from_arrays(&c, 3, xyz, r, id, &sim), GF_ERR_PARAM);
    assert_string_equal(gf_last_error(), "ids[0] = ids[2] = 5: ids must be unique");
    id[2] = 0;
    assert_int_equal(gf_sim_create_from_arrays(&c, 3, xyz, r, id, &sim), GF_ERR_PARAM);
    assert_non_null(strstr(gf_last_error(), "ids[2] = 0"));
    r[1] = NAN;
    assert_int_equal(gf_sim_create_from_arrays(&c, 3, xyz, r, NULL, &sim), GF_ERR_PARAM);
    assert_non_null(strstr(gf_last_error(), "radii[1]"));
    xyz[3] = 50;
    assert_int_equal(gf_sim_create_from_arrays(&c, 3, xyz, NULL, NULL, &sim), GF_ERR_PARAM);
    assert_non_null(strstr(gf_last_error(), "positions[1] = (50, 0, 0.5) is outside the container"));
    assert_int_equal(gf_sim_create_from_arrays(&c, 0, xyz, NULL, NULL, &sim), GF_ERR_PARAM);
    xyz[3] = 2;
    c.packing_layer_thickness = 10;
    assert_int_equal(gf_sim_create_from_arrays(&c, 3, xyz, NULL, NULL, &sim), GF_OK);
    int64_t got_id[3];
    int32_t layer[3];
    double got_r[3];
    assert_int_equal(gf_sim_copy_particles(sim, got_id, layer, NULL, got_r, 3, NULL), GF_OK);
    assert_true(got_id[0] == 1 && got_id[2] == 3 && layer[0] == 1 && layer[2] == 2 && got_r[1] == 0.5);
    gf_sim_destroy(sim);
}

// A generated silo, run a while, written as a snapshot and a run directory:
// the snapshot reads back, the run directory's checkpoint loads as the same state.
static void sim_written_as_files_reads_back(void **state)
{
    (void)state;
    const char *dir = gf_test_tmpdir();
    gf_config c = gf_test_silo_config(10, 400, 3);
    c.orifice_diameter = 5;
    gf_sim *sim = gf_test_generated_sim(&c);
    assert_int_equal(gf_sim_run(sim, 1.0, NULL), GF_OK);
    size_t n = gf_sim_particle_count(sim);
    char path[512], vtu[512], run[512];
    snprintf(path, sizeof path, "%s/now.dump", dir);
    snprintf(vtu, sizeof vtu, "%s/now.vtu", dir);
    snprintf(run, sizeof run, "%s/run", dir);
    assert_int_equal(gf_sim_write_snapshot(sim, path), GF_OK);
    assert_int_equal(gf_sim_write_vtk(sim, vtu), GF_OK);
    assert_int_equal(access(vtu, F_OK), 0);
    gf_snapshot *s;
    assert_int_equal(gf_snapshot_read(path, -1, &s), GF_OK);
    assert_int_equal(gf_snapshot_count(s), n);
    assert_true(gf_snapshot_time(s) == gf_sim_stat(sim, "time"));
    gf_snapshot_destroy(s);

    assert_int_equal(gf_sim_write_run_dir(sim, run, 0), GF_OK);
    assert_int_equal(gf_sim_write_run_dir(sim, run, 0), GF_ERR_EXISTS);
    assert_int_equal(gf_sim_write_run_dir(sim, run, 1), GF_OK);
    char ckpt[600], ini[600];
    snprintf(ckpt, sizeof ckpt, "%s/checkpoint.bin", run);
    snprintf(ini, sizeof ini, "%s/config.ini", run);
    gf_config saved = gf_config_default();
    assert_int_equal(gf_config_load(&saved, ini), GF_OK);
    gf_sim *back;
    assert_int_equal(gf_sim_load(&saved, ckpt, &back), GF_OK);
    assert_int_equal(gf_sim_particle_count(back), n);
    assert_true(gf_sim_stat(back, "events") == gf_sim_stat(sim, "events"));
    // The run directory is a series analyze reads: one frame, its exits.
    gf_series series = {0};
    assert_int_equal(gf_series_load(run, 0, NULL, &series), GF_OK);
    assert_int_equal(series.nframes, 1);
    assert_int_equal(series.frames[0].pk.n, n);
    assert_int_equal(series.nexits, gf_sim_exit_count(sim));
    gf_series_free(&series);
    gf_sim_destroy(back);
    gf_sim_destroy(sim);
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(snapshot_frames_radius_pass_and_gz),
    cmocka_unit_test(sim_from_arrays_checks_every_value),
    cmocka_unit_test(sim_written_as_files_reads_back),
};

GF_TEST_MAIN("bindings", tests)
