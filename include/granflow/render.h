// SPDX-License-Identifier: MIT
// Pictures of a run (cairo): the central slice of a packing seen from the -y
// side, coloured by initial layer or by local packing fraction, and a contact
// sheet of several snapshots side by side (2009 paper Figs. 3, 4 and 6).
#ifndef GRANFLOW_RENDER_H
#define GRANFLOW_RENDER_H

#include <signal.h>
#include <stdbool.h>
#include <stddef.h>

#include "granflow/analysis.h"
#include "granflow/config.h"
#include "granflow/core.h"
#include "granflow/draw.h"
#include "granflow/packing.h"

#ifdef __cplusplus
extern "C" {
#endif

/// What a particle's colour shows.
typedef enum gf_render_colour {
    GF_RENDER_LAYER = 0, ///< its initial layer (`layer` tag): two colours alternating by parity
    GF_RENDER_PHI = 1,   ///< its local packing fraction (a per-particle array), with a colour bar
} gf_render_colour;

/// gf_render_format (PNG, SVG, PDF) is in granflow/draw.h, included above.

/// Options of a picture. Make them with gf_render_opts_default(), then change fields.
///
/// Layout (in d, times px_per_d, rounded up to whole pixels): the view spans
/// x in [-W/2 - 2, W/2 + 2] (W = container_width) and z from min(0, exit_z) - 2
/// up to zmax + 1; a strip of gf_render_label_px() pixels above it carries the
/// time; in phi mode a strip of max(GF_RENDER_BAR_WIDTH d, 84 px) on the right
/// holds the colour bar.
typedef struct gf_render_opts {
    gf_render_colour colour; ///< GF_RENDER_LAYER (default) or GF_RENDER_PHI
    gf_render_format format; ///< GF_RENDER_AUTO (default)
    double px_per_d;         ///< pixels (PNG) or points (SVG, PDF) per particle diameter d; default 10, range [1, 200]
    double phi_lo, phi_hi;   ///< packing fraction at the two ends of the colour scale; default 0.55, 0.65
    double zmax;             ///< top of the view, d; NaN (default): the highest particle top (at least the orifice diameter)
    double ymin;             ///< only particles with y > ymin are drawn, d; default 0 (the central slice)
    bool label;              ///< write the time (and title) above the picture; default true
    const char *title;       ///< text after the time, e.g. the run's name; NULL (default) for none
} gf_render_opts;

/// Width of the colour-bar strip in phi mode, d (84 pixels at least).
#define GF_RENDER_BAR_WIDTH 10.0

/// The defaults listed in gf_render_opts.
GF_API gf_render_opts gf_render_opts_default(void);

/// Height of the label strip above a picture, pixels (0 when opts->label is false):
/// max(4 d, 28 px), so the text stays readable at small scales.
GF_API int gf_render_label_px(const gf_render_opts *opts);

/// Size of the picture gf_render_slice would make, pixels or points.
GF_API gf_status gf_render_slice_size(const gf_packing *pk, const gf_config *cfg,
                                      const gf_render_opts *opts, int *width, int *height);

/// Draws the particles of `pk` with y > opts->ymin as discs of their radius,
/// x to the right and z up (seen from the -y side), the far ones first, inside
/// the container of `cfg` (side walls, base and orifice drawn), with "t = TIME τ"
/// above. `phi` (pk->n packing fractions, NaN = unknown, drawn grey) is required
/// in phi mode and ignored otherwise. Writes `path` atomically (PATH.tmp, then
/// rename): on failure no file is left behind. GF_ERR_PARAM on bad options,
/// GF_ERR_IO when the file cannot be written.
GF_API gf_status gf_render_slice(const gf_packing *pk, double time, const gf_config *cfg,
                                 const double *phi, const gf_render_opts *opts, const char *path);

/// A contact sheet: the n frames side by side (at most 10 a row, in the order
/// given), each drawn as by gf_render_slice with its time above it, all to the
/// same scale and the same zmax (opts->zmax, or the highest of all frames);
/// opts->title, when set, goes in a strip above them all, and in phi mode one
/// colour bar on the right. `phi` is ignored in layer mode; in phi mode it
/// holds n arrays (frames[k].pk.n values each; a NULL array draws that frame
/// grey). Written atomically.
GF_API gf_status gf_render_sheet(const gf_frame *frames, size_t n, const gf_config *cfg,
                                 const double *const *phi, const gf_render_opts *opts,
                                 const char *path);

/// Options of gf_render_dir. Make them with gf_render_dir_opts_default(), then change fields.
typedef struct gf_render_dir_opts {
    gf_render_colour colour; ///< GF_RENDER_LAYER (default) or GF_RENDER_PHI
    bool raw;                ///< phi: each particle's volume over its Voronoi cell's (2009 paper Fig. 6;
                             ///< files *_phi_raw.*), not the field averaged within 2.2 d (Fig. 4; *_phi.*)
    const char *format;      ///< "png" (default), "svg" or "pdf": the files' extension and format
    double scale;            ///< pixels per particle diameter, 1 to 200 (default 10; the sheet uses half)
    const double *times;     ///< draw the snapshots nearest these times, tau (ntimes of them; may be NULL)
    size_t ntimes;
    bool all;                ///< draw every snapshot (not with times)
    bool sheet;              ///< the contact sheet (only it, unless times or all)
    size_t panels;           ///< snapshots on the contact sheet, evenly spaced, 1 to 40 (default 8)
    const char *outdir;      ///< where the pictures go; NULL (default): DIR/render, or render/ beside a dump file
    void (*written)(void *ctx, const char *path); ///< called with each file written; may be NULL
    void *ctx;               ///< passed to written
    volatile sig_atomic_t *stop; ///< polled at every snapshot read and picture drawn: once non-zero,
                                 ///< GF_ERR_INTERRUPTED (each picture is whole: written atomically); NULL: never
} gf_render_dir_opts;

/// The defaults listed in gf_render_dir_opts.
GF_API gf_render_dir_opts gf_render_dir_opts_default(void);

/// The pictures of a run directory, a directory of LAMMPS dumps or one dump
/// file (gf_series_load): slice_NNNNNN[_phi|_phi_raw].EXT for the chosen
/// snapshots (NNNNNN: the index in time order) and sheet[...].EXT, the contact
/// sheet, in opt->outdir (created). Without times, all or sheet: the first,
/// middle and last snapshots in opt->colour, the last also by packing fraction
/// when colouring by layer, and the sheet. Every picture has the same height,
/// the highest particle top of the run; the run's name (DIR's last component)
/// is its title. A time with no snapshot at it draws the nearest, with a
/// warning (gf_warning). GF_ERR_PARAM on bad options, GF_ERR_STATE when there
/// is no snapshot, or the error of reading the series or writing a picture.
GF_API gf_status gf_render_dir(const char *dir, const gf_render_dir_opts *opt);

#ifdef __cplusplus
}
#endif
#endif
