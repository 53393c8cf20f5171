// SPDX-License-Identifier: MIT
// Picture file formats, shared by every drawing (the drawing layer, src/draw/:
// a cairo canvas with no model knowledge, used by render and lga alike).
// granflow/render.h includes this header.
#ifndef GRANFLOW_DRAW_H
#define GRANFLOW_DRAW_H

#ifdef __cplusplus
extern "C" {
#endif

/// File format of a picture.
typedef enum gf_render_format {
    GF_RENDER_AUTO = 0, ///< from the file name: .svg, .pdf, anything else PNG
    GF_RENDER_PNG,      ///< raster, px_per_d pixels per d
    GF_RENDER_SVG,      ///< vector, px_per_d points per d
    GF_RENDER_PDF,      ///< vector, px_per_d points per d
} gf_render_format;

#ifdef __cplusplus
}
#endif
#endif
