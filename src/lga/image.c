// SPDX-License-Identifier: MIT
// LGA density maps and contact sheets (cairo, PNG): darker = denser, as in the
// paper's Figs. 5-13; walls blue.
#include "lga/image.h"

#include <cairo.h>
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "lga/lattice.h"
#include "draw/canvas.h"

static const double gf_lga_wall_rgb[3] = {0.176, 0.400, 0.659}; // steel blue
static const double gf_lga_sink_rgb[3] = {0.95, 0.80, 0.80};
static const double gf_lga_text_rgb[3] = {0.10, 0.10, 0.12};
enum { GF_LGA_MAX_PX = 32767 };

gf_status gf_lga_frame_capture(const gf_lga *l, gf_lga_frame *f)
{
    memset(f, 0, sizeof *f);
    size_t n = (size_t)l->w * (size_t)l->h;
    double *d = GF_NEW(double, n);
    f->v = GF_NEW(uint8_t, n);
    if (!d || !f->v) {
        if (d) GF_DELETE(d, n);
        gf_lga_frame_free(f);
        return gf_error_set(GF_ERR_NOMEM, "out of memory (LGA density map)");
    }
    gf_lga_density_smoothed(l, d);
    for (int j = 0; j < l->h; j++)
        for (int i = 0; i < l->w; i++) {
            size_t k = (size_t)j * (size_t)l->w + (size_t)i;
            uint16_t s = l->state[gf_lga_index(l, i, j)];
            if (s & GF_LGA_WALL) f->v[k] = GF_LGA_FRAME_WALL;
            else if (s & GF_LGA_SINK) f->v[k] = GF_LGA_FRAME_SINK;
            else f->v[k] = (uint8_t)fmin(GF_LGA_FRAME_MAX, floor(100.0 * d[k] + 0.5));
        }
    GF_DELETE(d, n);
    f->iteration = l->iteration;
    f->w = l->w;
    f->h = l->h;
    return GF_OK;
}

void gf_lga_frame_free(gf_lga_frame *f)
{
    if (f->v) GF_DELETE(f->v, (size_t)f->w * (size_t)f->h);
    memset(f, 0, sizeof *f);
}

void gf_lga_frame_cell(double px, int *cw, int *rh)
{
    // rows px tall (even, so odd columns shift by a whole half), columns px sqrt(3)/2 wide
    int r = 2 * (int)fmax(1.0, floor(0.5 * px + 0.5));
    *rh = r;
    *cw = (int)fmax(1.0, floor(0.86602540378443864676 * r + 0.5));
}

static void gf_lga_frame_size(const gf_lga_frame *f, double px, int *w, int *h)
{
    int cw, rh;
    gf_lga_frame_cell(px, &cw, &rh);
    *w = f->w * cw;
    *h = f->h * rh + rh / 2;
}

// Paints frame f with its top-left corner at (x0, y0) of the ARGB32/RGB24 data.
static void gf_lga_frame_paint(const gf_lga_frame *f, double px, unsigned char *data, int stride, int x0, int y0)
{
    int cw, rh;
    gf_lga_frame_cell(px, &cw, &rh);
    int height = f->h * rh + rh / 2;
    for (int j = 0; j < f->h; j++)
        for (int i = 0; i < f->w; i++) {
            uint8_t v = f->v[(size_t)j * (size_t)f->w + (size_t)i];
            double rgb[3];
            if (v == GF_LGA_FRAME_WALL) memcpy(rgb, gf_lga_wall_rgb, sizeof rgb);
            else if (v == GF_LGA_FRAME_SINK) memcpy(rgb, gf_lga_sink_rgb, sizeof rgb);
            else {
                double g = 1.0 - 0.92 * fmin(1.0, v / (100.0 * GF_LGA_MAP_FULL)); // darker = denser
                rgb[0] = rgb[1] = rgb[2] = g;
            }
            uint32_t pix = 0xFF000000u | ((uint32_t)floor(255 * rgb[0] + 0.5) << 16) |
                           ((uint32_t)floor(255 * rgb[1] + 0.5) << 8) | (uint32_t)floor(255 * rgb[2] + 0.5);
            // y up: row j's bottom edge at height j rh (+ rh/2 in odd columns)
            int ybot = height - (j * rh + ((i & 1) ? rh / 2 : 0));
            for (int y = ybot - rh; y < ybot; y++) {
                uint32_t *p = (uint32_t *)(data + (size_t)(y0 + y) * (size_t)stride) + x0 + i * cw;
                for (int x = 0; x < cw; x++) p[x] = pix;
            }
        }
}

static int gf_lga_label_px(double scale) { return (int)fmax(20.0, floor(3.0 * scale + 0.5)); }

static void gf_lga_text(cairo_t *cr, double x, double y, double size, const char *text)
{
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, size);
    cairo_set_source_rgb(cr, gf_lga_text_rgb[0], gf_lga_text_rgb[1], gf_lga_text_rgb[2]);
    cairo_move_to(cr, x, y);
    cairo_show_text(cr, text);
}

// Draws the frames at (x0, y0) + layout into an image surface and paints it.
static gf_status gf_lga_paint_frames(cairo_t *cr, const gf_lga_frame *frames, size_t n, double px, int cols,
                                     int label, int top, int gap)
{
    int fw, fh;
    gf_lga_frame_size(&frames[0], px, &fw, &fh);
    int rows = (int)((n + (size_t)cols - 1) / (size_t)cols);
    int W = cols * fw + (cols - 1) * gap, H = rows * (fh + label) + (rows - 1) * gap;
    cairo_surface_t *img = cairo_image_surface_create(CAIRO_FORMAT_RGB24, W, H);
    if (cairo_surface_status(img) != CAIRO_STATUS_SUCCESS) {
        cairo_surface_destroy(img);
        return gf_error_set(GF_ERR_NOMEM, "out of memory (LGA picture of %d x %d pixels)", W, H);
    }
    cairo_surface_flush(img);
    unsigned char *data = cairo_image_surface_get_data(img);
    int stride = cairo_image_surface_get_stride(img);
    memset(data, 0xFF, (size_t)stride * (size_t)H);
    for (size_t k = 0; k < n; k++) {
        int c = (int)(k % (size_t)cols), r = (int)(k / (size_t)cols);
        gf_lga_frame_paint(&frames[k], px, data, stride, c * (fw + gap), r * (fh + label + gap) + label);
    }
    cairo_surface_mark_dirty(img);
    cairo_set_source_surface(cr, img, 0, top);
    cairo_paint(cr);
    cairo_surface_destroy(img);
    // labels
    for (size_t k = 0; label && k < n; k++) {
        int c = (int)(k % (size_t)cols), r = (int)(k / (size_t)cols);
        char buf[64];
        snprintf(buf, sizeof buf, "it %lld", (long long)frames[k].iteration);
        double size = fmin(0.6 * label, fmax(8.0, 1.6 * fw / (double)strlen(buf)));
        gf_lga_text(cr, c * (fw + gap) + 2, top + r * (fh + label + gap) + 0.75 * label, size, buf);
    }
    return GF_OK;
}

// Pixel size of n frames of frame0's size, cols per row, with or without a title.
static void gf_lga_draw_size(const gf_lga_frame *frame0, size_t n, double px, int cols, bool title, double *W,
                             double *H)
{
    int fw, fh;
    gf_lga_frame_size(frame0, px, &fw, &fh);
    int label = gf_lga_label_px(px), gap = n > 1 ? (int)fmax(4.0, px * 2) : 0;
    int rows = (int)((n + (size_t)cols - 1) / (size_t)cols);
    int top = title ? label : 0;
    *W = (double)cols * fw + (cols - 1) * gap;
    *H = top + rows * (double)(fh + label) + (rows - 1) * gap;
}

static bool gf_lga_size_ok(double W, double H) { return W <= GF_LGA_MAX_PX && H <= GF_LGA_MAX_PX && W * H <= 1e8; }

// The sheet's layout: tall maps (channel, silo) side by side in one row, as
// in the paper's Figs. 6 and 7; wide ones (the pile) in a grid about as wide
// as tall. Then the scale: at most ~2400 pixels wide and ~8000 tall, at least
// 2 pixels per spacing.
static void gf_lga_sheet_layout(const gf_lga_frame *frame0, size_t n, double *px, int *cols)
{
    double aspect = (frame0->h + 0.5) / (frame0->w * 0.86602540378443864676); // height / width of a map
    *cols = aspect >= 1.5 ? (int)n : (int)fmax(1.0, fmin((double)n, floor(sqrt((double)n * aspect) + 0.5)));
    double rows = ceil((double)n / *cols);
    *px = fmax(2.0, fmin(8.0, fmin(2400.0 / (*cols * frame0->w * 0.86602540378443864676),
                                   8000.0 / (rows * (frame0->h + 0.5)))));
}

gf_status gf_lga_pictures_check(int w, int h, double map_px, size_t sheet_frames)
{
    gf_lga_frame f0 = {.w = w, .h = h};
    double W, H, SW, SH, px;
    int cols;
    gf_lga_draw_size(&f0, 1, map_px, 1, true, &W, &H);
    gf_lga_sheet_layout(&f0, sheet_frames, &px, &cols);
    gf_lga_draw_size(&f0, sheet_frames, px, cols, true, &SW, &SH);
    if (gf_lga_size_ok(W, H) && gf_lga_size_ok(SW, SH)) return GF_OK;
    if (!gf_lga_size_ok(W, H)) SW = W, SH = H;
    return gf_error_set(GF_ERR_PARAM,
                        "a lattice of %d x %d sites is too large to draw: its %s would be %.0f x %.0f pixels "
                        "(at most %d on a side and 10^8 in all); lower lga.width or lga.height",
                        w, h, gf_lga_size_ok(W, H) ? "contact sheet" : "maps", SW, SH, (int)GF_LGA_MAX_PX);
}

static gf_status gf_lga_draw(const gf_lga_frame *frames, size_t n, double px, int cols, const char *title,
                             const char *path)
{
    if (n == 0) return gf_error_set(GF_ERR_PARAM, "LGA picture %s: no frames", path);
    for (size_t k = 1; k < n; k++)
        if (frames[k].w != frames[0].w || frames[k].h != frames[0].h)
            return gf_error_set(GF_ERR_PARAM, "LGA picture %s: frames of different sizes", path);
    int label = gf_lga_label_px(px), gap = n > 1 ? (int)fmax(4.0, px * 2) : 0;
    int top = title ? label : 0;
    double W, H;
    gf_lga_draw_size(&frames[0], n, px, cols, title != NULL, &W, &H);
    if (!gf_lga_size_ok(W, H))
        return gf_error_set(GF_ERR_PARAM, "LGA picture %s: %.0f x %.0f pixels is too large; lower the scale", path,
                            W, H);
    gf_canvas c;
    gf_status st = gf_canvas_open(&c, path, GF_RENDER_PNG, (int)W, (int)H);
    if (st != GF_OK) return st;
    cairo_set_source_rgb(c.cr, 1, 1, 1);
    cairo_paint(c.cr);
    if (title) gf_lga_text(c.cr, 2, 0.75 * label, 0.6 * label, title);
    st = gf_lga_paint_frames(c.cr, frames, n, px, cols, label, top, gap);
    if (st != GF_OK) {
        gf_canvas_abort(&c);
        return st;
    }
    return gf_canvas_commit(&c);
}

gf_status gf_lga_frame_draw(const gf_lga_frame *f, double px, const char *title, const char *path)
{
    if (!(px >= 1 && px <= 50)) return gf_error_set(GF_ERR_PARAM, "LGA map: scale %g is not in [1, 50] pixels", px);
    return gf_lga_draw(f, 1, px, 1, title, path);
}

gf_status gf_lga_sheet_draw(const gf_lga_frame *frames, size_t n, const char *title, const char *path)
{
    if (n == 0) return gf_error_set(GF_ERR_PARAM, "LGA sheet %s: no frames", path);
    double px;
    int cols;
    gf_lga_sheet_layout(&frames[0], n, &px, &cols);
    return gf_lga_draw(frames, n, px, cols, title, path);
}

gf_status gf_lga_render_map(const gf_lga *l, double px, const char *label, const char *path)
{
    if (!l || !path) return gf_error_set(GF_ERR_PARAM, "gf_lga_render_map: NULL argument");
    gf_lga_frame f;
    gf_status st = gf_lga_frame_capture(l, &f);
    if (st != GF_OK) return st;
    st = gf_lga_frame_draw(&f, px, label, path);
    gf_lga_frame_free(&f);
    return st;
}
