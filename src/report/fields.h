// SPDX-License-Identifier: MIT
// Internal: what the keys of granflow's summaries mean, for the report's
// tables: each key in words and its unit.
#ifndef GF_REPORT_FIELDS_H
#define GF_REPORT_FIELDS_H

/// One key of summary.json (a run, an analysis, an LGA run) or of
/// compare/summary.csv.
typedef struct gf_report_field {
    const char *key;   ///< as in the file
    const char *words; ///< what it is, for a reader who does not know the key
    const char *unit;  ///< "" for a dimensionless number or a text
} gf_report_field;

/// The field of `key`, or NULL for a key the report does not know (shown as
/// it is, without a unit).
const gf_report_field *gf_report_field_find(const char *key);

#endif
