// SPDX-License-Identifier: MIT
// The spot engine (2009 paper Sec. 2, thesis Sec. 3.4): a packing drains
// through the orifice as spots of free volume rise from it.
#ifndef GRANFLOW_SIM_H
#define GRANFLOW_SIM_H

#include <signal.h>
#include <stddef.h>
#include <stdint.h>

#include "granflow/config.h"
#include "granflow/core.h"
#include "granflow/exit.h"
#include "granflow/packing.h"

#ifdef __cplusplus
extern "C" {
#endif

/// Opaque simulation handle: particles, spots, random state, clocks.
typedef struct gf_sim gf_sim;

/// Counters of a simulation (all since t = 0, kept across checkpoints).
typedef struct gf_sim_stats {
    double time;                 ///< simulated time, tau
    size_t particles_initial;    ///< particles at t = 0
    size_t particles_remaining;  ///< particles still in the container
    size_t particles_exited;     ///< exits through the orifice (with recirculation, one particle may exit many times)
    size_t particles_reinserted; ///< exits put back on the free surface (run.recirculate); initial = remaining + exited - reinserted
    size_t spots_active;         ///< spots currently in the packing
    uint64_t spots_inserted;     ///< spots born at the orifice
    uint64_t spots_deleted;      ///< spots removed at the top of the packing
    uint64_t spot_moves;         ///< spot() calls (moves that displaced particles)
    uint64_t relax_calls;        ///< relax() calls (local ones)
    uint64_t global_relaxations; ///< relaxations of the whole packing (relax.method = global)
    uint64_t events;             ///< Gillespie events (insertions + moves), or fixed steps
    uint64_t nlist_builds;       ///< neighbour-list rebuilds
    double spot_seconds;         ///< wall time inside spot(), when timing is on
    double relax_seconds;        ///< wall time inside relax(), local and global: t_relax (always measured)
    double spot_dz;              ///< sum of the z displacements spot() gave particles, d
    double relax_dz;             ///< sum of the z displacements relax() gave particles, d
} gf_sim_stats;


/// What gf_sim_run calls while it runs. Every member may be NULL/0.
typedef struct gf_sim_hooks {
    void *ctx; ///< passed back to every callback
    /// Snapshot number `index` at simulated time `time` (index * snapshot_interval).
    gf_status (*snapshot)(void *ctx, const gf_sim *sim, uint64_t index, double time);
    /// Every run.checkpoint_interval tau (when > 0).
    gf_status (*checkpoint)(void *ctx, const gf_sim *sim);
    /// Every `progress_every` events (fixed mode: spot moves).
    void (*progress)(void *ctx, const gf_sim *sim);
    uint64_t progress_every;
    /// When *stop becomes non-zero the run returns GF_ERR_INTERRUPTED at the
    /// next event boundary (safe to set from a signal handler).
    volatile sig_atomic_t *stop;
} gf_sim_hooks;
/// The defaults (what a NULL `hooks` means): every member NULL/0.
GF_API gf_sim_hooks gf_sim_hooks_default(void);

/// Checks `cfg` (validated on a copy) for what the engine needs of the
/// container before any packing is built: with run.recirculate = on and
/// run.reinsert = zone, room for a re-inserted sphere in the zone
/// run.reinsert_rmin <= r < run.reinsert_rmax (GF_ERR_PARAM naming both keys
/// otherwise). gf_sim_create and gf_run_dir call it first.
GF_API gf_status gf_sim_check_config(const gf_config *cfg);

/// Creates a simulation of `packing` (copied) under `cfg` (validated). Spots
/// and time start at zero.
GF_API gf_status gf_sim_create(const gf_config *cfg, const gf_packing *packing, gf_sim **out);
GF_API void gf_sim_destroy(gf_sim *sim);

/// Runs events until the simulated time passes `until` (tau), writing
/// snapshots due on the way, including one at `until` if it falls on the
/// snapshot grid. Returns GF_OK, GF_ERR_INTERRUPTED (stop flag; state is
/// consistent and can be saved) or an error from a hook or the engine.
GF_API gf_status gf_sim_run(gf_sim *sim, double until, const gf_sim_hooks *hooks);

/// Processes exactly one event (insertion or spot move). For tests and tools.
GF_API gf_status gf_sim_step(gf_sim *sim);

GF_API gf_sim_stats gf_sim_get_stats(const gf_sim *sim);
GF_API const gf_config *gf_sim_config(const gf_sim *sim);

/// Copies the particles still in the container into `out` (sorted by id).
GF_API gf_status gf_sim_particles(const gf_sim *sim, gf_packing *out);

/// The pass each particle of gf_sim_particles is on (same order: by id) into
/// pass[0, n); n must be the count gf_sim_particles returned.
GF_API gf_status gf_sim_passes(const gf_sim *sim, int32_t *pass, size_t n);

/// The exits so far, sorted by (time, id); `*n` receives the count. Owned by sim.
GF_API const gf_exit *gf_sim_exits(const gf_sim *sim, size_t *n);

/// Threads of the spatial fixed step (run.order = spatial); 0: every core.
/// The results do not depend on it, so it may change at any time.
GF_API void gf_sim_set_threads(gf_sim *sim, int threads);

/// Switches per-call timing of spot() and relax() on or off (costs ~50 ns a call).
GF_API void gf_sim_set_timing(gf_sim *sim, int on);

// ---- flat arrays and named numbers: what bindings use ------------------------

/// Creates a simulation of the packing `cfg` asks for (packing.file imported,
/// else generated; see gf_packing_for_config). `cfg` is validated on a copy.
/// Dropped particles of an import are reported through gf_warning(). The
/// packing is built with `opts` (may be NULL): once opts->stop is non-zero,
/// GF_ERR_INTERRUPTED and no simulation.
GF_API gf_status gf_sim_create_from_config(const gf_config *cfg, const gf_packing_opts *opts, gf_sim **out);

/// Creates a simulation of `n` particles given as flat arrays under `cfg`
/// (validated on a copy; its packing.* keys other than layer_thickness are
/// not used): centres `xyz[3i..3i+2]` (d), `radius[i]` (d; NULL: 0.5 each),
/// `id[i]` (unique, >= 1; NULL: 1..n). Layers are tagged from z
/// (packing.layer_thickness). GF_ERR_PARAM naming the index of the first
/// bad value (not finite, radius <= 0, id < 1 or repeated, centre outside
/// the container).
GF_API gf_status gf_sim_create_from_arrays(const gf_config *cfg, size_t n, const double *xyz, const double *radius,
                                           const int64_t *id, gf_sim **out);

/// Particles still in the container.
GF_API size_t gf_sim_particle_count(const gf_sim *sim);

/// Copies the particles still in the container, sorted by id: `id[i]`,
/// `layer[i]` (initial-layer tag), `xyz[3i..3i+2]` (centre, d), `radius[i]`;
/// any array may be NULL. GF_ERR_PARAM when more than `cap` particles remain.
/// `*n` (may be NULL) receives the count.
GF_API gf_status gf_sim_copy_particles(const gf_sim *sim, int64_t *id, int32_t *layer, double *xyz,
                                       double *radius, size_t cap, size_t *n);

/// Number of particles that have left so far.
GF_API size_t gf_sim_exit_count(const gf_sim *sim);

/// Copies the exits, sorted by (time, id): `id[i]`, `txy[3i..3i+2]` = time
/// (tau), x, y (d) where it crossed; either may be NULL. GF_ERR_PARAM when
/// more than `cap`.
GF_API gf_status gf_sim_copy_exits(const gf_sim *sim, int64_t *id, double *txy, size_t cap, size_t *n);

/// One counter of gf_sim_stats by its member name ("time", "spot_moves",
/// ...) as a double; NaN for an unknown name.
GF_API double gf_sim_stat(const gf_sim *sim, const char *name);
/// Number of counters; counter i is named gf_sim_stat_name(i) (NULL when out of range).
GF_API size_t gf_sim_stat_count(void);
GF_API const char *gf_sim_stat_name(size_t i);
/// Thread counts the parallel engines' speedup is projected for: 2, 8, 16, 64, 256.
#define GF_PAR_NPROJ 5
/// Layers of blocks along z whose work the domain engine's profile keeps.
#define GF_PAR_LAYERS 64

/// The parallel engines' decomposition and, while profiling, the work of
/// its blocks: each block's run of each colour phase is timed (thread CPU
/// time, so preemption on a shared machine does not count), and the
/// phase is scheduled on T threads (blocks heaviest first, each to the
/// thread that frees first) to project the speedup work / makespan. For the
/// domain engine (run.order = domains) a block is a sector of a domain, a
/// colour a sector index, and each phase's makespan on T > 1 workers adds
/// the halo exchange modelled at 2 us per message plus 10 GB/s.
typedef struct gf_par_profile {
    size_t blocks;          ///< blocks of the decomposition
    int colours;            ///< colours (blocks of one colour run side by side)
    int phases;             ///< phases per step (each runs every colour)
    int blocks_along[3];    ///< blocks along x, y, z
    int block_cells[3];     ///< grid cells per block along x, y, z
    uint64_t colour_phases; ///< colour phases run while profiling (with spots)
    uint64_t blocks_run;    ///< block runs in them (blocks with spots)
    double work_seconds;    ///< sum of the blocks' times
    double span_seconds;    ///< sum over the phases of the longest block
    int proj_threads[GF_PAR_NPROJ];              ///< 2, 8, 16, 64, 256
    double makespan_seconds[GF_PAR_NPROJ];       ///< sum of the phases' makespans on that many threads
    size_t domains;         ///< domain engine: domains (each owns one block of every colour)
    double window;          ///< domain engine: parallel.window, tau
    double profiled_tau;    ///< simulated time covered while profiling
    uint64_t barriers;      ///< phase barriers while profiling (barriers per tau = barriers / profiled_tau)
    double exchange_bytes;  ///< domain engine: modelled halo bytes sent, all blocks, while profiling
    uint64_t exchange_messages; ///< domain engine: modelled halo messages, all blocks, while profiling
    double serial_seconds;  ///< sweep engine: the one-thread bookkeeping's time (in work and every makespan)
    double part_seconds[4]; ///< sweep engine: work of the walk, the gather (spot displacements), the relaxation sweeps, the list refreshes
    double layer_seconds[GF_PAR_LAYERS]; ///< domain engine: work of the sectors of each layer along z (from the bottom; the last also holds those above)
} gf_par_profile;

/// Starts (on != 0, counters reset) or stops profiling the spatial step's blocks.
GF_API void gf_sim_set_par_profiling(gf_sim *sim, int on);
/// The spatial step's decomposition and the profile so far (zeros before
/// the first spatial step).
GF_API gf_par_profile gf_sim_par_profile(const gf_sim *sim);

/// Writes a checkpoint (versioned header, CRC-32, written then renamed). It
/// is built in memory first, in one block of its size.
GF_API gf_status gf_sim_save(const gf_sim *sim, const char *path);
/// An estimate from above of the size of the checkpoint, bytes, once every
/// particle still inside has left (each exit adds a record; with
/// recirculation, a record per particle): what gf_run_dir makes sure of, in
/// memory and on disk, before it runs.
GF_API size_t gf_sim_checkpoint_bound(const gf_sim *sim);
/// Restores a checkpoint. `cfg` may differ from the saved one only in [run]
/// and [output] keys (GF_ERR_PARAM otherwise); it becomes the sim's config.
GF_API gf_status gf_sim_load(const gf_config *cfg, const char *path, gf_sim **out);

#ifdef __cplusplus
}
#endif
#endif
