// SPDX-License-Identifier: MIT
// The 2D lattice-gas automaton of Kozicki & Tejchman (2005) for granular
// piles, channel flow and silos (SPEC 2): a hexagonal lattice whose sites hold
// up to 13 particles, one per velocity (rest, 6 nearest, 6 second-nearest
// directions), updated by collision (p, q, gravity g, friction k, wall
// roughness b) and two propagation steps (resting particles, gravity h; then
// moving particles). docs/lga.md describes the model as implemented.
//
// Units: lengths in lattice spacings (the nearest-neighbour distance, one
// particle diameter d), time in iterations. Site (i, j), column i = 0..width-1
// from the left, row j = 0..height-1 from the bottom, sits at
// x = i sqrt(3)/2, y = j + (i odd ? 1/2 : 0).
#ifndef GRANFLOW_LGA_H
#define GRANFLOW_LGA_H

#include <signal.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "granflow/config.h"
#include "granflow/core.h"

#ifdef __cplusplus
extern "C" {
#endif

/// An LGA engine (opaque): the lattice, its state, the collision table and the RNG.
typedef struct gf_lga gf_lga;

/// Bits of a site state (gf_lga_site): bit e (0..12) set = a particle with
/// velocity v_e (v0 = rest; v1..v6 nearest neighbours at 90, 150, 210, 270,
/// 330, 30 degrees; v7..v12 second-nearest at 120, 180, 240, 300, 0, 60
/// degrees, speed sqrt 3), plus the site kind.
enum {
    GF_LGA_SITE_PARTICLES = 0x1FFF, ///< the 13 velocity bits
    GF_LGA_SITE_WALL = 0x2000,      ///< a wall site (never holds particles)
    GF_LGA_SITE_SINK = 0x4000,      ///< an outlet site: particles reaching it leave the system
};

/// Counters of an engine.
typedef struct gf_lga_stats {
    int64_t iteration;    ///< iterations done
    int64_t particles;    ///< particles in the system now
    int64_t initial;      ///< particles at iteration 0
    int64_t added;        ///< particles fed in so far (pile)
    int64_t removed;      ///< particles that left through sinks so far
    int64_t last_outflow; ///< particles that left in the last iteration
    int64_t to_add;       ///< particles still to be fed in (pile)
    int width, height;    ///< lattice columns and rows
    int64_t fluid_sites;  ///< sites that are not walls
} gf_lga_stats;

/// Builds the scenario of cfg->lga_scenario (pile, channel or silo) with the
/// cfg->lga_* parameters and seeds the RNG from cfg->run_seed. `cfg` must be
/// valid (gf_config_validate); it is copied. GF_ERR_PARAM when the geometry
/// does not fit (e.g. an outlet wider than the silo), GF_ERR_NOMEM.
GF_API gf_status gf_lga_create(const gf_config *cfg, gf_lga **out);

/// An empty width x height lattice with wall edges (or rows that wrap, when
/// `periodic`), the parameters of `cfg`, and no particles; for tests and
/// custom geometries (set sites with gf_lga_set_site).
GF_API gf_status gf_lga_create_empty(const gf_config *cfg, int width, int height, bool periodic, gf_lga **out);

/// Frees the engine (NULL is fine).
GF_API void gf_lga_destroy(gf_lga *lga);

/// One iteration: feed (pile), collision with gravity g, friction k and wall
/// roughness b, first propagation (surplus resting particles scattered to
/// emptier neighbours; gravity h), second propagation (moving particles to
/// their neighbour, reflected by walls), removal at sinks.
GF_API void gf_lga_step(gf_lga *lga);

/// Runs `iterations` iterations, or fewer when `*stop` becomes non-zero (may be NULL).
GF_API void gf_lga_run(gf_lga *lga, int64_t iterations, volatile sig_atomic_t *stop);

/// The counters (constant time).
GF_API gf_lga_stats gf_lga_get_stats(const gf_lga *lga);

/// Particles with a non-zero velocity now (a pass over the lattice).
GF_API int64_t gf_lga_moving(const gf_lga *lga);

/// Lattice columns and rows.
GF_API int gf_lga_width(const gf_lga *lga);
GF_API int gf_lga_height(const gf_lga *lga);

/// Position of site (i, j), lattice spacings.
GF_API void gf_lga_site_position(int i, int j, double *x, double *y);

/// The state of site (i, j) (GF_LGA_SITE_* bits); 0 outside the lattice.
GF_API uint16_t gf_lga_site(const gf_lga *lga, int i, int j);

/// Sets site (i, j): the velocity bits and the wall/sink kind (walls hold no
/// particles). Recomputes the wall reflections when the kind changes and the
/// particle count. GF_ERR_PARAM outside the lattice or for particles on a wall.
GF_API gf_status gf_lga_set_site(gf_lga *lga, int i, int j, uint16_t state);

/// Particles per site, width x height values row by row (out[j * width + i]),
/// 0 on walls. `out` holds width * height doubles.
GF_API void gf_lga_density(const gf_lga *lga, double *out);

/// The density averaged over each site and its nearest non-wall neighbours
/// (the maps' smoothing); NaN on walls. `out` holds width * height doubles.
GF_API void gf_lga_density_smoothed(const gf_lga *lga, double *out);

/// Heap profile: for each column i, the height y (lattice spacings) of the top
/// of its highest resting particle above the floor (row 0 of the fluid),
/// 0 for an empty column, NaN for a wall or sink column. `out` holds width values.
GF_API void gf_lga_profile(const gf_lga *lga, double *out);

/// The heap's slope angle, degrees: least-squares lines through the profile of
/// each flank where it is between `lo` and `hi` times the peak height (the
/// apex and the tail left out), the mean of the two flanks' angles. `left` and
/// `right` (may be NULL) receive each flank's angle. NaN when a flank has
/// fewer than 3 points.
GF_API double gf_lga_slope_angle(const double *profile, int width, double lo, double hi, double *left,
                                 double *right);

/// When the outflow of a run had left: the first iteration by which at least
/// `fraction` (0 < fraction <= 1) of all the particles that left had left.
/// `iteration[k]` (increasing) is an iteration in which `count[k]` > 0
/// particles left, k < n; iterations without outflow may be omitted.
/// fraction 1 gives the last iteration with outflow. -1 when nothing left or
/// `fraction` is outside (0, 1].
GF_API int64_t gf_lga_outflow_time(const int64_t *iteration, const int64_t *count, size_t n, double fraction);

/// Density along the height: mean particles per fluid site of each row (height values).
GF_API void gf_lga_row_density(const gf_lga *lga, double *out);

/// Variance (over rows) of the row density smoothed over `window` rows
/// (periodic when the lattice is): how strong density waves along the height are.
GF_API double gf_lga_wave_variance(const gf_lga *lga, int window);

/// Options of gf_lga_run_dir.
typedef struct gf_lga_run_opts {
    const char *dir;               ///< output directory (created as needed)
    bool force;                    ///< allow a non-empty directory
    volatile sig_atomic_t *stop;   ///< set non-zero to stop early (may be NULL)
    void (*progress)(void *ctx, const gf_lga_stats *s, int64_t until); ///< every few hundred iterations; may be NULL
    void *ctx;                     ///< passed to progress
} gf_lga_run_opts;

/// The defaults: no force, no stop flag, no progress callback; set `dir`.
GF_API gf_lga_run_opts gf_lga_run_opts_default(void);

/// Headline numbers of a run (also written to DIR/summary.json).
typedef struct gf_lga_summary {
    gf_lga_scenario scenario;
    int64_t iterations;         ///< iterations done
    int64_t particles_initial;  ///< at iteration 0
    int64_t particles_added;    ///< fed in (pile)
    int64_t particles_removed;  ///< left through sinks
    int64_t particles_final;    ///< in the system at the end
    int64_t iterations_to_empty; ///< silo: first iteration with no particle left; -1 if never
    int64_t iterations_to_stop; ///< last iteration in which a particle left; -1 if none did
    int64_t t50, t90, t99;      ///< iterations by which 50, 90, 99% of what left had left; -1 if none did
    double slope_angle;         ///< pile: mean flank angle, degrees (NaN otherwise)
    double slope_left, slope_right; ///< pile: each flank, degrees
    double wave_variance_initial;   ///< channel: gf_lga_wave_variance at iteration 0
    double wave_variance_final;     ///< channel: mean over the last quarter of the run
    double wall_seconds;            ///< wall time of the run
    double site_updates_per_second; ///< fluid sites x iterations / wall time
} gf_lga_summary;

/// Runs the configured scenario into opts->dir: config.ini, maps/map_NNNNNN.png
/// (density maps at iteration 0, every lga.snapshot_interval and at the end),
/// sheet.png (contact sheet), outflow.csv (iteration, outflow, particles),
/// pile: profile.csv (x, height); channel: waves.csv (iteration, variance);
/// summary.json. Refuses a non-empty directory unless opts->force
/// (GF_ERR_PARAM). `summary` may be NULL.
GF_API gf_status gf_lga_run_dir(const gf_config *cfg, const gf_lga_run_opts *opts, gf_lga_summary *summary);

/// Draws a density map (darker = denser; walls blue) of the engine's current
/// state as a PNG at `path` (atomically), `px` pixels per lattice spacing,
/// with `label` above it (may be NULL).
GF_API gf_status gf_lga_render_map(const gf_lga *lga, double px, const char *label, const char *path);

#ifdef __cplusplus
}
#endif
#endif
