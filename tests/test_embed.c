// SPDX-License-Identifier: MIT
// The embedding API: config keys by name, warnings, allocator and assert
// hooks, the version, and a simulation read through flat arrays.
#include "support.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/options.h"
#include "config/keys.h"
#include "core/alloc.h"
#include "core/error.h"
#include "granflow/granflow.h"

// A valid value of key k other than its default, as INI text (from the
// table's type and range; the public API then has to accept it).
static void other_value(const gf_key *k, char *buf, size_t n)
{
    switch (k->type) {
    case GF_KEY_SET: // every name but the default's first, as a list ("vtk")
    case GF_KEY_ENUM: {
        size_t m = 0;
        while (k->names[m]) m++;
        snprintf(buf, n, "%s", strcmp(k->names[m - 1], k->def) ? k->names[m - 1] : k->names[0]);
        return;
    }
    case GF_KEY_PATH: snprintf(buf, n, "/tmp/a dir/%s.dump", k->name); return;
    case GF_KEY_UINT64: snprintf(buf, n, "18446744073709551557"); return;
    case GF_KEY_LIST: { // two increasing values in range
        double lo = fmax(k->min, -1e3), hi = fmin(k->max, 1e3);
        char a[32], b[32];
        gf_keys_format_double(lo + 0.25 * (hi - lo), a, sizeof a);
        gf_keys_format_double(lo + 0.625 * (hi - lo), b, sizeof b);
        snprintf(buf, n, "%s,%s", a, b);
        return;
    }
    case GF_KEY_DOUBLE:
    case GF_KEY_AUTO:
    case GF_KEY_INT64:
    case GF_KEY_SIZE: break;
    }
    double lo = k->min, hi = k->max, v;
    if (isfinite(lo) && isfinite(hi)) v = lo + 0.375 * (hi - lo);
    else if (isfinite(lo)) v = lo + 1.375;
    else if (isfinite(hi)) v = hi - 1.375;
    else v = -3.125;
    if (k->type == GF_KEY_INT64 || k->type == GF_KEY_SIZE) {
        v = floor(v) + (v == floor(v) ? 1 : 0);
        snprintf(buf, n, "%.0f", v);
        if (!strcmp(buf, k->def)) snprintf(buf, n, "%.0f", v + 1); // a value other than the default
    } else {
        gf_keys_format_double(v, buf, n);
    }
    GF_ASSERT(strcmp(buf, k->def) != 0);
}

static void config_get_set_round_trip_every_key(void **state)
{
    (void)state;
    gf_config *cfg = gf_config_create();
    assert_non_null(cfg);
    const size_t nkeys = gf_config_key_count();
    assert_int_equal(nkeys, gf_keys_count);
    char name[128], got[GF_PATH_MAX + 64], want[GF_PATH_MAX + 64];
    for (size_t i = 0; i < nkeys; i++) {
        assert_int_equal(gf_config_key_name(i, name, sizeof name), GF_OK);
        assert_non_null(gf_config_key_doc(i));
        // The default reads back as the table spells it.
        assert_int_equal(gf_config_get_key(cfg, name, got, sizeof got), GF_OK);
        assert_string_equal(got, gf_config_key_default(i));
        // Another valid value goes in and comes back the same text.
        other_value(&gf_keys[i], want, sizeof want);
        if (gf_config_set_key(cfg, name, want) != GF_OK) fail_msg("%s = %s: %s", name, want, gf_last_error());
        assert_int_equal(gf_config_get_key(cfg, name, got, sizeof got), GF_OK);
        if (strcmp(got, want)) fail_msg("%s: set %s, got %s", name, want, got);
    }
    // Every field changed: none of the keys reads its default any more, and a
    // second config set key by key from the first reads back identically.
    gf_config *copy = gf_config_create();
    for (size_t i = 0; i < nkeys; i++) {
        assert_int_equal(gf_config_key_name(i, name, sizeof name), GF_OK);
        assert_int_equal(gf_config_get_key(cfg, name, got, sizeof got), GF_OK);
        assert_string_not_equal(got, gf_config_key_default(i));
        assert_int_equal(gf_config_set_key(copy, name, got), GF_OK);
    }
    assert_memory_equal(cfg, copy, sizeof *cfg);
    gf_config_destroy(copy);
    gf_config_destroy(cfg);
}

// The analysis options go through the same key tables: every option's
// default reads back as the table spells it, another valid value set by name
// reads back the same, and a second set of options set option by option from
// the first is the same bytes.
static void analysis_get_set_round_trip_every_key(void **state)
{
    (void)state;
    gf_analysis_opts o, copy;
    o = gf_analysis_opts_default();
    copy = gf_analysis_opts_default();
    const size_t nkeys = gf_analysis_opts_key_count();
    assert_int_equal(nkeys, gf_analysis_keys.count);
    assert_true(nkeys >= 28);
    char name[128], got[256], want[256], kv[400];
    for (size_t i = 0; i < nkeys; i++) {
        assert_int_equal(gf_analysis_opts_key_name(i, name, sizeof name), GF_OK);
        assert_non_null(gf_analysis_opts_key_doc(i));
        assert_int_equal(gf_analysis_opts_get(&o, name, got, sizeof got), GF_OK);
        assert_string_equal(got, gf_analysis_opts_key_default(i));
        other_value(&gf_analysis_keys.keys[i], want, sizeof want);
        snprintf(kv, sizeof kv, "%s=%s", name, want);
        if (gf_analysis_opts_set(&o, kv) != GF_OK) fail_msg("%s: %s", kv, gf_last_error());
        assert_int_equal(gf_analysis_opts_get(&o, name, got, sizeof got), GF_OK);
        if (strcmp(got, want)) fail_msg("%s: set %s, got %s", name, want, got);
    }
    for (size_t i = 0; i < nkeys; i++) {
        assert_int_equal(gf_analysis_opts_key_name(i, name, sizeof name), GF_OK);
        assert_int_equal(gf_analysis_opts_get(&o, name, got, sizeof got), GF_OK);
        assert_string_not_equal(got, gf_analysis_opts_key_default(i));
        snprintf(kv, sizeof kv, "%s = %s", name, got);
        assert_int_equal(gf_analysis_opts_set(&copy, kv), GF_OK);
    }
    assert_memory_equal(&o, &copy, sizeof o);
    // "auto" goes back to the automatic window and zones.
    assert_int_equal(gf_analysis_opts_set(&o, "window.t0=auto"), GF_OK);
    assert_true(isnan(o.t0));
    assert_int_equal(gf_analysis_opts_set(&o, "zones.radii=auto"), GF_OK);
    assert_int_equal(o.zone_nradii, 0);
    // Errors name the option and say what is wrong, and change nothing.
    copy = o;
    assert_int_equal(gf_analysis_opts_set(&o, "gr.rmax=200"), GF_ERR_PARAM);
    assert_non_null(strstr(gf_last_error(), "gr.rmax"));
    assert_non_null(strstr(gf_last_error(), "out of range [0.1, 100]"));
    assert_int_equal(gf_analysis_opts_set(&o, "zones.radii=2,1"), GF_ERR_PARAM);
    assert_non_null(strstr(gf_last_error(), "increase"));
    assert_int_equal(gf_analysis_opts_set(&o, "velocity.heights=1,x"), GF_ERR_PARAM);
    assert_non_null(strstr(gf_last_error(), "'x' is not a number"));
    assert_int_equal(gf_analysis_opts_set(&o, "surface.columns=2.5"), GF_ERR_PARAM);
    assert_int_equal(gf_analysis_opts_set(&o, "gr.nosuch=1"), GF_ERR_PARAM);
    assert_non_null(strstr(gf_last_error(), "unknown key 'nosuch' in section [gr] (known: x0, x1, z0, z1, rmax, dr)"));
    assert_int_equal(gf_analysis_opts_set(&o, "nosuch.key=1"), GF_ERR_PARAM);
    assert_non_null(strstr(gf_last_error(), "nosuch"));
    assert_memory_equal(&o, &copy, sizeof o);
    assert_int_equal(gf_analysis_opts_get(&o, "gr.nosuch", got, sizeof got), GF_ERR_PARAM);
    assert_int_equal(gf_analysis_opts_key_name(nkeys, name, sizeof name), GF_ERR_PARAM);
    assert_null(gf_analysis_opts_key_default(nkeys));
    // On the heap, for bindings (the Python package): the defaults, copied whole.
    gf_analysis_opts *h = gf_analysis_opts_create();
    assert_non_null(h);
    gf_analysis_opts def = gf_analysis_opts_default();
    assert_memory_equal(h, &def, sizeof def);
    assert_int_equal(gf_analysis_opts_copy(h, &o), GF_OK);
    assert_memory_equal(h, &o, sizeof o);
    assert_int_equal(gf_analysis_opts_copy(NULL, &o), GF_ERR_PARAM);
    gf_analysis_opts_destroy(h);
}

static void config_by_name_errors(void **state)
{
    (void)state;
    gf_config *cfg = gf_config_create();
    char buf[64];
    assert_int_equal(gf_config_set_key(cfg, "spot.radius", "2.6"), GF_OK);
    assert_int_equal(gf_config_set_key(cfg, "spot.radius", "abc"), GF_ERR_PARAM);
    assert_non_null(strstr(gf_last_error(), "spot.radius"));
    assert_int_equal(gf_config_set_key(cfg, "spot.radius", "-1"), GF_ERR_PARAM);
    assert_non_null(strstr(gf_last_error(), "out of range"));
    assert_int_equal(gf_config_get_key(cfg, "spot.radius", buf, sizeof buf), GF_OK);
    assert_string_equal(buf, "2.6"); // failed sets left it alone
    assert_int_equal(gf_config_set_key(cfg, "spot.radus", "1"), GF_ERR_PARAM);
    assert_non_null(strstr(gf_last_error(), "keys of [spot]"));
    assert_int_equal(gf_config_set_key(cfg, "nosuch.key", "1"), GF_ERR_PARAM);
    assert_non_null(strstr(gf_last_error(), "sections:"));
    assert_int_equal(gf_config_get_key(cfg, "radius", buf, sizeof buf), GF_ERR_PARAM);
    assert_int_equal(gf_config_get_key(cfg, "spot.radius", buf, 3), GF_ERR_PARAM); // "2.6" needs 4
    assert_int_equal(gf_config_key_name(gf_config_key_count(), buf, sizeof buf), GF_ERR_PARAM);
    assert_null(gf_config_key_doc(gf_config_key_count()));
    gf_config_destroy(cfg);
}

static void version_from_cmake(void **state)
{
    (void)state;
    char v[32];
    snprintf(v, sizeof v, "%d.%d.%d", GF_VERSION_MAJOR, GF_VERSION_MINOR, GF_VERSION_PATCH);
    assert_string_equal(gf_version(), v);
    assert_string_equal(gf_version(), GF_VERSION_STRING);
}

typedef struct seen {
    int calls;
    char last[256];
} seen;

static void record_warning(void *ctx, const char *message)
{
    seen *s = ctx;
    s->calls++;
    snprintf(s->last, sizeof s->last, "%s", message);
}

static void warnings_are_kept_and_passed_on(void **state)
{
    (void)state;
    gf_warnings_clear();
    assert_int_equal(gf_warning_count(), 0);
    assert_null(gf_warning(0));
    seen s = {0};
    gf_set_warning_fn(record_warning, &s);
    for (int i = 0; i < GF_WARNINGS_KEPT + 5; i++) gf_warn("warning %d", i);
    gf_set_warning_fn(NULL, NULL);
    gf_warn("unheard");
    assert_int_equal(s.calls, GF_WARNINGS_KEPT + 5);
    assert_string_equal(s.last, "warning 36");
    // The newest GF_WARNINGS_KEPT, oldest first.
    assert_int_equal(gf_warning_count(), GF_WARNINGS_KEPT);
    char want[32];
    snprintf(want, sizeof want, "warning %d", GF_WARNINGS_KEPT + 5 - (GF_WARNINGS_KEPT - 1));
    assert_string_equal(gf_warning(0), want);
    assert_string_equal(gf_warning(GF_WARNINGS_KEPT - 1), "unheard");
    gf_warnings_clear();
    assert_int_equal(gf_warning_count(), 0);
}

static size_t hook_blocks, hook_bytes;

static void *counting_alloc(size_t size, size_t alignment)
{
    hook_blocks++;
    hook_bytes += size;
    return aligned_alloc(alignment, size);
}

static void counting_free(void *block, size_t size)
{
    hook_blocks--;
    hook_bytes -= size;
    free(block);
}

static void allocator_hook_sees_every_block(void **state)
{
    (void)state;
    gf_set_allocator(counting_alloc, counting_free);
    gf_config c = gf_test_silo_config(10, 300, 3);
    gf_sim *sim = NULL;
    assert_int_equal(gf_sim_create_from_config(&c, NULL, &sim), GF_OK);
    assert_true(hook_blocks > 0);
    // Every byte granflow counts went through the hook (rounded to cache lines).
    assert_true(hook_bytes >= gf_bytes_allocated());
    assert_true(hook_bytes < gf_bytes_allocated() + 64 * hook_blocks);
    for (int i = 0; i < 200; i++) assert_int_equal(gf_sim_step(sim), GF_OK);
    gf_sim_destroy(sim);
    assert_int_equal(hook_blocks, 0);
    assert_int_equal(hook_bytes, 0);
    gf_set_allocator(NULL, NULL);
}

// A counting allocator, installed through the public API for a whole
// session: config from an INI file, a run with checkpoints into a directory,
// a resume, the analysis, the report, a long error message. Every block the
// library takes must come through it and go back.
static _Atomic size_t count_allocs, count_frees, count_bytes_in, count_bytes_out;

static void *count_alloc(size_t size, size_t alignment)
{
    void *p = aligned_alloc(alignment, size);
    if (p) {
        count_allocs++;
        count_bytes_in += size;
    }
    return p;
}

static void count_free(void *block, size_t size)
{
    count_frees++;
    count_bytes_out += size;
    free(block);
}

// Blocks taken and given back since the counters were last read.
typedef struct counted {
    size_t allocs, frees;
} counted;

static counted count_since(counted *last)
{
    counted now = {count_allocs, count_frees}, d = {now.allocs - last->allocs, now.frees - last->frees};
    *last = now;
    return d;
}

static void allocator_counts_a_whole_session(void **state)
{
    (void)state;
    const size_t bytes0 = gf_bytes_allocated();
    gf_set_allocator(count_alloc, count_free);
    counted last = {0}, d;
    char dir[512], ini[600], path[700];
    snprintf(dir, sizeof dir, "%s/counted", gf_test_tmpdir());
    snprintf(ini, sizeof ini, "%s/counted.ini", gf_test_tmpdir());

    // A config by name, written and read back (the INI reader's lines).
    gf_config *cfg = gf_config_create();
    const char *sets[][2] = {{"container.width", "8"}, {"container.depth", "6"}, {"container.orifice_diameter", "4"},
                             {"packing.particles", "400"}, {"run.seed", "11"}, {"run.duration", "1"},
                             {"run.checkpoint_interval", "0.5"}, {"output.snapshot_interval", "0.25"}};
    for (size_t i = 0; i < sizeof sets / sizeof sets[0]; i++)
        assert_int_equal(gf_config_set_key(cfg, sets[i][0], sets[i][1]), GF_OK);
    assert_int_equal(gf_config_save(cfg, ini), GF_OK);
    count_since(&last);
    gf_config *loaded = gf_config_create();
    assert_int_equal(gf_config_load(loaded, ini), GF_OK);
    gf_config_destroy(loaded);
    d = count_since(&last);
    assert_true(d.allocs >= 2); // the config and the INI reader's line buffer
    assert_int_equal(d.allocs, d.frees);

    // A run into a directory, then resumed from its checkpoint.
    gf_run_opts o = gf_run_opts_default();
    o.dir = dir;
    assert_int_equal(gf_run_dir(cfg, &o, NULL), GF_OK);
    d = count_since(&last);
    assert_true(d.allocs > 10);
    assert_int_equal(d.allocs, d.frees);
    assert_int_equal(gf_config_set_key(cfg, "run.duration", "1.5"), GF_OK);
    o.resume = true;
    assert_int_equal(gf_run_dir(cfg, &o, NULL), GF_OK);
    d = count_since(&last);
    assert_true(d.allocs > 10); // the checkpoint read in, the config compared as text
    assert_int_equal(d.allocs, d.frees);

    // The analysis (tables, gnuplot scripts, summary) without running gnuplot.
    gf_series s = {0};
    assert_int_equal(gf_series_load(dir, 0, NULL, &s), GF_OK);
    gf_analysis_opts ao = gf_analysis_opts_default();
    snprintf(path, sizeof path, "%s/analysis", dir);
    assert_int_equal(gf_analyze(&s, &ao, NULL, path, false), GF_OK);
    gf_series_free(&s);
    d = count_since(&last);
    assert_true(d.allocs > 10);
    assert_int_equal(d.allocs, d.frees);

    // The report page: tables read line by line, the pictures listed.
    snprintf(path, sizeof path, "%s/analysis", dir);
    gf_test_write_file(path, "extra.svg", "<svg xmlns=\"http://www.w3.org/2000/svg\"/>");
    gf_report_info info;
    assert_int_equal(gf_report_write(dir, NULL, &info), GF_OK);
    assert_int_equal(info.images, 1);
    d = count_since(&last);
    assert_true(d.allocs >= 3);
    assert_int_equal(d.allocs, d.frees);

    // An error message longer than the kept text is built in a block too.
    char key[6000];
    memset(key, 'k', sizeof key - 1);
    key[sizeof key - 1] = '\0';
    assert_int_equal(gf_config_set_key(cfg, key, "1"), GF_ERR_PARAM);
    assert_true(strlen(gf_last_error()) < 4096);
    d = count_since(&last);
    assert_true(d.allocs >= 1);
    assert_int_equal(d.allocs, d.frees);

    gf_config_destroy(cfg);
    gf_set_allocator(NULL, NULL);
    // Everything taken was given back, block for block and byte for byte.
    assert_true(count_allocs > 50);
    assert_int_equal(count_allocs, count_frees);
    assert_int_equal(count_bytes_in, count_bytes_out);
    assert_int_equal(gf_bytes_allocated(), bytes0);
}

static int assert_calls, assert_line;
static char assert_cond[64], assert_file[256];

static int soft_assert(const char *condition, const char *file, int line)
{
    snprintf(assert_cond, sizeof assert_cond, "%s", condition);
    snprintf(assert_file, sizeof assert_file, "%s", file);
    assert_line = line;
    assert_calls++;
    return 0; // continue
}

static void assert_hook_is_called(void **state)
{
    (void)state;
    gf_set_assert_fn(soft_assert);
    gf_assert_fail("1 == 2", "here.c", 42);
    assert_int_equal(assert_calls, 1);
    assert_string_equal(assert_cond, "1 == 2");
    assert_string_equal(assert_file, "here.c");
    assert_int_equal(assert_line, 42);
    // The library's checks (GF_ASSERT) reach the hook in this Release
    // (NDEBUG) build too, with the condition's text and place.
    const int line = __LINE__ + 1;
    GF_ASSERT(assert_calls == 0);
    GF_ASSERT(assert_calls == 2); // holds: no call
    gf_set_assert_fn(NULL);
    assert_int_equal(assert_calls, 2);
    assert_string_equal(assert_cond, "assert_calls == 0");
    assert_non_null(strstr(assert_file, "test_embed.c"));
    assert_int_equal(assert_line, line);
}

// A small silo through the flat-array API: the particles plus the exits are
// the initial particles, ids sorted and unique, and the counters agree.
static void sim_arrays_account_for_every_particle(void **state)
{
    (void)state;
    gf_config *cfg = gf_config_create();
    const char *sets[][2] = {{"container.width", "10"}, {"container.depth", "6"}, {"container.orifice_diameter", "5"},
                             {"packing.particles", "1500"}, {"run.seed", "7"}};
    for (size_t i = 0; i < sizeof sets / sizeof sets[0]; i++)
        assert_int_equal(gf_config_set_key(cfg, sets[i][0], sets[i][1]), GF_OK);
    gf_sim *sim = NULL;
    assert_int_equal(gf_sim_create_from_config(cfg, NULL, &sim), GF_OK);
    gf_config_destroy(cfg);
    const size_t n0 = gf_sim_particle_count(sim);
    assert_int_equal(n0, 1500);
    assert_int_equal(gf_sim_run(sim, 3.0, NULL), GF_OK);
    assert_true(gf_sim_stat(sim, "time") >= 3.0);
    assert_true(isnan(gf_sim_stat(sim, "no_such_counter")));
    const size_t n = gf_sim_particle_count(sim), ne = gf_sim_exit_count(sim);
    assert_true(ne > 0);
    assert_int_equal(n + ne, n0);
    assert_int_equal((size_t)gf_sim_stat(sim, "particles_exited"), ne);
    int64_t *id = calloc(n, sizeof *id), *eid = calloc(ne, sizeof *eid);
    double *xyz = calloc(3 * n, sizeof *xyz), *txy = calloc(3 * ne, sizeof *txy);
    size_t got;
    assert_int_equal(gf_sim_copy_particles(sim, id, NULL, xyz, NULL, n - 1, &got), GF_ERR_PARAM);
    assert_int_equal(gf_sim_copy_particles(sim, id, NULL, xyz, NULL, n, &got), GF_OK);
    assert_int_equal(got, n);
    assert_int_equal(gf_sim_copy_exits(sim, eid, txy, ne, &got), GF_OK);
    assert_int_equal(got, ne);
    for (size_t i = 1; i < n; i++) assert_true(id[i] > id[i - 1]);
    for (size_t i = 0; i < n; i++) assert_true(xyz[3 * i + 2] > -0.5 && fabs(xyz[3 * i]) <= 5);
    for (size_t i = 0; i < ne; i++) {
        assert_true(txy[3 * i] > 0 && txy[3 * i] <= gf_sim_stat(sim, "time"));
        assert_true(hypot(txy[3 * i + 1], txy[3 * i + 2]) <= 2.5 + 0.5); // through the orifice
        if (i) assert_true(txy[3 * i] >= txy[3 * (i - 1)]);
    }
    // No id is both inside and gone; together they are 1..n0.
    char *mark = calloc(n0 + 1, 1);
    for (size_t i = 0; i < n; i++) mark[id[i]]++;
    for (size_t i = 0; i < ne; i++) mark[eid[i]]++;
    for (size_t i = 1; i <= n0; i++) assert_int_equal(mark[i], 1);
    for (size_t i = 0; i < gf_sim_stat_count(); i++) assert_false(isnan(gf_sim_stat(sim, gf_sim_stat_name(i))));
    assert_null(gf_sim_stat_name(gf_sim_stat_count()));
    free(mark);
    free(id);
    free(eid);
    free(xyz);
    free(txy);
    gf_sim_destroy(sim);
}

// Every options struct of include/granflow has a by-value default; NULL
// options pointers mean these.
static void options_defaults(void **state)
{
    (void)state;
    assert_int_equal(gf_dem_run_opts_default().ranks, 1);
    assert_null(gf_dem_run_opts_default().lmp);
    assert_false(gf_dem_run_opts_default().drain_only);
    assert_true(gf_dem_source_default().dump_dt == 0 && !gf_dem_source_default().config);
    gf_run_opts r = gf_run_opts_default();
    assert_true(!r.dir && !r.resume && !r.force && !r.stop && !r.progress);
    gf_lga_run_opts l = gf_lga_run_opts_default();
    assert_true(!l.dir && !l.force && !l.stop && !l.progress);
    gf_report_opts o = gf_report_opts_default();
    assert_true(!o.out && !o.compare && !o.title);
    gf_dem_refine_opts ro = gf_dem_refine_opts_default();
    assert_true(ro.max_iter == 0 && ro.flow_tol == 0 && ro.var_tol == 0 && !ro.progress && !ro.stop && !ro.start);
    gf_sim_hooks h = gf_sim_hooks_default();
    assert_true(!h.ctx && !h.snapshot && !h.checkpoint && !h.progress && h.progress_every == 0 && !h.stop);
    // The analysis defaults, by value: the values docs/analysis.md gives.
    gf_analysis_opts a = gf_analysis_opts_default();
    assert_true(isnan(a.t0) && isnan(a.t1) && a.vel_bin == 1.0 && a.vel_nheights == 6 && a.vel_heights[5] == 60.0);
    gf_render_opts ren = gf_render_opts_default();
    assert_true(ren.px_per_d == 10.0 && ren.phi_lo == 0.55 && ren.phi_hi == 0.65 && isnan(ren.zmax) && ren.label);
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(options_defaults),
    cmocka_unit_test(config_get_set_round_trip_every_key),
    cmocka_unit_test(analysis_get_set_round_trip_every_key),
    cmocka_unit_test(config_by_name_errors),
    cmocka_unit_test(version_from_cmake),
    cmocka_unit_test(warnings_are_kept_and_passed_on),
    cmocka_unit_test(allocator_hook_sees_every_block),
    cmocka_unit_test(allocator_counts_a_whole_session),
    cmocka_unit_test(assert_hook_is_called),
    cmocka_unit_test(sim_arrays_account_for_every_particle),
};

GF_TEST_MAIN("embed", tests)
