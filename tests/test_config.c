// SPDX-License-Identifier: MIT
// Configuration: defaults, INI loading and its error messages, --set, validation, round trips.
#include "support.h"

#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "config/keys.h"
#include "granflow/config.h"

// ---- helpers ---------------------------------------------------------------

static size_t key_size(const gf_key *k)
{
    switch (k->type) {
    case GF_KEY_ENUM:
    case GF_KEY_SET: return sizeof(int);
    case GF_KEY_PATH: return GF_PATH_MAX;
    case GF_KEY_LIST: return sizeof(double) * k->list_max;
    case GF_KEY_SIZE: return sizeof(size_t);
    case GF_KEY_DOUBLE:
    case GF_KEY_AUTO:
    case GF_KEY_INT64:
    case GF_KEY_UINT64: break;
    }
    return 8;
}

// Every field (all but cookie_) bitwise equal.
static void assert_same_fields(const gf_config *a, const gf_config *b)
{
    for (size_t i = 0; i < gf_keys_count; i++) {
        const gf_key *k = &gf_keys[i];
        if (memcmp((const char *)a + k->offset, (const char *)b + k->offset, key_size(k)) != 0) {
            char va[80], vb[80];
            gf_keys_format(k, a, va, sizeof va);
            gf_keys_format(k, b, vb, sizeof vb);
            fail_msg("%s.%s differs: %s vs %s", k->section, k->name, va, vb);
        }
    }
}

static void assert_contains(const char *text, const char *part)
{
    if (!strstr(text, part)) fail_msg("'%s' does not contain '%s'", text, part);
}

static const char *ini(const char *name, const char *text)
{
    return gf_test_write_file(gf_test_tmpdir(), name, text);
}

// Loads `text` as file `name` over the defaults and checks the status and that
// the message names the file, the line (":<line>:") and `part` (key etc.).
static void expect_load_error(const char *name, const char *text, int line, const char *part)
{
    char path[1024];
    snprintf(path, sizeof path, "%s", ini(name, text));
    gf_config cfg = gf_config_default();
    gf_status st = gf_config_load(&cfg, path);
    if (st != GF_ERR_PARAM)
        fail_msg("%s: status %s, message '%s'", name, gf_status_str(st), gf_last_error());
    const char *msg = gf_last_error();
    char at[1100];
    snprintf(at, sizeof at, "%s:%d: ", path, line);
    assert_contains(msg, at);
    if (part) assert_contains(msg, part);
}

static void expect_set_error(const char *assignment, const char *part)
{
    gf_config cfg = gf_config_default();
    gf_config before = cfg;
    gf_status st = gf_config_set(&cfg, assignment, "--set");
    if (st != GF_ERR_PARAM) fail_msg("%s: status %s", assignment, gf_status_str(st));
    assert_contains(gf_last_error(), "--set ");
    assert_contains(gf_last_error(), part);
    assert_same_fields(&cfg, &before); // a failed set changes nothing
}

static void load_ok(gf_config *cfg, const char *name, const char *text)
{
    gf_status st = gf_config_load(cfg, ini(name, text));
    if (st != GF_OK) fail_msg("%s: %s", name, gf_last_error());
}

// ---- defaults --------------------------------------------------------------

static void defaults_match_spec(void **state)
{
    (void)state;
    gf_config c = gf_config_default();
    assert_true(c.container_width == 50);
    assert_true(c.container_depth == 8);
    assert_int_equal(c.orifice_shape, GF_ORIFICE_CIRCLE);
    assert_true(c.orifice_diameter == 8);
    assert_true(c.exit_z == 0);
    assert_int_equal(c.packing_particles, 55000);
    assert_true(c.packing_fill_height == 0);
    assert_string_equal(c.packing_file, "");
    assert_true(c.packing_layer_thickness == 10);
    assert_true(c.spot_radius == 2.6);
    assert_true(c.spot_w == 399);
    assert_true(c.spot_insertion_rate == 375);
    assert_true(c.spot_move_rate == 28);
    assert_true(c.spot_step_xy == 0.676);
    assert_true(c.spot_step_z == 0.1);
    assert_true(c.spot_wall_distance == 1);
    assert_int_equal(c.spot_ball_centre, GF_BALL_MIDPOINT);
    assert_true(isnan(c.spot_insertion_margin));
    assert_true(c.relax_alpha == 0.8);
    assert_true(isnan(c.relax_radius));
    assert_true(c.run_duration == 60);
    assert_true(c.run_seed == 1);
    assert_true(c.run_checkpoint_interval == 10); // issue 16: a default bounds the work a kill loses
    assert_true(c.run_stall_time == 10);
    assert_true(c.output_snapshot_interval == 2);
    assert_int_equal(gf_config_validate(&c), GF_OK);
    assert_true(c.spot_insertion_margin == 2.6);
    assert_true(c.relax_radius == 2.6 + 1);
}

static int cmp_key_offset(const void *a, const void *b)
{
    size_t x = (*(const gf_key *const *)a)->offset, y = (*(const gf_key *const *)b)->offset;
    return x < y ? -1 : x > y;
}

// The table has one entry per field: sorted by offset, keys never overlap and
// the gaps between them are padding (< 8 bytes), so no field lacks a key.
static void key_table_covers_struct(void **state)
{
    (void)state;
    const gf_key *sorted[256];
    assert_true(gf_keys_count <= 256);
    for (size_t i = 0; i < gf_keys_count; i++) sorted[i] = &gf_keys[i];
    qsort(sorted, gf_keys_count, sizeof sorted[0], cmp_key_offset);
    size_t end = 0;
    for (size_t i = 0; i < gf_keys_count; i++) {
        const gf_key *k = sorted[i];
        assert_true(k->offset >= end);
        if (k->offset - end >= 8)
            fail_msg("no key for the field(s) before %s.%s", k->section, k->name);
        end = k->offset + key_size(k);
        assert_ptr_equal(gf_keys_find(&gf_config_keys, k->section, k->name), k); // names are unique
    }
    assert_true(offsetof(gf_config, cookie_) >= end && offsetof(gf_config, cookie_) - end < 8);
}

// gf_config_default() is built from the table's default texts; parsing each
// text again gives the same field, and the table lists the spec's defaults.
static void defaults_match_key_table(void **state)
{
    (void)state;
    gf_config d = gf_config_default();
    gf_config c = gf_config_default();
    memset((char *)&c, 0xAB, offsetof(gf_config, cookie_));
    for (size_t i = 0; i < gf_keys_count; i++) {
        char why[160];
        assert_int_equal(gf_keys_assign(&gf_keys[i], &c, gf_keys[i].def, why, sizeof why),
                         GF_KEY_OK);
        char text[64];
        gf_keys_format(&gf_keys[i], &d, text, sizeof text);
        assert_string_equal(text, gf_keys[i].def);
    }
    assert_same_fields(&c, &d);
    assert_string_equal(gf_keys_find(&gf_config_keys, "spot", "step_xy")->def, "0.676");
    assert_string_equal(gf_keys_find(&gf_config_keys, "relax", "radius")->def, "auto");
}

// ---- loading -------------------------------------------------------------

static void load_sets_several_keys(void **state)
{
    (void)state;
    gf_config c = gf_config_default();
    load_ok(&c, "several.ini",
            "# a comment\n"
            "[container]\n"
            "width = 40\n"
            "orifice_shape = slit\n"
            "orifice_diameter = 6.5\n"
            "exit_z = -2\n"
            "\n"
            "[spot]\n"
            "radius = 3 ; inline comment\n"
            "w: 250\n"
            "ball_centre = end\n"
            "wall_distance = -0.5\n"
            "insertion_margin = 1.25\n"
            "[packing]\n"
            "particles = 1000\n"
            "file = data/packing 1.dump\n"
            "[relax]\n"
            "alpha = 1\n"
            "[run]\n"
            "seed = 18446744073709551615\n"
            "duration = 1e2\n"
            "[output]\n"
            "snapshot_interval = 0.5\n");
    assert_true(c.container_width == 40);
    assert_true(c.container_depth == 8); // untouched keys keep their value
    assert_int_equal(c.orifice_shape, GF_ORIFICE_SLIT);
    assert_true(c.orifice_diameter == 6.5);
    assert_true(c.exit_z == -2);
    assert_true(c.spot_radius == 3);
    assert_true(c.spot_w == 250);
    assert_int_equal(c.spot_ball_centre, GF_BALL_END);
    assert_true(c.spot_wall_distance == -0.5);
    assert_true(c.spot_insertion_margin == 1.25);
    assert_int_equal(c.packing_particles, 1000);
    assert_string_equal(c.packing_file, "data/packing 1.dump");
    assert_true(c.relax_alpha == 1);
    assert_true(isnan(c.relax_radius));
    assert_true(c.run_seed == UINT64_MAX);
    assert_true(c.run_duration == 100);
    assert_true(c.output_snapshot_interval == 0.5);
    assert_int_equal(gf_config_validate(&c), GF_OK);
    assert_true(c.relax_radius == 4);
    assert_true(c.spot_insertion_margin == 1.25);
}

// Indented keys are plain keys (not libinih continuation lines); BOM, CRLF,
// spaces inside brackets, `auto` and an empty packing.file are accepted.
static void load_accepts_layout_variants(void **state)
{
    (void)state;
    gf_config c = gf_config_default();
    load_ok(
        &c, "layout.ini",
        "\xEF\xBB\xBF[ spot ]\r\n"
        "    radius = 4\r\n"
        "\tw = 300\r\n"
        "insertion_margin = auto\r\n"
        "; a comment far longer than libinih's line buffer: "
        "xxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxx"
        "xxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxx"
        "\r\n"
        "[packing]\r\n"
        "file =\r\n"
        "[relax]\n"
        "radius = 5\n"
        "radius = auto\n");
    assert_true(c.spot_radius == 4);
    assert_true(c.spot_w == 300);
    assert_true(isnan(c.spot_insertion_margin));
    assert_string_equal(c.packing_file, "");
    assert_true(isnan(c.relax_radius));
}

static void load_unknown_section(void **state)
{
    (void)state;
    expect_load_error("sec.ini", "[spot]\nradius = 3\n[spt]\nw = 3\n", 3, "unknown section [spt]");
}

static void load_unknown_empty_section(void **state)
{
    (void)state;
    expect_load_error("emptysec.ini", "; nothing\n[spt]\n", 2, "unknown section [spt]");
}

static void load_unknown_key(void **state)
{
    (void)state;
    expect_load_error("key.ini", "[spot]\nw = 3\n\n\nraduis = 2\n", 5,
                      "unknown key 'raduis' in section [spot] (known: radius, w, insertion_rate");
}

static void load_not_a_number(void **state)
{
    (void)state;
    expect_load_error("nan.ini", "[spot]\n\nw = 3x9\n", 3, "[spot] w = '3x9': not a number");
}

static void load_trailing_garbage(void **state)
{
    (void)state;
    expect_load_error("garbage.ini", "[container]\nwidth = 3.0x\n", 2,
                      "width = '3.0x': not a number");
    expect_load_error("garbage2.ini", "[container]\ndepth = 3 4\n", 2,
                      "depth = '3 4': not a number");
}

static void load_below_range(void **state)
{
    (void)state;
    expect_load_error("below.ini", "[relax]\nalpha = 0\n", 2,
                      "[relax] alpha = 0: out of range (0, 1]");
    expect_load_error("below2.ini", "[container]\nwidth = -1\n", 2,
                      "width = -1: out of range (0, 100000]");
    expect_load_error("below3.ini", "[packing]\nparticles = 0\n", 2,
                      "particles = 0: out of range [1, 50000000]");
    expect_load_error("below4.ini", "[spot]\nstep_xy = -0.1\n", 2,
                      "step_xy = -0.1: out of range [0, inf)");
    expect_load_error("below5.ini", "[spot]\ninsertion_margin = -1\n", 2,
                      "insertion_margin = -1: out of range [0, inf) or auto");
}

static void load_above_range(void **state)
{
    (void)state;
    expect_load_error("above.ini", "[relax]\n\n\n\nalpha = 1.5\n", 5,
                      "[relax] alpha = 1.5: out of range (0, 1]");
    expect_load_error("above2.ini", "[spot]\nradius = 20.5\n", 2,
                      "radius = 20.5: out of range (0, 20]");
    expect_load_error("above3.ini", "[container]\nexit_z = 0.6\n", 2,
                      "exit_z = 0.6: out of range [-100000, 0.5]");
    expect_load_error("above4.ini", "[packing]\nparticles = 50000001\n", 2,
                      "particles = 50000001: out of range");
}

static void load_integer_errors(void **state)
{
    (void)state;
    expect_load_error("int1.ini", "[packing]\nparticles = 1000.5\n", 2,
                      "particles = '1000.5': not an integer");
    expect_load_error("int2.ini", "[packing]\nparticles = 99999999999999999999\n", 2,
                      "out of range");
    expect_load_error("int3.ini", "[run]\nseed = -1\n", 2,
                      "seed = -1: out of range [0, 18446744073709551615]");
    expect_load_error("int4.ini", "[run]\nseed = 18446744073709551616\n", 2,
                      "seed = 18446744073709551616: out of range");
    expect_load_error("int5.ini", "[run]\nseed = 1e3\n", 2, "seed = '1e3': not an integer");
    expect_load_error("int6.ini", "[run]\nseed = abc\n", 2, "seed = 'abc': not a number");
}

static void load_rejects_nan_inf(void **state)
{
    (void)state;
    expect_load_error("nf1.ini", "[spot]\nwall_distance = nan\n", 2,
                      "wall_distance = 'nan': not a finite number");
    expect_load_error("nf2.ini", "[spot]\nwall_distance = -inf\n", 2, "not a finite number");
    expect_load_error("nf3.ini", "[run]\nduration = 1e999\n", 2,
                      "duration = '1e999': not a finite number");
    expect_load_error("nf4.ini", "[relax]\nradius = Auto\n", 2,
                      "radius = 'Auto': not a number or 'auto'");
}

static void load_empty_value(void **state)
{
    (void)state;
    expect_load_error("empty.ini", "[spot]\nw =\n", 2, "[spot] w = '': empty value");
    expect_load_error("empty2.ini", "[spot]\nball_centre = ; comment only\n", 2,
                      "ball_centre = '': empty value");
}

static void load_bad_enum(void **state)
{
    (void)state;
    expect_load_error("enum.ini", "[container]\norifice_shape = Circle\n", 2,
                      "orifice_shape = 'Circle': not one of: circle, slit");
    expect_load_error("enum2.ini", "[spot]\nball_centre = start\n", 2, "not one of: midpoint, end");
}

static void load_key_before_section(void **state)
{
    (void)state;
    expect_load_error("nosec.ini", "; header\nradius = 3\n[spot]\n", 2, "'radius'");
    assert_contains(gf_last_error(), "outside any [section]");
}

static void load_syntax_error(void **state)
{
    (void)state;
    expect_load_error("syntax.ini", "[spot]\nw = 3\nradius 3\n", 3, "syntax error");
    expect_load_error("syntax2.ini", "[spot\nw = 3\n", 1, "syntax error: missing ']'");
    expect_load_error("syntax3.ini", "[spot]\nw ; = 3\n", 2, "syntax error");
}

static void load_line_too_long(void **state)
{
    (void)state;
    char text[600];
    snprintf(text, sizeof text, "[packing]\nfile = %0400d\n", 7);
    expect_load_error("long.ini", text, 2, "line too long");
}

static void load_reports_first_error(void **state)
{
    (void)state;
    expect_load_error("first.ini", "[spot]\nw = x\nradius = 99\n[nope]\n", 2, "w = 'x'");
    expect_load_error("first2.ini", "[spot]\nbad line\nw = x\n", 2, "syntax error");
    expect_load_error("first3.ini", "[nope]\nbad line\n", 1, "unknown section [nope]");
}

static void load_missing_file(void **state)
{
    (void)state;
    gf_config c = gf_config_default();
    char path[1024];
    snprintf(path, sizeof path, "%s/does-not-exist.ini", gf_test_tmpdir());
    assert_int_equal(gf_config_load(&c, path), GF_ERR_IO);
    assert_contains(gf_last_error(), path);
    assert_int_equal(gf_config_load(&c, gf_test_tmpdir()), GF_ERR_IO); // a directory
}

// ---- --set -----------------------------------------------------------------

static void set_works(void **state)
{
    (void)state;
    gf_config c = gf_config_default();
    assert_int_equal(gf_config_set(&c, "spot.w=400", "--set"), GF_OK);
    assert_int_equal(gf_config_set(&c, "  spot.radius =  3 ", "--set"), GF_OK);
    assert_int_equal(gf_config_set(&c, "container.orifice_shape=slit", "--set"), GF_OK);
    assert_int_equal(gf_config_set(&c, "packing.file=a=b.dump", "--set"), GF_OK);
    assert_int_equal(gf_config_set(&c, "relax.radius=7", NULL), GF_OK);
    assert_true(c.spot_w == 400);
    assert_true(c.spot_radius == 3);
    assert_int_equal(c.orifice_shape, GF_ORIFICE_SLIT);
    assert_string_equal(c.packing_file, "a=b.dump");
    assert_true(c.relax_radius == 7);
    assert_int_equal(gf_config_set(&c, "relax.radius=auto", "--set"), GF_OK);
    assert_true(isnan(c.relax_radius));
    assert_int_equal(gf_config_set(&c, "packing.file=", "--set"), GF_OK);
    assert_string_equal(c.packing_file, "");
}

static void set_errors(void **state)
{
    (void)state;
    expect_set_error("spot.w=abc", "--set spot.w=abc: not a number");
    expect_set_error("relax.alpha=1.5", "--set relax.alpha=1.5: out of range (0, 1]");
    expect_set_error("relax.alpha=-1", "out of range (0, 1]");
    expect_set_error("spot.raduis=2", "unknown key 'raduis' in section [spot]");
    expect_set_error("spt.w=2", "unknown section [spt]");
    expect_set_error("spotw=2", "--set spotw=2: malformed assignment");
    expect_set_error("spot.w", "--set spot.w: malformed assignment");
    expect_set_error(".w=3", "malformed assignment");
    expect_set_error("spot.=3", "malformed assignment");
    expect_set_error("spot.w=", "--set spot.w=: empty value");
    expect_set_error("container.orifice_shape=square", "not one of: circle, slit");
    // Sizes are bounded like container.width: 1e300 once reached the packing
    // generator (200000 futile sweeps, rc 1) or the grid ("6.7e299 cells").
    expect_set_error("container.outlet_length=1e300", "out of range [0, 100000]");
    expect_set_error("container.exit_z=-1e300", "out of range [-100000, 0.5]");
    expect_set_error("container.radius=1e20", "out of range (0, 50000]");
    expect_set_error("container.outlet_diameter=1e300", "out of range (0, 100000]");
    expect_set_error("container.inner_radius=1e300", "out of range [0, 50000]");
}

// ---- validation ------------------------------------------------------------

static void validate_resolves_auto(void **state)
{
    (void)state;
    gf_config c = gf_config_default();
    assert_int_equal(gf_config_set(&c, "spot.radius=3", "--set"), GF_OK);
    assert_int_equal(gf_config_validate(&c), GF_OK);
    assert_true(c.relax_radius == 3 + 1);
    assert_true(c.spot_insertion_margin == 3);
    // Explicit values are kept.
    gf_config e = gf_config_default();
    e.relax_radius = 2.7;
    e.spot_insertion_margin = 0;
    assert_int_equal(gf_config_validate(&e), GF_OK);
    assert_true(e.relax_radius == 2.7);
    assert_true(e.spot_insertion_margin == 0);
}

static void expect_invalid(gf_config *c, const char *part1, const char *part2)
{
    gf_status st = gf_config_validate(c);
    if (st != GF_ERR_PARAM)
        fail_msg("validate gave %s, expected an error naming %s", gf_status_str(st), part1);
    assert_contains(gf_last_error(), part1);
    if (part2) assert_contains(gf_last_error(), part2);
}

static void validate_rejects_cross_key(void **state)
{
    (void)state;
    gf_config c = gf_config_default();
    c.orifice_diameter = 50;
    expect_invalid(&c, "container.orifice_diameter = 50", "container.width = 50");
    c = gf_config_default();
    c.orifice_diameter = 60;
    c.orifice_shape = GF_ORIFICE_SLIT;
    expect_invalid(&c, "container.orifice_diameter", "container.width");
    c = gf_config_default();
    c.orifice_diameter = 12; // wider than the depth: allowed
    assert_int_equal(gf_config_validate(&c), GF_OK);
    c = gf_config_default();
    c.spot_wall_distance = 4;
    expect_invalid(&c, "spot.wall_distance = 4", "min(container.width, container.depth) = 8");
    c.spot_wall_distance = 3.99;
    assert_int_equal(gf_config_validate(&c), GF_OK);
    c = gf_config_default();
    c.relax_radius = 2.5;
    expect_invalid(&c, "relax.radius = 2.5", "spot.radius = 2.6");
    c = gf_config_default();
    c.output_snapshot_interval = 100; // longer than the run: allowed
    assert_int_equal(gf_config_validate(&c), GF_OK);
}

// Loads `text` as file `name`, applies `set` (NULL: none) as --set, and
// expects validation to fail with exactly `want`, where "@" stands for the
// file's path.
static void expect_validate_message(const char *name, const char *text, const char *set, const char *want)
{
    char path[1024], full[4096];
    snprintf(path, sizeof path, "%s", ini(name, text));
    size_t n = 0;
    for (const char *p = want; *p && n + 1 < sizeof full; p++) {
        if (*p == '@') n += (size_t)snprintf(full + n, sizeof full - n, "%s", path);
        else full[n++] = *p;
        if (n >= sizeof full) n = sizeof full - 1;
    }
    full[n] = '\0';
    gf_config c = gf_config_default();
    assert_int_equal(gf_config_load(&c, path), GF_OK);
    if (set) assert_int_equal(gf_config_set(&c, set, "--set"), GF_OK);
    assert_int_equal(gf_config_validate(&c), GF_ERR_PARAM);
    assert_string_equal(gf_last_error(), full);
}

// Validation names where each key it quotes was set: FILE:LINE, --set or default.
static void validate_names_where_keys_were_set(void **state)
{
    (void)state;
    expect_validate_message("w1.ini", "[container]\nwidth = 50\norifice_diameter = 60\n", NULL,
                            "@:3: container.orifice_diameter = 60 must be less than container.width = 50 (@:2)");
    expect_validate_message("w2.ini", "[container]\norifice_diameter = 60\n", "container.width=40",
                            "@:2: container.orifice_diameter = 60 must be less than container.width = 40 (--set)");
    expect_validate_message("w3.ini", "[spot]\n\nradius = 3\n", "relax.radius=2",
                            "--set: relax.radius = 2 must be at least spot.radius = 3 (@:3)");
    expect_validate_message("w4.ini", "; a comment\n[packing]\ntypes = 1,x\n", NULL,
                            "@:3: packing.types = 1,x: 'x' is not an atom type (an integer >= 1)");
    expect_validate_message("w5.ini", "[dem]\ntimestep = 0.005\n", NULL,
                            "@:2: dem.timestep = 0.005 is too long for dem.kn = 200000 (default): at most 0.2 pi / "
                            "sqrt(2 kn) = 0.000993 tau");
    expect_validate_message("w6.ini", "[run]\nreinsert = zone\nreinsert_rmin = 5\nreinsert_rmax = 4\n", NULL,
                            "@:3: run.reinsert_rmin = 5 must be less than run.reinsert_rmax = 4 (@:4)");
    expect_validate_message("w7.ini", "[container]\nshape = cylinder\nradius = 5\noutlet_diameter = 12\n", NULL,
                            "@:4: container.outlet_diameter = 12 must be less than the cylinder's diameter 2R = 10 "
                            "(container.radius = 5 (@:3))");
    // Issue 26: the bounds worked out (the old text ended "2 * container.radius = 5",
    // read as a bound of 5), and a column whose gap to the funnel is too narrow.
    expect_validate_message("w7b.ini", "[container]\nshape = cylinder\nradius = 6\nhopper_angle = 30\ninner_radius = 5.5\n",
                            NULL,
                            "@:5: container.inner_radius = 5.5 leaves no room for a sphere: it must be less than "
                            "R - 1 = 5 (container.radius = 6 (@:3))");
    expect_validate_message("w7c.ini", "[container]\nshape = cylinder\ninner_radius = 2\nhopper_angle = 1e-300\n",
                            NULL,
                            "@:3: container.inner_radius = 2 with container.hopper_angle = 1e-300 (@:4) puts the "
                            "column's bottom 1.48e-301 d above the outlet, too low for a sphere under it, over the "
                            "whole disc where spots are born (radius container.outlet_diameter / 2 - "
                            "spot.insertion_margin = 1.4): every spot would be removed at its first step and nothing "
                            "could drain (raise container.hopper_angle to at least 6.71, or lower "
                            "container.inner_radius below 1.4)");
    expect_validate_message("w7d.ini",
                            "[container]\nshape = cylinder\nradius = 6\noutlet_diameter = 4\ninner_radius = 2\n"
                            "hopper_angle = 13\n",
                            NULL,
                            "@:5: container.inner_radius = 2 with container.hopper_angle = 13 (@:6) leaves a gap of "
                            "0.9 d between the column's bottom (z = 0.923) and the funnel, narrower than a sphere: "
                            "nothing could reach the outlet (raise container.hopper_angle, or lower "
                            "container.inner_radius)");
    expect_validate_message("w8.ini", "[spot]\nwall_distance = 4.5\n", NULL,
                            "@:2: spot.wall_distance = 4.5 leaves spots no room: 2 * spot.wall_distance must be "
                            "less than min(container.width, container.depth) = 8 (container.depth = 8 (default))");

    // gf_config_where / gf_config_is_set, and a copy keeps the record.
    const char *path = ini("w9.ini", "[container]\n\n  width = 30\n");
    gf_config c = gf_config_default();
    assert_int_equal(gf_config_load(&c, path), GF_OK);
    assert_int_equal(gf_config_set(&c, "spot.w=3", "--set"), GF_OK);
    char buf[1100], want[1100];
    snprintf(want, sizeof want, "%s:3", path);
    assert_int_equal(gf_config_where(&c, "container.width", buf, sizeof buf), GF_OK);
    assert_string_equal(buf, want);
    assert_int_equal(gf_config_where(&c, "spot.w", buf, sizeof buf), GF_OK);
    assert_string_equal(buf, "--set");
    assert_int_equal(gf_config_where(&c, "spot.radius", buf, sizeof buf), GF_OK);
    assert_string_equal(buf, "default");
    assert_int_equal(gf_config_where(&c, "spot.nope", buf, sizeof buf), GF_ERR_PARAM);
    assert_true(gf_config_is_set(&c, "container.width") && gf_config_is_set(&c, "spot.w"));
    assert_false(gf_config_is_set(&c, "spot.radius") || gf_config_is_set(&c, "nope"));
    gf_config *copy = gf_config_create();
    assert_int_equal(gf_config_copy(copy, &c), GF_OK);
    assert_int_equal(gf_config_where(copy, "container.width", buf, sizeof buf), GF_OK);
    assert_string_equal(buf, want);
    gf_config_destroy(copy);
    // A later assignment moves the record; set by name it says so.
    assert_int_equal(gf_config_set_key(&c, "container.width", "31"), GF_OK);
    assert_int_equal(gf_config_where(&c, "container.width", buf, sizeof buf), GF_OK);
    assert_string_equal(buf, "gf_config_set_key");
}

// In a cylinder the outlet is container.outlet_diameter: an orifice_diameter
// set apart from it is refused naming both keys; granflow's own effective
// config (both equal, one file) reads back, with an outlet --set over it.
static void cylinder_orifice_diameter_is_refused(void **state)
{
    (void)state;
    expect_validate_message("c1.ini", "[container]\nshape = cylinder\norifice_diameter = 6\n", NULL,
                            "@:3: container.orifice_diameter = 6 does nothing in a cylinder (container.shape = "
                            "cylinder), whose outlet is container.outlet_diameter = 8 (default): set that instead");
    expect_validate_message("c2.ini", "[container]\nshape = cylinder\noutlet_diameter = 5\norifice_diameter = 6\n",
                            NULL,
                            "@:4: container.orifice_diameter = 6 does nothing in a cylinder (container.shape = "
                            "cylinder), whose outlet is container.outlet_diameter = 5 (@:3): set that instead");
    // Equal to the outlet: nothing is lost.
    gf_config c = gf_config_default();
    assert_int_equal(gf_config_set(&c, "container.shape=cylinder", "--set"), GF_OK);
    assert_int_equal(gf_config_set(&c, "container.orifice_diameter=8", "--set"), GF_OK);
    assert_int_equal(gf_config_validate(&c), GF_OK);
    // The effective config of a cylinder reads back, and takes a new outlet.
    c = gf_config_default();
    assert_int_equal(gf_config_set(&c, "container.shape=cylinder", "--set"), GF_OK);
    assert_int_equal(gf_config_set(&c, "container.outlet_diameter=6", "--set"), GF_OK);
    assert_int_equal(gf_config_validate(&c), GF_OK);
    char path[1024];
    snprintf(path, sizeof path, "%s/cyl-effective.ini", gf_test_tmpdir());
    assert_int_equal(gf_config_save(&c, path), GF_OK);
    gf_config d = gf_config_default();
    assert_int_equal(gf_config_load(&d, path), GF_OK);
    assert_int_equal(gf_config_set(&d, "container.outlet_diameter=4", "--set"), GF_OK);
    assert_int_equal(gf_config_validate(&d), GF_OK);
    assert_true(d.orifice_diameter == 4);
    // A box keeps its orifice_diameter.
    c = gf_config_default();
    assert_int_equal(gf_config_set(&c, "container.orifice_diameter=6", "--set"), GF_OK);
    assert_int_equal(gf_config_validate(&c), GF_OK);
}

// Fields set directly (not through the parser) are range-checked too.
static void validate_rejects_bad_fields(void **state)
{
    (void)state;
    gf_config c = gf_config_default();
    c.spot_radius = 25;
    expect_invalid(&c, "spot.radius = 25", "out of range (0, 20]");
    c = gf_config_default();
    c.run_duration = NAN;
    expect_invalid(&c, "run.duration", "not a finite number");
    c = gf_config_default();
    c.packing_particles = 0;
    expect_invalid(&c, "packing.particles = 0", "out of range");
    c = gf_config_default();
    c.orifice_shape = (gf_orifice_shape)7;
    expect_invalid(&c, "container.orifice_shape", "circle, slit");
    c = gf_config_default();
    memset(c.packing_file, 'a', GF_PATH_MAX);
    expect_invalid(&c, "packing.file", "NUL");
}

static void cookie_is_checked(void **state)
{
    (void)state;
    gf_config c;
    memset(&c, 0, sizeof c);
    const char *want = "config not made by gf_config_default";
    assert_int_equal(gf_config_validate(&c), GF_ERR_PARAM);
    assert_contains(gf_last_error(), want);
    assert_int_equal(gf_config_set(&c, "spot.w=3", "--set"), GF_ERR_PARAM);
    assert_contains(gf_last_error(), want);
    assert_int_equal(gf_config_load(&c, "x.ini"), GF_ERR_PARAM);
    assert_contains(gf_last_error(), want);
    assert_int_equal(gf_config_write(&c, stdout), GF_ERR_PARAM);
    assert_contains(gf_last_error(), want);
    assert_int_equal(gf_config_save(&c, "x.ini"), GF_ERR_PARAM);
    assert_contains(gf_last_error(), want);
    assert_int_equal(gf_config_validate(NULL), GF_ERR_PARAM);
}

// ---- writing ---------------------------------------------------------------

static void round_trip(const gf_config *c, const char *name)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", gf_test_tmpdir(), name);
    if (gf_config_save(c, path) != GF_OK) fail_msg("save: %s", gf_last_error());
    gf_config back = gf_config_default();
    if (gf_config_load(&back, path) != GF_OK) fail_msg("load: %s", gf_last_error());
    assert_same_fields(c, &back);
}

static void round_trip_default(void **state)
{
    (void)state;
    gf_config c = gf_config_default();
    round_trip(&c, "default.ini");
    assert_int_equal(gf_config_validate(&c), GF_OK); // resolved auto keys are written as numbers
    round_trip(&c, "default-resolved.ini");
}

static void round_trip_modified(void **state)
{
    (void)state;
    gf_config c = gf_config_default();
    c.container_width = 0.1 + 0.2;
    c.container_depth = 1.0 / 3.0;
    c.orifice_shape = GF_ORIFICE_SLIT;
    c.orifice_diameter = 1e-300;
    c.exit_z = -0.0;
    c.packing_particles = 50000000;
    c.packing_fill_height = 12.5;
    snprintf(c.packing_file, sizeof c.packing_file, "some dir/packing #1;v=2.dump");
    c.packing_layer_thickness = 0.1; // the smallest accepted (issue 16: thinner bands overflow the tag)
    c.spot_radius = 20;
    c.spot_w = 1.7976931348623157e308;
    c.spot_insertion_rate = 3.141592653589793;
    c.spot_move_rate = 2.0 / 3.0;
    c.spot_step_xy = 0;
    c.spot_step_z = 0.1;
    c.spot_wall_distance = -2.5;
    c.spot_ball_centre = GF_BALL_END;
    c.spot_insertion_margin = 0;
    c.relax_alpha = 1;
    c.relax_radius = NAN; // unresolved auto
    c.run_duration = 1e-3;
    c.run_seed = UINT64_MAX;
    c.run_checkpoint_interval = 7;
    c.output_snapshot_interval = 0.7;
    round_trip(&c, "modified.ini");
    c.relax_radius = 39.999999999999993; // just under the largest accepted
    round_trip(&c, "modified2.ini");
}

static void write_format(void **state)
{
    (void)state;
    gf_config c = gf_config_default();
    char path[1024];
    snprintf(path, sizeof path, "%s/format.ini", gf_test_tmpdir());
    assert_int_equal(gf_config_save(&c, path), GF_OK);
    char tmp[1100];
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    assert_int_not_equal(access(tmp, F_OK), 0); // the temporary file was renamed
    char *text = gf_test_read_file(path, NULL);
    assert_non_null(text);
    assert_true(strncmp(text, "# granflow configuration (effective values)\n", 44) == 0);
    assert_contains(text, "\n[container]\n; container width (x), walls at x = +-width/2 [d], "
                          "default 50\nwidth = 50\n");
    assert_contains(text, "\nstep_xy = 0.676\n");
    assert_contains(text, "\nradius = auto\n");
    assert_contains(text, "\norifice_shape = circle\n");
    assert_contains(text, "\nfile =\n");
    assert_contains(text, "[output]\n");
    // No trailing white space; every key line follows its comment line.
    size_t keys = 0;
    const char *prev = NULL;
    for (char *line = strtok(text, "\n"); line; line = strtok(NULL, "\n")) {
        size_t n = strlen(line);
        if (n && (line[n - 1] == ' ' || line[n - 1] == '\t'))
            fail_msg("trailing space: '%s'", line);
        if (line[0] != ';' && line[0] != '#' && line[0] != '[') {
            keys++;
            assert_non_null(prev);
            assert_int_equal(prev[0], ';');
            assert_contains(prev, ", default ");
        }
        prev = line;
    }
    assert_int_equal(keys, gf_keys_count);
    free(text);
}

static void write_rejects_unwritable_path(void **state)
{
    (void)state;
    const char *bad[] = {"a\nb", " lead", "trail ", "x ;y", NULL};
    for (size_t i = 0; bad[i]; i++) {
        gf_config c = gf_config_default();
        snprintf(c.packing_file, sizeof c.packing_file, "%s", bad[i]);
        FILE *f = tmpfile();
        assert_non_null(f);
        assert_int_equal(gf_config_write(&c, f), GF_ERR_PARAM);
        assert_contains(gf_last_error(), "packing.file");
        fclose(f);
    }
    gf_config c = gf_config_default();
    memset(c.packing_file, 'p', 300);
    assert_int_equal(gf_config_write(&c, stdout), GF_ERR_PARAM);
    assert_contains(gf_last_error(), "too long");
}

static void save_reports_io_errors(void **state)
{
    (void)state;
    gf_config c = gf_config_default();
    char path[1024];
    snprintf(path, sizeof path, "%s/no/such/dir/x.ini", gf_test_tmpdir());
    assert_int_equal(gf_config_save(&c, path), GF_ERR_IO);
    assert_contains(gf_last_error(), "no/such/dir/x.ini.tmp");
    // Renaming onto a directory fails; the temporary file is then removed.
    char dir[1024], tmp[1100];
    snprintf(dir, sizeof dir, "%s/a-dir", gf_test_tmpdir());
    assert_int_equal(mkdir(dir, 0700), 0);
    gf_test_write_file(dir, "keep", "x");
    assert_int_equal(gf_config_save(&c, dir), GF_ERR_IO);
    assert_contains(gf_last_error(), "cannot rename");
    snprintf(tmp, sizeof tmp, "%s.tmp", dir);
    assert_int_not_equal(access(tmp, F_OK), 0);
    // A directory cannot be written to.
    assert_int_equal(gf_config_load(&c, dir), GF_ERR_IO);
}

// output.format is a list of formats: today's words (dump, vtk, both) mean
// what they meant, `both` stands for `dump,vtk`, the list reads back in table
// order, and a bad element is named with its place in the list.
static void output_format_is_a_list(void **state)
{
    (void)state;
    static const struct {
        const char *value;
        int bits;
        const char *back;
    } ok[] = {{"dump", GF_OUTPUT_DUMP, "dump"},
              {"vtk", GF_OUTPUT_VTK, "vtk"},
              {"both", GF_OUTPUT_DUMP | GF_OUTPUT_VTK, "dump,vtk"},
              {"dump,vtk", GF_OUTPUT_BOTH, "dump,vtk"},
              {"vtk, dump", GF_OUTPUT_BOTH, "dump,vtk"},
              {" vtk ,dump ", GF_OUTPUT_BOTH, "dump,vtk"}};
    for (size_t i = 0; i < sizeof ok / sizeof ok[0]; i++) {
        gf_config cfg = gf_config_default();
        char a[64], back[64];
        snprintf(a, sizeof a, "output.format=%s", ok[i].value);
        if (gf_config_set(&cfg, a, "--set") != GF_OK) fail_msg("%s: %s", a, gf_last_error());
        assert_int_equal((int)cfg.output_format, ok[i].bits);
        assert_int_equal(gf_config_get_key(&cfg, "output.format", back, sizeof back), GF_OK);
        assert_string_equal(back, ok[i].back);
        assert_int_equal(gf_config_validate(&cfg), GF_OK);
    }
    assert_int_equal((int)gf_config_default().output_format, GF_OUTPUT_DUMP);
    expect_set_error("output.format=dump,stl", "output.format=dump,stl: element 2 'stl' is not one of: dump, vtk");
    expect_set_error("output.format=xyz", "element 1 'xyz' is not one of: dump, vtk; both = dump,vtk");
    expect_set_error("output.format=dump,,vtk", "element 2 '' is not one of");
    expect_set_error("output.format=dump,both", "element 2 'both' is not one of");
    expect_set_error("output.format=vtk,vtk", "element 2 'vtk' is listed twice");
    expect_load_error("format.ini", "[output]\nformat = dump, pdf\n", 2, "[output] format = 'dump, pdf': element 2 'pdf'");
}

// ---- docs ------------------------------------------------------------------

// docs/config.md has a row for every key with its default and range.
static void docs_list_every_key(void **state)
{
    (void)state;
    char *doc = gf_test_read_file(GF_TEST_DATA "/../../docs/config.md", NULL);
    if (!doc) fail_msg("cannot read docs/config.md");
    for (size_t i = 0; i < gf_keys_count; i++) {
        const gf_key *k = &gf_keys[i];
        char cell[128], range[96];
        snprintf(cell, sizeof cell, "| `%s.%s` |", k->section, k->name);
        const char *row = strstr(doc, cell);
        if (!row) fail_msg("docs/config.md lacks a row starting '%s'", cell);
        const char *eol = strchr(row, '\n');
        size_t len = eol ? (size_t)(eol - row) : strlen(row);
        char line[1024];
        snprintf(line, sizeof line, "%.*s", (int)len, row);
        if (*k->def) {
            snprintf(cell, sizeof cell, "| %s |", k->def);
            assert_contains(line, cell);
        }
        gf_keys_range(k, range, sizeof range);
        snprintf(cell, sizeof cell, "| %s |", range);
        if (k->type != GF_KEY_PATH) assert_contains(line, cell);
    }
    free(doc);
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(defaults_match_spec),
    cmocka_unit_test(key_table_covers_struct),
    cmocka_unit_test(defaults_match_key_table),
    cmocka_unit_test(load_sets_several_keys),
    cmocka_unit_test(load_accepts_layout_variants),
    cmocka_unit_test(output_format_is_a_list),
    cmocka_unit_test(load_unknown_section),
    cmocka_unit_test(load_unknown_empty_section),
    cmocka_unit_test(load_unknown_key),
    cmocka_unit_test(load_not_a_number),
    cmocka_unit_test(load_trailing_garbage),
    cmocka_unit_test(load_below_range),
    cmocka_unit_test(load_above_range),
    cmocka_unit_test(load_integer_errors),
    cmocka_unit_test(load_rejects_nan_inf),
    cmocka_unit_test(load_empty_value),
    cmocka_unit_test(load_bad_enum),
    cmocka_unit_test(load_key_before_section),
    cmocka_unit_test(load_syntax_error),
    cmocka_unit_test(load_line_too_long),
    cmocka_unit_test(load_reports_first_error),
    cmocka_unit_test(load_missing_file),
    cmocka_unit_test(set_works),
    cmocka_unit_test(set_errors),
    cmocka_unit_test(validate_resolves_auto),
    cmocka_unit_test(validate_rejects_cross_key),
    cmocka_unit_test(validate_rejects_bad_fields),
    cmocka_unit_test(validate_names_where_keys_were_set),
    cmocka_unit_test(cylinder_orifice_diameter_is_refused),
    cmocka_unit_test(cookie_is_checked),
    cmocka_unit_test(round_trip_default),
    cmocka_unit_test(round_trip_modified),
    cmocka_unit_test(write_format),
    cmocka_unit_test(write_rejects_unwritable_path),
    cmocka_unit_test(save_reports_io_errors),
    cmocka_unit_test(docs_list_every_key),
};

GF_TEST_MAIN("config", tests)
