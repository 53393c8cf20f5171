// SPDX-License-Identifier: MIT
// Internal: one panel of a picture (a labelled view of the container and the
// slice of particles) and the colour bar, drawn onto any cairo context.
#ifndef GF_RENDER_PANEL_H
#define GF_RENDER_PANEL_H

#include <cairo.h>

#include "granflow/render.h"

/// Where a panel's view lies: d -> device units (pixels or points).
typedef struct gf_panel {
    double s;          ///< device units per d
    double xlo;        ///< x at the view's left edge, d
    double ztop, zbot; ///< z at the view's top and bottom edges, d
    int w, h;          ///< size of the view, device units
    int label;         ///< height of the label strip above the view
} gf_panel;

/// Top of the view (before the 1 d margin) for one packing: opts->zmax, or the
/// highest particle top, at least the orifice diameter.
double gf_panel_zmax(const gf_packing *pk, const gf_config *cfg, const gf_render_opts *o);

/// The panel of the container of cfg up to zmax (see gf_render_opts for the layout).
void gf_panel_layout(const gf_config *cfg, const gf_render_opts *o, double zmax, gf_panel *p);

/// Width of the colour-bar strip, device units.
int gf_panel_bar_width(const gf_render_opts *o);

/// Draws the panel with its top-left corner (label strip included) at (ox, oy).
/// The label is `text` (the time), followed by `title` (may be NULL) when both
/// fit. GF_ERR_NOMEM when the drawing order cannot be sorted.
gf_status gf_panel_draw(cairo_t *cr, double ox, double oy, const gf_panel *p, const gf_packing *pk,
                        const gf_config *cfg, const double *phi, const gf_render_opts *o,
                        const char *text, const char *title);

/// Draws the phi colour bar in the strip of width gf_panel_bar_width at (ox, oy), height h.
void gf_panel_colour_bar(cairo_t *cr, double ox, double oy, double h, const gf_render_opts *o);

/// Writes text with its left end at x and its baseline at y, font size `size`.
void gf_panel_text(cairo_t *cr, double x, double y, double size, const char *text);

#endif
