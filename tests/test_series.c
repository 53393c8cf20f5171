// SPDX-License-Identifier: MIT
// gf_series_load on run directories, directories of dumps and multi-frame
// dumps the tests write: time order, layers, container, exits, and errors.
#include "support.h"

#include <math.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "granflow/granflow.h"
#include "granflow/analysis.h"
#include "io/packing_frames.h"

/// A fresh subdirectory of the test's temporary directory.
static const char *subdir(const char *name)
{
    static char path[1024];
    snprintf(path, sizeof path, "%s/%s", gf_test_tmpdir(), name);
    assert_int_equal(mkdir(path, 0777), 0);
    return path;
}

static void expect_error(gf_status got, gf_status want, const char *part1, const char *part2)
{
    assert_int_equal(got, want);
    const char *msg = gf_last_error();
    if (!strstr(msg, part1) || (part2 && !strstr(msg, part2)))
        fail_msg("message '%s' lacks '%s'%s%s", msg, part1, part2 ? " or " : "", part2 ? part2 : "");
}

/// Index of the particle with this id in p (fails when absent).
static size_t find_id(const gf_packing *p, int64_t id)
{
    for (size_t i = 0; i < p->n; i++)
        if (p->id[i] == id) return i;
    fail_msg("no particle with id %lld", (long long)id);
    return 0;
}

// A run directory as `granflow run` writes it: config.ini, snapshots with
// TIME and the layer in `type`, exits.csv. Snapshots are written by the run's
// own writer; the exits file is out of time order to check the sort.
static void run_directory(void **state)
{
    (void)state;
    const char *dir = subdir("run");
    char path[1200];
    gf_config cfg = gf_config_default();
    cfg.container_width = 20;
    cfg.container_depth = 6;
    cfg.orifice_diameter = 4;
    assert_int_equal(gf_config_validate(&cfg), GF_OK);
    snprintf(path, sizeof path, "%s/config.ini", dir);
    assert_int_equal(gf_config_save(&cfg, path), GF_OK);
    snprintf(path, sizeof path, "%s/snapshots", dir);
    assert_int_equal(mkdir(path, 0777), 0);
    // Three snapshots: 4, 3, 2 particles at t = 0, 2, 4; layers 1, 1, 2, 3.
    const int32_t layer[4] = {1, 1, 2, 3};
    for (int k = 0; k < 3; k++) {
        gf_packing pk = {0};
        for (int i = k; i < 4; i++)
            assert_int_equal(gf_packing_push(&pk, i + 1, layer[i], -5.0 + i, 0.5, 10.0 * i + 1 - k, 0.5), GF_OK);
        snprintf(path, sizeof path, "%s/snapshots/snap_%06d.dump", dir, k);
        assert_int_equal(gf_run_write_snapshot(path, &cfg, &pk, NULL, 2.0 * k, (uint64_t)(1000 * k)), GF_OK);
        gf_packing_free(&pk);
    }
    gf_test_write_file(dir, "exits.csv", "id,time,x,y\n2,3.5,0.25,-1\n1,1.25,0.5,0.75\n");
    gf_test_write_file(dir, "summary.json", "{}\n"); // other files are ignored

    gf_series s;
    assert_int_equal(gf_series_load(dir, 0.0, NULL, &s), GF_OK);
    assert_int_equal(s.nframes, 3);
    assert_int_equal(s.n_initial, 4);
    for (int k = 0; k < 3; k++) {
        assert_true(s.frames[k].time == 2.0 * k);
        assert_int_equal(s.frames[k].pk.n, 4 - k);
        for (size_t i = 0; i < s.frames[k].pk.n; i++) {
            int64_t id = s.frames[k].pk.id[i];
            assert_int_equal(s.frames[k].pk.layer[i], layer[id - 1]);
            assert_true(s.frames[k].pk.r[i] == 0.5);
            gf_assert_near(s.frames[k].pk.z[i], 10.0 * (double)(id - 1) + 1 - k, 1e-7); // %.7f in the dump
        }
    }
    assert_true(s.cfg.container_width == 20 && s.cfg.container_depth == 6 && s.cfg.orifice_diameter == 4);
    assert_true(s.has_exits);
    assert_int_equal(s.nexits, 2);
    assert_int_equal(s.exits[0].id, 1); // sorted by time
    assert_true(s.exits[0].time == 1.25 && s.exits[0].x == 0.5 && s.exits[0].y == 0.75);
    assert_int_equal(s.exits[1].id, 2);
    assert_true(s.exits[1].time == 3.5);
    gf_series_free(&s);
    assert_int_equal(s.nframes, 0);
}

static const char *frame_text(char *buf, size_t n, long long ts, const char *time, const char *atoms)
{
    if (time)
        snprintf(buf, n,
                 "ITEM: TIME\n%s\nITEM: TIMESTEP\n%lld\nITEM: NUMBER OF ATOMS\n%d\n"
                 "ITEM: BOX BOUNDS ff ff ff\n0 20\n0 6\n0 40\nITEM: ATOMS id x y z\n%s",
                 time, ts, (int)(strlen(atoms) ? 2 : 0), atoms);
    else
        snprintf(buf, n,
                 "ITEM: TIMESTEP\n%lld\nITEM: NUMBER OF ATOMS\n%d\n"
                 "ITEM: BOX BOUNDS ff ff ff\n0 20\n0 6\n0 40\nITEM: ATOMS id x y z\n%s",
                 ts, (int)(strlen(atoms) ? 2 : 0), atoms);
    return buf;
}

// A DEM-style directory: dumps without ITEM: TIME, no type column, a box from
// 0 to 20 (not centred), names out of time order, and files to ignore.
static void dump_directory_needs_dt(void **state)
{
    (void)state;
    const char *dir = subdir("dem");
    char buf[1024];
    // a.dump is the later frame: name order is not time order.
    gf_test_write_file(dir, "a.dump", frame_text(buf, sizeof buf, 2000, NULL, "7 3 1 25\n8 12 5 5\n"));
    gf_test_write_file(dir, "dump.b", frame_text(buf, sizeof buf, 1000, NULL, "7 2 1 15\n8 11 5 4\n"));
    gf_test_write_file(dir, "c.lammpstrj", frame_text(buf, sizeof buf, 0, NULL, "7 1 1 5\n8 10 5 3\n"));
    gf_test_write_file(dir, "notes.md", "not a dump\n");
    gf_test_write_file(dir, ".hidden.dump", "not a dump either\n");
    gf_test_write_file(dir, "d.dump.tmp", "an unfinished write\n");

    gf_series s;
    expect_error(gf_series_load(dir, 0.0, NULL, &s), GF_ERR_PARAM, "a.dump:1: the frame at timestep 2000 has no ITEM: TIME",
                 "pass dump.dt");
    assert_int_equal(s.nframes, 0);

    assert_int_equal(gf_series_load(dir, 0.005, NULL, &s), GF_OK);
    assert_int_equal(s.nframes, 3);
    const double t[3] = {0.0, 5.0, 10.0}; // TIMESTEP x 0.005
    const double z7[3] = {5, 15, 25};
    for (int k = 0; k < 3; k++) {
        gf_assert_near(s.frames[k].time, t[k], 1e-12);
        const gf_packing *p = &s.frames[k].pk;
        size_t i = find_id(p, 7);
        assert_true(p->z[i] == z7[k]);
        // The box 0..20 x 0..6 is moved to -10..10 x -3..3.
        assert_true(p->x[i] == (double)(k + 1) - 10.0 && p->y[i] == -2.0);
        // Layers from the first frame's heights (10 d bands), kept by id:
        // id 7 starts at z = 5 (layer 1) and stays layer 1 at z = 15, 25.
        assert_int_equal(p->layer[i], 1);
        assert_int_equal(p->layer[find_id(p, 8)], 1);
    }
    // The walls where the particles end, about the box's centre: the widest
    // |x - 10| + r is 9.5 (x = 1), |y - 3| + r is 2.5 (not the box's 20 x 6).
    assert_true(s.cfg.container_width == 19 && s.cfg.container_depth == 5);
    char where[64];
    assert_int_equal(gf_config_where(&s.cfg, "container.width", where, sizeof where), GF_OK);
    assert_string_equal(where, "particle extent");
    assert_false(s.has_config);
    assert_false(s.has_exits);
    assert_null(s.exits);
    assert_int_equal(s.n_initial, 2);
    gf_series_free(&s);
}

// One dump with several frames (ITEM: TIME, type column) written out of time
// order; the last frame of a drained silo has 0 atoms.
static void multiframe_dump(void **state)
{
    (void)state;
    const char *dir = subdir("multi");
    const char *text =
        "ITEM: TIME\n4\nITEM: TIMESTEP\n40\nITEM: NUMBER OF ATOMS\n1\nITEM: BOX BOUNDS ff ff ff\n-5 5\n-2 2\n0 9\n"
        "ITEM: ATOMS id type x y z radius\n2 3 0 0 1 0.6\n"
        "ITEM: TIME\n0\nITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n2\nITEM: BOX BOUNDS ff ff ff\n-5 5\n-2 2\n0 9\n"
        "ITEM: ATOMS id type x y z radius\n1 2 0 0 4 0.4\n2 3 1 0 8 0.6\n"
        "ITEM: TIME\n6\nITEM: TIMESTEP\n60\nITEM: NUMBER OF ATOMS\n0\nITEM: BOX BOUNDS ff ff ff\n-5 5\n-2 2\n0 9\n"
        "ITEM: ATOMS id type x y z radius\n";
    char path[1200];
    snprintf(path, sizeof path, "%s", gf_test_write_file(dir, "all.dump", text));
    gf_series s;
    assert_int_equal(gf_series_load(path, 0.0, NULL, &s), GF_OK); // dump_dt unused: every frame has TIME
    assert_int_equal(s.nframes, 3);
    assert_true(s.frames[0].time == 0 && s.frames[1].time == 4 && s.frames[2].time == 6);
    assert_int_equal(s.frames[0].pk.n, 2);
    assert_int_equal(s.frames[1].pk.n, 1);
    assert_int_equal(s.frames[2].pk.n, 0);
    assert_int_equal(s.n_initial, 2);
    const gf_packing *p = &s.frames[0].pk;
    assert_int_equal(p->layer[find_id(p, 1)], 2);
    assert_int_equal(p->layer[find_id(p, 2)], 3);
    assert_true(p->r[find_id(p, 1)] == 0.4 && p->r[find_id(p, 2)] == 0.6);
    // Walls at the particles' extent over every frame: |x| + r up to 1.6, |y| + r 0.6.
    gf_assert_near(s.cfg.container_width, 3.2, 1e-12);
    gf_assert_near(s.cfg.container_depth, 1.2, 1e-12);
    assert_true(p->x[find_id(p, 2)] == 1.0); // a centred box is not shifted
    assert_false(s.has_exits);
    gf_series_free(&s);
}

static void same_time_is_an_error(void **state)
{
    (void)state;
    const char *dir = subdir("dup");
    char buf[1024];
    gf_test_write_file(dir, "a.dump", frame_text(buf, sizeof buf, 10, "2.5", "1 0 0 1\n2 1 0 1\n"));
    gf_test_write_file(dir, "b.dump", frame_text(buf, sizeof buf, 20, "2.5", "1 0 0 1\n2 1 0 1\n"));
    gf_series s;
    expect_error(gf_series_load(dir, 0.0, NULL, &s), GF_ERR_FORMAT, "two frames at the same time 2.5 tau", "b.dump:1");
}

static void truncated_dump_is_named(void **state)
{
    (void)state;
    const char *dir = subdir("trunc");
    char buf[1024];
    gf_test_write_file(dir, "a.dump", frame_text(buf, sizeof buf, 0, "0", "1 0 0 1\n2 1 0 1\n"));
    gf_test_write_file(dir, "b.dump", frame_text(buf, sizeof buf, 10, "1", "1 0 0 1\n")); // 1 of 2 atoms
    gf_series s;
    expect_error(gf_series_load(dir, 0.0, NULL, &s), GF_ERR_FORMAT, "b.dump:12:",
                 "ends after 1 of 2 atoms (truncated file?)");
    assert_int_equal(s.nframes, 0);
}

static void bad_exits_line(void **state)
{
    (void)state;
    const char *dir = subdir("badexits");
    char buf[1024];
    gf_test_write_file(dir, "a.dump", frame_text(buf, sizeof buf, 0, "0", "1 0 0 1\n2 1 0 1\n"));
    gf_series s;
    gf_test_write_file(dir, "exits.csv", "id,time,x,y\n1,0.5,0,0\n2,abc,0,0\n");
    expect_error(gf_series_load(dir, 0.0, NULL, &s), GF_ERR_FORMAT, "exits.csv:3:", "column 'time': 'abc'");
    gf_test_write_file(dir, "exits.csv", "id,time,x,y\n1,0.5,0,0\n2,0.7,0\n");
    expect_error(gf_series_load(dir, 0.0, NULL, &s), GF_ERR_FORMAT, "exits.csv:3:", "3 fields, expected 4");
    gf_test_write_file(dir, "exits.csv", "id,time,x,y,pass,entry_time,entry_r\n1,0.5,0,0,0,0,1\n");
    expect_error(gf_series_load(dir, 0.0, NULL, &s), GF_ERR_FORMAT, "exits.csv:2:", "column 'pass': '0'");
    gf_test_write_file(dir, "exits.csv", "id,t,x,y\n");
    expect_error(gf_series_load(dir, 0.0, NULL, &s), GF_ERR_FORMAT, "exits.csv:1:", "header 'id,time,x,y'");
    gf_test_write_file(dir, "exits.csv", "id,time,x,y\n\n1,0.5,0,0\n-3,0.7,0,0\n");
    expect_error(gf_series_load(dir, 0.0, NULL, &s), GF_ERR_FORMAT, "exits.csv:4:", "'-3' is not a positive integer");
    // A header only: a run in which nothing has left yet.
    gf_test_write_file(dir, "exits.csv", "id,time,x,y\r\n");
    assert_int_equal(gf_series_load(dir, 0.0, NULL, &s), GF_OK);
    assert_true(s.has_exits);
    assert_int_equal(s.nexits, 0);
    gf_series_free(&s);
}

static void missing_inputs(void **state)
{
    (void)state;
    const char *dir = subdir("empty");
    gf_series s;
    expect_error(gf_series_load(dir, 0.0, NULL, &s), GF_ERR_PARAM, "empty: no LAMMPS dumps in this directory", NULL);
    char path[1200];
    snprintf(path, sizeof path, "%s/nothing-here", gf_test_tmpdir());
    expect_error(gf_series_load(path, 0.0, NULL, &s), GF_ERR_IO, "cannot open", "nothing-here");
    // A run directory whose snapshots folder is empty.
    const char *run = subdir("emptyrun");
    snprintf(path, sizeof path, "%s/snapshots", run);
    assert_int_equal(mkdir(path, 0777), 0);
    expect_error(gf_series_load(run, 0.0, NULL, &s), GF_ERR_PARAM, "emptyrun/snapshots: no LAMMPS dumps", NULL);
    // A run with output.format = vtk: its .vtu snapshots are named, and what to do.
    const char *vrun = subdir("vturun");
    snprintf(path, sizeof path, "%s/snapshots", vrun);
    assert_int_equal(mkdir(path, 0777), 0);
    gf_test_write_file(vrun, "snapshots/snap_000000.vtu", "<?xml version=\"1.0\"?>\n");
    expect_error(gf_series_load(vrun, 0.0, NULL, &s), GF_ERR_PARAM, "vturun/snapshots: only VTK (.vtu) snapshots",
                 "output.format = dump or both");
    // An empty dump file: the importer's message.
    gf_test_write_file(run, "snapshots/snap_000000.dump", "");
    expect_error(gf_series_load(run, 0.0, NULL, &s), GF_ERR_FORMAT, "snap_000000.dump: no particles in file", NULL);
    expect_error(gf_series_load(run, -1.0, NULL, &s), GF_ERR_PARAM, "dump.dt", NULL);
}

// The per-frame reader keeps gf_packing_read's checks and reads TIME strictly.
static gf_status count_frames(void *ctx, const gf_packing_frame *f, gf_packing *pk)
{
    (void)f;
    (void)pk;
    (*(int *)ctx)++;
    return GF_OK;
}

static void frame_reader_errors(void **state)
{
    (void)state;
    const char *dir = subdir("frames");
    char buf[1024];
    int n = 0;
    const char *path = gf_test_write_file(dir, "t.dump", frame_text(buf, sizeof buf, 0, "soon", "1 0 0 1\n2 1 0 1\n"));
    expect_error(gf_packing_read_frames(path, count_frames, &n), GF_ERR_FORMAT, "t.dump:2: ITEM: TIME: 'soon'", NULL);
    path = gf_test_write_file(dir, "u.dump", frame_text(buf, sizeof buf, 0, "1", "1 0 0 1\n1 1 0 1\n"));
    expect_error(gf_packing_read_frames(path, count_frames, &n), GF_ERR_FORMAT,
                 "u.dump:13: duplicate id 1 (already on line 12)", NULL);
    path = gf_test_write_file(
        dir, "v.dump",
        "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n1\nITEM: BOX BOUNDS pp pp pp\n0 1\n0 1\n0 1\n"
        "ITEM: ATOMS id type x y z\n1 one 0 0 0\n");
    expect_error(gf_packing_read_frames(path, count_frames, &n), GF_ERR_FORMAT,
                 "v.dump:10: column 'type': 'one'", NULL);
    assert_int_equal(n, 0);
    // gf_packing_read ignores TIME and type as before.
    gf_packing p = {0};
    assert_int_equal(gf_packing_read(path, GF_FORMAT_AUTO, &p), GF_OK);
    assert_int_equal(p.layer[0], 0);
    gf_packing_free(&p);
}

// A particle that is not in the first frame is tagged by its own height,
// clamped like gf_packing_tag_layers: 1e300 is far beyond int32 (the cast
// was undefined; found by tests/fuzz/fuzz_series_load.c).
static void far_new_particle_layer(void **state)
{
    (void)state;
    const char *dir = subdir("far");
    gf_test_write_file(dir, "a.dump",
                       "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n1\nITEM: BOX BOUNDS ff ff ff\n-5 5\n-3 3\n0 20\n"
                       "ITEM: ATOMS id x y z\n1 0 0 10\n"
                       "ITEM: TIMESTEP\n1\nITEM: NUMBER OF ATOMS\n1\nITEM: BOX BOUNDS ff ff ff\n-5 5\n-3 3\n0 20\n"
                       "ITEM: ATOMS id x y z\n2 0 0 1e300\n");
    gf_series s;
    assert_int_equal(gf_series_load(dir, 0.5, NULL, &s), GF_OK);
    assert_int_equal(s.nframes, 2);
    assert_int_equal(s.frames[0].pk.layer[0], 2); // 1 + floor(10 / 10)
    assert_int_equal(s.frames[1].pk.layer[0], 1 + 1000000000);
    gf_series_free(&s);
}

// Dumps in SI units (gf_series_opts.units): metres and seconds become d and
// tau (d = 4 mm, g = 9.81: tau = sqrt(d / g)), positions, radii, the box and
// exits.csv alike, and TIMESTEP x dump_dt is in seconds; the walls are where
// the particles end, marked so, not the wider box.
static void si_units_are_converted(void **state)
{
    (void)state;
    const char *dir = subdir("si");
    const double d = 0.004, tau = sqrt(0.004 / 9.81);
    char buf[1024];
    for (int k = 0; k < 2; k++) {
        // Box -0.024..0.024 x -0.016..0.016 m (12 x 8 d), walls at +-5 and +-3 d.
        snprintf(buf, sizeof buf,
                 "ITEM: TIMESTEP\n%d\nITEM: NUMBER OF ATOMS\n2\nITEM: BOX BOUNDS ff ff ff\n-0.024 0.024\n-0.016 0.016\n"
                 "0 0.04\nITEM: ATOMS id type x y z radius\n1 1 -0.018 0.010 %.17g 0.002\n2 1 0.018 -0.010 0.006 0.002\n",
                 1000 * k, 0.002 + 0.004 * k);
        char name[32];
        snprintf(name, sizeof name, "dump.%d", 1000 * k);
        gf_test_write_file(dir, name, buf);
    }
    gf_test_write_file(dir, "exits.csv", "id,time,x,y\n3,0.004,0.002,-0.004\n");
    gf_series s;
    const gf_series_units si = {d, 9.81};
    assert_int_equal(gf_series_load(dir, 1e-5, &(gf_series_opts){.units = &si}, &s), GF_OK);
    assert_int_equal(s.nframes, 2);
    gf_assert_near(s.frames[1].time, 1000 * 1e-5 / tau, 1e-12); // 1000 steps of 10 us
    const gf_packing *p = &s.frames[0].pk;
    size_t i = find_id(p, 1);
    gf_assert_near(p->x[i], -4.5, 1e-12);
    gf_assert_near(p->y[i], 2.5, 1e-12);
    gf_assert_near(p->z[i], 0.5, 1e-12);
    gf_assert_near(p->r[i], 0.5, 1e-12);
    gf_assert_near(s.frames[1].pk.z[find_id(&s.frames[1].pk, 1)], 1.5, 1e-12);
    assert_int_equal(s.nexits, 1);
    gf_assert_near(s.exits[0].time, 0.004 / tau, 1e-12);
    gf_assert_near(s.exits[0].x, 0.5, 1e-12);
    gf_assert_near(s.exits[0].y, -1.0, 1e-12);
    // Walls at the particles' extent, |x| + r = 5, |y| + r = 3: not the box's 12 x 8.
    gf_assert_near(s.cfg.container_width, 10.0, 1e-12);
    gf_assert_near(s.cfg.container_depth, 6.0, 1e-12);
    char where[64];
    assert_int_equal(gf_config_where(&s.cfg, "container.depth", where, sizeof where), GF_OK);
    assert_string_equal(where, "particle extent");
    // A width given is kept.
    gf_config c = gf_config_default();
    assert_int_equal(gf_config_set(&c, "container.width=20", "--set"), GF_OK);
    assert_int_equal(gf_series_fit_walls(&s, &c), GF_OK);
    assert_true(c.container_width == 20.0);
    gf_assert_near(c.container_depth, 6.0, 1e-12);
    gf_series_free(&s);
    const gf_series_units bad = {0, 9.81};
    expect_error(gf_series_load(dir, 1e-5, &(gf_series_opts){.units = &bad}, &s), GF_ERR_PARAM, "dump.diameter = 0", NULL);
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(si_units_are_converted),
    cmocka_unit_test(run_directory),
    cmocka_unit_test(dump_directory_needs_dt),
    cmocka_unit_test(multiframe_dump),
    cmocka_unit_test(same_time_is_an_error),
    cmocka_unit_test(truncated_dump_is_named),
    cmocka_unit_test(bad_exits_line),
    cmocka_unit_test(missing_inputs),
    cmocka_unit_test(frame_reader_errors),
    cmocka_unit_test(far_new_particle_layer),
};

GF_TEST_MAIN("series", tests)
