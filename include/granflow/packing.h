// SPDX-License-Identifier: MIT
// Particle packings: generate one in the container (SPEC 1.2), import one
// for a run, measure one. The data type gf_packing, its storage and its file
// formats (read, write, snapshot frames) are in granflow/particles.h (the
// formats layer), included here: this header still gives all of it.
#ifndef GRANFLOW_PACKING_H
#define GRANFLOW_PACKING_H

#include <stddef.h>
#include <stdint.h>

#include <signal.h>

#include "granflow/config.h"
#include "granflow/core.h"
#include "granflow/particles.h"

#ifdef __cplusplus
extern "C" {
#endif

/// Sets every layer tag from the current z: 1 + floor(z / thickness).
GF_API void gf_packing_tag_layers(gf_packing *p, double thickness);

/// Options of building a packing: gf_packing_generate, gf_packing_for_config
/// and what builds one through them (gf_sim_create_from_config,
/// gf_dem_write_inputs). A NULL `opts` means gf_packing_opts_default().
typedef struct gf_packing_opts {
    /// Polled at every relaxation sweep (and every 65,536 spheres of each pass
    /// over them): once non-zero, GF_ERR_INTERRUPTED with nothing built
    /// (safe to set from a signal handler). NULL (default): never.
    volatile sig_atomic_t *stop;
} gf_packing_opts;

/// The defaults listed in gf_packing_opts.
GF_API gf_packing_opts gf_packing_opts_default(void);

/// Builds a random packing for `cfg` (packing.particles or packing.fill_height,
/// run.seed): no pair closer than 0.99 d, no centre closer than 0.5 d to a wall
/// or the base, bulk packing fraction 0.58-0.64. `opts` may be NULL.
GF_API gf_status gf_packing_generate(const gf_config *cfg, const gf_packing_opts *opts, gf_packing *out);

/// What gf_packing_import read and dropped.
typedef struct gf_packing_import_report {
    size_t read;        ///< particles in the frame read
    size_t other_types; ///< dropped: atom type not in packing.types
    size_t below_base;  ///< dropped: centre below the exit plane (gf_config_exit_plane; already exited, e.g. a DEM
                        ///< packing's particles falling through the orifice)
} gf_packing_import_report;

/// Imports `packing.file` as the initial packing of a run (SPEC 1.2, 1.8):
/// reads it (the last frame of a multi-frame LAMMPS dump), keeps only the atom
/// types of `packing.types` (a LAMMPS dump with a `type` column; empty: all;
/// a DEM floor of frozen particles is typically another type), drops every
/// particle whose centre lies below the exit plane (gf_config_exit_plane: `container.exit_z`, less a cylinder's pipe or a wedge's chute; counted as already
/// exited), and tags the layers by height. `rep` (may be NULL) gets the counts.
/// GF_ERR_PARAM when packing.types is set and the file has no type column,
/// or when no particle is left.
GF_API gf_status gf_packing_import(const gf_config *cfg, gf_packing *out, gf_packing_import_report *rep);

/// The initial packing of a run of `cfg`: packing.file imported
/// (gf_packing_import; `rep`, may be NULL, gets its counts), else generated
/// (gf_packing_generate with `opts`, may be NULL; `rep` zeroed). The one way
/// every user of a config's packing (a run, the DEM inputs, `granflow pack`,
/// a binding) gets it.
GF_API gf_status gf_packing_for_config(const gf_config *cfg, const gf_packing_opts *opts, gf_packing *out,
                                       gf_packing_import_report *rep);

/// Checks that every centre lies in the container of `cfg`: between the side
/// walls, and above the base unless over the orifice. GF_ERR_PARAM naming the
/// first particle outside.
GF_API gf_status gf_packing_check(const gf_packing *p, const gf_config *cfg);

/// Packing fraction of the particles whose centres lie in the box
/// [x0,x1] x [y0,y1] x [z0,z1] (sphere volume over box volume, centre count).
GF_API double gf_packing_fraction(const gf_packing *p, double x0, double x1, double y0, double y1,
                                  double z0, double z1);

/// Bulk packing fraction of a packing in the container of `cfg`, centres
/// counted 2 d clear of every wall, from 2 d above the base (or the funnel's
/// top) to 3 d below the highest centre: a box (gf_packing_fraction) for the
/// box and the wedge, the annulus 3 d inside the wall (and outside a column)
/// for a cylinder. NaN when that region is empty.
GF_API double gf_packing_bulk_fraction(const gf_packing *p, const gf_config *cfg);

/// Smallest centre-centre distance over all pairs (cell list; O(N)).
/// Returns +inf for fewer than two particles, NaN when out of memory or a
/// coordinate or radius is not finite.
GF_API double gf_packing_min_distance(const gf_packing *p);

#ifdef __cplusplus
}
#endif
#endif
