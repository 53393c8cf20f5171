// SPDX-License-Identifier: MIT
// granflow configuration: every key of the INI file as a plain field, with
// defaults equal to the papers' silo (SPEC 1.1-1.4). Units: d and tau.
#ifndef GRANFLOW_CONFIG_H
#define GRANFLOW_CONFIG_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "granflow/core.h"

#ifdef __cplusplus
extern "C" {
#endif

/// Shape of the hole in the base.
typedef enum gf_orifice_shape {
    GF_ORIFICE_CIRCLE = 0, ///< disc of diameter orifice_diameter centred at (orifice_x, orifice_y)
    GF_ORIFICE_SLIT = 1,   ///< |x - orifice_x| < orifice_diameter/2, all y
} gf_orifice_shape;

/// The container's shape (docs/geometry.md).
typedef enum gf_container_shape {
    GF_SHAPE_BOX = 0,      ///< walls at x = +-width/2, y = +-depth/2, flat base z = 0 with an orifice
    GF_SHAPE_CYLINDER = 1, ///< wall at radius `radius` about the z axis, optional conical funnel, outlet pipe, inner column
    GF_SHAPE_WEDGE = 2,    ///< plane-flow hopper: walls at y = +-depth/2, two walls inclined at hopper_angle down to a slit, chute
    GF_SHAPE_MESH = 3,     ///< walls from an STL file (container.mesh), the outlet the orifice keys' on the plane exit_z
} gf_container_shape;

/// Where the ball of a spot step is centred (thesis Sec. 3.4).
typedef enum gf_ball_centre {
    GF_BALL_MIDPOINT = 0, ///< s + v/2 (Stratonovich; the papers' choice)
    GF_BALL_END = 1,      ///< s + v (Ito)
} gf_ball_centre;

/// How time advances (2009 paper Sec. 2.1; SPEC 1.4).
typedef enum gf_run_mode {
    GF_MODE_EVENT = 0, ///< Gillespie events: one spot move or insertion at a time (the default)
    GF_MODE_FIXED = 1, ///< steps of dt = 1/mu: Poisson(lambda/mu) insertions, then every spot moves once
} gf_run_mode;

/// Order of the spot moves within a fixed step.
typedef enum gf_run_order {
    GF_ORDER_RANDOM = 0, ///< a fresh random permutation every step (method a)
    GF_ORDER_NEWEST = 1, ///< newest spots first (method b)
    GF_ORDER_SPATIAL = 2, ///< slab by slab in a fixed colouring, slabs of one colour in parallel (run.threads)
    GF_ORDER_DOMAINS = 3, ///< domains of sectors, each sector's spots moved at their own rate for a window of time (2009 paper Sec. 2.1)
    GF_ORDER_SWEEP = 4,   ///< windows: every spot's moves from the window's start, summed displacements, Jacobi relaxation sweeps
} gf_run_order;

/// What a spot does at a side wall (2009 paper Sec. 4).
typedef enum gf_spot_walls {
    GF_WALLS_TRUNCATE = 0, ///< the walk is truncated spot.wall_distance from the wall
    GF_WALLS_REFLECT = 1,  ///< d_w = 0 and the ball's part beyond a wall is reflected back
} gf_spot_walls;

/// How a spot chooses its step (issue 28; docs/stress.md).
typedef enum gf_flow_rule {
    GF_FLOW_DIFFUSIVE = 0, ///< the papers' walk: up by step_z, across by +-step_xy (the default)
    GF_FLOW_SFR = 1,       ///< Kamrin and Bazant's stochastic flow rule: along the slip lines of the stress field
} gf_flow_rule;

/// How an sfr spot rises (docs/stress.md, "The rise").
typedef enum gf_sfr_rise {
    GF_RISE_SLIP = 0,   ///< the whole slip-line step, up or down
    GF_RISE_STEADY = 1, ///< up by step_z every step, sideways by the slip-line step's horizontal part (the default)
} gf_sfr_rise;

/// The parameters of the limit-state stress solver (src/stress/; docs/stress.md),
/// made from the [stress] keys by gf_config_stress_def.
typedef struct gf_stress_def {
    double friction_angle;      ///< internal friction angle phi, degrees, in (0, 60)
    double wall_friction_angle; ///< wall friction angle phi_w, degrees, in [0, phi]
    double spacing;             ///< grid spacing, d, > 0
} gf_stress_def;

/// How often relax() runs (2009 paper Sec. 5; SPEC 1.5).
typedef enum gf_relax_method {
    GF_RELAX_FULL = 0,    ///< after every spot move
    GF_RELAX_NONE = 1,    ///< never
    GF_RELAX_RANDOM = 2,  ///< method 1: after a move with probability 1/k
    GF_RELAX_COUNTER = 3, ///< method 2: each spot relaxes on every k-th of its own moves
    GF_RELAX_GLOBAL = 4,  ///< method 3: the whole packing every k/mu
} gf_relax_method;

/// Which of the LGA paper's three problems `granflow lga` sets up (Sec. 3).
typedef enum gf_lga_scenario {
    GF_LGA_PILE = 0,    ///< a heap on a floor from particles added at the top (Sec. 3.1)
    GF_LGA_CHANNEL = 1, ///< a vertical channel, periodic top and bottom (Sec. 3.2)
    GF_LGA_SILO = 2,    ///< a parallel silo over a converging hopper, run until empty (Sec. 3.3)
} gf_lga_scenario;

/// The LGA silo's flow type: picks the default hopper angle.
typedef enum gf_lga_flow {
    GF_LGA_MASS = 0,   ///< steep hopper: the whole fill moves (Fig. 7a)
    GF_LGA_FUNNEL = 1, ///< shallow hopper: a central channel, stagnant zones at the walls (Fig. 7b)
} gf_lga_flow;

/// How `granflow dem` fills the container before the drainage (SPEC 1.8).
typedef enum gf_dem_fill {
    GF_DEM_POUR = 0,     ///< LAMMPS fix pour: particles rain in from above the fill height (the thesis' way)
    GF_DEM_GENERATE = 1, ///< granflow's packing (packing.file, else the generator), settled under gravity by LAMMPS
} gf_dem_fill;

/// Where a recirculated particle is put back on the free surface (run.reinsert).
typedef enum gf_reinsert {
    GF_REINSERT_RANDOM = 0, ///< uniformly over the whole cross-section
    GF_REINSERT_ZONE = 1,   ///< uniformly over the annulus run.reinsert_rmin <= r < run.reinsert_rmax
} gf_reinsert;

/// What a run writes at each snapshot (output.format, a list such as
/// `dump,vtk`): a bit set, one bit per format; at least one is set.
typedef enum gf_output_format {
    GF_OUTPUT_DUMP = 1 << 0, ///< LAMMPS text dumps (snapshots/snap_NNNNNN.dump)
    GF_OUTPUT_VTK = 1 << 1,  ///< VTK XML unstructured grids (snapshots/snap_NNNNNN.vtu)
    GF_OUTPUT_BOTH = GF_OUTPUT_DUMP | GF_OUTPUT_VTK, ///< both (output.format = both, or dump,vtk)
} gf_output_format;

/// How the VTK XML files of a run store their arrays (output.vtk_encoding).
typedef enum gf_vtk_encoding {
    GF_VTK_BINARY = 0, ///< zlib-compressed, raw appended (default)
    GF_VTK_ASCII = 1,  ///< inline text
} gf_vtk_encoding;

#define GF_PATH_MAX 1024
/// Room for this many keys in a gf_config's record of where each was set.
#define GF_CONFIG_MAX_KEYS 128
/// Distinct origins (files, "--set", ...) a gf_config remembers.
#define GF_CONFIG_MAX_ORIGINS 8

/// The whole configuration. Make it with gf_config_default(), then change
/// fields, load files (gf_config_load) or apply `section.key=value` strings
/// (gf_config_set); call gf_config_validate() before use.
typedef struct gf_config {
    // [container] walls at x = +-width/2, y = +-depth/2, base z = 0
    double container_width;            ///< width (x), d; default 50
    double container_depth;            ///< depth (y), d; default 8
    gf_orifice_shape orifice_shape;    ///< circle (default) or slit
    double orifice_diameter;           ///< diameter (circle) or full width (slit), d; default 8
    double orifice_x;                  ///< x of the orifice centre (circle) or mid-line (slit), d; default 0
    double orifice_y;                  ///< y of the orifice centre (circle only), d; default 0
    double exit_z;                     ///< particles whose centre falls below this leave, d; default 0
    gf_container_shape container_shape; ///< box (default), cylinder or wedge
    double container_radius;           ///< cylinder: radius of the wall, d; default 12.5
    double hopper_angle;               ///< cylinder, wedge: funnel (wall) angle to the horizontal, degrees; 0 = flat base (default)
    double outlet_diameter;            ///< cylinder: diameter of the outlet (and pipe), d; default 8
    double outlet_length;              ///< cylinder, wedge: length of the straight pipe (chute) below z = 0, d; default 0
    double inner_radius;               ///< cylinder: radius of a solid central column (0: none, default), d
    char container_mesh[GF_PATH_MAX];  ///< mesh: the STL file (relative to the INI file that names it)
    double container_mesh_scale;       ///< mesh: the file's coordinates times this are in d; default 1
    double container_mesh_resolution;  ///< mesh: spacing of the signed distance field's grid, d; default 0.5

    // [packing]
    int64_t packing_particles;         ///< number of spheres to generate; default 55000
    double packing_fill_height;        ///< if > 0: generate enough to fill to this height instead, d
    char packing_file[GF_PATH_MAX];    ///< import this packing instead of generating (LAMMPS dump, .xyz, .csv)
    double packing_layer_thickness;    ///< thickness of the colour bands tagging initial layers, d; default 10
    char packing_types[GF_PATH_MAX];   ///< atom types to import from a LAMMPS dump, "1,3" (empty: all)
    double packing_radius2;            ///< radius of the second species of a generated packing, d; default 0.5
    double packing_fraction2;          ///< number fraction of the second species; default 0 (monodisperse)

    // [dump] the units of the dumps granflow reads but did not write (packing.file, DEM runs)
    double dump_diameter;              ///< the particle diameter in their length unit; default 1 (they are in d)
    double dump_gravity;               ///< gravity in their units; default 1 (times in tau = sqrt(diameter / gravity))

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
    double spot_bias_exponent;         ///< beta of the biased walk (Sec. 3); 0 = unbiased (default)
    int spot_weighting;                ///< influence weighting on/off (Sec. 3); default off
    double spot_weighting_min_count;   ///< p below this counts as this many; default 20
    double spot_weighting_zmin;        ///< no weighting for balls centred below this height, d; default 30
    double spot_weighting_bulk_count;  ///< p_bulk, the bulk population of a ball; default 81.7
    gf_spot_walls spot_walls;          ///< truncate (default) or reflect
    gf_flow_rule spot_flow_rule;       ///< diffusive (default) or sfr (issue 28)
    gf_sfr_rise spot_sfr_rise;         ///< sfr: slip (default) or steady

    // [stress] the limit-state stress field the sfr walk follows (docs/stress.md)
    double stress_friction_angle;      ///< internal friction angle phi, degrees; default 30
    double stress_wall_friction_angle; ///< wall friction angle phi_w, degrees; default 20
    double stress_spacing;             ///< grid spacing, d; default 1

    // [relax] elastic relaxation (SPEC 1.3)
    double relax_alpha;                ///< fraction of an overlap removed per relaxation; default 0.8
    double relax_radius;               ///< r_e, d; default r_s + 1
    gf_relax_method relax_method;      ///< full (default), none, random, counter, global
    double relax_k;                    ///< the reduction factor k of the infrequent methods; default 10

    // [run]
    double run_duration;               ///< simulated time to reach, tau; default 60
    uint64_t run_seed;                 ///< seed of every random stream; default 1
    double run_checkpoint_interval;    ///< checkpoint every this many tau (0: only on stop/end); default 10
    double run_stall_time;             ///< stop when nothing has left for this long (0: never); default 10
    int64_t run_reorder_interval;      ///< events between full re-sorts of particle memory; default 1000000
    gf_run_mode run_mode;              ///< event (default) or fixed
    gf_run_order run_order;            ///< fixed mode: random (default), newest first, or spatial (parallel)
    int64_t run_threads;               ///< threads of the spatial fixed step; 0 (default): every core
    int run_recirculate;               ///< put exited particles back on the free surface (on/off); default off
    int64_t run_max_passes;            ///< recirculation: a particle leaves for good after this many passes; 0 (default): never
    gf_reinsert run_reinsert;          ///< recirculation: random (default) or zone
    double run_reinsert_rmin;          ///< zone re-insertion: inner radius from the axis x = y = 0, d; default 0
    double run_reinsert_rmax;          ///< zone re-insertion: outer radius, d; NaN = auto (to the wall)

    // [parallel] the domain engine (run.order = domains)
    double parallel_window;            ///< simulated time each sector runs per cycle, tau; default 0.1
    double parallel_domain_size;       ///< domain edge along a cut axis, d; 0 (default): the smallest that keeps sectors independent
    int parallel_cut;                  ///< bits 1 << axis of the axes cut into domains (x, y, z; default all)
    int64_t parallel_sectors;          ///< sectors per cut axis (2 as in SPPARKS, up to 4); default 2
    int64_t parallel_sweeps;           ///< run.order = sweep: Jacobi relaxation sweeps per window; default 2

    // [output]
    double output_snapshot_interval;   ///< snapshot every this many tau; default 2
    gf_output_format output_format;    ///< bits of GF_OUTPUT_*: dump (default), vtk or both
    gf_vtk_encoding output_vtk_encoding; ///< binary (default) or ascii

    // [lga] the 2D lattice-gas automaton (Kozicki & Tejchman 2005; SPEC 2). Lattice units:
    // nearest-neighbour distance 1 (one particle diameter), time in iterations.
    gf_lga_scenario lga_scenario;      ///< pile, channel or silo (default)
    gf_lga_flow lga_silo_flow;         ///< silo: mass (default, steep hopper) or funnel (shallow hopper)
    double lga_p;                      ///< collision parameter p (particles brought to rest); default 0.2
    double lga_q;                      ///< collision parameter q (particles sent in random directions); default 0.2
    double lga_g;                      ///< gravity g: probability of adding v4 (down) per collision; default 0.2
    double lga_h;                      ///< gravity h: probability a resting particle drops to an empty site below; default 0.05
    double lga_k;                      ///< friction k: probability the outgoing momentum is made horizontal; default 0.05
    double lga_b;                      ///< wall roughness b: probability a particle hitting a wall stops; default 0.05
    int64_t lga_iterations;            ///< iterations to run; 0 (default): the scenario's own end
    int64_t lga_width;                 ///< lattice columns (silo: of the parallel part); 0 (default): the scenario's
    int64_t lga_height;                ///< lattice rows (silo: of the parallel part); 0 (default): the scenario's
    int64_t lga_particles;             ///< particles (pile: to add; channel: initial; silo: fill); 0 (default): the scenario's
    double lga_feed_rate;              ///< pile: particles added per iteration at the top; default 8
    double lga_hopper_angle;           ///< silo: hopper wall angle from the vertical, degrees; NaN = auto (by silo_flow)
    double lga_outlet_width;           ///< silo: outlet width, d; default 16
    int64_t lga_snapshot_interval;     ///< density map every this many iterations; default 60

    // [dem] the LAMMPS run of `granflow dem` (SPEC 1.8): units lj, d = m = g = 1
    double dem_friction;               ///< Coulomb friction of particle-particle and particle-wall contacts; default 0.5
    double dem_kn;                     ///< Hertzian normal stiffness k_n, m g / d; default 2e5
    double dem_kt;                     ///< tangential stiffness k_t, m g / d; NaN = auto (2/7 k_n)
    double dem_gamman;                 ///< normal damping gamma_n, 1/tau; default 50
    double dem_gammat;                 ///< tangential damping gamma_t, 1/tau; NaN = auto (gamma_n / 2)
    double dem_timestep;               ///< integration step, tau; default 1e-4
    gf_dem_fill dem_fill_method;       ///< pour (default) or generate
    double dem_settle_time;            ///< longest settling after the fill, tau; default 20
    double dem_settle_ke;              ///< settling ends when the kinetic energy per particle falls below this, m g d; default 1e-6
    int64_t dem_mpi_ranks;             ///< MPI ranks for --run (mpirun -np N); 0 (default): one per core
    double dem_restart_interval;       ///< tau between the drain's restart files (drain.a/b.restart); 0: none; default 2

    uint32_t cookie_; ///< private: marks a config made by gf_config_default()
    // private: where each key got its value (read with gf_config_where)
    int32_t where_line_[GF_CONFIG_MAX_KEYS];                ///< private: line in the origin file, 0: none
    uint8_t where_origin_[GF_CONFIG_MAX_KEYS];              ///< private: 0 default, i: where_names_[i - 1]
    char where_names_[GF_CONFIG_MAX_ORIGINS][GF_PATH_MAX];  ///< private: the origins' names
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

/// The stress solver's parameters from cfg's [stress] keys (the one place that reads them).
GF_API gf_stress_def gf_config_stress_def(const gf_config *cfg);

/// Resolves derived defaults (relax.radius = spot.radius + 1, insertion margin
/// = spot.radius) and checks cross-key constraints. A message starts with where
/// the offending key was set and quotes where the others were, e.g.
/// "silo.ini:12: container.orifice_diameter = 60 must be less than
/// container.width = 50 (silo.ini:11)".
GF_API gf_status gf_config_validate(gf_config *cfg);

/// Where key `key` ("section.name") got its value, into `buf`: "FILE:LINE" for
/// an INI file, the origin of gf_config_set ("--set"), "gf_config_set_key",
/// or "default". GF_ERR_PARAM for an unknown key.
GF_API gf_status gf_config_where(const gf_config *cfg, const char *key, char *buf, size_t size);
/// The start of an error message about `key`: "WHERE: " (as gf_config_where
/// says) when the key was set, "" when it is at its default (or unknown).
/// Writes into `buf` and returns it.
GF_API const char *gf_config_where_lead(const gf_config *cfg, const char *key, char *buf, size_t size);
/// True when `key` was set by a file or an assignment (not left at its default).
GF_API bool gf_config_is_set(const gf_config *cfg, const char *key);

/// True when keys `a` and `b` ("section.name") were set by the same origin
/// (one file, or both by "--set"); false when either is at its default.
GF_API bool gf_config_same_origin(const gf_config *cfg, const char *a, const char *b);

/// The parts of a validation message about one or two keys (what the
/// shapes' checks, src/geom/, word theirs with): `lead` is "WHERE: " of the
/// first key not at its default (else ""), `key[i]` is "section.name =
/// value" followed by " (WHERE)" unless that is the lead's place.
typedef struct gf_config_msg {
    char lead[GF_PATH_MAX + 40]; ///< room for a "where" (GF_PATH_MAX + 32) and ": "
    char key[2][GF_PATH_MAX + 128];
} gf_config_msg;

/// Fills `m` for keys `a` and `b` ("section.name"; `b` may be NULL).
GF_API void gf_config_msg_make(gf_config_msg *m, const gf_config *cfg, const char *a, const char *b);

/// Most atom types `packing.types` may list.
#define GF_PACKING_MAXTYPES 16

/// Parses a `packing.types` list: integers >= 1 separated by commas and/or
/// spaces, e.g. "1" or "1, 3". Empty text (or only spaces) means every type:
/// *n = 0. GF_ERR_PARAM naming the bad item, or when more than `max` are given.
GF_API gf_status gf_packing_types_parse(const char *text, int32_t *types, size_t max, size_t *n);
/// Height below which a particle centre has left the container, d: exit_z,
/// less the outlet pipe's length for a cylinder (particles leave at its end).
GF_API double gf_config_exit_plane(const gf_config *cfg);

/// Writes the configuration as a valid INI file that gf_config_load reads back
/// to the same values (numbers printed with round-trip precision).
GF_API gf_status gf_config_write(const gf_config *cfg, FILE *out);
/// GF_OK when gf_config_write can write `cfg` so that it reads back the same;
/// GF_ERR_PARAM naming the key and where it was set otherwise (a path with a
/// line break, white space at an end, " ;" inside, or too long for one INI
/// line). A run checks this before it creates its directory (config.ini).
GF_API gf_status gf_config_check_writable(const gf_config *cfg);

// ---- by name: what bindings use (no dependence on the struct's layout) -----

/// A heap config holding the defaults (gf_config_default), or NULL (out of memory).
GF_API gf_config *gf_config_create(void);
/// Frees a config from gf_config_create (NULL is fine).
GF_API void gf_config_destroy(gf_config *cfg);
/// Copies every key of `src` into `dst`.
GF_API gf_status gf_config_copy(gf_config *dst, const gf_config *src);

/// Sets key `key` ("section.name", e.g. "spot.radius") from its INI text
/// ("2.6", "slit", "auto", a path); the value is checked exactly as in a file.
GF_API gf_status gf_config_set_key(gf_config *cfg, const char *key, const char *value);

/// Writes the value of `key` as the INI file spells it (round-trip number,
/// enum name, `auto`, path) into `buf` of `size` bytes (GF_PATH_MAX + 64 is
/// always enough). GF_ERR_PARAM for an unknown key or a short buffer.
GF_API gf_status gf_config_get_key(const gf_config *cfg, const char *key, char *buf, size_t size);

/// Number of keys; key i (0 <= i < count, file order) is named by gf_config_key_name.
GF_API size_t gf_config_key_count(void);
/// Writes "section.name" of key `i` into `buf`.
GF_API gf_status gf_config_key_name(size_t i, char *buf, size_t size);
/// One line saying what key `i` means (NULL when out of range).
GF_API const char *gf_config_key_doc(size_t i);
/// The default of key `i` as the INI file writes it (NULL when out of range).
GF_API const char *gf_config_key_default(size_t i);

/// Writes the configuration to `path` atomically (temporary file + rename).
GF_API gf_status gf_config_save(const gf_config *cfg, const char *path);

#ifdef __cplusplus
}
#endif
#endif
