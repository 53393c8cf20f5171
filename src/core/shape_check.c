// SPDX-License-Identifier: MIT
// The container-file check hook (core/shape_check.h).
#include "core/shape_check.h"

static gf_shape_check_fn *gf_shape_check_fn_;

void gf_shape_check_set(gf_shape_check_fn *fn) { gf_shape_check_fn_ = fn; }

gf_shape_check_fn *gf_shape_check_get(void) { return gf_shape_check_fn_; }
