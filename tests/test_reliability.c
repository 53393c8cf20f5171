// SPDX-License-Identifier: MIT
// Issue 16 at the library level: sizes that cannot wrap around, loops that
// stop on the stop flag, messages that keep their reason and never carry raw
// binary bytes. (tests/cli/reliability.sh checks the same through the CLI.)
#include "support.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>
#include <zlib.h>

#include "core/alloc.h"
#include "core/error.h"
#include "core/rng.h"
#include "granflow/granflow.h"

// n * size beyond SIZE_MAX is refused, not wrapped to a small block.
static void alloc_refuses_wrapping_sizes(void **state)
{
    (void)state;
    assert_null(gf_alloc_array(SIZE_MAX / 8 + 2, 8));
    assert_null(gf_alloc_array((size_t)1 << 62, 16));
    assert_null(gf_alloc(SIZE_MAX - 10)); // rounding up to 64 bytes would wrap
    double *p = GF_NEW(double, 3);
    assert_non_null(p);
    GF_DELETE(p, 3);
}

// A mean beyond 2^63 used to be cast to uint64 (undefined; 0 on x86).
static void poisson_of_a_huge_mean_is_huge(void **state)
{
    (void)state;
    gf_rng r;
    gf_rng_seed(&r, 1, 2);
    assert_true(gf_rng_poisson(&r, 1e308) >= UINT64_C(1) << 63);
    assert_true(gf_rng_poisson(&r, 1e19) >= UINT64_C(1) << 63);
    uint64_t k = gf_rng_poisson(&r, 1e6); // still the normal approximation: within 10 sd
    assert_true(k > 1e6 - 1e4 && k < 1e6 + 1e4);
}

// Band tags of far particles or hair-thin bands are clamped, never undefined.
static void layer_tags_are_clamped(void **state)
{
    (void)state;
    gf_packing p = {0};
    assert_int_equal(gf_packing_push(&p, 1, 0, 0, 0, 0.5, 0.5), GF_OK);
    assert_int_equal(gf_packing_push(&p, 2, 0, 0, 0, 25.0, 0.5), GF_OK);
    gf_packing_tag_layers(&p, 1e-300);
    assert_true(p.layer[0] > 0 && p.layer[1] > 0);
    assert_true(p.layer[1] >= p.layer[0]);
    gf_packing_tag_layers(&p, 10);
    assert_int_equal(p.layer[0], 1);
    assert_int_equal(p.layer[1], 3);
    gf_packing_free(&p);
}

// The generator refuses a footprint it cannot count cells for (a config not
// validated, as a library caller may pass), and stops on the flag.
static void generator_checks_sizes_and_stops(void **state)
{
    (void)state;
    gf_config c = gf_test_silo_config(12, 200, 1);
    gf_packing pk = {0};
    c.container_width = 1e20;
    assert_int_equal(gf_packing_generate(&c, NULL, &pk), GF_ERR_PARAM);
    assert_non_null(strstr(gf_last_error(), "larger than the generator's limit"));
    c = gf_test_silo_config(12, 200, 1);
    volatile sig_atomic_t stop = 1;
    assert_int_equal(gf_packing_generate(&c, &(gf_packing_opts){.stop = &stop}, &pk), GF_ERR_INTERRUPTED);
    assert_int_equal(pk.n, 0);
    stop = 0;
    assert_int_equal(gf_packing_generate(&c, &(gf_packing_opts){.stop = &stop}, &pk), GF_OK);
    assert_int_equal(pk.n, 200);
    gf_packing_free(&pk);
}

typedef struct snap_ctx {
    volatile sig_atomic_t *stop;
    int calls;
} snap_ctx;

static gf_status stop_at_first_snapshot(void *ctx, const gf_sim *sim, uint64_t index, double time)
{
    (void)sim;
    (void)index;
    (void)time;
    snap_ctx *s = ctx;
    s->calls++;
    *s->stop = 1; // as SIGTERM would, between two snapshots due at once
    return GF_OK;
}

// Many snapshots due before the next event: the stop flag ends the burst.
static void snapshot_burst_stops_on_the_flag(void **state)
{
    (void)state;
    gf_config c = gf_test_silo_config(12, 200, 1);
    c.output_snapshot_interval = 1e-4; // ~ a hundred snapshots due before the first event
    c.run_duration = 1;
    assert_int_equal(gf_config_validate(&c), GF_OK);
    gf_sim *sim = gf_test_generated_sim(&c);
    volatile sig_atomic_t stop = 0;
    snap_ctx s = {&stop, 0};
    gf_sim_hooks h = {.ctx = &s, .snapshot = stop_at_first_snapshot, .stop = &stop};
    assert_int_equal(gf_sim_run(sim, c.run_duration, &h), GF_ERR_INTERRUPTED);
    assert_int_equal(s.calls, 1);
    gf_sim_destroy(sim);
}

// The library calls behind analyze, render, bench, dem and calibrate return
// GF_ERR_INTERRUPTED on the flag and write nothing that looks complete.
static void long_calls_stop_on_the_flag(void **state)
{
    (void)state;
    volatile sig_atomic_t stop = 1;
    gf_config c = gf_test_silo_config(12, 200, 1);
    gf_sim *sim = NULL;
    assert_int_equal(gf_sim_create_from_config(&c, &(gf_packing_opts){.stop = &stop}, &sim), GF_ERR_INTERRUPTED);
    assert_null(sim);
    char dir[4096], path[4200];
    snprintf(dir, sizeof dir, "%s/dem", gf_test_tmpdir());
    c.dem_fill_method = GF_DEM_GENERATE;
    assert_int_equal(gf_dem_write_inputs(&c, dir, &(gf_packing_opts){.stop = &stop}, NULL), GF_ERR_INTERRUPTED);
    assert_int_equal(access(dir, F_OK), -1); // the packing comes before any file
    gf_bench_opts bo = gf_bench_opts_default();
    bo.large = false;
    bo.stop = &stop;
    gf_bench_report br;
    assert_int_equal(gf_bench(&c, &bo, &br), GF_ERR_INTERRUPTED);

    // A run directory of a few snapshots: reading, analysing, drawing it stop.
    c = gf_test_silo_config(12, 200, 1);
    c.run_duration = 1;
    c.output_snapshot_interval = 0.25;
    snprintf(dir, sizeof dir, "%s/run", gf_test_tmpdir());
    gf_run_opts ro = gf_run_opts_default();
    ro.dir = dir;
    assert_int_equal(gf_run_dir(&c, &ro, NULL), GF_OK);
    gf_series s;
    assert_int_equal(gf_series_load(dir, 0.0, &(gf_series_opts){.stop = &stop}, &s), GF_ERR_INTERRUPTED);
    assert_int_equal(s.nframes, 0);
    assert_int_equal(gf_series_load(dir, 0.0, NULL, &s), GF_OK);
    gf_analysis_opts o = gf_analysis_opts_default();
    o.stop = &stop;
    snprintf(path, sizeof path, "%s/analysis", dir);
    assert_int_equal(gf_analyze(&s, &o, NULL, path, false), GF_ERR_INTERRUPTED);
    snprintf(path, sizeof path, "%s/analysis/summary.json", dir);
    assert_int_equal(access(path, F_OK), -1);
    for (size_t k = 0; k < 2; k++) { // in a measurement's frame loop, not only between them
        gf_measure_out m = {0};
        gf_status st = (k ? gf_measure_velocity : gf_measure_voronoi)(&s, &o, &m);
        gf_measure_free(&m);
        assert_int_equal(st, GF_ERR_INTERRUPTED);
    }
    gf_series_free(&s);
    gf_render_dir_opts rd = gf_render_dir_opts_default();
    rd.stop = &stop;
    assert_int_equal(gf_render_dir(dir, &rd), GF_ERR_INTERRUPTED);
}

// Control bytes and invalid UTF-8 are written \xNN; valid UTF-8 stays.
static void messages_escape_binary_bytes(void **state)
{
    (void)state;
    gf_error_set(GF_ERR_FORMAT, "bad '%s'", "a\001\033[2J\377z \xce\xb1");
    assert_string_equal(gf_last_error(), "bad 'a\\x01\\x1B[2J\\xFFz \xce\xb1'");
    char out[8];
    assert_int_equal(gf_escape("\n\n", out, sizeof out), 8); // full length, as snprintf
    assert_string_equal(out, "\\x0A\\x0");
}

// A message longer than the buffer loses its middle, never its reason.
static void long_messages_keep_their_end(void **state)
{
    (void)state;
    size_t n = 20000;
    char *path = malloc(n + 1);
    memset(path, 'p', n);
    path[n] = '\0';
    gf_error_set(GF_ERR_IO, "cannot write %s: %s", path, "No space left on device");
    const char *e = gf_last_error();
    assert_true(strlen(e) < 4096);
    assert_true(strncmp(e, "cannot write ppp", 16) == 0);
    assert_non_null(strstr(e, " ... "));
    size_t len = strlen(e);
    assert_string_equal(e + len - strlen("pp: No space left on device"), "pp: No space left on device");
    free(path);
}

// The first occurrence of `s` in the len bytes at d, or NULL.
static char *find_bytes(char *d, size_t len, const char *s)
{
    size_t n = strlen(s);
    for (size_t i = 0; i + n <= len; i++)
        if (memcmp(d + i, s, n) == 0) return d + i;
    return NULL;
}

// The checkpoint at `path` with the first occurrence of `from` in its
// stored configuration text replaced by `to` (same length), its CRC-32 redone.
static void patch_checkpoint(const char *path, const char *from, const char *to)
{
    size_t len;
    char *d = gf_test_read_file(path, &len);
    const size_t head = 8 + 4 + 4 + 8 + 4;
    char *at = find_bytes(d + head, len - head, from);
    assert_non_null(at);
    memcpy(at, to, strlen(to));
    uint32_t crc = (uint32_t)crc32(crc32(0L, Z_NULL, 0), (const Bytef *)d + head, (uInt)(len - head));
    memcpy(d + 24, &crc, 4);
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(d, 1, len, f), len);
    fclose(f);
    free(d);
}

// A checkpoint compares settings, not comments: a key's documentation may
// change between versions and the run still resumes; a changed value is
// refused, naming its key.
static void checkpoint_compares_settings_not_comments(void **state)
{
    (void)state;
    gf_config c = gf_test_silo_config(10, 300, 3);
    gf_sim *sim = gf_test_generated_sim(&c);
    char path[600];
    snprintf(path, sizeof path, "%s/ck_comments.bin", gf_test_tmpdir());
    assert_int_equal(gf_sim_save(sim, path), GF_OK);
    gf_sim_destroy(sim);
    size_t len;
    char *d = gf_test_read_file(path, &len);
    assert_non_null(find_bytes(d, len, "; spot radius r_s")); // the doc line this test edits
    free(d);
    patch_checkpoint(path, "; spot radius r_s", "; SPOT RADIUS R_S");
    gf_sim *back = NULL;
    assert_int_equal(gf_sim_load(&c, path, &back), GF_OK);
    gf_sim_destroy(back);
    patch_checkpoint(path, "\nradius = 2.6\n", "\nradius = 2.7\n");
    assert_int_equal(gf_sim_load(&c, path, &back), GF_ERR_PARAM);
    assert_non_null(strstr(gf_last_error(), "spot.radius differs"));
}

// A checkpoint of a version that did not have a key (here container.orifice_x,
// its line turned into a comment) resumes while the key is at its default,
// and is refused, naming the key, once it is not.
static void checkpoint_of_an_older_version_resumes(void **state)
{
    (void)state;
    gf_config c = gf_test_silo_config(10, 300, 3);
    gf_sim *sim = gf_test_generated_sim(&c);
    char path[600];
    snprintf(path, sizeof path, "%s/ck_older.bin", gf_test_tmpdir());
    assert_int_equal(gf_sim_save(sim, path), GF_OK);
    gf_sim_destroy(sim);
    patch_checkpoint(path, "\norifice_x = 0\n", "\n; 3456789012\n");
    gf_sim *back = NULL;
    assert_int_equal(gf_sim_load(&c, path, &back), GF_OK);
    gf_sim_destroy(back);
    c.orifice_x = 0.5;
    assert_int_equal(gf_sim_load(&c, path, &back), GF_ERR_PARAM);
    assert_non_null(strstr(gf_last_error(), "container.orifice_x differs"));
}

// A checkpoint of a version without a whole section (here [dump], its
// header and keys turned into comments) resumes while its keys are at their
// defaults, and is refused, naming the key, once one is not.
static void checkpoint_without_a_new_section_resumes(void **state)
{
    (void)state;
    gf_config c = gf_test_silo_config(10, 300, 3);
    gf_sim *sim = gf_test_generated_sim(&c);
    char path[600];
    snprintf(path, sizeof path, "%s/ck_nosection.bin", gf_test_tmpdir());
    assert_int_equal(gf_sim_save(sim, path), GF_OK);
    gf_sim_destroy(sim);
    patch_checkpoint(path, "\n[dump]\n", "\n;dump]\n");
    patch_checkpoint(path, "\ndiameter = 1\n", "\n;iameter = 1\n");
    patch_checkpoint(path, "\ngravity = 1\n", "\n;ravity = 1\n");
    gf_sim *back = NULL;
    assert_int_equal(gf_sim_load(&c, path, &back), GF_OK);
    gf_sim_destroy(back);
    c.dump_diameter = 0.004;
    assert_int_equal(gf_sim_load(&c, path, &back), GF_ERR_PARAM);
    assert_non_null(strstr(gf_last_error(), "dump.diameter differs"));
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(checkpoint_compares_settings_not_comments),
    cmocka_unit_test(checkpoint_without_a_new_section_resumes),
    cmocka_unit_test(checkpoint_of_an_older_version_resumes),
    cmocka_unit_test(alloc_refuses_wrapping_sizes),
    cmocka_unit_test(poisson_of_a_huge_mean_is_huge),
    cmocka_unit_test(layer_tags_are_clamped),
    cmocka_unit_test(generator_checks_sizes_and_stops),
    cmocka_unit_test(snapshot_burst_stops_on_the_flag),
    cmocka_unit_test(long_calls_stop_on_the_flag),
    cmocka_unit_test(messages_escape_binary_bytes),
    cmocka_unit_test(long_messages_keep_their_end),
};

GF_TEST_MAIN("reliability", tests)
