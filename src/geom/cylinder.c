// SPDX-License-Identifier: MIT
// The cylinder: a wall at radius R about the z axis, a conical funnel at
// angle a to the horizontal from the wall down to the outlet of radius r_o at
// z = 0 (a = 0: a flat base with a circular hole), a straight pipe of radius
// r_o below it, and optionally a solid central column of radius r_i down to
// the top of the funnel (2006 pebble-bed paper, Rycroft et al., PRE 74
// 021306, Sec. II: cylinder, 30 or 60 degree funnel, outlet pipe; the
// annular core). In the (rho, z) half-plane every wall is a segment; each
// segment reports the points whose nearest point on it is interior, and each
// convex edge (the outlet rim, the column's bottom rim) is reported once.
#include "geom/container.h"

// Unit vector along (x, y) (the x axis at rho = 0) and rho.
static double gf_cyl_radial(double x, double y, double *ux, double *uy)
{
    double rho = sqrt(x * x + y * y);
    if (rho > 0.0) {
        *ux = x / rho;
        *uy = y / rho;
    } else {
        *ux = 1.0;
        *uy = 0.0;
    }
    return rho;
}

static int gf_cyl_walls(const gf_container *c, const double p[3], double reach, gf_wall_hit *hit)
{
    int n = 0;
    double ux, uy, z = p[2];
    double rho = gf_cyl_radial(p[0], p[1], &ux, &uy);
    double R = c->radius, ro = c->r_out;
    // The outer wall, above the funnel.
    if (z >= c->z_top && R - rho < reach) hit[n++] = (gf_wall_hit){R - rho, {-ux, -uy, 0.0}, true};
    // The funnel (the base plate when flat): t along it from the rim, s off it.
    double t = (rho - ro) * c->cos_a + z * c->sin_a;
    double s = z * c->cos_a - (rho - ro) * c->sin_a;
    if (t >= 0.0 && t <= c->cone_len) {
        if (s < reach) hit[n++] = (gf_wall_hit){s, {-c->sin_a * ux, -c->sin_a * uy, c->cos_a}, c->sin_a > 0.0};
    } else if (t < 0.0 && rho < ro && (c->pipe <= 0.0 || z > 0.0)) {
        // The rim of the outlet, a convex edge (the pipe takes over below it).
        double er = rho - ro, d = sqrt(er * er + z * z);
        if (d < reach && d > 0.0) hit[n++] = (gf_wall_hit){d, {er / d * ux, er / d * uy, z / d}, false};
    }
    // The outlet pipe.
    if (c->pipe > 0.0 && z <= 0.0 && z >= -c->pipe && ro - rho < reach)
        hit[n++] = (gf_wall_hit){ro - rho, {-ux, -uy, 0.0}, true};
    // The central column: its side, its flat bottom at z_top, the rim between.
    if (c->r_in > 0.0) {
        double ri = c->r_in, zb = c->z_top;
        if (z >= zb) {
            if (rho - ri < reach) hit[n++] = (gf_wall_hit){rho - ri, {ux, uy, 0.0}, true};
        } else if (rho <= ri) {
            if (zb - z < reach) hit[n++] = (gf_wall_hit){zb - z, {0.0, 0.0, -1.0}, false};
        } else {
            double er = rho - ri, ez = z - zb, d = sqrt(er * er + ez * ez);
            if (d < reach) hit[n++] = (gf_wall_hit){d, {er / d * ux, er / d * uy, ez / d}, false};
        }
    }
    return n;
}

static void gf_cyl_push(const gf_container *c, double x, double y, double z, double r, double alpha, double *dx,
                        double *dy, double *dz)
{
    // Most spheres are in the bulk, above the funnel and clear of the walls.
    double rho2 = x * x + y * y, ro = c->radius - r, ri = c->r_in + r;
    if (z >= c->z_top + r && rho2 < ro * ro && (c->r_in <= 0.0 || rho2 > ri * ri)) return;
    gf_container_push_walls(c, x, y, z, r, alpha, dx, dy, dz);
}

static bool gf_cyl_contains(const gf_container *c, double x, double y, double z, double r, double tol)
{
    double ux, uy, m = r - tol;
    double rho = gf_cyl_radial(x, y, &ux, &uy);
    double ro = c->r_out;
    if (rho > c->radius - m) return false;
    if (c->r_in > 0.0) { // distance from (rho, z) to the column's section
        double er = fmax(0.0, rho - c->r_in), ez = fmax(0.0, c->z_top - z);
        if (er * er + ez * ez < m * m || (er == 0.0 && ez == 0.0)) return false;
    }
    double t = (rho - ro) * c->cos_a + z * c->sin_a;
    double s = z * c->cos_a - (rho - ro) * c->sin_a;
    if (t >= 0.0 && t <= c->cone_len) return s >= m || (rho < ro && z < m); // over the outlet: anywhere
    if (t < 0.0) {
        if (rho >= ro) return false; // under the base, off the outlet
        if (c->pipe > 0.0 && z <= 0.0 && z >= -c->pipe) return rho <= ro - m;
    }
    return true;
}

static void gf_cyl_spot_clamp(const gf_container *c, double n[3], double dw)
{
    if (n[2] < 0.0) return; // below the outlet the walk keeps over the birth disc (the caller)
    double ux, uy;
    double rho = gf_cyl_radial(n[0], n[1], &ux, &uy);
    double rmax = c->radius - dw, rmin = 0.0;
    if (c->sin_a > 0.0 && n[2] < c->z_top) // d_w from the funnel, measured square to it
        rmax = fmin(rmax, c->r_out + n[2] * c->cos_a / c->sin_a - dw / c->sin_a);
    if (c->r_in > 0.0 && n[2] > c->z_top - dw) rmin = c->r_in + dw; // beside the column, or deflected round it
    if (rmax < 0.0) rmax = 0.0;
    if (rmin > rmax) rmin = rmax;
    double to = rho > rmax ? rmax : (rho < rmin ? rmin : rho);
    if (to == rho) return;
    n[0] = to * ux;
    n[1] = to * uy;
}

// Clear of the wall and, high up, of the column beside which it falls.
static bool gf_cyl_inside_xy(const gf_container *c, double x, double y, double r)
{
    double rho = sqrt(x * x + y * y);
    return rho <= c->radius - r && (c->r_in <= 0.0 || rho >= c->r_in + r);
}

// On the funnel (the flat base when a = 0) at distance r from it, measured
// square to it: s = z cos a - (rho - r_o) sin a = r; over the outlet, the
// plane z = r as for the box.
static double gf_cyl_floor_z(const gf_container *c, double x, double y, double r)
{
    double rho = sqrt(x * x + y * y);
    if (rho <= c->r_out || c->cos_a <= 0.0) return r;
    return (r + (rho - c->r_out) * c->sin_a) / c->cos_a;
}

// The disc inside the wall, or inside the funnel below its top (radius
// r_o + z / tan a), less the column above the funnel; the pipe below z = 0.
static double gf_cyl_section_area(const gf_container *c, double z)
{
    double ro = z < 0.0 ? c->r_out : c->radius;
    if (z < c->z_top && c->sin_a > 0.0) ro = fmin(ro, c->r_out + z * c->cos_a / c->sin_a);
    double ri = z >= c->z_top ? c->r_in : 0.0;
    return 3.14159265358979323846 * (ro * ro - ri * ri);
}

const gf_shape_ops gf_cylinder_ops = {
    .walls = gf_cyl_walls,
    .push = gf_cyl_push,
    .contains = gf_cyl_contains,
    .spot_clamp = gf_cyl_spot_clamp,
    .mirrors = gf_container_mirror_walls,
    .inside_xy = gf_cyl_inside_xy,
    .floor_z = gf_cyl_floor_z,
    .section_area = gf_cyl_section_area,
};
