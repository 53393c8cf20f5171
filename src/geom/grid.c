// SPDX-License-Identifier: MIT
#include "geom/grid.h"

#include <math.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"

// At most this many cells per particle, plus GF_GRID_CELLS_FREE: the
// papers' silo has 0.25 per particle; ~100 bytes a cell.
#define GF_GRID_CELLS_PER_PARTICLE 64.0
#define GF_GRID_CELLS_FREE 1048576.0

gf_status gf_grid_shape(gf_grid *g, const double lo[3], const double hi[3], double h, size_t np)
{
    memset(g, 0, sizeof *g);
    int n[3];
    for (int k = 0; k < 3; k++) {
        double span = hi[k] - lo[k];
        double cells = ceil(span / h);
        if (!(cells >= 1.0)) cells = 1.0;
        if (cells > 1 << 20) return gf_error_set(GF_ERR_PARAM, "grid too large (%g cells on an axis)", cells);
        n[k] = (int)cells;
    }
    // Cells far outnumbering particles only cost memory (a packing a hair
    // deep in a vast container): refused before anything is allocated.
    double cells = (double)n[0] * (double)n[1] * (double)n[2];
    if (cells > GF_GRID_CELLS_PER_PARTICLE * (double)np + GF_GRID_CELLS_FREE)
        return gf_error_set(GF_ERR_PARAM,
                            "grid of %.0f cells (%d x %d x %d) is too large for %zu particles: the container is far "
                            "larger than the packing",
                            cells, n[0], n[1], n[2], np);
    g->ox = lo[0];
    g->oy = lo[1];
    g->oz = lo[2];
    g->h = h;
    g->inv_h = 1.0 / h;
    g->nx = n[0];
    g->ny = n[1];
    g->nz = n[2];
    g->ncell = (size_t)n[0] * (size_t)n[1] * (size_t)n[2];
    g->np = np;
    g->i0 = 0;
    g->i1 = np;
    return GF_OK;
}

gf_status gf_grid_init_part(gf_grid *g, const double lo[3], const double hi[3], double h, size_t np, size_t i0,
                            size_t i1)
{
    gf_status st = gf_grid_shape(g, lo, hi, h, np);
    if (st != GF_OK) return st;
    g->i0 = i0 < np ? i0 : np;
    g->i1 = i1 < np ? (i1 > g->i0 ? i1 : g->i0) : np;
    g->count = GF_NEW_PAGES(uint32_t, g->ncell);
    g->slot = GF_NEW_PAGES(uint32_t, g->ncell * GF_CELL_CAP);
    g->top = GF_NEW(int32_t, (size_t)g->nx * (size_t)g->ny);
    g->cell_of = GF_NEW_PAGES(uint32_t, np ? np : 1);
    g->slot_of = GF_NEW_PAGES(uint32_t, np ? np : 1);
    if (!g->count || !g->slot || !g->top || !g->cell_of || !g->slot_of) {
        size_t cells = g->ncell;
        gf_grid_free(g);
        return gf_error_set(GF_ERR_NOMEM, "out of memory for a %zu-cell grid", cells);
    }
    gf_grid_clear(g);
    return GF_OK;
}

gf_status gf_grid_init(gf_grid *g, const double lo[3], const double hi[3], double h, size_t np)
{
    return gf_grid_init_part(g, lo, hi, h, np, 0, np);
}

void gf_grid_free(gf_grid *g)
{
    GF_DELETE_PAGES(g->count, g->ncell);
    GF_DELETE_PAGES(g->slot, g->ncell * GF_CELL_CAP);
    GF_DELETE(g->top, (size_t)g->nx * (size_t)g->ny);
    GF_DELETE_PAGES(g->cell_of, g->np ? g->np : 1);
    GF_DELETE_PAGES(g->slot_of, g->np ? g->np : 1);
    memset(g, 0, sizeof *g);
}

void gf_grid_clear(gf_grid *g)
{
    memset(g->count, 0, sizeof(uint32_t) * g->ncell);
    for (size_t c = 0; c < (size_t)g->nx * (size_t)g->ny; c++) g->top[c] = -1;
    for (size_t i = g->i0; i < g->i1; i++) g->cell_of[i] = GF_NO_CELL;
}

gf_status gf_grid_insert(gf_grid *g, uint32_t i, uint32_t c)
{
    uint32_t k = g->count[c];
    if (k >= GF_CELL_CAP) {
        return gf_error_set(GF_ERR_STATE,
                            "more than %d particle centres in one %.2g d cell (cell %u): the packing "
                            "overlaps far too much",
                            GF_CELL_CAP, g->h, c);
    }
    g->slot[(size_t)c * GF_CELL_CAP + k] = i;
    g->count[c] = k + 1;
    g->cell_of[i] = c;
    g->slot_of[i] = k;
    if (g->lazy_top) return GF_OK;
    int32_t cz;
    uint32_t col = gf_grid_cell_column(g, c, &cz);
    if (cz > g->top[col]) g->top[col] = cz;
    return GF_OK;
}

void gf_grid_remove(gf_grid *g, uint32_t i)
{
    uint32_t c = g->cell_of[i];
    if (c == GF_NO_CELL) return;
    uint32_t k = g->slot_of[i], last = g->count[c] - 1;
    uint32_t *s = g->slot + (size_t)c * GF_CELL_CAP;
    if (k != last) {
        s[k] = s[last];
        g->slot_of[s[k]] = k;
    }
    g->count[c] = last;
    g->cell_of[i] = GF_NO_CELL;
    if (last == 0 && !g->lazy_top) {
        int32_t cz;
        uint32_t col = gf_grid_cell_column(g, c, &cz);
        if (g->top[col] == cz) g->top[col] = gf_grid_top_from(g, col, cz - 1);
    }
}

void gf_grid_recompute_top(gf_grid *g) { gf_grid_recompute_top_cols(g, 0, (size_t)g->nx * (size_t)g->ny); }

void gf_grid_recompute_top_cols(gf_grid *g, size_t col0, size_t col1)
{
    for (size_t col = col0; col < col1; col++) g->top[col] = gf_grid_top_from(g, (uint32_t)col, g->nz - 1);
}

void gf_grid_range(const gf_grid *g, const double c[3], double r, int lo[3], int hi[3])
{
    lo[0] = gf_grid_axis(c[0] - r, g->ox, g->inv_h, g->nx);
    hi[0] = gf_grid_axis(c[0] + r, g->ox, g->inv_h, g->nx);
    lo[1] = gf_grid_axis(c[1] - r, g->oy, g->inv_h, g->ny);
    hi[1] = gf_grid_axis(c[1] + r, g->oy, g->inv_h, g->ny);
    lo[2] = gf_grid_axis(c[2] - r, g->oz, g->inv_h, g->nz);
    hi[2] = gf_grid_axis(c[2] + r, g->oz, g->inv_h, g->nz);
}

double gf_grid_column_top(const gf_grid *g, double x, double y, const double *z, size_t stride)
{
    return gf_grid_column_top_at(g, gf_grid_column(g, x, y), z, stride);
}

double gf_grid_column_top_at(const gf_grid *g, uint32_t col, const double *z, size_t stride)
{
    int32_t cz = g->top[col];
    if (cz < 0) return -INFINITY;
    uint32_t c = (uint32_t)cz * (uint32_t)g->nx * (uint32_t)g->ny + col;
    const uint32_t *s = g->slot + (size_t)c * GF_CELL_CAP;
    double best = -INFINITY;
    for (uint32_t k = 0; k < g->count[c]; k++) {
        double v = z[(size_t)s[k] * stride];
        if (v > best) best = v;
    }
    return best;
}

gf_status gf_grid_restore(gf_grid *g, const uint32_t *count, const uint32_t *slot, size_t np)
{
    gf_grid_clear(g);
    for (size_t c = 0; c < g->ncell; c++) {
        if (count[c] > GF_CELL_CAP) return gf_error_set(GF_ERR_FORMAT, "cell %zu holds %u particles", c, count[c]);
        for (uint32_t k = 0; k < count[c]; k++) {
            uint32_t i = slot[c * GF_CELL_CAP + k];
            if (i >= np || g->cell_of[i] != GF_NO_CELL)
                return gf_error_set(GF_ERR_FORMAT, "cell %zu lists particle %u twice or out of range", c, i);
            gf_status st = gf_grid_insert(g, i, (uint32_t)c);
            if (st != GF_OK) return st;
        }
    }
    return GF_OK;
}
