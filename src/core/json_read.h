// SPDX-License-Identifier: MIT
// Internal: the one JSON reader (jansson), for granflow's own flat JSON files
// (summary.json of runs and analyses) read back by the analysis and the
// report. Any layout a JSON tool may save them in reads the same (pretty,
// compact, reordered whitespace); tests/fuzz/fuzz_summary_json.c and
// fuzz_report.c fuzz it through its users.
#ifndef GF_CORE_JSON_READ_H
#define GF_CORE_JSON_READ_H

#include "granflow/core.h"

/// The kind of a member's value.
typedef enum gf_json_kind {
    GF_JSON_NULL,
    GF_JSON_BOOL,
    GF_JSON_INT,
    GF_JSON_REAL,
    GF_JSON_STRING,
    GF_JSON_ARRAY,
    GF_JSON_OBJECT,
} gf_json_kind;

/// One member of the top-level object; the strings live for the callback only.
typedef struct gf_json_member {
    const char *key;   ///< UTF-8, without NUL bytes
    gf_json_kind kind;
    double number;     ///< INT, REAL (an INT as a double too), BOOL as 0 or 1; else NaN
    long long integer; ///< INT (an integer beyond long long is read as a REAL)
    const char *text;  ///< STRING: the string; ARRAY, OBJECT: its compact JSON; else NULL
} gf_json_member;

/// Called on each member; a status other than GF_OK stops the reading and is returned.
typedef gf_status (*gf_json_member_fn)(void *ctx, const gf_json_member *m);

/// Reads the JSON file `path`, whose top value must be an object, and calls
/// `fn` on each member in file order. GF_ERR_IO when the file cannot be read
/// (errno kept: ENOENT for an absent one); GF_ERR_FORMAT ("PATH:LINE:COLUMN:
/// what is wrong") when it is not JSON, holds a key twice, or its top value is
/// not an object.
gf_status gf_json_read_members(const char *path, gf_json_member_fn fn, void *ctx);

#endif
