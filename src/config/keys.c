// SPDX-License-Identifier: MIT
// The table of gf_config's keys (their parsing, checking and printing: config/keytable.c).
#include "config/keys.h"

#include <errno.h>
#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

_Static_assert(sizeof(gf_orifice_shape) == sizeof(int), "enum keys are stored as int");
_Static_assert(sizeof(gf_container_shape) == sizeof(int), "enum keys are stored as int");
_Static_assert(sizeof(gf_ball_centre) == sizeof(int), "enum keys are stored as int");
_Static_assert(sizeof(gf_lga_scenario) == sizeof(int), "enum keys are stored as int");
_Static_assert(sizeof(gf_lga_flow) == sizeof(int), "enum keys are stored as int");
_Static_assert(sizeof(gf_dem_fill) == sizeof(int), "enum keys are stored as int");
_Static_assert(sizeof(gf_reinsert) == sizeof(int) && sizeof(gf_output_format) == sizeof(int) &&
                   sizeof(gf_vtk_encoding) == sizeof(int),
               "enum keys are stored as int");
_Static_assert(sizeof(gf_run_mode) == sizeof(int) && sizeof(gf_run_order) == sizeof(int) &&
                   sizeof(gf_spot_walls) == sizeof(int) && sizeof(gf_relax_method) == sizeof(int) &&
                   sizeof(gf_flow_rule) == sizeof(int) && sizeof(gf_sfr_rise) == sizeof(int),
               "enum keys are stored as int");

static const char *const gf_keys_orifice_names[] = {"circle", "slit", NULL};
static const char *const gf_keys_shape_names[] = {"box", "cylinder", "wedge", "mesh", NULL};
static const char *const gf_keys_ball_names[] = {"midpoint", "end", NULL};
static const char *const gf_keys_dem_fill_names[] = {"pour", "generate", NULL};
static const char *const gf_keys_lga_scenario_names[] = {"pile", "channel", "silo", NULL};
static const char *const gf_keys_lga_flow_names[] = {"mass", "funnel", NULL};
static const char *const gf_keys_mode_names[] = {"event", "fixed", NULL};
static const char *const gf_keys_order_names[] = {"random", "newest", "spatial", "domains", "sweep", NULL};
static const char *const gf_keys_walls_names[] = {"truncate", "reflect", NULL};
static const char *const gf_keys_flow_rule_names[] = {"diffusive", "sfr", NULL};
static const char *const gf_keys_sfr_rise_names[] = {"slip", "steady", NULL};
static const char *const gf_keys_onoff_names[] = {"off", "on", NULL};
static const char *const gf_keys_reinsert_names[] = {"random", "zone", NULL};
// output.format: bit i of gf_output_format is names[i] (a third format is one more name and bit).
static const char *const gf_keys_format_names[] = {"dump", "vtk", NULL};
static const char *const gf_keys_format_aliases[] = {"both", "dump,vtk", NULL};
static const char *const gf_keys_vtk_encoding_names[] = {"binary", "ascii", NULL};
static const char *const gf_keys_cut_names[] = {"x", "y", "z", NULL};
static const char *const gf_keys_cut_aliases[] = {"all", "x,y,z", "xyz", "x,y,z", "xy", "x,y",
                                                   "xz",  "x,z",   "yz",  "y,z",   NULL};
static const char *const gf_keys_relax_names[] = {"full", "none", "random", "counter", "global", NULL};

#define GF_OFF(field) offsetof(gf_config, field)
// Ranges: (0, inf), [0, inf), (-inf, inf).
#define GF_POSITIVE .min = 0, .max = INFINITY, .min_open = true
#define GF_NONNEG .min = 0, .max = INFINITY
#define GF_ANYREAL .min = -INFINITY, .max = INFINITY

const gf_key gf_keys[] = {
    {"container", "width", GF_KEY_DOUBLE, GF_OFF(container_width), .min = 0, .max = 1e5, .min_open = true, .def = "50",
     .unit = "d", .doc = "container width (x), walls at x = +-width/2"},
    {"container", "depth", GF_KEY_DOUBLE, GF_OFF(container_depth), .min = 0, .max = 1e5, .min_open = true, .def = "8",
     .unit = "d", .doc = "container depth (y), walls at y = +-depth/2"},
    {"container", "orifice_shape", GF_KEY_ENUM, GF_OFF(orifice_shape),
     .names = gf_keys_orifice_names, .def = "circle", .unit = "",
     .doc = "orifice shape: circle (disc centred at orifice_x, orifice_y) or slit (|x - orifice_x| < diameter/2, all y)"},
    {"container", "orifice_diameter", GF_KEY_DOUBLE, GF_OFF(orifice_diameter), GF_POSITIVE,
     .def = "8", .unit = "d",
     .doc = "orifice diameter (circle) or full width (slit), must be < container.width"},
    {"container", "orifice_x", GF_KEY_DOUBLE, GF_OFF(orifice_x), .min = -1e5, .max = 1e5, .def = "0", .unit = "d",
     .doc = "box: x of the orifice centre (circle) or mid-line (slit); the orifice must lie inside the base"},
    {"container", "orifice_y", GF_KEY_DOUBLE, GF_OFF(orifice_y), .min = -1e5, .max = 1e5, .def = "0", .unit = "d",
     .doc = "box, circular orifice: y of its centre; the orifice must lie inside the base"},
    {"container", "exit_z", GF_KEY_DOUBLE, GF_OFF(exit_z), .min = -1e5, .max = 0.5, .def = "0",
     .unit = "d", .doc = "particles whose centre falls below this height (less container.outlet_length) leave"},
    {"container", "shape", GF_KEY_ENUM, GF_OFF(container_shape), .names = gf_keys_shape_names, .def = "box",
     .unit = "", .doc = "box (width x depth, flat base with an orifice), cylinder (radius, funnel, outlet pipe) wedge (width x depth, inclined walls down to a slit, chute) or mesh (container.mesh)"},
    {"container", "radius", GF_KEY_DOUBLE, GF_OFF(container_radius), .min = 0, .max = 5e4, .min_open = true, .def = "12.5", .unit = "d",
     .doc = "cylinder: radius of the wall about the z axis (width and depth become 2 radius)"},
    {"container", "hopper_angle", GF_KEY_DOUBLE, GF_OFF(hopper_angle), .min = 0, .max = 80, .def = "0",
     .unit = "deg", .doc = "cylinder: funnel angle to the horizontal, cone from the wall down to the outlet (0: flat base); wedge: angle of its inclined walls to the horizontal, > 0"},
    {"container", "outlet_diameter", GF_KEY_DOUBLE, GF_OFF(outlet_diameter), .min = 0, .max = 1e5, .min_open = true, .def = "8",
     .unit = "d", .doc = "cylinder: diameter of the outlet at z = 0 and of the pipe below it (orifice_diameter follows it)"},
    {"container", "outlet_length", GF_KEY_DOUBLE, GF_OFF(outlet_length), .min = 0, .max = 1e5, .def = "0", .unit = "d",
     .doc = "cylinder: length of the straight pipe below the outlet; wedge: of the chute below the slit; particles leave at its end"},
    {"container", "inner_radius", GF_KEY_DOUBLE, GF_OFF(inner_radius), .min = 0, .max = 5e4, .def = "0", .unit = "d",
     .doc = "cylinder: radius of a solid central column down to the top of the funnel (0: none)"},
    {"container", "mesh", GF_KEY_PATH, GF_OFF(container_mesh), .def = "", .unit = "",
     .doc = "mesh: the walls as an STL file (ASCII or binary; a relative path is read from the INI file's folder), "
            "closed except for the outlet"},
    {"container", "mesh_scale", GF_KEY_DOUBLE, GF_OFF(container_mesh_scale), .min = 0, .max = 1e9, .min_open = true,
     .def = "1", .unit = "d per file unit", .doc = "mesh: the file's coordinates are multiplied by this (1: they are in d)"},
    {"container", "mesh_resolution", GF_KEY_DOUBLE, GF_OFF(container_mesh_resolution), .min = 0.05, .max = 10,
     .def = "0.5", .unit = "d",
     .doc = "mesh: grid spacing of the signed distance field (wall distances are exact near the walls whatever it is)"},

    {"packing", "particles", GF_KEY_INT64, GF_OFF(packing_particles), .min = 1, .max = 50000000,
     .def = "55000", .unit = "", .doc = "number of spheres to generate"},
    {"packing", "fill_height", GF_KEY_DOUBLE, GF_OFF(packing_fill_height), GF_NONNEG, .def = "0",
     .unit = "d",
     .doc = "if > 0, generate enough spheres to fill to this height (0: use particles)"},
    {"packing", "file", GF_KEY_PATH, GF_OFF(packing_file), .def = "", .unit = "",
     .doc = "packing to import (LAMMPS dump, .xyz, .csv, each possibly gzipped: `.gz`) instead of generating (empty: generate)"},
    {"packing", "layer_thickness", GF_KEY_DOUBLE, GF_OFF(packing_layer_thickness), .min = 0.1, .max = 1e6,
     .def = "10", .unit = "d", .doc = "thickness of the colour bands tagging initial layers"},
    {"packing", "types", GF_KEY_PATH, GF_OFF(packing_types), .def = "", .unit = "",
     .doc = "atom types to keep when importing a LAMMPS dump, e.g. 1 or 1,3 (empty: all)"},
    {"packing", "radius2", GF_KEY_DOUBLE, GF_OFF(packing_radius2), .min = 0.25, .max = 0.5, .def = "0.5",
     .unit = "d", .doc = "radius of the second species of a generated packing (the first has radius 0.5; a larger one is imported)"},
    {"packing", "fraction2", GF_KEY_DOUBLE, GF_OFF(packing_fraction2), .min = 0, .max = 1, .def = "0",
     .unit = "", .doc = "number fraction of the second species (0: monodisperse)"},

    {"dump", "diameter", GF_KEY_DOUBLE, GF_OFF(dump_diameter), .min = 0, .max = 1e6, .min_open = true, .def = "1",
     .unit = "dump length",
     .doc = "the particle diameter in the length unit of the dumps read (packing.file; analyze, calibrate, compare): "
            "1 for dumps in d, 0.004 for 4 mm spheres in metres"},
    {"dump", "gravity", GF_KEY_DOUBLE, GF_OFF(dump_gravity), .min = 0, .max = 1e9, .min_open = true, .def = "1",
     .unit = "dump length/time^2",
     .doc = "gravity in the dumps' units (9.81 in SI): their times are read in tau = sqrt(dump.diameter / dump.gravity)"},

    {"spot", "radius", GF_KEY_DOUBLE, GF_OFF(spot_radius), .min = 0, .max = 20, .min_open = true,
     .def = "2.6", .unit = "d", .doc = "spot radius r_s"},
    {"spot", "w", GF_KEY_DOUBLE, GF_OFF(spot_w), GF_POSITIVE, .def = "399", .unit = "",
     .doc = "ratio w of spot to particle displacement"},
    {"spot", "insertion_rate", GF_KEY_DOUBLE, GF_OFF(spot_insertion_rate), .min = 0, .max = 1e6,
     .min_open = true, .def = "375", .unit = "1/tau", .doc = "spot insertion rate lambda (spots per tau)"},
    {"spot", "move_rate", GF_KEY_DOUBLE, GF_OFF(spot_move_rate), .min = 0, .max = 1e6, .min_open = true, .def = "28",
     .unit = "1/tau", .doc = "spot move rate mu (moves per spot per tau)"},
    {"spot", "step_xy", GF_KEY_DOUBLE, GF_OFF(spot_step_xy), GF_NONNEG, .def = "0.676", .unit = "d",
     .doc = "horizontal random step dx = dy of a spot move"},
    {"spot", "step_z", GF_KEY_DOUBLE, GF_OFF(spot_step_z), GF_POSITIVE, .def = "0.1", .unit = "d",
     .doc = "upward step dz of a spot move"},
    {"spot", "wall_distance", GF_KEY_DOUBLE, GF_OFF(spot_wall_distance), GF_ANYREAL, .def = "1",
     .unit = "d", .doc = "closest approach d_w of a spot centre to a side wall (may be negative)"},
    {"spot", "ball_centre", GF_KEY_ENUM, GF_OFF(spot_ball_centre), .names = gf_keys_ball_names,
     .def = "midpoint", .unit = "",
     .doc = "centre of the ball a spot step moves: midpoint s+v/2 (Stratonovich) or end s+v (Ito)"},
    {"spot", "insertion_margin", GF_KEY_AUTO, GF_OFF(spot_insertion_margin), GF_NONNEG,
     .def = "auto", .unit = "d",
     .doc = "spots are born at least this far inside the orifice edge (auto: spot.radius)"},
    {"spot", "bias_exponent", GF_KEY_DOUBLE, GF_OFF(spot_bias_exponent), .min = 0, .max = 20, .def = "0",
     .unit = "", .doc = "beta: the walk picks candidate i with probability p_i^beta / sum p_j^beta (0: unbiased)"},
    {"spot", "weighting", GF_KEY_ENUM, GF_OFF(spot_weighting), .names = gf_keys_onoff_names, .def = "off",
     .unit = "", .doc = "influence weighting: displacement scaled by bulk_count / max(p, min_count)"},
    {"spot", "weighting_min_count", GF_KEY_DOUBLE, GF_OFF(spot_weighting_min_count), GF_POSITIVE,
     .def = "20", .unit = "particles", .doc = "influence weighting: smaller ball populations count as this"},
    {"spot", "weighting_zmin", GF_KEY_DOUBLE, GF_OFF(spot_weighting_zmin), GF_ANYREAL, .def = "30",
     .unit = "d", .doc = "influence weighting is off for balls centred below this height"},
    {"spot", "weighting_bulk_count", GF_KEY_DOUBLE, GF_OFF(spot_weighting_bulk_count), GF_POSITIVE,
     .def = "81.7", .unit = "particles", .doc = "influence weighting: p_bulk, the population of a ball in the bulk"},
    {"spot", "walls", GF_KEY_ENUM, GF_OFF(spot_walls), .names = gf_keys_walls_names, .def = "truncate",
     .unit = "", .doc = "truncate the walk at wall_distance, or reflect (d_w = 0, ball reflected at the walls)"},
    {"spot", "flow_rule", GF_KEY_ENUM, GF_OFF(spot_flow_rule), .names = gf_keys_flow_rule_names,
     .def = "diffusive", .unit = "",
     .doc = "diffusive (the papers' walk) or sfr (the stochastic flow rule: steps along the slip lines of the "
            "stress field, docs/stress.md)"},
    {"spot", "sfr_rise", GF_KEY_ENUM, GF_OFF(spot_sfr_rise), .names = gf_keys_sfr_rise_names, .def = "steady",
     .unit = "",
     .doc = "sfr: steady (up by step_z every step, across by the slip-line step's horizontal part) or slip (a "
            "step goes along its slip line, up or down; docs/stress.md)"},

    {"stress", "friction_angle", GF_KEY_DOUBLE, GF_OFF(stress_friction_angle), .min = 0, .max = 60,
     .min_open = true, .max_open = true, .def = "30", .unit = "deg",
     .doc = "internal friction angle phi of the Mohr-Coulomb stress field (sfr; 30: glass beads)"},
    {"stress", "wall_friction_angle", GF_KEY_DOUBLE, GF_OFF(stress_wall_friction_angle), .min = 0, .max = 60,
     .max_open = true, .def = "20", .unit = "deg",
     .doc = "wall friction angle phi_w of the stress field, at most stress.friction_angle"},
    {"stress", "spacing", GF_KEY_DOUBLE, GF_OFF(stress_spacing), .min = 0.05, .max = 100, .def = "1",
     .unit = "d", .doc = "grid spacing of the stress field (stress.csv)"},

    {"relax", "alpha", GF_KEY_DOUBLE, GF_OFF(relax_alpha), .min = 0, .max = 1, .min_open = true,
     .def = "0.8", .unit = "", .doc = "fraction of an overlap removed per relaxation"},
    {"relax", "radius", GF_KEY_AUTO, GF_OFF(relax_radius), .min = 0, .max = 40, .min_open = true, .def = "auto",
     .unit = "d",
     .doc = "elastic relaxation radius r_e, must be >= spot.radius (auto: spot.radius + 1)"},
    {"relax", "method", GF_KEY_ENUM, GF_OFF(relax_method), .names = gf_keys_relax_names, .def = "full",
     .unit = "", .doc = "full, none, random (probability 1/k), counter (every k-th move of a spot), global (all every k/mu)"},
    {"relax", "k", GF_KEY_DOUBLE, GF_OFF(relax_k), .min = 1, .max = 1e9, .def = "10", .unit = "",
     .doc = "reduction factor k of the random, counter and global methods"},

    {"run", "duration", GF_KEY_DOUBLE, GF_OFF(run_duration), GF_POSITIVE, .def = "60",
     .unit = "tau", .doc = "simulated time to reach"},
    {"run", "seed", GF_KEY_UINT64, GF_OFF(run_seed), GF_NONNEG, .def = "1", .unit = "",
     .doc = "seed of every random stream"},
    {"run", "checkpoint_interval", GF_KEY_DOUBLE, GF_OFF(run_checkpoint_interval), GF_NONNEG,
     .def = "10", .unit = "tau",
     .doc = "write a checkpoint every this long (0: only on stop and at the end); at most 10^5 per run.duration"},
    {"run", "stall_time", GF_KEY_DOUBLE, GF_OFF(run_stall_time), GF_NONNEG, .def = "10", .unit = "tau",
     .doc = "stop when no particle has left for this long while some remain (0: never)"},
    {"run", "reorder_interval", GF_KEY_INT64, GF_OFF(run_reorder_interval), .min = 1, .max = 1e12,
     .def = "1000000", .unit = "events",
     .doc = "events between full re-sorts of particles in memory (speed only; changes the last bits)"},
    {"run", "mode", GF_KEY_ENUM, GF_OFF(run_mode), .names = gf_keys_mode_names, .def = "event", .unit = "",
     .doc = "event (Gillespie) or fixed (steps of 1/mu: Poisson(lambda/mu) insertions, every spot moves once)"},
    {"run", "order", GF_KEY_ENUM, GF_OFF(run_order), .names = gf_keys_order_names, .def = "random",
     .unit = "", .doc = "fixed mode: order of the moves in a step: random, newest first, spatial (blocks in a "
                        "fixed colouring, in random phases, run in parallel; results do not depend on run.threads), or "
                        "domains (each sector of every domain moves its spots at their own rate for parallel.window "
                        "tau in turn; results depend on the parallel keys, not on run.threads), or sweep (windows "
                        "of parallel.window tau: every spot's moves read the window's start, their displacements "
                        "are summed, then parallel.sweeps Jacobi relaxation sweeps; results depend on the parallel "
                        "keys, not on run.threads)"},
    {"run", "threads", GF_KEY_INT64, GF_OFF(run_threads), .min = 0, .max = 4096, .def = "0", .unit = "",
     .doc = "threads of the parallel engines (run.order = spatial, domains, sweep); 0: every core"},
    {"run", "recirculate", GF_KEY_ENUM, GF_OFF(run_recirculate), .names = gf_keys_onoff_names, .def = "off",
     .unit = "", .doc = "put every particle that exits back on the free surface, its pass count + 1 (pebble-bed cycling)"},
    {"run", "max_passes", GF_KEY_INT64, GF_OFF(run_max_passes), .min = 0, .max = 1e9, .def = "0", .unit = "",
     .doc = "recirculation: a particle leaves for good at the end of this pass (0: never)"},
    {"run", "reinsert", GF_KEY_ENUM, GF_OFF(run_reinsert), .names = gf_keys_reinsert_names, .def = "random",
     .unit = "", .doc = "recirculation: where on the surface: random (whole cross-section) or zone (the annulus "
                        "reinsert_rmin <= r < reinsert_rmax around the axis x = y = 0)"},
    {"run", "reinsert_rmin", GF_KEY_DOUBLE, GF_OFF(run_reinsert_rmin), GF_NONNEG, .def = "0", .unit = "d",
     .doc = "zone re-insertion: inner radius from the axis"},
    {"run", "reinsert_rmax", GF_KEY_AUTO, GF_OFF(run_reinsert_rmax), GF_POSITIVE, .def = "auto", .unit = "d",
     .doc = "zone re-insertion: outer radius from the axis (auto: to the wall)"},

    {"parallel", "window", GF_KEY_DOUBLE, GF_OFF(parallel_window), .min = 0, .max = 10, .min_open = true,
     .def = "0.005", .unit = "tau",
     .doc = "run.order = domains: simulated time each sector runs before the next (halos exchanged between); "
            "run.order = sweep: the window whose moves all read its start; "
            "-> 0 recovers the event engine's statistics"},
    {"parallel", "domain_size", GF_KEY_DOUBLE, GF_OFF(parallel_domain_size), GF_NONNEG, .def = "0", .unit = "d",
     .doc = "run.order = domains: edge of a domain along each cut axis (0: the smallest that keeps same-index "
            "sectors of neighbouring domains independent)"},
    {"parallel", "cut", GF_KEY_SET, GF_OFF(parallel_cut), .names = gf_keys_cut_names, .aliases = gf_keys_cut_aliases,
     .def = "x,y,z", .unit = "",
     .doc = "run.order = domains: the axes cut into domains (those long enough for two sectors); z alone: "
            "horizontal slabs, fewer phases a window for flows in a central column"},
    {"parallel", "sectors", GF_KEY_INT64, GF_OFF(parallel_sectors), .min = 2, .max = 4, .def = "2", .unit = "",
     .doc = "run.order = domains: sectors per cut axis (2 as in SPPARKS; more: thinner sectors, more phases)"},
    {"parallel", "sweeps", GF_KEY_INT64, GF_OFF(parallel_sweeps), .min = 0, .max = 100, .def = "2", .unit = "",
     .doc = "run.order = sweep: Jacobi relaxation sweeps per window over the particles within r_e of its moves "
            "(0: none)"},

    {"output", "snapshot_interval", GF_KEY_DOUBLE, GF_OFF(output_snapshot_interval), GF_POSITIVE,
     .def = "2", .unit = "tau", .doc = "write a snapshot every this long; at most 10^5 per run.duration"},
    {"output", "format", GF_KEY_SET, GF_OFF(output_format), .names = gf_keys_format_names,
     .aliases = gf_keys_format_aliases, .def = "dump", .unit = "",
     .doc = "snapshot files, a list: dump (LAMMPS text), vtk (VTK XML .vtu and snapshots.pvd for ParaView); "
            "both = dump,vtk"},
    {"output", "vtk_encoding", GF_KEY_ENUM, GF_OFF(output_vtk_encoding), .names = gf_keys_vtk_encoding_names,
     .def = "binary", .unit = "",
     .doc = "arrays of the VTK XML files: binary (zlib-compressed, appended) or ascii (inline text)"},

    {"lga", "scenario", GF_KEY_ENUM, GF_OFF(lga_scenario), .names = gf_keys_lga_scenario_names,
     .def = "silo", .unit = "",
     .doc = "LGA problem: pile (heap from particles added at the top), channel (vertical, periodic), "
            "silo (parallel part over a hopper, run until empty)"},
    {"lga", "silo_flow", GF_KEY_ENUM, GF_OFF(lga_silo_flow), .names = gf_keys_lga_flow_names,
     .def = "mass", .unit = "",
     .doc = "silo type: mass (steep hopper) or funnel (shallow hopper); sets the auto hopper_angle"},
    {"lga", "p", GF_KEY_DOUBLE, GF_OFF(lga_p), .min = 0, .max = 1, .def = "0.2", .unit = "",
     .doc = "collision parameter p: n particles come to rest with probability p^n (1 - p)"},
    {"lga", "q", GF_KEY_DOUBLE, GF_OFF(lga_q), .min = 0, .max = 1, .def = "0.2", .unit = "",
     .doc = "collision parameter q: l particles leave in random directions with probability q^l (1 - q)"},
    {"lga", "g", GF_KEY_DOUBLE, GF_OFF(lga_g), .min = 0, .max = 1, .def = "0.2", .unit = "",
     .doc = "gravity g: probability that the downward velocity v4 is added at a collision"},
    {"lga", "h", GF_KEY_DOUBLE, GF_OFF(lga_h), .min = 0, .max = 1, .def = "0.05", .unit = "",
     .doc = "gravity h: probability per iteration that a resting particle drops to an empty site below"},
    {"lga", "k", GF_KEY_DOUBLE, GF_OFF(lga_k), .min = 0, .max = 1, .def = "0.05", .unit = "",
     .doc = "friction k: probability that the outgoing momentum is replaced by random horizontal-ish velocities"},
    {"lga", "b", GF_KEY_DOUBLE, GF_OFF(lga_b), .min = 0, .max = 1, .def = "0.05", .unit = "",
     .doc = "wall roughness b: probability that a particle hitting a wall stops"},
    {"lga", "iterations", GF_KEY_INT64, GF_OFF(lga_iterations), .min = 0, .max = 1e9, .def = "0",
     .unit = "iterations",
     .doc = "iterations to run (0: the scenario's end: pile settled, channel 2160, silo empty or stalled)"},
    {"lga", "width", GF_KEY_INT64, GF_OFF(lga_width), .min = 0, .max = 100000, .def = "0",
     .unit = "sites", .doc = "lattice columns; silo: of the parallel part (0: the scenario's default)"},
    {"lga", "height", GF_KEY_INT64, GF_OFF(lga_height), .min = 0, .max = 100000, .def = "0",
     .unit = "sites", .doc = "lattice rows; silo: of the parallel part (0: the scenario's default)"},
    {"lga", "particles", GF_KEY_INT64, GF_OFF(lga_particles), .min = 0, .max = 1e9, .def = "0",
     .unit = "",
     .doc = "pile: particles to add; channel: initial particles; silo: fill from the bottom (0: the scenario's default)"},
    {"lga", "feed_rate", GF_KEY_DOUBLE, GF_OFF(lga_feed_rate), .min = 0, .max = 1000, .min_open = true,
     .def = "8", .unit = "1/iteration", .doc = "pile: particles added at the top per iteration"},
    {"lga", "hopper_angle", GF_KEY_AUTO, GF_OFF(lga_hopper_angle), .min = 0, .max = 80,
     .min_open = true, .def = "auto", .unit = "deg",
     .doc = "silo: hopper wall angle from the vertical (auto: by silo_flow)"},
    {"lga", "outlet_width", GF_KEY_DOUBLE, GF_OFF(lga_outlet_width), .min = 1, .max = INFINITY,
     .def = "16", .unit = "d", .doc = "silo: width of the outlet at the bottom of the hopper"},
    {"lga", "snapshot_interval", GF_KEY_INT64, GF_OFF(lga_snapshot_interval), .min = 1, .max = 1e9,
     .def = "60", .unit = "iterations", .doc = "draw a density map every this many iterations"},

    {"dem", "friction", GF_KEY_DOUBLE, GF_OFF(dem_friction), .min = 0, .max = 10, .def = "0.5", .unit = "",
     .doc = "Coulomb friction coefficient of every contact, particles and walls (the papers' 0.5)"},
    {"dem", "kn", GF_KEY_DOUBLE, GF_OFF(dem_kn), GF_POSITIVE, .def = "200000", .unit = "m g/d",
     .doc = "Hertzian normal stiffness k_n of pair_style gran/hertz/history"},
    {"dem", "kt", GF_KEY_AUTO, GF_OFF(dem_kt), GF_NONNEG, .def = "auto", .unit = "m g/d",
     .doc = "tangential stiffness k_t (auto: 2/7 k_n)"},
    {"dem", "gamman", GF_KEY_DOUBLE, GF_OFF(dem_gamman), GF_NONNEG, .def = "50", .unit = "1/tau",
     .doc = "normal damping gamma_n"},
    {"dem", "gammat", GF_KEY_AUTO, GF_OFF(dem_gammat), GF_NONNEG, .def = "auto", .unit = "1/tau",
     .doc = "tangential damping gamma_t (auto: gamma_n / 2)"},
    {"dem", "timestep", GF_KEY_DOUBLE, GF_OFF(dem_timestep), .min = 0, .max = 0.01, .min_open = true,
     .def = "0.0001", .unit = "tau", .doc = "LAMMPS integration step, at most a tenth of the contact time"},
    {"dem", "fill_method", GF_KEY_ENUM, GF_OFF(dem_fill_method), .names = gf_keys_dem_fill_names,
     .def = "pour", .unit = "",
     .doc = "pour (fix pour from above the fill) or generate (granflow's packing settled under gravity)"},
    {"dem", "settle_time", GF_KEY_DOUBLE, GF_OFF(dem_settle_time), GF_POSITIVE, .def = "20", .unit = "tau",
     .doc = "longest settling after the fill before the orifice opens"},
    {"dem", "settle_ke", GF_KEY_DOUBLE, GF_OFF(dem_settle_ke), GF_NONNEG, .def = "1e-06", .unit = "m g d",
     .doc = "settling stops early once the kinetic energy per particle is below this (0: never)"},
    {"dem", "mpi_ranks", GF_KEY_INT64, GF_OFF(dem_mpi_ranks), .min = 0, .max = 4096, .def = "0", .unit = "",
     .doc = "MPI ranks of granflow dem --run (1: lmp without mpirun; 0: one per core)"},
    {"dem", "restart_interval", GF_KEY_DOUBLE, GF_OFF(dem_restart_interval), GF_NONNEG, .def = "2", .unit = "tau",
     .doc = "the drain writes a LAMMPS restart file this often (drain.a.restart and drain.b.restart in turn), "
            "from which granflow dem --continue goes on after an interruption (0: none)"},
};

const size_t gf_keys_count = sizeof gf_keys / sizeof gf_keys[0];
const gf_key_table gf_config_keys = {gf_keys, sizeof gf_keys / sizeof gf_keys[0]};

_Static_assert(sizeof gf_keys / sizeof gf_keys[0] <= GF_CONFIG_MAX_KEYS,
               "gf_config records where each key was set: raise GF_CONFIG_MAX_KEYS");
