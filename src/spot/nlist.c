// SPDX-License-Identifier: MIT
// Verlet neighbour lists for relax(): every pair closer than contact + skin,
// rebuilt when a particle has moved a good part of the skin. Rebuilds also
// compact exited particles away and re-sort the rest by cell for locality.
#include <math.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "spot/sim_internal.h"

// Permutes every per-particle array so that entry k takes old entry order[k].
static gf_status gf_nlist_permute(gf_sim *sim, const uint32_t *order, size_t m)
{
#define GF_PERMUTE(T, field)                                   \
    do {                                                       \
        T *tmp = GF_NEW(T, m ? m : 1);                         \
        if (!tmp) return gf_error_set(GF_ERR_NOMEM, "out of memory re-sorting particles"); \
        for (size_t k = 0; k < m; k++) tmp[k] = sim->field[order[k]]; \
        memcpy(sim->field, tmp, sizeof(T) * m);                \
        GF_DELETE(tmp, m ? m : 1);                             \
    } while (0)
    GF_PERMUTE(gf_pos, p);
    GF_PERMUTE(gf_pos, p0);
    GF_PERMUTE(int64_t, id);
    GF_PERMUTE(int32_t, layer);
#undef GF_PERMUTE
    for (size_t k = 0; k < m; k++) sim->alive[k] = 1;
    for (size_t k = m; k < sim->n; k++) sim->alive[k] = 0;
    sim->n = m;
    return GF_OK;
}

// Live particles sorted by grid cell (stable), exited ones dropped.
static gf_status gf_nlist_reorder(gf_sim *sim)
{
    gf_grid *g = &sim->grid;
    size_t ncell = g->ncell, n = sim->n;
    uint32_t *first = GF_NEW(uint32_t, ncell + 1), *cell = GF_NEW(uint32_t, n ? n : 1),
             *order = GF_NEW(uint32_t, n ? n : 1);
    gf_status st = GF_OK;
    if (!first || !cell || !order) {
        st = gf_error_set(GF_ERR_NOMEM, "out of memory re-sorting particles");
        goto done;
    }
    for (size_t i = 0; i < n; i++) {
        if (!sim->alive[i]) continue;
        cell[i] = gf_grid_cell(g, sim->p[i].x, sim->p[i].y, sim->p[i].z);
        first[cell[i] + 1]++;
    }
    for (size_t c = 0; c < ncell; c++) first[c + 1] += first[c];
    size_t m = first[ncell];
    for (size_t i = 0; i < n; i++)
        if (sim->alive[i]) order[first[cell[i]]++] = (uint32_t)i;
    st = gf_nlist_permute(sim, order, m);
done:
    GF_DELETE(first, ncell + 1);
    GF_DELETE(cell, n ? n : 1);
    GF_DELETE(order, n ? n : 1);
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

// Skins by position: every spot is born over the orifice, so the particles
// just above it are swept by all of them and move ~50 times faster than the
// bulk; they get thick skins (growing linearly to GF_SKIN_ORIFICE at the
// orifice centre over GF_SKIN_REACH), so they do not force a rebuild every
// few thousand steps. (Skins scaled to each particle's recent motion were
// tried and lose: spots, and so relax(), live exactly where particles move,
// which then carry the longest lists.)
// Distance of a point from the orifice centre (from the slit's mid-plane).
static double gf_orifice_distance(const gf_sim *sim, double x, double y, double z)
{
    double zr = z - sim->box.exit_z, d2 = zr * zr + x * x;
    if (sim->box.shape == GF_ORIFICE_CIRCLE) d2 += y * y;
    return sqrt(d2);
}

static double gf_skin_at(double d)
{
    double w = d < GF_SKIN_REACH ? 1.0 - (d > 0 ? d : 0) / GF_SKIN_REACH : 0.0;
    return GF_SKIN + (GF_SKIN_ORIFICE - GF_SKIN) * w;
}

static void gf_nlist_skins(gf_sim *sim)
{
    for (size_t i = 0; i < sim->n; i++)
        sim->p0[i].r = gf_skin_at(gf_orifice_distance(sim, sim->p[i].x, sim->p[i].y, sim->p[i].z));
}

gf_status gf_nlist_build(gf_sim *sim, bool reorder)
{
    gf_status st;
    if (reorder) {
        gf_nlist_skins(sim);
        if ((st = gf_nlist_reorder(sim)) != GF_OK) return st;
    }
    gf_grid *g = &sim->grid;
    if (reorder) {
        // New indices: refill the grid in index order and restart the schedule.
        gf_grid_clear(g);
        for (size_t i = 0; i < sim->n; i++) {
            if (!sim->alive[i]) continue;
            st = gf_grid_insert(g, (uint32_t)i, gf_grid_cell(g, sim->p[i].x, sim->p[i].y, sim->p[i].z));
            if (st != GF_OK) return st;
            sim->p0[i].x = sim->p[i].x;
            sim->p0[i].y = sim->p[i].y;
            sim->p0[i].z = sim->p[i].z;
        }
        sim->nl_built_at = sim->st.events;
    }
    // A list built away from p0 must also cover the motion since p0 (resume):
    // each particle may have moved up to h since p0 and h again until the trigger.
    double widen = reorder ? 1.0 : 2.0;

    GF_DELETE(sim->nl_start, sim->cap + 1);
    sim->nl_start = GF_NEW(uint32_t, sim->cap + 1);
    if (!sim->nl_start) return gf_error_set(GF_ERR_NOMEM, "out of memory for neighbour lists");
    size_t len = 0;
    for (size_t i = 0; i < sim->n; i++) {
        sim->nl_start[i] = (uint32_t)len;
        if (!sim->alive[i]) continue;
        const double c[3] = {sim->p[i].x, sim->p[i].y, sim->p[i].z};
        const double hskin = sim->p0[i].r;
        // The thickest skin a neighbour can have: skins grow towards the
        // orifice and neighbours are within ~3.5 d (reach plus their motion).
        double hnear = gf_skin_at(gf_orifice_distance(sim, c[0], c[1], c[2]) - 3.5);
        int lo[3], hi[3];
        gf_grid_range(g, c, 2.0 * sim->rmax + widen * (hskin + hnear), lo, hi);
        size_t begin = len;
        for (int cz = lo[2]; cz <= hi[2]; cz++)
            for (int cy = lo[1]; cy <= hi[1]; cy++)
                for (int cx = lo[0]; cx <= hi[0]; cx++) {
                    size_t cell = ((size_t)cz * (size_t)g->ny + (size_t)cy) * (size_t)g->nx + (size_t)cx;
                    const uint32_t *s = g->slot + cell * GF_CELL_CAP;
                    for (uint32_t k = 0; k < g->count[cell]; k++) {
                        uint32_t j = s[k];
                        if (j == i) continue;
                        double dx = c[0] - sim->p[j].x, dy = c[1] - sim->p[j].y, dz = c[2] - sim->p[j].z;
                        double cut = sim->p[i].r + sim->p[j].r + widen * (hskin + sim->p0[j].r);
                        if (dx * dx + dy * dy + dz * dz >= cut * cut) continue;
                        if (len == sim->nl_cap) {
                            size_t ncap = sim->nl_cap ? 2 * sim->nl_cap : 16 * sim->n + 64;
                            uint32_t *q = gf_realloc(sim->nl, sizeof(uint32_t) * sim->nl_cap,
                                                     sizeof(uint32_t) * ncap);
                            if (!q) return gf_error_set(GF_ERR_NOMEM, "out of memory for neighbour lists");
                            sim->nl = q;
                            sim->nl_cap = ncap;
                        }
                        sim->nl[len++] = j;
                    }
                }
        gf_sort_u32(sim->nl + begin, len - begin);
    }
    sim->nl_start[sim->n] = (uint32_t)len;
    sim->rebuild_due = false;
    sim->st.nlist_builds++;
    return GF_OK;
}
