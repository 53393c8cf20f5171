// SPDX-License-Identifier: MIT
// The container-keys check hook (core/shape_check.h).
#include "core/shape_check.h"

static gf_shape_validate_fn *gf_shape_validate_fn_;

void gf_shape_validate_set(gf_shape_validate_fn *fn) { gf_shape_validate_fn_ = fn; }

gf_shape_validate_fn *gf_shape_validate_get(void) { return gf_shape_validate_fn_; }
