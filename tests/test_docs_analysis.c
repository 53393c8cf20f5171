// SPDX-License-Identifier: MIT
// docs/analysis.md cannot drift from the code: its options table lists
// exactly the analysis options of the code with their defaults and ranges;
// every measurement has a section naming its CSV files, columns, plot and
// summary.json keys, as the measurements produce them.
#include "support.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "granflow/analysis.h"
#include "granflow/granflow.h"

#define DOC_PATH GF_TEST_DATA "/../../docs/analysis.md"

enum { MAX_KEYS = 64, KEY_LEN = 64, CELL_LEN = 128 };

/// One row of the options table: `key` | default | [lo, hi] | unit | meaning.
typedef struct doc_row {
    char key[KEY_LEN], def[CELL_LEN];
    double lo, hi;
    char names[CELL_LEN]; ///< a word-valued key: its values, "a, b" (lo, hi unused)
} doc_row;

static char *read_doc(void)
{
    char *doc = gf_test_read_file(DOC_PATH, NULL);
    if (!doc) fail_msg("cannot read %s", DOC_PATH);
    return doc;
}

/// The text of the section starting at `heading` (a line of its own) up to
/// the next heading of the same or a higher level, malloc'd; NULL if absent.
static char *section(const char *doc, const char *heading)
{
    char pat[160];
    snprintf(pat, sizeof pat, "\n%s\n", heading);
    const char *a = strstr(doc, pat);
    if (!a) return NULL;
    a++;
    size_t level = strspn(a, "#");
    const char *b = a + strlen(heading);
    for (const char *p = strchr(b, '\n'); p; p = strchr(p + 1, '\n')) {
        size_t l = strspn(p + 1, "#");
        if (l > 0 && l <= level && p[1 + l] == ' ') {
            b = p;
            break;
        }
        b = p + strlen(p);
    }
    size_t n = (size_t)(b - a);
    char *s = malloc(n + 1);
    assert_non_null(s);
    memcpy(s, a, n);
    s[n] = '\0';
    return s;
}

/// Copies the trimmed text of cell `col` (0-based) of a table row "| a | b |".
static bool row_cell(const char *row, int col, char *out, size_t n)
{
    const char *p = row;
    for (int c = 0; c <= col; c++) {
        p = strchr(p, '|');
        if (!p) return false;
        p++;
    }
    const char *e = strchr(p, '|');
    if (!e) return false;
    while (p < e && *p == ' ') p++;
    while (e > p && e[-1] == ' ') e--;
    snprintf(out, n, "%.*s", (int)(e - p), p);
    return true;
}

/// The rows of the "## Options" table.
static size_t doc_rows(const char *doc, doc_row *rows)
{
    char *sec = section(doc, "## Options");
    if (!sec) fail_msg("docs/analysis.md has no '## Options' section");
    size_t n = 0;
    for (const char *l = sec; l && *l; l = strchr(l, '\n') ? strchr(l, '\n') + 1 : NULL) {
        if (strncmp(l, "| `", 3) != 0) continue;
        assert_true(n < MAX_KEYS);
        doc_row *r = &rows[n++];
        char cell[CELL_LEN];
        assert_true(row_cell(l, 0, cell, sizeof cell));
        size_t len = strlen(cell);
        if (len < 3 || cell[0] != '`' || cell[len - 1] != '`') fail_msg("options table: key cell '%s'", cell);
        snprintf(r->key, sizeof r->key, "%.*s", (int)(len - 2), cell + 1);
        assert_true(row_cell(l, 1, r->def, sizeof r->def));
        assert_true(row_cell(l, 2, cell, sizeof cell));
        r->names[0] = '\0';
        if (cell[0] != '[') snprintf(r->names, sizeof r->names, "%s", cell); // a word-valued key
        else if (sscanf(cell, "[%lf, %lf]", &r->lo, &r->hi) != 2)
            fail_msg("options table: %s: range '%s' is not [lo, hi]", r->key, cell);
    }
    free(sec);
    return n;
}

/// The keys of the code (gf_analysis_opts_key_name); *defs gets their defaults.
static size_t code_keys(char keys[][KEY_LEN], const char *defs[])
{
    size_t n = gf_analysis_opts_key_count();
    assert_true(n <= MAX_KEYS);
    for (size_t i = 0; i < n; i++) {
        assert_int_equal(gf_analysis_opts_key_name(i, keys[i], KEY_LEN), GF_OK);
        defs[i] = gf_analysis_opts_key_default(i);
    }
    return n;
}

static gf_status set(gf_analysis_opts *o, const char *key, const char *value)
{
    char a[256];
    snprintf(a, sizeof a, "%s=%s", key, value);
    return gf_analysis_opts_set(o, a);
}

static gf_status set_num(gf_analysis_opts *o, const char *key, double v)
{
    char num[64];
    snprintf(num, sizeof num, "%.17g", v);
    return set(o, key, num);
}

/// Frames at t = 0..8: the documented automatic window is [2, 8].
static gf_series times_only(void)
{
    gf_series s;
    memset(&s, 0, sizeof s);
    s.cfg = gf_config_default();
    s.nframes = 9;
    s.frames = GF_NEW(gf_frame, s.nframes);
    assert_non_null(s.frames);
    for (size_t k = 0; k < s.nframes; k++) s.frames[k].time = (double)k;
    return s;
}

// Every key of the code has one row; every row's key is accepted; its
// documented default, set back, leaves the defaults as they are ("auto":
// the window rule); its range ends are accepted and values just beyond refused.
static void options_table_matches_the_code(void **state)
{
    (void)state;
    char *doc = read_doc();
    doc_row rows[MAX_KEYS];
    size_t nrow = doc_rows(doc, rows);
    char keys[MAX_KEYS][KEY_LEN];
    const char *defs[MAX_KEYS];
    size_t nkey = code_keys(keys, defs);
    assert_true(nkey >= 20);
    for (size_t k = 0; k < nkey; k++) {
        size_t hits = 0;
        for (size_t r = 0; r < nrow; r++) {
            if (strcmp(rows[r].key, keys[k]) != 0) continue;
            hits++;
            if (strcmp(rows[r].def, defs[k]) != 0)
                fail_msg("docs/analysis.md: %s: default %s, the code's is %s", keys[k], rows[r].def, defs[k]);
        }
        if (hits != 1) fail_msg("docs/analysis.md: key %s has %zu rows in the options table", keys[k], hits);
    }
    assert_int_equal(nrow, nkey); // and no row for a key the code does not have

    gf_analysis_opts def = gf_analysis_opts_default();
    gf_series s = times_only();
    double a0, a1;
    gf_analysis_window(&def, &s, &a0, &a1);
    gf_assert_near(a0, 2.0, 0); // a quarter of the way through 0..8
    gf_assert_near(a1, 8.0, 0); // to the end
    for (size_t r = 0; r < nrow; r++) {
        const doc_row *d = &rows[r];
        gf_analysis_opts o = def;
        if (strcmp(d->def, "auto") == 0 && strncmp(d->key, "window.", 7) != 0) {
            // An automatic default that is not a window end: "auto" restores it.
            if (set(&o, d->key, "1") != GF_OK || set(&o, d->key, "auto") != GF_OK || memcmp(&o, &def, sizeof o) != 0)
                fail_msg("docs: %s = auto does not restore the default", d->key);
        } else if (strcmp(d->def, "auto") == 0) {
            // The key is one end of the window, automatic until set.
            if (set(&o, d->key, "5") != GF_OK) fail_msg("%s=5 refused: %s", d->key, gf_last_error());
            double b0, b1;
            gf_analysis_window(&o, &s, &b0, &b1);
            bool start = b0 == 5.0 && b1 == a1, end = b1 == 5.0 && b0 == a0;
            if (!start && !end) fail_msg("%s (default auto) is not an end of the window", d->key);
        } else {
            if (set(&o, d->key, d->def) != GF_OK)
                fail_msg("docs: %s = %s refused: %s", d->key, d->def, gf_last_error());
            if (memcmp(&o, &def, sizeof o) != 0)
                fail_msg("docs: %s = %s is not the default of gf_analysis_opts_default", d->key, d->def);
        }
        o = def;
        if (d->names[0]) {
            // A word-valued key: each documented value accepted, another word refused.
            char list[CELL_LEN], *save = NULL;
            snprintf(list, sizeof list, "%s", d->names);
            for (char *w = strtok_r(list, ", ", &save); w; w = strtok_r(NULL, ", ", &save))
                if (set(&o, d->key, w) != GF_OK) fail_msg("docs: %s = %s refused: %s", d->key, w, gf_last_error());
            if (set(&o, d->key, "bogus") != GF_ERR_PARAM) fail_msg("docs: %s = bogus accepted", d->key);
            continue;
        }
        if (set_num(&o, d->key, d->lo) != GF_OK || set_num(&o, d->key, d->hi) != GF_OK)
            fail_msg("docs: %s: an end of the range [%g, %g] is refused: %s", d->key, d->lo, d->hi, gf_last_error());
        double eps_lo = 1e-6 * fmax(1.0, fabs(d->lo)), eps_hi = 1e-6 * fmax(1.0, fabs(d->hi));
        if (set_num(&o, d->key, d->lo - eps_lo) != GF_ERR_PARAM || set_num(&o, d->key, d->hi + eps_hi) != GF_ERR_PARAM)
            fail_msg("docs: %s: a value beyond the range [%g, %g] is accepted", d->key, d->lo, d->hi);
    }
    gf_series_free(&s);
    free(doc);
}

// A small silo flowing in 7 frames (t = 0..6): a Gaussian downward flow with
// some sideways jitter; particles below z = 0 leave, with their exits. Enough
// for every measurement to run and show all its tables and values.
static gf_series flowing_silo(void)
{
    gf_config c = gf_config_default();
    c.container_width = 12;
    c.container_depth = 6;
    c.orifice_diameter = 4;
    c.packing_particles = 1200;
    assert_int_equal(gf_config_validate(&c), GF_OK);
    gf_packing p0 = {0};
    assert_int_equal(gf_packing_generate(&c, NULL, &p0), GF_OK);
    gf_series s;
    memset(&s, 0, sizeof s);
    s.cfg = c;
    s.nframes = 7;
    s.frames = GF_NEW(gf_frame, s.nframes);
    gf_exit *ex = GF_NEW(gf_exit, p0.n); // the series holds exactly nexits: copied at the end
    assert_true(s.frames && ex);
    s.has_exits = true;
    s.n_initial = p0.n;
    for (size_t k = 0; k < s.nframes; k++) {
        double t = (double)k;
        s.frames[k].time = t;
        for (size_t i = 0; i < p0.n; i++) {
            double v = 0.3 + 1.2 * exp(-p0.x[i] * p0.x[i] / 8.0); // d/tau downwards
            double z = p0.z[i] - v * t, x = p0.x[i] + 0.02 * sin((double)p0.id[i] + t);
            if (z >= 0.0) {
                assert_int_equal(gf_packing_push(&s.frames[k].pk, p0.id[i], p0.layer[i], x, p0.y[i], z, 0.5), GF_OK);
            } else if (k + 1 == s.nframes) {
                ex[s.nexits++] = (gf_exit){.id = p0.id[i], .time = p0.z[i] / v, .x = p0.x[i], .y = p0.y[i], .pass = 1};
            }
        }
    }
    for (size_t a = 1; a < s.nexits; a++) // by time (insertion sort: a few hundred)
        for (size_t b = a; b > 0 && ex[b].time < ex[b - 1].time; b--) {
            gf_exit e = ex[b];
            ex[b] = ex[b - 1];
            ex[b - 1] = e;
        }
    assert_true(s.nexits > 10);
    s.exits = GF_NEW(gf_exit, s.nexits);
    assert_non_null(s.exits);
    memcpy(s.exits, ex, sizeof *ex * s.nexits);
    GF_DELETE(ex, p0.n);
    gf_packing_free(&p0);
    return s;
}

/// Fails unless "`word`" occurs in `text`.
static void assert_named(const char *text, const char *word, const char *where)
{
    char pat[128];
    snprintf(pat, sizeof pat, "`%s`", word);
    if (!strstr(text, pat)) fail_msg("docs/analysis.md: %s does not name %s", where, pat);
}

// Each measurement of gf_measures() has a section "### `NAME`" naming its
// CSV files (NAME.csv), their columns, its plot and its summary.json keys, as
// the measurement produces them.
static void every_measurement_is_documented(void **state)
{
    (void)state;
    char *doc = read_doc();
    gf_series s = flowing_silo();
    gf_analysis_opts o = gf_analysis_opts_default();
    // The papers' heights scaled to a silo ~14 d tall, as tests/cli/analyze.sh does.
    const char *sets[] = {"velocity.heights=3,6,9", "velocity.y_z0=4", "velocity.y_z1=10", "diffusion.z0=8",
                          "correlation.size=8",     "correlation.zc=7", "gr.x0=-5",      "gr.x1=5",
                          "gr.z0=3",                "gr.z1=9",          "density.z0=4",  "density.z1=8",
                          "surface.dx=1"};
    for (size_t k = 0; k < sizeof sets / sizeof sets[0]; k++)
        assert_int_equal(gf_analysis_opts_set(&o, sets[k]), GF_OK);
    // The worked example's table: from its heading to the next "## " heading.
    const char *found = strstr(doc, "\n## Worked example");
    if (!found) fail_msg("docs/analysis.md has no '## Worked example' section");
    size_t i0 = found ? (size_t)(found - doc) + 1 : 0;
    const char *ex1 = strstr(doc + i0, "\n## ");
    size_t exn = ex1 ? (size_t)(ex1 - doc) - i0 : strlen(doc + i0);
    char *example = malloc(exn + 1);
    assert_non_null(example);
    memcpy(example, doc + i0, exn);
    example[exn] = '\0';
    size_t n;
    const gf_measure_def *defs = gf_measures(&n);
    assert_int_equal(n, 11);
    for (size_t m = 0; m < n; m++) {
        char heading[96], where[256], file[96];
        snprintf(heading, sizeof heading, "### `%s`", defs[m].name);
        char *sec = section(doc, heading);
        if (!sec) fail_msg("docs/analysis.md has no section '%s'", heading);
        gf_measure_out out = {0};
        if (defs[m].run(&s, &o, &out) != GF_OK) fail_msg("%s failed on the test silo: %s", defs[m].name, gf_last_error());
        assert_true(out.ntables > 0 && out.gnuplot);
        snprintf(file, sizeof file, "%s.png", defs[m].name);
        snprintf(where, sizeof where, "section %s", heading);
        assert_named(sec, file, where);
        for (size_t t = 0; t < out.ntables; t++) {
            const gf_table *tb = &out.tables[t];
            snprintf(file, sizeof file, "%s.csv", tb->name);
            assert_named(sec, file, where);
            for (size_t c = 0; c < tb->ncol; c++) {
                snprintf(where, sizeof where, "section %s, file %s", heading, file);
                assert_named(sec, tb->cols[c], where);
            }
        }
        snprintf(where, sizeof where, "section %s", heading);
        for (size_t v = 0; v < out.nvalues; v++) {
            assert_named(sec, out.values[v].key, where);
            assert_named(example, out.values[v].key, "the worked example"); // with its value there
        }
        gf_measure_free(&out);
        free(sec);
    }
    // The keys gf_analyze adds to every summary.json.
    const char *driver[] = {"frames", "window_t0", "window_t1", "skipped_NAME"};
    for (size_t k = 0; k < 4; k++) assert_named(doc, driver[k], "the outputs");
    free(example);
    gf_series_free(&s);
    free(doc);
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(options_table_matches_the_code),
    cmocka_unit_test(every_measurement_is_documented),
};

GF_TEST_MAIN("docs_analysis", tests)
