// SPDX-License-Identifier: MIT
// Internal: the one counting-sort cell list. Points are binned into the
// cells of a box grid and listed cell by cell (compressed rows), in
// increasing index order within a cell, so every sum over a neighbourhood
// comes out the same bits on every build. O(n) to build, any number of
// points per cell; built once over a set of points (a frame, a packing, a
// generator sweep, the spots of a step) and then only read.
//
// The engine grid (geom/grid.h) has another job: particles move one at a
// time between two reads, so it keeps fixed-capacity cells with O(1) insert
// and remove, which a counting sort cannot do without a rebuild.
#ifndef GF_GEOM_CELLLIST_H
#define GF_GEOM_CELLLIST_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "granflow/core.h"

/// The cell of a point left out of the list (a non-finite coordinate, a dead particle).
#define GF_CELLLIST_OUT UINT32_MAX

typedef struct gf_celllist {
    double lo[3];    ///< lower corner of the grid
    double inv[3];   ///< cells per unit length along each axis
    int n[3];        ///< cells per axis (0 for a list sorted by given keys)
    size_t ncell;    ///< cells (or keys)
    size_t *start;   ///< ncell + 1 offsets: cell c holds idx[start[c]] .. idx[start[c + 1] - 1]
    uint32_t *idx;   ///< the points listed, by cell
    size_t nidx;     ///< how many are listed
    uint32_t *cell;  ///< per point: its cell, or GF_CELLLIST_OUT
    size_t cap_cell, cap_point; ///< allocated lengths of start (less one) and of idx / cell, kept across rebuilds
} gf_celllist;

/// A grid of n[0] x n[1] x n[2] cells from `lo`, inv[k] cells per unit
/// length along axis k. Keeps the storage of an earlier build.
gf_status gf_celllist_grid(gf_celllist *cl, const double lo[3], const double inv[3], const int n[3]);

/// Bins the n points (x[i], y[i], z[i]) into the grid (points outside it go
/// to its edge cells; non-finite ones are left out) and sorts them by cell.
gf_status gf_celllist_bin(gf_celllist *cl, const double *x, const double *y, const double *z, size_t n);

/// The usual neighbour-search list: a grid over the finite points' bounding
/// box with cubic cells of edge at least h (larger when the points are spread
/// so thinly that cells would outnumber them by far), then gf_celllist_bin.
gf_status gf_celllist_fit(gf_celllist *cl, const double *x, const double *y, const double *z, size_t n, double h);

/// A list of n points sorted by keys the caller computes: makes room, sets
/// ncell; the caller then writes cl->cell[i] < ncell (or GF_CELLLIST_OUT) for
/// every i < n and calls gf_celllist_sort.
gf_status gf_celllist_keys(gf_celllist *cl, size_t ncell, size_t n);
/// The counting sort of the points 0 .. n-1 by cl->cell (stable).
void gf_celllist_sort(gf_celllist *cl, size_t n);

void gf_celllist_free(gf_celllist *cl);

/// Cell along axis k of coordinate v (clamped into the grid; NaN gives 0).
static inline int gf_celllist_axis(const gf_celllist *cl, int k, double v)
{
    double f = (v - cl->lo[k]) * cl->inv[k];
    if (!(f >= 0.0)) return 0;
    if (f >= (double)cl->n[k]) return cl->n[k] - 1; // before the cast: a far point would not fit an int
    return (int)f;
}

/// Cell index of (cx, cy, cz).
static inline size_t gf_celllist_index(const gf_celllist *cl, int cx, int cy, int cz)
{
    return ((size_t)cz * (size_t)cl->n[1] + (size_t)cy) * (size_t)cl->n[0] + (size_t)cx;
}

/// Inclusive cell ranges lo..hi per axis covering the cube [c - r, c + r].
void gf_celllist_range(const gf_celllist *cl, const double c[3], double r, int lo[3], int hi[3]);

/// The idx ranges [lo[s], hi[s]) of the non-empty cells among the 13
/// "forward" neighbours of cell (cx, cy, cz) (those after it in index order):
/// over all cells, every two neighbouring cells come once. Returns how many.
int gf_celllist_forward(const gf_celllist *cl, int cx, int cy, int cz, size_t lo[13], size_t hi[13]);

/// Walks the points of every cell that meets the cube [c - r, c + r], cell by
/// cell in index order (z, then y, then x), in list order within a cell:
///     gf_celllist_near it; gf_celllist_near_start(&it, cl, c, r);
///     for (size_t j; gf_celllist_near_next(&it, &j);) ...
/// Callers test the true distance.
typedef struct gf_celllist_near {
    const gf_celllist *cl;
    int lo[3], hi[3];
    int cx, cy, cz;
    size_t q, end;
} gf_celllist_near;

static inline void gf_celllist_near_start(gf_celllist_near *it, const gf_celllist *cl, const double c[3], double r)
{
    it->cl = cl;
    gf_celllist_range(cl, c, r, it->lo, it->hi);
    it->cx = it->lo[0] - 1;
    it->cy = it->lo[1];
    it->cz = it->lo[2];
    it->q = it->end = 0;
}

static inline bool gf_celllist_near_next(gf_celllist_near *it, size_t *j)
{
    while (it->q == it->end) {
        if (++it->cx > it->hi[0]) {
            it->cx = it->lo[0];
            if (++it->cy > it->hi[1]) {
                it->cy = it->lo[1];
                if (++it->cz > it->hi[2]) {
                    it->cz = it->hi[2]; // stays done
                    it->cx = it->hi[0];
                    it->cy = it->hi[1];
                    return false;
                }
            }
        }
        size_t c = gf_celllist_index(it->cl, it->cx, it->cy, it->cz);
        it->q = it->cl->start[c];
        it->end = it->cl->start[c + 1];
    }
    *j = it->cl->idx[it->q++];
    return true;
}

#endif
