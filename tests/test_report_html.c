// SPDX-License-Identifier: MIT
// The readers of `granflow report` (src/report/html.c): the tables it makes
// of a CSV file and of summary.json (read with jansson, in any layout), escaped.
#include "support.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "report/html.h"

enum { TABLE_CSV, TABLE_JSON };

/// The HTML of the table of `text` (written to a file first), malloc'ed.
static char *table_of(int kind, const char *text, size_t max_rows)
{
    const char *path = gf_test_write_file(gf_test_tmpdir(), kind == TABLE_CSV ? "t.csv" : "t.json", text);
    char *buf = NULL;
    size_t len = 0;
    FILE *out = open_memstream(&buf, &len);
    assert_non_null(out);
    if (kind == TABLE_CSV) assert_true(gf_html_csv_table(out, path, max_rows));
    else assert_int_equal(gf_html_json_table(out, path), GF_OK);
    fclose(out);
    return buf;
}

// Empty fields are cells (strtok dropped them, shifting the columns after
// them; a trailing comma lost the last one); blank lines are skipped.
static void csv_keeps_empty_fields(void **state)
{
    (void)state;
    char *html = table_of(TABLE_CSV, "key,dem,spot\n\nflow,,3.5\nb_p,1.25,\n", 10);
    assert_string_equal(html, "<table class=\"csv\">\n"
                              "<tr><th>key</th><th>dem</th><th>spot</th></tr>\n"
                              "<tr><td>flow</td><td></td><td>3.5</td></tr>\n"
                              "<tr><td>b_p</td><td>1.25</td><td></td></tr>\n"
                              "</table>\n");
    free(html);
}

static void csv_rows_are_limited_and_escaped(void **state)
{
    (void)state;
    char *html = table_of(TABLE_CSV, "a&b,<c>\n1,2\n3,4\n", 1);
    assert_string_equal(html, "<table class=\"csv\">\n"
                              "<tr><th>a&amp;b</th><th>&lt;c&gt;</th></tr>\n"
                              "<tr><td>1</td><td>2</td></tr>\n"
                              "</table>\n");
    free(html);
}

static void json_key_value_rows(void **state)
{
    (void)state;
    char *html = table_of(TABLE_JSON, "{\n  \"frames\": 12,\n  \"b_p\": null,\n  \"note\": \"a \\\"<b>\\\"\"\n}\n", 0);
    assert_string_equal(html, "<table class=\"kv\">\n"
                              "<tr><th>frames</th><td>12</td></tr>\n"
                              "<tr><th>b_p</th><td>—</td></tr>\n"
                              "<tr><th>note</th><td>a &quot;&lt;b&gt;&quot;</td></tr>\n"
                              "</table>\n");
    free(html);
}

// The same summary.json re-saved as compact JSON (one line, no spaces), as
// json.dump or jq -c write it: the same rows. The line reader made one
// garbled row of it (issue 25).
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
    assert_non_null(strstr(a, "<tr><th>particles_exited</th><td>1234</td></tr>\n"));
    assert_non_null(strstr(a, "<tr><th>flow_rate</th><td>3.141592654</td></tr>\n"));
    assert_non_null(strstr(a, "<tr><th>status</th><td>finished, &quot;ok&quot;: yes</td></tr>\n"));
    // A seed above 2^63 (beyond jansson's integers) is read as a number, not refused.
    assert_non_null(strstr(a, "<tr><th>seed</th><td>1.844674407e+19</td></tr>\n"));
    free(a);
    free(b);
}

// Not JSON, or not an object: GF_ERR_FORMAT naming the file, line and column; nothing written.
static void json_malformed_is_an_error(void **state)
{
    (void)state;
    static const char *const bad[] = {"{\n  \"frames\": 12,\n  \"b_p\": nul\n}\n", "[1, 2]\n",
                                      "{\"a\": 1, \"a\": 2}", "{\"a\": 1} trailing", ""};
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        const char *path = gf_test_write_file(gf_test_tmpdir(), "bad.json", bad[k]);
        char *buf = NULL;
        size_t len = 0;
        FILE *out = open_memstream(&buf, &len);
        assert_non_null(out);
        assert_int_equal(gf_html_json_table(out, path), GF_ERR_FORMAT);
        fclose(out);
        assert_int_equal(len, 0);
        assert_non_null(strstr(gf_last_error(), path));
        free(buf);
    }
    const char *path = gf_test_write_file(gf_test_tmpdir(), "bad.json", bad[0]);
    FILE *out = fopen("/dev/null", "w");
    assert_int_equal(gf_html_json_table(out, path), GF_ERR_FORMAT);
    fclose(out);
    char want[4200];
    snprintf(want, sizeof want, "%s:3:", path); // the line of `nul`
    assert_non_null(strstr(gf_last_error(), want));
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(csv_keeps_empty_fields),
    cmocka_unit_test(csv_rows_are_limited_and_escaped),
    cmocka_unit_test(json_key_value_rows),
    cmocka_unit_test(json_compact_same_rows),
    cmocka_unit_test(json_malformed_is_an_error),
};

GF_TEST_MAIN("report_html", tests)
