// SPDX-License-Identifier: MIT
// The container as triangles: side walls and a base with its orifice cut out.
#include "geom/mesh.h"

#include <math.h>
#include <stdint.h>

#include "core/alloc.h"
#include "core/error.h"

#define GF_MESH_PI 3.14159265358979323846

size_t gf_mesh_vertex(gf_mesh *m, double x, double y, double z)
{
    if (m->nv == m->vcap) {
        size_t cap = m->vcap ? 2 * m->vcap : 64;
        double(*v)[3] = gf_realloc(m->v, m->vcap * sizeof *m->v, cap * sizeof *m->v);
        if (!v) return SIZE_MAX;
        m->v = v;
        m->vcap = cap;
    }
    m->v[m->nv][0] = x;
    m->v[m->nv][1] = y;
    m->v[m->nv][2] = z;
    return m->nv++;
}

bool gf_mesh_tri(gf_mesh *m, size_t a, size_t b, size_t c)
{
    if (a == SIZE_MAX || b == SIZE_MAX || c == SIZE_MAX) return false;
    if (m->nt == m->tcap) {
        size_t cap = m->tcap ? 2 * m->tcap : 64;
        size_t(*t)[3] = gf_realloc(m->t, m->tcap * sizeof *m->t, cap * sizeof *m->t);
        if (!t) return false;
        m->t = t;
        m->tcap = cap;
    }
    m->t[m->nt][0] = a;
    m->t[m->nt][1] = b;
    m->t[m->nt][2] = c;
    m->nt++;
    return true;
}

// The quad a-b-c-d (in order around it) as two triangles.
bool gf_mesh_quad(gf_mesh *m, const double a[3], const double b[3], const double c[3], const double d[3])
{
    size_t ia = gf_mesh_vertex(m, a[0], a[1], a[2]), ib = gf_mesh_vertex(m, b[0], b[1], b[2]);
    size_t ic = gf_mesh_vertex(m, c[0], c[1], c[2]), id = gf_mesh_vertex(m, d[0], d[1], d[2]);
    return gf_mesh_tri(m, ia, ib, ic) && gf_mesh_tri(m, ia, ic, id);
}

// Where the ray from the axis at angle th leaves the rectangle.
static void gf_mesh_rect_point(const gf_container *c, double th, double out[3])
{
    double cx = cos(th), sy = sin(th), t = INFINITY;
    if (cx > 0) t = fmin(t, (c->xhi - c->ox) / cx);
    if (cx < 0) t = fmin(t, (c->xlo - c->ox) / cx);
    if (sy > 0) t = fmin(t, (c->yhi - c->oy) / sy);
    if (sy < 0) t = fmin(t, (c->ylo - c->oy) / sy);
    out[0] = c->ox + t * cx;
    out[1] = c->oy + t * sy;
    out[2] = 0.0;
}

// A surface of revolution about the z axis: the segment (r0, z0) - (r1, z1)
// of the (rho, z) half-plane swept round in n steps.
bool gf_mesh_revolve(gf_mesh *m, double r0, double z0, double r1, double z1, int n)
{
    bool ok = true;
    for (int k = 0; k < n && ok; k++) {
        double t0 = 2.0 * GF_MESH_PI * k / n, t1 = 2.0 * GF_MESH_PI * (k + 1) / n;
        double c0 = cos(t0), s0 = sin(t0), c1 = cos(t1), s1 = sin(t1);
        double a[3] = {r0 * c0, r0 * s0, z0}, b[3] = {r0 * c1, r0 * s1, z0};
        double cc[3] = {r1 * c1, r1 * s1, z1}, d[3] = {r1 * c0, r1 * s0, z1};
        ok = gf_mesh_quad(m, a, b, cc, d);
    }
    return ok;
}

static gf_status gf_mesh_failed(gf_mesh *m)
{
    gf_mesh_free(m);
    return gf_error_set(GF_ERR_NOMEM, "out of memory for the container mesh");
}

// The cylinder (cylinder.c): wall, funnel (or flat annulus), outlet pipe and
// the inner column's side and bottom, each a surface of revolution.
gf_status gf_mesh_cylinder(const gf_container *c, double top, int segments, gf_mesh *m)
{
    const gf_cylinder_params *q = &c->u.cyl;
    int n = segments < 8 ? 8 : segments > 4096 ? 4096 : segments;
    double R = q->radius, ro = q->r_out, zt = c->z_col;
    bool ok = gf_mesh_revolve(m, R, zt, R, fmax(top, zt), n) && gf_mesh_revolve(m, ro, 0.0, R, zt, n);
    if (ok && q->pipe > 0.0) ok = gf_mesh_revolve(m, ro, -q->pipe, ro, 0.0, n);
    if (ok && q->r_in > 0.0)
        ok = gf_mesh_revolve(m, q->r_in, zt, q->r_in, fmax(top, zt), n) && gf_mesh_revolve(m, 0.0, zt, q->r_in, zt, n);
    return ok ? GF_OK : gf_mesh_failed(m);
}

gf_status gf_container_mesh(const gf_container *c, double top, int segments, gf_mesh *m)
{
    *m = (gf_mesh){0};
    return c->ops->mesh(c, top, segments, m);
}

// The box (box.c): side walls and the base with its orifice cut out.
gf_status gf_mesh_box(const gf_container *c, double top, int segments, gf_mesh *m)
{
    bool ok = true;
    // Side walls: x = xlo, xhi and y = ylo, yhi from z = 0 to top.
    const double X0 = c->xlo, X1 = c->xhi, Y0 = c->ylo, Y1 = c->yhi;
    const double corners[4][2] = {{X0, Y0}, {X1, Y0}, {X1, Y1}, {X0, Y1}};
    for (int k = 0; k < 4 && ok; k++) {
        const double *p = corners[k], *q = corners[(k + 1) % 4];
        double a[3] = {p[0], p[1], 0.0}, b[3] = {q[0], q[1], 0.0}, cc[3] = {q[0], q[1], top}, d[3] = {p[0], p[1], top};
        ok = gf_mesh_quad(m, a, b, cc, d);
    }
    if (c->shape == GF_ORIFICE_SLIT) { // two plates |x - ox| > hole
        const double L = c->ox - c->hole, R = c->ox + c->hole;
        double a[3] = {X0, Y0, 0}, b[3] = {L, Y0, 0}, cc[3] = {L, Y1, 0}, d[3] = {X0, Y1, 0};
        double e[3] = {R, Y0, 0}, f[3] = {X1, Y0, 0}, g[3] = {X1, Y1, 0}, h[3] = {R, Y1, 0};
        ok = ok && gf_mesh_quad(m, a, b, cc, d) && gf_mesh_quad(m, e, f, g, h);
    } else {
        // The plate between the hole's circle and the rectangle: quads from
        // circle points to where their rays meet the walls, with the four
        // corners' angles among the rays so the outline is exact (rays from
        // the hole's centre (ox, oy)).
        double ang[4096 + 4];
        int n = segments < 8 ? 8 : segments > 4096 ? 4096 : segments, na = 0;
        for (int k = 0; k < n; k++) ang[na++] = 2.0 * GF_MESH_PI * k / n;
        for (int k = 0; k < 4; k++) {
            double th = atan2(corners[k][1] - c->oy, corners[k][0] - c->ox);
            if (th < 0) th += 2.0 * GF_MESH_PI;
            int j = na++;
            while (j > 0 && ang[j - 1] > th) {
                ang[j] = ang[j - 1];
                j--;
            }
            ang[j] = th;
        }
        for (int k = 0; k < na && ok; k++) {
            double t0 = ang[k], t1 = ang[(k + 1) % na];
            double a[3] = {c->ox + c->hole * cos(t0), c->oy + c->hole * sin(t0), 0}, b[3], cc[3];
            double d[3] = {c->ox + c->hole * cos(t1), c->oy + c->hole * sin(t1), 0};
            gf_mesh_rect_point(c, t0, b);
            gf_mesh_rect_point(c, t1, cc);
            ok = gf_mesh_quad(m, a, b, cc, d);
        }
    }
    return ok ? GF_OK : gf_mesh_failed(m);
}

void gf_mesh_free(gf_mesh *m)
{
    gf_free(m->v, m->vcap * sizeof *m->v);
    gf_free(m->t, m->tcap * sizeof *m->t);
    *m = (gf_mesh){0};
}
