// SPDX-License-Identifier: MIT
// Internal: what the structure measurements (g(r), badness, Voronoi) share
// besides the cell list of geom/celllist.h: the window's frames.
#ifndef GF_ANALYSIS_STRUCTURE_H
#define GF_ANALYSIS_STRUCTURE_H

#include <stddef.h>

#include "granflow/analysis.h"

/// The frames k0 <= k < k1 whose times lie in the window [t0, t1] of `o`
/// (gf_analysis_window); k0 == k1 when none does.
void gf_structure_window(const gf_series *s, const gf_analysis_opts *o, size_t *k0, size_t *k1);

#endif
