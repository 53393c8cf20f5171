// SPDX-License-Identifier: MIT
// Verlet neighbour lists for relax(), kept per particle. Each particle has a
// reference position p0 and a skin h; pair (i, j) is listed exactly while
// |p0_i - p0_j| < r_i + r_j + h_i + h_j. A particle that has moved (almost)
// h_i from p0_i gets p0_i = x_i and its pairs are redone on the spot
// (gf_nlist_refresh), so no pair closer than contact is ever missing and no
// global rebuild is ever forced by motion. Full rebuilds come on a fixed event
// schedule only, to compact exited particles away and re-sort the rest by
// cell for locality.
#include <math.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "geom/celllist.h"
#include "spot/sim_internal.h"

// Permutes every per-particle array of the particles from `base` on so that
// entry base + k takes old entry base + order[k].
static gf_status gf_nlist_permute(gf_sim *sim, size_t base, const uint32_t *order, size_t m)
{
#define GF_PERMUTE(T, field)                                   \
    do {                                                       \
        T *tmp = GF_NEW(T, m ? m : 1);                         \
        if (!tmp) return gf_error_set(GF_ERR_NOMEM, "out of memory re-sorting particles"); \
        for (size_t k = 0; k < m; k++) tmp[k] = sim->field[base + order[k]]; \
        memcpy(sim->field + base, tmp, sizeof(T) * m);         \
        GF_DELETE(tmp, m ? m : 1);                             \
    } while (0)
    GF_PERMUTE(gf_pos, p);
    GF_PERMUTE(gf_ref, p0);
    GF_PERMUTE(int64_t, id);
    GF_PERMUTE(int32_t, layer);
    GF_PERMUTE(gf_hist, hist);
#undef GF_PERMUTE
    for (size_t k = 0; k < m; k++) sim->alive[base + k] = 1;
    if (sim->part) return GF_OK; // (a window of whole cell layers: nothing exited yet, nothing dropped)
    for (size_t k = m; k < sim->n; k++) sim->alive[k] = 0;
    sim->n = m;
    return GF_OK;
}

// Live particles sorted by grid cell (stable), exited ones dropped. A rank
// holding its window (sim->part) sorts the window: it holds every particle
// of a range of whole cell layers, in the file's order, from the index the
// particles of the layers below take, so its sort is the global sort's.
static gf_status gf_nlist_reorder(gf_sim *sim)
{
    gf_grid *g = &sim->grid;
    const size_t base = sim->part ? sim->win_lo : 0, n = (sim->part ? sim->win_hi : sim->n) - base;
    gf_celllist cl = {0};
    gf_status st = gf_celllist_keys(&cl, g->ncell, n);
    if (st == GF_OK) {
        for (size_t k = 0; k < n; k++) {
            size_t i = base + k;
            cl.cell[k] = sim->alive[i] ? gf_grid_cell(g, sim->p[i].x, sim->p[i].y, sim->p[i].z) : GF_CELLLIST_OUT;
        }
        gf_celllist_sort(&cl, n);
        st = gf_nlist_permute(sim, base, cl.idx, cl.nidx);
    }
    gf_celllist_free(&cl);
    return st;
}

static void gf_sort_u32(uint32_t *a, size_t n)
{
    for (size_t i = 1; i < n; i++) {
        uint32_t v = a[i];
        size_t j = i;
        while (j > 0 && a[j - 1] > v) {
            a[j] = a[j - 1];
            j--;
        }
        a[j] = v;
    }
}

// The listing rule. Symmetric in i and j to the last bit (negating a
// difference is exact, and the sums are written symmetrically), so the rows
// of i and j always agree, whoever computed them.
static inline bool gf_nlist_listed(const gf_sim *sim, uint32_t i, uint32_t j)
{
    const gf_ref *a = &sim->p0[i], *b = &sim->p0[j];
    double dx = (double)a->x - b->x, dy = (double)a->y - b->y, dz = (double)a->z - b->z;
    double cut = (sim->p[i].r + sim->p[j].r) + ((double)a->h + b->h);
    return dx * dx + dy * dy + dz * dz < cut * cut;
}

static inline uint32_t *gf_nlist_row(const gf_sim *sim, uint32_t i) { return sim->nl + ((size_t)i << sim->nl_shift); }

gf_status gf_nlist_slots(gf_sim *sim)
{
    double rmin = INFINITY, rmax = 0.0;
    if (sim->part) { // the whole packing's (window.c), not the window's
        rmin = sim->rmin_all;
        rmax = sim->rmax;
    }
    for (size_t i = 0; i < sim->n && !sim->part; i++) {
        if (!sim->alive[i]) continue;
        rmin = fmin(rmin, sim->p[i].r);
        rmax = fmax(rmax, sim->p[i].r);
    }
    unsigned shift = 4; // GF_NL_CAP
    if (rmax > rmin && rmin > 0.0) {
        double s = rmin / (rmax + rmin), need = 1.0 + 2.0 / (1.0 - sqrt(1.0 - s * s));
        while ((double)(1u << shift) < need && (1u << shift) < GF_NL_CAP_MAX) shift++;
        if ((double)(1u << shift) < need)
            return gf_error_set(GF_ERR_PARAM, "particle radii from %g to %g: a ratio above 3, more than the "
                                              "engine's neighbour lists hold", rmin, rmax);
    }
    _Static_assert((1u << 4) == GF_NL_CAP, "rows of equal radii have GF_NL_CAP slots");
    sim->nl_shift = shift;
    return GF_OK;
}

static gf_status gf_nlist_overflow(const gf_sim *sim, uint32_t i)
{
    return gf_error_set(GF_ERR_STATE,
                        "particle %lld has more than %d neighbours within contact + skin: the packing "
                        "overlaps far too much",
                        (long long)sim->id[i], (1 << sim->nl_shift) - 1);
}

// Fills row i with its neighbours by the listing rule, sorted. The grid holds
// current positions, each within h_j of its p0_j, hence the reach of the search.
static gf_status gf_nlist_find(gf_sim *sim, uint32_t i)
{
    const gf_grid *g = &sim->grid;
    const gf_ref *a = &sim->p0[i];
    const double c[3] = {a->x, a->y, a->z};
    // + the rounding of the float references (~1e-5 d at z ~ 100)
    double reach = sim->p[i].r + sim->rmax + a->h + 2.0 * sim->hmax + GF_SKIN_SLACK + 1e-3;
    int lo[3], hi[3];
    gf_grid_range(g, c, reach, lo, hi);
    uint32_t *row = gf_nlist_row(sim, i), n = 0;
    for (int cz = lo[2]; cz <= hi[2]; cz++)
        for (int cy = lo[1]; cy <= hi[1]; cy++)
            for (int cx = lo[0]; cx <= hi[0]; cx++) {
                uint32_t cnt;
                const uint32_t *s = gf_grid_slots(g, cx, cy, cz, &cnt);
                for (uint32_t k = 0; k < cnt; k++) {
                    uint32_t j = s[k];
                    if (j == i || !gf_nlist_listed(sim, i, j)) continue;
                    if (n == (1u << sim->nl_shift) - 1) {
                        row[0] = 0;
                        return gf_nlist_overflow(sim, i);
                    }
                    row[1 + n++] = j;
                }
            }
    gf_sort_u32(row + 1, n);
    row[0] = n;
    return GF_OK;
}

static gf_status gf_row_insert(gf_sim *sim, uint32_t j, uint32_t v)
{
    uint32_t *row = gf_nlist_row(sim, j), n = row[0];
    if (n == (1u << sim->nl_shift) - 1) return gf_nlist_overflow(sim, j);
    uint32_t *e = row + 1, k = n;
    while (k > 0 && e[k - 1] > v) {
        e[k] = e[k - 1];
        k--;
    }
    e[k] = v;
    row[0] = n + 1;
    return GF_OK;
}

static void gf_row_remove(gf_sim *sim, uint32_t j, uint32_t v)
{
    uint32_t *row = gf_nlist_row(sim, j), n = row[0], *e = row + 1, k = 0;
    while (k < n && e[k] != v) k++;
    if (k == n) return;
    for (; k + 1 < n; k++) e[k] = e[k + 1];
    row[0] = n - 1;
}

void gf_nlist_drop(gf_sim *sim, uint32_t i)
{
    uint32_t *row = gf_nlist_row(sim, i);
    for (uint32_t k = 1; k <= row[0]; k++) gf_row_remove(sim, row[k], i);
    row[0] = 0;
}

gf_status gf_nlist_find_row(gf_sim *sim, uint32_t i) { return gf_nlist_find(sim, i); }

gf_status gf_nlist_refresh(gf_sim *sim, uint32_t i)
{
    gf_nlist_drop(sim, i);
    sim->p0[i].x = (float)sim->p[i].x;
    sim->p0[i].y = (float)sim->p[i].y;
    sim->p0[i].z = (float)sim->p[i].z;
    gf_status st = gf_nlist_find(sim, i);
    if (st != GF_OK) return st;
    const uint32_t *row = gf_nlist_row(sim, i);
    for (uint32_t k = 1; k <= row[0]; k++)
        if ((st = gf_row_insert(sim, row[k], i)) != GF_OK) return st;
    return GF_OK;
}

gf_status gf_nlist_build(gf_sim *sim, bool reorder)
{
    gf_status st;
    // A rank holding its window builds the window's rows (those of its region
    // are whole: the window has a margin of the lists' reach beyond it).
    const size_t lo = sim->part ? sim->win_lo : 0, hi = sim->part ? sim->win_hi : sim->n;
    if (reorder) {
        for (size_t i = lo; i < hi; i++) sim->p0[i].h = (float)GF_SKIN;
        if ((st = gf_nlist_reorder(sim)) != GF_OK) return st;
    }
    gf_grid *g = &sim->grid;
    if (reorder) {
        // New indices: refill the grid in index order and restart the schedule.
        gf_grid_clear(g);
        for (size_t i = lo; i < hi; i++) {
            if (!sim->alive[i]) continue;
            st = gf_grid_insert(g, (uint32_t)i, gf_grid_cell(g, sim->p[i].x, sim->p[i].y, sim->p[i].z));
            if (st != GF_OK) return st;
            sim->p0[i].x = (float)sim->p[i].x;
            sim->p0[i].y = (float)sim->p[i].y;
            sim->p0[i].z = (float)sim->p[i].z;
        }
        sim->nl_built_at = sim->st.events;
    }
    sim->hmax = 0.0;
    double r = -1.0;
    bool mono = true;
    for (size_t i = lo; i < hi; i++) {
        if (!sim->alive[i]) continue;
        if (sim->p0[i].h > sim->hmax) sim->hmax = sim->p0[i].h;
        if (r < 0.0) r = sim->p[i].r;
        mono = mono && sim->p[i].r == r;
    }
    if (sim->part) { // every particle's radii (every skin is GF_SKIN after a window's build)
        mono = sim->rmin_all == sim->rmax_all;
        r = sim->rmax_all;
    }
    sim->contact2 = mono && r > 0.0 ? 4.0 * r * r : 0.0;
    if (!sim->nl) {
        sim->nl = GF_NEW_PAGES(uint32_t, sim->cap << sim->nl_shift);
        if (!sim->nl) return gf_error_set(GF_ERR_NOMEM, "out of memory for neighbour lists");
    }
    for (size_t i = lo; i < hi; i++) {
        if (!sim->alive[i] || !sim->use_nlist) {
            sim->nl[i << sim->nl_shift] = 0;
            continue;
        }
        if ((st = gf_nlist_find(sim, (uint32_t)i)) != GF_OK) return st;
    }
    sim->st.nlist_builds++;
    return GF_OK;
}
