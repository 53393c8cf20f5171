// SPDX-License-Identifier: MIT
// Internal: the C side of the thin Voro++ wrapper (voronoi_cells.cc).
#ifndef GF_ANALYSIS_VORONOI_CELLS_H
#define GF_ANALYSIS_VORONOI_CELLS_H

#include <stddef.h>

#include "granflow/core.h"

#ifdef __cplusplus
extern "C" {
#endif

/// Voronoi cells of the n points (x, y, z) in the box lo <= p < hi, with walls
/// on all six faces (non-periodic), computed by Voro++. vol[i]: the cell's
/// volume, d^3; rad2[i] (when rad2 is not NULL): the largest squared distance
/// from the point to a vertex of its cell, d^2. Both NaN for a point outside
/// the box, with a non-finite coordinate, or whose cell Voro++ could not build
/// (coincident points: Voro++ 0.4.6 gives up on both, tried by hand).
/// GF_ERR_PARAM for a degenerate box or too many points; GF_ERR_NOMEM when
/// Voro++ runs out of memory; GF_ERR_STATE for any other C++ exception.
gf_status gf_voro_cells(size_t n, const double *x, const double *y, const double *z, const double lo[3],
                        const double hi[3], double *vol, double *rad2);

#ifdef __cplusplus
}
#endif

#endif
