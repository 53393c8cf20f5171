// SPDX-License-Identifier: MIT
// Internal: the silo: side walls, a base at z = 0 with a hole, the exit plane.
#ifndef GF_GEOM_CONTAINER_H
#define GF_GEOM_CONTAINER_H

#include <math.h>
#include <stdbool.h>

#include "granflow/config.h"

typedef struct gf_container {
    double xlo, xhi, ylo, yhi; ///< side walls
    gf_orifice_shape shape;    ///< circle or slit
    double hole;               ///< orifice radius (circle) or half-width (slit)
    double exit_z;             ///< a centre below this (over the hole) has left
} gf_container;

/// Container of `cfg` (SPEC 1.1).
gf_container gf_container_make(const gf_config *cfg);

/// True when (x, y) lies over the hole in the base.
static inline bool gf_container_over_hole(const gf_container *c, double x, double y)
{
    if (c->shape == GF_ORIFICE_SLIT) return fabs(x) < c->hole;
    return x * x + y * y < c->hole * c->hole;
}

/// Relaxation push of the walls on a sphere of radius r at (x, y, z) (SPEC 1.3:
/// a particle closer than r to a wall moves away by alpha (r - distance)); the
/// base is a wall except over the hole, whose rim is an edge the sphere is
/// pushed away from. Adds to *dx, *dy, *dz.
void gf_container_push(const gf_container *c, double x, double y, double z, double r, double alpha,
                       double *dx, double *dy, double *dz);

/// True when a sphere of radius r at (x, y, z) is inside the container: within
/// the side walls and above the base, or anywhere over the hole.
bool gf_container_contains(const gf_container *c, double x, double y, double z, double r, double tol);

/// Bounding rectangle of the container's horizontal cross-section.
void gf_container_bounds_xy(const gf_container *c, double lo[2], double hi[2]);

/// True when a sphere of radius r centred at (x, y) at the top of the
/// container clears the side walls (re-insertion on the free surface asks
/// this of every position it tries; a new shape answers for its own walls).
bool gf_container_inside_xy(const gf_container *c, double x, double y, double r);

/// Lowest height the centre of a sphere of radius r at (x, y) can have on
/// the container's floor (the flat base: r).
double gf_container_floor_z(const gf_container *c, double x, double y, double r);

#endif
