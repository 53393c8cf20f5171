// SPDX-License-Identifier: MIT
// DEM side by side (SPEC 1.7-1.8): LAMMPS inputs for the same container, the
// LAMMPS run, DEM dumps as a series, calibration of the five spot parameters
// from a DEM run (thesis Sec. 3.3) and the comparison of two runs (Sec. 3.5).
#ifndef GRANFLOW_DEM_H
#define GRANFLOW_DEM_H

#include <signal.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "granflow/analysis.h"
#include "granflow/config.h"
#include "granflow/core.h"
#include "granflow/packing.h"

#ifdef __cplusplus
extern "C" {
#endif

// ---------------------------------------------------------------------------
// LAMMPS inputs (units lj: d = 1, particle mass 1, g = 1, so times are in tau).

/// Atom type of the flowing particles in the LAMMPS run.
#define GF_DEM_TYPE_FLOW 1
/// Atom type of the frozen beads (diameter 0.05 d) that model the sharp edge
/// of the orifice; they are never dumped.
#define GF_DEM_TYPE_RIM 2

/// What gf_dem_write_inputs planned.
typedef struct gf_dem_plan {
    int64_t particles;      ///< flowing particles
    double fill_height;     ///< expected top of the settled fill, d (phi = 0.6)
    double box_zlo, box_zhi; ///< the LAMMPS box in z, d (x and y are the container)
    double delete_z;        ///< particles are deleted below this height, d
    size_t rim_beads;       ///< frozen beads along the orifice edge
    int64_t snapshot_steps; ///< steps between drain dumps
    int64_t drain_steps;    ///< steps of the drainage (run.duration / dem.timestep)
    double pour_time;       ///< fill_method pour: longest pour, tau (0 for generate)
    int64_t reinsert_steps; ///< run.recirculate = on: steps between the reinsertions (0: particles leave)
    int64_t restart_steps;  ///< steps between the drain's restart files (dem.restart_interval; 0: none)
} gf_dem_plan;

/// Writes the LAMMPS inputs of a DEM run of the container of `cfg` into `dir`
/// (created as needed): `in.fill` (fill by fix pour or from granflow's packing
/// in `fill.data`, settle under gravity on a closed base, write `packing.dump`
/// and `settled.restart`), `in.drain` (open the orifice, drain for
/// run.duration, dump `snapshots/snap_NNNNNNNNN.dump` every
/// output.snapshot_interval with ITEM: TIME; with run.recirculate = on the
/// particles that fell through the orifice are put back on top instead of
/// deleted, each recorded in `reinserted.txt`: docs/dem.md; a LAMMPS restart file
/// every dem.restart_interval, to `drain.a.restart` and `drain.b.restart` in
/// turn: gf_dem_continue), and `config.ini` (the effective
/// configuration, which `calibrate`, `compare` and `analyze` read back).
/// Contacts: pair_style gran/hertz/history with the [dem] keys, the same
/// law on the flat side walls and the base. `plan` may be NULL. The packing
/// (dem.fill_method = generate) is built with `opts` (may be NULL;
/// gf_packing_for_config): once opts->stop is non-zero, GF_ERR_INTERRUPTED
/// and nothing written (the packing comes before any file).
GF_API gf_status gf_dem_write_inputs(const gf_config *cfg, const char *dir, const gf_packing_opts *opts,
                                     gf_dem_plan *plan);

/// The phases of a LAMMPS run (its inputs print a marker as each begins).
typedef enum gf_dem_phase {
    GF_DEM_PHASE_NONE = 0, ///< no marker seen yet
    GF_DEM_PHASE_FILL,     ///< pouring the particles in
    GF_DEM_PHASE_SETTLE,   ///< letting them come to rest
    GF_DEM_PHASE_DRAIN,    ///< the orifice open
    GF_DEM_PHASE_DONE,     ///< the inputs ran to their end
} gf_dem_phase;

/// The phase's name ("fill", "settle", "drain", "done"); "none" for
/// GF_DEM_PHASE_NONE, "?" for a value outside the enum.
GF_API const char *gf_dem_phase_name(gf_dem_phase phase);

/// One progress report of a LAMMPS run.
typedef struct gf_dem_progress {
    gf_dem_phase phase; ///< fill, settle, drain or done (never none)
    double time;        ///< LAMMPS time of the phase, tau
    double until;       ///< planned end of the phase, tau (0: unknown)
    int64_t particles;  ///< flowing particles now
    int64_t target;     ///< particles to pour (fill), else the particles at the start of the drain
    double ke;          ///< kinetic energy per particle, m g d
    double wall_seconds; ///< since gf_dem_run started
} gf_dem_progress;

/// Options of gf_dem_run.
typedef struct gf_dem_run_opts {
    int ranks;           ///< MPI ranks: 1 runs lmp directly; > 1 uses mpirun -np (when found)
    const char *lmp;     ///< the LAMMPS binary (NULL: $GF_LMP, else `lmp` on PATH)
    bool drain_only;     ///< skip in.fill (settled.restart must exist)
    void (*progress)(void *ctx, const gf_dem_progress *p); ///< may be NULL
    void *ctx;
    /// Polled at least every 0.2 s while LAMMPS runs (may be NULL): once
    /// non-zero, LAMMPS' process group gets SIGTERM (SIGKILL after 10 s), is
    /// reaped, and gf_dem_run returns GF_ERR_INTERRUPTED having marked the
    /// directory (GF_DEM_INTERRUPTED).
    volatile sig_atomic_t *stop;
    /// gf_dem_continue only: go on even though the drain's files were written
    /// in the last GF_DEM_BUSY_SECONDS (a LAMMPS that may still run there).
    bool force;
} gf_dem_run_opts;

/// gf_dem_continue refuses a directory whose drain has not ended (its log has
/// no `done` marker) and wrote its log, a restart file or a snapshot less
/// than this many seconds ago (with no newer interrupted.txt): its LAMMPS
/// may still be running, and the continuation would remove and write over
/// what it writes.
#define GF_DEM_BUSY_SECONDS 120

/// The file gf_dem_run writes into a run directory whose LAMMPS run was
/// stopped (and removes when a run completes): the phase, and what it removed
/// as possibly half-written (an interrupted fill: settled.restart and
/// packing.dump; an interrupted drain: the newest snapshot).
#define GF_DEM_INTERRUPTED "interrupted.txt"

/// The defaults (what a NULL opts means): one rank, `lmp` from $GF_LMP or PATH,
/// fill and drain, no progress callback.
GF_API gf_dem_run_opts gf_dem_run_opts_default(void);

/// Runs `in.fill` then `in.drain` of `dir` with LAMMPS (working directory
/// `dir`, logs in log.fill and log.drain), reporting the thermo output as
/// progress. GF_ERR_IO when lmp cannot be found or started, GF_ERR_PARAM
/// with LAMMPS' own ERROR line when it fails, GF_ERR_INTERRUPTED when
/// opts->stop stopped it or a signal killed LAMMPS (the directory marked).
GF_API gf_status gf_dem_run(const char *dir, const gf_dem_run_opts *opts);

/// What gf_dem_continue went on from and what it dropped.
typedef struct gf_dem_cont {
    char restart[32];       ///< the restart file: drain.a.restart or drain.b.restart
    int64_t step, total;    ///< its step, and the drain's last (run.duration / dem.timestep)
    double dt;              ///< dem.timestep, tau
    size_t kept_snaps;      ///< snapshots up to the restart's step, kept
    size_t dropped_snaps;   ///< snapshots after it, removed (the continuation writes its own)
    double dropped_until;   ///< the newest removed snapshot's time, tau (0: none)
    size_t kept_reins, dropped_reins; ///< recirculating: reinsertions before the restart kept, at or after it removed
    char unreadable[640];   ///< the other restart file when LAMMPS could not read it, and why ("": none)
} gf_dem_cont;

/// Continues the interrupted drain of `dir` (granflow dem --continue) with
/// the configuration `cfg` (DIR/config.ini; run.duration may be longer, and
/// is then saved there): LAMMPS reads the newer readable one of
/// DIR/drain.a.restart and drain.b.restart (written every
/// dem.restart_interval) and runs DIR/in.continue, made from DIR/in.drain,
/// up to run.duration (log: log.continue). The record stays one trajectory:
/// snapshots after the restart's step are removed first (a continuation is
/// not bit-identical to the run it replaces), as are a recirculating drain's
/// reinsertions from its time on; LAMMPS appends the rest, and exits.csv is
/// written from the whole reinserted.txt. GF_ERR_PARAM when the drain already
/// ran to run.duration, no restart file exists, or in.drain, the restart and
/// the configuration disagree; GF_ERR_FORMAT when LAMMPS can read neither
/// restart file (its error, naming the file); GF_ERR_EXISTS when the drain
/// may still be running (GF_DEM_BUSY_SECONDS; o->force goes on); otherwise
/// as gf_dem_run (the directory marked interrupted.txt when stopped). `out`
/// may be NULL.
GF_API gf_status gf_dem_continue(const char *dir, const gf_config *cfg, const gf_dem_run_opts *o, gf_dem_cont *out);

// ---------------------------------------------------------------------------
// A DEM run as a series.

/// Where a DEM run comes from and how to read it.
typedef struct gf_dem_source {
    double dump_dt;           ///< time per TIMESTEP for dumps without ITEM: TIME, in the dumps' unit (0: TIME is required)
    const char *config;       ///< INI file with the container and the dumps' units (NULL: DIR/config.ini, else fitted)
    const char *const *sets;  ///< `section.key=value` overrides of that config (e.g. container.width=50)
    size_t nsets;
    volatile sig_atomic_t *stop; ///< polled at every frame read: GF_ERR_INTERRUPTED once non-zero (NULL: never)
} gf_dem_source;

/// The defaults: dumps must carry ITEM: TIME, the container from DIR/config.ini
/// (else the dump's box), no overrides.
GF_API gf_dem_source gf_dem_source_default(void);

/// What gf_dem_series_load dropped, over all frames.
typedef struct gf_dem_load_report {
    bool have_type;          ///< the first dump has a `type` column
    size_t other_types;      ///< particle-frames of atom types not in packing.types
    size_t below_base;       ///< particle-frames whose centre was below container.exit_z (exited)
    double diameter, gravity; ///< the dumps' units they were read in (dump.diameter, dump.gravity)
    char container[2 * GF_PATH_MAX + 256]; ///< the container and where each size came from, and the units
} gf_dem_load_report;

/// Loads a DEM run (or any run) like gf_series_load, in the units
/// dump.diameter and dump.gravity of src->config and src->sets
/// (gf_series_opts.units; a run of granflow, with config.ini, is in d and tau
/// and any other units are an error), then applies the config (src->config,
/// else DIR/config.ini, and src->sets: the container, packing.types, exit_z),
/// keeps only the atom types of packing.types (re-tagging the layers by the
/// first frame's heights), and removes from every frame the particles below
/// container.exit_z: DEM keeps them until they fall to its deletion height,
/// granflow counts them as exited. Without DIR/config.ini the walls no config
/// gives are fitted to the particles left (gf_series_fit_walls). The series'
/// cfg has dump.diameter = dump.gravity = 1: it is in d and tau. `rep` may be NULL.
GF_API gf_status gf_dem_series_load(const char *path, const gf_dem_source *src, gf_series *out,
                                    gf_dem_load_report *rep);

/// What gf_dem_analyze read and did.
typedef struct gf_dem_analysis {
    size_t nframes, nexits;  ///< snapshots and exits read
    bool exits_derived;      ///< no exits.csv: the exits were read off the snapshots
    double exit_resolution;  ///< then their times are within +- this, tau (half a snapshot interval)
    double t_first, t_last;  ///< times of the first and last snapshot, tau
    gf_steady window;        ///< the window measured over (t0, t1) and why
    char outdir[GF_PATH_MAX + 16]; ///< where the results went
    char container[2 * GF_PATH_MAX + 256]; ///< the container, where each size came from, the units (gf_dem_load_report)
} gf_dem_analysis;

/// `granflow analyze` (SPEC 1.6): loads `path` (a run directory, a directory
/// of LAMMPS dumps or one dump) with gf_dem_series_load (`src` may be NULL:
/// the defaults; the dumps' time step is o->dump_dt either way), measures
/// over the window of `o` or, where that is auto, the steady flow
/// (gf_dem_window), and runs measurement `name` (NULL: all) into `outdir`
/// (NULL: PATH/analysis, or analysis/ beside a dump) with gf_analyze. `o` is
/// not changed; `info` may be NULL.
/// Where gf_dem_analyze writes by default: PATH/analysis for a directory,
/// analysis/ beside a single dump. GF_ERR_PARAM when it does not fit in n.
GF_API gf_status gf_dem_analyze_outdir(const char *path, char *out, size_t n);
GF_API gf_status gf_dem_analyze(const char *path, const gf_dem_source *src, const gf_analysis_opts *o,
                                const char *name, const char *outdir, bool plots, gf_dem_analysis *info);

// ---------------------------------------------------------------------------
// Calibration (thesis Sec. 3.3).

/// A measured or fitted number with its standard uncertainty (NaN: unknown).
typedef struct gf_dem_value {
    double value, err;
} gf_dem_value;

/// Everything gf_dem_calibrate measures and infers.
typedef struct gf_dem_calibration {
    double t0, t1;              ///< the window, tau
    size_t nparts;              ///< sub-windows behind the uncertainties
    // measured
    gf_dem_value flow_rate;     ///< Q, particles per tau
    gf_dem_value corr_length;   ///< beta of C(r) = a exp(-r / beta), d
    gf_dem_value var_slope;     ///< d Var / dz of the Gaussian v_z(x) profiles (v_z(r) in a cylinder), d
    size_t var_heights;         ///< heights used in that regression
    gf_dem_value diff_length;   ///< b_p, d
    gf_dem_value ball_count;    ///< p: particles in a spot ball placed where spots go (walls cut it)
    double ball_count_bulk;     ///< phi V_ball / V_p with the slice's phi (the thesis' 81.7)
    gf_dem_value slice_initial; ///< particles in the density slice at the first frame
    gf_dem_value slice_steady;  ///< ... averaged over the window
    double slice_z0, slice_z1;  ///< the slice, d
    // the five spot parameters
    gf_dem_value radius;        ///< r_s = beta / 0.72, d (spot.radius)
    gf_dem_value b_s;           ///< spot diffusion length = slope / 2, d
    gf_dem_value step_xy;       ///< dx = sqrt(4 b_s dz) for the config's spot.step_z, d
    gf_dem_value w;             ///< b_s / b_p
    gf_dem_value insertion_rate; ///< lambda = Q w / p, 1/tau
    gf_dem_value move_rate;     ///< mu = Q h / (dz dN), 1/tau
    // what could not be measured: one sentence each, with the fallback used
    char notes[6][240];
    size_t nnotes;
} gf_dem_calibration;

/// The thesis' ratio beta / r_s of the exponential fitted to the spot model's
/// velocity correlation (Sec. 3.3).
#define GF_DEM_BETA_PER_RS 0.72
/// The shortest correlation length taken as measured, d: the exponential is
/// fitted from r = 1 d (one diameter) on, so a shorter beta is not resolved
/// (a 1,000-sphere LAMMPS silo gave 0.5 d, r_s 0.7, and the refinement ran off).
#define GF_DEM_BETA_MIN 1.0

/// Sets the measurement regions of `o` for the container and fill of `s`
/// (the papers' regions scaled to the packing height; see docs/dem.md).
/// Options already changed from their defaults by the caller are kept when
/// `keep` is given (the gf_analysis_opts the caller started from).
GF_API void gf_dem_calibration_opts(const gf_series *s, const gf_analysis_opts *keep, gf_analysis_opts *o);

/// Measures the series over the window of `o` and infers the five spot
/// parameters; uncertainties from the scatter over sub-windows. `cfg` gives
/// spot.step_z and spot.wall_distance (where spots may go). A quantity that
/// cannot be measured (no fit, no density drop, a correlation longer than
/// its region) leaves its parameter at a fallback (the thesis' value, or
/// `cfg`'s), with a sentence in c->notes: never a NaN or a negative rate.
/// Only a run without outflow is an error (GF_ERR_PARAM).
GF_API gf_status gf_dem_calibrate(const gf_series *s, const gf_analysis_opts *o, const gf_config *cfg,
                                  gf_dem_calibration *c);

/// Copies the five calibrated values into `cfg` (spot.radius, spot.step_xy,
/// spot.w, spot.insertion_rate, spot.move_rate) and validates it.
GF_API gf_status gf_dem_calibration_apply(const gf_dem_calibration *c, gf_config *cfg);

/// Writes a human-readable table of the calibration (one line per value with
/// its uncertainty and the thesis' DEM value).
GF_API void gf_dem_calibration_print(const gf_dem_calibration *c, FILE *out);

/// Resolves an automatic window (o->t0 or o->t1 NaN) to the steady-flow
/// window of the series' outflow (gf_steady_window); `w` (may be NULL) gets
/// the window and the reason. A window given by the caller is kept.
GF_API gf_status gf_dem_window(const gf_series *s, gf_analysis_opts *o, gf_steady *w);

// ---------------------------------------------------------------------------
// Matching a spot run to a DEM run (thesis Sec. 3.5).

#define GF_DEM_FS_MAXZ 16
#define GF_DEM_FS_MAXL 32
/// The numbers a spot run must match a DEM run on, over the window of the
/// options, each with the standard error of its mean over window.parts
/// sub-windows (NaN: unknown or not measurable); the residence times (the
/// whole run, up to the options' rtd.tmax) with the uncertainty of a mean
/// of gf_measure_rtd (standard error, and the exit-time resolution of
/// exits read off the snapshots).
typedef struct gf_dem_flowstats {
    double t0, t1;                     ///< the window, tau
    size_t parts;                      ///< sub-windows behind the uncertainties (window.parts, fewer in a short window)
    gf_dem_value flow;                 ///< flow rate Q, particles per tau
    size_t nz;                         ///< velocity heights
    double z[GF_DEM_FS_MAXZ];          ///< their heights, d
    gf_dem_value var[GF_DEM_FS_MAXZ];  ///< variance of the Gaussian fit of the profile there, d^2
    double var_t0[GF_DEM_FS_MAXZ];     ///< the profile there averaged the frames from this time to t1
                                       ///< (velocity.window = height), tau; NaN: no steady frames there
    double var_drift[GF_DEM_FS_MAXZ];  ///< Var over the later half of the sub-windows less over the earlier,
                                       ///< relative to the whole window's (NaN: fewer than 4 sub-windows there)
    double var_drift_se[GF_DEM_FS_MAXZ]; ///< that difference in standard errors of itself
    const char *profile;               ///< that profile's name, gf_velocity_profile_name: v_z(x) or v_z(r)
    gf_dem_value bp;                   ///< particle diffusion length b_p, d
    gf_dem_value phi;                  ///< packing fraction in the density slice, in flow
    gf_dem_value drop;                 ///< particles fewer in the slice in flow than at rest
    gf_dem_value beta;                 ///< velocity correlation length (when asked), d
    gf_dem_value rtd;                  ///< mean residence time of the first frame's exited particles, tau
    double rtd_tmax;                   ///< residence times counted up to this, tau
    double rtd_resolution;             ///< their exit-time resolution, tau (0: exits.csv)
    size_t nlayer;                     ///< initial layers with exits
    int32_t layer[GF_DEM_FS_MAXL];     ///< their tags (1: the bottom 10 d band)
    gf_dem_value rtd_layer[GF_DEM_FS_MAXL]; ///< mean residence time of each, tau
} gf_dem_flowstats;
/// Measures `fs` on the series over the window of `o` (the correlation
/// length too when `correlation`: the slowest measurement).
GF_API gf_status gf_dem_flowstats_measure(const gf_series *s, const gf_analysis_opts *o, bool correlation,
                                          gf_dem_flowstats *fs);
/// Whether a DEM value is measured precisely enough to test a match within
/// `tol`: positive, with a relative standard error of at most tol.
GF_API bool gf_dem_flowstats_measured(gf_dem_value v, double tol);
/// True when the spot run's flow rate is within flow_tol (relative) of the
/// DEM's and its Var within var_tol at every height the DEM measured
/// (gf_dem_flowstats_measured with var_tol; at least one).
GF_API bool gf_dem_flowstats_match(const gf_dem_flowstats *dem, const gf_dem_flowstats *spot, double flow_tol,
                                   double var_tol);
/// Prints the table DEM | spot | difference with its uncertainty | verdict
/// (within or outside the tolerance: flow_tol for the flow rate, var_tol for
/// each Var; the other rows have none). The residence-time rows follow when
/// both runs counted them over the same span (gf_dem_compare_opts), else a
/// line saying why they are not compared.
GF_API void gf_dem_flowstats_table(const gf_dem_flowstats *dem, const gf_dem_flowstats *spot, double flow_tol,
                                   double var_tol, FILE *f);

/// The options of a comparison of `dem` and `spot`: `o` with rtd.tmax, when
/// auto, set to the shorter run's length (first to last snapshot), so both
/// residence-time distributions are cut at the same time.
GF_API void gf_dem_compare_opts(const gf_series *dem, const gf_series *spot, gf_analysis_opts *o);

/// Tolerances of the closed-loop calibration and of `granflow compare`.
#define GF_DEM_FLOW_TOL 0.05
#define GF_DEM_VAR_TOL 0.10

/// Options of gf_dem_refine.
typedef struct gf_dem_refine_opts {
    int max_iter;                    ///< spot runs at most (0: 6)
    double flow_tol, var_tol;        ///< 0: GF_DEM_FLOW_TOL, GF_DEM_VAR_TOL
    void (*progress)(void *ctx, int iter, int max_iter, const gf_config *cfg, const gf_dem_flowstats *dem,
                     const gf_dem_flowstats *spot, bool match); ///< after each spot run; may be NULL
    void *ctx;
    volatile sig_atomic_t *stop;     ///< GF_ERR_INTERRUPTED when it becomes non-zero; may be NULL
    const gf_packing *start;         ///< the spot runs' initial packing (NULL: the DEM's first frame)
} gf_dem_refine_opts;
/// The defaults (what a NULL `ro` means): every member 0/NULL.
GF_API gf_dem_refine_opts gf_dem_refine_opts_default(void);
/// The result of gf_dem_refine.
typedef struct gf_dem_refine_result {
    gf_dem_flowstats dem;            ///< the DEM's numbers
    gf_dem_flowstats first, last;    ///< the spot runs of the first guess and of the final parameters
    int runs;                        ///< spot runs made
    bool matched;                    ///< the final parameters meet both tolerances
    /// The kept parameters fitted jointly to the flow and the Var(z) line,
    /// each with its standard error (the kept run's noise carried through
    /// the model; err NaN: not fitted, e.g. r_s fixed by the correlation length).
    gf_dem_value insertion_rate, step_xy, radius;
    char unreached[512];             ///< when not matched: which targets were missed and why ("" when matched)
} gf_dem_refine_result;
/// Closed-loop calibration: runs the spot model from the DEM's first frame
/// with the parameters of `cfg` (the thesis relations' first guess) over the
/// DEM's window, compares, and adjusts them (spot.insertion_rate, step_xy and
/// radius together for the flow rate and the slope and level of the Var(z)
/// line, a least-squares step on a model learnt from the runs; spot.w for
/// b_p, spot.move_rate for the density drop, spot.radius from beta on the
/// first run when the DEM's correlation length is usable) until the flow rate is within
/// flow_tol and Var at every height within var_tol, or max_iter runs; `cfg`
/// ends with the best parameters found (the run closest to the targets).
GF_API gf_status gf_dem_refine(const gf_series *dem, const gf_analysis_opts *o, gf_config *cfg,
                               const gf_dem_refine_opts *ro, gf_dem_refine_result *res);
/// Prints the jointly fitted parameters with their standard errors and,
/// when the targets were not all met, which were missed and why.
GF_API void gf_dem_refine_print(const gf_dem_refine_result *res, FILE *out);

// ---------------------------------------------------------------------------
// Comparison (thesis Sec. 3.5).

/// Measures both runs the same way and writes into `outdir`: one CSV per
/// compared quantity with a column per run, gnuplot plots overlaying them
/// (when `plots`), central-slice pictures of both at the same times, and
/// `summary.md` with the headline numbers and their differences.
GF_API gf_status gf_dem_compare(const gf_series *dem, const gf_series *spot, const gf_analysis_opts *o,
                                const char *outdir, bool plots);

#ifdef __cplusplus
}
#endif
#endif
