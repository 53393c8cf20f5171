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

/// Neighbour-list skin, d. Pair (i, j) is listed while its reference
/// positions p0 (see nlist.c) are closer than contact + h_i + h_j (all
/// h_i = GF_SKIN today; the data model keeps one per particle); a particle
/// that has moved h_i - GF_SKIN_SLACK from its p0 gets a new p0 and its pairs
/// are redone then and there, so only its own list and its neighbours' change.
/// Such refreshes cost ~0.2 us each, hence thin skins: fewer list entries
/// for relax() to test, at the price of more (cheap) refreshes.
#define GF_SKIN 0.05
/// Motion allowed in the one step that crosses a trigger (a spot moves
/// particles ~0.002 d, a relaxation far less).
#define GF_SKIN_SLACK 0.01

/// Slots per neighbour list: slot 0 holds the count, the rest up to
/// GF_NL_CAP - 1 neighbours: one 64-byte cache line per particle (relax() is
/// bound by cold loads; 32 slots cost ~5% per step). Within contact + 2
/// GF_SKIN a unit sphere has ~7 centres at random close packing and at most
/// ~12 were seen in flow; more is reported as a packing that overlaps too much.
#define GF_NL_CAP 16
/// Most slots of a row: with unequal radii a row holds up to ~2 / (1 - cos t)
/// neighbours, sin t = r_min / (r_max + r_min) (small spheres around the
/// largest one, by solid angle), rounded up to a power of two: 16 for equal
/// radii, 64 up to r_max / r_min = 3, the most the engine accepts.
#define GF_NL_CAP_MAX 64

/// Most particle centres per d^3 a gather may hold (it sizes the per-thread
/// scratch): random close packing has 1.2, and relax() keeps pairs >= ~0.98 d
/// apart, so 4 is never reached by a packing the engine accepts; beyond it a
/// step fails with a clear error rather than writing past its scratch.
#define GF_GATHER_DENSITY 4.0
/// Full list rebuilds (compacting exited particles away and re-sorting the
/// rest by cell, for memory locality) come every run.reorder_interval events
/// (default 1,000,000). Between them lists are kept exact by per-particle
/// refreshes alone.

/// Where exited particles are parked until the next list rebuild compacts
/// them away: far enough that no live particle can overlap them.
#define GF_PARK_COORD 1.0e30

/// Recirculation (spot/recirculate.c): a re-inserted sphere rolls into a
/// pocket of the surface by steps of GF_SETTLE_STEP r down, each followed by
/// GF_SETTLE_SWEEPS passes pushing it out of its neighbours, for at most
/// GF_SETTLE_ITERS steps, ending after GF_SETTLE_PATIENCE steps in which it
/// did not move. Perched near the top of a sphere it rolls off geometrically
/// (~10% further per step), so a pocket is found in ~20-60 steps; the exact
/// set-down afterwards removes what the sweeps leave of its contacts' overlaps.
#define GF_SETTLE_STEP 0.2
#define GF_SETTLE_SWEEPS 8
#define GF_SETTLE_ITERS 400
#define GF_SETTLE_PATIENCE 4
/// Most a settled sphere may be lifted clear of its overlaps, times r; more
/// means the sweeps did not converge, and the plain drop is kept instead.
#define GF_SETTLE_LIFT 0.05
/// Targets tried for one re-insertion before the plain drop is kept (one
/// settling in five does not converge; eight fail together ~1e-6 of the time).
#define GF_SETTLE_TARGETS 8
/// A step that moves a settling sphere less than this times r counts as still.
#define GF_SETTLE_STILL 1e-6
/// Neighbours within r + r_max + this of a settling sphere are gathered, and
/// again after it has moved half of this, d.
#define GF_SETTLE_REACH 1.0
/// Clearance added to the resting height, d, so rounding never makes an overlap.
#define GF_REINSERT_GAP 1e-9
/// Rejection samples for a target in the re-insertion zone before giving up
/// (a zone of 1e-4 of the cross-section is still found with p > 0.99995).
#define GF_REINSERT_SAMPLES 100000

/// Largest particle count the engine accepts (32-bit indices in cells and lists).
#define GF_MAX_PARTICLES 100000000

/// Most snapshots, and most checkpoints, one run may write: run.duration /
/// output.snapshot_interval and run.duration / run.checkpoint_interval above
/// this are refused. A snapshot of the papers' silo is ~2 MB, so 10^5 of them
/// are already 200 GB; tinier intervals only make a run that never ends (the
/// next output time stops advancing once the interval is below the rounding
/// of the current time).
#define GF_MAX_OUTPUTS 100000

/// Largest ratio spot.insertion_rate / spot.move_rate: spots born per move
/// time. The papers use ~13; 10^4 would bury the orifice under thousands of
/// spots per step, and beyond it memory grows without bound.
#define GF_MAX_SPOTS_PER_MOVE 10000.0

/// snapshots.pvd is rewritten whole at every snapshot while it lists at most
/// this many (about 70 bytes each), then only at checkpoints and at the end:
/// rewriting it at every one of GF_MAX_OUTPUTS snapshots would write
/// hundreds of GB in all.
#define GF_PVD_EVERY_SNAPSHOT 1000

#endif
