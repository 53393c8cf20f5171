// SPDX-License-Identifier: MIT
// Particles as data and files (the formats layer, src/io/): the gf_packing
// type, its storage, and its file formats (LAMMPS text dump, XYZ, CSV, the
// run directory's snapshot frames). Building a packing for a container is
// granflow/packing.h, which includes this header.
#ifndef GRANFLOW_PARTICLES_H
#define GRANFLOW_PARTICLES_H

#include <stddef.h>
#include <stdint.h>

#include "granflow/config.h"
#include "granflow/core.h"

#ifdef __cplusplus
extern "C" {
#endif

/// A set of spheres, structure of arrays. Owns its arrays: release with
/// gf_packing_free(). Zero-initialise before first use ({0}).
typedef struct gf_packing {
    size_t n;        ///< number of particles
    size_t cap;      ///< allocated capacity (elements)
    int64_t *id;     ///< stable particle id (>= 1, unique)
    int32_t *layer;  ///< initial-layer tag: 1 + floor(z0 / layer_thickness)
    double *x, *y, *z; ///< centre, d
    double *r;       ///< radius, d (0.5 for the monodisperse papers' spheres)
} gf_packing;

/// File formats gf_packing_read/gf_packing_write understand.
typedef enum gf_packing_format {
    GF_FORMAT_AUTO = 0, ///< from the file name: .xyz, .csv, anything else = LAMMPS dump
    GF_FORMAT_LAMMPS,   ///< LAMMPS text dump, `ITEM: ATOMS id ... x y z` in any column order
    GF_FORMAT_XYZ,      ///< N, comment line, then `name x y z` lines
    GF_FORMAT_CSV,      ///< header line naming at least x,y,z (id, radius optional)
} gf_packing_format;

/// Makes room for `cap` particles, keeping the first n. GF_ERR_NOMEM on failure.
GF_API gf_status gf_packing_reserve(gf_packing *p, size_t cap);
/// Appends one particle (grows the arrays as needed).
GF_API gf_status gf_packing_push(gf_packing *p, int64_t id, int32_t layer, double x, double y,
                                 double z, double r);
/// Frees the arrays and zeroes the struct.
GF_API void gf_packing_free(gf_packing *p);

/// Reads a packing (the last frame of a multi-frame LAMMPS dump). Errors name
/// the file and line. Ids from the file are kept (they must be unique and
/// positive); files without ids get 1..N in file order. Missing radii = 0.5.
GF_API gf_status gf_packing_read(const char *path, gf_packing_format format, gf_packing *out);

/// Writes a packing (LAMMPS dump with `id type x y z radius`, XYZ or CSV) atomically.
GF_API gf_status gf_packing_write(const gf_packing *p, const char *path, gf_packing_format format,
                                  const gf_config *cfg);

/// Writes one snapshot frame in LAMMPS text-dump form (`ITEM: TIME`, then
/// `ITEM: TIMESTEP`, box, `ITEM: ATOMS id type x y z`, type = layer tag) to
/// `path`, atomically. A `radius` column follows when some radius is not
/// 0.5, and a `pass` column when `pass` (may be NULL; one per particle of
/// `p`, see gf_sim_passes) is given. Shared by the run directory and tools.
GF_API gf_status gf_run_write_snapshot(const char *path, const gf_config *cfg, const gf_packing *p, const int32_t *pass,
                                       double time, uint64_t step);

// ---- one frame of a dump as flat arrays: what bindings use ------------------

/// One frame of a LAMMPS text dump read into memory (opaque: bindings read
/// it through the functions below, not through a struct layout).
typedef struct gf_snapshot gf_snapshot;

/// Reads frame `frame` (0 = first; -1 = last) of the LAMMPS text dump
/// `path`, plain or gzip-compressed (any name), with the checks and messages
/// of gf_packing_read (file and line). Besides x y z (or unwrapped/scaled
/// forms) it keeps the id, type, radius (or diameter) and granflow's pass
/// columns. A frame may hold 0 particles. GF_ERR_IO when the file cannot be
/// opened, GF_ERR_FORMAT when it is malformed, GF_ERR_PARAM when it has no
/// frame `frame`.
GF_API gf_status gf_snapshot_read(const char *path, long frame, gf_snapshot **out);
GF_API void gf_snapshot_destroy(gf_snapshot *s);

/// Particles in the frame.
GF_API size_t gf_snapshot_count(const gf_snapshot *s);
/// Frames in the file the snapshot was read from.
GF_API size_t gf_snapshot_frames(const gf_snapshot *s);
/// ITEM: TIME (tau for granflow's snapshots), or NaN when the frame has none.
GF_API double gf_snapshot_time(const gf_snapshot *s);
/// ITEM: TIMESTEP.
GF_API int64_t gf_snapshot_step(const gf_snapshot *s);
/// The box (ITEM: BOX BOUNDS) into lo[3], hi[3]; returns 0 (arrays left
/// alone) when the frame has none, 1 otherwise.
GF_API int gf_snapshot_box(const gf_snapshot *s, double lo[3], double hi[3]);
/// Copies the particles in file order: `id[i]`, `type[i]` (the `type`
/// column, granflow's layer tag; 0 without one), `xyz[3i..3i+2]`,
/// `radius[i]` (0.5 without a radius or diameter column), `pass[i]` (1
/// without a pass column); any array may be NULL. GF_ERR_PARAM when more
/// than `cap` particles; `*n` (may be NULL) receives the count.
GF_API gf_status gf_snapshot_copy(const gf_snapshot *s, int64_t *id, int32_t *type, double *xyz, double *radius,
                                  int32_t *pass, size_t cap, size_t *n);

#ifdef __cplusplus
}
#endif
#endif
