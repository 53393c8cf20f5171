// SPDX-License-Identifier: MIT
// Internal: the check of a container's files (container.mesh) that the
// configuration's validation (config/) asks of the shapes (geom/), a sibling
// it may not call: geom registers it when the library is loaded
// (geom/meshload.c). It stays while config validates the shapes' keys
// (docs/geometry.md, "Adding a shape", step 2): only the mesh needs a file
// read, and its bounding box taken, at validation.
#ifndef GF_CORE_SHAPE_CHECK_H
#define GF_CORE_SHAPE_CHECK_H

#include "granflow/core.h"

/// Checks what a configuration (a gf_config *) names outside itself and
/// completes it (the mesh's bounding box into container.width and depth).
typedef gf_status gf_shape_check_fn(void *cfg);

void gf_shape_check_set(gf_shape_check_fn *fn);
/// The registered check, or NULL.
gf_shape_check_fn *gf_shape_check_get(void);

#endif
