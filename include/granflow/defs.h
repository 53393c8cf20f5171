// SPDX-License-Identifier: MIT
// Each module's small defs (issue 24): plain data built once from a validated
// gf_config by config/ (src/config/defs.c), the only place that reads the
// config's fields. A module takes its defs (the container, the spot engine,
// a run directory, the DEM input, the LGA) and reads nothing else; every
// derived value (r_e, the insertion radius, the thread count, the exit plane)
// is worked out here once. Field names carry no section prefix, so
// tests/check_layers.sh can tell a defs read from a gf_config read.
#ifndef GRANFLOW_DEFS_H
#define GRANFLOW_DEFS_H

#include "granflow/config.h"

#ifdef __cplusplus
extern "C" {
#endif

/// The container (container.*): what gf_container_make and the shapes read.
typedef struct gf_container_defs {
    gf_container_shape shape;
    double width, depth;              ///< bounding box (a mesh's, once validated), d
    struct {
        gf_orifice_shape shape;
        double diameter, x, y;        ///< container.orifice_diameter, orifice_x, orifice_y
    } orifice;
    double exit_level;                ///< container.exit_z
    double exit_plane;                ///< where particles leave: exit_level less a pipe or chute (gf_config_exit_plane)
    double radius;                    ///< cylinder wall
    double angle;                     ///< container.hopper_angle, degrees
    struct {
        double diameter, length;      ///< container.outlet_diameter, outlet_length
    } outlet;
    double column_radius;             ///< container.inner_radius
    char mesh[GF_PATH_MAX];           ///< container.mesh
    double mesh_scale, mesh_resolution;
} gf_container_defs;

/// The spot engine (spot.*, relax.*, run.*, parallel.*, output.snapshot_interval).
typedef struct gf_engine_defs {
    // spot
    double radius;                    ///< r_s
    double w, insertion_rate, move_rate, step_xy, step_z, wall_distance;
    gf_ball_centre ball_centre;
    double insertion_margin;          ///< resolved: auto = r_s
    double insertion_radius;          ///< spots are born on a disc of this radius: max(0, orifice/2 - margin)
    double birth_z;                   ///< and this high: the exit plane less r_s (SPEC 1.3 mass balance)
    double bias_exponent;
    bool weighting;
    double weighting_min_count, weighting_zmin, weighting_bulk_count;
    gf_spot_walls walls;
    gf_flow_rule flow_rule;           ///< spot.flow_rule: diffusive, or sfr along the stress field's slip lines
    gf_sfr_rise sfr_rise;             ///< spot.sfr_rise: slip, or steady (up by step_z every step)
    // relax
    double alpha;
    double r_e;                       ///< resolved: auto = r_s + 1
    gf_relax_method method;
    double k;
    // run
    double duration;
    uint64_t seed;
    double checkpoint_interval, stall_time;
    int64_t reorder_interval;
    gf_run_mode mode;
    gf_run_order order;
    int threads;                      ///< resolved: run.threads, or every core (gf_cpu_count) for 0
    bool threads_auto;                ///< run.threads = 0 (an MPI rank shares the cores with its neighbours)
    bool spatial;                     ///< a parallel fixed step: mode fixed, order spatial or domains
    bool recirculate;
    int64_t max_passes;
    gf_reinsert reinsert;
    double reinsert_rmin, reinsert_rmax;
    // parallel
    double window, domain_size;
    int64_t sectors;
    int cut; ///< bits 1 << axis: the axes run.order = domains may cut
    int64_t sweeps; ///< run.order = sweep: relaxation sweeps per window
    // output
    double snapshot_interval;
} gf_engine_defs;

/// A packing to make or import (packing.*, dump.*, run.seed).
typedef struct gf_packing_defs {
    int64_t particles;
    double fill_height;
    char file[GF_PATH_MAX];
    double layer_thickness;
    char types[GF_PATH_MAX];
    double radius2, fraction2;
    double unit_diameter, unit_gravity; ///< dump.diameter, dump.gravity
    uint64_t seed;
} gf_packing_defs;

/// A run directory (output.*, and the run.* keys it reports or stops on).
typedef struct gf_rundir_defs {
    double duration, stall_time, snapshot_interval;
    uint64_t seed;
    bool recirculate;
    gf_output_format format;
    gf_vtk_encoding vtk_encoding;
    char packing[GF_PATH_MAX];        ///< packing.file ("": generated)
    double unit_diameter;             ///< dump.diameter
    double exit_level;                ///< container.exit_z
} gf_rundir_defs;

/// The LAMMPS inputs of `granflow dem` (dem.*, and what the fill and drainage read).
typedef struct gf_dem_defs {
    double friction, kn, kt, gamman, gammat; ///< kt, gammat resolved (auto: 2/7 kn, gamman / 2)
    double timestep;
    gf_dem_fill fill;
    double settle_time, settle_ke;
    int64_t mpi_ranks;
    double restart_interval;            ///< tau between the drain's restart files (0: none)
    double duration, snapshot_interval;
    int64_t particles;
    double fill_height;
    uint64_t seed;
} gf_dem_defs;

/// The lattice-gas automaton (lga.*, run.seed).
typedef struct gf_lga_defs {
    gf_lga_scenario scenario;
    gf_lga_flow flow;
    double p, q, g, h, k, b;
    int64_t iterations, width, height, particles;
    double feed_rate;
    double angle;                     ///< lga.hopper_angle, NaN = auto (gf_lga_hopper_angle resolves it by the flow)
    double outlet_width;
    int64_t snapshot_interval;
    uint64_t seed;
} gf_lga_defs;

/// The spot parameters a calibration fits (spot.*, relax.radius).
typedef struct gf_spot_params {
    double radius, w, insertion_rate, move_rate, step_xy, step_z, wall_distance, insertion_margin, r_e;
} gf_spot_params;

/// Builders: cfg validated (gf_config_validate) unless said otherwise.
GF_API void gf_config_container_defs(const gf_config *cfg, gf_container_defs *d);
GF_API void gf_config_engine_defs(const gf_config *cfg, gf_engine_defs *d);
GF_API void gf_config_packing_defs(const gf_config *cfg, gf_packing_defs *d);
GF_API void gf_config_rundir_defs(const gf_config *cfg, gf_rundir_defs *d);
GF_API void gf_config_dem_defs(const gf_config *cfg, gf_dem_defs *d);
GF_API void gf_config_lga_defs(const gf_config *cfg, gf_lga_defs *d);
GF_API void gf_config_spot_params(const gf_config *cfg, gf_spot_params *d);

/// Typed setters for code that edits a config (calibration, checkpoints,
/// the mesh's extent): they change the fields and nothing else.
/// The fitted spot parameters; insertion margin and r_e back to auto.
GF_API void gf_config_set_spot_fit(gf_config *cfg, double radius, double w, double insertion_rate, double move_rate,
                                   double step_xy);
/// run.threads (0: every core).
GF_API void gf_config_set_threads(gf_config *cfg, int64_t threads);
/// The bounding box a mesh container was measured to have.
GF_API void gf_config_set_extent(gf_config *cfg, double width, double depth);
/// The outlet a shape's check settles (a cylinder's circle of
/// container.outlet_diameter, a wedge's slit): container.orifice_shape and
/// orifice_diameter, not marked as set.
GF_API void gf_config_set_orifice(gf_config *cfg, gf_orifice_shape shape, double diameter);
/// container.mesh, as written (no path resolution; a run's copy, a digest's name).
GF_API void gf_config_set_mesh_path(gf_config *cfg, const char *path);
/// Back to their defaults the run.* keys a resumed run may change (duration,
/// checkpoint interval, stall time, threads): what is left is its physics.
GF_API void gf_config_reset_run_keys(gf_config *cfg);
/// dump.diameter and dump.gravity.
GF_API void gf_config_set_dump_units(gf_config *cfg, double diameter, double gravity);

#ifdef __cplusplus
}
#endif
#endif
