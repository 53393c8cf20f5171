// SPDX-License-Identifier: MIT
// Internal: the table of configuration keys (section, name, type, field, range, default, doc).
#ifndef GF_CONFIG_KEYS_H
#define GF_CONFIG_KEYS_H

#include <stdbool.h>
#include <stddef.h>

#include "granflow/config.h"

/// How a key's value is written and stored.
typedef enum gf_key_type {
    GF_KEY_DOUBLE, ///< double, finite, in [min, max] (ends open or closed)
    GF_KEY_AUTO,   ///< double or the word `auto` (stored as NAN, resolved by gf_config_validate)
    GF_KEY_INT64,  ///< int64_t, decimal integer in [min, max]
    GF_KEY_UINT64, ///< uint64_t, any non-negative decimal integer
    GF_KEY_ENUM,   ///< int-sized C enum, value = index into `names`
    GF_KEY_PATH,   ///< char[GF_PATH_MAX]; may be empty
} gf_key_type;

/// One key of the INI file and the gf_config field it fills.
typedef struct gf_key {
    const char *section;      ///< INI section without brackets, e.g. "spot"
    const char *name;         ///< key within the section, e.g. "radius"
    gf_key_type type;         ///< value syntax and field type
    size_t offset;            ///< offsetof(gf_config, field)
    double min, max;          ///< numeric range; -INFINITY/INFINITY when unbounded
    bool min_open, max_open;  ///< true: the end is excluded
    const char *const *names; ///< GF_KEY_ENUM: NULL-terminated value names, index = enum value
    const char *def;          ///< default, as written in the INI file
    const char *unit;         ///< "d", "tau", "1/tau" or "" (dimensionless)
    const char *doc;          ///< one line: what the key means
} gf_key;

/// Every key, grouped by section in file order.
extern const gf_key gf_keys[];
/// Number of entries in gf_keys.
extern const size_t gf_keys_count;

/// Outcome of parsing one value.
typedef enum gf_key_result {
    GF_KEY_OK,           ///< stored
    GF_KEY_BAD_VALUE,    ///< not a number / not an allowed name / empty / too long
    GF_KEY_OUT_OF_RANGE, ///< well-formed but outside the key's range
} gf_key_result;

/// The key `section`.`name`, or NULL.
const gf_key *gf_keys_find(const char *section, const char *name);

/// True when `section` names a section of the table.
bool gf_keys_section_known(const char *section);

/// Writes "a, b, c": the keys of `section`, or all sections when `section` is NULL.
void gf_keys_list(const char *section, char *buf, size_t n);

/// Parses `value` (already trimmed) for key `k` and stores it into `cfg`. On
/// failure leaves `cfg` unchanged and writes the reason ("not a number",
/// "out of range (0, 1]", ...) into `why`.
gf_key_result gf_keys_assign(const gf_key *k, gf_config *cfg, const char *value, char *why,
                             size_t n);

/// Checks the value currently in `cfg` against the key's type and range
/// (an unresolved `auto` passes). On failure writes the reason into `why`.
bool gf_keys_check(const gf_key *k, const gf_config *cfg, char *why, size_t n);

/// Writes the field's value as the INI file spells it (shortest round-trip
/// number, enum name, `auto`, path text).
void gf_keys_format(const gf_key *k, const gf_config *cfg, char *buf, size_t n);

/// Shortest of %.15g/%.16g/%.17g that reads back to the same bits.
void gf_keys_format_double(double v, char *buf, size_t n);

/// The key's allowed values as text: "(0, 1]", "(-inf, 0.5]", "circle, slit", "any", "path".
void gf_keys_range(const gf_key *k, char *buf, size_t n);

#endif
