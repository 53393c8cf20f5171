// SPDX-License-Identifier: MIT
// DEM side by side (SPEC 1.8): the LAMMPS inputs run under Debian's lmp and
// give dumps granflow reads; DEM dumps import (column orders, scaled
// coordinates, several timesteps, truncated files, atom types, particles
// below the base).
#include "support.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "dem/lammps_output.h"
#include "geom/container.h"
#include "granflow/dem.h"
#include "granflow/granflow.h"

static const char *path_in(const char *sub)
{
    static char buf[800];
    snprintf(buf, sizeof buf, "%s/%s", gf_test_tmpdir(), sub);
    return buf;
}

// ---- the LAMMPS run -----------------------------------------------------------

static void lammps_run_gives_readable_dumps(void **state)
{
    (void)state;
    gf_config c = gf_config_default();
    c.container_width = 10;
    c.container_depth = 6;
    c.orifice_diameter = 4;
    c.packing_particles = 300;
    c.dem_fill_method = GF_DEM_GENERATE; // granflow's packing: no pour to wait for
    c.dem_settle_time = 0.3;
    c.run_duration = 0.3;
    c.output_snapshot_interval = 0.1;
    char dir[900];
    snprintf(dir, sizeof dir, "%s", path_in("dem"));
    gf_dem_plan plan;
    assert_int_equal(gf_dem_write_inputs(&c, dir, NULL, &plan), GF_OK);
    assert_int_equal(plan.particles, 300);
    assert_int_equal(plan.snapshot_steps, 1000);
    assert_int_equal(plan.drain_steps, 3000);
    // 2 pi R / 0.1 beads on the orifice edge (R = 2), all inside the 10 x 6 walls.
    assert_int_equal(plan.rim_beads, (size_t)ceil(2 * 3.14159265358979 * 2 / 0.1));
    // The same law everywhere: pair style and walls carry the [dem] keys.
    char in[1300];
    snprintf(in, sizeof in, "%s/in.fill", dir);
    char *text = gf_test_read_file(in, NULL);
    assert_non_null(text);
    assert_non_null(strstr(text, "pair_style gran/hertz/history 200000 57142.85714 50 25 0.5 1"));
    assert_non_null(strstr(text, "xplane -5 5"));
    free(text);

    // CI installs lammps (scripts/deps.sh): a machine without it fails here, loudly.
    gf_dem_run_opts ro = {.ranks = 1};
    gf_status st = gf_dem_run(dir, &ro);
    if (st != GF_OK) fail_msg("LAMMPS run failed: %s", gf_last_error());

    gf_series s;
    gf_dem_load_report rep;
    assert_int_equal(gf_dem_series_load(dir, NULL, &s, &rep), GF_OK);
    assert_int_equal(s.nframes, 4);
    for (size_t k = 0; k < 4; k++) gf_assert_near(s.frames[k].time, 0.1 * (double)k, 1e-9); // ITEM: TIME, in tau
    assert_false(rep.have_type);                                  // id x y z radius
    assert_true(s.cfg.container_width == 10 && s.cfg.orifice_diameter == 4); // from DIR/config.ini
    assert_int_equal(s.n_initial, 300);
    for (size_t k = 0; k < s.nframes; k++) {
        const gf_packing *p = &s.frames[k].pk;
        assert_true(p->n <= 300 && (k == 0 || p->n <= s.frames[k - 1].pk.n));
        for (size_t i = 0; i < p->n; i++) {
            // Centres inside the walls (a Hertzian overlap is far below 0.01 d) and above the base.
            assert_true(fabs(p->x[i]) <= 5 - 0.49 && fabs(p->y[i]) <= 3 - 0.49 && p->z[i] >= 0);
            assert_true(p->id[i] >= 1 && p->id[i] <= 300);
            gf_assert_near(p->r[i], 0.5, 1e-12);
        }
    }
    gf_series_free(&s);

    // The settled packing is a run's initial packing as it is.
    gf_config r = gf_config_default();
    snprintf(r.packing_file, sizeof r.packing_file, "%s/packing.dump", dir);
    snprintf(r.packing_types, sizeof r.packing_types, "1");
    gf_packing pk = {0};
    gf_packing_import_report ir;
    assert_int_equal(gf_packing_import(&r, &pk, &ir), GF_OK);
    assert_int_equal(pk.n, 300);
    assert_int_equal(ir.other_types + ir.below_base, 0);
    gf_packing_free(&pk);
}

// A hopper (cylinder, 60 degree funnel, outlet pipe, central column): the
// walls are one LAMMPS region (wall/gran/region), and the DEM particles stay
// inside the same container granflow's geometry describes.
static void lammps_hopper_walls_hold(void **state)
{
    (void)state;
    gf_config c = gf_config_default();
    c.container_shape = GF_SHAPE_CYLINDER;
    c.container_radius = 5;
    c.hopper_angle = 60;
    c.outlet_diameter = 4;
    c.outlet_length = 1;
    c.inner_radius = 1;
    c.packing_particles = 300;
    c.dem_fill_method = GF_DEM_GENERATE;
    c.dem_settle_time = 0.3;
    c.run_duration = 0.3;
    c.output_snapshot_interval = 0.1;
    char dir[900];
    snprintf(dir, sizeof dir, "%s", path_in("dem_hopper"));
    gf_dem_plan plan;
    assert_int_equal(gf_dem_write_inputs(&c, dir, NULL, &plan), GF_OK);
    char in[1300];
    snprintf(in, sizeof in, "%s/in.drain", dir);
    char *text = gf_test_read_file(in, NULL);
    assert_non_null(text);
    assert_non_null(strstr(text, "cone z 0 0 2 5 0 5.196152423 open 1 open 2")); // (5 - 2) tan 60
    assert_non_null(strstr(text, "side out"));
    assert_non_null(strstr(text, "wall/gran/region"));
    assert_null(strstr(text, "xplane"));
    free(text);
    gf_dem_run_opts ro = {.ranks = 1};
    if (gf_dem_run(dir, &ro) != GF_OK) fail_msg("LAMMPS run failed: %s", gf_last_error());
    gf_series s;
    gf_dem_load_report rep;
    assert_int_equal(gf_dem_series_load(dir, NULL, &s, &rep), GF_OK);
    assert_int_equal(s.nframes, 4);
    assert_true(s.cfg.container_shape == GF_SHAPE_CYLINDER && s.cfg.container_width == 10);
    gf_container box = gf_container_make(&s.cfg);
    for (size_t k = 0; k < s.nframes; k++) {
        const gf_packing *p = &s.frames[k].pk;
        assert_true(p->n > 250);
        for (size_t i = 0; i < p->n; i++)
            if (!gf_container_contains(&box, p->x[i], p->y[i], p->z[i], 0.49, 0.0))
                fail_msg("frame %zu: particle at (%g, %g, %g) is through a wall", k, p->x[i], p->y[i], p->z[i]);
    }
    gf_series_free(&s);
}

// ---- importing dumps ------------------------------------------------------------

static const char *wdump(const char *name, const char *text)
{
    return gf_test_write_file(gf_test_tmpdir(), name, text);
}

#define BOX "ITEM: BOX BOUNDS ff ff ff\n-5 5\n-3 3\n-2 20\n"

// Any column order; a DEM floor (type 2, below the base) and a particle
// falling through the orifice (type 1, z < 0) are dropped and counted.
static void import_types_and_below_base(void **state)
{
    (void)state;
    char f[900];
    snprintf(f, sizeof f, "%.800s", wdump("floor.dump", "ITEM: TIMESTEP\n100\nITEM: NUMBER OF ATOMS\n6\n" BOX
                                        "ITEM: ATOMS z type id y x\n"
                                        "0.5 1 1 0 0\n"
                                        "1.5 1 2 0.5 1\n"
                                        "-0.5 2 3 0 2\n"
                                        "-0.5 2 4 0 3\n"
                                        "-1.0 1 5 0 0.2\n"
                                        "2.5 1 6 1 -1\n"));
    gf_config c = gf_config_default();
    c.container_width = 10;
    c.container_depth = 6;
    c.orifice_diameter = 4;
    snprintf(c.packing_file, sizeof c.packing_file, "%s", f);
    snprintf(c.packing_types, sizeof c.packing_types, "1");
    gf_packing pk = {0};
    gf_packing_import_report rep;
    assert_int_equal(gf_packing_import(&c, &pk, &rep), GF_OK);
    assert_int_equal(rep.read, 6);
    assert_int_equal(rep.other_types, 2);
    assert_int_equal(rep.below_base, 1);
    assert_int_equal(pk.n, 3);
    // Columns found by name: id 2 has x = 1, y = 0.5, z = 1.5; layers by height.
    assert_int_equal(pk.id[1], 2);
    assert_true(pk.x[1] == 1 && pk.y[1] == 0.5 && pk.z[1] == 1.5);
    assert_int_equal(pk.layer[1], 1);
    gf_packing_free(&pk);
    // Without a type filter only the particles below the base go (the floor too).
    c.packing_types[0] = '\0';
    assert_int_equal(gf_packing_import(&c, &pk, &rep), GF_OK);
    assert_int_equal(pk.n, 3);
    assert_int_equal(rep.below_base, 3);
    gf_packing_free(&pk);
    // A type filter needs a type column.
    const char *nt = wdump("notype.dump", "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n1\n" BOX "ITEM: ATOMS id x y z\n1 0 0 1\n");
    snprintf(c.packing_file, sizeof c.packing_file, "%s", nt);
    snprintf(c.packing_types, sizeof c.packing_types, "1,2");
    assert_int_equal(gf_packing_import(&c, &pk, &rep), GF_ERR_PARAM);
    assert_non_null(strstr(gf_last_error(), "no `type` column"));
    // Nothing left is an error naming the counts.
    snprintf(c.packing_file, sizeof c.packing_file, "%s", f);
    snprintf(c.packing_types, sizeof c.packing_types, "7");
    assert_int_equal(gf_packing_import(&c, &pk, &rep), GF_ERR_PARAM);
    if (!strstr(gf_last_error(), "no particle left of 6")) fail_msg("%s", gf_last_error());
}

// One packing for a config, whoever asks (gf_packing_for_config): a run's
// first snapshot and the DEM inputs' fill.data hold the same particles of a
// dump filtered by packing.types (a floor of type 2 and a type-1 particle
// below the base dropped), at the same places.
static void run_and_dem_get_the_same_packing(void **state)
{
    (void)state;
    char text[16384];
    int len = snprintf(text, sizeof text, "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n%d\n" BOX "ITEM: ATOMS id type x y z\n",
                       60 + 8 + 1);
    int id = 1;
    for (int iz = 0; iz < 4; iz++)
        for (int iy = -1; iy <= 1; iy++)
            for (int ix = -2; ix <= 2; ix++)
                len += snprintf(text + len, sizeof text - (size_t)len, "%d 1 %g %g %g\n", id++, 1.01 * ix + 0.003 * iz,
                                1.01 * iy, 0.5 + 1.01 * iz);
    for (int k = 0; k < 8; k++) len += snprintf(text + len, sizeof text - (size_t)len, "%d 2 %d 2 -0.5\n", id++, k - 4);
    snprintf(text + len, sizeof text - (size_t)len, "%d 1 0 0 -1.5\n", id++);
    gf_config c = gf_config_default();
    c.container_width = 10;
    c.container_depth = 6;
    c.orifice_diameter = 4;
    c.run_duration = 0.5;
    c.dem_fill_method = GF_DEM_GENERATE;
    snprintf(c.packing_file, sizeof c.packing_file, "%s", wdump("typed.dump", text));
    snprintf(c.packing_types, sizeof c.packing_types, "1");
    gf_packing ref = {0}, snap = {0};
    gf_packing_import_report rep;
    assert_int_equal(gf_packing_for_config(&c, NULL, &ref, &rep), GF_OK);
    assert_int_equal(ref.n, 60);
    assert_int_equal(rep.other_types, 8);
    assert_int_equal(rep.below_base, 1);

    char dir[900], path[1000];
    snprintf(dir, sizeof dir, "%s", path_in("typed_run"));
    gf_run_opts ro = gf_run_opts_default();
    ro.dir = dir;
    assert_int_equal(gf_run_dir(&c, &ro, NULL), GF_OK);
    snprintf(path, sizeof path, "%s/snapshots/snap_000000.dump", dir);
    assert_int_equal(gf_packing_read(path, GF_FORMAT_LAMMPS, &snap), GF_OK);
    assert_int_equal(snap.n, ref.n);
    for (size_t k = 0; k < ref.n; k++) {
        size_t j = 0;
        while (j < snap.n && snap.id[j] != ref.id[k]) j++;
        assert_true(j < snap.n);
        assert_true(fabs(snap.x[j] - ref.x[k]) < 1e-9 && fabs(snap.y[j] - ref.y[k]) < 1e-9 &&
                    fabs(snap.z[j] - ref.z[k]) < 1e-9);
    }

    snprintf(dir, sizeof dir, "%s", path_in("typed_dem"));
    gf_dem_plan plan;
    assert_int_equal(gf_dem_write_inputs(&c, dir, NULL, &plan), GF_OK);
    assert_int_equal(plan.particles, 60);
    snprintf(path, sizeof path, "%s/fill.data", dir);
    FILE *f = fopen(path, "r");
    assert_non_null(f);
    char line[512];
    while (fgets(line, sizeof line, f) && strncmp(line, "Atoms", 5) != 0) {}
    size_t k = 0;
    while (fgets(line, sizeof line, f)) {
        long n, type;
        double diam, rho, x, y, z;
        if (sscanf(line, "%ld %ld %lf %lf %lf %lf %lf", &n, &type, &diam, &rho, &x, &y, &z) != 7) continue;
        assert_true(k < ref.n);
        assert_int_equal(n, (long)k + 1);
        assert_true(fabs(x - ref.x[k]) < 1e-9 && fabs(y - ref.y[k]) < 1e-9 && fabs(z - ref.z[k]) < 1e-9);
        k++;
    }
    fclose(f);
    assert_int_equal(k, ref.n);
    gf_packing_free(&ref);
    gf_packing_free(&snap);
}

static void types_parse(void **state)
{
    (void)state;
    int32_t t[GF_PACKING_MAXTYPES];
    size_t n;
    assert_int_equal(gf_packing_types_parse("", t, GF_PACKING_MAXTYPES, &n), GF_OK);
    assert_int_equal(n, 0);
    assert_int_equal(gf_packing_types_parse(" 1, 3 4", t, GF_PACKING_MAXTYPES, &n), GF_OK);
    assert_int_equal(n, 3);
    assert_true(t[0] == 1 && t[1] == 3 && t[2] == 4);
    assert_int_equal(gf_packing_types_parse("1,x", t, GF_PACKING_MAXTYPES, &n), GF_ERR_PARAM);
    assert_non_null(strstr(gf_last_error(), "'x' is not an atom type"));
    assert_int_equal(gf_packing_types_parse("0", t, GF_PACKING_MAXTYPES, &n), GF_ERR_PARAM);
    assert_int_equal(gf_packing_types_parse("-1", t, GF_PACKING_MAXTYPES, &n), GF_ERR_PARAM);
    assert_int_equal(gf_packing_types_parse("1 2 3", t, 2, &n), GF_ERR_PARAM);
    // The config rejects a bad list, naming the key.
    gf_config c = gf_config_default();
    assert_int_equal(gf_config_set(&c, "packing.types=1,2.5", "--set"), GF_OK);
    assert_int_equal(gf_config_validate(&c), GF_ERR_PARAM);
    assert_non_null(strstr(gf_last_error(), "packing.types"));
    // dem.timestep is checked against the contact time of dem.kn.
    c = gf_config_default();
    assert_int_equal(gf_config_set(&c, "dem.timestep=0.005", "--set"), GF_OK);
    assert_int_equal(gf_config_validate(&c), GF_ERR_PARAM);
    assert_non_null(strstr(gf_last_error(), "dem.timestep"));
    c = gf_config_default();
    assert_int_equal(gf_config_validate(&c), GF_OK);
    gf_assert_near(c.dem_kt, 2.0 / 7.0 * 200000, 1e-9); // auto
    gf_assert_near(c.dem_gammat, 25, 1e-12);
}

// A multi-frame dump with scaled coordinates and TIMESTEP only: --timestep
// gives the times; the type filter and the particles below the base apply to
// every frame; the layers are tagged by the first frame's heights; the
// particle gone below the base is an exit read off the frames.
static void series_scaled_steps_types(void **state)
{
    (void)state;
    // Box x -5..5, y -3..3, z -2..20: xs = (x + 5) / 10, zs = (z + 2) / 22.
    const char *f = wdump("multi.dump",
                          "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n3\n" BOX "ITEM: ATOMS id type xs ys zs\n"
                          "1 1 0.5 0.5 0.5\n"     // (0, 0, 9)
                          "2 1 0.6 0.5 0.95\n"    // (1, 0, 18.9)
                          "3 2 0.7 0.5 0.0681818\n" // floor, z = -0.5
                          "ITEM: TIMESTEP\n20000\nITEM: NUMBER OF ATOMS\n3\n" BOX "ITEM: ATOMS id type xs ys zs\n"
                          "1 1 0.5 0.5 0.0454545\n" // z = -1: exited
                          "2 1 0.6 0.5 0.5\n"
                          "3 2 0.7 0.5 0.0681818\n");
    gf_series s;
    // Without a time step the frames cannot be placed in time.
    assert_int_equal(gf_dem_series_load(f, NULL, &s, NULL), GF_ERR_PARAM);
    assert_non_null(strstr(gf_last_error(), "dump.dt"));
    // Two particles span 3 d: the walls (the box's here) are given.
    const char *sets[] = {"packing.types=1", "container.orifice_diameter=4", "container.width=10",
                          "container.depth=6"};
    gf_dem_source src = {.dump_dt = 1e-4, .sets = sets, .nsets = 4};
    gf_dem_load_report rep;
    assert_int_equal(gf_dem_series_load(f, &src, &s, &rep), GF_OK);
    assert_true(rep.have_type);
    assert_int_equal(rep.other_types, 2);
    assert_int_equal(rep.below_base, 1);
    assert_int_equal(s.nframes, 2);
    gf_assert_near(s.frames[1].time, 2.0, 1e-12); // 20000 steps of 1e-4 tau
    assert_true(s.cfg.container_width == 10 && s.cfg.orifice_diameter == 4);
    assert_int_equal(s.n_initial, 2);
    assert_int_equal(s.frames[1].pk.n, 1);
    gf_assert_near(s.frames[0].pk.z[1], 18.9, 1e-5);
    // Layers: 1 + floor(z0 / 10) of the first frame, carried by id (not the type).
    assert_int_equal(s.frames[0].pk.layer[0], 1);
    assert_int_equal(s.frames[0].pk.layer[1], 2);
    assert_int_equal(s.frames[1].pk.layer[0], 2);
    // No exits.csv: particle 1, below the base in the second frame, exited
    // between the two, at the midpoint t = 1 (+- 1 tau), where it was in the first.
    assert_true(s.has_exits && s.exits_derived);
    assert_int_equal(s.nexits, 1);
    assert_true(s.exits[0].id == 1 && s.exits[0].time == 1.0 && s.exits[0].x == 0.0 && s.exits[0].pass == 1);
    gf_assert_near(s.exit_resolution, 1.0, 1e-12);
    // The same dump gzipped: the same series, bit for bit (the type column
    // is found through the compression too).
    char gz[1024];
    snprintf(gz, sizeof gz, "%s.gz", f);
    assert_true(gf_test_gzip(f, gz, 0) > 0);
    gf_series g;
    gf_dem_load_report grep2;
    assert_int_equal(gf_dem_series_load(gz, &src, &g, &grep2), GF_OK);
    assert_int_equal(grep2.other_types, rep.other_types);
    assert_int_equal(grep2.below_base, rep.below_base);
    assert_int_equal(g.nframes, s.nframes);
    for (size_t k = 0; k < s.nframes; k++) {
        assert_true(g.frames[k].time == s.frames[k].time);
        assert_int_equal(g.frames[k].pk.n, s.frames[k].pk.n);
        assert_memory_equal(g.frames[k].pk.z, s.frames[k].pk.z, s.frames[k].pk.n * sizeof(double));
        assert_memory_equal(g.frames[k].pk.layer, s.frames[k].pk.layer, s.frames[k].pk.n * sizeof *s.frames[k].pk.layer);
    }
    gf_series_free(&g);
    gf_series_free(&s);
    // ITEM: TIME wins over the step count when present.
    const char *t = wdump("timed.dump", "ITEM: TIME\n0.5\nITEM: TIMESTEP\n5000\nITEM: NUMBER OF ATOMS\n1\n" BOX
                                        "ITEM: ATOMS id x y z\n1 0 0 3\n");
    assert_int_equal(gf_dem_series_load(t, &src, &s, NULL), GF_ERR_PARAM); // types need a type column
    src.nsets = 3; // the orifice and the walls, without packing.types
    src.sets = sets + 1;
    assert_int_equal(gf_dem_series_load(t, &src, &s, NULL), GF_OK);
    gf_assert_near(s.frames[0].time, 0.5, 1e-12);
    gf_series_free(&s);
}

static void truncated_dump_is_an_error(void **state)
{
    (void)state;
    const char *f = wdump("cut.dump", "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n3\n" BOX "ITEM: ATOMS id x y z\n"
                                      "1 0 0 1\n2 1 0 1\n");
    gf_series s;
    gf_dem_source src = {.dump_dt = 1e-4};
    gf_status st = gf_dem_series_load(f, &src, &s, NULL);
    assert_int_equal(st, GF_ERR_FORMAT);
    assert_non_null(strstr(gf_last_error(), "cut.dump"));
    gf_config c = gf_config_default();
    snprintf(c.packing_file, sizeof c.packing_file, "%s", f);
    gf_packing pk = {0};
    assert_int_equal(gf_packing_import(&c, &pk, NULL), GF_ERR_FORMAT);
    assert_non_null(strstr(gf_last_error(), "cut.dump"));
}

// The dumps' `type` column read, the layers are tagged again by height and
// carried by id; a particle not in the first frame gets its own height's tag,
// clamped (1e300 overflowed an int32 cast; found by fuzz_series_load.c).
static void dem_far_new_particle_layer(void **state)
{
    (void)state;
    const char *f = wdump("far.dump", "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n1\n" BOX "ITEM: ATOMS id type x y z\n"
                                      "1 1 0 0 10\nITEM: TIMESTEP\n1\nITEM: NUMBER OF ATOMS\n1\n" BOX
                                      "ITEM: ATOMS id type x y z\n2 1 0 0 1e300\n");
    gf_series s;
    const char *sets[] = {"container.width=10", "container.depth=6"}; // one particle's extent is no silo
    gf_dem_source src = {.dump_dt = 0.5, .sets = sets, .nsets = 2};
    assert_int_equal(gf_dem_series_load(f, &src, &s, NULL), GF_OK);
    assert_int_equal(s.nframes, 2);
    assert_int_equal(s.frames[1].pk.n, 1);
    assert_int_equal(s.frames[1].pk.layer[0], 1 + 1000000000);
    gf_series_free(&s);
}

static void lammps_output_progress(void *ctx, const gf_dem_progress *p) { *(gf_dem_progress *)ctx = *p; }

// LAMMPS' output as gf_dem_run reads it: phases, thermo lines, and counts far
// beyond int64 (or not numbers) clamped rather than converted (undefined;
// found by tests/fuzz/fuzz_lammps_output.c).
static void lammps_output_lines(void **state)
{
    (void)state;
    gf_dem_progress last = {0};
    gf_dem_run_opts o = {.ranks = 1, .progress = lammps_output_progress, .ctx = &last};
    gf_dem_reader r = {.o = &o, .t_phase = NAN};
    char l1[] = "granflow-phase fill 4000 20\n", l2[] = "0 10 0 0", l3[] = "1000 11.5 1200 0.25\r\n";
    gf_dem_line(&r, l1);
    assert_int_equal(last.phase, GF_DEM_PHASE_FILL);
    assert_string_equal(gf_dem_phase_name(last.phase), "fill");
    assert_int_equal(last.target, 4000);
    gf_dem_line(&r, l2);
    gf_dem_line(&r, l3);
    gf_assert_near(last.time, 1.5, 1e-12); // from the phase's first thermo line
    assert_int_equal(last.particles, 1200);
    char l4[] = "2000 12 1e300 0", l5[] = "granflow-phase drain 1e30 100", l6[] = "3000 13 nan 0";
    gf_dem_line(&r, l4);
    assert_int_equal(last.particles, INT64_C(1) << 62);
    gf_dem_line(&r, l5);
    assert_int_equal(last.phase, GF_DEM_PHASE_DRAIN);
    assert_string_equal(gf_dem_phase_name(last.phase), "drain");
    assert_int_equal(last.target, INT64_C(1) << 62);
    gf_dem_line(&r, l6);
    assert_int_equal(last.particles, 0);
    char l7[] = "ERROR: Lost atoms (src/thermo.cpp:488)\n";
    gf_dem_line(&r, l7);
    assert_string_equal(r.error, "ERROR: Lost atoms (src/thermo.cpp:488)");
    // "settled" ends the settle phase: still settle (one phase, not a new one).
    char l8[] = "granflow-phase settle 0 50", l9[] = "granflow-phase settled 3000 0.001";
    gf_dem_line(&r, l8);
    assert_int_equal(last.phase, GF_DEM_PHASE_SETTLE);
    gf_dem_line(&r, l9);
    assert_int_equal(last.phase, GF_DEM_PHASE_SETTLE);
    assert_string_equal(gf_dem_phase_name(GF_DEM_PHASE_DONE), "done");
    assert_string_equal(gf_dem_phase_name((gf_dem_phase)99), "?");
}

// What granflow dem --continue reads: a restart file's probe line, and the
// continued drain's marker, after which the thermo times are the drain's
// own (step * dt from its start), not from the continuation's start.
static void lammps_output_continue(void **state)
{
    (void)state;
    gf_dem_progress last = {0};
    gf_dem_run_opts o = {.ranks = 1, .progress = lammps_output_progress, .ctx = &last};
    gf_dem_reader r = {.o = &o, .t_phase = NAN, .restart_step = -1};
    char l1[] = "granflow-restart 150000 0.0001\n", l2[] = "granflow-phase continue 590 40\n",
         l3[] = "150000 15 590 0.02";
    gf_dem_line(&r, l1);
    assert_int_equal(r.restart_step, 150000);
    gf_assert_near(r.restart_dt, 1e-4, 1e-18);
    gf_dem_line(&r, l2);
    assert_int_equal(last.phase, GF_DEM_PHASE_DRAIN);
    assert_int_equal(last.target, 590);
    gf_assert_near(last.until, 40.0, 1e-12);
    gf_dem_line(&r, l3);
    gf_assert_near(last.time, 15.0, 1e-12);
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(lammps_run_gives_readable_dumps),
    cmocka_unit_test(lammps_hopper_walls_hold),
    cmocka_unit_test(import_types_and_below_base),
    cmocka_unit_test(run_and_dem_get_the_same_packing),
    cmocka_unit_test(types_parse),
    cmocka_unit_test(series_scaled_steps_types),
    cmocka_unit_test(truncated_dump_is_an_error),
    cmocka_unit_test(lammps_output_lines),
    cmocka_unit_test(lammps_output_continue),
    cmocka_unit_test(dem_far_new_particle_layer),
};

GF_TEST_MAIN("dem", tests)
