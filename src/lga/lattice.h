// SPDX-License-Identifier: MIT
// Internal: the hexagonal lattice of the LGA paper (Sec. 2, Fig. 1): site states,
// the 13 velocities, neighbour offsets, walls, sinks and the engine's state.
#ifndef GF_LGA_LATTICE_H
#define GF_LGA_LATTICE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "core/rng.h"
#include "granflow/config.h"
#include "granflow/defs.h"
#include "granflow/lga.h"
#include "lga/table.h"

// Site state bits: bit 0 = v0 (rest), bit i = v_i (i = 1..12), then flags.
#define GF_LGA_REST 0x0001u
#define GF_LGA_MOVERS 0x1FFEu    ///< v1..v12
#define GF_LGA_PARTICLES 0x1FFFu ///< v0..v12
#define GF_LGA_WALL 0x2000u      ///< a wall site: holds no particles
#define GF_LGA_SINK 0x4000u      ///< an outlet site: whatever reaches it leaves the system
#define GF_LGA_MARK 0x8000u      ///< scratch: the resting particle here already moved this iteration

// Per-site wall data: `wall[]` holds the directions (bits 1..12) blocked by a
// wall; `refl[]` the index of the site's reflection map in `maps`.

/// How the particles heading into the walls at one site come back: maps[k][e]
/// is the velocity a particle with blocked velocity e leaves with.
typedef struct gf_lga_reflection {
    uint8_t to[13];
} gf_lga_reflection;

/// How far (in nearest-neighbour steps) surplus resting particles are carried
/// to find a free v0 slot, and the search's queue length.
#define GF_LGA_SCATTER_RADIUS 12
#define GF_LGA_SCATTER_QUEUE 1024

/// Most sites a lattice may have (about 2 GB of state): beyond, surely a mistake.
#define GF_LGA_MAX_SITES 1.0e8

/// Halo of wall (or periodic ghost) sites around the interior: second-nearest moves reach 2 columns.
#define GF_LGA_HALO 2

/// The engine. Sites are stored row by row (j up, i to the right) with a halo
/// of GF_LGA_HALO sites on every side; site (i, j) sits at
/// x = i sqrt(3)/2, y = j + (i odd ? 1/2 : 0) (nearest-neighbour distance 1).
struct gf_lga {
    gf_config cfg;          ///< the configuration (validated copy, auto values resolved), for config/'s messages and config.ini
    gf_lga_defs d;          ///< what the automaton reads (gf_config_lga_defs of cfg)
    gf_lga_scenario scenario;
    int w, h;               ///< interior columns and rows
    int stride, rows;       ///< w + 2 halo, h + 2 halo
    size_t nsites;          ///< stride * rows
    bool periodic;          ///< rows wrap (channel): row h-1 neighbours row 0
    uint16_t *state, *next; ///< site states (two buffers for the streaming step)
    uint16_t *wall;         ///< blocked directions per site
    uint16_t *refl;         ///< reflection map of each site with blocked directions
    gf_lga_reflection *maps; ///< the distinct reflection maps
    size_t nmaps, capmaps;
    uint8_t *excess;        ///< resting particles beyond the one v0 slot (0 between iterations)
    size_t *pending;        ///< sites with excess > 0, in the order found (capacity 2 nsites)
    size_t npending;
    size_t npersist;        ///< pending[0 .. npersist) were already there last iteration
    uint32_t *stamp;        ///< scratch of the scatter search: visited marks
    uint32_t *crowded;      ///< iteration + 1 when a failed scatter search last covered the site
    uint32_t stamp_now;
    size_t *queue;          ///< scratch of the scatter search (GF_LGA_SCATTER_QUEUE entries)
    uint8_t *busy;          ///< per row: may hold particles (rows without are skipped)
    uint8_t *busy_next;     ///< the same, being computed by the streaming step
    uint16_t *rowbuf;       ///< scratch of the collision: one row before its update (stride entries)
    int16_t *qdy;           ///< height of each queued site relative to the start, half spacings
    size_t *sinks;          ///< the sink sites
    size_t nsinks;
    ptrdiff_t off[2][13];   ///< index offset of the neighbour in direction e, by column parity
    gf_lga_table *table;    ///< the collision table
    gf_rng rng;
    int64_t settle_skip;    ///< resting particles the gravity-h draw passes over before its next success

    // probability thresholds against 32-bit uniforms (2^32 = always)
    uint64_t thr_p[14], thr_q[14]; ///< P(n >= k) = p^k, P(l >= k) = q^k, 32-bit fixed point
    uint64_t thr_g, thr_h, thr_k, thr_b;

    // the feed (pile): particles enter as v4 at these sites
    size_t *feed_sites;
    size_t nfeed;
    double feed_rate, feed_due;
    int64_t feed_total;     ///< particles still to add

    // counters
    int64_t iteration;
    int64_t particles;      ///< in the system now
    int64_t added, removed; ///< since the start
    int64_t last_outflow;   ///< removed in the last iteration
    int64_t initial;        ///< at iteration 0
    int64_t fluid_sites;    ///< non-wall interior sites
};

/// Direction tables: lattice displacement of v_e in half units (x in sqrt(3)/2,
/// y in 1/2): v_e = (gf_lga_da[e] sqrt(3)/2, gf_lga_db[e] / 2).
extern const int gf_lga_da[13], gf_lga_db[13];
/// The direction opposite to e (0 -> 0).
extern const int gf_lga_opp[13];
/// Column and row step of the neighbour in direction e from a column of parity `odd`.
int gf_lga_di(int e);
int gf_lga_dj(int e, int odd);

/// Index of the interior site (i, j) (no range check).
static inline size_t gf_lga_index(const gf_lga *l, int i, int j)
{
    return (size_t)(j + GF_LGA_HALO) * (size_t)l->stride + (size_t)(i + GF_LGA_HALO);
}

/// Index of the neighbour of (i, j) in direction e, rows wrapped when periodic;
/// a halo index (a wall) when it falls off a non-periodic edge.
size_t gf_lga_neighbour(const gf_lga *l, int i, int j, int e);

/// The same from a site index (interior sites only): offset, then rows wrapped.
static inline size_t gf_lga_neighbour_idx(const gf_lga *l, size_t idx, int odd, int e)
{
    size_t t = (size_t)((ptrdiff_t)idx + l->off[odd][e]);
    if (l->periodic) {
        size_t lo = (size_t)GF_LGA_HALO * (size_t)l->stride, hi = lo + (size_t)l->h * (size_t)l->stride;
        if (t < lo) t += (size_t)l->h * (size_t)l->stride;
        else if (t >= hi) t -= (size_t)l->h * (size_t)l->stride;
    }
    return t;
}

/// Marks the row of site idx as holding particles.
static inline void gf_lga_mark_busy(gf_lga *l, size_t idx)
{
    l->busy[idx / (size_t)l->stride - GF_LGA_HALO] = 1;
}

/// Recomputes the busy flag of every row from the states.
void gf_lga_lattice_busy(gf_lga *l);

/// Whether a w x h lattice is within GF_LGA_MAX_SITES (the sites of the
/// lattice itself; the halo around it does not count against the limit).
bool gf_lga_lattice_fits(int w, int h);

/// Allocates an all-empty w x h lattice with a wall halo (rows wrap when
/// periodic), the collision table and the thresholds from cfg.
gf_status gf_lga_lattice_alloc(gf_lga *l, int w, int h, bool periodic);

/// Frees what gf_lga_lattice_alloc and the scenario allocated.
void gf_lga_lattice_free(gf_lga *l);

/// Recomputes the blocked directions and reflection map of every site from
/// the wall flags (after the geometry changes).
gf_status gf_lga_lattice_walls(gf_lga *l);

/// Copies the edge rows into the ghost rows (periodic lattices) before streaming.
void gf_lga_lattice_ghosts(gf_lga *l, uint16_t *buf);

/// Number of particles in a state (0..13), by table (no popcount instruction needed).
static inline int gf_lga_count(const gf_lga *l, uint16_t s) { return l->table->count[s & GF_LGA_PARTICLES]; }

/// A 32-bit uniform random number.
static inline uint64_t gf_lga_u32(gf_rng *r) { return gf_rng_next(r) >> 32; }

#endif
