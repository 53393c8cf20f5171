// SPDX-License-Identifier: MIT
// Internal: the pieces of an HTML page the report writes: escaped text,
// inlined images, tables from granflow's flat JSON and CSV files.
#ifndef GF_REPORT_HTML_H
#define GF_REPORT_HTML_H

#include <stdbool.h>
#include <stdio.h>

#include "granflow/core.h"

/// Writes `s` with &, <, >, " escaped.
void gf_html_text(FILE *out, const char *s);

/// Writes the bytes of file `path` in base64 (RFC 4648, no line breaks).
gf_status gf_html_base64_file(FILE *out, const char *path);

/// Writes <img src="data:MIME;base64,..." alt="ALT">. MIME from the suffix (.png, .svg).
gf_status gf_html_image(FILE *out, const char *path, const char *alt);

/// A two-column table of the members of a JSON object (summary.json, in any
/// layout: pretty or compact). Writes nothing and returns GF_ERR_IO when the
/// file cannot be read (errno ENOENT when absent), GF_ERR_FORMAT (file, line,
/// column) when it is not a JSON object.
gf_status gf_html_json_table(FILE *out, const char *path);

/// A table of a CSV file (header row, then rows), at most `max_rows` rows;
/// every field is a cell, empty ones too; blank lines are skipped.
/// Returns false (writes nothing) when the file is absent.
bool gf_html_csv_table(FILE *out, const char *path, size_t max_rows);

/// The whole text file `path` in <pre>. Returns false when absent.
bool gf_html_pre_file(FILE *out, const char *path);

#endif
