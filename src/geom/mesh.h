// SPDX-License-Identifier: MIT
// Internal: the container's walls as a triangle mesh, for pictures and
// ParaView (container.vtk in a run directory).
#ifndef GF_GEOM_MESH_H
#define GF_GEOM_MESH_H

#include <stdbool.h>
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

/// The walls of `c` up to height `top` (its shape's mesh op: the box's side
/// walls and base with its hole, the cylinder's wall, funnel, pipe and
/// column, the wedge's walls; circles drawn with `segments` edges).
gf_status gf_container_mesh(const gf_container *c, double top, int segments, gf_mesh *out);
void gf_mesh_free(gf_mesh *m);

/// The shapes' mesh ops (m starts empty; freed on failure).
gf_status gf_mesh_box(const gf_container *c, double top, int segments, gf_mesh *m);
gf_status gf_mesh_cylinder(const gf_container *c, double top, int segments, gf_mesh *m);

/// Building blocks for a shape's mesh: a vertex (its index; SIZE_MAX when
/// out of memory), a triangle, the quad a-b-c-d as two triangles, and the
/// segment (r0, z0)-(r1, z1) of the (rho, z) half-plane swept round the z axis in n steps.
size_t gf_mesh_vertex(gf_mesh *m, double x, double y, double z);
bool gf_mesh_tri(gf_mesh *m, size_t a, size_t b, size_t c);
bool gf_mesh_quad(gf_mesh *m, const double a[3], const double b[3], const double c[3], const double d[3]);
bool gf_mesh_revolve(gf_mesh *m, double r0, double z0, double r1, double z1, int n);

#endif
