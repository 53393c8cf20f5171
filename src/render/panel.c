// SPDX-License-Identifier: MIT
// One panel of a picture: the container (walls, base, orifice) and the
// central slice of the packing seen from the -y side (2009 paper Fig. 3).
#include "render/panel.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "core/alloc.h"
#include "core/error.h"
#include "geom/container.h"
#include "granflow/defs.h"
#include "render/palette.h"

enum { GF_LABEL_MIN_PX = 28, GF_BAR_MIN_PX = 84 };
static const double gf_margin = 2.0; // empty border around the container, d
static const double gf_wall = 0.5;   // drawn thickness of the walls and the base, d

int gf_render_label_px(const gf_render_opts *o)
{
    if (!o->label) return 0;
    return (int)ceil(fmax(4.0 * o->px_per_d, (double)GF_LABEL_MIN_PX));
}

int gf_panel_bar_width(const gf_render_opts *o)
{
    return (int)ceil(fmax(GF_RENDER_BAR_WIDTH * o->px_per_d, (double)GF_BAR_MIN_PX));
}

double gf_panel_zmax(const gf_packing *pk, const gf_config *cfg, const gf_render_opts *o)
{
    if (isfinite(o->zmax)) return o->zmax;
    gf_container_defs cd;
    gf_config_container_defs(cfg, &cd);
    double top = cd.orifice.diameter;
    for (size_t i = 0; i < pk->n; i++)
        if (pk->z[i] + pk->r[i] > top) top = pk->z[i] + pk->r[i];
    return top;
}

void gf_panel_layout(const gf_config *cfg, const gf_render_opts *o, double zmax, gf_panel *p)
{
    gf_container_defs cd;
    gf_config_container_defs(cfg, &cd);
    double w = cd.width;
    p->s = o->px_per_d;
    p->xlo = -0.5 * w - gf_margin;
    p->ztop = zmax + 1.0;
    p->zbot = fmin(0.0, gf_config_exit_plane(cfg)) - gf_margin;
    // the small slack keeps exact products (e.g. 14 d x 10 px) from rounding up a pixel
    p->w = (int)ceil((w + 2.0 * gf_margin) * p->s - 1e-9);
    p->h = (int)ceil((p->ztop - p->zbot) * p->s - 1e-9);
    p->label = gf_render_label_px(o);
}

void gf_panel_text(cairo_t *cr, double x, double y, double size, const char *text)
{
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, size);
    cairo_set_source_rgb(cr, gf_palette_text[0], gf_palette_text[1], gf_palette_text[2]);
    cairo_move_to(cr, x, y);
    cairo_show_text(cr, text);
}

static double gf_text_width(cairo_t *cr, double size, const char *text)
{
    cairo_text_extents_t e;
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, size);
    cairo_text_extents(cr, text, &e);
    return e.x_advance;
}

/// "TEXT    TITLE" in `room` units of width: the title goes first when it does
/// not fit, then the font shrinks (to 9 units at least).
static void gf_panel_label(cairo_t *cr, double x, double y, double size, double room, const char *text,
                           const char *title)
{
    char both[320];
    if (title && title[0]) {
        snprintf(both, sizeof both, "%s    %s", text ? text : "", title);
        if (gf_text_width(cr, size, both) <= room) {
            gf_panel_text(cr, x, y, size, both);
            return;
        }
    }
    if (!text || !text[0]) return;
    double w = gf_text_width(cr, size, text);
    if (w > room && w > 0) size = fmax(9.0, size * room / w);
    gf_panel_text(cr, x, y, size, text);
}

typedef struct gf_depth {
    double y;
    size_t i;
} gf_depth;

/// Far (large y) first, so that the particles nearest the viewer end on top.
static int gf_depth_cmp(const void *a, const void *b)
{
    const gf_depth *u = a, *v = b;
    if (u->y != v->y) return u->y > v->y ? -1 : 1;
    return u->i < v->i ? -1 : (u->i > v->i);
}

static void gf_rect(cairo_t *cr, double x0, double y0, double x1, double y1)
{
    cairo_rectangle(cr, fmin(x0, x1), fmin(y0, y1), fabs(x1 - x0), fabs(y1 - y0));
}

gf_status gf_panel_draw(cairo_t *cr, double ox, double oy, const gf_panel *p, const gf_packing *pk,
                        const gf_config *cfg, const double *phi, const gf_render_opts *o,
                        const char *text, const char *title)
{
    const double s = p->s, vy = oy + p->label; // top of the view
    gf_container_defs cd;
    gf_config_container_defs(cfg, &cd);
#define GF_X(x) (ox + ((x) - p->xlo) * s)
#define GF_Y(z) (vy + (p->ztop - (z)) * s)
    const double hw = 0.5 * cd.width;
    // The orifice's edges in x (around container.orifice_x), within the walls.
    const double hl = fmax(cd.orifice.x - 0.5 * cd.orifice.diameter, -hw);
    const double hr = fmin(cd.orifice.x + 0.5 * cd.orifice.diameter, hw);

    // the set of visible particles, far first
    size_t m = 0;
    gf_depth *order = NULL;
    if (pk->n) {
        order = GF_NEW(gf_depth, pk->n);
        if (!order) return gf_error_set(GF_ERR_NOMEM, "out of memory sorting %zu particles", pk->n);
        for (size_t i = 0; i < pk->n; i++) {
            double r = pk->r[i], z = pk->z[i];
            if (!(pk->y[i] > o->ymin) || z - r > p->ztop || z + r < p->zbot) continue;
            order[m++] = (gf_depth){pk->y[i], i};
        }
        qsort(order, m, sizeof *order, gf_depth_cmp);
    }

    cairo_save(cr);
    cairo_rectangle(cr, ox, oy, p->w, p->label + p->h);
    cairo_clip(cr);
    cairo_set_source_rgb(cr, gf_palette_outside[0], gf_palette_outside[1], gf_palette_outside[2]);
    cairo_paint(cr);
    cairo_set_source_rgb(cr, gf_palette_inside[0], gf_palette_inside[1], gf_palette_inside[2]);
    const gf_container box = gf_container_make(cfg);
    // The slice y = 0 of the container (src/geom/: each shape draws its own):
    // the inside, then its walls as thick lines the particles then cover where
    // they touch, and a solid part (a column). A rectangular container's
    // walls and base are drawn after the particles, outside the inside.
    const bool rect = gf_container_rectangular(&box);
    gf_outline ol;
    gf_container_outline(&box, p->ztop, &ol);
    if (rect && ol.n == 4) {
        gf_rect(cr, GF_X(ol.p[0][0]), GF_Y(ol.p[0][1]), GF_X(ol.p[2][0]), GF_Y(ol.p[2][1]));
    } else {
        for (int k = 0; k < ol.n; k++) (k ? cairo_line_to : cairo_move_to)(cr, GF_X(ol.p[k][0]), GF_Y(ol.p[k][1]));
        cairo_close_path(cr);
    }
    cairo_fill(cr);
    cairo_set_source_rgb(cr, gf_palette_wall[0], gf_palette_wall[1], gf_palette_wall[2]);
    cairo_set_line_width(cr, 2.0 * gf_wall * s);
    for (int side = 0; side < 2; side++) {
        if (ol.nwall[side] < 2) continue;
        for (int k = 0; k < ol.nwall[side]; k++)
            (k ? cairo_line_to : cairo_move_to)(cr, GF_X(ol.wall[side][k][0]), GF_Y(ol.wall[side][k][1]));
        cairo_stroke(cr);
    }
    if (ol.nsolid >= 3) {
        for (int k = 0; k < ol.nsolid; k++) (k ? cairo_line_to : cairo_move_to)(cr, GF_X(ol.solid[k][0]), GF_Y(ol.solid[k][1]));
        cairo_close_path(cr);
        cairo_fill(cr);
    }

    // particles: flat discs with a darker rim so that touching ones stay apart
    const double rim = 0.07 * s;
    cairo_set_line_width(cr, rim);
    for (size_t k = 0; k < m; k++) {
        size_t i = order[k].i;
        double c[3];
        if (o->colour == GF_RENDER_PHI)
            gf_palette_phi(phi ? phi[i] : NAN, o->phi_lo, o->phi_hi, c);
        else
            gf_palette_layer(pk->layer[i], c);
        cairo_new_path(cr);
        cairo_arc(cr, GF_X(pk->x[i]), GF_Y(pk->z[i]), pk->r[i] * s - 0.5 * rim, 0.0, 6.283185307179586);
        cairo_set_source_rgb(cr, c[0], c[1], c[2]);
        if (s >= 3.0) {
            cairo_fill_preserve(cr);
            cairo_set_source_rgb(cr, 0.62 * c[0], 0.62 * c[1], 0.62 * c[2]);
            cairo_stroke(cr);
        } else {
            cairo_fill(cr);
        }
    }

    // walls and base, outside the container so they hide no particle
    cairo_set_source_rgb(cr, gf_palette_wall[0], gf_palette_wall[1], gf_palette_wall[2]);
    if (rect) gf_rect(cr, GF_X(-hw - gf_wall), GF_Y(-gf_wall), GF_X(-hw), GF_Y(p->ztop));
    if (rect) gf_rect(cr, GF_X(hw), GF_Y(-gf_wall), GF_X(hw + gf_wall), GF_Y(p->ztop));
    if (rect && hl > -hw) gf_rect(cr, GF_X(-hw - gf_wall), GF_Y(-gf_wall), GF_X(hl), GF_Y(0.0));
    if (rect && hr < hw) gf_rect(cr, GF_X(hr), GF_Y(-gf_wall), GF_X(hw + gf_wall), GF_Y(0.0));
    cairo_fill(cr);
    const double exit_plane = gf_config_exit_plane(cfg);
    if (exit_plane < 0.0) { // where particles leave, across the orifice
        double dash = 0.5 * s;
        cairo_set_dash(cr, &dash, 1, 0.0);
        cairo_set_line_width(cr, fmax(0.08 * s, 1.0));
        cairo_move_to(cr, GF_X(hl), GF_Y(exit_plane));
        cairo_line_to(cr, GF_X(hr), GF_Y(exit_plane));
        cairo_stroke(cr);
        cairo_set_dash(cr, NULL, 0, 0.0);
    }

    if (p->label) gf_panel_label(cr, GF_X(-hw), oy + 0.7 * p->label, 0.5 * p->label, p->w - 2.0 * (GF_X(-hw) - ox), text, title);
    cairo_restore(cr);
#undef GF_X
#undef GF_Y
    GF_DELETE(order, pk->n);
    return GF_OK;
}

void gf_panel_colour_bar(cairo_t *cr, double ox, double oy, double h, const gf_render_opts *o)
{
    const double bw = gf_panel_bar_width(o);
    const double fs = fmax(1.6 * o->px_per_d, 12.0);
    const double len = fmin(0.6 * h, fmax(30.0 * o->px_per_d, 10.0 * fs));
    const double x0 = ox + 0.1 * bw, x1 = x0 + fmax(0.15 * bw, 8.0);
    const double top = oy + 0.5 * (h - len), bot = top + len;

    cairo_save(cr);
    cairo_rectangle(cr, ox, oy, bw, h);
    cairo_clip(cr);
    cairo_set_source_rgb(cr, gf_palette_outside[0], gf_palette_outside[1], gf_palette_outside[2]);
    cairo_paint(cr);
    cairo_pattern_t *g = cairo_pattern_create_linear(0.0, bot, 0.0, top);
    int n = gf_palette_phi_stops();
    for (int k = 0; k < n; k++) {
        double c[3];
        gf_palette_phi_stop(k, c);
        cairo_pattern_add_color_stop_rgb(g, (double)k / (n - 1), c[0], c[1], c[2]);
    }
    cairo_rectangle(cr, x0, top, x1 - x0, len);
    cairo_set_source(cr, g);
    cairo_fill_preserve(cr);
    cairo_pattern_destroy(g);
    cairo_set_source_rgb(cr, gf_palette_text[0], gf_palette_text[1], gf_palette_text[2]);
    cairo_set_line_width(cr, 1.0);
    cairo_stroke(cr);

    char buf[32];
    for (int k = 0; k <= 2; k++) {
        double v = o->phi_lo + 0.5 * k * (o->phi_hi - o->phi_lo);
        double y = bot - 0.5 * k * len;
        cairo_set_source_rgb(cr, gf_palette_text[0], gf_palette_text[1], gf_palette_text[2]);
        cairo_move_to(cr, x1, y);
        cairo_line_to(cr, x1 + 0.4 * fs, y);
        cairo_stroke(cr);
        snprintf(buf, sizeof buf, "%.*f", o->phi_hi - o->phi_lo < 0.04 ? 3 : 2, v);
        gf_panel_text(cr, x1 + 0.6 * fs, y + 0.35 * fs, fs, buf);
    }
    gf_panel_text(cr, x0, top - 0.8 * fs, 1.3 * fs, "\xcf\x86"); // phi (U+03C6)
    cairo_restore(cr);
}
