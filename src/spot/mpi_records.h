// SPDX-License-Identifier: MIT
// Internal: the records of the MPI exchange of the spatial fixed step
// (par_mpi.c packs them; mpi_records.c checks and applies a received
// message). Apart from par_mpi.c, so that the checks of a received message
// are built, and tested, in every build (tests/test_mpi_records.c).
//
// A message: u32 length in bytes, u32 count of each kind (GF_TOUCH_*), then
// the records kind by kind: particle (gf_mpi_part), moved (gf_mpi_pos), row
// (u32 index, the neighbour-list row), cell (gf_mpi_cell, its GF_CELL_CAP
// slots), spot (gf_mpi_spot), block (u32 index, the block's bytes).
#ifndef GF_SPOT_MPI_RECORDS_H
#define GF_SPOT_MPI_RECORDS_H

#include <stddef.h>
#include <stdint.h>

#include "spot/sim_internal.h"

/// A particle's whole record: with its id, layer tag and history, which a
/// rank that read only its region of the packing (window.c) has not for a
/// particle entering that region from beyond it.
typedef struct gf_mpi_part {
    uint32_t i, cell, slot, alive;
    gf_pos p;
    gf_ref p0;
    int64_t id;
    int32_t layer, pad_;
    gf_hist hist;
} gf_mpi_part;

/// Particle i's whole record.
static inline gf_mpi_part gf_mpi_part_of(const gf_sim *sim, uint32_t i)
{
    const gf_grid *g = &sim->grid;
    return (gf_mpi_part){i, g->cell_of[i], g->slot_of[i], sim->alive[i], sim->p[i], sim->p0[i],
                         sim->id[i], sim->layer[i], 0, sim->hist[i]};
}

/// A cell's record, followed by its GF_CELL_CAP slots.
typedef struct gf_mpi_cell {
    uint32_t c, count;
} gf_mpi_cell;

/// A moved particle's record: its position only.
typedef struct gf_mpi_pos {
    uint32_t i, pad_;
    double x, y, z;
} gf_mpi_pos;

/// A spot's record.
typedef struct gf_mpi_spot {
    double x, y, z, next; ///< next: the time of its next move (the domain engine's clock)
    uint32_t k, count, dead, pad_;
} gf_mpi_spot;

/// The message's head: its length and the count of each kind.
typedef struct gf_mpi_head {
    uint32_t v[1 + GF_TOUCH_KINDS];
} gf_mpi_head;

/// Entry limits (indices must be below them) and record sizes of each kind.
void gf_mpi_records_kinds(const gf_sim *sim, size_t nblock, size_t block_size, size_t limit[GF_TOUCH_KINDS],
                          size_t rec[GF_TOUCH_KINDS]);

/// Whether the `len` bytes at msg, rank `from`'s message, are a message this
/// sim can apply: its head's length is len and matches its counts, and every
/// record's index (particle, cell, slot, list entry, spot, block) is in range.
/// GF_ERR_STATE naming the rank and the record otherwise (the ranks are out of
/// step, or run different configurations); every rank checks every message,
/// so all come to the same answer without another collective.
gf_status gf_mpi_records_check(const gf_sim *sim, const unsigned char *msg, size_t len, size_t nblock,
                               size_t block_size, int from);

/// Applies a checked message: every kind but the cells (cells = false), or
/// the cells (cells = true), whose slots also give the cell and slot of every
/// particle in them (taken last, over the particles' own records). Adds the
/// particle and cell records applied to *parts and *cells.
void gf_mpi_records_apply(gf_sim *sim, const unsigned char *msg, uint8_t *dead, void *blocks, size_t nblock,
                          size_t block_size, bool cells, uint64_t *parts, uint64_t *ncells);

#endif
