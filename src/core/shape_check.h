// SPDX-License-Identifier: MIT
// Internal: the check of a container's own keys that the configuration's
// validation (config/) asks of the shapes (geom/), a sibling it may not call:
// geom registers it when the library is loaded (geom/shapes.c). It looks the
// shape up in the shape table and runs that shape's validate op (its row in
// its own file: docs/geometry.md, "Adding a shape"), so config names no
// shape: a cylinder's radius, a wedge's slope, a mesh's file are checked, and
// the keys they settle (bounding box, outlet) completed, by their shape.
#ifndef GF_CORE_SHAPE_CHECK_H
#define GF_CORE_SHAPE_CHECK_H

#include "granflow/core.h"

/// Checks the container keys of a configuration (a gf_config *) for the
/// shape it names, and completes them through config's setters (a cylinder's
/// bounding box and outlet, a wedge's slit, a mesh's bounding box). Sets
/// *wall_key to the key that bounds a spot's room across the container in
/// messages ("container.radius"), or NULL: the smaller of container.width
/// and container.depth.
typedef gf_status gf_shape_validate_fn(void *cfg, const char **wall_key);

void gf_shape_validate_set(gf_shape_validate_fn *fn);
/// The registered check, or NULL (the geometry is not linked in).
gf_shape_validate_fn *gf_shape_validate_get(void);

#endif
