// SPDX-License-Identifier: MIT
// Internal: what the structure measurements (g(r), badness, Voronoi) share:
// a counting-sort cell list for neighbour searches and the window's frames.
#ifndef GF_ANALYSIS_STRUCTURE_H
#define GF_ANALYSIS_STRUCTURE_H

#include <stddef.h>
#include <stdint.h>

#include "granflow/analysis.h"

/// Points binned into cubic cells (compressed rows: cell c holds
/// idx[start[c]] .. idx[start[c+1]-1]). Points with a non-finite coordinate
/// are left out. O(N) to build, any number of points per cell.
typedef struct gf_cell_list {
    double lo[3];   ///< lower corner of the grid, d
    double h;       ///< cell edge, d
    int n[3];       ///< cells per axis
    size_t ncell;
    size_t *start;  ///< ncell + 1 offsets
    uint32_t *idx;  ///< point indices, sorted by cell
    size_t nidx;    ///< points listed (the finite ones)
} gf_cell_list;

/// Bins the n points (x[i], y[i], z[i]) into cells of edge at least h (the
/// edge grows when the points are spread so thinly that cells would outnumber
/// them by far). GF_ERR_NOMEM on failure.
gf_status gf_cell_list_build(gf_cell_list *cl, const double *x, const double *y, const double *z,
                             size_t n, double h);
void gf_cell_list_free(gf_cell_list *cl);

/// Inclusive cell ranges lo..hi per axis covering the cube [c - r, c + r].
void gf_cell_list_range(const gf_cell_list *cl, const double c[3], double r, int lo[3], int hi[3]);

/// Cell index of (cx, cy, cz).
static inline size_t gf_cell_list_index(const gf_cell_list *cl, int cx, int cy, int cz)
{
    return ((size_t)cz * (size_t)cl->n[1] + (size_t)cy) * (size_t)cl->n[0] + (size_t)cx;
}

/// The frames k0 <= k < k1 whose times lie in the window [t0, t1] of `o`
/// (gf_analysis_window); k0 == k1 when none does.
void gf_structure_window(const gf_series *s, const gf_analysis_opts *o, size_t *k0, size_t *k1);

#endif
