// SPDX-License-Identifier: MIT
// Internal: the container's walls as a triangle mesh, for pictures and
// ParaView (container.vtk in a run directory).
#ifndef GF_GEOM_MESH_H
#define GF_GEOM_MESH_H

#include <stddef.h>

#include "geom/container.h"
#include "granflow/core.h"

/// Triangles over vertices; owned arrays (gf_mesh_free).
typedef struct gf_mesh {
    double (*v)[3];   ///< vertices
    size_t nv, vcap;
    size_t (*t)[3];   ///< triangles, as indices into v
    size_t nt, tcap;
} gf_mesh;

/// The walls of `c` up to height `top`: a box's side walls and base with its
/// hole (a circle drawn with `segments` edges); a cylinder's wall, funnel,
/// outlet pipe and central column (circles of `segments` edges). A new shape
/// adds its case here.
gf_status gf_container_mesh(const gf_container *c, double top, int segments, gf_mesh *out);
void gf_mesh_free(gf_mesh *m);

#endif
