// SPDX-License-Identifier: MIT
// Reading and writing packings (SPEC 1.2 import): LAMMPS text dumps in any
// column order, XYZ, CSV; error messages naming file and line; round trips.
#include "support.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include "granflow/packing.h"

#define DATA(name) GF_TEST_DATA "/" name

// ---------------------------------------------------------------------------
// helpers

static void expect_contains(const char *text, const char *needle)
{
    if (!strstr(text, needle)) {
        print_error("message \"%s\" does not contain \"%s\"\n", text, needle);
        fail();
    }
}

/// Reads `path` expecting failure `want`; the message must name `file` and,
/// when line > 0, contain ":<line>:"; and `phrase` when not NULL. A packing
/// holding data beforehand must come back empty.
static void expect_error(const char *path, gf_packing_format fmt, gf_status want, const char *file,
                         long line, const char *phrase)
{
    gf_packing p = {0};
    assert_int_equal(gf_packing_push(&p, 99, 1, 1.0, 2.0, 3.0, 0.5), GF_OK);
    gf_status st = gf_packing_read(path, fmt, &p);
    if (st != want)
        print_error("status %d (%s), message \"%s\"\n", (int)st, gf_status_str(st),
                    gf_last_error());
    assert_int_equal(st, want);
    assert_int_equal(p.n, 0);
    assert_null(p.x);
    assert_null(p.id);
    const char *msg = gf_last_error();
    expect_contains(msg, file);
    if (line > 0) {
        char tag[32];
        snprintf(tag, sizeof tag, ":%ld:", line);
        expect_contains(msg, tag);
    }
    if (phrase) expect_contains(msg, phrase);
}

/// Writes `text` into the test's temporary directory as `name` and returns its path.
static const char *tmpfile_with(const char *name, const char *text)
{
    return gf_test_write_file(gf_test_tmpdir(), name, text);
}

static const char *tmppath(const char *name)
{
    static char path[1024];
    snprintf(path, sizeof path, "%s/%s", gf_test_tmpdir(), name);
    return path;
}

/// Index of particle `id`, failing the test when it is absent.
static size_t find_id(const gf_packing *p, int64_t id)
{
    for (size_t i = 0; i < p->n; i++)
        if (p->id[i] == id) return i;
    print_error("id %lld not found\n", (long long)id);
    fail();
    return 0;
}

static void expect_particle(const gf_packing *p, int64_t id, double x, double y, double z, double r)
{
    size_t i = find_id(p, id);
    gf_assert_near(p->x[i], x, 1e-12);
    gf_assert_near(p->y[i], y, 1e-12);
    gf_assert_near(p->z[i], z, 1e-12);
    gf_assert_near(p->r[i], r, 1e-12);
    assert_int_equal(p->layer[i], 0);
}

/// Deterministic uniform numbers in [0, 1) (splitmix64), for random packings.
static double uniform(uint64_t *s)
{
    uint64_t z = (*s += 0x9E3779B97F4A7C15u);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9u;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBu;
    z ^= z >> 31;
    return (double)(z >> 11) * 0x1.0p-53;
}

/// n random particles in the papers' silo, ids shuffled (not 1..n) unless `seq_ids`.
static void random_packing(gf_packing *p, size_t n, uint64_t seed, int seq_ids, int same_radius)
{
    uint64_t s = seed;
    for (size_t i = 0; i < n; i++) {
        double x = -24.5 + 49.0 * uniform(&s);
        double y = -3.5 + 7.0 * uniform(&s);
        double z = 0.5 + 120.0 * uniform(&s);
        double r = same_radius ? 0.5 : 0.4 + 0.2 * uniform(&s);
        int64_t id = seq_ids ? (int64_t)i + 1 : (int64_t)(7 * (n - i)) + 3;
        assert_int_equal(gf_packing_push(p, id, (int32_t)(i % 5) - 1, x, y, z, r), GF_OK);
    }
}

static void rel_near(double a, double b)
{
    double tol = 1e-9 * (fabs(b) > 1.0 ? fabs(b) : 1.0);
    gf_assert_near(a, b, tol);
}

static void expect_same(const gf_packing *a, const gf_packing *b, int check_ids, int check_radii)
{
    assert_int_equal(a->n, b->n);
    for (size_t i = 0; i < a->n; i++) {
        if (check_ids)
            assert_int_equal(a->id[i], b->id[i]);
        else
            assert_int_equal(b->id[i], (int64_t)i + 1);
        rel_near(b->x[i], a->x[i]);
        rel_near(b->y[i], a->y[i]);
        rel_near(b->z[i], a->z[i]);
        if (check_radii)
            rel_near(b->r[i], a->r[i]);
        else
            assert_true(b->r[i] == 0.5);
    }
}

// ---------------------------------------------------------------------------
// LAMMPS dumps that must be read

static void lammps_id_type_xyz(void **state)
{
    (void)state;
    gf_packing p = {0};
    assert_int_equal(gf_packing_read(DATA("id_type_xyz.dump"), GF_FORMAT_AUTO, &p), GF_OK);
    assert_int_equal(p.n, 3);
    assert_int_equal(p.id[0], 7); // file order is kept
    assert_int_equal(p.id[1], 3);
    assert_int_equal(p.id[2], 12);
    expect_particle(&p, 7, -1.5, 0.25, 0.5, 0.5);
    expect_particle(&p, 3, 2.0, -3.5, 1.5, 0.5);
    expect_particle(&p, 12, 24.5, 3.5, 59.5, 0.5);
    gf_packing_free(&p);
}

static void lammps_xyz_id_type_radius_crlf(void **state)
{
    (void)state;
    gf_packing p = {0};
    assert_int_equal(gf_packing_read(DATA("xyz_id_type_radius_crlf.dump"), GF_FORMAT_LAMMPS, &p),
                     GF_OK);
    assert_int_equal(p.n, 3);
    expect_particle(&p, 7, -1.5, 0.25, 0.5, 0.5);
    expect_particle(&p, 3, 2.0, -3.5, 1.5, 0.45);
    expect_particle(&p, 12, 24.5, 3.5, 59.5, 0.55);
    gf_packing_free(&p);
}

static void lammps_scaled_coordinates(void **state)
{
    (void)state;
    gf_packing p = {0};
    assert_int_equal(gf_packing_read(DATA("scaled.dump"), GF_FORMAT_AUTO, &p), GF_OK);
    assert_int_equal(p.n, 2);
    // box x -25..25, y -4..4, z 0..40
    expect_particle(&p, 1, 0.0, 0.0, 0.5, 0.5);
    expect_particle(&p, 2, -12.5, 2.0, 20.0, 0.5);
    gf_packing_free(&p);
}

static void lammps_unwrapped_coordinates(void **state)
{
    (void)state;
    const char *path =
        tmpfile_with("unwrapped.dump", "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n1\n"
                                       "ITEM: BOX BOUNDS pp pp ff\n0 1\n0 1\n0 1\n"
                                       "ITEM: ATOMS id zu yu xu\n5 3.0 2.0 1.0\n");
    gf_packing p = {0};
    assert_int_equal(gf_packing_read(path, GF_FORMAT_AUTO, &p), GF_OK);
    assert_int_equal(p.n, 1);
    expect_particle(&p, 5, 1.0, 2.0, 3.0, 0.5);
    gf_packing_free(&p);
}

static void lammps_time_before_timestep(void **state)
{
    (void)state;
    gf_packing p = {0};
    assert_int_equal(gf_packing_read(DATA("time_first.dump"), GF_FORMAT_AUTO, &p), GF_OK);
    assert_int_equal(p.n, 2);
    expect_particle(&p, 1, 1.0, 2.0, 2.5, 0.5); // second (last) frame
    expect_particle(&p, 2, 4.0, -2.0, 5.5, 0.5);
    gf_packing_free(&p);
}

static void lammps_multiframe_takes_last(void **state)
{
    (void)state;
    gf_packing p = {0};
    assert_int_equal(gf_packing_read(DATA("multiframe.dump"), GF_FORMAT_AUTO, &p), GF_OK);
    assert_int_equal(p.n, 3);
    assert_int_equal(p.id[0], 4);
    expect_particle(&p, 4, 3.0, 0.0, 0.75, 0.5);
    expect_particle(&p, 2, 1.0, 0.0, 0.5, 0.5);
    expect_particle(&p, 3, 2.0, 0.0, 0.625, 0.5);
    gf_packing_free(&p);
}

static void lammps_diameter_column(void **state)
{
    (void)state;
    gf_packing p = {0};
    assert_int_equal(gf_packing_read(DATA("diameter.dump"), GF_FORMAT_AUTO, &p), GF_OK);
    assert_int_equal(p.n, 2);
    expect_particle(&p, 1, 0.0, 0.0, 0.5, 0.5);
    expect_particle(&p, 2, 1.0, 0.0, 0.4, 0.4);
    gf_packing_free(&p);
}

static void lammps_without_ids_numbers_in_order(void **state)
{
    (void)state;
    gf_packing p = {0};
    assert_int_equal(gf_packing_read(DATA("noid.dump"), GF_FORMAT_AUTO, &p), GF_OK);
    assert_int_equal(p.n, 3);
    for (size_t i = 0; i < 3; i++) {
        assert_int_equal(p.id[i], (int64_t)i + 1);
        gf_assert_near(p.x[i], (double)i, 0.0);
    }
    gf_packing_free(&p);
}

static void read_replaces_previous_content(void **state)
{
    (void)state;
    gf_packing p = {0};
    random_packing(&p, 100, 5, 0, 0);
    assert_int_equal(gf_packing_read(DATA("noid.dump"), GF_FORMAT_AUTO, &p), GF_OK);
    assert_int_equal(p.n, 3);
    assert_int_equal(p.id[2], 3);
    gf_packing_free(&p);
}

// ---------------------------------------------------------------------------
// XYZ and CSV that must be read

static void xyz_reads(void **state)
{
    (void)state;
    gf_packing p = {0};
    assert_int_equal(gf_packing_read(DATA("packing.xyz"), GF_FORMAT_AUTO, &p), GF_OK);
    assert_int_equal(p.n, 3);
    for (size_t i = 0; i < 3; i++) assert_int_equal(p.id[i], (int64_t)i + 1);
    expect_particle(&p, 1, 0.0, 0.0, 0.5, 0.5);
    expect_particle(&p, 2, 1.0, -1.0, 0.5, 0.5); // the extra column is ignored
    expect_particle(&p, 3, 2.5, 1.25, 1.5, 0.5);
    gf_packing_free(&p);
}

static void csv_extra_columns_any_order(void **state)
{
    (void)state;
    gf_packing p = {0};
    assert_int_equal(gf_packing_read(DATA("extra_columns.csv"), GF_FORMAT_AUTO, &p), GF_OK);
    assert_int_equal(p.n, 3);
    expect_particle(&p, 10, -2.0, 1.0, 0.5, 0.5);
    expect_particle(&p, 20, 2.0, -1.0, 1.5, 0.45);
    expect_particle(&p, 30, 0.0, 0.0, 2.5, 0.5);
    gf_packing_free(&p);
}

static void csv_without_ids(void **state)
{
    (void)state;
    gf_packing p = {0};
    assert_int_equal(gf_packing_read(DATA("noid.csv"), GF_FORMAT_AUTO, &p), GF_OK);
    assert_int_equal(p.n, 2);
    expect_particle(&p, 1, 0.0, 0.0, 0.5, 0.5);
    expect_particle(&p, 2, 1.0, 0.0, 0.5, 0.5);
    gf_packing_free(&p);
}

static void csv_diameter_alias(void **state)
{
    (void)state;
    const char *path = tmpfile_with("alias.csv", "D,z,y,x\n0.9,1,2,3\n");
    gf_packing p = {0};
    assert_int_equal(gf_packing_read(path, GF_FORMAT_AUTO, &p), GF_OK);
    expect_particle(&p, 1, 3.0, 2.0, 1.0, 0.45);
    gf_packing_free(&p);
}

// ---------------------------------------------------------------------------
// errors: status, file name and line in the message, `out` left empty

static const char frame1[] = // lines 1-11
    "ITEM: TIMESTEP\n1000\nITEM: NUMBER OF ATOMS\n2\nITEM: BOX BOUNDS ff ff ff\n-25 25\n-4 4\n0 "
    "60\n"
    "ITEM: ATOMS id type x y z\n1 1 0 0 1\n2 1 1 0 1\n";

static void error_truncated_last_frame(void **state)
{
    (void)state;
    char text[1024];
    snprintf(text, sizeof text, "%s%s", frame1,
             "ITEM: TIMESTEP\n5000\nITEM: NUMBER OF ATOMS\n3\nITEM: BOX BOUNDS ff ff ff\n-25 "
             "25\n-4 4\n0 60\n"
             "ITEM: ATOMS id type x y z\n1 1 0 0 0.5\n");
    const char *path = tmpfile_with("cut_frame.dump", text);
    expect_error(path, GF_FORMAT_AUTO, GF_ERR_FORMAT, "cut_frame.dump", 21,
                 "frame at timestep 5000 ends after 1 of 3 atoms (truncated file?)");
}

static void error_truncated_frame_cut_by_next(void **state)
{
    (void)state;
    // first frame announces 3 atoms but only 2 follow before the next ITEM:
    const char *path =
        tmpfile_with("short_first.dump",
                     "ITEM: TIMESTEP\n10\nITEM: NUMBER OF ATOMS\n3\nITEM: BOX BOUNDS ff ff ff\n"
                     "-1 1\n-1 1\n0 2\nITEM: ATOMS id x y z\n1 0 0 1\n2 0 0 1\n"
                     "ITEM: TIMESTEP\n20\n");
    expect_error(path, GF_FORMAT_AUTO, GF_ERR_FORMAT, "short_first.dump", 12,
                 "timestep 10 ends after 2 of 3 atoms");
}

static void error_truncated_header(void **state)
{
    (void)state;
    char text[1024];
    snprintf(text, sizeof text, "%s%s", frame1, "ITEM: TIMESTEP\n2000\nITEM: NUMBER OF ATOMS\n2\n");
    const char *path = tmpfile_with("cut_header.dump", text);
    expect_error(path, GF_FORMAT_AUTO, GF_ERR_FORMAT, "cut_header.dump", 15,
                 "header of the frame at timestep 2000");

    snprintf(text, sizeof text, "%s%s", frame1,
             "ITEM: TIMESTEP\n2000\nITEM: NUMBER OF ATOMS\n2\nITEM: BOX BOUNDS ff ff ff\n-25 25\n");
    path = tmpfile_with("cut_box.dump", text);
    expect_error(path, GF_FORMAT_AUTO, GF_ERR_FORMAT, "cut_box.dump", 17, "BOX BOUNDS");

    path = tmpfile_with("cut_value.dump", "ITEM: TIMESTEP\n");
    expect_error(path, GF_FORMAT_AUTO, GF_ERR_FORMAT, "cut_value.dump", 1, "truncated");
}

static void error_missing_section(void **state)
{
    (void)state;
    const char *path =
        tmpfile_with("no_count.dump", "ITEM: TIMESTEP\n0\nITEM: BOX BOUNDS ff ff ff\n"
                                      "0 1\n0 1\n0 1\nITEM: ATOMS id x y z\n1 0 0 0\n");
    expect_error(path, GF_FORMAT_AUTO, GF_ERR_FORMAT, "no_count.dump", 7, "NUMBER OF ATOMS");
}

static void error_bad_number(void **state)
{
    (void)state;
    const char *path =
        tmpfile_with("bad_number.dump",
                     "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n2\nITEM: BOX BOUNDS ff ff ff\n"
                     "0 1\n0 1\n0 1\nITEM: ATOMS id type x y z\n1 1 0 0 0.5\n2 1 0 0 abc\n");
    expect_error(path, GF_FORMAT_AUTO, GF_ERR_FORMAT, "bad_number.dump", 11,
                 "column 'z': 'abc' is not a number");
    path = tmpfile_with("bad_csv.csv", "x,y,z\n1,2,3\n1,2x,3\n");
    expect_error(path, GF_FORMAT_AUTO, GF_ERR_FORMAT, "bad_csv.csv", 3,
                 "column 'y': '2x' is not a number");
    path = tmpfile_with("bad_xyz.xyz", "1\n\nC 0 nan 1\n");
    expect_error(path, GF_FORMAT_AUTO, GF_ERR_FORMAT, "bad_xyz.xyz", 3, "column 'y'");
}

static void error_wrong_column_count(void **state)
{
    (void)state;
    const char *path = tmpfile_with(
        "columns.dump", "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n2\nITEM: BOX BOUNDS ff ff ff\n"
                        "0 1\n0 1\n0 1\nITEM: ATOMS id type x y z\n1 1 0 0 0.5\n2 1 0 0 0.5 9\n");
    expect_error(path, GF_FORMAT_AUTO, GF_ERR_FORMAT, "columns.dump", 11, "6 columns");
    path = tmpfile_with("cut_line.csv", "x,y,z\n1,2,3\n1,2");
    expect_error(path, GF_FORMAT_AUTO, GF_ERR_FORMAT, "cut_line.csv", 3, "truncated");
    path = tmpfile_with("columns.csv", "x,y,z\n1,2,3\n1,2\n");
    expect_error(path, GF_FORMAT_AUTO, GF_ERR_FORMAT, "columns.csv", 3, "2 fields");
}

static void error_too_many_atom_lines(void **state)
{
    (void)state;
    const char *path =
        tmpfile_with("extra_line.dump",
                     "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n1\nITEM: BOX BOUNDS ff ff ff\n"
                     "0 1\n0 1\n0 1\nITEM: ATOMS id type x y z\n1 1 0 0 0.5\n2 1 0 0 0.5\n");
    expect_error(path, GF_FORMAT_AUTO, GF_ERR_FORMAT, "extra_line.dump", 11, "NUMBER OF ATOMS");
}

static void error_duplicate_id(void **state)
{
    (void)state;
    const char *path = tmpfile_with(
        "dup.dump", "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n3\nITEM: BOX BOUNDS ff ff ff\n"
                    "0 1\n0 1\n0 1\nITEM: ATOMS id type x y z\n4 1 0 0 0.5\n5 1 0 0 1.5\n"
                    "4 1 0 0 2.5\n");
    expect_error(path, GF_FORMAT_AUTO, GF_ERR_FORMAT, "dup.dump", 12,
                 "duplicate id 4 (already on line 10)");
    path = tmpfile_with("zero_id.csv", "id,x,y,z\n0,1,2,3\n");
    expect_error(path, GF_FORMAT_AUTO, GF_ERR_FORMAT, "zero_id.csv", 2, "not positive");
}

static void error_missing_z_column(void **state)
{
    (void)state;
    const char *path = tmpfile_with(
        "no_z.dump", "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n1\nITEM: BOX BOUNDS ff ff ff\n"
                     "0 1\n0 1\n0 1\nITEM: ATOMS id type x y vz\n1 1 0 0 0.5\n");
    expect_error(path, GF_FORMAT_AUTO, GF_ERR_FORMAT, "no_z.dump", 9, "found: id type x y vz");
}

static void error_scaled_without_box(void **state)
{
    (void)state;
    const char *path = tmpfile_with("no_box.dump", "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n1\n"
                                                   "ITEM: ATOMS id xs ys zs\n1 0.5 0.5 0.5\n");
    expect_error(path, GF_FORMAT_AUTO, GF_ERR_FORMAT, "no_box.dump", 5, "BOX BOUNDS");
}

static void error_missing_file(void **state)
{
    (void)state;
    expect_error(tmppath("does_not_exist.dump"), GF_FORMAT_AUTO, GF_ERR_IO, "does_not_exist.dump",
                 0, "No such file");
}

static void error_empty_file(void **state)
{
    (void)state;
    expect_error(tmpfile_with("empty.dump", ""), GF_FORMAT_AUTO, GF_ERR_FORMAT, "empty.dump", 0,
                 "no particles in file");
    expect_error(tmpfile_with("blank.xyz", "\n\n"), GF_FORMAT_AUTO, GF_ERR_FORMAT, "blank.xyz", 0,
                 "no particles in file");
    expect_error(tmpfile_with("empty.csv", ""), GF_FORMAT_AUTO, GF_ERR_FORMAT, "empty.csv", 0,
                 "no particles in file");
}

static void error_zero_atoms(void **state)
{
    (void)state;
    const char *path = tmpfile_with(
        "zero.dump", "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n0\n"
                     "ITEM: BOX BOUNDS ff ff ff\n0 1\n0 1\n0 1\nITEM: ATOMS id x y z\n");
    expect_error(path, GF_FORMAT_AUTO, GF_ERR_FORMAT, "zero.dump", 4, "no particles in file");
    path = tmpfile_with("header_only.csv", "id,x,y,z\n\n");
    expect_error(path, GF_FORMAT_AUTO, GF_ERR_FORMAT, "header_only.csv", 1, "no particles in file");
    path = tmpfile_with("zero.xyz", "0\ncomment\n");
    expect_error(path, GF_FORMAT_AUTO, GF_ERR_FORMAT, "zero.xyz", 1, "no particles in file");
}

static void error_xyz_fewer_lines(void **state)
{
    (void)state;
    const char *path = tmpfile_with("short.xyz", "4\ncomment\nC 0 0 0.5\nC 1 0 0.5\nC 2 0 0.5\n");
    expect_error(path, GF_FORMAT_AUTO, GF_ERR_FORMAT, "short.xyz", 5, "after 3 of the 4 atoms");
    path = tmpfile_with("short2.xyz", "4\n");
    expect_error(path, GF_FORMAT_AUTO, GF_ERR_FORMAT, "short2.xyz", 1, "truncated");
    path = tmpfile_with("cut_line.xyz", "2\ncomment\nC 0 0 0.5\nC 1 0");
    expect_error(path, GF_FORMAT_AUTO, GF_ERR_FORMAT, "cut_line.xyz", 4, "truncated");
    path = tmpfile_with("not_count.xyz", "C 0 0 0\n");
    expect_error(path, GF_FORMAT_AUTO, GF_ERR_FORMAT, "not_count.xyz", 1, "number of atoms");
}

// Extended XYZ (issue 26: `pack -o p.xyz` of a bidisperse packing dropped
// the radii, and the re-import ran monodisperse without a word): the comment
// line's Properties= places the radius (and the positions); a malformed one
// is refused, naming the line.
static void xyz_properties_give_the_radii(void **state)
{
    (void)state;
    gf_packing p = {0};
    const char *path = tmpfile_with("ext.xyz", "2\nx Properties=species:S:1:pos:R:3:radius:R:1 t=0\n"
                                               "P 0 0 0.5 0.5\nP 1 0 0.5 0.35\n");
    assert_int_equal(gf_packing_read(path, GF_FORMAT_AUTO, &p), GF_OK);
    assert_int_equal(p.n, 2);
    assert_true(p.r[0] == 0.5 && p.r[1] == 0.35 && p.x[1] == 1.0);
    path = tmpfile_with("ext2.xyz", "1\nProperties=species:S:1:radius:R:1:id:I:1:pos:R:3\nP 0.6 7 1 2 3\n");
    assert_int_equal(gf_packing_read(path, GF_FORMAT_AUTO, &p), GF_OK);
    assert_true(p.n == 1 && p.r[0] == 0.6 && p.x[0] == 1.0 && p.y[0] == 2.0 && p.z[0] == 3.0);
    gf_packing_free(&p);
    expect_error(tmpfile_with("ext3.xyz", "1\nProperties=species:S:1:pos:R:3:radius:R:1\nP 0 0 0.5\n"),
                 GF_FORMAT_AUTO, GF_ERR_FORMAT, "ext3.xyz", 3, "Properties=");
    expect_error(tmpfile_with("ext4.xyz", "1\nProperties=species:S\nP 0 0 0.5\n"), GF_FORMAT_AUTO,
                 GF_ERR_FORMAT, "ext4.xyz", 2, "NAME:TYPE:COUNT");
    expect_error(tmpfile_with("ext5.xyz", "1\nProperties=species:S:1:radius:R:1\nP 0.5\n"), GF_FORMAT_AUTO,
                 GF_ERR_FORMAT, "ext5.xyz", 2, "no pos:R:3");
    expect_error(tmpfile_with("ext6.xyz", "1\nProperties=species:S:1:pos:R:3:radius:R:1\nP 0 0 0.5 -1\n"),
                 GF_FORMAT_AUTO, GF_ERR_FORMAT, "ext6.xyz", 3, "radius must be positive");
}

static void error_csv_without_z(void **state)
{
    (void)state;
    const char *path = tmpfile_with("no_z.csv", "id, X ,y,radius\n1,0,0,0.5\n");
    expect_error(path, GF_FORMAT_AUTO, GF_ERR_FORMAT, "no_z.csv", 1, "found: id,X,y,radius");
}

static void error_triclinic_box(void **state)
{
    (void)state;
    const char *path = tmpfile_with(
        "tri.dump",
        "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n1\nITEM: BOX BOUNDS xy xz yz pp pp pp\n"
        "0 1 0.1\n0 1 0\n0 1 0\nITEM: ATOMS id x y z\n1 0 0 0.5\n");
    expect_error(path, GF_FORMAT_AUTO, GF_ERR_FORMAT, "tri.dump", 5, "triclinic");
    path = tmpfile_with("tri3.dump",
                        "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n1\nITEM: BOX BOUNDS pp pp pp\n"
                        "0 1 0.1\n0 1 0\n0 1 0\nITEM: ATOMS id x y z\n1 0 0 0.5\n");
    expect_error(path, GF_FORMAT_AUTO, GF_ERR_FORMAT, "tri3.dump", 6, "triclinic");
}

static void error_not_a_dump(void **state)
{
    (void)state;
    expect_error(DATA("packing.xyz"), GF_FORMAT_LAMMPS, GF_ERR_FORMAT, "packing.xyz", 1, "ITEM:");
}

// ---------------------------------------------------------------------------
// writing

static void roundtrip(gf_packing_format fmt, const char *name, int ids_kept, int radii_kept)
{
    gf_packing a = {0}, b = {0};
    random_packing(&a, 500, 42, !ids_kept, !radii_kept);
    const char *path = tmppath(name);
    assert_int_equal(gf_packing_write(&a, path, fmt, NULL), GF_OK);
    assert_int_equal(gf_packing_read(path, GF_FORMAT_AUTO, &b), GF_OK);
    expect_same(&a, &b, ids_kept, radii_kept);
    // bit-exact, not only to 1e-9
    for (size_t i = 0; i < a.n; i++)
        assert_true(a.x[i] == b.x[i] && a.y[i] == b.y[i] && a.z[i] == b.z[i]);
    char tmp[1100];
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    assert_int_not_equal(access(tmp, F_OK), 0); // no temporary file left behind
    gf_packing_free(&a);
    gf_packing_free(&b);
}

static void roundtrip_lammps(void **state)
{
    (void)state;
    roundtrip(GF_FORMAT_LAMMPS, "rt.dump", 1, 1);
}

static void roundtrip_xyz(void **state)
{
    (void)state;
    roundtrip(GF_FORMAT_XYZ, "rt.xyz", 0, 1); // radii kept (issue 26: a bidisperse packing lost them)
}

static void roundtrip_csv(void **state)
{
    (void)state;
    roundtrip(GF_FORMAT_CSV, "rt.csv", 1, 1);
}

static void write_lammps_layout(void **state)
{
    (void)state;
    gf_packing p = {0};
    assert_int_equal(gf_packing_push(&p, 5, 3, 0.5, -1.0, 2.0, 0.5), GF_OK);
    assert_int_equal(gf_packing_push(&p, 9, 0, 0.25, 1.0, 10.0, 0.5), GF_OK);
    gf_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.container_width = 50.0;
    cfg.container_depth = 8.0;
    const char *path = tmppath("layout.dump");
    assert_int_equal(gf_packing_write(&p, path, GF_FORMAT_AUTO, &cfg), GF_OK);
    char *text = gf_test_read_file(path, NULL);
    assert_non_null(text);
    assert_string_equal(text,
                        "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n2\nITEM: BOX BOUNDS ff ff ff\n"
                        "-25 25\n-4 4\n0 10.5\nITEM: ATOMS id type x y z radius\n"
                        "5 3 0.5 -1 2 0.5\n9 1 0.25 1 10 0.5\n");
    free(text);

    // without a configuration: the particles' bounding box
    assert_int_equal(gf_packing_write(&p, path, GF_FORMAT_LAMMPS, NULL), GF_OK);
    text = gf_test_read_file(path, NULL);
    assert_non_null(text);
    expect_contains(text, "ITEM: BOX BOUNDS ff ff ff\n-0.25 1\n-1.5 1.5\n0 10.5\n");
    free(text);

    path = tmppath("layout.csv");
    assert_int_equal(gf_packing_write(&p, path, GF_FORMAT_AUTO, NULL), GF_OK);
    text = gf_test_read_file(path, NULL);
    assert_string_equal(text, "id,type,x,y,z,radius\n5,3,0.5,-1,2,0.5\n9,1,0.25,1,10,0.5\n");
    free(text);

    path = tmppath("layout.xyz");
    assert_int_equal(gf_packing_write(&p, path, GF_FORMAT_AUTO, NULL), GF_OK);
    text = gf_test_read_file(path, NULL);
    assert_string_equal(text, "2\ngranflow packing Properties=species:S:1:pos:R:3:radius:R:1\n"
                              "P 0.5 -1 2 0.5\nP 0.25 1 10 0.5\n");
    free(text);
    gf_packing_free(&p);
}

static void write_error_names_path(void **state)
{
    (void)state;
    gf_packing p = {0};
    assert_int_equal(gf_packing_push(&p, 1, 1, 0.0, 0.0, 0.5, 0.5), GF_OK);
    const char *path = tmppath("no_such_dir/out.dump");
    assert_int_equal(gf_packing_write(&p, path, GF_FORMAT_AUTO, NULL), GF_ERR_IO);
    expect_contains(gf_last_error(), "no_such_dir/out.dump");

    // rename fails when the target is a non-empty directory: the .tmp must go
    char dir[1024], inner[1100], tmp[1100];
    snprintf(dir, sizeof dir, "%s", tmppath("target_is_dir"));
    assert_int_equal(mkdir(dir, 0700), 0);
    snprintf(inner, sizeof inner, "%s/x", dir);
    FILE *f = fopen(inner, "w");
    assert_non_null(f);
    fclose(f);
    assert_int_equal(gf_packing_write(&p, dir, GF_FORMAT_LAMMPS, NULL), GF_ERR_IO);
    expect_contains(gf_last_error(), "target_is_dir");
    snprintf(tmp, sizeof tmp, "%s.tmp", dir);
    assert_int_not_equal(access(tmp, F_OK), 0);

    p.x[0] = NAN;
    assert_int_equal(gf_packing_write(&p, tmppath("nan.dump"), GF_FORMAT_AUTO, NULL), GF_ERR_PARAM);
    gf_packing_free(&p);
}

// ---------------------------------------------------------------------------
// big files

static void big_dump_50000(void **state)
{
    (void)state;
    gf_packing a = {0}, b = {0}, c = {0};
    random_packing(&a, 50000, 7, 0, 0);
    const char *p1 = tmppath("big.dump");
    assert_int_equal(gf_packing_write(&a, p1, GF_FORMAT_AUTO, NULL), GF_OK);
    assert_int_equal(gf_packing_read(p1, GF_FORMAT_AUTO, &b), GF_OK);
    expect_same(&a, &b, 1, 1);

    // a three-frame file made of two different packings: the last frame wins,
    // which makes the reader seek back across many buffer refills
    random_packing(&c, 40000, 8, 1, 1);
    char p2[1024];
    snprintf(p2, sizeof p2, "%s", tmppath("big2.dump"));
    assert_int_equal(gf_packing_write(&c, p2, GF_FORMAT_AUTO, NULL), GF_OK);
    size_t n1, n2;
    char *t1 = gf_test_read_file(p1, &n1), *t2 = gf_test_read_file(p2, &n2);
    assert_non_null(t1);
    assert_non_null(t2);
    FILE *f = fopen(tmppath("multi.dump"), "wb");
    assert_non_null(f);
    fwrite(t1, 1, n1, f);
    fwrite(t1, 1, n1, f);
    fwrite(t2, 1, n2, f);
    fclose(f);
    gf_packing_free(&b);
    assert_int_equal(gf_packing_read(tmppath("multi.dump"), GF_FORMAT_AUTO, &b), GF_OK);
    expect_same(&c, &b, 1, 1);

    // the same, truncated in the middle of the last frame
    f = fopen(tmppath("multi_cut.dump"), "wb");
    assert_non_null(f);
    fwrite(t1, 1, n1, f);
    fwrite(t2, 1, n2 - n2 / 3, f);
    fclose(f);
    gf_packing_free(&b);
    assert_int_equal(gf_packing_read(tmppath("multi_cut.dump"), GF_FORMAT_AUTO, &b), GF_ERR_FORMAT);
    expect_contains(gf_last_error(), "multi_cut.dump:");
    expect_contains(gf_last_error(), "of 40000 atoms (truncated file?)");
    assert_int_equal(b.n, 0);

    free(t1);
    free(t2);
    gf_packing_free(&a);
    gf_packing_free(&c);
}

/// Non-seekable input (a FIFO) takes the one-pass path: every frame converted.
// gzip: the same bytes compressed read as the same packing, whatever the
// format (the name without .gz decides it), and a compressed file named
// without .gz reads too; a cut or corrupted .gz is a format error naming it.
static void gzip_reads_like_plain(void **state)
{
    (void)state;
    gf_packing a = {0}, b = {0}, c = {0};
    random_packing(&a, 20000, 9, 1, 1);
    const char *names[] = {"z.dump", "z.xyz", "z.csv"};
    for (size_t k = 0; k < 3; k++) {
        char plain[1024], gz[1024 + 8];
        snprintf(plain, sizeof plain, "%s", tmppath(names[k]));
        snprintf(gz, sizeof gz, "%s.gz", plain);
        assert_int_equal(gf_packing_write(&a, plain, GF_FORMAT_AUTO, NULL), GF_OK);
        assert_true(gf_test_gzip(plain, gz, 0) > 0);
        assert_int_equal(gf_packing_read(plain, GF_FORMAT_AUTO, &b), GF_OK);
        assert_int_equal(gf_packing_read(gz, GF_FORMAT_AUTO, &c), GF_OK);
        assert_int_equal(b.n, c.n);
        assert_memory_equal(b.x, c.x, b.n * sizeof *b.x);
        assert_memory_equal(b.z, c.z, b.n * sizeof *b.z);
        assert_memory_equal(b.id, c.id, b.n * sizeof *b.id);
        assert_memory_equal(b.y, c.y, b.n * sizeof *b.y);
        assert_memory_equal(b.r, c.r, b.n * sizeof *b.r);
    }
    // A multi-frame dump, compressed: the reader seeks back to the last frame.
    size_t n1;
    char *t1 = gf_test_read_file(tmppath("z.dump"), &n1);
    assert_non_null(t1);
    FILE *f = fopen(tmppath("zz.dump"), "wb");
    assert_non_null(f);
    fwrite(t1, 1, n1, f);
    fwrite(t1, 1, n1, f);
    fclose(f);
    free(t1);
    char plain[1024], hidden[1024];
    snprintf(plain, sizeof plain, "%s", tmppath("zz.dump"));
    snprintf(hidden, sizeof hidden, "%s", tmppath("zz_gzip_inside.dump"));
    size_t full = gf_test_gzip(plain, hidden, 0);
    assert_true(full > 0);
    gf_packing_free(&c);
    assert_int_equal(gf_packing_read(hidden, GF_FORMAT_AUTO, &c), GF_OK);
    expect_same(&a, &c, 1, 1);

    // Cut at two thirds: rc 3 (GF_ERR_FORMAT), the file named, the cause said.
    char cut[1024];
    snprintf(cut, sizeof cut, "%s", tmppath("zz_cut.dump.gz"));
    assert_true(gf_test_gzip(plain, cut, full * 2 / 3) > 0);
    expect_error(cut, GF_FORMAT_AUTO, GF_ERR_FORMAT, "zz_cut.dump.gz:", 0, "truncated gzip file");
    // Only the 8-byte trailer missing: the text is whole but the file is not.
    assert_true(gf_test_gzip(plain, cut, full - 8) > 0);
    expect_error(cut, GF_FORMAT_AUTO, GF_ERR_FORMAT, "zz_cut.dump.gz:", 0, "truncated gzip file");
    // A flipped byte in the middle of the compressed data.
    size_t nz;
    char *z = gf_test_read_file(hidden, &nz);
    assert_non_null(z);
    z[nz / 2] ^= 0x55;
    f = fopen(cut, "wb");
    assert_non_null(f);
    fwrite(z, 1, nz, f);
    fclose(f);
    free(z);
    expect_error(cut, GF_FORMAT_AUTO, GF_ERR_FORMAT, "zz_cut.dump.gz:", 0, NULL);
    gf_packing_free(&a);
    gf_packing_free(&b);
    gf_packing_free(&c);
}

// Issue 26: a .gz with bytes after its gzip data was read as if whole (zlib
// ignores them), and a cut one was reported at ":1:" whatever the place of
// the cut. Two gzip members one after the other are still one file.
static void gzip_garbage_and_the_place_of_a_cut(void **state)
{
    (void)state;
    gf_packing a = {0}, c = {0};
    random_packing(&a, 3000, 11, 1, 1);
    char plain[1024], gz[1024], bad[1024];
    snprintf(plain, sizeof plain, "%s", tmppath("gg.dump"));
    snprintf(gz, sizeof gz, "%s", tmppath("gg.dump.gz"));
    snprintf(bad, sizeof bad, "%s", tmppath("gg_bad.dump.gz"));
    assert_int_equal(gf_packing_write(&a, plain, GF_FORMAT_AUTO, NULL), GF_OK);
    size_t full = gf_test_gzip(plain, gz, 0);
    assert_true(full > 0);
    size_t nz;
    char *z = gf_test_read_file(gz, &nz);
    assert_non_null(z);
    const char *tails[] = {"garbage\n", "x"}; // (a tail starting 1f 8b is a bad member: zlib says corrupt)
    for (size_t k = 0; k < 2; k++) {
        FILE *f = fopen(bad, "wb");
        assert_non_null(f);
        fwrite(z, 1, nz, f);
        fputs(tails[k], f);
        fclose(f);
        expect_error(bad, GF_FORMAT_AUTO, GF_ERR_FORMAT, "gg_bad.dump.gz", 0, "bytes after the end of the gzip data");
    }
    FILE *f = fopen(bad, "wb"); // two members: read as one file (the second frame is the last)
    assert_non_null(f);
    fwrite(z, 1, nz, f);
    fwrite(z, 1, nz, f);
    fclose(f);
    assert_int_equal(gf_packing_read(bad, GF_FORMAT_AUTO, &c), GF_OK);
    expect_same(&a, &c, 1, 1);
    free(z);
    // Cut at a third: the line of the cut, far past line 1.
    assert_true(gf_test_gzip(plain, bad, full / 3) > 0);
    expect_error(bad, GF_FORMAT_AUTO, GF_ERR_FORMAT, "gg_bad.dump.gz", 0, "truncated gzip file");
    long line = 0;
    const char *m = strstr(gf_last_error(), "gg_bad.dump.gz:");
    assert_non_null(m);
    assert_int_equal(sscanf(m, "gg_bad.dump.gz:%ld:", &line), 1);
    if (!(line > 100 && line < 3010)) fail_msg("the cut is reported at line %ld: %s", line, gf_last_error());
    gf_packing_free(&a);
    gf_packing_free(&c);
}

static void read_from_fifo(void **state)
{
    (void)state;
    char fifo[1024];
    snprintf(fifo, sizeof fifo, "%s", tmppath("pipe.dump"));
    assert_int_equal(mkfifo(fifo, 0600), 0);
    char *text = gf_test_read_file(DATA("multiframe.dump"), NULL);
    assert_non_null(text);
    for (int round = 0; round < 2; round++) {
        size_t len = strlen(text) - (round ? 24 : 0); // round 1: drop the last atom line
        pid_t pid = fork();
        assert_true(pid >= 0);
        if (pid == 0) {
            FILE *f = fopen(fifo, "wb");
            if (f) {
                fwrite(text, 1, len, f);
                fclose(f);
            }
            _exit(0);
        }
        gf_packing p = {0};
        gf_status st = gf_packing_read(fifo, GF_FORMAT_LAMMPS, &p);
        int status;
        waitpid(pid, &status, 0);
        if (round == 0) {
            assert_int_equal(st, GF_OK);
            assert_int_equal(p.n, 3);
            expect_particle(&p, 3, 2.0, 0.0, 0.625, 0.5);
        } else {
            assert_int_equal(st, GF_ERR_FORMAT);
            expect_contains(gf_last_error(), "ends after 2 of 3 atoms");
            assert_int_equal(p.n, 0);
        }
        gf_packing_free(&p);
    }
    free(text);
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(lammps_id_type_xyz),
    cmocka_unit_test(lammps_xyz_id_type_radius_crlf),
    cmocka_unit_test(lammps_scaled_coordinates),
    cmocka_unit_test(lammps_unwrapped_coordinates),
    cmocka_unit_test(lammps_time_before_timestep),
    cmocka_unit_test(lammps_multiframe_takes_last),
    cmocka_unit_test(lammps_diameter_column),
    cmocka_unit_test(lammps_without_ids_numbers_in_order),
    cmocka_unit_test(read_replaces_previous_content),
    cmocka_unit_test(xyz_reads),
    cmocka_unit_test(csv_extra_columns_any_order),
    cmocka_unit_test(csv_without_ids),
    cmocka_unit_test(csv_diameter_alias),
    cmocka_unit_test(error_truncated_last_frame),
    cmocka_unit_test(error_truncated_frame_cut_by_next),
    cmocka_unit_test(error_truncated_header),
    cmocka_unit_test(error_missing_section),
    cmocka_unit_test(error_bad_number),
    cmocka_unit_test(error_wrong_column_count),
    cmocka_unit_test(error_too_many_atom_lines),
    cmocka_unit_test(error_duplicate_id),
    cmocka_unit_test(error_missing_z_column),
    cmocka_unit_test(error_scaled_without_box),
    cmocka_unit_test(error_missing_file),
    cmocka_unit_test(error_empty_file),
    cmocka_unit_test(error_zero_atoms),
    cmocka_unit_test(error_xyz_fewer_lines),
    cmocka_unit_test(xyz_properties_give_the_radii),
    cmocka_unit_test(error_csv_without_z),
    cmocka_unit_test(error_triclinic_box),
    cmocka_unit_test(error_not_a_dump),
    cmocka_unit_test(roundtrip_lammps),
    cmocka_unit_test(roundtrip_xyz),
    cmocka_unit_test(roundtrip_csv),
    cmocka_unit_test(write_lammps_layout),
    cmocka_unit_test(write_error_names_path),
    cmocka_unit_test(big_dump_50000),
    cmocka_unit_test(gzip_reads_like_plain),
    cmocka_unit_test(gzip_garbage_and_the_place_of_a_cut),
    cmocka_unit_test(read_from_fifo),
};

GF_TEST_MAIN("import", tests)
