// SPDX-License-Identifier: MIT
// Internal helpers shared by the DEM files (src/dem/).
#ifndef GF_DEM_INTERNAL_H
#define GF_DEM_INTERNAL_H

#include "granflow/core.h"

/// mkdir -p: creates `path` and its missing parents.
gf_status gf_dem_mkdirs(const char *path);

#endif
