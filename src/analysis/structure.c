// SPDX-License-Identifier: MIT
// Cell list and window selection shared by the structure measurements.
#include "analysis/structure.h"

#include <math.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"

// Largest cell count per axis: keeps the offsets array small for outliers.
#define GF_CL_MAXAXIS 2048

gf_status gf_cell_list_build(gf_cell_list *cl, const double *x, const double *y, const double *z,
                             size_t n, double h)
{
    memset(cl, 0, sizeof *cl);
    if (n > UINT32_MAX) return gf_error_set(GF_ERR_PARAM, "cell list: %zu points is too many", n);
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
    cl->h = h;
    cl->ncell = 1;
    for (int k = 0; k < 3; k++) {
        cl->lo[k] = lo[k];
        cl->n[k] = (int)(floor((hi[k] - lo[k]) / h) + 1.0);
        if (cl->n[k] > GF_CL_MAXAXIS) cl->n[k] = GF_CL_MAXAXIS;
        cl->ncell *= (size_t)cl->n[k];
    }
    cl->start = GF_NEW(size_t, cl->ncell + 1);
    cl->idx = GF_NEW(uint32_t, nfin ? nfin : 1);
    cl->nidx = nfin;
    uint32_t *cell = GF_NEW(uint32_t, n ? n : 1);
    if (!cl->start || !cl->idx || !cell) {
        GF_DELETE(cell, n ? n : 1);
        gf_cell_list_free(cl);
        return gf_error_set(GF_ERR_NOMEM, "out of memory for a cell list of %zu points", n);
    }
    for (size_t i = 0; i < n; i++) {
        if (!isfinite(x[i]) || !isfinite(y[i]) || !isfinite(z[i])) {
            cell[i] = UINT32_MAX;
            continue;
        }
        int ci[3];
        for (int k = 0; k < 3; k++) {
            int v = (int)((c[k][i] - lo[k]) / h);
            ci[k] = v < 0 ? 0 : v >= cl->n[k] ? cl->n[k] - 1 : v;
        }
        cell[i] = (uint32_t)gf_cell_list_index(cl, ci[0], ci[1], ci[2]);
        cl->start[cell[i] + 1]++;
    }
    for (size_t k = 0; k < cl->ncell; k++) cl->start[k + 1] += cl->start[k];
    // Fill in increasing index order within each cell (deterministic sums).
    for (size_t i = 0; i < n; i++)
        if (cell[i] != UINT32_MAX) cl->idx[cl->start[cell[i]]++] = (uint32_t)i;
    for (size_t k = cl->ncell; k > 0; k--) cl->start[k] = cl->start[k - 1];
    cl->start[0] = 0;
    GF_DELETE(cell, n ? n : 1);
    return GF_OK;
}

void gf_cell_list_free(gf_cell_list *cl)
{
    if (cl->start) GF_DELETE(cl->start, cl->ncell + 1);
    if (cl->idx) GF_DELETE(cl->idx, cl->nidx ? cl->nidx : 1);
    memset(cl, 0, sizeof *cl);
}

static int gf_cell_axis(const gf_cell_list *cl, int k, double v)
{
    double f = (v - cl->lo[k]) / cl->h;
    if (!(f >= 0.0)) return 0;
    if (f >= (double)cl->n[k]) return cl->n[k] - 1;
    return (int)f;
}

void gf_cell_list_range(const gf_cell_list *cl, const double c[3], double r, int lo[3], int hi[3])
{
    for (int k = 0; k < 3; k++) {
        lo[k] = gf_cell_axis(cl, k, c[k] - r);
        hi[k] = gf_cell_axis(cl, k, c[k] + r);
    }
}

void gf_structure_window(const gf_series *s, const gf_analysis_opts *o, size_t *k0, size_t *k1)
{
    double t0, t1;
    gf_analysis_window(o, s, &t0, &t1);
    gf_window_frames(s, t0, t1, k0, k1);
}
