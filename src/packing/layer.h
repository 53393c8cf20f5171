// SPDX-License-Identifier: MIT
// Internal: the initial-layer tag of one height, the one rule behind
// gf_packing_tag_layers and the tags the series loaders carry between frames.
#ifndef GF_PACKING_LAYER_H
#define GF_PACKING_LAYER_H

#include <stdint.h>

/// 1 + floor(z / thickness), the band index clamped to [-1e9, 1e9] (a
/// hair-thin band or a far particle would overflow int32; NaN gives 1).
int32_t gf_packing_layer_of(double z, double thickness);

#endif
