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
#include <stddef.h>
#include <stdio.h>

#include "granflow/config.h"
#include "granflow/defs.h"

/// Most wall elements a point can be near at once (box: 4 sides + base;
/// cylinder: wall, funnel or rim, pipe, column side, bottom or edge; wedge:
/// 2 flat sides, then per inclined side its wall, slope or rim, and chute).
#define GF_WALL_HITS 8

/// One wall element near a point: its signed distance (negative beyond the
/// wall) and the unit normal pointing from the wall into the container.
typedef struct gf_wall_hit {
    double gap;
    double n[3];
    bool side; ///< a side wall (spots are truncated at it and reflected in it), not a base, rim or edge
} gf_wall_hit;

typedef struct gf_container gf_container;
struct gf_mesh;

/// The coordinate a shape's velocity profiles and diffusion are measured in
/// (docs/analysis.md): x across the container, or r from the axis x = y = 0.
typedef enum gf_profile_coord {
    GF_PROFILE_X = 0,
    GF_PROFILE_R = 1,
} gf_profile_coord;

/// Most points of one polyline of an outline (a mesh's slice, simplified, may need more than the analytic shapes).
#define GF_OUTLINE_MAX 32

/// The container cut by the plane y = 0, seen from -y, for pictures
/// (render/panel.c): the inside as one polygon in (x, z), the walls as up to
/// two polylines drawn thick over it, and a solid part (a column) filled in
/// the wall colour. Points above `ztop` are clamped to it by the shape.
typedef struct gf_outline {
    int n;                                   ///< points of the inside polygon (closed)
    double p[GF_OUTLINE_MAX][2];
    int nwall[2];                            ///< points of each wall polyline (0: none; the box draws none)
    double wall[2][GF_OUTLINE_MAX][2];
    int nsolid;                              ///< points of the solid polygon (0: none)
    double solid[GF_OUTLINE_MAX][2];
} gf_outline;

/// The region where the bulk packing fraction is measured
/// (gf_packing_bulk_fraction): a box lo..hi, or when `annulus` the ring
/// r0 <= rho < r1 about the z axis for lo[2] <= z < hi[2]. Empty when a
/// hi <= lo.
typedef struct gf_bulk_region {
    bool annulus;
    double lo[3], hi[3];
    double r0, r1;
} gf_bulk_region;

/// The functions that make a shape. Every one is required: nothing outside
/// src/geom/ asks which shape a container is, it asks the container (the
/// gf_container_* functions below call these).
typedef struct gf_shape_ops {
    // ---- the spot engine ----
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

    // ---- packing, analysis, pictures, DEM ----
    /// Volume of the inside between z0 < z1, d^3 (gf_container_slice_volume_by_sections
    /// integrates section_area; the box's is exact).
    double (*slice_volume)(const gf_container *c, double z0, double z1);
    /// A cheap test: true only when a sphere of radius m at p touches no wall
    /// (false is always safe; the packing generator skips walls() on true).
    bool (*clear)(const gf_container *c, double x, double y, double z, double m);
    /// The annulus about the z axis that holds the cross-section above the
    /// funnel: r[0] the inner edge (a column; 0 without), r[1] the outer
    /// (the wall, or the farthest corner).
    void (*radii)(const gf_container *c, double r[2]);
    /// The coordinate of its velocity profiles: x, or r about the axis.
    gf_profile_coord (*profile)(const gf_container *c);
    /// The slice y = 0 up to ztop, for pictures.
    void (*outline)(const gf_container *c, double ztop, gf_outline *o);
    /// The walls as triangles up to `top` (src/geom/mesh.c: gf_container_mesh), circles with `segments` edges.
    gf_status (*mesh)(const gf_container *c, double top, int segments, struct gf_mesh *m);
    /// LAMMPS commands of the walls `fix wall/gran` acts on in both stages of
    /// `granflow dem` (src/dem/lammps_input.c), regions named `pre`_*,
    /// contact law `law` (the wall/gran arguments), simulation box zlo..zhi.
    /// f = NULL: only whether LAMMPS can hold the walls (GF_ERR_PARAM and a
    /// message saying why not: a mesh's triangles).
    gf_status (*lammps_walls)(const gf_container *c, FILE *f, const char *pre, const char *law, double zlo, double zhi);
    /// LAMMPS commands of the base during drainage only (the box's plate with
    /// its hole; nothing when lammps_walls holds the whole vessel).
    void (*lammps_base)(const gf_container *c, FILE *f, const char *law, double zlo);
    /// `region pour ...`: the column's cross-section shrunk by `inset`
    /// between zlo and zhi, for fix pour. f = NULL: only whether pouring is
    /// possible (GF_ERR_PARAM and a message saying why not).
    gf_status (*lammps_pour)(const gf_container *c, FILE *f, double inset, double zlo, double zhi);
    /// One line describing the container for reports, with where each of
    /// the shape's first three keys (gf_shape.keys) was set: where[k].
    int (*describe)(const gf_container *c, const char *const where[3], char *buf, size_t n);
    /// What particles leave through, for messages ("orifice", "end of the outlet pipe").
    const char *(*outlet_name)(const gf_container *c);
} gf_shape_ops;

/// One row of the shape table (src/geom/shapes.c): a value of
/// `container.shape`, its functions, and the container.* keys it reads (the
/// first three describe it in reports; NULL-terminated).
typedef struct gf_shape {
    const char *name;            ///< the key's value, "box"
    gf_container_shape id;       ///< config's enum value of that name
    const gf_shape_ops *ops;
    const char *const *keys;     ///< e.g. {"container.width", "container.depth", ..., NULL}
    /// Fills the shape's parameters of c (c->u) from the container defs of
    /// a validated config; the shared fields are already set (bounding box
    /// from width and depth, outlet from the orifice keys, exit plane).
    void (*make)(gf_container *c, const gf_container_defs *d);
    /// True when its walls are the bounding box's sides and its floor the
    /// plane z = 0 (the box): code may then use the bounding box directly.
    bool rectangular;
    /// Checks the shape's own keys in the container defs `d` of `cfg` (while
    /// gf_config_validate runs: each key is in its range, nothing across
    /// keys is checked yet), and completes what it settles through config's
    /// setters (gf_config_set_extent, gf_config_set_orifice). Errors name
    /// file, line and key (gf_config_msg_make). NULL: nothing to check.
    gf_status (*validate)(const gf_container_defs *d, gf_config *cfg);
    /// The key that bounds a spot's room across the container, named when
    /// spot.wall_distance leaves none ("container.radius"); NULL: the smaller
    /// of container.width and container.depth.
    const char *wall_key;
} gf_shape;

/// The shape of a container.shape value; NULL for none.
const gf_shape *gf_shape_find(gf_container_shape id);

/// Adds a shape to the table (tests; a shape not built in). At most 4; false
/// when full. A row whose id is a built-in's stands in for it until removed
/// (a test's stand-in for container.shape = wedge, which config can parse).
bool gf_shape_register(const gf_shape *s);
/// Removes a shape gf_shape_register added; false when it is not there.
bool gf_shape_unregister(const gf_shape *s);

/// A cylinder's parameters (cylinder.c): wall radius, outlet radius, column
/// radius, pipe, funnel.
typedef struct gf_cylinder_params {
    double radius, r_out, r_in;
    double pipe;               ///< length of the outlet pipe below z = 0
    double sin_a, cos_a;       ///< funnel angle to the horizontal
    double angle;              ///< the same in degrees (container.hopper_angle)
    double cone_len;           ///< length of the funnel's slant, rim to wall
} gf_cylinder_params;

/// A wedge hopper's parameters (wedge.c). Side k = 0 is the left (x < the
/// slit), k = 1 the right; each inclined wall runs from the slit's edge
/// x = ox -+ hole at z = 0 up to its side wall x = xlo or xhi.
typedef struct gf_wedge_params {
    double sin_a, cos_a;       ///< wall angle to the horizontal
    double angle;              ///< the same in degrees (container.hopper_angle)
    double chute;              ///< length of the straight chute below z = 0
    double run[2];             ///< horizontal run of each inclined wall, slit edge to side wall
    double top[2];             ///< height where each meets its side wall
    double len[2];             ///< its slant length
} gf_wedge_params;

struct gf_container {
    const gf_shape_ops *ops;
    const gf_shape *type;      ///< its row of the shape table
    double xlo, xhi, ylo, yhi; ///< side walls (box) or bounding box
    gf_orifice_shape shape;    ///< the outlet: circle or slit (a cylinder's is a circle, a wedge's a slit)
    double hole;               ///< outlet radius (circle) or half-width (slit)
    double ox, oy;             ///< outlet centre (circle) or mid-line x = ox (slit); 0 for a cylinder
    double z_exit;             ///< exit plane: a centre below this (over the outlet) has left
    double z_col;              ///< where the straight column starts: the top of a funnel (0 for a flat base)
    double z_bottom;           ///< the lower end of the walls: -(pipe or chute length), 0 for a flat base
    double gate_z;             ///< where the outlet is closed while a packing is made (DEM fill)
    /// The shape's own parameters (its file reads its member).
    union {
        gf_cylinder_params cyl;
        gf_wedge_params wedge;
        const struct gf_meshshape *mesh; ///< a mesh's loaded walls (meshshape.c), shared by every copy; NULL: none
        unsigned char raw[128]; ///< room for a shape of another file (a test's; a mesh's handle)
    } u;
};

extern const gf_shape_ops gf_box_ops;
extern const gf_shape_ops gf_cylinder_ops;
extern const gf_shape_ops gf_wedge_ops;
extern const gf_shape gf_box_shape;
extern const gf_shape gf_cylinder_shape;
extern const gf_shape gf_wedge_shape;
extern const gf_shape gf_mesh_shape;

/// Container of `cfg` (validated: SPEC 1.1, docs/geometry.md). A
/// container.shape with no row in the table gets the box's walls and a
/// NULL `type` (validation refuses such a config first).
gf_container gf_container_make(const gf_config *cfg);
/// The same from the container defs (gf_config_container_defs): what it calls.
gf_container gf_container_build(const gf_container_defs *d);

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
    return z < c->z_exit && gf_container_over_hole(c, x, y);
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

/// Radius of a central column (0: none).
double gf_container_inner_radius(const gf_container *c);

/// Volume of the inside between the heights z0 < z1, d^3 (a slice of the
/// packing: its packing fraction).
double gf_container_slice_volume(const gf_container *c, double z0, double z1);

/// The cross-sections integrated by the midpoint rule on 256 layers (a shape's slice_volume).
double gf_container_slice_volume_by_sections(const gf_container *c, double z0, double z1);

/// Width of the cross-section along x, d (a box's width, a cylinder's diameter).
static inline double gf_container_width(const gf_container *c) { return c->xhi - c->xlo; }

/// True when velocity profiles in it are radial, v_z(r) about the axis.
static inline bool gf_container_profile_radial(const gf_container *c) { return c->ops->profile(c) == GF_PROFILE_R; }

/// True when its walls are the bounding box's sides and its floor z = 0 (see gf_shape.rectangular).
static inline bool gf_container_rectangular(const gf_container *c) { return !c->type || c->type->rectangular; }

/// The value of container.shape ("box").
static inline const char *gf_container_name(const gf_container *c) { return c->type ? c->type->name : "box"; }

/// True when container.`key` ("container.width") is one of the keys its shape reads.
bool gf_container_reads_key(const gf_container *c, const char *key);

/// True when a sphere of radius m at p certainly touches no wall.
static inline bool gf_container_clear(const gf_container *c, double x, double y, double z, double m)
{
    return c->ops->clear(c, x, y, z, m);
}

/// The slice y = 0 up to ztop, for pictures.
void gf_container_outline(const gf_container *c, double ztop, gf_outline *o);

/// The region of the bulk packing fraction (gf_packing_bulk_fraction): from
/// 2 d above the funnel (or base) to 3 d below `top`, 2 d inside flat walls
/// (the bounding box's), or for a radial shape the annulus 3 d inside its
/// radii (curved walls order the layers next to them further in).
void gf_container_bulk(const gf_container *c, double top, gf_bulk_region *b);

/// The LAMMPS walls of `granflow dem` (see gf_shape_ops).
gf_status gf_container_lammps_walls(const gf_container *c, FILE *f, const char *pre, const char *law, double zlo,
                               double zhi);
void gf_container_lammps_base(const gf_container *c, FILE *f, const char *law, double zlo);
gf_status gf_container_lammps_pour(const gf_container *c, FILE *f, double inset, double zlo, double zhi);

/// A line describing the container, with where its keys were set (cfg's origins).
void gf_container_describe(const gf_container *c, const gf_config *cfg, char *buf, size_t n);

/// What particles leave through ("orifice", "end of the outlet pipe"), for messages.
static inline const char *gf_container_outlet_name(const gf_container *c) { return c->ops->outlet_name(c); }

#endif
