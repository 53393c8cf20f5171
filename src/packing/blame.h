// SPDX-License-Identifier: MIT
// Internal: naming a particle of a packing in an error, with the file and
// line it came from when it was imported (packing.file).
#ifndef GF_PACKING_BLAME_H
#define GF_PACKING_BLAME_H

#include "granflow/config.h"
#include "granflow/particles.h"

/// Re-sets the last error (status `st`, text kept) to name the highest
/// particle of `p`, which sets a grid's height: "FILE:LINE: TEXT: particle id
/// N at (x, y, z) is the highest ... (packing.file, WHERE)". Returns `st`.
gf_status gf_packing_blame_highest(const gf_packing *p, const gf_config *cfg, gf_status st);

#endif
