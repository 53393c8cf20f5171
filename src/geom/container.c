// SPDX-License-Identifier: MIT
// The silo geometry of SPEC 1.1 (2009 paper Sec. 2: walls x = +-25, y = +-4, base z = 0).
#include "geom/container.h"

gf_container gf_container_make(const gf_config *cfg)
{
    gf_container c = {
        .xlo = -0.5 * cfg->container_width,
        .xhi = 0.5 * cfg->container_width,
        .ylo = -0.5 * cfg->container_depth,
        .yhi = 0.5 * cfg->container_depth,
        .shape = cfg->orifice_shape,
        .hole = 0.5 * cfg->orifice_diameter,
        .exit_z = cfg->exit_z,
    };
    return c;
}

void gf_container_push(const gf_container *c, double x, double y, double z, double r, double alpha,
                       double *dx, double *dy, double *dz)
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
    if (c->shape == GF_ORIFICE_SLIT) {
        ex = x >= 0 ? x - c->hole : x + c->hole;
        ey = 0.0;
    } else {
        double rho = sqrt(x * x + y * y);
        if (rho <= 0.0) return; // the rim is a full hole radius away
        double s = (rho - c->hole) / rho;
        ex = x * s;
        ey = y * s;
    }
    double dist = sqrt(ex * ex + ey * ey + z * z);
    if (dist >= r || dist <= 0.0) return;
    double f = alpha * (r - dist) / dist;
    *dx += f * ex;
    *dy += f * ey;
    *dz += f * z;
}

bool gf_container_contains(const gf_container *c, double x, double y, double z, double r, double tol)
{
    if (x < c->xlo + r - tol || x > c->xhi - r + tol) return false;
    if (y < c->ylo + r - tol || y > c->yhi - r + tol) return false;
    return z >= r - tol || gf_container_over_hole(c, x, y);
}

void gf_container_bounds_xy(const gf_container *c, double lo[2], double hi[2])
{
    lo[0] = c->xlo;
    lo[1] = c->ylo;
    hi[0] = c->xhi;
    hi[1] = c->yhi;
}

bool gf_container_inside_xy(const gf_container *c, double x, double y, double r)
{
    return x >= c->xlo + r && x <= c->xhi - r && y >= c->ylo + r && y <= c->yhi - r;
}

double gf_container_floor_z(const gf_container *c, double x, double y, double r)
{
    (void)c;
    (void)x;
    (void)y;
    return r;
}
