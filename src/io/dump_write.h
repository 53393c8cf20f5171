// SPDX-License-Identifier: MIT
// Internal: the one writer of a LAMMPS text-dump frame (ITEM: TIMESTEP ...
// ITEM: ATOMS and the atom lines). A run's snapshots (snapshot.c) and packing
// exports (packing_write.c) both write through it; they differ only in the
// frame's options below.
#ifndef GF_IO_DUMP_WRITE_H
#define GF_IO_DUMP_WRITE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "granflow/particles.h"

/// How the numbers of a frame are written.
typedef enum gf_dump_numbers {
    /// A run's snapshot: positions to 1e-7 d (%.7f; what analysis needs, and
    /// a third of the bytes of an exact form), radii %.7g, the box %.17g,
    /// types the layer tags as they are.
    GF_DUMP_SNAPSHOT,
    /// A packing to read back: every number the shortest text that reads back
    /// bit for bit (gf_dump_exact), types below 1 written as 1 (LAMMPS'
    /// atom types start at 1).
    GF_DUMP_EXACT,
} gf_dump_numbers;

/// One frame: the particles and what goes around them.
typedef struct gf_dump_frame {
    const gf_packing *p;
    gf_dump_numbers numbers;
    bool has_time;         ///< an ITEM: TIME section (time, tau) before ITEM: TIMESTEP
    double time;
    uint64_t step;         ///< ITEM: TIMESTEP
    double lo[3], hi[3];   ///< ITEM: BOX BOUNDS ff ff ff
    bool radius;           ///< a radius column
    const int32_t *pass;   ///< a pass column, one per particle (NULL: none)
} gf_dump_frame;

/// Writes the frame to `f` (the caller opens and commits the file).
void gf_dump_write_frame(FILE *f, const gf_dump_frame *fr);

/// The shortest of %.15g and %.17g that reads back as exactly v, so a
/// written number reads back bit for bit while typical values such as 0.5
/// stay short. Used for the exact dumps and for XYZ and CSV.
void gf_dump_exact(char *buf, size_t size, double v);

#endif
