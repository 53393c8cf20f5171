// SPDX-License-Identifier: MIT
// Internal: the pieces of an HTML page the report writes: escaped text,
// inlined images, tables from granflow's flat JSON and CSV files.
#ifndef GF_REPORT_HTML_H
#define GF_REPORT_HTML_H

#include <stdbool.h>
#include <stdio.h>

#include "granflow/core.h"

/// Largest picture a report inlines, bytes on disk (the pictures of a run are
/// below 1 MB; a link to /dev/zero would otherwise fill the disk).
#define GF_HTML_PICTURE_MAX ((long long)64 * 1024 * 1024)
/// Largest text file a report shows (summary.json, CSV tables, config.ini).
#define GF_HTML_TEXT_MAX ((long long)16 * 1024 * 1024)

/// Writes `s` with &, <, >, " escaped.
void gf_html_text(FILE *out, const char *s);

/// Writes the bytes of file `path` in base64 (RFC 4648, no line breaks).
gf_status gf_html_base64_file(FILE *out, const char *path);

/// Writes <img src="data:MIME;base64,..." alt="ALT">. MIME from the suffix (.png, .svg).
gf_status gf_html_image(FILE *out, const char *path, const char *alt);

/// One entry of a flat JSON object (summary.json).
typedef struct gf_html_entry {
    char key[64];
    char value[512]; ///< a number or `null` as written, or a string without its quotes
    bool text;       ///< the value was a string
} gf_html_entry;

/// Reads the JSON object of `path` (summary.json, in any layout: pretty or
/// compact; jansson) into `e` (at most `max` entries; more are dropped).
/// Returns the number read, -1 when the file is absent, -2 when it cannot be
/// read or is not a JSON object (gf_last_error() names the file, line and
/// column; no entry is made).
int gf_html_json_read(const char *path, gf_html_entry *e, size_t max);
/// gf_html_json_read with the reason of a failure: the entries of `path` into
/// e[0, *n); GF_OK with *n = -1 when it is absent; on an error *n = -2 and the
/// status says what (GF_ERR_IO: not a regular file or unreadable; GF_ERR_FORMAT: not JSON).
gf_status gf_html_json_load(const char *path, gf_html_entry *e, size_t max, int *n);

/// Writes the number `text` (as a summary writes it) with 4 significant
/// digits: 1.412 x 10<sup>-7</sup>, 39.69, 68970. Whole numbers written
/// without a point or exponent (counts) stay as they are; other text is
/// escaped as it is.
void gf_html_number(FILE *out, const char *text);

/// Writes a unit, `^2` as a superscript.
void gf_html_unit(FILE *out, const char *unit);

/// The table of `n` entries: each row the quantity in words, its value (4
/// significant digits), its unit and its key. An entry with `why[k]` set
/// (why may be NULL) is left out of the table and listed below it, in words
/// with its key, saying why.
void gf_html_kv_table(FILE *out, const gf_html_entry *e, size_t n, const char *const *why);

// The text readers below: *found false (nothing written, GF_OK) when the file
// is absent. Only a regular file of at most GF_HTML_TEXT_MAX bytes is read
// (lines of at most GF_TEXTSCAN_MAX_SHORT_LINE); anything else, a read error
// or running out of memory is an error naming the file (and line).

/// gf_html_kv_table of the file `path` (gf_html_json_read), nothing left out;
/// GF_ERR_FORMAT (file, line, column) when it is not a JSON object.
gf_status gf_html_json_table(FILE *out, const char *path, bool *found);

/// A table of a CSV file (header row, then rows), at most `max_rows` rows;
/// every field is a cell, empty ones too; blank lines are skipped; numbers
/// with 4 significant digits. A first column named `key` (compare's
/// summary.csv) is shown in words, its unit in a last column.
gf_status gf_html_csv_table(FILE *out, const char *path, size_t max_rows, bool *found);

/// The whole text file `path` in <pre>.
gf_status gf_html_pre_file(FILE *out, const char *path, bool *found);

#endif
