// SPDX-License-Identifier: MIT
// Internal: the parts of one LGA iteration (paper Sec. 2), in the order
// gf_lga_step runs them.
#ifndef GF_LGA_STEP_H
#define GF_LGA_STEP_H

#include "lga/lattice.h"

/// Adds `n` resting particles beyond the v0 slot at site idx (listed for the scatter).
static inline void gf_lga_add_excess(gf_lga *l, size_t idx, int n)
{
    if (!l->excess[idx]) l->pending[l->npending++] = idx;
    l->excess[idx] = (uint8_t)(l->excess[idx] + n);
}

/// Pile: adds the particles due this iteration at the feed sites (as v4, falling).
void gf_lga_feed(gf_lga *l);

/// The outcome of one site's collision: the new velocity bits of a site whose
/// 13-bit state is `s` (p, q, k only when it holds 2 or more particles;
/// gravity g when `gravity`, i.e. the site is not supported from below), and
/// in *excess the particles brought to rest beyond the one v0 slot. Consumes
/// random numbers from l->rng.
uint16_t gf_lga_collide_state(gf_lga *l, uint16_t s, bool gravity, int *excess);

/// The collision step over the lattice: every site with a moving particle,
/// and every lone resting particle without support below it; then wall
/// roughness b for particles about to hit a wall. Fills l->pending.
void gf_lga_collide(gf_lga *l);

/// First propagation, part 1: the particles in excess at a site go to the
/// nearest free v0 slots (breadth first, the emptiest of the nearest ring);
/// those that find none within GF_LGA_SCATTER_RADIUS stay stacked for later.
void gf_lga_scatter(gf_lga *l);

/// First propagation, part 2 (gravity h): a resting particle moves, with
/// probability h, to an empty site in one of the directions v3 v4 v5 v9 v10.
void gf_lga_settle(gf_lga *l);

/// Second propagation: every moving particle to the neighbour its velocity
/// points at, reflected where a wall blocks it.
void gf_lga_stream(gf_lga *l);

/// Removes the particles on sink sites; returns how many.
int64_t gf_lga_drain(gf_lga *l);

#endif
