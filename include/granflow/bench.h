// SPDX-License-Identifier: MIT
// The benchmark (`granflow bench`): the spot engine on the papers' silo in
// steady flow, microseconds per spot() and relax() call (2009 paper Sec. 2:
// 7.15 us and 115 us), steps per second on one thread and on all, parallel
// efficiency, memory per particle, the projected wall time of a full
// drainage, the same on a silo ten times larger; and the lattice-gas
// automaton's site updates per second (SPEC 2). Figures are wall-clock
// measurements: they depend on the machine and its load.
#ifndef GRANFLOW_BENCH_H
#define GRANFLOW_BENCH_H

#include <signal.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "granflow/config.h"
#include "granflow/core.h"
#include "granflow/sim.h"

#ifdef __cplusplus
extern "C" {
#endif

/// Ranks whose figures gf_bench_spot keeps one by one.
#define GF_BENCH_RANKS 64

/// Figures of one silo in steady flow.
typedef struct gf_bench_spot {
    size_t particles, spots;   ///< particles at the start; spots active at the end
    int threads;               ///< threads of the "all" window
    double pack_s, warm_s;     ///< packing (gf_packing_for_config and engine set-up) and warm-up wall time, s
    double sps_all, sps_one;   ///< steps (spot moves) per second, all threads / one
    double spot_us, relax_us;  ///< per call, one thread
    double flow;               ///< particles per tau over the windows
    double moves_per_tau;      ///< spot moves per tau over the windows
    double bytes_per_particle; ///< the library's allocations / particles
    double drain_s;            ///< projected wall seconds to drain what is left, all threads
    size_t remaining;          ///< particles left at the end
    gf_par_profile prof;       ///< the parallel engine's blocks (sectors), over the timed one-thread window
    /// MPI ranks the silo ran on (1 without mpirun), and per rank (the first
    /// GF_BENCH_RANKS; filled on rank 0): its peak resident set when the silo
    /// was done (bytes, getrusage ru_maxrss), and the bytes it sent per
    /// exchanged phase over the warm-up and the windows (0 on one rank).
    /// Also the particles in its region (slab and halo) and in its slab
    /// when the silo was done: what it would hold were the memory divided
    /// (one process: every particle).
    int ranks;
    double rank_peak_rss_bytes[GF_BENCH_RANKS];
    double rank_exchange_bytes_per_phase[GF_BENCH_RANKS];
    double rank_region_particles[GF_BENCH_RANKS];
    double rank_slab_particles[GF_BENCH_RANKS];
    /// Particle records it held when the silo was done (a non-zero id): one
    /// process, every particle; an MPI rank of the domain engine that read
    /// packing.file keeping its region (issue 23), that region's, with a
    /// margin and the particles its neighbours sent it; every particle once a
    /// gather made its state whole.
    double rank_held_particles[GF_BENCH_RANKS];
} gf_bench_spot;

/// The lattice-gas automaton's speed: the paper's channel (the lga.* keys of
/// the config) in its density-wave regime, timed after a warm-up of 200 iterations.
typedef struct gf_bench_lga {
    double site_updates_per_second, seconds;
    int64_t sites, iterations, particles;
} gf_bench_lga;

/// Options of gf_bench. Make them with gf_bench_opts_default(), then change fields.
typedef struct gf_bench_opts {
    double warmup;      ///< tau of flow before the timed windows (default 40: spots reach the top of the papers' packing)
    double window;      ///< tau of each timed window (default 1)
    size_t particles;   ///< packing.particles of the silo; 0 (default): the config's
    bool event;         ///< the event-driven engine (one thread) instead of the domain engine (default false)
    bool spatial;       ///< the spatial fixed step instead of the domain engine (default false)
    bool sweep;         ///< the sweep engine (run.order = sweep) instead of the domain engine (default false)
    bool large;         ///< also the silo ten times larger (default true)
    bool lga_only;      ///< only the lattice-gas automaton (default false)
    int64_t lga_iters;      ///< timed LGA iterations (default 1000)
    /// Called once a silo is packed, before its warm-up (may be NULL): b->particles,
    /// b->pack_s and b->threads are set; `sim` holds the packing.
    void (*packed)(void *ctx, const gf_bench_spot *b, const gf_sim *sim, double warmup);
    void *ctx;          ///< passed to packed
    /// Polled while packing, warming up, in every timed window and LGA run:
    /// once non-zero, gf_bench returns GF_ERR_INTERRUPTED (no figures). NULL: never.
    volatile sig_atomic_t *stop;
} gf_bench_opts;

/// The defaults listed in gf_bench_opts.
GF_API gf_bench_opts gf_bench_opts_default(void);

/// What gf_bench measured.
typedef struct gf_bench_report {
    bool lga_only;             ///< only `lga` holds figures
    bool large;                ///< `big` holds figures
    const char *engine;        ///< "domains", "spatial", "sweep" or "event"
    double warmup, window;     ///< tau
    gf_bench_spot silo, big;   ///< the silo of the config, and the one ten times larger
    double peak_rss_bytes;     ///< peak resident set of the process after the silo, bytes
    double step_us;            ///< us per spot move on one thread
    double efficiency;         ///< steps per second on all threads over threads x on one
    gf_bench_lga lga;
} gf_bench_report;

/// Runs the benchmark on the silo `cfg` describes (its packing made as a run
/// makes it: gf_packing_for_config, so packing.file with packing.types is
/// imported the same way): packs, warms up, then times three windows (all
/// threads, one thread, one thread with spot() and relax() clocked call by
/// call); with opts->large the same on a silo of ten times the particles in
/// ten times the cross-section (same height, orifice and spots); then the LGA.
GF_API gf_status gf_bench(const gf_config *cfg, const gf_bench_opts *opts, gf_bench_report *out);

/// Writes the report as one JSON object on one line (`granflow bench --json`), or as text.
GF_API void gf_bench_write(FILE *f, const gf_bench_report *r, bool json);

#ifdef __cplusplus
}
#endif
#endif
