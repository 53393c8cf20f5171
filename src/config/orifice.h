// SPDX-License-Identifier: MIT
// Internal: the checks of the orifice position (container.orifice_x, orifice_y).
#ifndef GF_CONFIG_ORIFICE_H
#define GF_CONFIG_ORIFICE_H

#include "granflow/config.h"

/// Checks that the orifice lies inside the base (SPEC 1.1; docs/config.md):
/// a slit spans the depth (orifice_y = 0),
/// and |orifice_x| + orifice_diameter/2 < container.width/2; a circle off the
/// mid-plane y = 0 also needs |orifice_y| + orifice_diameter/2 <= container.depth/2
/// (a centred circle may span the depth, as in the papers' 50 x 8 box).
/// Run after the shape's check (a cylinder's outlet on its axis, its keys
/// copied into the box's: src/geom/cylinder.c). GF_ERR_PARAM naming the key.
gf_status gf_config_check_orifice(const gf_config *cfg);

#endif
