// SPDX-License-Identifier: MIT
// Internal: density maps of the LGA as pictures (paper Figs. 5-13: darker =
// denser) and contact sheets of several iterations.
#ifndef GF_LGA_IMAGE_H
#define GF_LGA_IMAGE_H

#include <stddef.h>
#include <stdint.h>

#include "granflow/lga.h"

/// Particles per site (smoothed) at which a map is black.
#define GF_LGA_MAP_FULL 1.0
/// Codes of a frame's sites beyond the density.
enum { GF_LGA_FRAME_WALL = 255, GF_LGA_FRAME_SINK = 254, GF_LGA_FRAME_MAX = 253 };

/// One captured density map: v[j * w + i] = round(100 x smoothed density),
/// at most GF_LGA_FRAME_MAX, or a wall/sink code.
typedef struct gf_lga_frame {
    int64_t iteration;
    int w, h;
    uint8_t *v;
} gf_lga_frame;

/// Captures the engine's current smoothed density.
gf_status gf_lga_frame_capture(const gf_lga *l, gf_lga_frame *f);

/// Frees a frame's data.
void gf_lga_frame_free(gf_lga_frame *f);

/// Pixel size of a site column and row at `px` pixels per lattice spacing.
void gf_lga_frame_cell(double px, int *cw, int *rh);

/// Draws one frame (`px` pixels per lattice spacing) with "iteration N" and
/// `title` (may be NULL) above it, to a PNG at `path`, atomically.
gf_status gf_lga_frame_draw(const gf_lga_frame *f, double px, const char *title, const char *path);

/// A contact sheet of the n frames in the given order, all at one scale
/// (chosen so that the sheet is at most about 2400 pixels wide and 8000 tall,
/// 2 pixels per spacing at least): tall maps in one row, wide ones in a grid about as wide
/// as tall; written atomically as a PNG.
gf_status gf_lga_sheet_draw(const gf_lga_frame *frames, size_t n, const char *title, const char *path);

/// GF_OK if the maps of a w x h lattice (at `map_px`, with a title) and a
/// contact sheet of `sheet_frames` of them fit the picture limits; otherwise
/// GF_ERR_PARAM naming the size. Checked before a run starts, so that a
/// lattice too large to draw is refused up front, not after its run.
gf_status gf_lga_pictures_check(int w, int h, double map_px, size_t sheet_frames);

#endif
