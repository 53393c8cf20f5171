// SPDX-License-Identifier: MIT
// Internal: STL files (ASCII and binary) read into a welded triangle mesh
// with its edge adjacency, and the checks a container's walls need of it
// (docs/geometry.md, "Containers from STL").
#ifndef GF_GEOM_STL_H
#define GF_GEOM_STL_H

#include <stddef.h>
#include <stdint.h>

#include "granflow/core.h"

/// Most triangles a file may hold (a CAD export of a bin has thousands; the
/// cap keeps a bad count from asking for gigabytes).
#define GF_STL_MAX_TRIANGLES 4000000
/// Largest STL file read, bytes (4e6 ASCII facets of ~250 bytes).
#define GF_STL_MAX_BYTES (1LL << 30)

/// A welded mesh: vertices shared by their triangles, triangles as vertex
/// ids in the file's order (counter-clockwise seen from outside, the STL
/// rule), and for each triangle edge k (v[k] -> v[k+1]) the triangle across
/// it, or -1 on an open (boundary) edge. Owned arrays (gf_stl_free).
typedef struct gf_stl {
    size_t nv, nt;
    double (*v)[3];
    uint32_t (*t)[3];
    int32_t (*adj)[3];
} gf_stl;

/// Reads `path` (ASCII `solid ... endsolid` or binary: 80-byte header,
/// uint32 count, 50 bytes a triangle), multiplies coordinates by `scale`,
/// welds equal vertices and builds the adjacency. Refused, with a message
/// naming the file and (1-based) triangle: not an STL file, a truncated
/// binary, a malformed or non-finite number, no triangles, a degenerate
/// triangle (area below 1e-10 d^2 or an edge below 1e-6 d), a stored normal
/// opposite to the vertex order, an edge shared by more than two triangles,
/// two triangles with opposite orientations across an edge.
/// GF_ERR_IO (cannot read), GF_ERR_FORMAT (the file), GF_ERR_NOMEM.
gf_status gf_stl_read(const char *path, double scale, gf_stl *out);

/// The same from bytes in memory (`name` is used in messages).
gf_status gf_stl_parse(const char *name, const unsigned char *data, size_t len, double scale, gf_stl *out);

void gf_stl_free(gf_stl *m);

#endif
