// SPDX-License-Identifier: MIT
// Internal: container.shape = mesh, walls from an STL file (docs/geometry.md,
// "Containers from STL"): its ops and row in meshshape.c, its loading in
// meshload.c. The mesh is read and its field built once per (file, scale,
// resolution, outlet) in a process and kept for its life (a gf_container is
// a plain value, copied freely, never freed): every container made from the
// same configuration shares it.
#ifndef GF_GEOM_MESHSHAPE_H
#define GF_GEOM_MESHSHAPE_H

#include <stdint.h>

#include "geom/container.h"
#include "geom/sdf.h"

/// A loaded mesh container: the field of its surface and what was checked
/// against (the outlet on the exit plane).
typedef struct gf_meshshape {
    gf_sdf sdf;
    gf_orifice_shape shape; ///< the outlet: container.orifice_shape, _diameter, _x, _y on the plane exit_z
    double hole, ox, oy, z_exit;
    double top;             ///< height of the cross-section re-insertion asks about (just under the lid)
    uint64_t digest;        ///< FNV-1a of the file's bytes (a checkpoint names the mesh by it)
    uint8_t *tconvex;       ///< per triangle, bit k: edge k is convex seen from inside (or open)
    uint8_t *tconcave;      ///< per triangle, bit k: edge k is concave seen from inside
    uint8_t *vconvex;       ///< per vertex: on a convex or open edge
    uint32_t *vstart, *vnbr; ///< each vertex's neighbours (CSR)
    uint32_t *vfirst;       ///< each vertex's lowest-numbered triangle
    bool closed;            ///< no open edge: the outlet is cut out of the walls by the orifice keys
    double z_col;           ///< where the cross-section stops changing (a funnel's top; the floor for straight walls)
    double axis_r;          ///< > 0: a solid of revolution about the z axis (a cylinder, a cone) of this wall radius; 0: none
    char path[GF_PATH_MAX]; ///< container.mesh as given (messages)
} gf_meshshape;

/// The mesh container of `cfg` (container.mesh, mesh_scale, mesh_resolution,
/// the orifice keys and exit_z): from the cache, else read, checked and
/// built. Fails with a message naming the file and the triangle (not an STL
/// file, truncated, degenerate, inverted or inconsistent normals, open away
/// from the outlet, reaching below the exit plane, an outlet that opens
/// onto no inside).
gf_status gf_meshshape_load(const gf_container_defs *d, const gf_meshshape **out);

/// Area of the mesh's horizontal cross-section at height z, d^2 (0 below the exit plane).
double gf_meshshape_section(const gf_meshshape *ms, double z);

/// The segment (x0, z0, x1, z1) where triangle t of the mesh crosses the
/// plane y (pictures: the outline of the section); false when it does not.
bool gf_meshshape_slice_y(const gf_meshshape *ms, double y, size_t t, double seg[4]);

/// The FNV-1a digest of the bytes of cfg's container.mesh (a checkpoint
/// names the mesh by it: a run directory's copy is the same mesh).
gf_status gf_meshshape_digest(const gf_container_defs *d, uint64_t *digest);

/// Frees every cached mesh (tests that count allocations; no container
/// made earlier may be used afterwards).
void gf_meshshape_cache_clear(void);

/// The mesh row's validate op (gf_shape): container.mesh named, the file
/// read and checked, its bounding box set as container.width and depth.
gf_status gf_meshshape_validate(const gf_container_defs *d, gf_config *cfg);

#endif
