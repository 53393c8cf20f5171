// SPDX-License-Identifier: MIT
// The container of a configuration, and what shapes share (docs/geometry.md).
#include "geom/container.h"

#include "geom/meshshape.h"

static const double gf_deg = 3.14159265358979323846 / 180.0;

gf_container gf_container_make(const gf_config *cfg)
{
    gf_container c = {
        .ops = &gf_box_ops,
        .kind = cfg->container_shape,
        .xlo = -0.5 * cfg->container_width,
        .xhi = 0.5 * cfg->container_width,
        .ylo = -0.5 * cfg->container_depth,
        .yhi = 0.5 * cfg->container_depth,
        .shape = cfg->orifice_shape,
        .hole = 0.5 * cfg->orifice_diameter,
        .ox = cfg->orifice_x,
        .oy = cfg->orifice_y,
        .exit_z = gf_config_exit_plane(cfg),
    };
    if (cfg->container_shape == GF_SHAPE_CYLINDER) {
        double R = cfg->container_radius, ro = 0.5 * cfg->outlet_diameter, a = cfg->hopper_angle * gf_deg;
        c.ops = &gf_cylinder_ops;
        c.xlo = c.ylo = -R;
        c.xhi = c.yhi = R;
        c.shape = GF_ORIFICE_CIRCLE;
        c.hole = ro;
        c.ox = c.oy = 0.0; // on the axis (validation rejects an off-centre outlet)
        c.radius = R;
        c.r_out = ro;
        c.r_in = cfg->inner_radius;
        c.pipe = cfg->outlet_length;
        c.sin_a = cfg->hopper_angle > 0.0 ? sin(a) : 0.0;
        c.cos_a = cfg->hopper_angle > 0.0 ? cos(a) : 1.0;
        c.z_top = (R - ro) * c.sin_a / c.cos_a;
        c.cone_len = (R - ro) / c.cos_a;
    }
    if (cfg->container_shape == GF_SHAPE_MESH) gf_meshshape_fill(&c, cfg); // the outlet: the orifice keys'
    return c;
}

void gf_container_push(const gf_container *c, double x, double y, double z, double r, double alpha, double *dx,
                       double *dy, double *dz)
{
    c->ops->push(c, x, y, z, r, alpha, dx, dy, dz);
}

void gf_container_bounds(const gf_container *c, double ztop, double lo[3], double hi[3])
{
    lo[0] = c->xlo;
    lo[1] = c->ylo;
    lo[2] = fmin(0.0, c->exit_z) - 1.0;
    hi[0] = c->xhi;
    hi[1] = c->yhi;
    hi[2] = ztop;
}

void gf_container_push_walls(const gf_container *c, double x, double y, double z, double r, double alpha,
                             double *dx, double *dy, double *dz)
{
    gf_wall_hit hit[GF_WALL_HITS];
    const double p[3] = {x, y, z};
    int n = c->ops->walls(c, p, r, hit);
    for (int k = 0; k < n; k++) {
        double f = alpha * (r - hit[k].gap);
        *dx += f * hit[k].n[0];
        *dy += f * hit[k].n[1];
        *dz += f * hit[k].n[2];
    }
}

int gf_container_mirror_walls(const gf_container *c, const double ctr[3], double rs, double m[][3])
{
    gf_wall_hit hit[GF_WALL_HITS];
    int n = c->ops->walls(c, ctr, rs, hit), k = 0;
    for (int h = 0; h < n; h++) {
        if (!hit[h].side || hit[h].gap <= -rs) continue;
        for (int a = 0; a < 3; a++) m[k][a] = ctr[a] - 2.0 * hit[h].gap * hit[h].n[a];
        k++;
    }
    return k;
}

void gf_container_bounds_xy(const gf_container *c, double lo[2], double hi[2])
{
    lo[0] = c->xlo;
    lo[1] = c->ylo;
    hi[0] = c->xhi;
    hi[1] = c->yhi;
}

double gf_container_outer_radius(const gf_container *c)
{
    if (c->kind == GF_SHAPE_CYLINDER) return c->radius;
    return hypot(fmax(-c->xlo, c->xhi), fmax(-c->ylo, c->yhi));
}

double gf_container_slice_volume(const gf_container *c, double z0, double z1)
{
    // Midpoint rule on 256 layers: exact for the box, within ~1e-5 for a funnel.
    const int n = 256;
    double h = (z1 - z0) / n, v = 0.0;
    for (int k = 0; k < n; k++) v += c->ops->section_area(c, z0 + (k + 0.5) * h);
    return v * h;
}
