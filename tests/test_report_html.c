// SPDX-License-Identifier: MIT
// The readers of `granflow report` (src/report/html.c): the tables it makes
// of a CSV file and of summary.json, escaped.
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
    bool found = false;
    assert_int_equal(kind == TABLE_CSV ? gf_html_csv_table(out, path, max_rows, &found)
                                       : gf_html_json_table(out, path, &found),
                     GF_OK);
    assert_true(found);
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
                              "<tr><th>note</th><td>a \\&quot;&lt;b&gt;\\&quot;</td></tr>\n"
                              "</table>\n");
    free(html);
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(csv_keeps_empty_fields),
    cmocka_unit_test(csv_rows_are_limited_and_escaped),
    cmocka_unit_test(json_key_value_rows),
};

GF_TEST_MAIN("report_html", tests)
