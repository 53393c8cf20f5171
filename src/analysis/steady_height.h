// SPDX-License-Identifier: MIT
// Internal: where the flow at one height has become steady (issue 27). The
// spot model carries the orifice's opening upward at the spots' rise speed
// (mu x step_z, ~2.8 d/tau with the papers' values), so high in the
// container its profiles are still building up long after the outflow is
// steady; a profile at height z is averaged only over the frame pairs where
// the mean v_z there has reached its late value.
#ifndef GF_ANALYSIS_STEADY_HEIGHT_H
#define GF_ANALYSIS_STEADY_HEIGHT_H

#include <stdbool.h>
#include <stddef.h>

/// Verdict on one height.
typedef struct gf_steady_height {
    bool steady;     ///< false: no steady frames (no downward flow, or still speeding up at the end)
    size_t first;    ///< first steady frame pair (when steady)
    double late;     ///< late mean v_z, d/tau (the last half of the pairs)
    char why[160];   ///< one sentence: which pairs and why
} gf_steady_height;

/// From the mean v_z of the band at one height in each of n consecutive frame
/// pairs (NaN: no particle there), finds the first pair from which the flow
/// is steady: the late value L is the mean over the last half of the pairs,
/// its noise the pairs' sd there; the steady part starts at the first chunk
/// (an eighth of the pairs, at least 2) whose mean lies within max(0.5%,
/// 2.5 standard deviations of the difference) of L. Fewer than 4 pairs: all
/// of them (too few to judge). No downward flow in the late half (L within
/// 3 standard errors of 0, or upward), or a last quarter faster than the
/// third by more than 3 standard errors (the quarters' own noise, pooled;
/// judged with 2 pairs or more in each) and 5%: not steady.
gf_steady_height gf_steady_height_find(const double *mean_vz, size_t n);

#endif
