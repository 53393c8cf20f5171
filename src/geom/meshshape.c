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
#include <stdio.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "geom/mesh.h"

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
    if (ms->closed && fabs(q[2] - ms->z_exit) < 1e-9 && gf_ms_over_hole(ms, q[0], q[1])) return true;
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
        in = s->vopen[v] ? p[2] >= ms->z_exit : d[0] * vn[0] + d[1] * vn[1] + d[2] * vn[2] <= 0.0;
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
    const gf_meshshape *ms = c->u.mesh;
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
    const gf_meshshape *ms = c->u.mesh;
    if (!ms) return false;
    double m = r - tol, p[3] = {x, y, z};
    bool hole = gf_container_over_hole(c, x, y);
    if (z < ms->z_exit) return hole; // passing through the outlet, as the box's
    double d = gf_sdf_distance(&ms->sdf, p, fmax(m, 0.0));
    if (ms->closed && hole && z < ms->z_exit + fmax(m, 0.0)) return true;
    if (!(d > 0.0)) return hole && z < ms->z_exit + fmax(m, 0.0) && d > -1e-9;
    return d >= m || (hole && z < ms->z_exit + m);
}

static void gf_ms_spot_clamp(const gf_container *c, double n[3], double dw)
{
    const gf_meshshape *ms = c->u.mesh;
    if (!ms || n[2] < ms->z_exit) return;
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
    const gf_meshshape *ms = c->u.mesh;
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
    const gf_meshshape *ms = c->u.mesh;
    if (!ms) return r;
    const gf_sdf *s = &ms->sdf;
    double z = s->hi[2] - r, step = fmax(0.05, fmin(0.25, 0.5 * r));
    double p[3] = {x, y, z};
    if (gf_sdf_distance(s, p, r) < r) return z;
    double lo = ms->z_exit + r;
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
double gf_meshshape_section(const gf_meshshape *ms, double z)
{
    if (!ms || z < ms->z_exit) return 0.0;
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

static double gf_ms_section_area(const gf_container *c, double z) { return gf_meshshape_section(c->u.mesh, z); }

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


// ---- packing, analysis, pictures, DEM --------------------------------------------

// The field bounds the true distance (gf_sdf_value: within h sqrt 3 of it):
// clear when even the worst case leaves room for the sphere.
static bool gf_ms_clear(const gf_container *c, double x, double y, double z, double m)
{
    const gf_meshshape *ms = c->u.mesh;
    if (!ms || z < ms->z_exit + m) return false;
    const double p[3] = {x, y, z};
    return gf_sdf_value(&ms->sdf, p) > m + ms->sdf.h * gf_ms_sqrt3 * 1.001 + 1e-9;
}

static void gf_ms_radii(const gf_container *c, double r[2])
{
    const gf_meshshape *ms = c->u.mesh;
    r[0] = 0.0;
    r[1] = ms && ms->axis_r > 0.0 ? ms->axis_r : hypot(fmax(-c->xlo, c->xhi), fmax(-c->ylo, c->yhi));
}

static gf_profile_coord gf_ms_profile(const gf_container *c)
{
    // A solid of revolution about z (meshload.c) is measured as a cylinder;
    // any other mesh across x, as a box.
    const gf_meshshape *ms = c->u.mesh;
    return ms && ms->axis_r > 0.0 ? GF_PROFILE_R : GF_PROFILE_X;
}

// ---- the outline: the mesh cut by y = 0, chained, simplified -----------------

typedef double gf_ms_seg[4]; // x0, z0, x1, z1
typedef double gf_ms_pt[2];  // x, z

static bool gf_ms_near2(const double a[2], const double b[2], double eps)
{
    return fabs(a[0] - b[0]) <= eps && fabs(a[1] - b[1]) <= eps;
}

// Drops repeated and collinear points of the polyline p (n points; closed:
// the last joins the first); returns the new count.
static int gf_ms_simplify(double (*p)[2], int n, bool closed, double eps)
{
    int changed = 1;
    while (changed && n > 2) {
        changed = 0;
        for (int j = 0; j < n && n > 2; j++) {
            if (!closed && (j == 0 || j == n - 1)) continue;
            const double *a = p[(j + n - 1) % n], *b = p[j], *q = p[(j + 1) % n];
            double ux = b[0] - a[0], uz = b[1] - a[1], vx = q[0] - b[0], vz = q[1] - b[1];
            double lu = hypot(ux, uz), lv = hypot(vx, vz);
            bool drop = lu <= eps || lv <= eps || (fabs(ux * vz - uz * vx) <= 1e-9 * lu * lv && ux * vx + uz * vz > 0.0);
            if (!drop) continue;
            memmove(p[j], p[j + 1], (size_t)(n - j - 1) * sizeof p[0]);
            n--;
            j--;
            changed = 1;
        }
    }
    return n;
}

static void gf_ms_box_outline(const gf_container *c, double ztop, gf_outline *o)
{
    const double q[4][2] = {{c->xlo, c->z_exit}, {c->xhi, c->z_exit}, {c->xhi, ztop}, {c->xlo, ztop}};
    o->n = 4;
    memcpy(o->p, q, sizeof q);
}

// The slice's segments chained into the longest polyline (a closed mesh's
// slice is one loop; an open one's runs from one rim of the outlet over the
// lid to the other), simplified and clamped at ztop: the inside. The walls
// are its segments but the lid above ztop and the exit plane over the outlet.
static void gf_ms_outline(const gf_container *c, double ztop, gf_outline *o)
{
    const gf_meshshape *ms = c->u.mesh;
    if (!ms) {
        gf_ms_box_outline(c, ztop, o);
        return;
    }
    const size_t nt = ms->sdf.mesh.nt;
    double (*seg)[4] = GF_NEW(gf_ms_seg, nt);
    double (*pt)[2] = GF_NEW(gf_ms_pt, 2 * nt + 2);
    bool *used = GF_NEW(bool, nt);
    size_t ns = 0;
    if (seg && pt && used)
        for (size_t t = 0; t < nt; t++)
            if (gf_meshshape_slice_y(ms, 0.0, t, seg[ns])) ns++;
    const double eps = 1e-7 * fmax(1.0, ms->sdf.hi[2] - ms->sdf.lo[2]);
    int best = 0;
    bool closed = false;
    for (size_t s0 = 0; s0 < ns; s0++) {
        if (used[s0]) continue;
        // Chain from segment s0 both ways into pt[] (kept when the longest).
        size_t cap = 2 * nt + 2, head = nt + 1, tail = head; // pt[head..tail]
        double (*q)[2] = pt; // reuse: the longest chain is copied to the front when found
        double tmp[2][2] = {{seg[s0][0], seg[s0][1]}, {seg[s0][2], seg[s0][3]}};
        used[s0] = true;
        double (*ch)[2] = GF_NEW(gf_ms_pt, cap);
        if (!ch) break;
        memcpy(ch[head], tmp[0], sizeof tmp[0]);
        memcpy(ch[++tail], tmp[1], sizeof tmp[1]);
        for (bool grew = true; grew;) {
            grew = false;
            for (size_t s = 0; s < ns; s++) {
                if (used[s]) continue;
                const double a[2] = {seg[s][0], seg[s][1]}, b[2] = {seg[s][2], seg[s][3]};
                const double *add = NULL;
                bool front = false;
                if (gf_ms_near2(a, ch[tail], eps)) add = b;
                else if (gf_ms_near2(b, ch[tail], eps)) add = a;
                else if (head > 0 && gf_ms_near2(a, ch[head], eps)) add = b, front = true;
                else if (head > 0 && gf_ms_near2(b, ch[head], eps)) add = a, front = true;
                if (!add || (!front && tail + 1 >= cap)) continue;
                used[s] = grew = true;
                if (front) memcpy(ch[--head], add, sizeof ch[0]);
                else memcpy(ch[++tail], add, sizeof ch[0]);
            }
        }
        int n = (int)(tail - head + 1);
        if (n > best) {
            memcpy(q, ch + head, (size_t)n * sizeof ch[0]);
            best = n;
        }
        GF_DELETE(ch, cap);
    }
    GF_DELETE(seg, nt);
    GF_DELETE(used, nt);
    if (best < 3) {
        GF_DELETE(pt, 2 * nt + 2);
        gf_ms_box_outline(c, ztop, o);
        return;
    }
    int n = best;
    closed = gf_ms_near2(pt[0], pt[n - 1], eps);
    if (closed) n--;
    for (int j = 0; j < n; j++) pt[j][1] = fmin(pt[j][1], ztop);
    n = gf_ms_simplify(pt, n, closed, eps);
    // More corners than an outline holds (a finely curved STL): every k-th.
    if (n > GF_OUTLINE_MAX) {
        int m = 0;
        for (int j = 0; j < GF_OUTLINE_MAX; j++) {
            int from = (int)((double)j * (n - 1) / (GF_OUTLINE_MAX - 1) + 0.5);
            memcpy(pt[m++], pt[from], sizeof pt[0]);
        }
        n = m;
    }
    o->n = n;
    memcpy(o->p, pt, (size_t)n * sizeof pt[0]);
    // The walls: runs of segments that are neither the cut at ztop nor the
    // exit plane over the outlet. A loop starts at such a segment.
    const double tol = 1e-6 * fmax(1.0, fabs(ms->z_exit));
    int nseg = closed ? n : n - 1, start = 0;
    bool wall[GF_OUTLINE_MAX];
    for (int j = 0; j < nseg; j++) {
        const double *a = pt[j], *b = pt[(j + 1) % n];
        bool lid = a[1] >= ztop - 1e-9 && b[1] >= ztop - 1e-9;
        double mx = 0.5 * (a[0] + b[0]);
        bool hole = fabs(a[1] - ms->z_exit) <= tol && fabs(b[1] - ms->z_exit) <= tol && fabs(mx - c->ox) < c->hole;
        wall[j] = !lid && !hole;
        if (closed && !wall[j] && start == 0) start = j + 1;
    }
    int k = -1;
    bool in = false;
    for (int i = 0; i < nseg; i++) {
        int j = (start + i) % nseg;
        if (!wall[j]) {
            in = false;
            continue;
        }
        if (!in) {
            if (k == 1) break; // a third run (rare): left out of the picture
            k++;
            in = true;
            memcpy(o->wall[k][o->nwall[k]++], pt[j], sizeof pt[0]);
        }
        if (o->nwall[k] < GF_OUTLINE_MAX) memcpy(o->wall[k][o->nwall[k]++], pt[(j + 1) % n], sizeof pt[0]);
    }
    GF_DELETE(pt, 2 * nt + 2);
}

// The STL's own triangles, whatever the height.
static gf_status gf_ms_mesh(const gf_container *c, double top, int segments, gf_mesh *m)
{
    (void)top;
    (void)segments;
    const gf_meshshape *ms = c->u.mesh;
    if (!ms) return GF_OK;
    const gf_stl *s = &ms->sdf.mesh;
    bool ok = true;
    for (size_t v = 0; v < s->nv && ok; v++) ok = gf_mesh_vertex(m, s->v[v][0], s->v[v][1], s->v[v][2]) != SIZE_MAX;
    for (size_t t = 0; t < s->nt && ok; t++) ok = gf_mesh_tri(m, s->t[t][0], s->t[t][1], s->t[t][2]);
    if (ok) return GF_OK;
    gf_mesh_free(m);
    return gf_error_set(GF_ERR_NOMEM, "out of memory for the container mesh");
}

// LAMMPS cannot hold these walls: granflow dem asks lammps_walls with f =
// NULL first and stops with this message.
static gf_status gf_ms_lammps_refuse(const gf_container *c)
{
    return gf_error_set(GF_ERR_PARAM,
                        "container.shape = mesh (%s): granflow dem cannot model it: LAMMPS' granular walls "
                        "(fix wall/gran, wall/gran/region) take planes, cylinders and regions, not a triangle "
                        "mesh; run the spot model on it (granflow run), or describe the container as a box, "
                        "cylinder or wedge for DEM",
                        c->u.mesh ? c->u.mesh->path : "no mesh loaded");
}

static gf_status gf_ms_lammps_walls(const gf_container *c, FILE *f, const char *pre, const char *law, double zlo,
                                    double zhi)
{
    (void)f;
    (void)pre;
    (void)law;
    (void)zlo;
    (void)zhi;
    return gf_ms_lammps_refuse(c);
}

static void gf_ms_lammps_base(const gf_container *c, FILE *f, const char *law, double zlo)
{
    (void)c;
    (void)law;
    (void)zlo;
    if (f) fprintf(f, "# container.shape = mesh: no LAMMPS walls (granflow dem refuses it before writing)\n");
}

static gf_status gf_ms_lammps_pour(const gf_container *c, FILE *f, double inset, double zlo, double zhi)
{
    (void)f;
    (void)inset;
    (void)zlo;
    (void)zhi;
    return gf_ms_lammps_refuse(c);
}

static int gf_ms_describe(const gf_container *c, const char *const where[3], char *buf, size_t n)
{
    const gf_meshshape *ms = c->u.mesh;
    return snprintf(buf, n, "mesh %s (%s), %zu triangles, scale %s, %g x %g x %g d, outlet %g d (%s)",
                    ms ? ms->path : "(not loaded)", where[0], ms ? ms->sdf.mesh.nt : (size_t)0, where[1],
                    c->xhi - c->xlo, c->yhi - c->ylo, ms ? ms->sdf.hi[2] - ms->sdf.lo[2] : 0.0, 2.0 * c->hole,
                    where[2]);
}

static const char *gf_ms_outlet_name(const gf_container *c)
{
    return c->z_exit < 0.0 ? "outlet on the exit plane" : "orifice";
}

// The mesh from the cache (validation loaded it; NULL when it cannot be
// loaded: then the container has no inside), its bounding box, the outlet
// the orifice keys' on the exit plane.
static void gf_ms_make(gf_container *c, const gf_container_defs *d)
{
    const gf_meshshape *ms = NULL;
    if (gf_meshshape_load(d, &ms) != GF_OK) gf_error_clear();
    c->u.mesh = ms;
    c->z_exit = d->exit_level;
    c->z_bottom = fmin(0.0, d->exit_level); // the packing is built from the outlet up
    c->gate_z = fmin(0.0, d->exit_level);
    c->z_col = ms ? ms->z_col : 0.0;
    if (ms) {
        c->xlo = ms->sdf.lo[0];
        c->xhi = ms->sdf.hi[0];
        c->ylo = ms->sdf.lo[1];
        c->yhi = ms->sdf.hi[1];
    }
}

static const gf_shape_ops gf_mesh_ops = {
    .walls = gf_ms_walls_of,
    .push = gf_ms_push,
    .contains = gf_ms_contains,
    .spot_clamp = gf_ms_spot_clamp,
    .mirrors = gf_container_mirror_walls,
    .inside_xy = gf_ms_inside_xy,
    .floor_z = gf_ms_floor_z,
    .section_area = gf_ms_section_area,
    .slice_volume = gf_container_slice_volume_by_sections,
    .clear = gf_ms_clear,
    .radii = gf_ms_radii,
    .profile = gf_ms_profile,
    .outline = gf_ms_outline,
    .mesh = gf_ms_mesh,
    .lammps_walls = gf_ms_lammps_walls,
    .lammps_base = gf_ms_lammps_base,
    .lammps_pour = gf_ms_lammps_pour,
    .describe = gf_ms_describe,
    .outlet_name = gf_ms_outlet_name,
};

static const char *const gf_ms_keys[] = {"container.mesh",          "container.mesh_scale",
                                         "container.orifice_diameter", "container.mesh_resolution",
                                         "container.orifice_shape", "container.orifice_x",
                                         "container.orifice_y",     "container.exit_z",
                                         NULL};

const gf_shape gf_mesh_shape = {
    .name = "mesh",
    .id = GF_SHAPE_MESH,
    .ops = &gf_mesh_ops,
    .keys = gf_ms_keys,
    .make = gf_ms_make,
    .rectangular = false,
    .validate = gf_meshshape_validate,
};
