// SPDX-License-Identifier: MIT
// The counting-sort cell list (geom/celllist.h).
#include "geom/celllist.h"

#include <math.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"

// Largest cell count per axis of gf_celllist_fit: keeps the offsets small for outliers.
#define GF_CL_MAXAXIS 2048

// Room for ncell cells and n points; storage only ever grows (by half again).
static gf_status gf_celllist_room(gf_celllist *cl, size_t ncell, size_t n)
{
    if (ncell >= UINT32_MAX || n >= UINT32_MAX)
        return gf_error_set(GF_ERR_PARAM, "cell list: %zu points in %zu cells is too many", n, ncell);
    if (ncell > cl->cap_cell || !cl->start) {
        size_t cap = ncell + ncell / 2;
        size_t *s = GF_NEW(size_t, cap + 1);
        if (!s) return gf_error_set(GF_ERR_NOMEM, "out of memory for a cell list of %zu cells", ncell);
        if (cl->start) GF_DELETE(cl->start, cl->cap_cell + 1);
        cl->start = s;
        cl->cap_cell = cap;
    }
    if (n > cl->cap_point || !cl->idx) {
        size_t cap = n + n / 2 + 16;
        uint32_t *a = GF_NEW(uint32_t, cap), *b = GF_NEW(uint32_t, cap);
        if (!a || !b) {
            GF_DELETE(a, cap);
            GF_DELETE(b, cap);
            return gf_error_set(GF_ERR_NOMEM, "out of memory for a cell list of %zu points", n);
        }
        if (cl->idx) GF_DELETE(cl->idx, cl->cap_point);
        if (cl->cell) GF_DELETE(cl->cell, cl->cap_point);
        cl->idx = a;
        cl->cell = b;
        cl->cap_point = cap;
    }
    cl->ncell = ncell;
    return GF_OK;
}

gf_status gf_celllist_grid(gf_celllist *cl, const double lo[3], const double inv[3], const int n[3])
{
    size_t ncell = 1;
    for (int k = 0; k < 3; k++) {
        if (n[k] < 1) return gf_error_set(GF_ERR_PARAM, "cell list: %d cells along an axis", n[k]);
        cl->lo[k] = lo[k];
        cl->inv[k] = inv[k];
        cl->n[k] = n[k];
        ncell *= (size_t)n[k];
    }
    cl->ncell = ncell;
    return GF_OK;
}

gf_status gf_celllist_keys(gf_celllist *cl, size_t ncell, size_t n) { return gf_celllist_room(cl, ncell, n); }

void gf_celllist_sort(gf_celllist *cl, size_t n)
{
    size_t *s = cl->start, ncell = cl->ncell;
    const uint32_t *cell = cl->cell;
    memset(s, 0, sizeof *s * (ncell + 1));
    for (size_t i = 0; i < n; i++)
        if (cell[i] != GF_CELLLIST_OUT) s[cell[i] + 1]++;
    for (size_t c = 0; c < ncell; c++) s[c + 1] += s[c];
    cl->nidx = s[ncell];
    // Placed in increasing index order (stable); s[c] ends as the end of cell c.
    for (size_t i = 0; i < n; i++)
        if (cell[i] != GF_CELLLIST_OUT) cl->idx[s[cell[i]]++] = (uint32_t)i;
    for (size_t c = ncell; c > 0; c--) s[c] = s[c - 1];
    s[0] = 0;
}

gf_status gf_celllist_bin(gf_celllist *cl, const double *x, const double *y, const double *z, size_t n)
{
    gf_status st = gf_celllist_room(cl, cl->ncell, n);
    if (st != GF_OK) return st;
    for (size_t i = 0; i < n; i++) {
        if (!isfinite(x[i]) || !isfinite(y[i]) || !isfinite(z[i])) {
            cl->cell[i] = GF_CELLLIST_OUT;
            continue;
        }
        int cx = gf_celllist_axis(cl, 0, x[i]), cy = gf_celllist_axis(cl, 1, y[i]), cz = gf_celllist_axis(cl, 2, z[i]);
        cl->cell[i] = (uint32_t)gf_celllist_index(cl, cx, cy, cz);
    }
    gf_celllist_sort(cl, n);
    return GF_OK;
}

gf_status gf_celllist_fit(gf_celllist *cl, const double *x, const double *y, const double *z, size_t n, double h)
{
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    const double *c[3] = {x, y, z};
    size_t nfin = 0;
    for (size_t i = 0; i < n; i++) {
        if (!isfinite(x[i]) || !isfinite(y[i]) || !isfinite(z[i])) continue;
        for (int k = 0; k < 3; k++) {
            lo[k] = fmin(lo[k], c[k][i]);
            hi[k] = fmax(hi[k], c[k][i]);
        }
        nfin++;
    }
    if (nfin == 0)
        for (int k = 0; k < 3; k++) lo[k] = hi[k] = 0.0;
    // At most ~8 cells per point: a far outlier must not blow the grid up.
    double vol = 1.0;
    for (int k = 0; k < 3; k++) vol *= fmax(hi[k] - lo[k], h);
    double hmin = cbrt(vol / (8.0 * (double)(nfin + 1)));
    if (h < hmin) h = hmin;
    for (int k = 0; k < 3; k++) h = fmax(h, (hi[k] - lo[k]) / (GF_CL_MAXAXIS - 1));
    int nc[3];
    double inv[3];
    for (int k = 0; k < 3; k++) {
        double f = floor((hi[k] - lo[k]) / h) + 1.0;
        nc[k] = f > GF_CL_MAXAXIS ? GF_CL_MAXAXIS : (int)f;
        inv[k] = 1.0 / h;
    }
    gf_status st = gf_celllist_grid(cl, lo, inv, nc);
    return st == GF_OK ? gf_celllist_bin(cl, x, y, z, n) : st;
}

void gf_celllist_free(gf_celllist *cl)
{
    if (cl->start) GF_DELETE(cl->start, cl->cap_cell + 1);
    if (cl->idx) GF_DELETE(cl->idx, cl->cap_point);
    if (cl->cell) GF_DELETE(cl->cell, cl->cap_point);
    memset(cl, 0, sizeof *cl);
}

void gf_celllist_range(const gf_celllist *cl, const double c[3], double r, int lo[3], int hi[3])
{
    for (int k = 0; k < 3; k++) {
        lo[k] = gf_celllist_axis(cl, k, c[k] - r);
        hi[k] = gf_celllist_axis(cl, k, c[k] + r);
    }
}

int gf_celllist_forward(const gf_celllist *cl, int cx, int cy, int cz, size_t lo[13], size_t hi[13])
{
    const size_t *s = cl->start;
    int ns = 0;
    for (int dz = 0; dz <= 1; dz++)
        for (int dy = (dz ? -1 : 0); dy <= 1; dy++)
            for (int dx = (dz || dy ? -1 : 1); dx <= 1; dx++) {
                int jx = cx + dx, jy = cy + dy, jz = cz + dz;
                if (jx < 0 || jy < 0 || jx >= cl->n[0] || jy >= cl->n[1] || jz >= cl->n[2]) continue;
                size_t b = gf_celllist_index(cl, jx, jy, jz);
                if (s[b] == s[b + 1]) continue;
                lo[ns] = s[b];
                hi[ns] = s[b + 1];
                ns++;
            }
    return ns;
}
