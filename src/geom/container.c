// SPDX-License-Identifier: MIT
// The container of a configuration, and what shapes share (docs/geometry.md).
#include "geom/container.h"

gf_container gf_container_make(const gf_config *cfg)
{
    gf_container_defs d;
    gf_config_container_defs(cfg, &d);
    return gf_container_build(&d);
}

gf_container gf_container_build(const gf_container_defs *d)
{
    const gf_shape *t = gf_shape_find(d->shape);
    gf_container c = {
        .ops = t ? t->ops : &gf_box_ops,
        .type = t,
        .xlo = -0.5 * d->width,
        .xhi = 0.5 * d->width,
        .ylo = -0.5 * d->depth,
        .yhi = 0.5 * d->depth,
        .shape = d->orifice.shape,
        .hole = 0.5 * d->orifice.diameter,
        .ox = d->orifice.x,
        .oy = d->orifice.y,
        .z_exit = d->exit_plane,
    };
    if (t && t->make) t->make(&c, d);
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
    lo[2] = fmin(0.0, c->z_exit) - 1.0;
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
    double r[2];
    c->ops->radii(c, r);
    return r[1];
}

double gf_container_inner_radius(const gf_container *c)
{
    double r[2];
    c->ops->radii(c, r);
    return r[0];
}

double gf_container_slice_volume(const gf_container *c, double z0, double z1)
{
    return c->ops->slice_volume(c, z0, z1);
}

double gf_container_slice_volume_by_sections(const gf_container *c, double z0, double z1)
{
    // Midpoint rule on 256 layers: exact for a prism, within ~1e-5 for a funnel.
    const int n = 256;
    double h = (z1 - z0) / n, v = 0.0;
    for (int k = 0; k < n; k++) v += c->ops->section_area(c, z0 + (k + 0.5) * h);
    return v * h;
}

void gf_container_outline(const gf_container *c, double ztop, gf_outline *o)
{
    *o = (gf_outline){0};
    c->ops->outline(c, ztop, o);
}

void gf_container_bulk(const gf_container *c, double top, gf_bulk_region *b)
{
    // Curved walls order the first layers: the ring 2-3 d from a cylinder's
    // wall is denser than the bulk by ~0.05 (docs/geometry.md), so a radial
    // container keeps 3 d from its walls, a flat-walled one 2 d.
    *b = (gf_bulk_region){0};
    b->lo[2] = c->z_col + 2.0;
    b->hi[2] = top - 3.0;
    if (gf_container_profile_radial(c)) {
        double r[2];
        c->ops->radii(c, r);
        b->annulus = true;
        b->r0 = r[0] > 0.0 ? r[0] + 3.0 : 0.0;
        b->r1 = r[1] - 3.0;
        b->lo[0] = b->lo[1] = -r[1];
        b->hi[0] = b->hi[1] = r[1];
        return;
    }
    b->lo[0] = c->xlo + 2;
    b->hi[0] = c->xhi - 2;
    b->lo[1] = c->ylo + 2;
    b->hi[1] = c->yhi - 2;
}

gf_status gf_container_lammps_walls(const gf_container *c, FILE *f, const char *pre, const char *law, double zlo,
                               double zhi)
{
    return c->ops->lammps_walls(c, f, pre, law, zlo, zhi);
}

void gf_container_lammps_base(const gf_container *c, FILE *f, const char *law, double zlo)
{
    c->ops->lammps_base(c, f, law, zlo);
}

gf_status gf_container_lammps_pour(const gf_container *c, FILE *f, double inset, double zlo, double zhi)
{
    return c->ops->lammps_pour(c, f, inset, zlo, zhi);
}

void gf_container_describe(const gf_container *c, const gf_config *cfg, char *buf, size_t n)
{
    char w[3][GF_PATH_MAX + 32];
    const char *where[3];
    for (int k = 0; k < 3; k++) {
        const char *key = c->type && c->type->keys ? c->type->keys[k] : NULL;
        w[k][0] = 0;
        if (key) gf_config_where(cfg, key, w[k], sizeof w[k]);
        where[k] = w[k];
    }
    if (n) buf[0] = 0;
    c->ops->describe(c, where, buf, n);
}
