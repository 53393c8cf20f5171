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
#include "geom/mesh.h"
#include "core/error.h"

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
    double R = c->u.cyl.radius, ro = c->u.cyl.r_out;
    // The outer wall, above the funnel.
    if (z >= c->z_col && R - rho < reach) hit[n++] = (gf_wall_hit){R - rho, {-ux, -uy, 0.0}, true};
    // The funnel (the base plate when flat): t along it from the rim, s off it.
    double t = (rho - ro) * c->u.cyl.cos_a + z * c->u.cyl.sin_a;
    double s = z * c->u.cyl.cos_a - (rho - ro) * c->u.cyl.sin_a;
    if (t >= 0.0 && t <= c->u.cyl.cone_len) {
        if (s < reach) hit[n++] = (gf_wall_hit){s, {-c->u.cyl.sin_a * ux, -c->u.cyl.sin_a * uy, c->u.cyl.cos_a}, c->u.cyl.sin_a > 0.0};
    } else if (t < 0.0 && rho < ro && (c->u.cyl.pipe <= 0.0 || z > 0.0)) {
        // The rim of the outlet, a convex edge (the pipe takes over below it).
        double er = rho - ro, d = sqrt(er * er + z * z);
        if (d < reach && d > 0.0) hit[n++] = (gf_wall_hit){d, {er / d * ux, er / d * uy, z / d}, false};
    }
    // The outlet pipe.
    if (c->u.cyl.pipe > 0.0 && z <= 0.0 && z >= -c->u.cyl.pipe && ro - rho < reach)
        hit[n++] = (gf_wall_hit){ro - rho, {-ux, -uy, 0.0}, true};
    // The central column: its side, its flat bottom at z_top, the rim between.
    if (c->u.cyl.r_in > 0.0) {
        double ri = c->u.cyl.r_in, zb = c->z_col;
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
    double rho2 = x * x + y * y, ro = c->u.cyl.radius - r, ri = c->u.cyl.r_in + r;
    if (z >= c->z_col + r && rho2 < ro * ro && (c->u.cyl.r_in <= 0.0 || rho2 > ri * ri)) return;
    gf_container_push_walls(c, x, y, z, r, alpha, dx, dy, dz);
}

static bool gf_cyl_contains(const gf_container *c, double x, double y, double z, double r, double tol)
{
    double ux, uy, m = r - tol;
    double rho = gf_cyl_radial(x, y, &ux, &uy);
    double ro = c->u.cyl.r_out;
    if (rho > c->u.cyl.radius - m) return false;
    if (c->u.cyl.r_in > 0.0) { // distance from (rho, z) to the column's section
        double er = fmax(0.0, rho - c->u.cyl.r_in), ez = fmax(0.0, c->z_col - z);
        if (er * er + ez * ez < m * m || (er == 0.0 && ez == 0.0)) return false;
    }
    double t = (rho - ro) * c->u.cyl.cos_a + z * c->u.cyl.sin_a;
    double s = z * c->u.cyl.cos_a - (rho - ro) * c->u.cyl.sin_a;
    if (t >= 0.0 && t <= c->u.cyl.cone_len) return s >= m || (rho < ro && z < m); // over the outlet: anywhere
    if (t < 0.0) {
        if (rho >= ro) return false; // under the base, off the outlet
        if (c->u.cyl.pipe > 0.0 && z <= 0.0 && z >= -c->u.cyl.pipe) return rho <= ro - m;
    }
    return true;
}

static void gf_cyl_spot_clamp(const gf_container *c, double n[3], double dw)
{
    if (n[2] < 0.0) return; // below the outlet the walk keeps over the birth disc (the caller)
    double ux, uy;
    double rho = gf_cyl_radial(n[0], n[1], &ux, &uy);
    double rmax = c->u.cyl.radius - dw, rmin = 0.0;
    if (c->u.cyl.sin_a > 0.0 && n[2] < c->z_col) // d_w from the funnel, measured square to it
        rmax = fmin(rmax, c->u.cyl.r_out + n[2] * c->u.cyl.cos_a / c->u.cyl.sin_a - dw / c->u.cyl.sin_a);
    if (c->u.cyl.r_in > 0.0 && n[2] > c->z_col - dw) rmin = c->u.cyl.r_in + dw; // beside the column, or deflected round it
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
    return rho <= c->u.cyl.radius - r && (c->u.cyl.r_in <= 0.0 || rho >= c->u.cyl.r_in + r);
}

// On the funnel (the flat base when a = 0) at distance r from it, measured
// square to it: s = z cos a - (rho - r_o) sin a = r; over the outlet, the
// plane z = r as for the box.
static double gf_cyl_floor_z(const gf_container *c, double x, double y, double r)
{
    double rho = sqrt(x * x + y * y);
    if (rho <= c->u.cyl.r_out || c->u.cyl.cos_a <= 0.0) return r;
    return (r + (rho - c->u.cyl.r_out) * c->u.cyl.sin_a) / c->u.cyl.cos_a;
}

// The disc inside the wall, or inside the funnel below its top (radius
// r_o + z / tan a), less the column above the funnel; the pipe's disc below
// z = 0 (the packing generator's slices, arithmetic for arithmetic).
static double gf_cyl_section_area(const gf_container *c, double z)
{
    const gf_cylinder_params *q = &c->u.cyl;
    double R = q->radius;
    if (z < 0.0) R = q->r_out;
    else if (q->sin_a > 0.0 && z < c->z_col) R = q->r_out + z * q->cos_a / q->sin_a;
    double ri = q->r_in > 0.0 && z >= c->z_col ? q->r_in : 0.0;
    return 3.14159265358979323846 * (R * R - ri * ri);
}

// Above the funnel, clear of the wall and the column.
static bool gf_cyl_clear(const gf_container *c, double x, double y, double z, double m)
{
    const gf_cylinder_params *q = &c->u.cyl;
    double rho2 = x * x + y * y, ro = q->radius - m, ri = q->r_in + m;
    return z >= c->z_col + m && rho2 < ro * ro && (q->r_in <= 0.0 || rho2 > ri * ri);
}

static void gf_cyl_radii(const gf_container *c, double r[2])
{
    r[0] = c->u.cyl.r_in;
    r[1] = c->u.cyl.radius;
}

static gf_profile_coord gf_cyl_profile(const gf_container *c)
{
    (void)c;
    return GF_PROFILE_R;
}

static void gf_outline_put(double (*p)[2], int *n, double x, double z)
{
    if (*n >= GF_OUTLINE_MAX) return;
    p[*n][0] = x;
    p[*n][1] = z;
    (*n)++;
}

// The axial section: wall, funnel, pipe, and the column as a solid part.
static void gf_cyl_outline(const gf_container *c, double ztop, gf_outline *o)
{
    const gf_cylinder_params *q = &c->u.cyl;
    const double hw = q->radius, zt = c->z_col, ro = q->r_out, zb = -q->pipe;
    const double inside[8][2] = {{-hw, ztop}, {-hw, zt}, {-ro, 0.0}, {-ro, zb},
                                 {ro, zb},    {ro, 0.0}, {hw, zt},   {hw, ztop}};
    for (int k = 0; k < 8; k++) gf_outline_put(o->p, &o->n, inside[k][0], inside[k][1]);
    for (int side = 0; side < 2; side++) {
        double sg = side ? 1.0 : -1.0;
        gf_outline_put(o->wall[side], &o->nwall[side], sg * hw, ztop);
        gf_outline_put(o->wall[side], &o->nwall[side], sg * hw, zt);
        gf_outline_put(o->wall[side], &o->nwall[side], sg * ro, 0.0);
        if (q->pipe > 0.0) gf_outline_put(o->wall[side], &o->nwall[side], sg * ro, zb);
    }
    if (q->r_in > 0.0) {
        const double col[4][2] = {{-q->r_in, zt}, {q->r_in, zt}, {q->r_in, ztop}, {-q->r_in, ztop}};
        for (int k = 0; k < 4; k++) gf_outline_put(o->solid, &o->nsolid, col[k][0], col[k][1]);
    }
}

// One region used by fix wall/gran/region, pre_vessel (docs/geometry.md):
// the wall above the funnel, the funnel (a cone), the outlet pipe continued
// to zlo (particles leave below its end), less a central column; open faces
// where the parts join, so that only the container's surface pushes.
static gf_status gf_cyl_lammps_walls(const gf_container *c, FILE *f, const char *pre, const char *law, double zlo,
                                double zhi)
{
    if (!f) return GF_OK; // LAMMPS holds these walls
    const gf_cylinder_params *b = &c->u.cyl;
    fprintf(f, "# the cylinder: wall radius %g, funnel at %g degrees to the outlet of radius %g at z = 0, pipe %g d\n",
            b->radius, b->angle, b->r_out, b->pipe);
    // Without a column the shell is the vessel (LAMMPS refuses a union of one region).
    const char *shell = b->r_in > 0.0 ? "shell" : "vessel";
    if (b->sin_a > 0.0) {
        fprintf(f,
                "region %s_wall cylinder z 0 0 %.10g %.10g %.10g open 1 open 2 units box\n"
                "region %s_funnel cone z 0 0 %.10g %.10g 0 %.10g open 1 open 2 units box\n"
                "region %s_pipe cylinder z 0 0 %.10g %.10g 0 open 1 open 2 units box\n"
                "region %s_%s union 3 %s_wall %s_funnel %s_pipe\n",
                pre, b->radius, c->z_col, zhi, pre, b->r_out, b->radius, c->z_col, pre, b->r_out, zlo, pre, shell,
                pre, pre, pre);
    } else { // a flat base: its lower face, with the hole the pipe cuts in it
        fprintf(f,
                "region %s_wall cylinder z 0 0 %.10g 0 %.10g open 2 units box\n"
                "region %s_pipe cylinder z 0 0 %.10g %.10g 0 open 1 open 2 units box\n"
                "region %s_%s union 2 %s_wall %s_pipe\n",
                pre, b->radius, zhi, pre, b->r_out, zlo, pre, shell, pre, pre);
    }
    if (b->r_in > 0.0)
        fprintf(f,
                "region %s_column cylinder z 0 0 %.10g %.10g %.10g open 2 side out units box\n"
                "region %s_vessel intersect 2 %s_shell %s_column\n",
                pre, b->r_in, c->z_col, zhi + 1.0, pre, pre, pre);
    fprintf(f, "fix walls flow wall/gran/region hertz/history %s region %s_vessel\n", law, pre);
    return GF_OK;
}

static void gf_cyl_lammps_base(const gf_container *c, FILE *f, const char *law, double zlo)
{
    (void)c;
    (void)f;
    (void)law;
    (void)zlo; // the vessel region holds the base
}

static gf_status gf_cyl_lammps_pour(const gf_container *c, FILE *f, double inset, double zlo, double zhi)
{
    if (c->u.cyl.r_in > 0.0)
        return gf_error_set(GF_ERR_PARAM, "dem.fill_method = pour cannot pour around container.inner_radius (fix "
                                          "pour would insert into the column): use dem.fill_method = generate");
    if (f)
        fprintf(f, "region pour cylinder z 0 0 %.10g %.10g %.10g units box\n", c->u.cyl.radius - inset, zlo, zhi);
    return GF_OK;
}

static int gf_cyl_describe(const gf_container *c, const char *const where[3], char *buf, size_t n)
{
    return snprintf(buf, n, "cylinder of radius %g d (%s), funnel %g deg (%s), outlet %g d (%s)", c->u.cyl.radius,
                    where[0], c->u.cyl.angle, where[1], 2.0 * c->u.cyl.r_out, where[2]);
}

static const char *gf_cyl_outlet_name(const gf_container *c)
{
    return c->u.cyl.pipe > 0.0 ? "end of the outlet pipe" : "outlet";
}

static void gf_cyl_make(gf_container *c, const gf_container_defs *d)
{
    gf_cylinder_params *q = &c->u.cyl;
    double R = d->radius, ro = 0.5 * d->outlet.diameter;
    double a = d->angle * (3.14159265358979323846 / 180.0);
    c->xlo = c->ylo = -R;
    c->xhi = c->yhi = R;
    c->shape = GF_ORIFICE_CIRCLE;
    c->hole = ro;
    c->ox = c->oy = 0.0; // on the axis (validation rejects an off-centre outlet)
    q->radius = R;
    q->r_out = ro;
    q->r_in = d->column_radius;
    q->pipe = d->outlet.length;
    q->angle = d->angle;
    q->sin_a = d->angle > 0.0 ? sin(a) : 0.0;
    q->cos_a = d->angle > 0.0 ? cos(a) : 1.0;
    c->z_col = (R - ro) * q->sin_a / q->cos_a;
    q->cone_len = (R - ro) / q->cos_a;
    c->z_bottom = -q->pipe;
    c->gate_z = fmin(c->z_exit, 0.0);
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
    .slice_volume = gf_container_slice_volume_by_sections,
    .clear = gf_cyl_clear,
    .radii = gf_cyl_radii,
    .profile = gf_cyl_profile,
    .outline = gf_cyl_outline,
    .mesh = gf_mesh_cylinder,
    .lammps_walls = gf_cyl_lammps_walls,
    .lammps_base = gf_cyl_lammps_base,
    .lammps_pour = gf_cyl_lammps_pour,
    .describe = gf_cyl_describe,
    .outlet_name = gf_cyl_outlet_name,
};

// ---- the check of its keys (gf_config_validate) ----------------------------

// The checks of a cylinder; then its bounding box and outlet in the box's
// keys, for everything that reads those (grid, dumps, analysis, pictures).
static gf_status gf_cyl_validate(const gf_container_defs *d, gf_config *cfg)
{
    gf_config_msg m;
    if (d->orifice.shape != GF_ORIFICE_CIRCLE) {
        gf_config_msg_make(&m, cfg, "container.orifice_shape", "container.shape");
        return gf_error_set(GF_ERR_PARAM, "%s%s is not possible with %s: its outlet is a circle "
                                          "(container.outlet_diameter)", m.lead, m.key[0], m.key[1]);
    }
    // A cylinder's outlet is outlet_diameter; an orifice_diameter set apart
    // from it would be ignored. (A written effective config sets both equal
    // in one file, and an outlet set elsewhere over it rules.)
    if (gf_config_is_set(cfg, "container.orifice_diameter") && d->orifice.diameter != d->outlet.diameter &&
        (!gf_config_is_set(cfg, "container.outlet_diameter") ||
         gf_config_same_origin(cfg, "container.orifice_diameter", "container.outlet_diameter"))) {
        gf_config_msg_make(&m, cfg, "container.orifice_diameter", "container.outlet_diameter");
        return gf_error_set(GF_ERR_PARAM, "%s%s does nothing in a cylinder (container.shape = cylinder), whose "
                                          "outlet is %s: set that instead", m.lead, m.key[0], m.key[1]);
    }
    // The bound is printed worked out (2R, R - 1): "less than 2 *
    // container.radius = 0.5" read as if 0.5 were the bound (issue 26).
    if (!(d->outlet.diameter < 2.0 * d->radius)) {
        gf_config_msg_make(&m, cfg, "container.outlet_diameter", "container.radius");
        return gf_error_set(GF_ERR_PARAM, "%s%s must be less than the cylinder's diameter 2R = %g (%s)", m.lead,
                            m.key[0], 2.0 * d->radius, m.key[1]);
    }
    if (d->column_radius > 0.0 && !(d->column_radius + 1.0 < d->radius)) {
        gf_config_msg_make(&m, cfg, "container.inner_radius", "container.radius");
        return gf_error_set(GF_ERR_PARAM, "%s%s leaves no room for a sphere: it must be less than R - 1 = %g (%s)",
                            m.lead, m.key[0], d->radius - 1.0, m.key[1]);
    }
    if (d->column_radius > 0.0 && !(d->angle > 0.0)) {
        gf_config_msg_make(&m, cfg, "container.inner_radius", "container.hopper_angle");
        return gf_error_set(GF_ERR_PARAM, "%s%s needs container.hopper_angle > 0, not %s: the column ends at the "
                                          "top of the funnel, and on a flat base it would stand on the outlet",
                            m.lead, m.key[0], m.key[1]);
    }
    if (d->column_radius > 0.0) {
        // Everything reaches the outlet through the gap between the column's
        // bottom rim (r_i, z_top) and the funnel (docs/geometry.md): its
        // distance to the funnel's line, or to the outlet's rim (r_o, 0) when
        // the foot of that distance falls inside the outlet. A gap narrower
        // than a sphere closes the silo (issue 26: hopper_angle = 1e-300 was
        // accepted, then failed with "cannot drain").
        const double a = d->angle * (3.14159265358979323846 / 180.0);
        const double R = d->radius, ro = 0.5 * d->outlet.diameter, ri = d->column_radius;
        const double z_top = (R - ro) * tan(a);
        const double t = (ri - ro) * cos(a) + z_top * sin(a);
        const double gap = t >= 0.0 ? (R - ri) * sin(a) : hypot(ri - ro, z_top);
        if (!(gap >= 1.0)) {
            gf_config_msg_make(&m, cfg, "container.inner_radius", "container.hopper_angle");
            return gf_error_set(GF_ERR_PARAM,
                                "%s%s with %s leaves a gap of %.3g d between the column's bottom (z = %.3g) and "
                                "the funnel, narrower than a sphere: nothing could reach the outlet (raise "
                                "container.hopper_angle, or lower container.inner_radius)",
                                m.lead, m.key[0], m.key[1], gap, z_top);
        }
        // Spots are born on the disc of radius r_o - spot.insertion_margin
        // and removed at the first step that takes them above the highest
        // particle of their grid column. Under a column whose bottom is too
        // low for a sphere there is none: if the column covers that whole
        // disc, every spot goes at once and nothing can ever drain.
        gf_engine_defs e;
        gf_config_engine_defs(cfg, &e);
        const double birth = fmax(0.0, ro - e.insertion_margin);
        if (z_top < 1.0 && ri >= birth) {
            gf_config_msg_make(&m, cfg, "container.inner_radius", "container.hopper_angle");
            return gf_error_set(GF_ERR_PARAM,
                                "%s%s with %s puts the column's bottom %.3g d above the outlet, too low for a "
                                "sphere under it, over the whole disc where spots are born (radius "
                                "container.outlet_diameter / 2 - spot.insertion_margin = %g): every spot would be "
                                "removed at its first step and nothing could drain (raise container.hopper_angle "
                                "to at least %.3g, or lower container.inner_radius below %g)",
                                m.lead, m.key[0], m.key[1], z_top, birth, atan(1.0 / (R - ro)) * (180.0 / 3.14159265358979323846),
                                birth);
        }
    }
    // The outlet is on the axis (docs/config.md, "Checks across keys").
    const double xy[2] = {d->orifice.x, d->orifice.y};
    const char *key[2] = {"container.orifice_x", "container.orifice_y"};
    for (int k = 0; k < 2; k++) {
        if (xy[k] == 0.0) continue;
        gf_config_msg_make(&m, cfg, key[k], "container.shape");
        return gf_error_set(GF_ERR_PARAM, "%s%s: a cylinder's outlet is on its axis (x = y = 0); an "
                                          "off-centre orifice needs container.shape = box, not %s",
                            m.lead, m.key[0], m.key[1]);
    }
    gf_config_set_extent(cfg, 2.0 * d->radius, 2.0 * d->radius);
    gf_config_set_orifice(cfg, d->orifice.shape, d->outlet.diameter);
    return GF_OK;
}

static const char *const gf_cyl_keys[] = {"container.radius",        "container.hopper_angle",
                                          "container.outlet_diameter", "container.outlet_length",
                                          "container.inner_radius",  NULL};

const gf_shape gf_cylinder_shape = {
    .name = "cylinder",
    .id = GF_SHAPE_CYLINDER,
    .ops = &gf_cylinder_ops,
    .keys = gf_cyl_keys,
    .make = gf_cyl_make,
    .rectangular = false,
    .validate = gf_cyl_validate,
    .wall_key = "container.radius",
};
