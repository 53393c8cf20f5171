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
    bool no_flow;    ///< not steady because nothing flows down here in the late half
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

/// A spot run's flow at height z is steady once the spots born when the
/// orifice opened have risen there, plus three standard deviations of their
/// arrival (issue 27 item 2: "t > t_start + z / rise speed for spot runs"):
/// `moves` = (z - birth height + r_s) / step_z moves at rate mu take
/// (moves + 3 sqrt(moves)) / mu. This is the time returned, from the run's start.
double gf_steady_height_rise_time(double z, double birth_z, double r_s, double step_z, double mu);

/// Replaces the verdict `v` of gf_steady_height_find on the pairs starting at
/// t_pair[0..n) by the spot run's: steady from the first pair starting at or
/// after t_ready, when at least an eighth of the pairs (and 2) do; a height
/// where nothing flows stays not steady, and one the spots reach too late
/// keeps the noise's verdict. The rise time does not depend on the noise, so
/// runs of the same parameters agree on which heights they measure (the
/// noise test alone read slow swings of a spot run's flow as a start-up).
void gf_steady_height_by_rise(gf_steady_height *v, const double *t_pair, size_t n, double t_ready);

#endif
