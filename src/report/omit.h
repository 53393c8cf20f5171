// SPDX-License-Identifier: MIT
// Internal: which numbers of a run's summaries mean nothing for that run
// (the zones of a box silo without recirculation, the angle of a surface that
// never moved, a heap's slope in a silo run, ...), and why.
#ifndef GF_REPORT_OMIT_H
#define GF_REPORT_OMIT_H

#include <stdbool.h>
#include <stddef.h>

#include "report/html.h"

/// What the report knows of the run beyond its summaries.
typedef struct gf_report_context {
    bool have_config;    ///< DIR/config.ini was read
    bool box;            ///< container.shape = box
    bool recirculate;    ///< run.recirculate = on
    bool surface_still;  ///< analysis/surface.csv: the same angle in every snapshot (two or more)
    bool diffusion_empty; ///< analysis: no particle followed (diffusion_particles = 0)
    bool density_empty;   ///< analysis: the counted slice was empty (density_initial null)
    char scenario[16];   ///< an LGA run's lga.scenario from its summary ("" for a spot run)
    char surface_why[256]; ///< the reason given for the surface angle when surface_still
} gf_report_context;

/// Reads DIR/config.ini, DIR/analysis/summary.json and surface.csv (each optional; a
/// config.ini that does not load leaves have_config false) into `c`; the
/// scenario comes from the run's summary entries `run`.
void gf_report_context_read(gf_report_context *c, const char *dir, const gf_html_entry *run, size_t nrun);

/// For each of the `n` entries of a summary, why it is left out of the report
/// (why[k], a text that lives as long as `c` and `e`), or NULL to show it.
void gf_report_omit(const gf_report_context *c, const gf_html_entry *e, size_t n, const char **why);

/// Whether the plot of measurement `name` (analysis/NAME.png) is left out:
/// its numbers are (zones, surface), or it would be empty (diffusion with
/// nobody followed, density of an empty slice).
bool gf_report_omit_plot(const gf_report_context *c, const char *name);

#endif
