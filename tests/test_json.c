// SPDX-License-Identifier: MIT
// The one JSON writer (core/json.c): escaping, nesting in both layouts,
// numbers in their fixed formats and null for what JSON cannot hold; and the
// one reader (core/json_read.c, jansson) reading back what the writer wrote.
#include "support.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/json.h"
#include "core/json_read.h"

/// What `write` puts on a stream, as a malloc'd string.
static char *capture(void (*write)(gf_json *), bool pretty)
{
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    assert_non_null(f);
    gf_json j = gf_json_start(f, pretty);
    write(&j);
    assert_int_equal(fclose(f), 0);
    return buf;
}

static void expect_text(void (*write)(gf_json *), bool pretty, const char *want)
{
    char *got = capture(write, pretty);
    if (strcmp(got, want)) fail_msg("wrote\n%s\nexpected\n%s", got, want);
    free(got);
}

static void write_strings(gf_json *j)
{
    gf_json_object_begin(j, NULL);
    gf_json_string(j, "plain", "silo 50 x 8");
    gf_json_string(j, "quote\"key", "say \"hi\"\\now");
    gf_json_string(j, "ctl", "a\nb\tc\x01");
    gf_json_string(j, "utf8", "\xc3\xa9t\xc3\xa9"); // bytes >= 0x80 pass through
    gf_json_string(j, "null", NULL);
    gf_json_end(j);
}

static void strings_are_escaped(void **state)
{
    (void)state;
    expect_text(write_strings, false,
                "{\"plain\": \"silo 50 x 8\", \"quote\\\"key\": \"say \\\"hi\\\"\\\\now\", "
                "\"ctl\": \"a\\u000ab\\u0009c\\u0001\", \"utf8\": \"\xc3\xa9t\xc3\xa9\", \"null\": \"\"}\n");
}

static void write_nested(gf_json *j)
{
    gf_json_object_begin(j, NULL);
    gf_json_int(j, "n", -3);
    gf_json_object_begin(j, "inner");
    gf_json_bool(j, "yes", true);
    gf_json_bool(j, "no", false);
    gf_json_object_begin(j, "empty");
    gf_json_end(j);
    gf_json_end(j);
    gf_json_array_begin(j, "xyz");
    gf_json_int(j, NULL, 1);
    gf_json_uint(j, NULL, 18446744073709551615u);
    gf_json_object_begin(j, NULL);
    gf_json_null(j, "a");
    gf_json_int(j, "b", 2);
    gf_json_end(j);
    gf_json_array_begin(j, NULL);
    gf_json_end(j);
    gf_json_end(j);
    gf_json_string(j, "last", "x");
    gf_json_end(j);
}

static void nesting_pretty_and_compact(void **state)
{
    (void)state;
    expect_text(write_nested, true,
                "{\n"
                "  \"n\": -3,\n"
                "  \"inner\": {\n"
                "    \"yes\": true,\n"
                "    \"no\": false,\n"
                "    \"empty\": {}\n"
                "  },\n"
                "  \"xyz\": [1, 18446744073709551615, {\"a\": null, \"b\": 2}, []],\n"
                "  \"last\": \"x\"\n"
                "}\n");
    expect_text(write_nested, false,
                "{\"n\": -3, \"inner\": {\"yes\": true, \"no\": false, \"empty\": {}}, "
                "\"xyz\": [1, 18446744073709551615, {\"a\": null, \"b\": 2}, []], \"last\": \"x\"}\n");
}

static void write_numbers(gf_json *j)
{
    gf_json_object_begin(j, NULL);
    gf_json_fixed(j, "f3", 2.0 / 3.0, 3);
    gf_json_fixed(j, "f0", 1234.5678, 0);
    gf_json_fixed(j, "f1neg", -0.04, 1);
    gf_json_general(j, "g9", 1.0 / 3.0, 9);
    gf_json_general(j, "g6", 1e-7, 6);
    gf_json_general(j, "g10", 123456789012.0, 10);
    gf_json_general(j, "nan", NAN, 6);
    gf_json_fixed(j, "inf", INFINITY, 2);
    gf_json_general(j, "minf", -INFINITY, 2);
    gf_json_int(j, "big", -9223372036854775807 - 1);
    gf_json_end(j);
}

static void numbers_have_fixed_formats(void **state)
{
    (void)state;
    expect_text(write_numbers, false,
                "{\"f3\": 0.667, \"f0\": 1235, \"f1neg\": -0.0, \"g9\": 0.333333333, \"g6\": 1e-07, "
                "\"g10\": 1.23456789e+11, \"nan\": null, \"inf\": null, \"minf\": null, "
                "\"big\": -9223372036854775808}\n");
}

static void write_top_array(gf_json *j)
{
    gf_json_array_begin(j, NULL);
    gf_json_general(j, NULL, 0.5, 6);
    gf_json_string(j, NULL, "a");
    gf_json_end(j);
    gf_json_end(j); // one end too many: nothing more is written
}

static void top_level_array(void **state)
{
    (void)state;
    expect_text(write_top_array, true, "[0.5, \"a\"]\n");
}

/// The members read, one "key=kind:value" line each.
static gf_status collect(void *ctx, const gf_json_member *m)
{
    FILE *f = ctx;
    fprintf(f, "%s=%d:", m->key, (int)m->kind);
    if (m->kind == GF_JSON_INT) fprintf(f, "%lld", m->integer);
    else if (m->kind == GF_JSON_REAL || m->kind == GF_JSON_BOOL) fprintf(f, "%.17g", m->number);
    else if (m->text) fputs(m->text, f);
    fputc('\n', f);
    return GF_OK;
}

// What the writer writes, pretty or compact, the reader reads back member by
// member in file order, strings unescaped, nested values as compact JSON.
static void reader_reads_the_writer_back(void **state)
{
    (void)state;
    for (int pretty = 0; pretty < 2; pretty++) {
        char *text = capture(write_nested, pretty);
        const char *path = gf_test_write_file(gf_test_tmpdir(), "r.json", text);
        char *got = NULL;
        size_t len = 0;
        FILE *f = open_memstream(&got, &len);
        assert_non_null(f);
        assert_int_equal(gf_json_read_members(path, collect, f), GF_OK);
        fclose(f);
        // 2^64 - 1 is beyond jansson's integers: then every number is read as a double.
        assert_string_equal(got, "n=3:-3\ninner=6:{\"yes\":true,\"no\":false,\"empty\":{}}\n"
                                 "xyz=5:[1.0,1.8446744073709552e19,{\"a\":null,\"b\":2.0},[]]\nlast=4:x\n");
        free(got);
        free(text);
    }
    char *text = capture(write_strings, true);
    const char *path = gf_test_write_file(gf_test_tmpdir(), "r.json", text);
    char *got = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&got, &len);
    assert_int_equal(gf_json_read_members(path, collect, f), GF_OK);
    fclose(f);
    assert_string_equal(got, "plain=4:silo 50 x 8\nquote\"key=4:say \"hi\"\\now\nctl=4:a\nb\tc\x01\n"
                             "utf8=4:\xc3\xa9t\xc3\xa9\nnull=4:\n");
    free(got);
    free(text);
    // An absent file: GF_ERR_IO, errno ENOENT.
    assert_int_equal(gf_json_read_members("/nonexistent/summary.json", collect, NULL), GF_ERR_IO);
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(reader_reads_the_writer_back),
    cmocka_unit_test(strings_are_escaped),
    cmocka_unit_test(nesting_pretty_and_compact),
    cmocka_unit_test(numbers_have_fixed_formats),
    cmocka_unit_test(top_level_array),
};

GF_TEST_MAIN("json", tests)
