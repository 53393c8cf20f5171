// SPDX-License-Identifier: MIT
// The key table and the parsing, checking and printing of single values.
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
_Static_assert(sizeof(gf_reinsert) == sizeof(int) && sizeof(gf_output_format) == sizeof(int),
               "enum keys are stored as int");
_Static_assert(sizeof(gf_run_mode) == sizeof(int) && sizeof(gf_run_order) == sizeof(int) &&
                   sizeof(gf_spot_walls) == sizeof(int) && sizeof(gf_relax_method) == sizeof(int),
               "enum keys are stored as int");

static const char *const gf_keys_orifice_names[] = {"circle", "slit", NULL};
static const char *const gf_keys_shape_names[] = {"box", "cylinder", NULL};
static const char *const gf_keys_ball_names[] = {"midpoint", "end", NULL};
static const char *const gf_keys_dem_fill_names[] = {"pour", "generate", NULL};
static const char *const gf_keys_lga_scenario_names[] = {"pile", "channel", "silo", NULL};
static const char *const gf_keys_lga_flow_names[] = {"mass", "funnel", NULL};
static const char *const gf_keys_mode_names[] = {"event", "fixed", NULL};
static const char *const gf_keys_order_names[] = {"random", "newest", "spatial", NULL};
static const char *const gf_keys_walls_names[] = {"truncate", "reflect", NULL};
static const char *const gf_keys_onoff_names[] = {"off", "on", NULL};
static const char *const gf_keys_reinsert_names[] = {"random", "zone", NULL};
static const char *const gf_keys_format_names[] = {"dump", "vtk", "both", NULL};
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
     .doc = "orifice shape: circle (disc centred at x = y = 0) or slit (|x| < diameter/2, all y)"},
    {"container", "orifice_diameter", GF_KEY_DOUBLE, GF_OFF(orifice_diameter), GF_POSITIVE,
     .def = "8", .unit = "d",
     .doc = "orifice diameter (circle) or full width (slit), must be < container.width"},
    {"container", "exit_z", GF_KEY_DOUBLE, GF_OFF(exit_z), .min = -1e5, .max = 0.5, .def = "0",
     .unit = "d", .doc = "particles whose centre falls below this height (less container.outlet_length) leave"},
    {"container", "shape", GF_KEY_ENUM, GF_OFF(container_shape), .names = gf_keys_shape_names, .def = "box",
     .unit = "", .doc = "box (width x depth, flat base with an orifice) or cylinder (radius, funnel, outlet pipe)"},
    {"container", "radius", GF_KEY_DOUBLE, GF_OFF(container_radius), .min = 0, .max = 5e4, .min_open = true, .def = "12.5", .unit = "d",
     .doc = "cylinder: radius of the wall about the z axis (width and depth become 2 radius)"},
    {"container", "hopper_angle", GF_KEY_DOUBLE, GF_OFF(hopper_angle), .min = 0, .max = 80, .def = "0",
     .unit = "deg", .doc = "cylinder: funnel angle to the horizontal, cone from the wall down to the outlet (0: flat base)"},
    {"container", "outlet_diameter", GF_KEY_DOUBLE, GF_OFF(outlet_diameter), .min = 0, .max = 1e5, .min_open = true, .def = "8",
     .unit = "d", .doc = "cylinder: diameter of the outlet at z = 0 and of the pipe below it (orifice_diameter follows it)"},
    {"container", "outlet_length", GF_KEY_DOUBLE, GF_OFF(outlet_length), .min = 0, .max = 1e5, .def = "0", .unit = "d",
     .doc = "cylinder: length of the straight pipe below the outlet; particles leave at its end"},
    {"container", "inner_radius", GF_KEY_DOUBLE, GF_OFF(inner_radius), .min = 0, .max = 5e4, .def = "0", .unit = "d",
     .doc = "cylinder: radius of a solid central column down to the top of the funnel (0: none)"},

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
     .unit = "", .doc = "fixed mode: order of the moves in a step: random, newest first, or spatial (blocks in a "
                        "fixed colouring, in random phases, run in parallel; results do not depend on run.threads)"},
    {"run", "threads", GF_KEY_INT64, GF_OFF(run_threads), .min = 0, .max = 4096, .def = "0", .unit = "",
     .doc = "threads of the spatial fixed step (run.order = spatial); 0: every core"},
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

    {"output", "snapshot_interval", GF_KEY_DOUBLE, GF_OFF(output_snapshot_interval), GF_POSITIVE,
     .def = "2", .unit = "tau", .doc = "write a snapshot every this long; at most 10^5 per run.duration"},
    {"output", "format", GF_KEY_ENUM, GF_OFF(output_format), .names = gf_keys_format_names, .def = "dump",
     .unit = "", .doc = "snapshot files: dump (LAMMPS text), vtk (VTK XML .vtu for ParaView) or both"},

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
     .min_open = true, .def = "auto", .unit = "degrees",
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
};

const size_t gf_keys_count = sizeof gf_keys / sizeof gf_keys[0];

const gf_key *gf_keys_find(const char *section, const char *name)
{
    for (size_t i = 0; i < gf_keys_count; i++)
        if (strcmp(gf_keys[i].section, section) == 0 && strcmp(gf_keys[i].name, name) == 0)
            return &gf_keys[i];
    return NULL;
}

bool gf_keys_section_known(const char *section)
{
    for (size_t i = 0; i < gf_keys_count; i++)
        if (strcmp(gf_keys[i].section, section) == 0) return true;
    return false;
}

// Appends `s` to the NUL-terminated text in buf[0..n), truncating.
static void gf_keys_append(char *buf, size_t n, const char *s)
{
    size_t len = strlen(buf);
    if (len + 1 < n) snprintf(buf + len, n - len, "%s", s);
}

void gf_keys_list(const char *section, char *buf, size_t n)
{
    if (n == 0) return;
    buf[0] = '\0';
    for (size_t i = 0; i < gf_keys_count; i++) {
        const gf_key *k = &gf_keys[i];
        const char *item;
        if (section) {
            if (strcmp(k->section, section) != 0) continue;
            item = k->name;
        } else {
            if (i > 0 && strcmp(gf_keys[i - 1].section, k->section) == 0) continue;
            item = k->section;
        }
        if (buf[0]) gf_keys_append(buf, n, ", ");
        gf_keys_append(buf, n, item);
    }
}

static double *gf_keys_dfield(gf_config *cfg, const gf_key *k)
{
    return (double *)((char *)cfg + k->offset);
}

static const double *gf_keys_cdfield(const gf_config *cfg, const gf_key *k)
{
    return (const double *)((const char *)cfg + k->offset);
}

static bool gf_keys_in_range(const gf_key *k, double v)
{
    bool lo = k->min_open ? v > k->min : v >= k->min;
    bool hi = k->max_open ? v < k->max : v <= k->max;
    return lo && hi;
}

void gf_keys_format_double(double v, char *buf, size_t n)
{
    uint64_t want, got;
    memcpy(&want, &v, sizeof want);
    for (int prec = 15; prec <= 17; prec++) {
        snprintf(buf, n, "%.*g", prec, v);
        double back = strtod(buf, NULL);
        memcpy(&got, &back, sizeof got);
        if (got == want) return;
    }
}

void gf_keys_range(const gf_key *k, char *buf, size_t n)
{
    if (n == 0) return;
    buf[0] = '\0';
    switch (k->type) {
    case GF_KEY_ENUM:
        for (size_t i = 0; k->names[i]; i++) {
            if (i > 0) gf_keys_append(buf, n, ", ");
            gf_keys_append(buf, n, k->names[i]);
        }
        return;
    case GF_KEY_PATH: snprintf(buf, n, "path"); return;
    case GF_KEY_UINT64: snprintf(buf, n, "[0, %" PRIu64 "]", UINT64_MAX); return;
    case GF_KEY_DOUBLE:
    case GF_KEY_AUTO:
    case GF_KEY_INT64: break;
    }
    char lo[32] = "-inf", hi[32] = "inf";
    if (isfinite(k->min)) gf_keys_format_double(k->min, lo, sizeof lo);
    if (isfinite(k->max)) gf_keys_format_double(k->max, hi, sizeof hi);
    snprintf(buf, n, "%c%s, %s%c%s", k->min_open || !isfinite(k->min) ? '(' : '[', lo, hi,
             k->max_open || !isfinite(k->max) ? ')' : ']',
             k->type == GF_KEY_AUTO ? " or auto" : "");
}

static gf_key_result gf_keys_out_of_range(const gf_key *k, char *why, size_t n)
{
    char range[64];
    gf_keys_range(k, range, sizeof range);
    snprintf(why, n, "out of range %s", range);
    return GF_KEY_OUT_OF_RANGE;
}

// strtod/strtoll over the whole string; NULL or "" never parse.
static bool gf_keys_parse_double(const char *s, double *out)
{
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    if (end == s || *end != '\0') return false;
    *out = v;
    return true;
}

static gf_key_result gf_keys_assign_double(const gf_key *k, gf_config *cfg, const char *value,
                                           char *why, size_t n)
{
    double v;
    if (!gf_keys_parse_double(value, &v)) {
        snprintf(why, n, k->type == GF_KEY_AUTO ? "not a number or 'auto'" : "not a number");
        return GF_KEY_BAD_VALUE;
    }
    if (!isfinite(v)) {
        snprintf(why, n, "not a finite number");
        return GF_KEY_BAD_VALUE;
    }
    if (!gf_keys_in_range(k, v)) return gf_keys_out_of_range(k, why, n);
    *gf_keys_dfield(cfg, k) = v;
    return GF_KEY_OK;
}

static gf_key_result gf_keys_bad_integer(const char *value, char *why, size_t n)
{
    double v;
    snprintf(why, n, gf_keys_parse_double(value, &v) ? "not an integer" : "not a number");
    return GF_KEY_BAD_VALUE;
}

static gf_key_result gf_keys_assign_int64(const gf_key *k, gf_config *cfg, const char *value,
                                          char *why, size_t n)
{
    char *end;
    errno = 0;
    long long v = strtoll(value, &end, 10);
    if (end == value || *end != '\0') return gf_keys_bad_integer(value, why, n);
    if (errno == ERANGE || !gf_keys_in_range(k, (double)v)) return gf_keys_out_of_range(k, why, n);
    int64_t x = (int64_t)v;
    memcpy((char *)cfg + k->offset, &x, sizeof x);
    return GF_KEY_OK;
}

static gf_key_result gf_keys_assign_uint64(const gf_key *k, gf_config *cfg, const char *value,
                                           char *why, size_t n)
{
    char *end;
    errno = 0;
    unsigned long long v = strtoull(value, &end, 10);
    if (end == value || *end != '\0') return gf_keys_bad_integer(value, why, n);
    // strtoull accepts "-1" and wraps it around; a minus sign is out of range here.
    if (errno == ERANGE || value[0] == '-') return gf_keys_out_of_range(k, why, n);
    uint64_t x = (uint64_t)v;
    memcpy((char *)cfg + k->offset, &x, sizeof x);
    return GF_KEY_OK;
}

static gf_key_result gf_keys_assign_enum(const gf_key *k, gf_config *cfg, const char *value,
                                         char *why, size_t n)
{
    for (int i = 0; k->names[i]; i++) {
        if (strcmp(k->names[i], value) == 0) {
            memcpy((char *)cfg + k->offset, &i, sizeof i);
            return GF_KEY_OK;
        }
    }
    char names[128];
    gf_keys_range(k, names, sizeof names);
    snprintf(why, n, "not one of: %s", names);
    return GF_KEY_BAD_VALUE;
}

gf_key_result gf_keys_assign(const gf_key *k, gf_config *cfg, const char *value, char *why,
                             size_t n)
{
    if (value[0] == '\0' && k->type != GF_KEY_PATH) {
        snprintf(why, n, "empty value");
        return GF_KEY_BAD_VALUE;
    }
    switch (k->type) {
    case GF_KEY_AUTO:
        if (strcmp(value, "auto") == 0) {
            *gf_keys_dfield(cfg, k) = NAN;
            return GF_KEY_OK;
        }
        return gf_keys_assign_double(k, cfg, value, why, n);
    case GF_KEY_DOUBLE: return gf_keys_assign_double(k, cfg, value, why, n);
    case GF_KEY_INT64: return gf_keys_assign_int64(k, cfg, value, why, n);
    case GF_KEY_UINT64: return gf_keys_assign_uint64(k, cfg, value, why, n);
    case GF_KEY_ENUM: return gf_keys_assign_enum(k, cfg, value, why, n);
    case GF_KEY_PATH: {
        size_t len = strlen(value);
        if (len >= GF_PATH_MAX) {
            snprintf(why, n, "path too long (%zu bytes, at most %d)", len, GF_PATH_MAX - 1);
            return GF_KEY_BAD_VALUE;
        }
        char *dst = (char *)cfg + k->offset;
        memset(dst, 0, GF_PATH_MAX);
        memcpy(dst, value, len);
        return GF_KEY_OK;
    }
    }
    snprintf(why, n, "unknown key type");
    return GF_KEY_BAD_VALUE;
}

bool gf_keys_check(const gf_key *k, const gf_config *cfg, char *why, size_t n)
{
    const char *field = (const char *)cfg + k->offset;
    switch (k->type) {
    case GF_KEY_AUTO:
    case GF_KEY_DOUBLE: {
        double v = *gf_keys_cdfield(cfg, k);
        if (k->type == GF_KEY_AUTO && isnan(v)) return true;
        if (!isfinite(v)) {
            snprintf(why, n, "not a finite number");
            return false;
        }
        if (gf_keys_in_range(k, v)) return true;
        gf_keys_out_of_range(k, why, n);
        return false;
    }
    case GF_KEY_INT64: {
        int64_t v;
        memcpy(&v, field, sizeof v);
        if (gf_keys_in_range(k, (double)v)) return true;
        gf_keys_out_of_range(k, why, n);
        return false;
    }
    case GF_KEY_UINT64: return true;
    case GF_KEY_ENUM: {
        int v, count = 0;
        memcpy(&v, field, sizeof v);
        while (k->names[count]) count++;
        if (v < 0 || v >= count) {
            char names[128];
            gf_keys_range(k, names, sizeof names);
            snprintf(why, n, "enum value %d is not one of: %s", v, names);
            return false;
        }
        return true;
    }
    case GF_KEY_PATH:
        if (!memchr(field, '\0', GF_PATH_MAX)) {
            snprintf(why, n, "path is not NUL-terminated within %d bytes", GF_PATH_MAX);
            return false;
        }
        return true;
    }
    return false;
}

void gf_keys_format(const gf_key *k, const gf_config *cfg, char *buf, size_t n)
{
    const char *field = (const char *)cfg + k->offset;
    switch (k->type) {
    case GF_KEY_AUTO:
        if (isnan(*gf_keys_cdfield(cfg, k))) {
            snprintf(buf, n, "auto");
            return;
        }
        gf_keys_format_double(*gf_keys_cdfield(cfg, k), buf, n);
        return;
    case GF_KEY_DOUBLE: gf_keys_format_double(*gf_keys_cdfield(cfg, k), buf, n); return;
    case GF_KEY_INT64: {
        int64_t v;
        memcpy(&v, field, sizeof v);
        snprintf(buf, n, "%" PRId64, v);
        return;
    }
    case GF_KEY_UINT64: {
        uint64_t v;
        memcpy(&v, field, sizeof v);
        snprintf(buf, n, "%" PRIu64, v);
        return;
    }
    case GF_KEY_ENUM: {
        int v, count = 0;
        memcpy(&v, field, sizeof v);
        while (k->names[count]) count++;
        if (v >= 0 && v < count)
            snprintf(buf, n, "%s", k->names[v]);
        else
            snprintf(buf, n, "%d", v);
        return;
    }
    case GF_KEY_PATH: snprintf(buf, n, "%.*s", GF_PATH_MAX - 1, field); return;
    }
    if (n) buf[0] = '\0';
}
