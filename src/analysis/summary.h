// SPDX-License-Identifier: MIT
// Internal: the headline numbers and notes of analysis/summary.json, which
// gf_analyze writes and reads back (so that one measurement keeps the
// others' numbers); tests/fuzz/fuzz_summary_json.c fuzzes the reader.
#ifndef GF_ANALYSIS_SUMMARY_H
#define GF_ANALYSIS_SUMMARY_H

#include <stddef.h>

#include "granflow/analysis.h"

/// One headline number or note: value, or text when it is a string.
typedef struct gf_summary_item {
    char key[GF_TABLE_NAME];
    double value;
    char text[256];
    int is_text;
} gf_summary_item;

/// The entries of one summary.json, in file order.
typedef struct gf_summary {
    gf_summary_item item[256];
    size_t n;
} gf_summary;

/// The entry `key`, added (zeroed) when new; NULL when the summary is full or
/// the key too long.
gf_summary_item *gf_summary_slot(gf_summary *s, const char *key);

/// Sets `key` to the number v (NaN and infinities are written as null).
void gf_summary_num(gf_summary *s, const char *key, double v);

/// Sets `key` to `text`, cut to at most 255 bytes (at a UTF-8 character's start), with quotes, backslashes and
/// control characters made `'` so that the JSON stays valid.
void gf_summary_text(gf_summary *s, const char *key, const char *text);

/// Adds the entries of the summary.json at `path` (a JSON object of numbers,
/// strings and nulls, in any layout: gf_summary_write's, or compact). An
/// absent file adds nothing; GF_ERR_FORMAT names the file, and the line or
/// key, of one that is not such an object; GF_ERR_IO an unreadable one, or
/// anything but a regular file (a FIFO or a link to /dev/zero in its place
/// would never end); a file over 16 MB is refused.
gf_status gf_summary_read(gf_summary *s, const char *path);

/// Writes the summary to `path` (atomically).
gf_status gf_summary_write(const gf_summary *s, const char *path);

#endif
