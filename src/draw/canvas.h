// SPDX-License-Identifier: MIT
// Internal: a cairo surface of any format whose file is written atomically
// (PATH.tmp through a stream, renamed over PATH on success, removed on failure).
// The drawing layer (src/draw/, layer 1): no model knowledge; render and lga draw on it.
#ifndef GF_DRAW_CANVAS_H
#define GF_DRAW_CANVAS_H

#include <cairo.h>
#include <stdio.h>

#include "granflow/config.h"
#include "granflow/core.h"
#include "granflow/draw.h"

typedef struct gf_canvas {
    cairo_surface_t *surface;
    cairo_t *cr;
    gf_render_format format; ///< resolved: PNG, SVG or PDF
    FILE *f;                 ///< PATH.tmp
    char tmp[GF_PATH_MAX + 8];
    const char *path;
    int write_failed;        ///< the stream could not write (disk full, ...)
} gf_canvas;

/// The format `fmt` stands for with `path` (GF_RENDER_AUTO: by the extension).
gf_render_format gf_canvas_format(gf_render_format fmt, const char *path);

/// Opens PATH.tmp and a width x height surface (pixels or points) on it.
gf_status gf_canvas_open(gf_canvas *c, const char *path, gf_render_format fmt, int width, int height);

/// Finishes the picture, writes it, renames PATH.tmp over PATH. Frees everything.
gf_status gf_canvas_commit(gf_canvas *c);

/// Frees everything and removes PATH.tmp (after the caller's own error).
void gf_canvas_abort(gf_canvas *c);

#endif
