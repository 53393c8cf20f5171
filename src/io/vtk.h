// SPDX-License-Identifier: MIT
// Internal: VTK files for ParaView, meshio and OVITO: particles as a VTK XML
// unstructured grid (.vtu) with its time, the series as a collection (.pvd),
// the container as XML polydata (.vtp) and as legacy VTK polydata (.vtk).
#ifndef GF_IO_VTK_H
#define GF_IO_VTK_H

#include <stdint.h>

#include "geom/mesh.h"
#include "granflow/config.h"
#include "granflow/core.h"
#include "granflow/particles.h"

/// Writes the particles of `p` to `path` (atomically) as a .vtu: one vertex
/// cell per particle, point data id, radius, pass (1 everywhere when `pass`
/// is NULL) and layer, and the time (tau) as field data TimeValue, the name
/// ParaView reads. GF_VTK_BINARY: the arrays zlib-compressed in a raw
/// appended block; GF_VTK_ASCII: inline text.
gf_status gf_vtk_write_particles_as(const char *path, const gf_packing *p, const int32_t *pass, double time,
                                    gf_vtk_encoding enc);
/// gf_vtk_write_particles_as in binary.
gf_status gf_vtk_write_particles(const char *path, const gf_packing *p, const int32_t *pass, double time);

/// Writes a triangle mesh to `path` (atomically) as VTK XML polydata (.vtp).
gf_status gf_vtk_write_surface(const char *path, const gf_mesh *m, gf_vtk_encoding enc);

/// Writes a triangle mesh to `path` (atomically) as legacy ASCII VTK polydata.
gf_status gf_vtk_write_mesh(const char *path, const gf_mesh *m, const char *title);

/// Writes the collection `path` (.pvd, atomically): datasets files[k]
/// (relative to the .pvd's folder) at times[k], k < n.
gf_status gf_vtk_write_collection(const char *path, const char *const *files, const double *times, size_t n);

/// The time of a .vtu written by gf_vtk_write_particles (TimeValue, or the
/// TIME of earlier versions). GF_ERR_IO / GF_ERR_FORMAT when there is none.
gf_status gf_vtk_read_time(const char *path, double *time);

#endif
