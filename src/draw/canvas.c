// SPDX-License-Identifier: MIT
// A cairo surface written atomically, in PNG, SVG or PDF.
#include "draw/canvas.h"

#include <cairo-pdf.h>
#include <cairo-svg.h>
#include <errno.h>
#include <string.h>
#include <strings.h>

#include "core/atomic_file.h"
#include "core/error.h"

gf_render_format gf_canvas_format(gf_render_format fmt, const char *path)
{
    if (fmt != GF_RENDER_AUTO) return fmt;
    const char *dot = strrchr(path, '.');
    const char *slash = strrchr(path, '/');
    if (dot && (!slash || dot > slash)) {
        if (strcasecmp(dot, ".svg") == 0) return GF_RENDER_SVG;
        if (strcasecmp(dot, ".pdf") == 0) return GF_RENDER_PDF;
    }
    return GF_RENDER_PNG;
}

static cairo_status_t gf_canvas_write(void *closure, const unsigned char *data, unsigned int length)
{
    gf_canvas *c = closure;
    if (fwrite(data, 1, length, c->f) != length) {
        c->write_failed = errno ? errno : EIO;
        return CAIRO_STATUS_WRITE_ERROR;
    }
    return CAIRO_STATUS_SUCCESS;
}

static void gf_canvas_release(gf_canvas *c)
{
    if (c->cr) cairo_destroy(c->cr);
    if (c->surface) cairo_surface_destroy(c->surface);
    c->cr = NULL;
    c->surface = NULL;
}

gf_status gf_canvas_open(gf_canvas *c, const char *path, gf_render_format fmt, int width, int height)
{
    memset(c, 0, sizeof *c);
    c->path = path;
    c->format = gf_canvas_format(fmt, path);
    gf_status st = gf_atomic_open(path, c->tmp, sizeof c->tmp, &c->f);
    if (st != GF_OK) return st;
    switch (c->format) {
    case GF_RENDER_SVG:
        c->surface = cairo_svg_surface_create_for_stream(gf_canvas_write, c, width, height);
        if (cairo_surface_status(c->surface) == CAIRO_STATUS_SUCCESS)
            cairo_svg_surface_set_document_unit(c->surface, CAIRO_SVG_UNIT_PX);
        break;
    case GF_RENDER_PDF:
        c->surface = cairo_pdf_surface_create_for_stream(gf_canvas_write, c, width, height);
        if (cairo_surface_status(c->surface) == CAIRO_STATUS_SUCCESS)
            cairo_pdf_surface_set_metadata(c->surface, CAIRO_PDF_METADATA_CREATOR, "granflow");
        break;
    default:
        c->format = GF_RENDER_PNG;
        c->surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height);
        break;
    }
    cairo_status_t cs = cairo_surface_status(c->surface);
    if (cs == CAIRO_STATUS_SUCCESS) {
        c->cr = cairo_create(c->surface);
        cs = cairo_status(c->cr);
    }
    if (cs != CAIRO_STATUS_SUCCESS) {
        gf_canvas_abort(c);
        return gf_error_set(cs == CAIRO_STATUS_NO_MEMORY ? GF_ERR_NOMEM : GF_ERR_IO,
                            "cannot draw %s (%d x %d): %s", path, width, height,
                            cairo_status_to_string(cs));
    }
    return GF_OK;
}

gf_status gf_canvas_commit(gf_canvas *c)
{
    cairo_status_t cs = cairo_status(c->cr);
    if (cs == CAIRO_STATUS_SUCCESS) {
        if (c->format == GF_RENDER_PNG) {
            cairo_surface_flush(c->surface);
            cs = cairo_surface_write_to_png_stream(c->surface, gf_canvas_write, c);
        } else {
            cairo_surface_finish(c->surface); // vector surfaces write their tail here
            cs = cairo_surface_status(c->surface);
        }
    }
    gf_canvas_release(c);
    if (cs != CAIRO_STATUS_SUCCESS || c->write_failed) {
        gf_status st = gf_error_set(GF_ERR_IO, "cannot write %s: %s", c->path,
                                    c->write_failed ? strerror(c->write_failed)
                                                    : cairo_status_to_string(cs));
        gf_atomic_abort(c->f, c->tmp);
        c->f = NULL;
        return st;
    }
    gf_status st = gf_atomic_commit(c->f, c->tmp, c->path);
    c->f = NULL;
    return st;
}

void gf_canvas_abort(gf_canvas *c)
{
    gf_canvas_release(c);
    if (c->f) gf_atomic_abort(c->f, c->tmp);
    c->f = NULL;
}
