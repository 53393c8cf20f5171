// SPDX-License-Identifier: MIT
// The signed distance field of a triangle mesh (geom/sdf.h).
#include "geom/sdf.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"

static double gf_sdf_dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static void gf_sdf_sub(const double a[3], const double b[3], double r[3])
{
    for (int k = 0; k < 3; k++) r[k] = a[k] - b[k];
}

static void gf_sdf_cross(const double a[3], const double b[3], double r[3])
{
    r[0] = a[1] * b[2] - a[2] * b[1];
    r[1] = a[2] * b[0] - a[0] * b[2];
    r[2] = a[0] * b[1] - a[1] * b[0];
}

// Ericson, Real-Time Collision Detection, 5.1.5: the closest point by the
// Voronoi regions of the triangle's vertices, edges and face.
gf_sdf_region gf_sdf_closest(const gf_sdf *s, uint32_t t, const double p[3], double q[3])
{
    const double *a = s->mesh.v[s->mesh.t[t][0]], *b = s->mesh.v[s->mesh.t[t][1]], *c = s->mesh.v[s->mesh.t[t][2]];
    double ab[3], ac[3], ap[3], bp[3], cp[3];
    gf_sdf_sub(b, a, ab);
    gf_sdf_sub(c, a, ac);
    gf_sdf_sub(p, a, ap);
    double d1 = gf_sdf_dot(ab, ap), d2 = gf_sdf_dot(ac, ap);
    if (d1 <= 0.0 && d2 <= 0.0) {
        memcpy(q, a, 3 * sizeof *q);
        return GF_SDF_VERT0;
    }
    gf_sdf_sub(p, b, bp);
    double d3 = gf_sdf_dot(ab, bp), d4 = gf_sdf_dot(ac, bp);
    if (d3 >= 0.0 && d4 <= d3) {
        memcpy(q, b, 3 * sizeof *q);
        return GF_SDF_VERT0 + 1;
    }
    double vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
        double v = d1 / (d1 - d3);
        for (int k = 0; k < 3; k++) q[k] = a[k] + v * ab[k];
        return GF_SDF_EDGE0; // a -> b
    }
    gf_sdf_sub(p, c, cp);
    double d5 = gf_sdf_dot(ab, cp), d6 = gf_sdf_dot(ac, cp);
    if (d6 >= 0.0 && d5 <= d6) {
        memcpy(q, c, 3 * sizeof *q);
        return GF_SDF_VERT0 + 2;
    }
    double vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
        double w = d2 / (d2 - d6);
        for (int k = 0; k < 3; k++) q[k] = a[k] + w * ac[k];
        return GF_SDF_EDGE0 + 2; // c -> a
    }
    double va = d3 * d6 - d5 * d4;
    if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
        double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        for (int k = 0; k < 3; k++) q[k] = b[k] + w * (c[k] - b[k]);
        return GF_SDF_EDGE0 + 1; // b -> c
    }
    double den = 1.0 / (va + vb + vc), v = vb * den, w = vc * den;
    for (int k = 0; k < 3; k++) q[k] = a[k] + ab[k] * v + ac[k] * w;
    return GF_SDF_FACE;
}

// Signed distance from p to triangle t: |p - q|, negative outside, the side
// taken from the pseudonormal of the feature q lies on (Baerentzen & Aanaes
// 2005: the face normal, the sum of an edge's two faces' normals, the
// angle-weighted vertex normal). Near the outlet (open edges and their
// vertices) a point is inside when it is above the exit plane.
static double gf_sdf_tri(const gf_sdf *s, uint32_t t, const double p[3])
{
    double q[3], d[3], pn[3];
    gf_sdf_region r = gf_sdf_closest(s, t, p, q);
    gf_sdf_sub(p, q, d);
    double dist = sqrt(gf_sdf_dot(d, d));
    bool open = false;
    if (r == GF_SDF_FACE) {
        memcpy(pn, s->n[t], sizeof pn);
    } else if (r < GF_SDF_VERT0) {
        int k = r - GF_SDF_EDGE0;
        int32_t u = s->mesh.adj[t][k];
        if (u < 0) open = true;
        else
            for (int a = 0; a < 3; a++) pn[a] = s->n[t][a] + s->n[u][a];
    } else {
        uint32_t v = s->mesh.t[t][r - GF_SDF_VERT0];
        if (s->vopen[v]) open = true;
        else memcpy(pn, s->vn[v], sizeof pn);
    }
    bool in = open ? p[2] >= s->z_exit : gf_sdf_dot(d, pn) <= 0.0;
    return in ? dist : -dist;
}

// ---- buckets ----------------------------------------------------------------

static int gf_sdf_cell(double x, double x0, double h, int n)
{
    double f = floor((x - x0) / h);
    return f < 0.0 ? 0 : (f > n - 1 ? n - 1 : (int)f);
}

void gf_sdf_near(const gf_sdf *s, const double p[3], double reach, bool (*f)(void *ctx, uint32_t t), void *ctx)
{
    int lo[3], hi[3];
    const int n[3] = {s->bx, s->by, s->bz};
    for (int a = 0; a < 3; a++) {
        if (p[a] + reach < s->b0[a] || p[a] - reach > s->b0[a] + n[a] * s->bh) return;
        lo[a] = gf_sdf_cell(p[a] - reach, s->b0[a], s->bh, n[a]);
        hi[a] = gf_sdf_cell(p[a] + reach, s->b0[a], s->bh, n[a]);
    }
    for (int k = lo[2]; k <= hi[2]; k++)
        for (int j = lo[1]; j <= hi[1]; j++)
            for (int i = lo[0]; i <= hi[0]; i++) {
                size_t cell = ((size_t)k * s->by + j) * s->bx + i;
                for (uint32_t e = s->bstart[cell]; e < s->bstart[cell + 1]; e++) {
                    uint32_t t = s->blist[e];
                    const int32_t *r = s->trange[t];
                    // Once only: in the first cell of the query that it meets.
                    if ((r[0] > lo[0] ? r[0] : lo[0]) != i || (r[1] > lo[1] ? r[1] : lo[1]) != j ||
                        (r[2] > lo[2] ? r[2] : lo[2]) != k)
                        continue;
                    if (!f(ctx, t)) return;
                }
            }
}

typedef struct gf_sdf_best {
    const gf_sdf *s;
    const double *p;
    double reach, best; // best: signed, |best| smallest
    bool found;
} gf_sdf_best;

static bool gf_sdf_best_visit(void *ctx, uint32_t t)
{
    gf_sdf_best *b = ctx;
    double d = gf_sdf_tri(b->s, t, b->p);
    if (fabs(d) <= b->reach && (!b->found || fabs(d) < fabs(b->best))) {
        b->best = d;
        b->found = true;
    }
    return true;
}

double gf_sdf_value(const gf_sdf *s, const double p[3])
{
    const int n[3] = {s->nx, s->ny, s->nz};
    int i0[3];
    double f[3];
    for (int a = 0; a < 3; a++) {
        double u = (p[a] - s->g0[a]) / s->h;
        if (!(u >= 0.0)) u = 0.0;
        if (u > n[a] - 1.000001) u = n[a] - 1.000001;
        i0[a] = (int)u;
        f[a] = u - i0[a];
    }
    double v = 0.0;
    for (int c = 0; c < 8; c++) {
        int di = c & 1, dj = (c >> 1) & 1, dk = (c >> 2) & 1;
        double w = (di ? f[0] : 1 - f[0]) * (dj ? f[1] : 1 - f[1]) * (dk ? f[2] : 1 - f[2]);
        v += w * s->d[((size_t)(i0[2] + dk) * s->ny + (i0[1] + dj)) * s->nx + (i0[0] + di)];
    }
    // Outside the grid the field continues as the distance to it, less.
    double out = 0.0;
    for (int a = 0; a < 3; a++) {
        double lo = s->g0[a], hi = s->g0[a] + (n[a] - 1) * s->h;
        double e = p[a] < lo ? lo - p[a] : (p[a] > hi ? p[a] - hi : 0.0);
        out += e * e;
    }
    return out > 0.0 ? fmin(v, 0.0) - sqrt(out) : v;
}

double gf_sdf_distance(const gf_sdf *s, const double p[3], double exact)
{
    double v = gf_sdf_value(s, p), slack = s->h * 1.7320508075688772 * 1.001 + 1e-9;
    if (fabs(v) > exact + slack) return v;
    gf_sdf_best b = {s, p, fabs(v) + slack, 0.0, false};
    gf_sdf_near(s, p, b.reach, gf_sdf_best_visit, &b);
    return b.found ? b.best : v;
}

void gf_sdf_normal(const gf_sdf *s, const double p[3], double n[3])
{
    const double e = 1e-5;
    double len = 0.0;
    for (int a = 0; a < 3; a++) {
        double pp[3] = {p[0], p[1], p[2]}, pm[3] = {p[0], p[1], p[2]};
        pp[a] += e;
        pm[a] -= e;
        n[a] = (gf_sdf_distance(s, pp, 1.0) - gf_sdf_distance(s, pm, 1.0)) / (2.0 * e);
        len += n[a] * n[a];
    }
    len = sqrt(len);
    for (int a = 0; a < 3; a++) n[a] = len > 0.0 ? n[a] / len : 0.0;
}

bool gf_sdf_inside(const gf_sdf *s, const double p[3])
{
    if (p[2] < s->z_exit) return false;
    return gf_sdf_distance(s, p, 0.0) > 0.0;
}

// ---- building ---------------------------------------------------------------

// Normals, pseudonormals, open vertices, bounding box.
static gf_status gf_sdf_normals(gf_sdf *s)
{
    const gf_stl *m = &s->mesh;
    s->n = gf_alloc_array(m->nt, sizeof *s->n);
    s->vn = gf_alloc_array(m->nv, sizeof *s->vn);
    s->vopen = GF_NEW(uint8_t, m->nv);
    if (!s->n || !s->vn || !s->vopen) return gf_error_set(GF_ERR_NOMEM, "out of memory for the mesh's normals");
    for (int a = 0; a < 3; a++) {
        s->lo[a] = INFINITY;
        s->hi[a] = -INFINITY;
    }
    for (size_t v = 0; v < m->nv; v++)
        for (int a = 0; a < 3; a++) {
            s->lo[a] = fmin(s->lo[a], m->v[v][a]);
            s->hi[a] = fmax(s->hi[a], m->v[v][a]);
        }
    for (size_t t = 0; t < m->nt; t++) {
        const double *P[3] = {m->v[m->t[t][0]], m->v[m->t[t][1]], m->v[m->t[t][2]]};
        double e1[3], e2[3], c[3];
        gf_sdf_sub(P[1], P[0], e1);
        gf_sdf_sub(P[2], P[0], e2);
        gf_sdf_cross(e1, e2, c);
        double l = sqrt(gf_sdf_dot(c, c));
        for (int a = 0; a < 3; a++) s->n[t][a] = c[a] / l;
        for (int k = 0; k < 3; k++) {
            double u[3], w[3];
            gf_sdf_sub(P[(k + 1) % 3], P[k], u);
            gf_sdf_sub(P[(k + 2) % 3], P[k], w);
            double cosang = gf_sdf_dot(u, w) / sqrt(gf_sdf_dot(u, u) * gf_sdf_dot(w, w));
            double ang = acos(cosang > 1.0 ? 1.0 : (cosang < -1.0 ? -1.0 : cosang));
            for (int a = 0; a < 3; a++) s->vn[m->t[t][k]][a] += ang * s->n[t][a];
            if (m->adj[t][k] < 0) s->vopen[m->t[t][k]] = s->vopen[m->t[t][(k + 1) % 3]] = 1;
        }
    }
    return GF_OK;
}

static gf_status gf_sdf_buckets(gf_sdf *s)
{
    const gf_stl *m = &s->mesh;
    // Cells of about a diameter, coarser for a large container.
    double ext = fmax(s->hi[0] - s->lo[0], fmax(s->hi[1] - s->lo[1], s->hi[2] - s->lo[2]));
    s->bh = fmax(1.0, ext / 256.0);
    int *n[3] = {&s->bx, &s->by, &s->bz};
    for (int a = 0; a < 3; a++) {
        s->b0[a] = s->lo[a] - 0.5 * s->bh;
        *n[a] = (int)ceil((s->hi[a] - s->lo[a]) / s->bh) + 1;
    }
    size_t ncell = (size_t)s->bx * s->by * s->bz;
    s->bstart = GF_NEW(uint32_t, ncell + 1);
    s->trange = gf_alloc_array(m->nt, sizeof *s->trange);
    if (!s->bstart || !s->trange) return gf_error_set(GF_ERR_NOMEM, "out of memory for the mesh's buckets");
    size_t total = 0;
    for (size_t t = 0; t < m->nt; t++) {
        size_t cnt = 1;
        for (int a = 0; a < 3; a++) {
            double lo = INFINITY, hi = -INFINITY;
            for (int k = 0; k < 3; k++) {
                lo = fmin(lo, m->v[m->t[t][k]][a]);
                hi = fmax(hi, m->v[m->t[t][k]][a]);
            }
            s->trange[t][a] = gf_sdf_cell(lo, s->b0[a], s->bh, *n[a]);
            s->trange[t][a + 3] = gf_sdf_cell(hi, s->b0[a], s->bh, *n[a]);
            cnt *= (size_t)(s->trange[t][a + 3] - s->trange[t][a] + 1);
        }
        total += cnt;
        if (total > GF_SDF_MAX_NODES)
            return gf_error_set(GF_ERR_PARAM, "the mesh's triangles meet more than %d cells of its buckets",
                                GF_SDF_MAX_NODES);
    }
    s->blist = GF_NEW(uint32_t, total ? total : 1);
    s->nlist = total ? total : 1;
    if (!s->blist) return gf_error_set(GF_ERR_NOMEM, "out of memory for the mesh's buckets");
    for (int pass = 0; pass < 2; pass++) {
        for (size_t t = 0; t < m->nt; t++) {
            const int32_t *r = s->trange[t];
            for (int k = r[2]; k <= r[5]; k++)
                for (int j = r[1]; j <= r[4]; j++)
                    for (int i = r[0]; i <= r[3]; i++) {
                        size_t cell = ((size_t)k * s->by + j) * s->bx + i;
                        if (pass == 0) s->bstart[cell + 1]++;
                        else s->blist[s->bstart[cell]++] = (uint32_t)t;
                    }
        }
        if (pass == 0)
            for (size_t c = 0; c < ncell; c++) s->bstart[c + 1] += s->bstart[c];
        else // the fill advanced every start to the next cell's: shift back
            for (size_t c = ncell; c > 0; c--) s->bstart[c] = s->bstart[c - 1];
        if (pass == 1) s->bstart[0] = 0;
    }
    return GF_OK;
}

static int gf_sdf_cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : (x > y);
}

// Node signs from the parity of the crossings of a vertical ray up from
// each node (nodes below the exit plane are outside: the outlet is open
// there, and nothing of the inside lies lower). The rays are shifted off
// the grid by an irrational fraction of h so no ray meets an edge exactly.
static gf_status gf_sdf_signs(gf_sdf *s, uint8_t *in)
{
    const gf_stl *m = &s->mesh;
    const double sx = 0.3819660112501051e-6 * s->h, sy = 0.6180339887498949e-6 * s->h;
    size_t ncol = (size_t)s->nx * s->ny;
    uint32_t *start = GF_NEW(uint32_t, ncol + 1);
    if (!start) return gf_error_set(GF_ERR_NOMEM, "out of memory for the mesh's field");
    double *zs = NULL;
    size_t nz = 0;
    gf_status st = GF_OK;
    for (int pass = 0; pass < 2; pass++) {
        for (size_t t = 0; t < m->nt; t++) {
            const double *P[3] = {m->v[m->t[t][0]], m->v[m->t[t][1]], m->v[m->t[t][2]]};
            if (s->n[t][2] == 0.0) continue; // vertical: no ray crosses it
            double xl = fmin(P[0][0], fmin(P[1][0], P[2][0])), xh = fmax(P[0][0], fmax(P[1][0], P[2][0]));
            double yl = fmin(P[0][1], fmin(P[1][1], P[2][1])), yh = fmax(P[0][1], fmax(P[1][1], P[2][1]));
            int i0 = (int)ceil((xl - sx - s->g0[0]) / s->h), i1 = (int)floor((xh - sx - s->g0[0]) / s->h);
            int j0 = (int)ceil((yl - sy - s->g0[1]) / s->h), j1 = (int)floor((yh - sy - s->g0[1]) / s->h);
            if (i0 < 0) i0 = 0;
            if (j0 < 0) j0 = 0;
            if (i1 > s->nx - 1) i1 = s->nx - 1;
            if (j1 > s->ny - 1) j1 = s->ny - 1;
            for (int j = j0; j <= j1; j++)
                for (int i = i0; i <= i1; i++) {
                    double x = s->g0[0] + i * s->h + sx, y = s->g0[1] + j * s->h + sy;
                    // Inside the projected triangle: the three edge functions share a sign.
                    double w[3];
                    for (int k = 0; k < 3; k++) {
                        const double *a = P[(k + 1) % 3], *b = P[(k + 2) % 3];
                        w[k] = (b[0] - a[0]) * (y - a[1]) - (b[1] - a[1]) * (x - a[0]);
                    }
                    bool pos = w[0] > 0 && w[1] > 0 && w[2] > 0, neg = w[0] < 0 && w[1] < 0 && w[2] < 0;
                    if (!pos && !neg) continue;
                    size_t col = (size_t)j * s->nx + i;
                    if (pass == 0) {
                        start[col + 1]++;
                        continue;
                    }
                    double sum = w[0] + w[1] + w[2];
                    zs[start[col]++] = (w[0] * P[0][2] + w[1] * P[1][2] + w[2] * P[2][2]) / sum;
                }
        }
        if (pass == 0) {
            for (size_t c = 0; c < ncol; c++) start[c + 1] += start[c];
            nz = start[ncol];
            zs = GF_NEW(double, nz ? nz : 1);
            if (!zs) {
                st = gf_error_set(GF_ERR_NOMEM, "out of memory for the mesh's field");
                break;
            }
        } else {
            for (size_t c = ncol; c > 0; c--) start[c] = start[c - 1];
            start[0] = 0;
        }
    }
    for (size_t col = 0; st == GF_OK && col < ncol; col++) {
        double *z = zs + start[col];
        size_t n = start[col + 1] - start[col], above = n;
        qsort(z, n, sizeof *z, gf_sdf_cmp);
        // March up the column: `above` crossings lie above the node.
        size_t c = 0;
        for (int k = 0; k < s->nz; k++) {
            double zk = s->g0[2] + k * s->h;
            while (c < n && z[c] <= zk) c++;
            above = n - c;
            in[(size_t)k * ncol + col] = zk >= s->z_exit && (above & 1);
        }
    }
    GF_DELETE(zs, nz ? nz : 1);
    GF_DELETE(start, ncol + 1);
    return st;
}

static gf_status gf_sdf_field(gf_sdf *s)
{
    const gf_stl *m = &s->mesh;
    // A bounded node count (also what lets the compiler see the sizes below
    // are sane: an unchecked product made GCC's LTO warn in gf_alloc).
    if (s->nx <= 0 || s->ny <= 0 || s->nz <= 0 ||
        (double)s->nx * (double)s->ny * (double)s->nz > (double)GF_SDF_MAX_NODES)
        return gf_error_set(GF_ERR_PARAM,
                            "the mesh's field would have %g nodes (%d x %d x %d), more than %g: a coarser "
                            "container.mesh_resolution",
                            (double)s->nx * (double)s->ny * (double)s->nz, s->nx, s->ny, s->nz,
                            (double)GF_SDF_MAX_NODES);
    size_t nn = (size_t)s->nx * (size_t)s->ny * (size_t)s->nz;
    uint8_t *in = GF_NEW(uint8_t, nn);
    s->d = GF_NEW(float, nn);
    if (!in || !s->d) {
        GF_DELETE(in, nn);
        return gf_error_set(GF_ERR_NOMEM, "out of memory for the mesh's field (%zu nodes)", nn);
    }
    for (size_t i = 0; i < nn; i++) s->d[i] = (float)s->band;
    // Exact distances within the band: each triangle visits the nodes near it.
    for (size_t t = 0; t < m->nt; t++) {
        int lo[3], hi[3];
        const int n[3] = {s->nx, s->ny, s->nz};
        for (int a = 0; a < 3; a++) {
            double l = INFINITY, h = -INFINITY;
            for (int k = 0; k < 3; k++) {
                l = fmin(l, m->v[m->t[t][k]][a]);
                h = fmax(h, m->v[m->t[t][k]][a]);
            }
            lo[a] = (int)ceil((l - s->band - s->g0[a]) / s->h);
            hi[a] = (int)floor((h + s->band - s->g0[a]) / s->h);
            if (lo[a] < 0) lo[a] = 0;
            if (hi[a] > n[a] - 1) hi[a] = n[a] - 1;
        }
        for (int k = lo[2]; k <= hi[2]; k++)
            for (int j = lo[1]; j <= hi[1]; j++)
                for (int i = lo[0]; i <= hi[0]; i++) {
                    const double p[3] = {s->g0[0] + i * s->h, s->g0[1] + j * s->h, s->g0[2] + k * s->h};
                    size_t id = ((size_t)k * s->ny + j) * s->nx + i;
                    double q[3], e[3];
                    gf_sdf_closest(s, (uint32_t)t, p, q);
                    gf_sdf_sub(p, q, e);
                    double dd = sqrt(gf_sdf_dot(e, e));
                    if (dd < s->d[id]) s->d[id] = (float)dd;
                }
    }
    gf_status st = gf_sdf_signs(s, in);
    for (size_t i = 0; st == GF_OK && i < nn; i++)
        if (!in[i]) s->d[i] = -s->d[i];
    GF_DELETE(in, nn);
    return st;
}

gf_status gf_sdf_build(gf_sdf *s, gf_stl *mesh, double exit_z, double h)
{
    *s = (gf_sdf){.mesh = *mesh, .z_exit = exit_z, .h = h};
    *mesh = (gf_stl){0};
    if (!(h > 0.0 && isfinite(h))) return gf_error_set(GF_ERR_PARAM, "mesh resolution %g must be > 0", h);
    gf_status st = gf_sdf_normals(s);
    if (st != GF_OK) return st;
    // The band: exact node values out to 3 cells (and a diameter), enough
    // that every query near a wall finds a node value it can trust.
    s->band = fmax(3.0 * h, 1.0);
    int *n[3] = {&s->nx, &s->ny, &s->nz};
    double nodes = 1.0;
    for (int a = 0; a < 3; a++) {
        s->g0[a] = s->lo[a] - 2.0 * h;
        *n[a] = (int)ceil((s->hi[a] - s->lo[a]) / h) + 5;
        nodes *= *n[a];
    }
    if (!(nodes <= GF_SDF_MAX_NODES))
        return gf_error_set(GF_ERR_PARAM,
                            "a field of spacing %g d over the mesh's %g x %g x %g d needs %.3g nodes, more than %d: "
                            "raise the spacing",
                            h, s->hi[0] - s->lo[0], s->hi[1] - s->lo[1], s->hi[2] - s->lo[2], nodes, GF_SDF_MAX_NODES);
    st = gf_sdf_buckets(s);
    if (st == GF_OK) st = gf_sdf_field(s);
    return st;
}

void gf_sdf_free(gf_sdf *s)
{
    const gf_stl *m = &s->mesh;
    GF_DELETE(s->n, m->nt);
    GF_DELETE(s->vn, m->nv);
    GF_DELETE(s->vopen, m->nv);
    GF_DELETE(s->d, (size_t)s->nx * s->ny * s->nz);
    GF_DELETE(s->bstart, (size_t)s->bx * s->by * s->bz + 1);
    GF_DELETE(s->blist, s->nlist);
    GF_DELETE(s->trange, m->nt);
    gf_stl_free(&s->mesh);
    *s = (gf_sdf){0};
}
