// SPDX-License-Identifier: MIT
// Internal: the second particle size of a generated packing (packing.radius2,
// packing.fraction2).
#ifndef GF_PACKING_BIDISPERSE_H
#define GF_PACKING_BIDISPERSE_H

#include "granflow/config.h"
#include "granflow/packing.h"

/// Gives a random packing.fraction2 of the particles of `p` (a generated
/// packing of radius 0.5) the radius packing.radius2 (<= 0.5: no overlap
/// can appear). Drawn from run.seed on its own stream.
gf_status gf_packing_bidisperse(const gf_config *cfg, gf_packing *p);

#endif
