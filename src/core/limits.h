// SPDX-License-Identifier: MIT
// Internal: every tunable size, capacity and tolerance of the engine, each
// with the reason for its value (STYLE item 6).
#ifndef GF_CORE_LIMITS_H
#define GF_CORE_LIMITS_H

/// Edge of a cell of the particle grid, d. Measured (docs/performance.md):
/// 1.5 beats 1.2 by ~5% per step; small cells waste loop overhead on nearly
/// empty cells, large ones test too many candidates outside the ball.
#define GF_CELL_SIZE 1.5

/// Slots per grid cell. A 1.5 d cube holds ~4 centres at random close
/// packing and at most ~10 of non-overlapping unit spheres; 24 leaves room
/// for overlapping input (DEM packings overlap by ~0.1%).
#define GF_CELL_CAP 24

/// Neighbour-list skin, d: pair (i, j) is listed when closer than contact +
/// h_i + h_j (all h_i = GF_SKIN today; the data model keeps one per
/// particle), and the lists are rebuilt once any particle has moved
/// h_i - GF_SKIN_SLACK from where they were built. Thinner skins make relax()
/// cheaper (fewer candidates) and rebuilds more frequent.
#define GF_SKIN 0.11
/// Skin at the orifice centre and the distance over which it falls to
/// GF_SKIN: particles there are swept by every spot (see nlist.c).
#define GF_SKIN_ORIFICE 0.6
#define GF_SKIN_REACH 8.0
/// Motion allowed in the one step that crosses a trigger (a spot moves
/// particles ~0.002 d, a relaxation far less).
#define GF_SKIN_SLACK 0.01

/// Where exited particles are parked until the next list rebuild compacts
/// them away: far enough that no live particle can overlap them.
#define GF_PARK_COORD 1.0e30

/// Largest particle count the engine accepts (32-bit indices in cells and lists).
#define GF_MAX_PARTICLES 100000000

#endif
