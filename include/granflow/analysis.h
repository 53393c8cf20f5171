// SPDX-License-Identifier: MIT
// Measurements of a run (SPEC 1.6): the statistics the 2009 paper and the
// thesis plot, computed from a series of snapshots (granflow's or any LAMMPS
// dumps, so a DEM run is measured the same way) and the exits of a run.
#ifndef GRANFLOW_ANALYSIS_H
#define GRANFLOW_ANALYSIS_H

#include <signal.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "granflow/config.h"
#include "granflow/core.h"
#include "granflow/packing.h"
#include "granflow/exit.h"

#ifdef __cplusplus
extern "C" {
#endif

// ---------------------------------------------------------------------------
// Input: a time series of snapshots.

/// One snapshot: its simulated time and its particles.
typedef struct gf_frame {
    double time;   ///< tau (ITEM: TIME, or TIMESTEP x the dump time step)
    gf_packing pk; ///< particles, in file order
} gf_frame;

/// Everything a measurement may read. `frames` and `exits` are gf_alloc'ed
/// arrays of exactly nframes / nexits elements (gf_series_free releases them
/// and every frame's packing), so a test may build a series in memory.
typedef struct gf_series {
    size_t nframes;
    gf_frame *frames;   ///< in time order
    gf_exit *exits;     ///< from exits.csv (sorted by time), NULL when there is none
    size_t nexits;
    bool has_exits;
    bool exits_derived;     ///< the exits were read off the frames (gf_series_derive_exits), not exits.csv
    double exit_resolution; ///< tau: a derived exit time is within +- this of the true one (half the
                            ///< longest frame interval an exit was found in); 0 for exits.csv
    size_t n_initial;   ///< particles in the first frame
    gf_config cfg;      ///< the run's config.ini when there is one, else defaults with the
                        ///< container centred on the first frame's box and fitted to the
                        ///< particles (gf_series_fit_walls)
    bool has_config;    ///< cfg is the run's config.ini (a run of granflow: its dumps are in d and tau)
    bool spot_run;      ///< a spot run of granflow (its summary.json counts spot moves): the flow at
                        ///< height z starts once the spots born at the opening have risen there
} gf_series;

/// The units of dumps granflow did not write (the keys dump.diameter and
/// dump.gravity): lengths are read in d, times in tau = sqrt(diameter / gravity).
typedef struct gf_series_units {
    double diameter; ///< the particle diameter in the dumps' length unit (1: they are in d; 0.004: 4 mm in metres)
    double gravity;  ///< gravity in the dumps' units (1 with diameter 1: times in tau; 9.81 in SI)
} gf_series_units;

/// Options of gf_series_load. A NULL `opts` means gf_series_opts_default().
typedef struct gf_series_opts {
    /// The dumps' units (NULL, default: d and tau): positions, radii, the box
    /// and exits.csv are divided by units->diameter, times (ITEM: TIME,
    /// TIMESTEP x dump_dt, exits.csv) by sqrt(diameter / gravity); dump_dt is
    /// then in the dumps' time unit (seconds for an SI dump).
    const gf_series_units *units;
    /// Polled at every frame: once non-zero, GF_ERR_INTERRUPTED with nothing
    /// loaded. NULL (default): never.
    volatile sig_atomic_t *stop;
} gf_series_opts;

/// The defaults listed in gf_series_opts.
GF_API gf_series_opts gf_series_opts_default(void);

/// Loads a run directory (config.ini, snapshots/*.dump, exits.csv), a
/// directory of LAMMPS dumps, or one (multi-frame) LAMMPS dump. Frames come in
/// time order; `dump_dt` converts TIMESTEP to tau when a dump has no ITEM: TIME
/// (0: frames without it are an error). `opts` may be NULL.
GF_API gf_status gf_series_load(const char *path, double dump_dt, const gf_series_opts *opts, gf_series *out);
/// The walls of a box container (`cfg` with container.shape = box) where the
/// particles of `s` end: container.width (depth) = twice the largest |x| (|y|)
/// + radius of a particle at or above the exit plane in any frame, each only
/// when `cfg` does not have it from a file or an assignment
/// (gf_config_is_set), and then marked as set by "particle extent"
/// (gf_config_where). Another shape (a cylinder, a wedge: walls not at its
/// bounding box), or a series without particles, is left as it is.
GF_API gf_status gf_series_fit_walls(const gf_series *s, gf_config *cfg);
GF_API void gf_series_free(gf_series *s);
/// Exits of a series without exits.csv (the dumps of a DEM drain), read off
/// its frames: a particle in frame k and not in frame k + 1 exited at the
/// midpoint of their times, at its (x, y) of frame k; only its first
/// disappearance counts; entry at the first frame (entry_r from its position
/// there, NaN for an id not in it), pass 1. Sets has_exits, exits_derived
/// and exit_resolution (half the longest frame interval an exit was found
/// in). A series that has exits is left as it is. GF_ERR_PARAM when an id
/// occurs twice in one frame.
GF_API gf_status gf_series_derive_exits(gf_series *s);

// Particles matched by id across frames, and the frames of a time window
// (the motion measurements, the DEM comparison).

/// Id -> index map of one packing: its ids sorted, with their indices.
typedef struct gf_idmap {
    size_t n;
    struct gf_idmap_entry {
        int64_t id;
        size_t idx;
    } *e;
} gf_idmap;

/// Builds the map; GF_ERR_PARAM when an id occurs twice.
GF_API gf_status gf_idmap_build(const gf_packing *pk, gf_idmap *m);
/// Index of `id` in the packing, or SIZE_MAX when it is not there (O(log n)).
GF_API size_t gf_idmap_find(const gf_idmap *m, int64_t id);
GF_API void gf_idmap_free(gf_idmap *m);

/// The frames whose times lie in [t0, t1] (to 1e-9 relative): k0 .. k1-1.
/// Returns the count k1 - k0.
GF_API size_t gf_window_frames(const gf_series *s, double t0, double t1, size_t *k0, size_t *k1);

// ---------------------------------------------------------------------------
// Output: tables (one CSV each) and headline numbers.

#define GF_TABLE_MAXCOL 12
#define GF_TABLE_NAME 48

/// A table of doubles with named columns (names carry their units, e.g.
/// "z_d", "vz_d_per_tau"). Zero-initialise, then gf_table_init.
typedef struct gf_table {
    char name[GF_TABLE_NAME];                  ///< file stem: NAME.csv
    size_t ncol, nrow, cap;
    char cols[GF_TABLE_MAXCOL][GF_TABLE_NAME];
    double *v;                                 ///< row-major, nrow x ncol
} gf_table;

/// `cols`: comma-separated column names.
GF_API gf_status gf_table_init(gf_table *t, const char *name, const char *cols);
GF_API gf_status gf_table_add(gf_table *t, const double *row);
GF_API void gf_table_free(gf_table *t);
/// Writes the table as CSV (header line, then %.10g values), atomically.
GF_API gf_status gf_table_write_csv(const gf_table *t, const char *path);

#define GF_MEASURE_MAXTABLE 6
#define GF_MEASURE_MAXVALUE 12

/// What one measurement produces.
typedef struct gf_measure_out {
    size_t ntables;
    gf_table tables[GF_MEASURE_MAXTABLE];
    size_t nvalues;
    struct {
        char key[GF_TABLE_NAME]; ///< summary.json key, e.g. "flow_rate"
        double value;            ///< NaN when it could not be measured
    } values[GF_MEASURE_MAXVALUE];
    /// gnuplot commands (malloc'd) that draw the measurement's plot from its
    /// CSV files (named TABLE.csv, read from the current directory) onto the
    /// terminal and output the caller has set: axes labelled in d and tau.
    char *gnuplot;
} gf_measure_out;

GF_API gf_status gf_measure_value(gf_measure_out *o, const char *key, double value);
GF_API gf_status gf_measure_gnuplot(gf_measure_out *o, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
GF_API void gf_measure_free(gf_measure_out *o);

// ---------------------------------------------------------------------------
// Options: regions, heights and windows, the papers' values by default.

/// Which frames each v_z(x) profile averages (velocity.window).
typedef enum gf_vel_window {
    GF_VEL_WINDOW_HEIGHT, ///< per height: the pairs of the window where the flow at that height is steady
    GF_VEL_WINDOW_RUN,    ///< every pair of the window (the outflow's steady window), at every height
} gf_vel_window;

typedef struct gf_analysis_opts {
    double t0, t1;            ///< time window for steady-state averages, tau; NaN = auto:
                              ///< from a quarter of the way through the run to its end
    double dump_dt;           ///< tau per TIMESTEP for dumps without ITEM: TIME (0: required)
    // velocity
    double vel_bin;           ///< bin edge of the mean velocity field, d (1)
    double vel_heights[16];   ///< heights of the v_z(x) profiles, d (10, 20, ..., 60)
    size_t vel_nheights;
    double vel_band;          ///< half-thickness of the band around each height, d (1)
    int vel_window;           ///< gf_vel_window: frames of each profile (height)
    double vely_xhalf;        ///< v_z(y) region |x| < this (10)
    double vely_z0, vely_z1;  ///< v_z(y) region in z (50, 70)
    // diffusion
    double diff_xhalf;        ///< particles starting with |x| < this (5)
    double diff_z0;           ///< ... and above this height (60)
    // correlation
    double corr_size;         ///< edge of the square region high in the centre, d (16)
    double corr_zc;           ///< its centre height, d (60)
    // g(r), g3, badness
    double gr_x0, gr_x1, gr_z0, gr_z1; ///< region (-15, 15, 15, 45)
    double gr_rmax, gr_dr;    ///< g(r) range and bin, d (4, 0.02)
    double g3_rcut;           ///< bond length for bond angles, d (1.38)
    // voronoi
    double vor_avg_radius;    ///< averaging radius of the packing-fraction field, d (2.2)
    // density
    double dens_z0, dens_z1;  ///< the slice, d (50, 70)
    // surface
    double surf_dx;           ///< column spacing, d (2.5): x_j = dx j - dx/2, j = 1..10
    size_t surf_ncols;        ///< columns (10)
    // zones (reactor outputs, docs/pebble-bed.md): radii from the axis x = y = 0
    double zone_radii[16];    ///< outer radii of the radial zones, increasing, d; the last zone reaches
                              ///< the wall (none given: four zones of equal area within the wall)
    size_t zone_nradii;       ///< how many radii were given (0: automatic)
    double zone_dr;           ///< radial bin of v_z(r), d (0.5)
    double zone_dz;           ///< height bin of the streamlines, d (2)
    // rtd
    double rtd_tmax;          ///< residence times counted up to this, tau; NaN = auto: the whole run
    /// sub-windows the uncertainties of calibrate and compare are taken over (4): the standard error
    /// of the mean over them (fewer when the window has under 3 frames per part)
    size_t window_parts;
    /// Not an option key: polled in the frame loops of every measurement, of
    /// gf_analyze, gf_dem_analyze, gf_dem_calibrate, gf_dem_flowstats_measure
    /// and gf_dem_compare; once non-zero (a signal handler may set it) they
    /// return GF_ERR_INTERRUPTED. NULL (the default): never.
    volatile sig_atomic_t *stop;
} gf_analysis_opts;

/// The defaults (docs/analysis.md), by value.
GF_API gf_analysis_opts gf_analysis_opts_default(void);
/// The defaults on the heap, for callers that do not lay out the struct (the
/// Python package); NULL when out of memory. Free with gf_analysis_opts_destroy.
GF_API gf_analysis_opts *gf_analysis_opts_create(void);
GF_API void gf_analysis_opts_destroy(gf_analysis_opts *o);
/// *dst = *src.
GF_API gf_status gf_analysis_opts_copy(gf_analysis_opts *dst, const gf_analysis_opts *src);
/// Sets one option from "key=value" (keys in docs/analysis.md). Errors name the key.
GF_API gf_status gf_analysis_opts_set(gf_analysis_opts *o, const char *assignment);
/// The value of option `key` as gf_analysis_opts_set reads it back (e.g. "10,20,30", "auto").
GF_API gf_status gf_analysis_opts_get(const gf_analysis_opts *o, const char *key, char *buf, size_t size);
/// Number of options; option i (0 <= i < count) is named by gf_analysis_opts_key_name.
GF_API size_t gf_analysis_opts_key_count(void);
/// "section.key" of option i.
GF_API gf_status gf_analysis_opts_key_name(size_t i, char *buf, size_t size);
/// One line on option i, or NULL past the end.
GF_API const char *gf_analysis_opts_key_doc(size_t i);
/// Option i's default as gf_analysis_opts_get writes it, or NULL past the end.
GF_API const char *gf_analysis_opts_key_default(size_t i);
/// Checks the options across keys: window.t0 < window.t1 when both are set.
/// GF_ERR_PARAM naming both keys and their values. gf_dem_window and
/// gf_dem_analyze call it (gf_analyze takes a window already resolved, which
/// may be a single snapshot).
GF_API gf_status gf_analysis_opts_check(const gf_analysis_opts *o);
/// The window [t0, t1] resolved against the series (auto -> a quarter in, to the end).
GF_API void gf_analysis_window(const gf_analysis_opts *o, const gf_series *s, double *t0, double *t1);

/// The steady-flow window of a drainage, found from its outflow.
typedef struct gf_steady {
    bool found;        ///< false: no steady part; t0, t1 are the default window
    double t0, t1;     ///< the window, tau
    double rate;       ///< the flow rate fitted over it, particles per tau (NaN when not found)
    char reason[320];  ///< one sentence: which window and why
} gf_steady;

/// The steady part of an outflow curve (count[k] particles exited by time
/// t[k], k < n, times increasing): first the longest stretch where the rate,
/// smoothed over ~100 exits, stays within max(5%, 3 sigma of its noise) of
/// its median; then each edge is the outermost frame whose edge chunk (an
/// eighth of the window) flows at the rate of the rest of the window, within
/// max(0.5%, 2.5 sigma). The start-up (rate ramping up from rest) and the
/// emptying (rate falling) are left out as far as the noise lets them be
/// seen. Too few frames or exits, or no steady part over a fifth of the
/// run: found = false and the default window.
GF_API gf_status gf_steady_window_curve(const double *t, const double *count, size_t n, gf_steady *w);
/// gf_steady_window_curve of a series: the particles exited by each snapshot
/// (n_initial less those present).
GF_API gf_status gf_steady_window(const gf_series *s, gf_steady *w);

// ---------------------------------------------------------------------------
// The measurements. Each fills `out` (zero-initialised by the caller).

GF_API gf_status gf_measure_outflow(const gf_series *s, const gf_analysis_opts *o, gf_measure_out *out);
GF_API gf_status gf_measure_velocity(const gf_series *s, const gf_analysis_opts *o, gf_measure_out *out);
GF_API gf_status gf_measure_diffusion(const gf_series *s, const gf_analysis_opts *o, gf_measure_out *out);
GF_API gf_status gf_measure_correlation(const gf_series *s, const gf_analysis_opts *o, gf_measure_out *out);
GF_API gf_status gf_measure_gr(const gf_series *s, const gf_analysis_opts *o, gf_measure_out *out);
GF_API gf_status gf_measure_voronoi(const gf_series *s, const gf_analysis_opts *o, gf_measure_out *out);
GF_API gf_status gf_measure_density(const gf_series *s, const gf_analysis_opts *o, gf_measure_out *out);
GF_API gf_status gf_measure_surface(const gf_series *s, const gf_analysis_opts *o, gf_measure_out *out);
GF_API gf_status gf_measure_badness(const gf_series *s, const gf_analysis_opts *o, gf_measure_out *out);
GF_API gf_status gf_measure_rtd(const gf_series *s, const gf_analysis_opts *o, gf_measure_out *out);
GF_API gf_status gf_measure_zones(const gf_series *s, const gf_analysis_opts *o, gf_measure_out *out);

/// Whether the velocity profiles of a run in `cfg`'s container are radial,
/// v_z(r) about the axis (a cylinder), rather than v_z(x) across the width
/// (the box, the wedge): the container's profile coordinate.
GF_API bool gf_velocity_radial(const gf_config *cfg);
/// The name of those profiles in labels, tables and notes: "v_z(r)" or "v_z(x)".
GF_API const char *gf_velocity_profile_name(const gf_config *cfg);

/// A measurement by name ("outflow", "velocity", ...), in the order above.
typedef struct gf_measure_def {
    const char *name;
    const char *what; ///< one line for --help
    gf_status (*run)(const gf_series *, const gf_analysis_opts *, gf_measure_out *);
} gf_measure_def;
GF_API const gf_measure_def *gf_measures(size_t *n);

/// Runs the named measurement (NULL: all) on the series and writes into
/// `outdir`: NAME.csv for each table, NAME.png (gnuplot, when `plots`), and
/// merges the headline numbers into outdir/summary.json.
GF_API gf_status gf_analyze(const gf_series *s, const gf_analysis_opts *o, const char *name,
                            const char *outdir, bool plots);

// ---------------------------------------------------------------------------
// Building blocks, public for tests and for calibration (SPEC 1.7).

/// Least squares y = a x + b. Returns GF_ERR_PARAM with fewer than 2 distinct x.
GF_API gf_status gf_fit_linear(const double *x, const double *y, size_t n, double *a, double *b);
/// y = A exp(-(x - mu)^2 / (2 var)) (+ nothing): Levenberg-Marquardt from moments.
GF_API gf_status gf_fit_gaussian(const double *x, const double *y, size_t n, double *amp,
                                 double *mu, double *var);
/// y = a exp(-x / beta).
GF_API gf_status gf_fit_exponential(const double *x, const double *y, size_t n, double *a,
                                    double *beta);

/// Packing badness B = (1/p) sum_i sum_{j != i} delta_ij^2 over the particles
/// i whose centres lie in the box [lo, hi] (2009 paper Sec. 5; delta_ij the
/// overlap r_i + r_j - |x_i - x_j| when positive; p = their number).
GF_API double gf_badness(const gf_packing *pk, const double lo[3], const double hi[3]);

/// Local packing fraction of every particle: its volume over its Voronoi cell
/// volume, cells cut by the walls x = +-W/2, y = +-D/2, z = 0 (and an open
/// top at z = ztop). Particles outside the box get NaN. `phi` has pk->n entries.
GF_API gf_status gf_voronoi_fraction(const gf_packing *pk, double width, double depth, double ztop,
                                     double *phi);
/// The averaged packing-fraction field of the 2009 paper's Fig. 4, per
/// particle: the total volume of the bulk particles within `radius` d of it
/// (itself included when it is bulk) over the total volume of their Voronoi
/// cells, the `phi_avg` column of gf_measure_voronoi (same cells, same bulk).
/// Cells are cut as in gf_voronoi_fraction, the top at `ztop` (NaN: the
/// highest centre with z >= 0, plus 1 d, as gf_measure_voronoi does). Bulk
/// particles: those whose centre lies more than 1.5 d below the local free
/// surface (the highest centre within ~2 d horizontally) and whose cell does
/// not reach the top. NaN for a particle outside the box or with
/// no bulk particle within `radius` (a surface particle gets the value of the
/// bulk near it). `phi_avg` has pk->n entries. GF_ERR_PARAM when width, depth
/// or ztop (unless NaN) is not a finite positive number, or radius is not a
/// finite number >= 0.
GF_API gf_status gf_voronoi_field(const gf_packing *pk, double width, double depth, double ztop,
                                  double radius, double *phi_avg);
/// Volume of every Voronoi cell (same walls), for tests; NaN outside.
GF_API gf_status gf_voronoi_volumes(const gf_packing *pk, double width, double depth, double ztop,
                                    double *vol);

#ifdef __cplusplus
}
#endif

#endif
