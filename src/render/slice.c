// SPDX-License-Identifier: MIT
// gf_render_slice and gf_render_sheet: whole pictures made of panels.
#include "granflow/render.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "core/error.h"
#include "draw/canvas.h"
#include "granflow/defs.h"
#include "render/panel.h"

enum { GF_RENDER_MAX_PX = 32767, GF_SHEET_MAX_COLS = 10 }; // cairo's largest image side
static const double gf_render_max_area = 1e8; // pixels (400 MB as an image): beyond, surely a mistake

gf_render_opts gf_render_opts_default(void)
{
    return (gf_render_opts){
        .colour = GF_RENDER_LAYER,
        .format = GF_RENDER_AUTO,
        .px_per_d = 10.0,
        .phi_lo = 0.55,
        .phi_hi = 0.65,
        .zmax = NAN,
        .ymin = 0.0,
        .label = true,
        .title = NULL,
    };
}

static gf_status gf_render_check(const gf_config *cfg, const gf_render_opts *o, const char *path)
{
    if (!cfg || !o) return gf_error_set(GF_ERR_PARAM, "render: no config or options");
    if (path && !path[0]) return gf_error_set(GF_ERR_PARAM, "render: empty output path");
    if (!(o->px_per_d >= 1.0 && o->px_per_d <= 200.0))
        return gf_error_set(GF_ERR_PARAM, "render: scale must be 1-200 pixels per d, got %g", o->px_per_d);
    if (o->colour != GF_RENDER_LAYER && o->colour != GF_RENDER_PHI)
        return gf_error_set(GF_ERR_PARAM, "render: unknown colour mode %d", (int)o->colour);
    if (o->format < GF_RENDER_AUTO || o->format > GF_RENDER_PDF)
        return gf_error_set(GF_ERR_PARAM, "render: unknown format %d", (int)o->format);
    if (!(isfinite(o->phi_lo) && isfinite(o->phi_hi) && o->phi_lo < o->phi_hi))
        return gf_error_set(GF_ERR_PARAM, "render: packing fraction scale [%g, %g] is empty", o->phi_lo,
                            o->phi_hi);
    gf_container_defs cd;
    gf_config_container_defs(cfg, &cd);
    if (!(cd.width > 0 && isfinite(cd.width) && cd.orifice.diameter >= 0 &&
          isfinite(cd.orifice.diameter) && isfinite(cd.exit_level)))
        return gf_error_set(GF_ERR_PARAM, "render: bad container (width %g, orifice %g, exit_z %g)",
                            cd.width, cd.orifice.diameter, cd.exit_level);
    if (isnan(o->ymin) || (!isnan(o->zmax) && !isfinite(o->zmax)))
        return gf_error_set(GF_ERR_PARAM, "render: ymin and zmax must be finite");
    return GF_OK;
}

static gf_status gf_render_fits(double w, double h)
{
    if (w > GF_RENDER_MAX_PX || h > GF_RENDER_MAX_PX || w < 1 || h < 1 || w * h > gf_render_max_area)
        return gf_error_set(GF_ERR_PARAM, "render: a %.0f x %.0f picture is too large (at most %d a side, "
                                          "%.0f pixels); lower the scale or zmax",
                            w, h, GF_RENDER_MAX_PX, gf_render_max_area);
    return GF_OK;
}

/// "t = 12.5 τ": two decimals, trailing zeros dropped down to one (20.0, 0.25).
static void gf_render_time_text(char *buf, size_t n, double time)
{
    char num[48];
    snprintf(num, sizeof num, "%.2f", time);
    size_t len = strlen(num);
    if (len >= 4 && num[len - 1] == '0' && num[len - 3] == '.') num[len - 1] = '\0';
    snprintf(buf, n, "t = %s \xcf\x84", num);
}

gf_status gf_render_slice_size(const gf_packing *pk, const gf_config *cfg, const gf_render_opts *o,
                               int *width, int *height)
{
    gf_status st = gf_render_check(cfg, o, NULL);
    if (st != GF_OK) return st;
    gf_panel p;
    gf_panel_layout(cfg, o, gf_panel_zmax(pk, cfg, o), &p);
    double w = p.w + (o->colour == GF_RENDER_PHI ? gf_panel_bar_width(o) : 0);
    double h = (double)p.label + p.h;
    if ((st = gf_render_fits(w, h)) != GF_OK) return st;
    *width = (int)w;
    *height = (int)h;
    return GF_OK;
}

gf_status gf_render_slice(const gf_packing *pk, double time, const gf_config *cfg, const double *phi,
                          const gf_render_opts *o, const char *path)
{
    if (!pk || !path) return gf_error_set(GF_ERR_PARAM, "render: no packing or output path");
    if (o && o->colour == GF_RENDER_PHI && !phi && pk->n)
        return gf_error_set(GF_ERR_PARAM, "render %s: colouring by packing fraction needs the phi values", path);
    int w, h;
    gf_status st = gf_render_check(cfg, o, path);
    if (st == GF_OK) st = gf_render_slice_size(pk, cfg, o, &w, &h);
    if (st != GF_OK) return st;
    gf_panel p;
    gf_panel_layout(cfg, o, gf_panel_zmax(pk, cfg, o), &p);

    gf_canvas c;
    if ((st = gf_canvas_open(&c, path, o->format, w, h)) != GF_OK) return st;
    char text[64];
    gf_render_time_text(text, sizeof text, time);
    st = gf_panel_draw(c.cr, 0.0, 0.0, &p, pk, cfg, phi, o, text, o->title);
    if (st == GF_OK && o->colour == GF_RENDER_PHI) gf_panel_colour_bar(c.cr, p.w, 0.0, h, o);
    if (st != GF_OK) {
        gf_canvas_abort(&c);
        return st;
    }
    return gf_canvas_commit(&c);
}

gf_status gf_render_sheet(const gf_frame *frames, size_t n, const gf_config *cfg,
                          const double *const *phi, const gf_render_opts *o, const char *path)
{
    if (!frames || !n || !path) return gf_error_set(GF_ERR_PARAM, "render: a contact sheet needs frames and a path");
    gf_status st = gf_render_check(cfg, o, path);
    if (st != GF_OK) return st;
    if (o->colour == GF_RENDER_PHI && !phi)
        return gf_error_set(GF_ERR_PARAM, "render %s: colouring by packing fraction needs the phi values", path);

    double zmax = o->zmax;
    if (!isfinite(zmax)) {
        zmax = -INFINITY;
        for (size_t k = 0; k < n; k++) zmax = fmax(zmax, gf_panel_zmax(&frames[k].pk, cfg, o));
    }
    gf_panel p;
    gf_panel_layout(cfg, o, zmax, &p);
    size_t ncol = n < GF_SHEET_MAX_COLS ? n : GF_SHEET_MAX_COLS, nrow = (n + ncol - 1) / ncol;
    int title = o->title ? gf_render_label_px(&(gf_render_opts){.px_per_d = o->px_per_d, .label = true}) : 0;
    int bar = o->colour == GF_RENDER_PHI ? gf_panel_bar_width(o) : 0;
    double cell_h = (double)p.label + p.h;
    double w = (double)ncol * p.w + bar, h = title + (double)nrow * cell_h;
    if ((st = gf_render_fits(w, h)) != GF_OK) return st;

    gf_canvas c;
    if ((st = gf_canvas_open(&c, path, o->format, (int)w, (int)h)) != GF_OK) return st;
    cairo_set_source_rgb(c.cr, 1.0, 1.0, 1.0);
    cairo_paint(c.cr);
    if (title) gf_panel_text(c.cr, 0.5 * p.s * 4.0, 0.7 * title, 0.5 * title, o->title);
    char text[64];
    for (size_t k = 0; k < n && st == GF_OK; k++) {
        gf_render_time_text(text, sizeof text, frames[k].time);
        double ox = (double)(k % ncol) * p.w, oy = title + (double)(k / ncol) * cell_h;
        st = gf_panel_draw(c.cr, ox, oy, &p, &frames[k].pk, cfg, phi ? phi[k] : NULL, o, text, NULL);
    }
    if (st == GF_OK && bar) gf_panel_colour_bar(c.cr, (double)ncol * p.w, title, h - title, o);
    if (st != GF_OK) {
        gf_canvas_abort(&c);
        return st;
    }
    return gf_canvas_commit(&c);
}
