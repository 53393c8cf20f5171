// SPDX-License-Identifier: MIT
// Internal: tables of `section.name` keys (type, struct field, range,
// default, doc) and the one implementation that parses, checks, prints,
// lists, gets and sets them: gf_config's keys (config/keys.c) and the
// analysis options (analysis/options.c) are two tables over it.
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
    GF_KEY_SIZE,   ///< size_t, decimal integer in [min, max]
    GF_KEY_SET,    ///< int-sized bit set: a comma-separated list of `names` (bit i = names[i]), or an alias
    GF_KEY_LIST,   ///< double[list_max], comma-separated, 1 to list_max values in [min, max]; count at count_offset
} gf_key_type;

/// One key and the struct field it fills.
typedef struct gf_key {
    const char *section;      ///< INI section without brackets, e.g. "spot"
    const char *name;         ///< key within the section, e.g. "radius"
    gf_key_type type;         ///< value syntax and field type
    size_t offset;            ///< offsetof(struct, field)
    double min, max;          ///< numeric range; -INFINITY/INFINITY when unbounded
    bool min_open, max_open;  ///< true: the end is excluded
    const char *const *names; ///< GF_KEY_ENUM: NULL-terminated value names, index = enum value;
                              ///< GF_KEY_SET: the names of the bits, bit i = names[i]
    const char *const *aliases; ///< GF_KEY_SET: NULL-terminated pairs {word, list}: a word that stands
                                ///< for a list as the whole value (e.g. "both", "dump,vtk"); may be NULL
    const char *def;          ///< default, as written in the INI file
    const char *unit;         ///< "d", "tau", "1/tau" or "" (dimensionless)
    const char *doc;          ///< one line: what the key means
    size_t count_offset;      ///< GF_KEY_LIST: offsetof the size_t count of values
    size_t list_max;          ///< GF_KEY_LIST: room for this many values
    bool increasing;          ///< GF_KEY_LIST: the values must increase
    bool auto_empty;          ///< GF_KEY_LIST: `auto` empties the list (count 0), which reads back as `auto`
} gf_key;

/// A table of keys over one struct, grouped by section.
typedef struct gf_key_table {
    const gf_key *keys;
    size_t count;
} gf_key_table;

/// gf_config's keys, grouped by section in file order.
extern const gf_key gf_keys[];
/// Number of entries in gf_keys.
extern const size_t gf_keys_count;
/// The same as a table.
extern const gf_key_table gf_config_keys;

/// Outcome of parsing one value.
typedef enum gf_key_result {
    GF_KEY_OK,           ///< stored
    GF_KEY_BAD_VALUE,    ///< not a number / not an allowed name / empty / too long
    GF_KEY_OUT_OF_RANGE, ///< well-formed but outside the key's range
} gf_key_result;

/// The key `section`.`name` of table `t`, or NULL.
const gf_key *gf_keys_find(const gf_key_table *t, const char *section, const char *name);

/// True when `section` names a section of the table.
bool gf_keys_section_known(const gf_key_table *t, const char *section);

/// Writes "a, b, c": the keys of `section`, or all sections when `section` is NULL.
void gf_keys_list(const gf_key_table *t, const char *section, char *buf, size_t n);

/// The key named "section.name", or NULL with the error set: "`fn`: unknown
/// key 'KEY'" and the keys of its section, or the sections.
const gf_key *gf_keys_lookup(const gf_key_table *t, const char *key, const char *fn);

/// Parses `value` (already trimmed) for key `k` and stores it into the struct
/// at `base`. On failure leaves it unchanged and writes the reason ("not a
/// number", "out of range (0, 1]", ...) into `why`.
gf_key_result gf_keys_assign(const gf_key *k, void *base, const char *value, char *why, size_t n);

/// Checks the value currently in the struct at `base` against the key's type
/// and range (an unresolved `auto` passes). On failure writes the reason into `why`.
bool gf_keys_check(const gf_key *k, const void *base, char *why, size_t n);

/// Writes the field's value as the INI file spells it (shortest round-trip
/// number, enum name, `auto`, path text, comma-separated list).
void gf_keys_format(const gf_key *k, const void *base, char *buf, size_t n);

/// Stores every key's default into the struct at `base` (zeroed by the caller).
void gf_keys_defaults(const gf_key_table *t, void *base);

/// Stores `value` for section.name, or sets the error: `lead` starts the
/// message ("x.ini:3" or "--set spot.w=abc"); `show_value` adds
/// "[section] name = value" after it (file style). GF_ERR_PARAM on failure.
/// `found` (may be NULL) receives the key stored, NULL on failure.
gf_status gf_keys_apply(const gf_key_table *t, void *base, const char *lead, bool show_value, const char *section,
                        const char *name, const char *value, const gf_key **found);

/// Stores "section.name=value" (white space around each part ignored);
/// errors start with "`origin` section.name=value". GF_ERR_PARAM on failure.
/// `found` (may be NULL) receives the key stored, NULL on failure.
gf_status gf_keys_set(const gf_key_table *t, void *base, const char *assignment, const char *origin,
                      const gf_key **found);

/// Writes the value of key "section.name" into buf (`fn` names the caller in errors).
gf_status gf_keys_get(const gf_key_table *t, const void *base, const char *key, char *buf, size_t size,
                      const char *fn);

/// "section.name" of key i into buf (`fn` names the caller in errors).
gf_status gf_keys_name(const gf_key_table *t, size_t i, char *buf, size_t size, const char *fn);

/// Shortest of %.15g/%.16g/%.17g that reads back to the same bits.
void gf_keys_format_double(double v, char *buf, size_t n);

/// The key's allowed values as text: "(0, 1]", "(-inf, 0.5]", "circle, slit", "any", "path".
void gf_keys_range(const gf_key *k, char *buf, size_t n);

#endif
