// SPDX-License-Identifier: MIT
// The box (SPEC 1.1; 2009 paper Sec. 2: walls x = +-25, y = +-4, base z = 0
// with a circular or slit orifice, centred at container.orifice_x, orifice_y).
#include "geom/container.h"
#include "geom/mesh.h"

static int gf_box_walls(const gf_container *c, const double p[3], double reach, gf_wall_hit *hit)
{
    int n = 0;
    const double side[4][4] = {{p[0] - c->xlo, 1, 0, 0}, {c->xhi - p[0], -1, 0, 0},
                               {p[1] - c->ylo, 0, 1, 0}, {c->yhi - p[1], 0, -1, 0}};
    for (int k = 0; k < 4; k++)
        if (side[k][0] < reach) hit[n++] = (gf_wall_hit){side[k][0], {side[k][1], side[k][2], side[k][3]}, true};
    if (p[2] >= reach) return n;
    if (!gf_container_over_hole(c, p[0], p[1])) {
        hit[n++] = (gf_wall_hit){p[2], {0, 0, 1}, false}; // the base plate
        return n;
    }
    // Over the hole: the nearest plate point is on the rim (a circle or the two slit edges).
    double ex, ey, qx = p[0] - c->ox, qy = p[1] - c->oy; // q: from the outlet centre
    if (c->shape == GF_ORIFICE_SLIT) {
        ex = qx >= 0 ? qx - c->hole : qx + c->hole;
        ey = 0.0;
    } else {
        double rho = sqrt(qx * qx + qy * qy);
        if (rho <= 0.0) return n;
        double s = (rho - c->hole) / rho;
        ex = qx * s;
        ey = qy * s;
    }
    double dist = sqrt(ex * ex + ey * ey + p[2] * p[2]);
    if (dist < reach && dist > 0.0) hit[n++] = (gf_wall_hit){dist, {ex / dist, ey / dist, p[2] / dist}, false};
    return n;
}

static void gf_box_push(const gf_container *c, double x, double y, double z, double r, double alpha, double *dx,
                        double *dy, double *dz)
{
    double g;
    if ((g = x - c->xlo) < r) *dx += alpha * (r - g);
    if ((g = c->xhi - x) < r) *dx -= alpha * (r - g);
    if ((g = y - c->ylo) < r) *dy += alpha * (r - g);
    if ((g = c->yhi - y) < r) *dy -= alpha * (r - g);
    if (z >= r) return;
    if (!gf_container_over_hole(c, x, y)) {
        if (z > -r) *dz += alpha * (r - z); // on the plate (a centre under it is left to the side walls)
        return;
    }
    // Over the hole: the nearest plate point is on the rim (a circle or the two slit edges).
    double ex, ey; // horizontal vector from the rim point to the centre
    double qx = x - c->ox, qy = y - c->oy; // from the outlet centre
    if (c->shape == GF_ORIFICE_SLIT) {
        ex = qx >= 0 ? qx - c->hole : qx + c->hole;
        ey = 0.0;
    } else {
        double rho = sqrt(qx * qx + qy * qy);
        if (rho <= 0.0) return; // the rim is a full hole radius away
        double s = (rho - c->hole) / rho;
        ex = qx * s;
        ey = qy * s;
    }
    double dist = sqrt(ex * ex + ey * ey + z * z);
    if (dist >= r || dist <= 0.0) return;
    double f = alpha * (r - dist) / dist;
    *dx += f * ex;
    *dy += f * ey;
    *dz += f * z;
}

static bool gf_box_contains(const gf_container *c, double x, double y, double z, double r, double tol)
{
    if (x < c->xlo + r - tol || x > c->xhi - r + tol) return false;
    if (y < c->ylo + r - tol || y > c->yhi - r + tol) return false;
    return z >= r - tol || gf_container_over_hole(c, x, y);
}

static double gf_clamp(double v, double lo, double hi) { return v < lo ? lo : (v > hi ? hi : v); }

static void gf_box_spot_clamp(const gf_container *c, double n[3], double dw)
{
    n[0] = gf_clamp(n[0], c->xlo + dw, c->xhi - dw);
    n[1] = gf_clamp(n[1], c->ylo + dw, c->yhi - dw);
}

static int gf_box_mirrors(const gf_container *c, const double ctr[3], double rs, double m[][3])
{
    int n = 0;
    const double walls[4] = {c->xlo, c->xhi, c->ylo, c->yhi};
    for (int w = 0; w < 4; w++) {
        int axis = w / 2;
        if (fabs(ctr[axis] - walls[w]) >= rs) continue;
        m[n][0] = ctr[0];
        m[n][1] = ctr[1];
        m[n][2] = ctr[2];
        m[n][axis] = 2.0 * walls[w] - ctr[axis];
        n++;
    }
    return n;
}

static bool gf_box_inside_xy(const gf_container *c, double x, double y, double r)
{
    return x >= c->xlo + r && x <= c->xhi - r && y >= c->ylo + r && y <= c->yhi - r;
}

static double gf_box_floor_z(const gf_container *c, double x, double y, double r)
{
    (void)c;
    (void)x;
    (void)y;
    return r;
}

static double gf_box_section_area(const gf_container *c, double z)
{
    (void)z;
    return (c->xhi - c->xlo) * (c->yhi - c->ylo);
}

static double gf_box_slice_volume(const gf_container *c, double z0, double z1)
{
    return (z1 - z0) * (c->xhi - c->xlo) * (c->yhi - c->ylo);
}

static bool gf_box_clear(const gf_container *c, double x, double y, double z, double m)
{
    return x >= c->xlo + m && x <= c->xhi - m && y >= c->ylo + m && y <= c->yhi - m && z >= m;
}

static void gf_box_radii(const gf_container *c, double r[2])
{
    r[0] = 0.0;
    r[1] = hypot(fmax(-c->xlo, c->xhi), fmax(-c->ylo, c->yhi));
}

static gf_profile_coord gf_box_profile(const gf_container *c)
{
    (void)c;
    return GF_PROFILE_X;
}

// The inside only: the panel draws the walls and the base with its hole
// around it (gf_container_rectangular).
static void gf_box_outline(const gf_container *c, double ztop, gf_outline *o)
{
    const double p[4][2] = {{c->xlo, 0.0}, {c->xhi, 0.0}, {c->xhi, ztop}, {c->xlo, ztop}};
    for (int k = 0; k < 4; k++) {
        o->p[k][0] = p[k][0];
        o->p[k][1] = p[k][1];
    }
    o->n = 4;
}

// Four planes; the base comes in the drain stage (gf_box_lammps_base).
static gf_status gf_box_lammps_walls(const gf_container *c, FILE *f, const char *pre, const char *law, double zlo,
                                double zhi)
{
    if (!f) return GF_OK; // LAMMPS holds these walls
    (void)pre;
    (void)zlo;
    (void)zhi;
    fprintf(f,
            "fix wall_x flow wall/gran hertz/history %s xplane %.10g %.10g\n"
            "fix wall_y flow wall/gran hertz/history %s yplane %.10g %.10g\n",
            law, c->xlo, c->xhi, law, c->ylo, c->yhi);
    return GF_OK;
}

static void gf_box_lammps_base(const gf_container *c, FILE *f, const char *law, double zlo)
{
    fprintf(f, "# the base with its hole: the surface of (z > 0) united with the hole below it\n"
               "region above block INF INF INF INF 0 INF units box\n");
    const double R = c->hole, ox = c->ox, oy = c->oy; // the orifice centre
    if (c->shape == GF_ORIFICE_SLIT)
        fprintf(f, "region hole block %.10g %.10g INF INF %.10g 1 units box\n", ox - R, ox + R, zlo);
    else
        fprintf(f, "region hole cylinder z %.10g %.10g %.10g %.10g 1 units box\n", ox, oy, R, zlo);
    fprintf(f, "region vessel union 2 above hole\n"
               "fix base flow wall/gran/region hertz/history %s region vessel\n",
            law);
}

static gf_status gf_box_lammps_pour(const gf_container *c, FILE *f, double inset, double zlo, double zhi)
{
    if (f)
        fprintf(f, "region pour block %.10g %.10g %.10g %.10g %.10g %.10g units box\n", c->xlo + inset,
                c->xhi - inset, c->ylo + inset, c->yhi - inset, zlo, zhi);
    return GF_OK;
}

static int gf_box_describe(const gf_container *c, const char *const where[3], char *buf, size_t n)
{
    return snprintf(buf, n, "container %g x %g d (width: %s; depth: %s), orifice %g d (%s)", c->xhi - c->xlo,
                    c->yhi - c->ylo, where[0], where[1], 2.0 * c->hole, where[2]);
}

static const char *gf_box_outlet_name(const gf_container *c)
{
    (void)c;
    return "orifice";
}

const gf_shape_ops gf_box_ops = {
    .walls = gf_box_walls,
    .push = gf_box_push,
    .contains = gf_box_contains,
    .spot_clamp = gf_box_spot_clamp,
    .mirrors = gf_box_mirrors,
    .inside_xy = gf_box_inside_xy,
    .floor_z = gf_box_floor_z,
    .section_area = gf_box_section_area,
    .slice_volume = gf_box_slice_volume,
    .clear = gf_box_clear,
    .radii = gf_box_radii,
    .profile = gf_box_profile,
    .outline = gf_box_outline,
    .mesh = gf_mesh_box,
    .lammps_walls = gf_box_lammps_walls,
    .lammps_base = gf_box_lammps_base,
    .lammps_pour = gf_box_lammps_pour,
    .describe = gf_box_describe,
    .outlet_name = gf_box_outlet_name,
};

static const char *const gf_box_keys[] = {"container.width",    "container.depth",    "container.orifice_diameter",
                                          "container.orifice_shape", "container.orifice_x", "container.orifice_y",
                                          NULL};

const gf_shape gf_box_shape = {
    .name = "box",
    .id = GF_SHAPE_BOX,
    .ops = &gf_box_ops,
    .keys = gf_box_keys,
    .make = NULL, // the shared fields are the whole box
    .rectangular = true,
};
