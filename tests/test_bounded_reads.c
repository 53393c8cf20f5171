// SPDX-License-Identifier: MIT
// Reads with an end (issue 26, item 4): every line the library reads has a
// cap, running out of memory is an error and never the end of a file, and
// the files a run wrote are read back only when they are regular files of
// bounded size (a FIFO or a link to /dev/zero in their place used to block
// or read for ever). One reader does it all: core/textscan.h, over
// gf_fs_open_regular / gf_fs_read_all (core/fs.h).
#include "support.h"

#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "analysis/summary.h"
#include "core/alloc.h"
#include "core/fs.h"
#include "core/textscan.h"
#include "granflow/granflow.h"
#include "io/exits_read.h"
#include "report/html.h"

// A FIFO in the test's directory (no writer: opening it to read would wait).
static const char *fifo(const char *name)
{
    static char path[4096];
    snprintf(path, sizeof path, "%s/%s", gf_test_tmpdir(), name);
    unlink(path);
    assert_int_equal(mkfifo(path, 0600), 0);
    return path;
}

// Whole lines of any length up to the cap, \r\n endings, a last line
// without its newline; the numbers of the lines.
static void lines_of_any_length_up_to_the_cap(void **state)
{
    (void)state;
    const size_t bytes0 = gf_bytes_allocated();
    char *text = malloc(300000);
    memset(text, 'x', 300000);
    memcpy(text, "a\r\n\n", 4);
    text[4 + 200000] = '\n';
    memcpy(text + 4 + 200001, "last", 5);
    const char *path = gf_test_write_file(gf_test_tmpdir(), "lines.txt", text);
    free(text);
    gf_textscan ts;
    char *line;
    size_t len;
    gf_status st;
    assert_int_equal(gf_textscan_open(&ts, path), GF_OK);
    assert_int_equal(gf_textscan_next(&ts, &line, &len, &st), 1);
    assert_string_equal(line, "a");
    assert_int_equal(gf_textscan_next(&ts, &line, &len, &st), 1);
    assert_string_equal(line, "");
    assert_int_equal(gf_textscan_next(&ts, &line, &len, &st), 1);
    assert_int_equal(len, 200000);
    assert_int_equal(gf_textscan_next(&ts, &line, &len, &st), 1);
    assert_string_equal(line, "last");
    assert_int_equal(ts.line, 4);
    assert_int_equal(gf_textscan_next(&ts, &line, &len, &st), 0);
    assert_int_equal(st, GF_OK);
    gf_textscan_close(&ts);

    // The same file with a cap of 64 kB: its third line is refused.
    assert_int_equal(gf_textscan_open(&ts, path), GF_OK);
    ts.max_line = GF_TEXTSCAN_MAX_SHORT_LINE;
    assert_int_equal(gf_textscan_next(&ts, &line, &len, &st), 1);
    assert_int_equal(gf_textscan_next(&ts, &line, &len, &st), 1);
    assert_int_equal(gf_textscan_next(&ts, &line, &len, &st), -1);
    assert_int_equal(st, GF_ERR_FORMAT);
    char want[4200];
    snprintf(want, sizeof want, "%s:3: line longer than 65536 bytes", path);
    assert_non_null(strstr(gf_last_error(), want));
    gf_textscan_close(&ts);
    assert_int_equal(gf_bytes_allocated(), bytes0);
}

// `granflow run /dev/zero`: a configuration with no line end used to grow
// memory at ~0.5 GB/s; now its first line is too long (exit 2).
static void config_without_line_ends(void **state)
{
    (void)state;
    gf_config c = gf_config_default();
    assert_int_equal(gf_config_load(&c, "/dev/zero"), GF_ERR_PARAM);
    assert_non_null(strstr(gf_last_error(), "/dev/zero:1: line longer than 65536 bytes"));
    // A comment line of 10 kB is still fine.
    char *text = malloc(10100);
    memset(text, 'c', 10100);
    memcpy(text, "; ", 2);
    snprintf(text + 10000, 100, "\n[run]\nseed = 7\n");
    const char *path = gf_test_write_file(gf_test_tmpdir(), "long_comment.ini", text);
    free(text);
    assert_int_equal(gf_config_load(&c, path), GF_OK);
    assert_int_equal(c.run_seed, 7);
}

// Every allocation fails: loading a configuration is an error (it was read
// as the end of the file, and the run went on with the defaults, rc 0).
static size_t failing_allocs;
static void *failing_alloc(size_t size, size_t alignment)
{
    (void)size;
    (void)alignment;
    failing_allocs++;
    return NULL;
}

static void out_of_memory_is_not_the_end_of_the_file(void **state)
{
    (void)state;
    const char *path = gf_test_write_file(gf_test_tmpdir(), "seed.ini", "[run]\nseed = 9\n");
    // (summary.json is read by jansson, which allocates with malloc and
    // reports its own out of memory as an error, never as the file's end.)
    gf_config c = gf_config_default();
    failing_allocs = 0;
    gf_set_allocator(failing_alloc, NULL);
    gf_status load = gf_config_load(&c, path);
    gf_set_allocator(NULL, NULL);
    assert_true(failing_allocs > 0);
    assert_int_equal(load, GF_ERR_NOMEM);
    assert_non_null(strstr(gf_last_error(), "seed.ini"));
    assert_int_not_equal(c.run_seed, 9);
}

// What a run wrote is read back only from a regular file: a FIFO is refused
// at once (it blocked), /dev/zero too (it was read until memory ran out).
static void run_files_are_regular_files(void **state)
{
    (void)state;
    const size_t bytes0 = gf_bytes_allocated();
    unsigned char *data;
    size_t len, cap;
    assert_int_equal(gf_fs_read_all(fifo("ck.bin"), 0, &data, &len, &cap), GF_ERR_IO);
    assert_non_null(strstr(gf_last_error(), "ck.bin: not a regular file (a FIFO)"));
    assert_int_equal(gf_fs_read_all("/dev/zero", 0, &data, &len, &cap), GF_ERR_IO);
    assert_non_null(strstr(gf_last_error(), "/dev/zero: not a regular file (a character device)"));
    assert_int_equal(gf_fs_read_all(gf_test_tmpdir(), 0, &data, &len, &cap), GF_ERR_IO);
    assert_non_null(strstr(gf_last_error(), "not a regular file (a directory)"));
    const char *big = gf_test_write_file(gf_test_tmpdir(), "big.txt", "0123456789");
    assert_int_equal(gf_fs_read_all(big, 9, &data, &len, &cap), GF_ERR_FORMAT);
    assert_non_null(strstr(gf_last_error(), "big.txt: 10 bytes, more than the 9 expected"));
    assert_int_equal(gf_fs_read_all(big, 10, &data, &len, &cap), GF_OK);
    assert_int_equal(len, 10);
    assert_string_equal((char *)data, "0123456789");
    gf_free(data, cap);

    // The checkpoint, exits.csv and analysis/summary.json of a run directory.
    gf_config c = gf_config_default();
    gf_sim *sim = NULL;
    assert_int_equal(gf_sim_load(&c, fifo("checkpoint.bin"), &sim), GF_ERR_IO);
    assert_non_null(strstr(gf_last_error(), "not a regular file (a FIFO)"));
    gf_exit *ex = NULL;
    size_t nex = 0;
    assert_int_equal(gf_exits_read(fifo("exits.csv"), &ex, &nex), GF_ERR_IO);
    assert_non_null(strstr(gf_last_error(), "exits.csv: not a regular file (a FIFO)"));
    gf_summary *s = calloc(1, sizeof *s);
    assert_int_equal(gf_summary_read(s, fifo("summary.json")), GF_ERR_IO);
    assert_int_equal(gf_summary_read(s, "/nonexistent/summary.json"), GF_OK); // absent: nothing to add
    free(s);
    assert_int_equal(gf_bytes_allocated(), bytes0);
}

// The readers of `granflow report`: a FIFO summary.json blocked it, and a
// picture linked to /dev/zero was written out until the disk was full.
static void report_reads_regular_files_only(void **state)
{
    (void)state;
    char *buf = NULL;
    size_t n = 0;
    FILE *out = open_memstream(&buf, &n);
    assert_non_null(out);
    bool found = true;
    assert_int_equal(gf_html_json_table(out, fifo("s.json"), &found), GF_ERR_IO);
    assert_int_equal(gf_html_csv_table(out, fifo("s.csv"), 10, &found), GF_ERR_IO);
    assert_int_equal(gf_html_pre_file(out, "/dev/zero", &found), GF_ERR_IO);
    assert_int_equal(gf_html_base64_file(out, "/dev/zero"), GF_ERR_IO);
    assert_non_null(strstr(gf_last_error(), "/dev/zero: not a regular file (a character device)"));
    assert_int_equal(gf_html_json_table(out, "/nonexistent/summary.json", &found), GF_OK);
    assert_false(found);
    fclose(out);
    assert_int_equal(n, 0); // nothing written for what was refused
    free(buf);
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(lines_of_any_length_up_to_the_cap),
    cmocka_unit_test(config_without_line_ends),
    cmocka_unit_test(out_of_memory_is_not_the_end_of_the_file),
    cmocka_unit_test(run_files_are_regular_files),
    cmocka_unit_test(report_reads_regular_files_only),
};

GF_TEST_MAIN("bounded_reads", tests)
