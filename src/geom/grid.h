// SPDX-License-Identifier: MIT
// Internal: uniform cell grid over the container with fixed-capacity cells
// (STYLE item 8). Points outside the grid are clamped into its edge cells, so
// every particle is always findable; queries test true distances.
// Not the counting-sort cell list of geom/celllist.h: the engine moves one
// particle at a time between two reads, so its cells must take O(1) inserts
// and removals (and be saved in checkpoints slot by slot), which a list
// sorted once per build cannot do.
#ifndef GF_GEOM_GRID_H
#define GF_GEOM_GRID_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "core/limits.h"
#include "granflow/core.h"

#define GF_NO_CELL UINT32_MAX

typedef struct gf_grid {
    double ox, oy, oz;   ///< origin (lower corner)
    double h, inv_h;     ///< cell edge and its inverse
    int nx, ny, nz;      ///< cells per axis
    size_t ncell;        ///< nx * ny * nz
    uint32_t *count;     ///< particles per cell
    uint32_t *slot;      ///< cell c holds slot[c * GF_CELL_CAP + k], k < count[c]
    int32_t *top;        ///< per column (cx + nx cy): highest non-empty cz, -1 if none
    bool lazy_top;       ///< top[] not kept by insert/remove (parallel phases): gf_grid_recompute_top after
    size_t np;           ///< capacity of the per-particle arrays
    size_t i0, i1;       ///< the particles gf_grid_clear resets, [i0, i1): all but on an MPI rank
                         ///< holding its region only (spot/window.c), whose other pages stay untouched
    uint32_t *cell_of;   ///< per particle: its cell, GF_NO_CELL when not in the grid
    uint32_t *slot_of;   ///< per particle: its position k in that cell
} gf_grid;

/// Grid covering [lo, hi] with cells of edge ~h, for particle indices < np.
gf_status gf_grid_init(gf_grid *g, const double lo[3], const double hi[3], double h, size_t np);
/// gf_grid_init whose clearing (gf_grid_clear) resets the particles [i0, i1)
/// only: the pages of the others' records are never touched (spot/window.c).
gf_status gf_grid_init_part(gf_grid *g, const double lo[3], const double hi[3], double h, size_t np, size_t i0,
                            size_t i1);
/// The grid's geometry alone (origin, cell size, cells per axis, with the
/// checks of gf_grid_init), nothing allocated: which cell layer a point
/// falls in, before the grid is made.
gf_status gf_grid_shape(gf_grid *g, const double lo[3], const double hi[3], double h, size_t np);
void gf_grid_free(gf_grid *g);
/// Empties every cell.
void gf_grid_clear(gf_grid *g);

static inline int gf_grid_axis(double v, double o, double inv_h, int n)
{
    double f = (v - o) * inv_h;
    if (!(f >= 0.0)) return 0; // also catches NaN
    if (f >= (double)n) return n - 1; // before the cast: a far point would not fit an int
    return (int)f;
}

/// Cell index of a point (clamped).
static inline uint32_t gf_grid_cell(const gf_grid *g, double x, double y, double z)
{
    int cx = gf_grid_axis(x, g->ox, g->inv_h, g->nx);
    int cy = gf_grid_axis(y, g->oy, g->inv_h, g->ny);
    int cz = gf_grid_axis(z, g->oz, g->inv_h, g->nz);
    return (uint32_t)((cz * g->ny + cy) * g->nx + cx);
}

/// The coordinates (cx, cy, cz) of a cell index.
static inline void gf_grid_cell_coords(const gf_grid *g, size_t cell, int c[3])
{
    c[0] = (int)(cell % (size_t)g->nx);
    c[1] = (int)(cell / (size_t)g->nx % (size_t)g->ny);
    c[2] = (int)(cell / ((size_t)g->nx * (size_t)g->ny));
}

/// Column index (cx + nx cy) of a point (clamped).
static inline uint32_t gf_grid_column(const gf_grid *g, double x, double y)
{
    return (uint32_t)(gf_grid_axis(y, g->oy, g->inv_h, g->ny) * g->nx + gf_grid_axis(x, g->ox, g->inv_h, g->nx));
}
/// The column (cx + nx cy) of cell c, and its layer cz in *cz.
static inline uint32_t gf_grid_cell_column(const gf_grid *g, uint32_t c, int32_t *cz)
{
    const uint32_t layer = (uint32_t)g->nx * (uint32_t)g->ny;
    *cz = (int32_t)(c / layer);
    return c % layer;
}
/// The highest non-empty layer of column col at or below layer z (-1: none).
static inline int32_t gf_grid_top_from(const gf_grid *g, uint32_t col, int32_t z)
{
    const size_t layer = (size_t)g->nx * (size_t)g->ny;
    while (z >= 0 && g->count[(size_t)z * layer + col] == 0) z--;
    return z;
}
/// The particles of cell (cx, cy, cz): *n of them from the returned slots.
static inline const uint32_t *gf_grid_slots(const gf_grid *g, int cx, int cy, int cz, uint32_t *n)
{
    size_t cell = ((size_t)cz * (size_t)g->ny + (size_t)cy) * (size_t)g->nx + (size_t)cx;
    *n = g->count[cell];
    return g->slot + cell * GF_CELL_CAP;
}

/// Puts particle i into cell c. GF_ERR_STATE when the cell is full.
gf_status gf_grid_insert(gf_grid *g, uint32_t i, uint32_t c);
/// Takes particle i out of its cell (no-op when it is in none).
void gf_grid_remove(gf_grid *g, uint32_t i);

/// Moves particle i to the cell of (x, y, z) if that differs from its cell.
static inline gf_status gf_grid_update(gf_grid *g, uint32_t i, double x, double y, double z)
{
    uint32_t c = gf_grid_cell(g, x, y, z);
    if (c == g->cell_of[i]) return GF_OK;
    gf_grid_remove(g, i);
    return gf_grid_insert(g, i, c);
}

/// Refills the cells from saved counts and slots (a checkpoint), so that the
/// order particles are found in, and with it every floating-point sum, is
/// the one of the run that saved them. GF_ERR_FORMAT if they are inconsistent.
gf_status gf_grid_restore(gf_grid *g, const uint32_t *count, const uint32_t *slot, size_t np);

/// Inclusive cell ranges of the box [c - r, c + r] (clamped to the grid).
void gf_grid_range(const gf_grid *g, const double c[3], double r, int lo[3], int hi[3]);

/// Recomputes top[] from the counts (after phases that ran with lazy_top).
void gf_grid_recompute_top(gf_grid *g);
/// The same for the columns [col0, col1) only (columns side by side).
void gf_grid_recompute_top_cols(gf_grid *g, size_t col0, size_t col1);
/// Largest z among particles in the column of cells containing (x, y), or
/// -INFINITY when the column is empty. `z` is the particles' z array, stride `stride`.
double gf_grid_column_top(const gf_grid *g, double x, double y, const double *z, size_t stride);
/// The same for column `col` (cx + nx cy).
double gf_grid_column_top_at(const gf_grid *g, uint32_t col, const double *z, size_t stride);

#endif
