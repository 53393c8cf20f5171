// SPDX-License-Identifier: MIT
// STL files read into a welded mesh (geom/stl.h; docs/geometry.md).
// Everything a file says is checked before it is believed: the binary count
// against the file's size, every number for being finite, every triangle for
// an area and a direction, every edge for having one partner that runs the
// other way. A bad file is refused with the triangle that makes it bad.
#include "geom/stl.h"

#include <ctype.h>
#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "core/fs.h"

// Triangles as read: three vertices and the stored normal (zero when absent).
typedef struct gf_stl_raw {
    const char *name;
    size_t n, cap;
    double (*p)[4][3]; // [0..2] vertices, [3] stored normal
} gf_stl_raw;

static bool gf_stl_raw_push(gf_stl_raw *r, double tri[4][3])
{
    if (r->n == r->cap) {
        size_t cap = r->cap ? 2 * r->cap : 64;
        void *p = gf_realloc(r->p, r->cap * sizeof *r->p, cap * sizeof *r->p);
        if (!p) return false;
        r->p = p;
        r->cap = cap;
    }
    memcpy(r->p[r->n++], tri, sizeof *r->p);
    return true;
}

// ---- ASCII ----------------------------------------------------------------

typedef struct gf_stl_text {
    const char *s, *end;
    int line;
} gf_stl_text;

// The next whitespace-separated word into `w` (empty at the end of the text).
static void gf_stl_word(gf_stl_text *t, char *w, size_t n)
{
    while (t->s < t->end && isspace((unsigned char)*t->s)) {
        if (*t->s == '\n') t->line++;
        t->s++;
    }
    size_t k = 0;
    while (t->s < t->end && !isspace((unsigned char)*t->s)) {
        if (k + 1 < n) w[k++] = *t->s;
        t->s++;
    }
    w[k] = '\0';
}

static void gf_stl_skip_line(gf_stl_text *t)
{
    while (t->s < t->end && *t->s != '\n') t->s++;
}

static gf_status gf_stl_expect(gf_stl_text *t, const char *name, size_t tri, const char *want)
{
    char w[64];
    gf_stl_word(t, w, sizeof w);
    if (strcmp(w, want) == 0) return GF_OK;
    return gf_error_set(GF_ERR_FORMAT, "%s:%d: triangle %zu: expected '%s', found '%.40s'", name, t->line, tri, want,
                        *w ? w : "end of file");
}

static gf_status gf_stl_numbers(gf_stl_text *t, const char *name, size_t tri, double *v)
{
    for (int k = 0; k < 3; k++) {
        char w[64], *e;
        gf_stl_word(t, w, sizeof w);
        v[k] = strtod(w, &e);
        if (!*w || *e || !isfinite(v[k]))
            return gf_error_set(GF_ERR_FORMAT, "%s:%d: triangle %zu: '%.40s' is not a finite number", name, t->line,
                                tri, *w ? w : "end of file");
    }
    return GF_OK;
}

static gf_status gf_stl_ascii(const unsigned char *data, size_t len, gf_stl_raw *r)
{
    gf_stl_text t = {(const char *)data, (const char *)data + len, 1};
    char w[64];
    gf_stl_word(&t, w, sizeof w); // "solid"
    gf_stl_skip_line(&t);         // and its name
    for (;;) {
        gf_stl_word(&t, w, sizeof w);
        size_t tri = r->n + 1;
        if (strcmp(w, "endsolid") == 0) {
            gf_stl_skip_line(&t);
            gf_stl_word(&t, w, sizeof w);
            if (!*w) return GF_OK;
            if (strcmp(w, "solid") == 0) { // another solid follows: its facets join the mesh
                gf_stl_skip_line(&t);
                continue;
            }
            return gf_error_set(GF_ERR_FORMAT, "%s:%d: '%.40s' after endsolid", r->name, t.line, w);
        }
        if (strcmp(w, "facet") != 0)
            return gf_error_set(GF_ERR_FORMAT, "%s:%d: triangle %zu: expected 'facet' or 'endsolid', found '%.40s'",
                                r->name, t.line, tri, *w ? w : "end of file");
        if (tri > GF_STL_MAX_TRIANGLES)
            return gf_error_set(GF_ERR_FORMAT, "%s:%d: more than %d triangles", r->name, t.line, GF_STL_MAX_TRIANGLES);
        double p[4][3];
        gf_status st = gf_stl_expect(&t, r->name, tri, "normal");
        if (st == GF_OK) st = gf_stl_numbers(&t, r->name, tri, p[3]);
        if (st == GF_OK) st = gf_stl_expect(&t, r->name, tri, "outer");
        if (st == GF_OK) st = gf_stl_expect(&t, r->name, tri, "loop");
        for (int k = 0; k < 3 && st == GF_OK; k++) {
            st = gf_stl_expect(&t, r->name, tri, "vertex");
            if (st == GF_OK) st = gf_stl_numbers(&t, r->name, tri, p[k]);
        }
        if (st == GF_OK) st = gf_stl_expect(&t, r->name, tri, "endloop");
        if (st == GF_OK) st = gf_stl_expect(&t, r->name, tri, "endfacet");
        if (st != GF_OK) return st;
        if (!gf_stl_raw_push(r, p)) return gf_error_set(GF_ERR_NOMEM, "%s: out of memory for its triangles", r->name);
    }
}

// ---- binary ---------------------------------------------------------------

static double gf_stl_f32(const unsigned char *b)
{
    uint32_t u = (uint32_t)b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 | (uint32_t)b[3] << 24;
    float f;
    memcpy(&f, &u, sizeof f);
    return (double)f;
}

static gf_status gf_stl_binary(const unsigned char *data, size_t len, uint32_t count, gf_stl_raw *r)
{
    for (uint32_t i = 0; i < count; i++) {
        const unsigned char *b = data + 84 + 50 * (size_t)i;
        double p[4][3];
        for (int k = 0; k < 12; k++) {
            double v = gf_stl_f32(b + 4 * k);
            if (!isfinite(v))
                return gf_error_set(GF_ERR_FORMAT, "%s: triangle %u: a coordinate or normal is not finite", r->name,
                                    i + 1);
            p[(k / 3 + 3) % 4][k % 3] = v; // the normal comes first in the file
        }
        if (!gf_stl_raw_push(r, p)) return gf_error_set(GF_ERR_NOMEM, "%s: out of memory for its triangles", r->name);
    }
    (void)len;
    return GF_OK;
}

// ---- welding and adjacency ------------------------------------------------

typedef struct gf_stl_key {
    double x[3];
    size_t i;
} gf_stl_key;

static int gf_stl_key_cmp(const void *pa, const void *pb)
{
    const gf_stl_key *a = pa, *b = pb;
    for (int k = 0; k < 3; k++)
        if (a->x[k] != b->x[k]) return a->x[k] < b->x[k] ? -1 : 1;
    return a->i < b->i ? -1 : (a->i > b->i);
}

typedef struct gf_stl_edge {
    uint32_t lo, hi; // vertex ids, lo < hi
    uint32_t tri;
    uint8_t k, fwd; // edge k of tri; fwd: it runs lo -> hi
} gf_stl_edge;

static int gf_stl_edge_cmp(const void *pa, const void *pb)
{
    const gf_stl_edge *a = pa, *b = pb;
    if (a->lo != b->lo) return a->lo < b->lo ? -1 : 1;
    if (a->hi != b->hi) return a->hi < b->hi ? -1 : 1;
    return a->tri < b->tri ? -1 : (a->tri > b->tri);
}

// Checks each triangle's shape and stored normal (on the unscaled mesh: scaled here).
static gf_status gf_stl_check_triangles(const gf_stl_raw *r)
{
    for (size_t i = 0; i < r->n; i++) {
        double(*p)[3] = r->p[i];
        double e[3][3], cr[3];
        for (int k = 0; k < 3; k++)
            for (int a = 0; a < 3; a++) e[k][a] = p[(k + 1) % 3][a] - p[k][a];
        cr[0] = e[0][1] * e[1][2] - e[0][2] * e[1][1];
        cr[1] = e[0][2] * e[1][0] - e[0][0] * e[1][2];
        cr[2] = e[0][0] * e[1][1] - e[0][1] * e[1][0];
        double area = 0.5 * sqrt(cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]);
        double emin = INFINITY;
        for (int k = 0; k < 3; k++) emin = fmin(emin, sqrt(e[k][0] * e[k][0] + e[k][1] * e[k][1] + e[k][2] * e[k][2]));
        if (!(area >= 1e-10) || !(emin >= 1e-6))
            return gf_error_set(GF_ERR_FORMAT,
                                "%s: triangle %zu is degenerate (area %.3g d^2, shortest edge %.3g d): its vertices "
                                "(%g, %g, %g), (%g, %g, %g), (%g, %g, %g) are (nearly) on one line",
                                r->name, i + 1, area, emin, p[0][0], p[0][1], p[0][2], p[1][0], p[1][1], p[1][2],
                                p[2][0], p[2][1], p[2][2]);
        const double *n = p[3];
        double nn = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        if (nn > 0.0 && (n[0] * cr[0] + n[1] * cr[1] + n[2] * cr[2]) < -0.5 * nn * 2.0 * area)
            return gf_error_set(GF_ERR_FORMAT,
                                "%s: triangle %zu: its stored normal (%g, %g, %g) points against its vertex order "
                                "(STL vertices run counter-clockwise seen from outside, the normal points out): an "
                                "inverted normal",
                                r->name, i + 1, n[0], n[1], n[2]);
    }
    return GF_OK;
}

static gf_status gf_stl_build(const gf_stl_raw *r, gf_stl *m)
{
    size_t nc = 3 * r->n;
    gf_stl_key *keys = GF_NEW(gf_stl_key, nc);
    gf_stl_edge *edges = GF_NEW(gf_stl_edge, nc);
    uint32_t *id = GF_NEW(uint32_t, nc);
    m->t = gf_alloc_array(r->n, sizeof *m->t);
    m->adj = gf_alloc_array(r->n, sizeof *m->adj);
    m->nt = r->n; // the sizes of t and adj, for gf_stl_free on every path
    gf_status st = GF_OK;
    if (!keys || !edges || !id || !m->t || !m->adj) {
        st = gf_error_set(GF_ERR_NOMEM, "%s: out of memory for its mesh", r->name);
        goto done;
    }
    for (size_t c = 0; c < nc; c++) {
        memcpy(keys[c].x, r->p[c / 3][c % 3], sizeof keys[c].x);
        keys[c].i = c;
    }
    qsort(keys, nc, sizeof *keys, gf_stl_key_cmp);
    size_t nv = 0;
    for (size_t c = 0; c < nc; c++) {
        if (c == 0 || memcmp(keys[c].x, keys[c - 1].x, sizeof keys[c].x) != 0) nv++;
        id[keys[c].i] = (uint32_t)(nv - 1);
    }
    m->v = gf_alloc_array(nv, sizeof *m->v);
    m->nv = nv;
    if (!m->v) {
        st = gf_error_set(GF_ERR_NOMEM, "%s: out of memory for its mesh", r->name);
        goto done;
    }
    for (size_t c = 0; c < nc; c++) memcpy(m->v[id[keys[c].i]], keys[c].x, sizeof m->v[0]);
    for (size_t i = 0; i < r->n; i++)
        for (int k = 0; k < 3; k++) {
            uint32_t a = id[3 * i + k], b = id[3 * i + (k + 1) % 3];
            m->t[i][k] = a;
            m->adj[i][k] = -1;
            edges[3 * i + k] = (gf_stl_edge){a < b ? a : b, a < b ? b : a, (uint32_t)i, (uint8_t)k, a < b};
        }
    qsort(edges, nc, sizeof *edges, gf_stl_edge_cmp);
    for (size_t e = 0; e < nc;) {
        size_t f = e + 1;
        while (f < nc && edges[f].lo == edges[e].lo && edges[f].hi == edges[e].hi) f++;
        const gf_stl_edge *a = &edges[e];
        const double *p = m->v[a->lo], *q = m->v[a->hi];
        if (f - e > 2) {
            st = gf_error_set(GF_ERR_FORMAT,
                              "%s: triangle %u: its edge (%g, %g, %g)-(%g, %g, %g) is shared by %zu triangles (%u, "
                              "%u, %u...): a wall surface has at most two on an edge",
                              r->name, edges[e + 2].tri + 1, p[0], p[1], p[2], q[0], q[1], q[2], f - e, a->tri + 1,
                              edges[e + 1].tri + 1, edges[e + 2].tri + 1);
            goto done;
        }
        if (f - e == 2) {
            const gf_stl_edge *b = &edges[e + 1];
            if (a->fwd == b->fwd) {
                st = gf_error_set(GF_ERR_FORMAT,
                                  "%s: triangle %u: its vertices run the same way as triangle %u's across their "
                                  "edge (%g, %g, %g)-(%g, %g, %g): inconsistent orientation (one of them is flipped)",
                                  r->name, b->tri + 1, a->tri + 1, p[0], p[1], p[2], q[0], q[1], q[2]);
                goto done;
            }
            m->adj[a->tri][a->k] = (int32_t)b->tri;
            m->adj[b->tri][b->k] = (int32_t)a->tri;
        }
        e = f;
    }
done:
    GF_DELETE(keys, nc);
    GF_DELETE(edges, nc);
    GF_DELETE(id, nc);
    return st;
}

gf_status gf_stl_parse(const char *name, const unsigned char *data, size_t len, double scale, gf_stl *out)
{
    *out = (gf_stl){0};
    if (!(scale > 0.0 && isfinite(scale))) return gf_error_set(GF_ERR_PARAM, "%s: scale %g must be > 0", name, scale);
    gf_stl_raw r = {.name = name};
    gf_status st;
    uint32_t count = 0;
    if (len >= 84) count = (uint32_t)data[80] | (uint32_t)data[81] << 8 | (uint32_t)data[82] << 16 | (uint32_t)data[83] << 24;
    bool binary = len >= 84 && count <= GF_STL_MAX_TRIANGLES && len == 84 + 50 * (size_t)count;
    size_t s = 0;
    while (s < len && isspace(data[s])) s++;
    bool ascii = !binary && len - s >= 5 && memcmp(data + s, "solid", 5) == 0 &&
                 (len - s == 5 || isspace(data[s + 5]));
    if (binary) {
        st = gf_stl_binary(data, len, count, &r);
    } else if (ascii) {
        st = gf_stl_ascii(data, len, &r);
    } else if (len < 84) {
        st = gf_error_set(GF_ERR_FORMAT,
                          "%s: not an STL file: %zu bytes, too short for a binary STL (84 bytes of header and count), "
                          "and it does not start with 'solid'",
                          name, len);
    } else if (count > GF_STL_MAX_TRIANGLES) {
        st = gf_error_set(GF_ERR_FORMAT, "%s: not an STL file: a binary STL declaring %u triangles (at most %d)", name,
                          count, GF_STL_MAX_TRIANGLES);
    } else if (len < 84 + 50 * (size_t)count) {
        st = gf_error_set(GF_ERR_FORMAT,
                          "%s: truncated binary STL: its header declares %u triangles (%zu bytes), the file has %zu "
                          "bytes: triangle %zu is cut short",
                          name, count, 84 + 50 * (size_t)count, len, (len - 84) / 50 + 1);
    } else {
        st = gf_error_set(GF_ERR_FORMAT,
                          "%s: not an STL file: a binary STL declaring %u triangles has %zu bytes more than they take",
                          name, count, len - 84 - 50 * (size_t)count);
    }
    if (st == GF_OK && r.n == 0) st = gf_error_set(GF_ERR_FORMAT, "%s: no triangles", name);
    if (st == GF_OK)
        for (size_t i = 0; i < r.n; i++)
            for (int k = 0; k < 3; k++)
                for (int a = 0; a < 3; a++) r.p[i][k][a] *= scale;
    if (st == GF_OK) st = gf_stl_check_triangles(&r);
    if (st == GF_OK) st = gf_stl_build(&r, out);
    gf_free(r.p, r.cap * sizeof *r.p);
    if (st != GF_OK) gf_stl_free(out);
    return st;
}

gf_status gf_stl_read(const char *path, double scale, gf_stl *out)
{
    *out = (gf_stl){0};
    unsigned char *data = NULL;
    size_t len = 0, cap = 0;
    gf_status st = gf_fs_read_all(path, GF_STL_MAX_BYTES, &data, &len, &cap);
    if (st != GF_OK) return st;
    st = gf_stl_parse(path, data, len, scale, out);
    gf_free(data, cap);
    return st;
}

void gf_stl_free(gf_stl *m)
{
    GF_DELETE(m->v, m->nv);
    GF_DELETE(m->t, m->nt);
    GF_DELETE(m->adj, m->nt);
    *m = (gf_stl){0};
}
