// SPDX-License-Identifier: MIT
// Internal: the LGA paper's three problems (Sec. 3) as lattices, walls and fills.
#ifndef GF_LGA_SCENARIO_H
#define GF_LGA_SCENARIO_H

#include "lga/lattice.h"

/// Default sizes (cfg keys at 0 / auto), chosen to match the paper's counts.
#define GF_LGA_PILE_WIDTH 420       ///< columns (364 d): the heap of 15,000 never reaches the edges
#define GF_LGA_PILE_HEIGHT 140      ///< rows: heap (~90) plus the fall from the feed
#define GF_LGA_PILE_PARTICLES 15000 ///< Sec. 3.1
#define GF_LGA_CHANNEL_WIDTH 50     ///< fluid columns between the two walls
#define GF_LGA_CHANNEL_HEIGHT 1000  ///< rows
#define GF_LGA_CHANNEL_PARTICLES 35000 ///< Sec. 3.2 (0.7 per site)
#define GF_LGA_CHANNEL_ITERATIONS 2160 ///< the last panel of Fig. 6
#define GF_LGA_SILO_WIDTH 120       ///< columns of the parallel part (104 d)
#define GF_LGA_SILO_HEIGHT 280      ///< rows of the parallel part
#define GF_LGA_SILO_PARTICLES 35000 ///< Sec. 3.3
#define GF_LGA_MASS_ANGLE 20.0      ///< hopper wall from the vertical, degrees: mass flow
#define GF_LGA_FUNNEL_ANGLE 60.0    ///< funnel flow (the wall at the angle of repose)
#define GF_LGA_STALL_ITERATIONS 5000 ///< silo auto end: nothing left for this long
#define GF_LGA_SLOPE_LO 0.3         ///< the heap slope is fitted where the profile is between
#define GF_LGA_SLOPE_HI 0.9         ///< these fractions of its peak (tail and apex left out)

/// Builds the lattice of l->cfg's scenario (l->cfg set, everything else zero).
gf_status gf_lga_scenario_build(gf_lga *l);

/// Recomputes walls, the sink list and the particle count after the sites changed.
gf_status gf_lga_scenario_finish(gf_lga *l);

/// The hopper angle the silo uses, degrees (lga.hopper_angle, or by lga.silo_flow when auto).
double gf_lga_hopper_angle(const gf_lga_defs *d);

#endif
