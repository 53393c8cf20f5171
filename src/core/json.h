// SPDX-License-Identifier: MIT
// Internal: the one JSON writer (summary.json of runs, analyses and LGA
// runs; `granflow bench --json`). Objects and arrays nest; numbers are
// printed in a format the caller fixes, so files stay stable byte for byte.
#ifndef GF_CORE_JSON_H
#define GF_CORE_JSON_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

/// Deepest nesting of objects and arrays.
enum { GF_JSON_DEPTH = 16 };

/// A writer on a stream. Pretty: every member of an object on its own line,
/// indented by two spaces a level. Compact: members separated by ", " on one
/// line. Arrays are always on one line ([1, 2, 3]).
typedef struct gf_json {
    FILE *f;
    bool pretty;
    int depth;                    ///< open objects and arrays
    bool array[GF_JSON_DEPTH];    ///< level k is an array (else an object)
    bool nonempty[GF_JSON_DEPTH]; ///< level k has a member already
} gf_json;

/// A writer on f, nothing written yet; gf_json_object_begin(j, NULL) opens the top value.
gf_json gf_json_start(FILE *f, bool pretty);

/// Opens an object: a member `key` of the enclosing object, or (key NULL) an
/// element of an array or the top value.
void gf_json_object_begin(gf_json *j, const char *key);
/// Opens an array (key as for an object).
void gf_json_array_begin(gf_json *j, const char *key);
/// Closes the innermost object or array; closing the top value ends the line.
void gf_json_end(gf_json *j);

/// A string, escaped: quote, backslash and control bytes (as \u00XX).
void gf_json_string(gf_json *j, const char *key, const char *s);
void gf_json_int(gf_json *j, const char *key, int64_t v);
void gf_json_uint(gf_json *j, const char *key, uint64_t v);
void gf_json_bool(gf_json *j, const char *key, bool v);
void gf_json_null(gf_json *j, const char *key);
/// A number with `decimals` digits after the point (printf %.*f); null when
/// not finite (JSON has no inf or nan).
void gf_json_fixed(gf_json *j, const char *key, double v, int decimals);
/// A number with `digits` significant digits (printf %.*g); null when not finite.
void gf_json_general(gf_json *j, const char *key, double v, int digits);

#endif
