// SPDX-License-Identifier: MIT
// Internal: the container's geometry behind one interface (docs/geometry.md).
// A shape is one file (box.c, cylinder.c) filling a gf_shape_ops table: its
// walls near a point (distance and normal), the relaxation push, the inside
// test, the spot walk's truncation and the mirror images of the reflection
// variant. What every shape shares is plain data here: the bounding box, the
// circular (or slit) outlet over which particles leave, the exit plane.
#ifndef GF_GEOM_CONTAINER_H
#define GF_GEOM_CONTAINER_H

#include <math.h>
#include <stdbool.h>

#include "granflow/config.h"

/// Most wall elements a point can be near at once (box: 4 sides + base;
/// cylinder: wall, funnel or rim, pipe, column side, bottom or edge).
#define GF_WALL_HITS 6

/// One wall element near a point: its signed distance (negative beyond the
/// wall) and the unit normal pointing from the wall into the container.
typedef struct gf_wall_hit {
    double gap;
    double n[3];
    bool side; ///< a side wall (spots are truncated at it and reflected in it), not a base, rim or edge
} gf_wall_hit;

typedef struct gf_container gf_container;

/// The functions that make a shape.
typedef struct gf_shape_ops {
    /// The wall elements closer than `reach` to p (at most GF_WALL_HITS); returns their number.
    int (*walls)(const gf_container *c, const double p[3], double reach, gf_wall_hit *hit);
    /// Relaxation push of the walls on a sphere of radius r at p (SPEC 1.3: a
    /// sphere closer than r to a wall moves away from it by alpha (r - gap)); adds to d.
    void (*push)(const gf_container *c, double x, double y, double z, double r, double alpha, double *dx,
                 double *dy, double *dz);
    /// True when a sphere of radius r at p is inside (tol: slack allowed).
    bool (*contains)(const gf_container *c, double x, double y, double z, double r, double tol);
    /// Spot walk truncation above the base (z >= 0): moves candidate n to
    /// at least dw from every side wall (2009 paper Sec. 2, d_w).
    void (*spot_clamp)(const gf_container *c, double n[3], double dw);
    /// Mirror images of a ball of radius rs centred at c in the side walls it
    /// crosses (2009 paper Sec. 4); returns their number (<= GF_WALL_HITS).
    int (*mirrors)(const gf_container *c, const double ctr[3], double rs, double m[][3]);
    /// True when a sphere of radius r centred at (x, y), high in the container,
    /// clears the side walls (re-insertion on the free surface).
    bool (*inside_xy)(const gf_container *c, double x, double y, double r);
    /// Lowest height of the centre of a sphere of radius r resting on the floor at (x, y).
    double (*floor_z)(const gf_container *c, double x, double y, double r);
    /// Area of the horizontal cross-section of the inside at height z, d^2.
    double (*section_area)(const gf_container *c, double z);
} gf_shape_ops;

struct gf_container {
    const gf_shape_ops *ops;
    gf_container_shape kind;
    double xlo, xhi, ylo, yhi; ///< side walls (box) or bounding box (cylinder)
    gf_orifice_shape shape;    ///< the outlet: circle or slit (a cylinder's is a circle)
    double hole;               ///< outlet radius (circle) or half-width (slit)
    double ox, oy;             ///< outlet centre (circle) or mid-line x = ox (slit); 0 for a cylinder
    double exit_z;             ///< exit plane: a centre below this (over the outlet) has left
    // Cylinder (cylinder.c): wall radius, outlet radius, column radius, funnel.
    double radius, r_out, r_in;
    double z_top;              ///< top of the funnel (0 for a flat base); the column ends here
    double pipe;               ///< length of the outlet pipe below z = 0
    double sin_a, cos_a;       ///< funnel angle to the horizontal
    double cone_len;           ///< length of the funnel's slant, rim to wall
    // Mesh (meshshape.c): the loaded walls, shared by every copy (NULL: none could be read).
    const struct gf_meshshape *mesh;
};

extern const gf_shape_ops gf_box_ops;
extern const gf_shape_ops gf_cylinder_ops;

/// Container of `cfg` (validated: SPEC 1.1, docs/geometry.md).
gf_container gf_container_make(const gf_config *cfg);

/// True when (x, y) lies over the outlet (the hole in the base).
static inline bool gf_container_over_hole(const gf_container *c, double x, double y)
{
    double dx = x - c->ox, dy = y - c->oy;
    if (c->shape == GF_ORIFICE_SLIT) return fabs(dx) < c->hole;
    return dx * dx + dy * dy < c->hole * c->hole;
}

/// True when a centre at (x, y, z) has left through the outlet.
static inline bool gf_container_exited(const gf_container *c, double x, double y, double z)
{
    return z < c->exit_z && gf_container_over_hole(c, x, y);
}

static inline int gf_container_walls(const gf_container *c, const double p[3], double reach, gf_wall_hit *hit)
{
    return c->ops->walls(c, p, reach, hit);
}

/// The wall push of the container's shape: one out-of-line call per sphere
/// from relax(), as before there were shapes (of the ways tried, the one
/// that adds least to the box's hot loop, docs/geometry.md); it jumps on to
/// the shape's push.
void gf_container_push(const gf_container *c, double x, double y, double z, double r, double alpha, double *dx,
                       double *dy, double *dz);

static inline bool gf_container_contains(const gf_container *c, double x, double y, double z, double r, double tol)
{
    return c->ops->contains(c, x, y, z, r, tol);
}

/// Bounding box of the container's inside: x, y of the walls, z from below
/// the exit plane to `ztop`.
void gf_container_bounds(const gf_container *c, double ztop, double lo[3], double hi[3]);

/// Helpers for shapes: push and mirrors from the wall elements of walls().
void gf_container_push_walls(const gf_container *c, double x, double y, double z, double r, double alpha,
                             double *dx, double *dy, double *dz);
int gf_container_mirror_walls(const gf_container *c, const double ctr[3], double rs, double m[][3]);

/// Bounding rectangle of the container's horizontal cross-section.
void gf_container_bounds_xy(const gf_container *c, double lo[2], double hi[2]);

/// True when a sphere of radius r centred at (x, y) at the top of the
/// container clears the side walls (re-insertion on the free surface asks
/// this of every position it tries; a new shape answers for its own walls).
static inline bool gf_container_inside_xy(const gf_container *c, double x, double y, double r)
{
    return c->ops->inside_xy(c, x, y, r);
}

/// Lowest height the centre of a sphere of radius r at (x, y) can have on
/// the container's floor (the flat base: r; a funnel: above its surface).
static inline double gf_container_floor_z(const gf_container *c, double x, double y, double r)
{
    return c->ops->floor_z(c, x, y, r);
}

/// Radius from the axis x = y = 0 that encloses the cross-section (the
/// cylinder's wall; the box's corners).
double gf_container_outer_radius(const gf_container *c);

/// Volume of the inside between the heights z0 < z1, d^3: the
/// cross-sections integrated (a slice of the packing: its packing fraction).
double gf_container_slice_volume(const gf_container *c, double z0, double z1);

#endif
