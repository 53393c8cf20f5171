// SPDX-License-Identifier: MIT
// Internal: every frame of a LAMMPS text dump with its time, box and `type` column;
// the line of one particle of a packing file.
#ifndef GF_IO_PACKING_FRAMES_H
#define GF_IO_PACKING_FRAMES_H

#include "granflow/core.h"
#include "granflow/particles.h"

/// What the header of one frame said.
typedef struct gf_packing_frame {
    long long timestep;  ///< ITEM: TIMESTEP (always present)
    int have_time;       ///< the frame has ITEM: TIME
    double time;         ///< its value, in the file's time unit (0 without it)
    int have_box;        ///< the frame has ITEM: BOX BOUNDS
    double lo[3], hi[3]; ///< the box, d (divided by the length unit of gf_packing_read_frames_in)
    int have_type;       ///< the ATOMS have a `type` column, read into pk->layer (else layer = 0)
    const int32_t *pass; ///< gf_packing_read_frames_pass only: granflow's `pass` column, one per
                         ///< particle of pk (NULL: no such column); valid during the callback only
    long line;           ///< line of the frame's first ITEM
} gf_packing_frame;

/// Called once per frame, in file order. `pk` holds the frame's particles; the
/// callback may keep them by moving the struct out and zeroing *pk. A status
/// other than GF_OK stops the reading and is returned.
typedef gf_status (*gf_packing_frame_fn)(void *ctx, const gf_packing_frame *f, gf_packing *pk);

/// Reads every frame of a LAMMPS text dump in one pass, with the same checks
/// and messages as gf_packing_read (truncated frames, bad columns, duplicate
/// ids, all naming the file and line). Unlike gf_packing_read, a frame may
/// have 0 atoms (a drained silo), ITEM: TIME is converted (a malformed value
/// is an error) and the `type` column becomes the layer tag.
gf_status gf_packing_read_frames(const char *path, gf_packing_frame_fn fn, void *ctx);
/// gf_packing_read_frames of a file whose particle diameter is `unit` in its
/// own length unit: positions, the radius or diameter column and the box are
/// divided by it, so they come out in d; a radius without a column stays
/// 0.5 d. Times are left in the file's unit.
gf_status gf_packing_read_frames_in(const char *path, double unit, gf_packing_frame_fn fn, void *ctx);

/// gf_packing_read of a file whose particle diameter is `unit` in its own
/// length unit, converted to d as gf_packing_read_frames_in does.
gf_status gf_packing_read_in(const char *path, gf_packing_format format, double unit, gf_packing *out);

/// Whether a row read (position and radius in d) is kept: 1 keeps it.
typedef int (*gf_packing_keep_fn)(void *ctx, const double xyz[3], double r);
/// gf_packing_read_in (format from the name) keeping only the rows `keep`
/// keeps, in file order; the others are read for their position and radius
/// only and cost no memory (a rank's region of a large packing, issue 23).
/// Without an id column, ids still number every row. A file whose rows are
/// all dropped reads as an empty packing.
gf_status gf_packing_read_where(const char *path, double unit, gf_packing_keep_fn keep, void *ctx, gf_packing *out);

/// gf_packing_read_frames that also reads granflow's `pass` column (a
/// positive integer, else GF_ERR_FORMAT naming file and line) into f->pass.
/// Only the snapshot reader asks for it: the series loaders ignore a DEM
/// dump's columns they do not use, whatever their values.
gf_status gf_packing_read_frames_pass(const char *path, gf_packing_frame_fn fn, void *ctx);

/// Line of the particle with id `id` in the packing file `path` as
/// gf_packing_read reads it (a dump's last complete frame; without an id
/// column, id i is the i-th row), or 0 when the file cannot be read or has no
/// such particle. For error messages: it reads the whole file again.
long gf_packing_line_of(const char *path, int64_t id);

#endif
