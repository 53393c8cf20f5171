// SPDX-License-Identifier: MIT
// granflow configuration: every key of the INI file as a plain field, with
// defaults equal to the papers' silo (SPEC 1.1-1.4). Units: d and tau.
#ifndef GRANFLOW_CONFIG_H
#define GRANFLOW_CONFIG_H

#include <stdint.h>
#include <stdio.h>

#include "granflow/core.h"

#ifdef __cplusplus
extern "C" {
#endif

/// Shape of the hole in the base.
typedef enum gf_orifice_shape {
    GF_ORIFICE_CIRCLE = 0, ///< disc of diameter orifice_diameter centred at (0, 0)
    GF_ORIFICE_SLIT = 1,   ///< |x| < orifice_diameter/2, all y
} gf_orifice_shape;

/// Where the ball of a spot step is centred (thesis Sec. 3.4).
typedef enum gf_ball_centre {
    GF_BALL_MIDPOINT = 0, ///< s + v/2 (Stratonovich; the papers' choice)
    GF_BALL_END = 1,      ///< s + v (Ito)
} gf_ball_centre;

#define GF_PATH_MAX 1024

/// The whole configuration. Make it with gf_config_default(), then change
/// fields, load files (gf_config_load) or apply `section.key=value` strings
/// (gf_config_set); call gf_config_validate() before use.
typedef struct gf_config {
    // [container] walls at x = +-width/2, y = +-depth/2, base z = 0
    double container_width;            ///< width (x), d; default 50
    double container_depth;            ///< depth (y), d; default 8
    gf_orifice_shape orifice_shape;    ///< circle (default) or slit
    double orifice_diameter;           ///< diameter (circle) or full width (slit), d; default 8
    double exit_z;                     ///< particles whose centre falls below this leave, d; default 0

    // [packing]
    int64_t packing_particles;         ///< number of spheres to generate; default 55000
    double packing_fill_height;        ///< if > 0: generate enough to fill to this height instead, d
    char packing_file[GF_PATH_MAX];    ///< import this packing instead of generating (LAMMPS dump, .xyz, .csv)
    double packing_layer_thickness;    ///< thickness of the colour bands tagging initial layers, d; default 10

    // [spot] the five fitted parameters and the walk (2009 paper Fig. 2)
    double spot_radius;                ///< r_s, d; default 2.6
    double spot_w;                     ///< spot/particle displacement ratio w; default 399
    double spot_insertion_rate;        ///< lambda, spots per tau; default 375
    double spot_move_rate;             ///< mu, moves per spot per tau; default 28
    double spot_step_xy;               ///< dx = dy, d; default 0.676
    double spot_step_z;                ///< dz, d; default 0.1
    double spot_wall_distance;         ///< d_w: closest approach of a spot centre to a side wall, d; default 1
    gf_ball_centre spot_ball_centre;   ///< midpoint (default) or end
    double spot_insertion_margin;      ///< spots are born at least this far inside the orifice edge; default r_s

    // [relax] elastic relaxation (SPEC 1.3)
    double relax_alpha;                ///< fraction of an overlap removed per relaxation; default 0.8
    double relax_radius;               ///< r_e, d; default r_s + 1

    // [run]
    double run_duration;               ///< simulated time to reach, tau; default 60
    uint64_t run_seed;                 ///< seed of every random stream; default 1
    double run_checkpoint_interval;    ///< checkpoint every this many tau (0: only on stop/end); default 0
    int64_t run_reorder_interval;      ///< events between full re-sorts of particle memory; default 1000000

    // [output]
    double output_snapshot_interval;   ///< snapshot every this many tau; default 2

    uint32_t cookie_; ///< private: marks a config made by gf_config_default()
} gf_config;

/// The papers' silo (55,000 particles, 50 x 8 container, orifice 8, Fig. 2 parameters).
GF_API gf_config gf_config_default(void);

/// Reads an INI file over `cfg`. Unknown sections/keys, malformed numbers and
/// out-of-range values fail with GF_ERR_PARAM (or GF_ERR_IO) and a message
/// naming the file, line and key; `cfg` may then be partly updated.
GF_API gf_status gf_config_load(gf_config *cfg, const char *path);

/// Applies one `section.key=value` assignment; `origin` names where it came
/// from in error messages (e.g. "--set").
GF_API gf_status gf_config_set(gf_config *cfg, const char *assignment, const char *origin);

/// Resolves derived defaults (relax.radius = spot.radius + 1, insertion margin
/// = spot.radius) and checks cross-key constraints.
GF_API gf_status gf_config_validate(gf_config *cfg);

/// Writes the configuration as a valid INI file that gf_config_load reads back
/// to the same values (numbers printed with round-trip precision).
GF_API gf_status gf_config_write(const gf_config *cfg, FILE *out);

/// Writes the configuration to `path` atomically (temporary file + rename).
GF_API gf_status gf_config_save(const gf_config *cfg, const char *path);

#ifdef __cplusplus
}
#endif
#endif
