// SPDX-License-Identifier: MIT
// Internal: the checks of an imported packing (import.c), also made by an
// MPI rank on the window of packing.file it keeps (spot/window.c).
#ifndef GF_PACKING_IMPORT_H
#define GF_PACKING_IMPORT_H

#include "granflow/config.h"
#include "granflow/particles.h"

// Radii the engine takes, d (its unit is the mean diameter): the cell grid
// (GF_CELL_SIZE 1.5) finds every contact of radii up to 0.75, and the
// neighbour lists (GF_NL_CAP) hold the neighbours of radii down to 0.25.
#define GF_IMPORT_RMIN 0.25
#define GF_IMPORT_RMAX 0.75

/// What the engine cannot simulate: radii outside [GF_IMPORT_RMIN,
/// GF_IMPORT_RMAX], and two particles on one centre; GF_ERR_FORMAT naming
/// packing.file and the particles.
gf_status gf_packing_import_check(const gf_config *cfg, const gf_packing *p);

#endif
