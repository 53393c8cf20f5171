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
/// Only a regular file of at most GF_HTML_PICTURE_MAX bytes (a FIFO, device
/// or directory is an error naming the file, never a wait or an endless read).
gf_status gf_html_base64_file(FILE *out, const char *path);

/// Writes <img src="data:MIME;base64,..." alt="ALT">. MIME from the suffix (.png, .svg).
gf_status gf_html_image(FILE *out, const char *path, const char *alt);

// The text readers below: *found false (nothing written, GF_OK) when the file
// is absent. Only a regular file of at most GF_HTML_TEXT_MAX bytes with lines
// of at most GF_TEXTSCAN_MAX_SHORT_LINE is read; anything else, a read error
// or running out of memory is an error naming the file (and line).

/// A two-column table of a flat JSON object written one `"key": value` per
/// line (summary.json).
gf_status gf_html_json_table(FILE *out, const char *path, bool *found);

/// A table of a CSV file (header row, then rows), at most `max_rows` rows;
/// every field is a cell, empty ones too; blank lines are skipped.
gf_status gf_html_csv_table(FILE *out, const char *path, size_t max_rows, bool *found);

/// The whole text file `path` in <pre>.
gf_status gf_html_pre_file(FILE *out, const char *path, bool *found);

#endif
