// SPDX-License-Identifier: MIT
// container.shape = mesh (geom/meshshape.h; docs/geometry.md, "Containers
// from STL"). The walls near a point are the mesh's features near it, found
// through the field's buckets and measured exactly: a face whose closest
// point is inside it, a convex (or open: the outlet's rim) edge or vertex
// whose Voronoi region holds the point, each reported once, as the cylinder
// reports its segments and rims. The field answers the rest: most points are
// far from every wall (one interpolation says so), the inside test is its
// sign.
#include "geom/meshshape.h"

#include <math.h>
#include <stdatomic.h>
#include <stdio.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "core/fs.h"
#include "core/shape_check.h"

static const double gf_ms_sqrt3 = 1.7320508075688772;

// ---- the walls --------------------------------------------------------------

typedef struct gf_ms_walls {
    const gf_container *c;
    const gf_meshshape *ms;
    const double *p;
    double reach, search; // search: radius of the triangles looked at
    gf_wall_hit *hit;
    int n;
} gf_ms_walls;

// Adds a hit, keeping the GF_WALL_HITS nearest. Hits whose normals are
// within GF_MS_MERGE of each other are one wall, the nearer kept: the facets
// of a curved wall (a cylinder's n-gon meets at 360/n degrees) would
// otherwise push twice near every seam, where a sphere reaches both; the
// box's corners (90 degrees) and a funnel's foot (60 at a 60 degree hopper)
// stay two walls, as the analytic shapes report them.
#define GF_MS_MERGE 0.9 // cos 25.8 degrees
static void gf_ms_add(gf_ms_walls *w, double gap, const double n[3], bool side)
{
    for (int k = 0; k < w->n; k++)
        if (w->hit[k].n[0] * n[0] + w->hit[k].n[1] * n[1] + w->hit[k].n[2] * n[2] > GF_MS_MERGE) {
            if (gap < w->hit[k].gap) w->hit[k] = (gf_wall_hit){gap, {n[0], n[1], n[2]}, side};
            return;
        }
    int at = w->n;
    if (w->n == GF_WALL_HITS) {
        at = 0;
        for (int k = 1; k < w->n; k++)
            if (w->hit[k].gap > w->hit[at].gap) at = k;
        if (w->hit[at].gap <= gap) return;
    } else {
        w->n++;
    }
    w->hit[at] = (gf_wall_hit){gap, {n[0], n[1], n[2]}, side};
}

static bool gf_ms_over_hole(const gf_meshshape *ms, double x, double y)
{
    double dx = x - ms->ox, dy = y - ms->oy;
    if (ms->shape == GF_ORIFICE_SLIT) return fabs(dx) < ms->hole;
    return dx * dx + dy * dy < ms->hole * ms->hole;
}

static bool gf_ms_visit(void *ctx, uint32_t t)
{
    gf_ms_walls *w = ctx;
    const gf_meshshape *ms = w->ms;
    const gf_sdf *s = &ms->sdf;
    const double *p = w->p;
    double q[3], d[3];
    gf_sdf_region r = gf_sdf_closest(s, t, p, q);
    for (int a = 0; a < 3; a++) d[a] = p[a] - q[a];
    double dist = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (!(dist < w->search)) return true;
    // A closed mesh's base is cut open over the outlet by the orifice keys.
    if (ms->closed && fabs(q[2] - ms->exit_z) < 1e-9 && gf_ms_over_hole(ms, q[0], q[1])) return true;
    const double *no = s->n[t]; // outward
    bool plane = r == GF_SDF_FACE, in = true;
    if (r != GF_SDF_FACE && r < GF_SDF_VERT0) {
        int k = r - GF_SDF_EDGE0;
        int32_t u = s->mesh.adj[t][k];
        if (u >= 0) { // once, from the higher-numbered side, and only in the edge's region of both
            if ((uint32_t)u < t) return true;
            double q2[3];
            gf_sdf_region r2 = gf_sdf_closest(s, (uint32_t)u, p, q2);
            if (r2 == GF_SDF_FACE || r2 >= GF_SDF_VERT0 || s->mesh.adj[u][r2 - GF_SDF_EDGE0] != (int32_t)t) return true;
        }
        bool convex = (ms->tconvex[t] >> k) & 1, concave = (ms->tconcave[t] >> k) & 1;
        plane = !convex && !concave; // two triangles of one plane: the plane
        in = !concave;               // a concave edge is nearest only to points beyond both faces
    } else if (r >= GF_SDF_VERT0) {
        uint32_t v = s->mesh.t[t][r - GF_SDF_VERT0];
        if (ms->vfirst[v] != t) return true; // once
        const double *pv = s->mesh.v[v];
        for (uint32_t e = ms->vstart[v]; e < ms->vstart[v + 1]; e++) { // in the vertex's Voronoi region
            const double *pw = s->mesh.v[ms->vnbr[e]];
            if (d[0] * (pw[0] - pv[0]) + d[1] * (pw[1] - pv[1]) + d[2] * (pw[2] - pv[2]) > 0.0) return true;
        }
        const double *vn = s->vn[v];
        in = s->vopen[v] ? p[2] >= ms->exit_z : d[0] * vn[0] + d[1] * vn[1] + d[2] * vn[2] <= 0.0;
        if (!ms->vconvex[v] && in) return true; // inside a concave corner: its faces answer
    }
    if (plane) {
        const double *a = s->mesh.v[s->mesh.t[t][0]];
        double gap = -(no[0] * (p[0] - a[0]) + no[1] * (p[1] - a[1]) + no[2] * (p[2] - a[2]));
        if (gap < w->reach) gf_ms_add(w, gap, (double[3]){-no[0], -no[1], -no[2]}, fabs(no[2]) < 0.999);
        return true;
    }
    if (!(dist > 0.0)) return true;
    double sg = in ? 1.0 : -1.0;
    if (sg * dist < w->reach) gf_ms_add(w, sg * dist, (double[3]){sg * d[0] / dist, sg * d[1] / dist, sg * d[2] / dist}, false);
    return true;
}

static int gf_ms_walls_of(const gf_container *c, const double p[3], double reach, gf_wall_hit *hit)
{
    const gf_meshshape *ms = c->mesh;
    if (!ms) return 0;
    const gf_sdf *s = &ms->sdf;
    // Most points are far from every wall: the field says so in one look.
    if (gf_sdf_value(s, p) > reach + s->h * gf_ms_sqrt3 * 1.001 + 1e-9) return 0;
    // Points beyond a wall (a negative gap; spot.wall_distance <= 0 asks
    // only for those) are looked for up to a diameter beyond it.
    gf_ms_walls w = {c, ms, p, reach, fabs(reach) + 1.0, hit, 0};
    gf_sdf_near(s, p, w.search, gf_ms_visit, &w);
    return w.n;
}

static void gf_ms_push(const gf_container *c, double x, double y, double z, double r, double alpha, double *dx,
                       double *dy, double *dz)
{
    gf_container_push_walls(c, x, y, z, r, alpha, dx, dy, dz);
}

static bool gf_ms_contains(const gf_container *c, double x, double y, double z, double r, double tol)
{
    const gf_meshshape *ms = c->mesh;
    if (!ms) return false;
    double m = r - tol, p[3] = {x, y, z};
    bool hole = gf_container_over_hole(c, x, y);
    if (z < ms->exit_z) return hole; // passing through the outlet, as the box's
    double d = gf_sdf_distance(&ms->sdf, p, fmax(m, 0.0));
    if (ms->closed && hole && z < ms->exit_z + fmax(m, 0.0)) return true;
    if (!(d > 0.0)) return hole && z < ms->exit_z + fmax(m, 0.0) && d > -1e-9;
    return d >= m || (hole && z < ms->exit_z + m);
}

static void gf_ms_spot_clamp(const gf_container *c, double n[3], double dw)
{
    const gf_meshshape *ms = c->mesh;
    if (!ms || n[2] < ms->exit_z) return;
    // Moved sideways (as the cylinder moves it off its funnel) until it is
    // d_w from every side wall near it: twice, for corners.
    for (int pass = 0; pass < 3; pass++) {
        gf_wall_hit hit[GF_WALL_HITS];
        int nh = gf_ms_walls_of(c, n, dw, hit);
        bool moved = false;
        double mx = 0.0, my = 0.0;
        for (int k = 0; k < nh; k++) {
            if (!hit[k].side || !(hit[k].gap < dw)) continue;
            double hx = hit[k].n[0], hy = hit[k].n[1], l2 = hx * hx + hy * hy;
            if (l2 <= 0.0) continue;
            double f = (dw - hit[k].gap) / l2;
            mx += f * hx;
            my += f * hy;
            moved = true;
        }
        if (!moved) return;
        n[0] += mx;
        n[1] += my;
    }
}

static bool gf_ms_inside_xy(const gf_container *c, double x, double y, double r)
{
    const gf_meshshape *ms = c->mesh;
    if (!ms) return false;
    const double p[3] = {x, y, ms->top};
    if (!(gf_sdf_distance(&ms->sdf, p, r) > 0.0)) return false;
    gf_wall_hit hit[GF_WALL_HITS];
    int nh = gf_ms_walls_of(c, p, r, hit);
    for (int k = 0; k < nh; k++)
        if (hit[k].side && hit[k].gap < r) return false;
    return true;
}

// Down the column at (x, y) from under the lid to the first wall a sphere of
// radius r meets (marched, then bisected to 1e-9 d); the exit plane + r over
// the outlet.
static double gf_ms_floor_z(const gf_container *c, double x, double y, double r)
{
    const gf_meshshape *ms = c->mesh;
    if (!ms) return r;
    const gf_sdf *s = &ms->sdf;
    double z = s->hi[2] - r, step = fmax(0.05, fmin(0.25, 0.5 * r));
    double p[3] = {x, y, z};
    if (gf_sdf_distance(s, p, r) < r) return z;
    double lo = ms->exit_z + r;
    while (z - step > lo) {
        p[2] = z - step;
        if (gf_sdf_distance(s, p, r) < r) break;
        z -= step;
    }
    if (z - step <= lo) {
        p[2] = lo;
        if (gf_sdf_distance(s, p, r) >= r || gf_container_over_hole(c, x, y)) return lo;
    }
    double a = fmax(lo, z - step), b = z; // blocked at a, clear at b
    for (int it = 0; it < 60 && b - a > 1e-9; it++) {
        p[2] = 0.5 * (a + b);
        if (gf_sdf_distance(s, p, r) < r) a = p[2];
        else b = p[2];
    }
    return b;
}

// The slice of the closed surface at height z: each triangle crossing it
// gives a segment, oriented with the inside on its left; the shoelace sum.
static double gf_ms_section_area(const gf_container *c, double z)
{
    const gf_meshshape *ms = c->mesh;
    if (!ms || z < ms->exit_z) return 0.0;
    const gf_stl *m = &ms->sdf.mesh;
    double area = 0.0;
    for (size_t t = 0; t < m->nt; t++) {
        const double *no = ms->sdf.n[t];
        double pt[2][2];
        int np = 0;
        for (int k = 0; k < 3 && np < 2; k++) {
            const double *a = m->v[m->t[t][k]], *b = m->v[m->t[t][(k + 1) % 3]];
            if ((a[2] > z) == (b[2] > z)) continue;
            double f = (z - a[2]) / (b[2] - a[2]);
            pt[np][0] = a[0] + f * (b[0] - a[0]);
            pt[np][1] = a[1] + f * (b[1] - a[1]);
            np++;
        }
        if (np != 2) continue;
        double ex = pt[1][0] - pt[0][0], ey = pt[1][1] - pt[0][1];
        double s = ey * no[0] - ex * no[1] > 0.0 ? 1.0 : -1.0;
        area += s * (pt[0][0] * pt[1][1] - pt[0][1] * pt[1][0]);
    }
    return fmax(0.0, 0.5 * area);
}

bool gf_meshshape_slice_y(const gf_meshshape *ms, double y, size_t t, double seg[4])
{
    const gf_stl *m = &ms->sdf.mesh;
    int np = 0;
    for (int k = 0; k < 3 && np < 2; k++) {
        const double *a = m->v[m->t[t][k]], *b = m->v[m->t[t][(k + 1) % 3]];
        if ((a[1] > y) == (b[1] > y)) continue;
        double f = (y - a[1]) / (b[1] - a[1]);
        seg[2 * np] = a[0] + f * (b[0] - a[0]);
        seg[2 * np + 1] = a[2] + f * (b[2] - a[2]);
        np++;
    }
    return np == 2;
}

const gf_shape_ops gf_mesh_ops = {
    .walls = gf_ms_walls_of,
    .push = gf_ms_push,
    .contains = gf_ms_contains,
    .spot_clamp = gf_ms_spot_clamp,
    .mirrors = gf_container_mirror_walls,
    .inside_xy = gf_ms_inside_xy,
    .floor_z = gf_ms_floor_z,
    .section_area = gf_ms_section_area,
};

// ---- loading and checking -----------------------------------------------------

// Convexity of each edge, seen from inside, and the vertex tables.
static gf_status gf_ms_topology(gf_meshshape *ms)
{
    const gf_sdf *s = &ms->sdf;
    const gf_stl *m = &s->mesh;
    ms->tconvex = GF_NEW(uint8_t, m->nt);
    ms->tconcave = GF_NEW(uint8_t, m->nt);
    ms->vconvex = GF_NEW(uint8_t, m->nv);
    ms->vstart = GF_NEW(uint32_t, m->nv + 1);
    ms->vnbr = GF_NEW(uint32_t, 6 * m->nt);
    ms->vfirst = GF_NEW(uint32_t, m->nv);
    if (!ms->tconvex || !ms->tconcave || !ms->vconvex || !ms->vstart || !ms->vnbr || !ms->vfirst)
        return gf_error_set(GF_ERR_NOMEM, "out of memory for the mesh's tables");
    for (size_t v = 0; v < m->nv; v++) ms->vfirst[v] = UINT32_MAX;
    for (size_t t = 0; t < m->nt; t++)
        for (int k = 0; k < 3; k++) {
            uint32_t a = m->t[t][k];
            if (ms->vfirst[a] == UINT32_MAX) ms->vfirst[a] = (uint32_t)t;
            int32_t u = m->adj[t][k];
            bool convex = u < 0, concave = false;
            if (u >= 0) {
                // The neighbour's far vertex against this triangle's plane
                // (outward normal): beyond it, the wall folds away from the
                // inside, and the edge juts into it (convex: the outlet's rim
                // over a pipe); short of it, an inside corner (concave).
                const uint32_t *tu = m->t[u];
                uint32_t far = tu[0] != a && tu[0] != m->t[t][(k + 1) % 3] ? tu[0]
                               : tu[1] != a && tu[1] != m->t[t][(k + 1) % 3] ? tu[1] : tu[2];
                const double *pa = m->v[a], *pf = m->v[far];
                double e[3] = {pf[0] - pa[0], pf[1] - pa[1], pf[2] - pa[2]};
                double len = sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
                double h = (s->n[t][0] * e[0] + s->n[t][1] * e[1] + s->n[t][2] * e[2]) / len;
                convex = h > 1e-9;
                concave = h < -1e-9;
            }
            if (convex) {
                ms->tconvex[t] |= (uint8_t)(1u << k);
                ms->vconvex[a] = ms->vconvex[m->t[t][(k + 1) % 3]] = 1;
            }
            if (concave) ms->tconcave[t] |= (uint8_t)(1u << k);
            // Neighbours: each edge a -> b from a's side (its partner
            // gives b -> a); an open edge from both ends here.
            ms->vstart[a + 1]++;
            if (u < 0) ms->vstart[m->t[t][(k + 1) % 3] + 1]++;
        }
    for (size_t v = 0; v < m->nv; v++) ms->vstart[v + 1] += ms->vstart[v];
    uint32_t *fill = GF_NEW(uint32_t, m->nv);
    if (!fill) return gf_error_set(GF_ERR_NOMEM, "out of memory for the mesh's tables");
    for (size_t t = 0; t < m->nt; t++)
        for (int k = 0; k < 3; k++) {
            uint32_t a = m->t[t][k], b = m->t[t][(k + 1) % 3];
            ms->vnbr[ms->vstart[a] + fill[a]++] = b;
            if (m->adj[t][k] < 0) ms->vnbr[ms->vstart[b] + fill[b]++] = a;
        }
    GF_DELETE(fill, m->nv);
    return GF_OK;
}

// What the walls must be for the outlet to be the only way out: nothing below
// the exit plane, every open edge on the outlet, the normals outward, the
// outlet opening onto the inside.
static gf_status gf_ms_check(const gf_meshshape *ms, const char *path)
{
    const gf_sdf *s = &ms->sdf;
    const gf_stl *m = &s->mesh;
    const double tol = 1e-6 * fmax(1.0, fabs(ms->exit_z));
    char outlet[160];
    if (ms->shape == GF_ORIFICE_SLIT)
        snprintf(outlet, sizeof outlet, "the slit |x - %g| < %g (container.orifice_x, orifice_diameter / 2)", ms->ox,
                 ms->hole);
    else
        snprintf(outlet, sizeof outlet, "the disc of radius %g about (%g, %g) (container.orifice_diameter / 2, "
                 "orifice_x, orifice_y)", ms->hole, ms->ox, ms->oy);
    for (size_t t = 0; t < m->nt; t++)
        for (int k = 0; k < 3; k++) {
            const double *a = m->v[m->t[t][k]];
            if (a[2] < ms->exit_z - tol)
                return gf_error_set(GF_ERR_FORMAT,
                                    "%s: triangle %zu: its vertex (%g, %g, %g) is below the exit plane z = %g "
                                    "(container.exit_z): the outlet must be the mesh's lowest part",
                                    path, t + 1, a[0], a[1], a[2], ms->exit_z);
        }
    bool open = false;
    for (size_t t = 0; t < m->nt; t++)
        for (int k = 0; k < 3; k++) {
            if (m->adj[t][k] >= 0) continue;
            open = true;
            const double *a = m->v[m->t[t][k]], *b = m->v[m->t[t][(k + 1) % 3]];
            for (int e = 0; e < 2; e++) {
                const double *p = e ? b : a;
                double dx = p[0] - ms->ox, dy = p[1] - ms->oy;
                bool on = fabs(p[2] - ms->exit_z) <= tol &&
                          (ms->shape == GF_ORIFICE_SLIT ? fabs(dx) <= ms->hole + 0.05
                                                        : sqrt(dx * dx + dy * dy) <= ms->hole + 0.05);
                if (!on)
                    return gf_error_set(GF_ERR_FORMAT,
                                        "%s: triangle %zu: its edge (%g, %g, %g)-(%g, %g, %g) is open (no triangle "
                                        "on its other side) away from the outlet, %s on the exit plane z = %g: the "
                                        "mesh must be closed (watertight) except for the outlet",
                                        path, t + 1, a[0], a[1], a[2], b[0], b[1], b[2], outlet, ms->exit_z);
            }
        }
    // The volume enclosed, the outlet closed by a lid on the exit plane: with
    // the apex on that plane, the lid adds nothing.
    const double o[3] = {ms->ox, ms->oy, ms->exit_z};
    double vol = 0.0;
    for (size_t t = 0; t < m->nt; t++) {
        double e[3][3];
        for (int k = 0; k < 3; k++)
            for (int a = 0; a < 3; a++) e[k][a] = m->v[m->t[t][k]][a] - o[a];
        vol += (e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) - e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
                e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0])) / 6.0;
    }
    if (!(vol > 0.0))
        return gf_error_set(GF_ERR_FORMAT,
                            "%s: triangle 1 (and every other): the mesh is inside out, its normals point inward "
                            "(enclosed volume %.6g d^3): STL vertices run counter-clockwise seen from outside; "
                            "reverse each triangle's vertex order",
                            path, vol);
    double y = ms->shape == GF_ORIFICE_SLIT ? 0.5 * (s->lo[1] + s->hi[1]) : ms->oy;
    const double in[3] = {ms->ox, y, ms->exit_z + fmin(0.25, 0.5 * (s->hi[2] - s->lo[2]))};
    if (!gf_sdf_inside(s, in))
        return gf_error_set(GF_ERR_FORMAT,
                            "%s: the outlet, %s on the exit plane z = %g, does not open onto the mesh's inside "
                            "(the point (%g, %g, %g) just above it is outside)%s",
                            path, outlet, ms->exit_z, in[0], in[1], in[2],
                            open ? "" : "; the mesh is closed: its base must lie on the exit plane over the outlet");
    return GF_OK;
}

static void gf_ms_release(gf_meshshape *ms)
{
    const gf_stl *m = &ms->sdf.mesh;
    GF_DELETE(ms->tconvex, m->nt);
    GF_DELETE(ms->tconcave, m->nt);
    GF_DELETE(ms->vconvex, m->nv);
    GF_DELETE(ms->vstart, m->nv + 1);
    GF_DELETE(ms->vnbr, 6 * m->nt);
    GF_DELETE(ms->vfirst, m->nv);
    gf_sdf_free(&ms->sdf);
}

static gf_status gf_ms_build(const gf_config *cfg, gf_meshshape *ms)
{
    *ms = (gf_meshshape){
        .shape = cfg->orifice_shape,
        .hole = 0.5 * cfg->orifice_diameter,
        .ox = cfg->orifice_x,
        .oy = cfg->orifice_y,
        .exit_z = cfg->exit_z,
    };
    unsigned char *data = NULL;
    size_t len = 0, cap = 0;
    gf_status st = gf_fs_read_all(cfg->container_mesh, GF_STL_MAX_BYTES, &data, &len, &cap);
    if (st != GF_OK) return st;
    uint64_t h = 1469598103934665603ull;
    for (size_t i = 0; i < len; i++) h = (h ^ data[i]) * 1099511628211ull;
    ms->digest = h;
    gf_stl mesh;
    st = gf_stl_parse(cfg->container_mesh, data, len, cfg->container_mesh_scale, &mesh);
    gf_free(data, cap);
    if (st != GF_OK) return st;
    st = gf_sdf_build(&ms->sdf, &mesh, cfg->exit_z, cfg->container_mesh_resolution);
    if (st == GF_OK) st = gf_ms_topology(ms);
    if (st == GF_OK) {
        ms->closed = true;
        for (size_t t = 0; t < ms->sdf.mesh.nt && ms->closed; t++)
            for (int k = 0; k < 3; k++)
                if (ms->sdf.mesh.adj[t][k] < 0) ms->closed = false;
        ms->top = ms->sdf.hi[2] - 1.0;
        st = gf_ms_check(ms, cfg->container_mesh);
    }
    if (st != GF_OK) gf_ms_release(ms);
    return st;
}

// ---- the cache ------------------------------------------------------------------

typedef struct gf_ms_entry {
    struct gf_ms_entry *next;
    char path[GF_PATH_MAX];
    double scale, res, hole, ox, oy, exit_z;
    gf_orifice_shape shape;
    gf_meshshape ms;
} gf_ms_entry;

static gf_ms_entry *gf_ms_cache;
static atomic_flag gf_ms_lock = ATOMIC_FLAG_INIT;

static bool gf_ms_same(const gf_ms_entry *e, const gf_config *cfg)
{
    return strcmp(e->path, cfg->container_mesh) == 0 && e->scale == cfg->container_mesh_scale &&
           e->res == cfg->container_mesh_resolution && e->hole == 0.5 * cfg->orifice_diameter &&
           e->ox == cfg->orifice_x && e->oy == cfg->orifice_y && e->exit_z == cfg->exit_z &&
           e->shape == cfg->orifice_shape;
}

gf_status gf_meshshape_load(const gf_config *cfg, const gf_meshshape **out)
{
    *out = NULL;
    if (!cfg->container_mesh[0])
        return gf_error_set(GF_ERR_PARAM, "container.shape = mesh needs container.mesh = FILE.stl");
    while (atomic_flag_test_and_set(&gf_ms_lock)) {
    }
    gf_status st = GF_OK;
    gf_ms_entry *e = gf_ms_cache;
    while (e && !gf_ms_same(e, cfg)) e = e->next;
    if (!e) {
        e = gf_alloc(sizeof *e);
        if (!e) st = gf_error_set(GF_ERR_NOMEM, "out of memory for a mesh");
        if (st == GF_OK) st = gf_ms_build(cfg, &e->ms);
        if (st == GF_OK) {
            snprintf(e->path, sizeof e->path, "%s", cfg->container_mesh);
            e->scale = cfg->container_mesh_scale;
            e->res = cfg->container_mesh_resolution;
            e->hole = 0.5 * cfg->orifice_diameter;
            e->ox = cfg->orifice_x;
            e->oy = cfg->orifice_y;
            e->exit_z = cfg->exit_z;
            e->shape = cfg->orifice_shape;
            e->next = gf_ms_cache;
            gf_ms_cache = e;
        } else {
            gf_free(e, sizeof *e);
            e = NULL;
        }
    }
    atomic_flag_clear(&gf_ms_lock);
    if (e) *out = &e->ms;
    return st;
}

void gf_meshshape_cache_clear(void)
{
    while (atomic_flag_test_and_set(&gf_ms_lock)) {
    }
    while (gf_ms_cache) {
        gf_ms_entry *e = gf_ms_cache;
        gf_ms_cache = e->next;
        gf_ms_release(&e->ms);
        gf_free(e, sizeof *e);
    }
    atomic_flag_clear(&gf_ms_lock);
}

void gf_meshshape_fill(gf_container *c, const gf_config *cfg)
{
    const gf_meshshape *ms = NULL;
    if (gf_meshshape_load(cfg, &ms) != GF_OK) gf_error_clear(); // validated before: cached; else no inside
    c->ops = &gf_mesh_ops;
    c->mesh = ms;
    c->exit_z = cfg->exit_z;
    c->pipe = fmax(0.0, -cfg->exit_z); // the packing is built from the outlet up
    if (ms) {
        c->xlo = ms->sdf.lo[0];
        c->xhi = ms->sdf.hi[0];
        c->ylo = ms->sdf.lo[1];
        c->yhi = ms->sdf.hi[1];
    }
}

// ---- the configuration's check ------------------------------------------------

// container.shape = mesh: the file read and checked (its messages lead with
// where container.mesh was set), its bounding box as container.width and
// depth (symmetric about x = y = 0, as the box code reads them).
static gf_status gf_ms_config_check(void *arg)
{
    gf_config *cfg = arg;
    if (cfg->container_shape != GF_SHAPE_MESH) return GF_OK;
    char where[GF_PATH_MAX + 32];
    if (gf_config_where(cfg, "container.mesh", where, sizeof where) != GF_OK) snprintf(where, sizeof where, "?");
    const gf_meshshape *ms;
    gf_status st = gf_meshshape_load(cfg, &ms);
    if (st != GF_OK) {
        char why[1024];
        snprintf(why, sizeof why, "%s", gf_last_error());
        return gf_error_set(st == GF_ERR_NOMEM ? st : GF_ERR_PARAM, "%s: container.mesh: %s", where, why);
    }
    cfg->container_width = 2.0 * fmax(fabs(ms->sdf.lo[0]), fabs(ms->sdf.hi[0]));
    cfg->container_depth = 2.0 * fmax(fabs(ms->sdf.lo[1]), fabs(ms->sdf.hi[1]));
    return GF_OK;
}

__attribute__((constructor)) static void gf_ms_register(void) { gf_shape_check_set(gf_ms_config_check); }
