// SPDX-License-Identifier: MIT
// Internal: VTK files for ParaView (and OVITO): particles as a VTK XML
// unstructured grid (.vtu), the container as a legacy VTK polydata surface.
#ifndef GF_IO_VTK_H
#define GF_IO_VTK_H

#include <stdint.h>

#include "geom/mesh.h"
#include "granflow/core.h"
#include "granflow/particles.h"

/// Writes the particles of `p` to `path` (atomically) as an ASCII .vtu: one
/// vertex cell per particle, point data id, radius, pass (1 everywhere when
/// `pass` is NULL) and layer, and the time (tau) as field data TIME.
gf_status gf_vtk_write_particles(const char *path, const gf_packing *p, const int32_t *pass, double time);

/// Writes a triangle mesh to `path` (atomically) as legacy ASCII VTK polydata.
gf_status gf_vtk_write_mesh(const char *path, const gf_mesh *m, const char *title);

#endif
