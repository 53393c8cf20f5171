// SPDX-License-Identifier: MIT
// A rank's window of packing.file (issue 23 item 3): an MPI rank of the
// domain engine reads the file and keeps only the particles of its region
// (its slab of domains and their halo, slabs.h) and a margin of the
// neighbour lists' reach, at the indices one process gives them, so that
// its pages of every other particle's records are never written (they stay
// fresh zero pages, not resident: core/alloc.c gf_alloc_pages).
//
// One process numbers the particles by a stable sort on their grid cell
// (nlist.c), z-major, so the particles of a range of whole cell layers take
// a range of indices, from the count of those in the layers below. The file
// is read twice: first for the count, the highest centre (it sets the grid's
// height, and with it the slabs) and the radii; then keeping the window's
// rows, in file order, and counting those below it. No MPI here: rank and
// ranks are numbers, so every build tests it (tests/test_slabs.c).
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "granflow/defs.h"
#include "granflow/packing.h"
#include "io/packing_frames.h"
#include "packing/import.h"
#include "spot/sim_internal.h"

typedef struct gf_win_scan {
    double exit_plane;       ///< rows below it are already out (dropped, as gf_packing_import does)
    size_t kept;             ///< pass 1: rows at or above it
    double zmax, rmin, rmax; ///< pass 1: of those
    const gf_grid *g;        ///< pass 2: the grid's shape
    int lo, hi;              ///< pass 2: the window's layers
    size_t below;            ///< pass 2: rows kept by one process in the layers below the window
} gf_win_scan;

static int gf_win_count(void *ctx, const double v[3], double r)
{
    gf_win_scan *s = ctx;
    if (v[2] < s->exit_plane) return 0;
    if (s->kept == 0 || v[2] > s->zmax) s->zmax = v[2];
    if (s->kept == 0 || r < s->rmin) s->rmin = r;
    if (s->kept == 0 || r > s->rmax) s->rmax = r;
    s->kept++;
    return 0;
}

static int gf_win_keep(void *ctx, const double v[3], double r)
{
    (void)r;
    gf_win_scan *s = ctx;
    if (v[2] < s->exit_plane) return 0;
    const gf_grid *g = s->g;
    int L = gf_grid_axis(v[2], g->oz, g->inv_h, g->nz); // (the layer gf_grid_cell gives)
    if (L < s->lo) {
        s->below++;
        return 0;
    }
    return L < s->hi;
}

// Pass 1 and the grid's shape, as gf_sim_create and gf_sim_make_grid make them.
static gf_status gf_win_shape(gf_sim *sim, const gf_packing_defs *pd, gf_win_scan *s)
{
    gf_packing none = {0};
    gf_status st = gf_packing_read_where(pd->file, pd->unit_diameter, gf_win_count, s, &none);
    gf_packing_free(&none);
    if (st != GF_OK) return st;
    if (s->kept == 0)
        return gf_error_set(GF_ERR_PARAM, "%s: no particle left (all below the exit plane, container.exit_z less "
                                          "container.outlet_length)", pd->file);
    if (s->kept > GF_MAX_PARTICLES)
        return gf_error_set(GF_ERR_PARAM, "%zu particles: more than the engine's limit of %d", s->kept,
                            GF_MAX_PARTICLES);
    if (!(s->rmin >= GF_IMPORT_RMIN && s->rmax <= GF_IMPORT_RMAX))
        return gf_error_set(GF_ERR_FORMAT, "%s: radii from %g to %g d: the engine takes radii in [%g, %g] d",
                            pd->file, s->rmin, s->rmax, GF_IMPORT_RMIN, GF_IMPORT_RMAX);
    sim->rmax = sim->rmax_all = s->rmax;
    sim->rmin_all = s->rmin;
    double top = s->zmax > 0.0 ? s->zmax : 0.0; // (gf_sim_make_grid's top starts at 0)
    sim->grid_ztop = top + 2.0;
    if (sim->d.recirculate) sim->grid_ztop += 0.5 * top + 8.0;
    double lo[3], hi[3];
    gf_sim_grid_bounds(sim, lo, hi);
    return gf_grid_shape(&sim->grid, lo, hi, GF_CELL_SIZE, s->kept);
}

// The window's particles at their indices; the checks of an import on them.
static gf_status gf_win_place(gf_sim *sim, const gf_packing_defs *pd, gf_packing *pk, size_t base, size_t total)
{
    // (A window above the packing's top, in the room recirculation leaves, holds none.)
    gf_status st = pk->n > 0 ? gf_packing_import_check(&sim->cfg, pk) : GF_OK;
    if (st != GF_OK) return st;
    gf_packing_tag_layers(pk, pd->layer_thickness);
    if ((st = gf_packing_check(pk, &sim->cfg)) != GF_OK) return st;
    if ((st = gf_sim_alloc_particles(sim, total)) != GF_OK) return st;
    sim->n = sim->n_alive = sim->n_initial = total;
    sim->win_lo = base;
    sim->win_hi = base + pk->n;
    for (size_t k = 0; k < pk->n; k++) {
        size_t i = base + k;
        sim->p[i] = (gf_pos){pk->x[k], pk->y[k], pk->z[k], pk->r[k]};
        sim->id[i] = pk->id[k];
        sim->layer[i] = pk->layer[k];
        sim->alive[i] = 1;
        sim->hist[i] = (gf_hist){0.0, hypot(pk->x[k], pk->y[k]), 1, 0};
    }
    return GF_OK;
}

int gf_window_margin(const gf_sim *sim)
{
    // A neighbour-list search's reach (nlist.c gf_nlist_find, every skin
    // GF_SKIN) in whole layers, so the rows of the region are whole.
    const double reach = 2.0 * sim->rmax + 3.0 * GF_SKIN + GF_SKIN_SLACK + 1e-3;
    return (int)ceil(reach / sim->grid.h) + 1;
}

static int gf_cmp_u32(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return (x > y) - (x < y);
}

gf_status gf_window_resort(gf_sim *sim, size_t c0, size_t c1, size_t base, size_t n, double rmin, double rmax)
{
    gf_grid *g = &sim->grid;
    // The window's particles in one process's new order: by cell, then by
    // index (its re-sort is stable), each cell's slots sorted.
    size_t k = 0;
    for (size_t c = c0; c < c1; c++) k += g->count[c];
    uint32_t *old = GF_NEW(uint32_t, k ? k : 1);
    gf_pos *p = GF_NEW(gf_pos, k ? k : 1);
    int64_t *id = GF_NEW(int64_t, k ? k : 1);
    int32_t *layer = GF_NEW(int32_t, k ? k : 1);
    gf_hist *hist = GF_NEW(gf_hist, k ? k : 1);
    gf_status st = GF_OK;
    if (!old || !p || !id || !layer || !hist) st = gf_error_set(GF_ERR_NOMEM, "out of memory re-sorting particles");
    if (st == GF_OK && base + k > sim->cap)
        st = gf_error_set(GF_ERR_STATE, "re-sort: a window of %zu particles from %zu, beyond the %zu there are", k, base,
                          sim->cap);
    for (size_t c = c0, j = 0; st == GF_OK && c < c1; c++) {
        memcpy(old + j, g->slot + c * GF_CELL_CAP, g->count[c] * sizeof *old);
        qsort(old + j, g->count[c], sizeof *old, gf_cmp_u32);
        j += g->count[c];
    }
    for (size_t j = 0; st == GF_OK && j < k; j++) {
        p[j] = sim->p[old[j]];
        id[j] = sim->id[old[j]];
        layer[j] = sim->layer[old[j]];
        hist[j] = sim->hist[old[j]];
    }
    if (st == GF_OK) {
        // The old window's records past the new one are left as they are
        // (stale, never read: outside the window).
        for (size_t c = c0; c < c1; c++) g->count[c] = 0;
        for (size_t j = 0; j < k; j++) {
            size_t i = base + j;
            sim->p[i] = p[j];
            sim->id[i] = id[j];
            sim->layer[i] = layer[j];
            sim->hist[i] = hist[j];
            sim->alive[i] = 1;
            sim->p0[i] = (gf_ref){(float)p[j].x, (float)p[j].y, (float)p[j].z, (float)GF_SKIN};
            g->cell_of[i] = GF_NO_CELL;
        }
        sim->n = n;
        sim->part = true;
        sim->win_lo = base;
        sim->win_hi = base + k;
        g->i0 = base;
        g->i1 = base + k;
        sim->rmin_all = rmin;
        sim->rmax_all = rmax;
        for (size_t j = 0; st == GF_OK && j < k; j++)
            st = gf_grid_insert(g, (uint32_t)(base + j), gf_grid_cell(g, p[j].x, p[j].y, p[j].z));
    }
    GF_DELETE(old, k ? k : 1);
    GF_DELETE(p, k ? k : 1);
    GF_DELETE(id, k ? k : 1);
    GF_DELETE(layer, k ? k : 1);
    GF_DELETE(hist, k ? k : 1);
    if (st != GF_OK) return st;
    sim->nl_built_at = sim->st.events;
    return gf_nlist_build(sim, false); // (the rows of the window; hmax and contact2 of every particle)
}

gf_status gf_sim_create_part(const gf_config *cfg, int R, int me, gf_sim **out)
{
    *out = NULL;
    gf_packing_defs pd;
    gf_config_packing_defs(cfg, &pd);
    if (!pd.file[0] || pd.types[0])
        return gf_error_set(GF_ERR_PARAM, "a rank's window needs packing.file without packing.types");
    if (R < 1 || me < 0 || me >= R) return gf_error_set(GF_ERR_PARAM, "rank %d of %d", me, R);
    gf_status st;
    gf_sim *sim = gf_sim_new(cfg, &st);
    if (!sim) return st;
    gf_win_scan s = {.exit_plane = gf_config_exit_plane(&sim->cfg)};
    gf_packing pk = {0};
    sim->part = true;
    if ((st = gf_win_shape(sim, &pd, &s)) != GF_OK) goto fail;
    if ((st = gf_nlist_slots(sim)) != GF_OK) goto fail;
    const int margin = gf_window_margin(sim);
    s.g = &sim->grid;
    if ((st = gf_dom_window_layers(sim, R, me, margin, &s.lo, &s.hi)) != GF_OK) goto fail;
    if ((st = gf_packing_read_where(pd.file, pd.unit_diameter, gf_win_keep, &s, &pk)) != GF_OK) goto fail;
    if ((st = gf_win_place(sim, &pd, &pk, s.below, s.kept)) != GF_OK) goto fail;
    gf_packing_free(&pk);
    if ((st = gf_sim_make_grid(sim)) != GF_OK) goto fail;
    if ((st = gf_sim_finish(sim)) != GF_OK) goto fail;
    *out = sim;
    return GF_OK;
fail:
    gf_packing_free(&pk);
    gf_sim_discard(sim);
    return st;
}
