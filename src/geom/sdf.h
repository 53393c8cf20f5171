// SPDX-License-Identifier: MIT
// Internal: the signed distance field of a closed (or outlet-open) triangle
// mesh (docs/geometry.md, "Containers from STL"). Built once: node values on
// a grid of spacing h (exact distances within a band of the surface, the
// sign everywhere from the parity of a vertical ray), read by trilinear
// interpolation; within h sqrt(3) of the surface the distance is made exact
// from the triangles near the point (a bucket grid), so walls are as exact
// as the mesh whatever h is. Positive inside.
#ifndef GF_GEOM_SDF_H
#define GF_GEOM_SDF_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "geom/stl.h"
#include "granflow/core.h"

/// Most grid nodes (of the field and of the buckets) a mesh may ask for.
#define GF_SDF_MAX_NODES 50000000

/// Where on a triangle its closest point to a query lies.
typedef enum gf_sdf_region {
    GF_SDF_FACE = 0,  ///< inside the triangle
    GF_SDF_EDGE0 = 1, ///< on edge k (v[k] -> v[k+1]) = GF_SDF_EDGE0 + k
    GF_SDF_VERT0 = 4, ///< on vertex k = GF_SDF_VERT0 + k
} gf_sdf_region;

typedef struct gf_sdf {
    gf_stl mesh;           ///< owned
    double (*n)[3];        ///< outward unit normal of each triangle
    double (*vn)[3];       ///< angle-weighted pseudonormal of each vertex (outward)
    uint8_t *vopen;        ///< vertex on an open (boundary) edge
    double z_exit;         ///< nothing below this plane is inside (the outlet's plane)
    double lo[3], hi[3];   ///< the mesh's bounding box
    // The field: nodes lo - pad + h (i, j, k).
    double g0[3], h, band;
    int nx, ny, nz;
    float *d;
    // Buckets: triangles by the cells of side bh their bounding box meets.
    double b0[3], bh;
    int bx, by, bz;
    uint32_t *bstart, *blist;
    size_t nlist;
    int32_t (*trange)[6]; ///< each triangle's cell range: lo x, y, z, hi x, y, z
} gf_sdf;

/// Builds the field of `mesh` (moved in: the field owns it, also on failure),
/// spacing h > 0, points below `exit_z` outside. GF_ERR_NOMEM; GF_ERR_PARAM
/// when the grid would exceed GF_SDF_MAX_NODES (naming h).
gf_status gf_sdf_build(gf_sdf *s, gf_stl *mesh, double exit_z, double h);
void gf_sdf_free(gf_sdf *s);

/// The interpolated field at p (within h sqrt(3) of the true signed distance,
/// which it also bounds: far from the surface it is clamped at +-band).
double gf_sdf_value(const gf_sdf *s, const double p[3]);

/// Signed distance from p to the mesh, exact (to rounding) where it is less
/// than `exact` + 0 in magnitude, interpolated beyond. Positive inside.
double gf_sdf_distance(const gf_sdf *s, const double p[3], double exact);

/// Unit normal of the field at p: its gradient (central differences of
/// gf_sdf_distance, exact near the walls), pointing into the container.
void gf_sdf_normal(const gf_sdf *s, const double p[3], double n[3]);

/// True when p is inside the mesh (and not below the exit plane).
bool gf_sdf_inside(const gf_sdf *s, const double p[3]);

/// Closest point q on triangle t to p and where it lies on t.
gf_sdf_region gf_sdf_closest(const gf_sdf *s, uint32_t t, const double p[3], double q[3]);

/// Calls f(ctx, t) once for every triangle whose bounding box comes within
/// `reach` of p (a superset of those within reach); stops early when f
/// returns false. Thread-safe (no scratch state).
void gf_sdf_near(const gf_sdf *s, const double p[3], double reach, bool (*f)(void *ctx, uint32_t t), void *ctx);

#endif
