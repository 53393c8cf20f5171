// SPDX-License-Identifier: MIT
// A run directory: what `granflow run` writes (config.ini, snapshots/,
// exits.csv, summary.json, checkpoint.bin) and how a run resumes from it.
#ifndef GRANFLOW_RUN_H
#define GRANFLOW_RUN_H

#include <signal.h>

#include "granflow/config.h"
#include "granflow/core.h"
#include "granflow/particles.h"
#include "granflow/sim.h"

#ifdef __cplusplus
extern "C" {
#endif

/// Where a run is, as a progress callback sees it.
typedef enum gf_run_phase {
    GF_RUN_PHASE_PACKING = 0, ///< building the initial packing
    GF_RUN_PHASE_READING,     ///< importing packing.file
    GF_RUN_PHASE_IMPORTED,    ///< the import is done (note: what it kept and dropped)
    GF_RUN_PHASE_RUNNING,     ///< the engine runs
    GF_RUN_PHASE_STALLED,     ///< the run stops early (note: why)
    GF_RUN_PHASE_DONE,        ///< the run ended
} gf_run_phase;

/// The phase's name ("packing", "reading", "imported", "running", "stalled",
/// "done"); "?" for a value outside the enum.
GF_API const char *gf_run_phase_name(gf_run_phase phase);

/// What a progress callback sees.
typedef struct gf_run_progress {
    gf_run_phase phase;     ///< where the run is
    double time, until;     ///< simulated time and the run's end, tau
    double start;           ///< simulated time when this invocation started (0, or where a resume began)
    size_t initial, remaining; ///< particles at t = 0 and now
    double steps_per_second;   ///< spot moves per wall second, this invocation
    double wall_seconds;       ///< wall time of this invocation so far
    const char *note;          ///< "imported": what the import of packing.file kept and dropped; "stalled": why
} gf_run_progress;

/// Options of gf_run_dir.
typedef struct gf_run_opts {
    const char *dir;      ///< run directory (created as needed)
    int resume;           ///< continue from dir/checkpoint.bin (cfg = dir/config.ini + overrides)
    int force;            ///< allow a fresh run over a directory that already holds one
    volatile sig_atomic_t *stop; ///< set non-zero (e.g. by SIGINT) to checkpoint and stop
    void (*progress)(void *ctx, const gf_run_progress *p); ///< may be NULL
    void *ctx;            ///< passed to progress
    /// Non-zero: run in step with another process that writes dir (an MPI
    /// rank other than 0): on resume read dir/checkpoint.bin, but write
    /// nothing, take no lock and clear nothing.
    int replica;
} gf_run_opts;

/// The defaults: a fresh run, no progress callback, no stop flag; set `dir`.
GF_API gf_run_opts gf_run_opts_default(void);

/// Runs (or resumes) a simulation into opts->dir: snapshots every
/// output.snapshot_interval as LAMMPS dumps in dir/snapshots/, with the new
/// exits appended (and flushed) to exits.csv and summary.json rewritten at
/// each; a checkpoint at every run.checkpoint_interval, on stop and at the
/// end. A fresh run first removes what an earlier run left in dir (config.ini,
/// checkpoint.bin, exits.csv, summary.json, snapshots, analysis/, render/);
/// a run holds a lock on dir/.lock, and a second run there fails (GF_ERR_PARAM).
/// A silo from which nothing has left for run.stall_time stops early with
/// status "stalled" (GF_OK), or GF_ERR_STATE if nothing ever left. Returns
/// GF_OK, GF_ERR_INTERRUPTED (checkpoint written; `stats` all zero when it
/// came while building the packing, before anything was written) or an
/// error (summary.json then says "failed"). `stats` (may be NULL) receives
/// the final counters.
GF_API gf_status gf_run_dir(const gf_config *cfg, const gf_run_opts *opts, gf_sim_stats *stats);

/// GF_OK when no granflow run holds dir/.lock (or there is none, or no dir);
/// GF_ERR_PARAM, "DIR is in use by another granflow run (pid N, lock
/// DIR/.lock) ...", when one does. Touches nothing. gf_run_dir checks this
/// first, before it builds a packing or reads a checkpoint; a caller may ask
/// before anything of its own (the CLI, before "no run to resume").
GF_API gf_status gf_run_dir_check_free(const char *dir);

/// gf_run_write_snapshot (one snapshot frame as a LAMMPS dump) is a file
/// format: it is declared in granflow/particles.h, included above.

// ---- the state of a simulation driven by hand (bindings, notebooks) --------

/// Writes the particles of `sim` as one snapshot frame (gf_run_write_snapshot:
/// the time, the events as TIMESTEP, the pass column under run.recirculate)
/// to `path`, atomically; granflow analyze, render and gf_snapshot_read read it.
GF_API gf_status gf_sim_write_snapshot(const gf_sim *sim, const char *path);

/// Writes the particles of `sim` as a VTK XML unstructured grid (.vtu, as
/// the run directory's output.format = vtk snapshots) to `path`, atomically.
GF_API gf_status gf_sim_write_vtk(const gf_sim *sim, const char *path);

/// Writes the state of `sim` as a run directory `dir`, as if `granflow run`
/// had stopped there: config.ini, checkpoint.bin (`granflow run --resume`
/// goes on from it), exits.csv, summary.json (status "saved") and the
/// snapshot of the current time in snapshots/ (with container.vtk and a .vtu
/// under output.format = vtk or both). A directory that already holds a run
/// (checkpoint.bin) is GF_ERR_EXISTS unless `force`; a fresh write first
/// removes what an earlier run left there, as gf_run_dir does.
GF_API gf_status gf_sim_write_run_dir(const gf_sim *sim, const char *dir, int force);

#ifdef __cplusplus
}
#endif
#endif
