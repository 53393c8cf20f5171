// SPDX-License-Identifier: MIT
// The keys of the summaries in words, with their units (docs/analysis.md,
// docs/lga.md, README's run outputs say the same at more length).
#include "report/fields.h"

#include <stddef.h>
#include <string.h>

// Lengths in particle diameters d, times in tau = sqrt(d/g) (spot runs and
// analyses) or iterations (LGA runs); "" is dimensionless.
static const gf_report_field gf_report_fields[] = {
    // a run (summary.json of `granflow run`)
    {"granflow_version", "granflow version", ""},
    {"status", "state of the run", ""},
    {"error", "what stopped the run", ""},
    {"seed", "random seed", ""},
    {"particles_initial", "particles at the start", "particles"},
    {"particles_remaining", "particles in the container at the end", "particles"},
    {"particles_exited", "particles that left through the orifice", "particles"},
    {"particles_reinserted", "particles put back on the free surface", "particles"},
    {"spots_inserted", "spots born at the orifice", "spots"},
    {"spots_deleted", "spots removed at the top of the packing", "spots"},
    {"spots_active", "spots in the container at the end", "spots"},
    {"spot_moves", "spot moves", "moves"},
    {"relax_calls", "local relaxations", "calls"},
    {"events", "events simulated (spot insertions and moves)", "events"},
    {"global_relaxations", "relaxations of the whole packing", "calls"},
    {"t_relax", "time spent relaxing", "s"},
    {"neighbour_list_builds", "neighbour-list rebuilds", "builds"},
    {"simulated_time", "simulated time", "tau"},
    {"wall_seconds", "wall-clock time of the run", "s"},
    {"steps_per_second", "spot moves per second of wall-clock time", "1/s"},
    // an analysis (analysis/summary.json; compare/summary.csv uses the same keys)
    {"frames", "snapshots read", "snapshots"},
    {"window_t0", "start of the averaging window", "tau"},
    {"window_t1", "end of the averaging window", "tau"},
    {"flow_rate", "steady outflow rate", "particles/tau"},
    {"velocity_variance_slope", "growth with height of the width (variance) of v_z(x)", "d"},
    {"velocity_variance_intercept", "width (variance) of v_z(x) extrapolated to z = 0", "d^2"},
    {"velocity_unsteady_heights", "profile heights with no steady frames (reported, not fitted)", ""},
    {"diffusion_length", "diffusion length b_p", "d"},
    {"diffusion_particles", "particles followed for the diffusion", "particles"},
    {"correlation_length", "velocity correlation length beta", "d"},
    {"correlation_amplitude", "velocity correlation amplitude a", ""},
    {"correlation_unsteadiness", "unsteadiness of the flow in the correlation region", ""},
    {"gr_first_peak_r", "distance of the first peak of g(r)", "d"},
    {"coordination", "neighbours per particle (closer than g3.rcut)", "neighbours"},
    {"bulk_packing_fraction", "packing fraction of the bulk (Voronoi)", ""},
    {"density_initial", "particles in the counted slice, first snapshot", "particles"},
    {"density_steady", "particles in the counted slice, steady flow", "particles"},
    {"surface_angle", "angle of the free surface", "degrees"},
    {"badness", "packing badness B (squared overlaps per particle)", ""},
    {"rtd_mean", "mean residence time", "tau"},
    {"rtd_median", "median residence time", "tau"},
    {"rtd_exited", "exits counted for the residence times", "particles"},
    {"rtd_mean_err", "uncertainty of the mean residence time", "tau"},
    {"rtd_resolution", "resolution of the exit times", "tau"},
    {"rtd_tmax", "residence times counted up to", "tau"},
    {"zones_count", "radial zones", "zones"},
    {"transit_mean", "mean transit time (entry to exit)", "tau"},
    {"passes_max", "highest pass through the container", "passes"},
    // an LGA run (summary.json of `granflow lga`)
    {"scenario", "problem of the LGA paper", ""},
    {"silo_flow", "silo type", ""},
    {"hopper_angle", "hopper wall angle from the vertical", "degrees"},
    {"outlet_width", "outlet width", "d"},
    {"p", "collision parameter p", "probability"},
    {"q", "collision parameter q", "probability"},
    {"g", "gravity parameter g", "probability"},
    {"h", "gravity parameter h", "probability"},
    {"k", "friction parameter k", "probability"},
    {"b", "wall roughness b", "probability"},
    {"lattice_width", "lattice width", "columns"},
    {"lattice_height", "lattice height", "rows"},
    {"fluid_sites", "sites particles can occupy", "sites"},
    {"iterations", "iterations run", "iterations"},
    {"particles_added", "particles fed in at the top", "particles"},
    {"particles_removed", "particles that left through the sinks", "particles"},
    {"particles_final", "particles at the end", "particles"},
    {"iterations_to_empty", "iterations until the silo was empty", "iterations"},
    {"iterations_to_stop", "iteration of the last outflow", "iterations"},
    {"t50", "iterations until 50% of the outflow had left", "iterations"},
    {"t90", "iterations until 90% of the outflow had left", "iterations"},
    {"t99", "iterations until 99% of the outflow had left", "iterations"},
    {"mean_outflow_rate", "mean outflow rate", "particles/iteration"},
    {"slope_angle", "slope of the heap (mean of its flanks)", "degrees"},
    {"slope_left", "slope of the heap's left flank", "degrees"},
    {"slope_right", "slope of the heap's right flank", "degrees"},
    {"wave_variance_initial", "density-wave variance at the start", "(particles/site)^2"},
    {"wave_variance_final", "density-wave variance, last quarter of the run", "(particles/site)^2"},
    {"wave_variance_ratio", "growth of the density waves (final / initial)", ""},
    {"site_updates_per_second", "site updates per second of wall-clock time", "1/s"},
};

const gf_report_field *gf_report_field_find(const char *key)
{
    for (size_t k = 0; k < sizeof gf_report_fields / sizeof gf_report_fields[0]; k++)
        if (!strcmp(gf_report_fields[k].key, key)) return &gf_report_fields[k];
    return NULL;
}
