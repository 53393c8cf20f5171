// SPDX-License-Identifier: MIT
// The readers and tables of `granflow report` (src/report/html.c, omit.c):
// the tables it makes of a CSV file and of summary.json, escaped, in words
// with units and 4 significant digits; what it leaves out of a run's tables
// as not meaningful, and why.
#include "support.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "report/html.h"
#include "report/omit.h"

/// What `write` writes to a stream, malloc'ed.
#define CAPTURE(buf, write)                                                                                            \
    do {                                                                                                               \
        size_t len_ = 0;                                                                                               \
        FILE *out = open_memstream(&(buf), &len_);                                                                     \
        assert_non_null(out);                                                                                          \
        write;                                                                                                         \
        fclose(out);                                                                                                   \
    } while (0)

enum { TABLE_CSV, TABLE_JSON };

/// The HTML of the table of `text` (written to a file first), malloc'ed.
static char *table_of(int kind, const char *text, size_t max_rows)
{
    const char *path = gf_test_write_file(gf_test_tmpdir(), kind == TABLE_CSV ? "t.csv" : "t.json", text);
    char *buf = NULL;
    size_t len = 0;
    FILE *out = open_memstream(&buf, &len);
    assert_non_null(out);
    bool found = false;
    if (kind == TABLE_CSV) assert_int_equal(gf_html_csv_table(out, path, max_rows, &found), GF_OK);
    else assert_int_equal(gf_html_json_table(out, path, &found), GF_OK);
    assert_true(found);
    fclose(out);
    return buf;
}

// Empty fields are cells (strtok dropped them, shifting the columns after
// them; a trailing comma lost the last one); blank lines are skipped.
static void csv_keeps_empty_fields(void **state)
{
    (void)state;
    char *html = table_of(TABLE_CSV, "name,dem,spot\n\nflow,,3.5\nb_p,1.25,\n", 10);
    assert_string_equal(html, "<table class=\"csv\">\n"
                              "<tr><th>name</th><th>dem</th><th>spot</th></tr>\n"
                              "<tr><td class=\"num\">flow</td><td class=\"num\"></td><td class=\"num\">3.5</td></tr>\n"
                              "<tr><td class=\"num\">b_p</td><td class=\"num\">1.25</td><td class=\"num\"></td></tr>\n"
                              "</table>\n");
    free(html);
}

static void csv_rows_are_limited_and_escaped(void **state)
{
    (void)state;
    char *html = table_of(TABLE_CSV, "a&b,<c>\n1,2\n3,4\n", 1);
    assert_string_equal(html, "<table class=\"csv\">\n"
                              "<tr><th>a&amp;b</th><th>&lt;c&gt;</th></tr>\n"
                              "<tr><td class=\"num\">1</td><td class=\"num\">2</td></tr>\n"
                              "</table>\n");
    free(html);
}

// compare's summary.csv: a first column of keys is shown in words, the key
// and its unit in columns of their own, numbers to 4 significant digits, the
// column names with spaces.
static void csv_keys_in_words_with_units(void **state)
{
    (void)state;
    char *html = table_of(TABLE_CSV,
                          "key,dem,spot,relative_difference\nflow_rate,40.07017992,39.69080648,-0.009467725056\n"
                          "velocity_variance_intercept,10.50077744,7.14197092,-0.3198626517\nmystery,1,2,3\n",
                          10);
    assert_string_equal(html,
                        "<table class=\"csv\">\n"
                        "<tr><th>Quantity</th><th>dem</th><th>spot</th><th>relative difference</th><th>Unit</th><th>Key</th></tr>\n"
                        "<tr><th>steady outflow rate</th><td class=\"num\">40.07</td><td class=\"num\">39.69</td>"
                        "<td class=\"num\">-0.009468</td><td>particles/tau</td><td><code>flow_rate</code></td></tr>\n"
                        "<tr><th>width (variance) of v_z(x) extrapolated to z = 0</th><td class=\"num\">10.5</td>"
                        "<td class=\"num\">7.142</td><td class=\"num\">-0.3199</td><td>d<sup>2</sup></td>"
                        "<td><code>velocity_variance_intercept</code></td></tr>\n"
                        "<tr><th>mystery</th><td class=\"num\">1</td><td class=\"num\">2</td><td class=\"num\">3</td>"
                        "<td></td><td><code>mystery</code></td></tr>\n"
                        "</table>\n");
    free(html);
}

// A summary's table: the quantity in words, the value, the unit, the key;
// texts escaped, null as a dash (nothing is left out without a reason).
static void json_rows_in_words_with_units(void **state)
{
    (void)state;
    char *html = table_of(TABLE_JSON,
                          "{\n  \"particles_exited\": 12,\n  \"flow_rate\": null,\n  \"note\": \"a \\\"<b>\\\"\"\n}\n", 0);
    assert_string_equal(html, "<table class=\"kv\">\n"
                              "<tr><th>Quantity</th><th>Value</th><th>Unit</th><th>Key</th></tr>\n"
                              "<tr><th>particles that left through the orifice</th><td class=\"num\">12</td>"
                              "<td>particles</td><td><code>particles_exited</code></td></tr>\n"
                              "<tr><th>steady outflow rate</th><td class=\"num\">—</td><td>particles/tau</td>"
                              "<td><code>flow_rate</code></td></tr>\n"
                              "<tr><th>note</th><td>a &quot;&lt;b&gt;&quot;</td><td></td><td><code>note</code></td></tr>\n"
                              "</table>\n");
    free(html);
}

// The same summary.json re-saved as compact JSON (one line, no spaces), as
// json.dump or jq -c write it: the same rows (jansson reads both). The line
// reader made one garbled row of it (issue 25).
static void json_compact_same_rows(void **state)
{
    (void)state;
    const char *pretty = "{\n  \"granflow_version\": \"0.1.0\",\n  \"seed\": 18446744073709551615,\n"
                         "  \"particles_exited\": 1234,\n  \"flow_rate\": 3.141592654,\n  \"b_p\": null,\n"
                         "  \"status\": \"finished, \\\"ok\\\": yes\"\n}\n";
    const char *compact = "{\"granflow_version\":\"0.1.0\",\"seed\":18446744073709551615,\"particles_exited\":1234,"
                          "\"flow_rate\":3.141592654,\"b_p\":null,\"status\":\"finished, \\\"ok\\\": yes\"}";
    char *a = table_of(TABLE_JSON, pretty, 0), *b = table_of(TABLE_JSON, compact, 0);
    assert_string_equal(a, b);
    assert_non_null(strstr(a, "<td class=\"num\">1234</td><td>particles</td><td><code>particles_exited</code>"));
    assert_non_null(strstr(a, "<td class=\"num\">3.142</td>"));
    assert_non_null(strstr(a, "<td>finished, &quot;ok&quot;: yes</td>"));
    // A seed above 2^63 (beyond jansson's integers) is read as a number, not refused.
    assert_non_null(strstr(a, "<td class=\"num\">1.845 × 10<sup>19</sup></td>"));
    free(a);
    free(b);
}

// Not JSON, or not an object: GF_ERR_FORMAT naming the file, line and column; nothing written.
static void json_malformed_is_an_error(void **state)
{
    (void)state;
    static const char *const bad[] = {"{\n  \"frames\": 12,\n  \"b_p\": nul\n}\n", "[1, 2]\n",
                                      "{\"a\": 1, \"a\": 2}", "{\"a\": 1} trailing", ""};
    bool found;
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        const char *path = gf_test_write_file(gf_test_tmpdir(), "bad.json", bad[k]);
        char *buf = NULL;
        size_t len = 0;
        FILE *out = open_memstream(&buf, &len);
        assert_non_null(out);
        assert_int_equal(gf_html_json_table(out, path, &found), GF_ERR_FORMAT);
        fclose(out);
        assert_int_equal(len, 0);
        assert_non_null(strstr(gf_last_error(), path));
        free(buf);
    }
    const char *path = gf_test_write_file(gf_test_tmpdir(), "bad.json", bad[0]);
    FILE *out = fopen("/dev/null", "w");
    assert_int_equal(gf_html_json_table(out, path, &found), GF_ERR_FORMAT);
    fclose(out);
    char want[4200];
    snprintf(want, sizeof want, "%s:3:", path); // the line of `nul`
    assert_non_null(strstr(gf_last_error(), want));
}

// 4 significant digits: plain decimals from 0.001 to 999999 (trailing zeros
// of the rounding dropped), a power of ten outside; counts exact; texts as
// they are.
static void numbers_to_4_significant_digits(void **state)
{
    (void)state;
    static const char *const cases[][2] = {
        {"39.69080648", "39.69"},   {"68973.5", "68970"},     {"-0.3519371912", "-0.3519"},
        {"0.001240343705", "0.00124"}, {"0.99", "0.99"},      {"4.000", "4"},
        {"1.411590747e-07", "1.412 × 10<sup>-7</sup>"},      {"123456789.5", "1.235 × 10<sup>8</sup>"},
        {"3.0e-4", "3 × 10<sup>-4</sup>"}, {"125", "125"},    {"55000", "55000"},
        {"-7", "-7"},               {"0.0", "0"},             {"null", "—"},
        {"complete", "complete"},   {"1e999", "1e999"},       {"<b>", "&lt;b&gt;"},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        char *html = NULL;
        CAPTURE(html, gf_html_number(out, cases[k][0]));
        if (strcmp(html, cases[k][1])) fail_msg("%s written as '%s', not '%s'", cases[k][0], html, cases[k][1]);
        free(html);
    }
}

static gf_html_entry entry(const char *key, const char *value, bool text)
{
    gf_html_entry e = {.text = text};
    snprintf(e.key, sizeof e.key, "%s", key);
    snprintf(e.value, sizeof e.value, "%s", value);
    return e;
}

// Rows with a reason are not in the table; each reason is one line naming
// the rows it covers, in words with the key.
static void left_out_rows_listed_by_reason(void **state)
{
    (void)state;
    gf_html_entry e[] = {entry("flow_rate", "3.5", false), entry("zones_count", "4", false),
                         entry("surface_angle", "-0.35", false), entry("passes_max", "1", false)};
    const char *why[] = {NULL, "no zones here", "still", "no zones here"};
    char *html = NULL;
    CAPTURE(html, gf_html_kv_table(out, e, 4, why));
    assert_non_null(strstr(html, "<code>flow_rate</code>"));
    assert_null(strstr(html, "<td><code>zones_count</code>"));
    assert_non_null(strstr(html, "<li>radial zones (<code>zones_count</code>), highest pass through the container "
                                 "(<code>passes_max</code>): no zones here</li>\n"
                                 "<li>angle of the free surface (<code>surface_angle</code>): still</li>\n"));
    free(html);
}

static const char *why_of(const gf_report_context *c, const gf_html_entry *e, size_t n, const char *key)
{
    const char *why[16];
    gf_report_omit(c, e, n, why);
    for (size_t k = 0; k < n; k++)
        if (!strcmp(e[k].key, key)) return why[k];
    fail_msg("no key %s", key);
    return NULL;
}

// The zones of a box silo without recirculation, the angle of a surface
// that never moved, reinsertions without recirculation, null numbers and the
// analysis' own skipped_ notes are left out; a cylinder or a recirculating
// box keeps its zones, a moving surface its angle.
static void spot_run_omissions(void **state)
{
    (void)state;
    const char *dir = gf_test_tmpdir();
    char sub[1100];
    snprintf(sub, sizeof sub, "%s/analysis", dir);
    mkdir(sub, 0755);
    gf_test_write_file(dir, "analysis/surface.csv", "time_tau,slope,angle_deg\n0,0.1,5.7\n2,0.1,5.7\n4,0.1,5.7\n");
    gf_test_write_file(dir, "config.ini", "[container]\nshape = box\n");
    gf_html_entry e[] = {entry("zones_count", "4", false),       entry("transit_mean", "2.5", false),
                         entry("passes_max", "1", false),         entry("surface_angle", "5.7", false),
                         entry("particles_reinserted", "0", false), entry("density_initial", "null", false),
                         entry("skipped_rtd", "no exits", true),  entry("flow_rate", "3.5", false)};
    size_t n = sizeof e / sizeof e[0];
    gf_report_context c;
    gf_report_context_read(&c, dir, NULL, 0);
    assert_true(c.have_config && c.box && !c.recirculate && c.surface_still);
    assert_non_null(strstr(why_of(&c, e, n, "zones_count"), "box silo without recirculation"));
    assert_non_null(why_of(&c, e, n, "transit_mean"));
    assert_non_null(why_of(&c, e, n, "passes_max"));
    assert_non_null(strstr(why_of(&c, e, n, "surface_angle"), "did not move"));
    assert_non_null(strstr(why_of(&c, e, n, "surface_angle"), "5.7 degrees in all 3 snapshots"));
    assert_non_null(strstr(why_of(&c, e, n, "particles_reinserted"), "run.recirculate = off"));
    assert_non_null(strstr(why_of(&c, e, n, "density_initial"), "density.z0"));
    assert_string_equal(why_of(&c, e, n, "skipped_rtd"), "no exits");
    assert_null(why_of(&c, e, n, "flow_rate"));
    assert_true(gf_report_omit_plot(&c, "zones") && gf_report_omit_plot(&c, "surface"));
    assert_false(gf_report_omit_plot(&c, "outflow"));

    // a cylinder, recirculating, and a surface that moved: all shown
    gf_test_write_file(dir, "config.ini", "[container]\nshape = cylinder\n[run]\nrecirculate = on\n");
    gf_test_write_file(dir, "analysis/surface.csv", "time_tau,slope,angle_deg\n0,0.1,5.7\n2,0.12,6.8\n");
    gf_report_context_read(&c, dir, NULL, 0);
    assert_true(c.have_config && !c.box && c.recirculate && !c.surface_still);
    for (size_t k = 0; k < 5; k++) assert_null(why_of(&c, e, n, e[k].key));
    assert_false(gf_report_omit_plot(&c, "zones") || gf_report_omit_plot(&c, "surface"));

    // a recirculating box keeps its zones; no config.ini: nothing left out for it
    gf_test_write_file(dir, "config.ini", "[container]\nshape = box\n[run]\nrecirculate = on\n");
    gf_report_context_read(&c, dir, NULL, 0);
    assert_null(why_of(&c, e, n, "zones_count"));
    gf_test_write_file(dir, "config.ini", "[container]\nbogus = 1\n");
    gf_report_context_read(&c, dir, NULL, 0);
    assert_false(c.have_config);
    assert_null(why_of(&c, e, n, "zones_count"));
    assert_null(why_of(&c, e, n, "particles_reinserted"));
}

// An LGA run: what its scenario does not measure is left out, and a silo
// that never emptied says so (its outflow times stay).
static void lga_run_omissions(void **state)
{
    (void)state;
    gf_html_entry e[] = {entry("scenario", "silo", true),        entry("particles_added", "0", false),
                         entry("iterations_to_empty", "null", false), entry("iterations_to_stop", "626", false),
                         entry("t50", "226", false),               entry("slope_angle", "null", false),
                         entry("wave_variance_ratio", "null", false), entry("mean_outflow_rate", "0.06", false)};
    size_t n = sizeof e / sizeof e[0];
    gf_report_context c;
    gf_report_context_read(&c, "/nonexistent", e, n);
    assert_string_equal(c.scenario, "silo");
    assert_non_null(strstr(why_of(&c, e, n, "iterations_to_empty"), "not empty at the end"));
    assert_non_null(strstr(why_of(&c, e, n, "particles_added"), "pile"));
    assert_non_null(strstr(why_of(&c, e, n, "slope_angle"), "pile only"));
    assert_non_null(strstr(why_of(&c, e, n, "wave_variance_ratio"), "channel only"));
    assert_null(why_of(&c, e, n, "iterations_to_stop"));
    assert_null(why_of(&c, e, n, "t50"));
    assert_null(why_of(&c, e, n, "mean_outflow_rate"));
    assert_null(why_of(&c, e, n, "scenario"));
    e[0] = entry("scenario", "channel", true);
    gf_report_context_read(&c, "/nonexistent", e, n);
    assert_non_null(strstr(why_of(&c, e, n, "mean_outflow_rate"), "nothing leaves"));
    assert_non_null(strstr(why_of(&c, e, n, "iterations_to_empty"), "only a silo"));
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(csv_keeps_empty_fields),
    cmocka_unit_test(csv_rows_are_limited_and_escaped),
    cmocka_unit_test(csv_keys_in_words_with_units),
    cmocka_unit_test(json_rows_in_words_with_units),
    cmocka_unit_test(json_compact_same_rows),
    cmocka_unit_test(json_malformed_is_an_error),
    cmocka_unit_test(numbers_to_4_significant_digits),
    cmocka_unit_test(left_out_rows_listed_by_reason),
    cmocka_unit_test(spot_run_omissions),
    cmocka_unit_test(lga_run_omissions),
};

GF_TEST_MAIN("report_html", tests)
