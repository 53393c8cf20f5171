// SPDX-License-Identifier: MIT
// One self-contained HTML page for a run directory: the summary, every plot
// and picture (inlined), the config, and the DEM comparison when there is one.
#ifndef GRANFLOW_REPORT_H
#define GRANFLOW_REPORT_H

#include <stddef.h>

#include "granflow/core.h"

#ifdef __cplusplus
extern "C" {
#endif

/// Options of gf_report_write. Make them with gf_report_opts_default().
typedef struct gf_report_opts {
    const char *out;     ///< the page to write; NULL (default): DIR/report.html
    const char *compare; ///< a `granflow compare` output directory; NULL (default): DIR/compare if present
    const char *title;   ///< page title; NULL (default): "granflow run DIR"
} gf_report_opts;

/// What gf_report_write put on the page.
typedef struct gf_report_info {
    size_t images;        ///< pictures inlined (PNG and SVG)
    size_t bytes;         ///< size of the page
    int compared;         ///< 1 when a DEM comparison is on the page
} gf_report_info;

/// The defaults: every member NULL.
GF_API gf_report_opts gf_report_opts_default(void);

/// Writes the report of run directory `dir` (what `granflow run`, `analyze`,
/// `render` and `compare` left there; each part optional except config.ini or
/// summary.json): summary.json and analysis/summary.json as tables, every
/// analysis/*.png, render/*.png|svg (a spot run), *.png and maps/*.png (an
/// LGA run) inlined as a data URI, the comparison
/// with the DEM (compare/summary.csv, compare.png, the DEM and spot slices
/// side by side), and config.ini. Written atomically; `opts` and `info` may
/// be NULL. GF_ERR_PARAM when `dir` is not a run directory.
GF_API gf_status gf_report_write(const char *dir, const gf_report_opts *opts, gf_report_info *info);

#ifdef __cplusplus
}
#endif
#endif
