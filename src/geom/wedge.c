// SPDX-License-Identifier: MIT
// The wedge hopper (plane flow, Jenike's other design chart; the quasi-2D
// silos of Choi, Kudrolli & Bazant): flat walls at y = ylo, yhi; below the
// vertical walls x = xlo, xhi two walls inclined at angle a to the
// horizontal run down to a slit at z = 0, |x - ox| < hole, across the whole
// depth; a straight chute of that width below it (length `chute`). In the
// (x, z) plane each side is the cylinder's (rho, z) half-plane (cylinder.c)
// with q = the distance outward from the slit's edge: its side wall, its
// inclined wall and the slit's rim (a convex edge), then the chute.
#include "core/error.h"
#include "geom/container.h"
#include "geom/mesh.h"

// Side k (0: left, 1: right): its outward sign and q, the distance from the
// slit's edge outward (negative over the slit).
static inline double gf_wedge_sign(int k) { return k ? 1.0 : -1.0; }
static inline double gf_wedge_q(const gf_container *c, int k, double x)
{
    return gf_wedge_sign(k) * (x - c->ox) - c->hole;
}

static int gf_wedge_walls(const gf_container *c, const double p[3], double reach, gf_wall_hit *hit)
{
    const gf_wedge_params *w = &c->u.wedge;
    int n = 0;
    const double z = p[2];
    if (p[1] - c->ylo < reach) hit[n++] = (gf_wall_hit){p[1] - c->ylo, {0.0, 1.0, 0.0}, true};
    if (c->yhi - p[1] < reach) hit[n++] = (gf_wall_hit){c->yhi - p[1], {0.0, -1.0, 0.0}, true};
    for (int k = 0; k < 2; k++) {
        const double sg = gf_wedge_sign(k), q = gf_wedge_q(c, k, p[0]);
        // The vertical wall above the inclined one.
        if (z >= w->top[k] && w->run[k] - q < reach) hit[n++] = (gf_wall_hit){w->run[k] - q, {-sg, 0.0, 0.0}, true};
        // The inclined wall: t along it from the slit's edge, s off it.
        const double t = q * w->cos_a + z * w->sin_a, s = z * w->cos_a - q * w->sin_a;
        if (t >= 0.0 && t <= w->len[k]) {
            if (s < reach) hit[n++] = (gf_wall_hit){s, {-sg * w->sin_a, 0.0, w->cos_a}, true};
        } else if (t < 0.0 && q < 0.0 && (w->chute <= 0.0 || z > 0.0)) {
            // The slit's edge, a convex edge (the chute takes over below it).
            double d = sqrt(q * q + z * z);
            if (d < reach && d > 0.0) hit[n++] = (gf_wall_hit){d, {sg * q / d, 0.0, z / d}, false};
        }
        // The chute's wall.
        if (w->chute > 0.0 && z <= 0.0 && z >= -w->chute && -q < reach)
            hit[n++] = (gf_wall_hit){-q, {-sg, 0.0, 0.0}, true};
    }
    return n;
}

// Above both inclined walls and clear of the flat ones.
static bool gf_wedge_clear(const gf_container *c, double x, double y, double z, double m)
{
    return z >= c->z_col + m && x >= c->xlo + m && x <= c->xhi - m && y >= c->ylo + m && y <= c->yhi - m;
}

static void gf_wedge_push(const gf_container *c, double x, double y, double z, double r, double alpha, double *dx,
                          double *dy, double *dz)
{
    if (gf_wedge_clear(c, x, y, z, r)) return; // most spheres: in the bulk, above the hopper
    gf_container_push_walls(c, x, y, z, r, alpha, dx, dy, dz);
}

static bool gf_wedge_contains(const gf_container *c, double x, double y, double z, double r, double tol)
{
    const gf_wedge_params *w = &c->u.wedge;
    const double m = r - tol;
    if (y < c->ylo + m || y > c->yhi - m) return false;
    for (int k = 0; k < 2; k++) {
        const double q = gf_wedge_q(c, k, x);
        if (q > w->run[k] - m) return false;
        const double t = q * w->cos_a + z * w->sin_a, s = z * w->cos_a - q * w->sin_a;
        if (t >= 0.0 && t <= w->len[k]) {
            if (!(s >= m || (q < 0.0 && z < m))) return false; // over the slit: anywhere
        } else if (t < 0.0) {
            if (q >= 0.0) return false; // under the inclined wall, off the slit
            if (w->chute > 0.0 && z <= 0.0 && z >= -w->chute && q > -m) return false;
        }
    }
    return true;
}

static double gf_wedge_clamp(double v, double lo, double hi) { return v < lo ? lo : (v > hi ? hi : v); }

// d_w from every wall, measured square to it: at an inclined wall the
// allowed x at height z is the slit's edge + z cot a - d_w / sin a.
static void gf_wedge_spot_clamp(const gf_container *c, double n[3], double dw)
{
    const gf_wedge_params *w = &c->u.wedge;
    n[1] = gf_wedge_clamp(n[1], c->ylo + dw, c->yhi - dw); // the flat walls reach down the chute
    if (n[2] < 0.0) return; // below the slit the walk keeps over the birth band (the caller)
    double lo = c->xlo + dw, hi = c->xhi - dw;
    const double out = n[2] * w->cos_a / w->sin_a - dw / w->sin_a;
    if (n[2] < w->top[0]) lo = fmax(lo, c->ox - c->hole - out);
    if (n[2] < w->top[1]) hi = fmin(hi, c->ox + c->hole + out);
    if (lo > hi) lo = hi = 0.5 * (lo + hi);
    n[0] = gf_wedge_clamp(n[0], lo, hi);
}

static bool gf_wedge_inside_xy(const gf_container *c, double x, double y, double r)
{
    return x >= c->xlo + r && x <= c->xhi - r && y >= c->ylo + r && y <= c->yhi - r;
}

// On an inclined wall at distance r, measured square to it (s = r); over
// the slit, the plane z = r.
static double gf_wedge_floor_z(const gf_container *c, double x, double y, double r)
{
    (void)y;
    const gf_wedge_params *w = &c->u.wedge;
    double q = fmax(gf_wedge_q(c, 0, x), gf_wedge_q(c, 1, x));
    if (q <= 0.0) return r;
    return (r + q * w->sin_a) / w->cos_a;
}

// The width between the inclined walls (at most the vertical ones') times
// the depth; the chute's below z = 0.
static double gf_wedge_section_area(const gf_container *c, double z)
{
    const gf_wedge_params *w = &c->u.wedge;
    if (z < 0.0) return 2.0 * c->hole * (c->yhi - c->ylo);
    const double spread = z * w->cos_a / w->sin_a;
    const double lo = fmax(c->xlo, c->ox - c->hole - spread), hi = fmin(c->xhi, c->ox + c->hole + spread);
    return (hi - lo) * (c->yhi - c->ylo);
}

static void gf_wedge_radii(const gf_container *c, double r[2])
{
    r[0] = 0.0;
    r[1] = hypot(fmax(-c->xlo, c->xhi), fmax(-c->ylo, c->yhi));
}

static gf_profile_coord gf_wedge_profile(const gf_container *c)
{
    (void)c;
    return GF_PROFILE_X;
}

static void gf_wedge_put(double (*p)[2], int *n, double x, double z)
{
    if (*n >= GF_OUTLINE_MAX) return;
    p[*n][0] = x;
    p[*n][1] = z;
    (*n)++;
}

// The side k's wall from the top down: vertical wall, inclined wall, chute.
static void gf_wedge_profile_line(const gf_container *c, int k, double ztop, double (*p)[2], int *n)
{
    const gf_wedge_params *w = &c->u.wedge;
    const double sg = gf_wedge_sign(k), xw = k ? c->xhi : c->xlo, xe = c->ox + sg * c->hole;
    gf_wedge_put(p, n, xw, fmax(ztop, w->top[k]));
    gf_wedge_put(p, n, xw, w->top[k]);
    gf_wedge_put(p, n, xe, 0.0);
    if (w->chute > 0.0) gf_wedge_put(p, n, xe, -w->chute);
}

static void gf_wedge_outline(const gf_container *c, double ztop, gf_outline *o)
{
    for (int k = 0; k < 2; k++) gf_wedge_profile_line(c, k, ztop, o->wall[k], &o->nwall[k]);
    for (int j = 0; j < o->nwall[0]; j++) gf_wedge_put(o->p, &o->n, o->wall[0][j][0], o->wall[0][j][1]);
    for (int j = o->nwall[1] - 1; j >= 0; j--) gf_wedge_put(o->p, &o->n, o->wall[1][j][0], o->wall[1][j][1]);
}

// The two flat walls as polygons (the part above z = 0 is convex: a fan from
// the left edge of the slit; the chute a rectangle), the others as quads
// across the depth.
static gf_status gf_wedge_mesh(const gf_container *c, double top, int segments, gf_mesh *m)
{
    (void)segments;
    const gf_wedge_params *w = &c->u.wedge;
    const double T = fmax(top, c->z_col), xa = c->ox - c->hole, xb = c->ox + c->hole;
    const double poly[6][2] = {{xa, 0.0}, {xb, 0.0}, {c->xhi, w->top[1]}, {c->xhi, T}, {c->xlo, T}, {c->xlo, w->top[0]}};
    bool ok = true;
    for (int f = 0; f < 2 && ok; f++) {
        const double y = f ? c->yhi : c->ylo;
        size_t v[6];
        for (int j = 0; j < 6; j++) v[j] = gf_mesh_vertex(m, poly[j][0], y, poly[j][1]);
        for (int j = 1; j + 1 < 6 && ok; j++) ok = gf_mesh_tri(m, v[0], v[j], v[j + 1]);
        if (ok && w->chute > 0.0) {
            double a[3] = {xa, y, -w->chute}, b[3] = {xb, y, -w->chute}, cc[3] = {xb, y, 0.0}, d[3] = {xa, y, 0.0};
            ok = gf_mesh_quad(m, a, b, cc, d);
        }
    }
    for (int k = 0; k < 2 && ok; k++) {
        double line[GF_OUTLINE_MAX][2];
        int n = 0;
        gf_wedge_profile_line(c, k, T, line, &n);
        for (int j = 0; j + 1 < n && ok; j++) {
            double a[3] = {line[j][0], c->ylo, line[j][1]}, b[3] = {line[j + 1][0], c->ylo, line[j + 1][1]};
            double cc[3] = {line[j + 1][0], c->yhi, line[j + 1][1]}, d[3] = {line[j][0], c->yhi, line[j][1]};
            ok = gf_mesh_quad(m, a, b, cc, d);
        }
    }
    if (ok) return GF_OK;
    gf_mesh_free(m);
    return gf_error_set(GF_ERR_NOMEM, "out of memory for the container mesh");
}

// The flat walls as planes (fix wall/gran yplane, as the box's); the rest as
// one region, pre_vessel: the intersection of the half-spaces inside the
// vertical walls, above the inclined ones and above z = 0, united with the
// chute, a block over the slit from zlo up to z = 1 (continued below its end,
// as the cylinder's pipe, so that leaving particles fall freely). The union
// drops each part's surface inside the other (LAMMPS region union): the
// plane z = 0 over the slit and the chute's walls above z = 0.
static gf_status gf_wedge_lammps_walls(const gf_container *c, FILE *f, const char *pre, const char *law, double zlo,
                                  double zhi)
{
    if (!f) return GF_OK; // LAMMPS holds these walls
    (void)zhi;
    const gf_wedge_params *w = &c->u.wedge;
    const double xa = c->ox - c->hole, xb = c->ox + c->hole;
    fprintf(f,
            "# the wedge hopper: walls at %g degrees to the horizontal down to the slit %.10g < x < %.10g at z = 0, "
            "chute %g d\n"
            "fix wall_y flow wall/gran hertz/history %s yplane %.10g %.10g\n"
            "region %s_x0 plane %.10g 0 0 1 0 0 units box\n"
            "region %s_x1 plane %.10g 0 0 -1 0 0 units box\n"
            "region %s_s0 plane %.10g 0 0 %.10g 0 %.10g units box\n"
            "region %s_s1 plane %.10g 0 0 %.10g 0 %.10g units box\n"
            "region %s_z0 plane 0 0 0 0 0 1 units box\n"
            "region %s_hopper intersect 5 %s_x0 %s_x1 %s_s0 %s_s1 %s_z0\n"
            "region %s_chute block %.10g %.10g INF INF %.10g 1 units box\n"
            "region %s_vessel union 2 %s_hopper %s_chute\n"
            "fix walls flow wall/gran/region hertz/history %s region %s_vessel\n",
            w->angle, xa, xb, w->chute, law, c->ylo, c->yhi, pre, c->xlo, pre, c->xhi, pre, xa, w->sin_a, w->cos_a,
            pre, xb, -w->sin_a, w->cos_a, pre, pre, pre, pre, pre, pre, pre, pre, xa, xb, zlo, pre, pre, pre, law,
            pre);
    return GF_OK;
}

static void gf_wedge_lammps_base(const gf_container *c, FILE *f, const char *law, double zlo)
{
    (void)c;
    (void)f;
    (void)law;
    (void)zlo; // the vessel region holds the inclined walls and the chute
}

static gf_status gf_wedge_lammps_pour(const gf_container *c, FILE *f, double inset, double zlo, double zhi)
{
    if (f)
        fprintf(f, "region pour block %.10g %.10g %.10g %.10g %.10g %.10g units box\n", c->xlo + inset,
                c->xhi - inset, c->ylo + inset, c->yhi - inset, zlo, zhi);
    return GF_OK;
}

static int gf_wedge_describe(const gf_container *c, const char *const where[3], char *buf, size_t n)
{
    return snprintf(buf, n, "wedge hopper %g x %g d (width: %s), walls at %g deg (%s), slit %g d (%s)",
                    c->xhi - c->xlo, c->yhi - c->ylo, where[0], c->u.wedge.angle, where[1], 2.0 * c->hole, where[2]);
}

static const char *gf_wedge_outlet_name(const gf_container *c)
{
    return c->u.wedge.chute > 0.0 ? "end of the chute" : "slit";
}

static void gf_wedge_make(gf_container *c, const gf_container_defs *d)
{
    gf_wedge_params *w = &c->u.wedge;
    const double a = d->angle * (3.14159265358979323846 / 180.0);
    c->shape = GF_ORIFICE_SLIT;
    c->oy = 0.0;
    w->angle = d->angle;
    w->sin_a = sin(a);
    w->cos_a = cos(a);
    w->chute = d->outlet.length;
    w->run[0] = fmax(0.0, (c->ox - c->hole) - c->xlo);
    w->run[1] = fmax(0.0, c->xhi - (c->ox + c->hole));
    for (int k = 0; k < 2; k++) {
        w->top[k] = w->run[k] * w->sin_a / w->cos_a;
        w->len[k] = w->run[k] / w->cos_a;
    }
    c->z_col = fmax(w->top[0], w->top[1]);
    c->z_bottom = -w->chute;
    c->gate_z = fmin(c->z_exit, 0.0);
}

const gf_shape_ops gf_wedge_ops = {
    .walls = gf_wedge_walls,
    .push = gf_wedge_push,
    .contains = gf_wedge_contains,
    .spot_clamp = gf_wedge_spot_clamp,
    .mirrors = gf_container_mirror_walls,
    .inside_xy = gf_wedge_inside_xy,
    .floor_z = gf_wedge_floor_z,
    .section_area = gf_wedge_section_area,
    .slice_volume = gf_container_slice_volume_by_sections,
    .clear = gf_wedge_clear,
    .radii = gf_wedge_radii,
    .profile = gf_wedge_profile,
    .outline = gf_wedge_outline,
    .mesh = gf_wedge_mesh,
    .lammps_walls = gf_wedge_lammps_walls,
    .lammps_base = gf_wedge_lammps_base,
    .lammps_pour = gf_wedge_lammps_pour,
    .describe = gf_wedge_describe,
    .outlet_name = gf_wedge_outlet_name,
};

// ---- the check of its keys (gf_config_validate) ----------------------------

// The checks of a wedge hopper (docs/geometry.md, "The wedge hopper"): its
// outlet is a slit (container.orifice_diameter wide, at container.orifice_x)
// between walls inclined at container.hopper_angle > 0.
static gf_status gf_wedge_validate(const gf_container_defs *d, gf_config *cfg)
{
    gf_config_msg m;
    if (!(d->angle > 0.0)) {
        gf_config_msg_make(&m, cfg, "container.hopper_angle", "container.shape");
        return gf_error_set(GF_ERR_PARAM, "%s%s must be more than 0 with %s: a wedge's walls are inclined "
                                          "(0 < angle <= 80 degrees to the horizontal); a flat base with a slit "
                                          "is container.shape = box with container.orifice_shape = slit",
                            m.lead, m.key[0], m.key[1]);
    }
    if (gf_config_is_set(cfg, "container.orifice_shape") && d->orifice.shape != GF_ORIFICE_SLIT) {
        gf_config_msg_make(&m, cfg, "container.orifice_shape", "container.shape");
        return gf_error_set(GF_ERR_PARAM, "%s%s is not possible with %s: its outlet is a slit across the depth, "
                                          "container.orifice_diameter wide", m.lead, m.key[0], m.key[1]);
    }
    if (d->column_radius > 0.0) {
        gf_config_msg_make(&m, cfg, "container.inner_radius", "container.shape");
        return gf_error_set(GF_ERR_PARAM, "%s%s: a central column needs container.shape = cylinder, not %s",
                            m.lead, m.key[0], m.key[1]);
    }
    gf_config_set_orifice(cfg, GF_ORIFICE_SLIT, d->orifice.diameter);
    return GF_OK;
}

static const char *const gf_wedge_keys[] = {"container.width",         "container.hopper_angle",
                                            "container.orifice_diameter", "container.depth",
                                            "container.outlet_length", "container.orifice_x",
                                            NULL};

const gf_shape gf_wedge_shape = {
    .name = "wedge",
    .id = GF_SHAPE_WEDGE,
    .ops = &gf_wedge_ops,
    .keys = gf_wedge_keys,
    .make = gf_wedge_make,
    .rectangular = false,
    .validate = gf_wedge_validate,
};
