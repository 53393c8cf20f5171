// SPDX-License-Identifier: MIT
// Internal helpers shared by the DEM files (src/dem/).
#ifndef GF_DEM_INTERNAL_H
#define GF_DEM_INTERNAL_H

#include <stdio.h>

#include "granflow/core.h"
#include "granflow/dem.h"

/// Sub-windows behind calibrate's and compare's uncertainties: window.parts
/// (limited to [2, most]) when the window's nframes give each at least 3
/// frames, else 2 with at least 6 frames, else 1.
size_t gf_dem_window_parts(const gf_analysis_opts *o, size_t nframes, size_t most);

/// in.drain's `restart N drain.a.restart drain.b.restart` (nothing when
/// plan->restart_steps is 0), before the drain's first run.
void gf_dem_restart_line(FILE *f, const gf_dem_plan *plan, double timestep);

// ---- granflow dem --continue (lammps_continue.c) ---------------------------------

/// Whether the newer of DIR/log.drain and log.continue says its drain ran
/// to its end (the `done` marker after the last `drain` or `continue`
/// marker), and to which time (*until, tau; the marker's 6 digits).
bool gf_dem_cont_done(const char *dir, double *until);
/// GF_ERR_EXISTS when the drain of DIR wrote its log, a restart file or a
/// snapshot in the last GF_DEM_BUSY_SECONDS and no newer interrupted.txt
/// says granflow stopped it: its LAMMPS may still be running (the caller
/// asks only of a drain whose log has not ended: gf_dem_cont_done).
gf_status gf_dem_cont_check_idle(const char *dir);
/// Puts each snapshot's ITEM: TIME right (step * dt) where LAMMPS wrote the
/// time of a run after read_restart (from 0); counts those rewritten.
gf_status gf_dem_cont_fix_times(const char *dir, double dt, size_t *fixed);
/// gf_dem_cont_fix_times of the one snapshot of step `step`, if it exists
/// (as the continuation goes: LAMMPS has closed it once its thermo line of
/// that step is out).
gf_status gf_dem_cont_fix_step(const char *dir, int64_t step, double dt);
/// Checks DIR/in.drain against cfg, removes the tail after `step` (snapshots;
/// reinsertions) and writes DIR/in.continue reading `restart` (fills c).
gf_status gf_dem_cont_prepare(const char *dir, const gf_config *cfg, const char *restart, int64_t step,
                              gf_dem_cont *c);

// ---- recirculation (lammps_recirculate.c, reinserted.c; issue 27 item 4) --------

/// The reinsertion file LAMMPS appends to, in the run directory.
#define GF_DEM_REINSERTED "reinserted.txt"
/// What granflow dem cannot do under run.recirculate = on (run.max_passes,
/// a central column), as GF_ERR_PARAM naming the key and where it was set.
gf_status gf_dem_recirc_check(const gf_config *c);
/// Room above a packing whose top is at `top` the reinsertion slab needs, d
/// (the slab and the packing's rise as it dilates in flow).
double gf_dem_recirc_headroom(double top);
/// in.drain's drainage with reinsertion (after the base and before the end).
void gf_dem_recirc_drain(FILE *f, const gf_config *c, const gf_dem_plan *plan, double rmax, long seed);
/// DIR/exits.csv (the format of a spot run's: id,time,x,y,pass,entry_time,
/// entry_r) from DIR/reinserted.txt, the initial entry radii from
/// DIR/packing.dump. GF_OK and nothing written when the file is absent.
gf_status gf_dem_write_exits(const char *dir);
/// How long ago a particle now h below the exit plane and falling at u (> 0
/// down) crossed it in free fall (g = 1): the exit time of a reinsertion.
double gf_dem_fall_time(double h, double u);

/// Weighted least-squares line Var(z) = level + slope (z - zm) through the
/// heights the DEM measured precisely enough (gf_dem_flowstats_measured with
/// vtol), weighted by the DEM's 1 / err^2, zm their weighted mean height (so
/// level and slope are uncorrelated), fitted to the DEM's and to the spot's
/// Var at those heights with the same weights (so the two lines compare);
/// each coefficient with its standard error from the run's own errors.
typedef struct gf_dem_var_lines {
    int n;                           ///< heights used (below 2, or all at one height: no line)
    double zm;                       ///< the weighted mean height, d
    gf_dem_value level[2], slope[2]; ///< [0] the DEM's, [1] the spot's: Var at zm, d Var / dz
} gf_dem_var_lines;
void gf_dem_var_lines_fit(const gf_dem_flowstats *dem, const gf_dem_flowstats *spot, double vtol,
                          gf_dem_var_lines *l);

// ---- the joint step (refine_step.c; issue 27 item 3) ---------------------------

/// Targets (rows) and parameters (columns) of the joint step: p = (ln(lambda /
/// w), ln step_xy, r_s) set y = (ln Q, ln d Var / dz, ln Var at zm).
enum { GF_REF_FLOW = 0, GF_REF_SLOPE = 1, GF_REF_LEVEL = 2 };
enum { GF_REF_LAMBDA = 0, GF_REF_STEP = 1, GF_REF_RADIUS = 2 };
/// The three targets of a DEM and a spot run, each with the combined
/// standard error of their difference; ok: measured (the slope needs two
/// heights, the level one).
typedef struct gf_ref_targets {
    double dem[3], spot[3], sig[3];
    bool ok[3];
    gf_dem_var_lines lines;
} gf_ref_targets;
void gf_ref_targets_make(const gf_dem_flowstats *dem, const gf_dem_flowstats *spot, double vtol, gf_ref_targets *t);
/// The linear model dy = J dp of the targets' response to the parameters.
typedef struct gf_ref_model {
    double J[3][3];
    double diag0[3]; ///< each target's slope in its own parameter at the start (kept within a factor 4)
} gf_ref_model;
/// J from the thesis' relations at r_s and the spot's Var line (slope, level).
void gf_ref_model_init(gf_ref_model *m, double r_s, double slope, double level);
/// Broyden's update of the rows `ok` from a run's change dp -> dy, each only
/// when the change (observed or predicted) exceeds twice its noise sig.
void gf_ref_model_update(gf_ref_model *m, const double dp[3], const double dy[3], const double sig[3],
                         const bool ok[3], double r_s);
/// The weighted least-squares step dp over the rows `row` (residuals r,
/// errors sig) and the free columns `col`, with a prior of standard
/// deviation rs_prior (d; 0: none) against moving r_s; cov gets the
/// covariance of the free parameters (the inverse of the weighted normal
/// matrix, the prior included). Returns the number of free parameters
/// solved for (0: none, or singular).
int gf_ref_step(const gf_ref_model *m, const double r[3], const double sig[3], const bool row[3], const bool col[3],
                double rs_prior, double dp[3], double cov[3][3]);
/// How far a spot run is from the targets: worst, the largest of |dQ| / (Q
/// ftol) and |dVar| / (Var vtol) over the heights the DEM measured well
/// enough and the spot run had steady (INFINITY without a flow); unseen, the
/// DEM's measured heights the spot run never had steady.
typedef struct gf_ref_score {
    double worst;
    int unseen;
} gf_ref_score;
gf_ref_score gf_ref_score_of(const gf_dem_flowstats *dem, const gf_dem_flowstats *spot, double ftol, double vtol);
/// a closer than b: fewer unseen heights first (a run that measures fewer
/// heights never wins on the ones it kept), then the smaller worst.
bool gf_ref_score_better(gf_ref_score a, gf_ref_score b);
/// Every target met: no unseen height and worst <= 1.
bool gf_ref_score_matched(gf_ref_score s);
/// Scales dp so that no log moves by more than ln maxf and r_s by no more
/// than a factor maxf; returns the factor applied (1: none).
double gf_ref_limit(double dp[3], double r_s, double maxf);

#endif
