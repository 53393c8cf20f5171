// SPDX-License-Identifier: MIT
// A mesh container's walls read, checked and kept (geom/meshshape.h): the
// STL's topology (convex and concave edges, each vertex's neighbours), the
// checks that leave the outlet the only way out, the cache every container
// of the same configuration shares, and the mesh row's validate op that
// configuration's validation reaches through core/shape_check.h (config
// cannot call geom).
#include "geom/meshshape.h"

#include <math.h>
#include <stdatomic.h>
#include <stdio.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "core/fs.h"

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
    const double tol = 1e-6 * fmax(1.0, fabs(ms->z_exit));
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
            if (a[2] < ms->z_exit - tol)
                return gf_error_set(GF_ERR_FORMAT,
                                    "%s: triangle %zu: its vertex (%g, %g, %g) is below the exit plane z = %g "
                                    "(container.exit_z): the outlet must be the mesh's lowest part",
                                    path, t + 1, a[0], a[1], a[2], ms->z_exit);
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
                bool on = fabs(p[2] - ms->z_exit) <= tol &&
                          (ms->shape == GF_ORIFICE_SLIT ? fabs(dx) <= ms->hole + 0.05
                                                        : sqrt(dx * dx + dy * dy) <= ms->hole + 0.05);
                if (!on)
                    return gf_error_set(GF_ERR_FORMAT,
                                        "%s: triangle %zu: its edge (%g, %g, %g)-(%g, %g, %g) is open (no triangle "
                                        "on its other side) away from the outlet, %s on the exit plane z = %g: the "
                                        "mesh must be closed (watertight) except for the outlet",
                                        path, t + 1, a[0], a[1], a[2], b[0], b[1], b[2], outlet, ms->z_exit);
            }
        }
    // The volume enclosed, the outlet closed by a lid on the exit plane: with
    // the apex on that plane, the lid adds nothing.
    const double o[3] = {ms->ox, ms->oy, ms->z_exit};
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
    const double in[3] = {ms->ox, y, ms->z_exit + fmin(0.25, 0.5 * (s->hi[2] - s->lo[2]))};
    if (!gf_sdf_inside(s, in))
        return gf_error_set(GF_ERR_FORMAT,
                            "%s: the outlet, %s on the exit plane z = %g, does not open onto the mesh's inside "
                            "(the point (%g, %g, %g) just above it is outside)%s",
                            path, outlet, ms->z_exit, in[0], in[1], in[2],
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

// Where the straight column starts (gf_container.z_col: the bulk region and
// granflow dem's fill measure from there): the lowest of 64 levels from the
// floor to under the lid above which every cross-section is within 1 % of
// the one under the lid (a funnel's top; the floor for straight walls).
static double gf_ms_column_start(const gf_meshshape *ms)
{
    const double z0 = fmax(0.0, ms->z_exit), z1 = ms->sdf.hi[2] - 0.5;
    if (!(z1 > z0)) return z0;
    const double a1 = gf_meshshape_section(ms, z1);
    double zc = z1;
    for (int k = 63; k >= 0; k--) {
        double z = z0 + (z1 - z0) * k / 64.0;
        if (!(fabs(gf_meshshape_section(ms, z) - a1) <= 0.01 * a1)) break;
        zc = z;
    }
    return zc;
}

// Whether the mesh is a solid of revolution about the z axis (a cylinder, a
// cone, a hopper's funnel), as a cylinder is: its profiles are then radial,
// v_z(r), and its bulk an annulus, so that a mesh of examples/hopper-60.ini
// is measured as the analytic cylinder is. The test: a centred circular
// outlet, the axis inside at every level above the outlet, and at 24 levels
// and 8 radii the distance to the walls (out to the field's band) equal on
// 16 directions within 0.05 d plus the chord
// of a 64-gon (a CAD export's facets). Returns the wall's radius, or 0.
static const double gf_ms_pi = 3.14159265358979323846;

static double gf_ms_axis_radius(const gf_meshshape *ms)
{
    if (ms->shape != GF_ORIFICE_CIRCLE || fabs(ms->ox) > 1e-9 || fabs(ms->oy) > 1e-9) return 0.0;
    const gf_sdf *s = &ms->sdf;
    double rmax = 0.0;
    for (int a = 0; a < 2; a++) rmax = fmax(rmax, fmax(-s->lo[a], s->hi[a]));
    if (!(rmax > 0.0)) return 0.0;
    for (int a = 0; a < 2; a++) // the bounding box centred on the axis, a square
        if (fabs(s->lo[a] + s->hi[a]) > 0.05 * rmax || fabs(s->hi[a] - s->lo[a] - 2.0 * rmax) > 0.05 * rmax) return 0.0;
    const double tol = 0.05 + rmax * (1.0 - cos(gf_ms_pi / 64.0));
    const double z0 = fmax(0.0, ms->z_exit), z1 = ms->top;
    if (!(z1 > z0)) return 0.0;
    for (int k = 0; k < 24; k++) {
        double z = z0 + (z1 - z0) * (k + 0.5) / 24.0, axis[3] = {0.0, 0.0, z};
        if (!gf_sdf_inside(s, axis)) return 0.0;
        for (int i = 1; i <= 8; i++) {
            double r = rmax * i / 8.0, lo = INFINITY, hi = -INFINITY;
            for (int j = 0; j < 16; j++) {
                double p[3] = {r * cos(2.0 * gf_ms_pi * j / 16.0), r * sin(2.0 * gf_ms_pi * j / 16.0), z};
                // Exact within the field's band (the interpolation errs by up
                // to h sqrt 3), clamped beyond it as the field is.
                double d = fmin(fmax(gf_sdf_distance(s, p, 1e30), -s->band), s->band);
                lo = fmin(lo, d);
                hi = fmax(hi, d);
            }
            if (hi - lo > tol) return 0.0;
        }
    }
    return rmax;
}

static gf_status gf_ms_build(const gf_container_defs *d, gf_meshshape *ms)
{
    *ms = (gf_meshshape){
        .shape = d->orifice.shape,
        .hole = 0.5 * d->orifice.diameter,
        .ox = d->orifice.x,
        .oy = d->orifice.y,
        .z_exit = d->exit_level,
    };
    unsigned char *data = NULL;
    size_t len = 0, cap = 0;
    gf_status st = gf_fs_read_all(d->mesh, GF_STL_MAX_BYTES, &data, &len, &cap);
    if (st != GF_OK) return st;
    uint64_t h = 1469598103934665603ull;
    for (size_t i = 0; i < len; i++) h = (h ^ data[i]) * 1099511628211ull;
    ms->digest = h;
    gf_stl mesh;
    st = gf_stl_parse(d->mesh, data, len, d->mesh_scale, &mesh);
    gf_free(data, cap);
    if (st != GF_OK) return st;
    st = gf_sdf_build(&ms->sdf, &mesh, d->exit_level, d->mesh_resolution);
    if (st == GF_OK) st = gf_ms_topology(ms);
    if (st == GF_OK) {
        ms->closed = true;
        for (size_t t = 0; t < ms->sdf.mesh.nt && ms->closed; t++)
            for (int k = 0; k < 3; k++)
                if (ms->sdf.mesh.adj[t][k] < 0) ms->closed = false;
        ms->top = ms->sdf.hi[2] - 1.0;
        st = gf_ms_check(ms, d->mesh);
    }
    if (st == GF_OK) {
        snprintf(ms->path, sizeof ms->path, "%s", d->mesh);
        ms->z_col = gf_ms_column_start(ms);
        ms->axis_r = gf_ms_axis_radius(ms);
    }
    if (st != GF_OK) gf_ms_release(ms);
    return st;
}

// ---- the cache ------------------------------------------------------------------

typedef struct gf_ms_entry {
    struct gf_ms_entry *next;
    char path[GF_PATH_MAX];
    double scale, res, hole, ox, oy, z_exit;
    gf_orifice_shape shape;
    gf_meshshape ms;
} gf_ms_entry;

static gf_ms_entry *gf_ms_cache;
static atomic_flag gf_ms_lock = ATOMIC_FLAG_INIT;

static bool gf_ms_same(const gf_ms_entry *e, const gf_container_defs *d)
{
    return strcmp(e->path, d->mesh) == 0 && e->scale == d->mesh_scale && e->res == d->mesh_resolution &&
           e->hole == 0.5 * d->orifice.diameter && e->ox == d->orifice.x && e->oy == d->orifice.y &&
           e->z_exit == d->exit_level && e->shape == d->orifice.shape;
}

gf_status gf_meshshape_load(const gf_container_defs *d, const gf_meshshape **out)
{
    *out = NULL;
    if (!d->mesh[0])
        return gf_error_set(GF_ERR_PARAM, "container.shape = mesh needs container.mesh = FILE.stl");
    while (atomic_flag_test_and_set(&gf_ms_lock)) {
    }
    gf_status st = GF_OK;
    gf_ms_entry *e = gf_ms_cache;
    while (e && !gf_ms_same(e, d)) e = e->next;
    if (!e) {
        e = gf_alloc(sizeof *e);
        if (!e) st = gf_error_set(GF_ERR_NOMEM, "out of memory for a mesh");
        if (st == GF_OK) st = gf_ms_build(d, &e->ms);
        if (st == GF_OK) {
            snprintf(e->path, sizeof e->path, "%s", d->mesh);
            e->scale = d->mesh_scale;
            e->res = d->mesh_resolution;
            e->hole = 0.5 * d->orifice.diameter;
            e->ox = d->orifice.x;
            e->oy = d->orifice.y;
            e->z_exit = d->exit_level;
            e->shape = d->orifice.shape;
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

gf_status gf_meshshape_digest(const gf_container_defs *d, uint64_t *digest)
{
    const gf_meshshape *ms;
    gf_status st = gf_meshshape_load(d, &ms);
    if (st == GF_OK) *digest = ms->digest;
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

// ---- the check of its keys (gf_config_validate) ----------------------------

// container.shape = mesh: the file read and checked (its messages lead with
// where container.mesh was set), its bounding box as container.width and
// depth (symmetric about x = y = 0, as the box code reads them).
gf_status gf_meshshape_validate(const gf_container_defs *d, gf_config *cfg)
{
    if (!d->mesh[0]) {
        gf_config_msg m;
        gf_config_msg_make(&m, cfg, "container.shape", "container.mesh");
        return gf_error_set(GF_ERR_PARAM, "%s%s = mesh needs %s = FILE.stl (the walls as an STL file)", m.lead,
                            m.key[0], m.key[1]);
    }
    char where[GF_PATH_MAX + 32];
    if (gf_config_where(cfg, "container.mesh", where, sizeof where) != GF_OK) snprintf(where, sizeof where, "?");
    const gf_meshshape *ms;
    gf_status st = gf_meshshape_load(d, &ms);
    if (st != GF_OK) {
        char why[1024];
        snprintf(why, sizeof why, "%s", gf_last_error());
        return gf_error_set(st == GF_ERR_NOMEM ? st : GF_ERR_PARAM, "%s: container.mesh: %s", where, why);
    }
    gf_config_set_extent(cfg, 2.0 * fmax(fabs(ms->sdf.lo[0]), fabs(ms->sdf.hi[0])),
                         2.0 * fmax(fabs(ms->sdf.lo[1]), fabs(ms->sdf.hi[1])));
    return GF_OK;
}
