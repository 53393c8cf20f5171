// SPDX-License-Identifier: MIT
// Particle bookkeeping (the bottom of the engine): the particle and exit
// arrays, particles leaving through the orifice, the cells and neighbour
// lists of particles a step moved, and the public particle queries. Called by
// the mechanism (mechanism.c) and the kernel (walk.c); calls only nlist.c and
// recirculate.c.
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "core/alloc.h"
#include "core/clock.h"
#include "core/error.h"
#include "spot/sim_internal.h"
#include "spot/slabs.h"

gf_status gf_sim_alloc_particles(gf_sim *sim, size_t n)
{
    sim->cap = n;
    sim->p = GF_NEW_PAGES(gf_pos, n);
    sim->p0 = GF_NEW_PAGES(gf_ref, n);
    sim->id = GF_NEW_PAGES(int64_t, n);
    sim->layer = GF_NEW_PAGES(int32_t, n);
    sim->alive = GF_NEW_PAGES(uint8_t, n);
    sim->mark = GF_NEW_PAGES(uint32_t, n);
    sim->hist = GF_NEW_PAGES(gf_hist, n);
    if (!sim->p || !sim->p0 || !sim->id || !sim->layer || !sim->alive || !sim->mark || !sim->hist)
        return gf_error_set(GF_ERR_NOMEM, "out of memory for %zu particles", n);
    return GF_OK;
}

bool gf_sim_exits_reserve(gf_sim *sim, size_t extra)
{
    if (sim->nexit + extra <= sim->exit_cap) return true;
    size_t cap = sim->exit_cap ? sim->exit_cap + sim->exit_cap / 2 : 1024;
    if (cap < sim->nexit + extra) cap = sim->nexit + extra;
    gf_exit *x = gf_realloc(sim->exits, sim->exit_cap * sizeof(gf_exit), cap * sizeof(gf_exit));
    if (!x) return false;
    sim->exits = x;
    sim->exit_cap = cap;
    return true;
}

// Logs the list row of particle i and the rows of the particles it names
// (MPI exchange: the rows a drop or a refresh of i changes).
static void gf_touch_row(const gf_sim *sim, gf_work *w, uint32_t i)
{
    if (!w->log || !sim->use_nlist) return;
    gf_work_touch(w, GF_TOUCH_ROW, i);
    const uint32_t *row = sim->nl + ((size_t)i << sim->nl_shift);
    for (uint32_t k = 1; k <= row[0]; k++) gf_work_touch(w, GF_TOUCH_ROW, row[k]);
}

bool gf_sim_exit_slow(gf_sim *sim, gf_work *w, uint32_t i)
{
    gf_pos *q = &sim->p[i];
    if (!gf_container_exited(&sim->box, q->x, q->y, q->z)) return false;
    const gf_hist *h = &sim->hist[i];
    gf_exit e = {sim->id[i], w->timed ? w->t : sim->t, q->x, q->y, h->pass, h->t_entry, h->r_entry};
    const bool back = gf_sim_recirculates(sim, h->pass);
    if (w->defer_exits) {
        // The parallel step: kept by the worker, merged (sorted by id) after the phase.
        if (w->nexit == w->exit_cap) {
            size_t cap = w->exit_cap ? 2 * w->exit_cap : 64;
            gf_exit *x = gf_realloc(w->exits, w->exit_cap * sizeof(gf_exit), cap * sizeof(gf_exit));
            if (x) w->exits = x;
            uint32_t *sl = gf_realloc(w->exit_slot, w->exit_cap * sizeof(uint32_t), cap * sizeof(uint32_t));
            if (sl) w->exit_slot = sl;
            if (!x || !sl) { // out of memory: the particle stays, and the step reports it
                w->exit_failed = true;
                return false;
            }
            w->exit_cap = cap;
        }
        w->exit_slot[w->nexit] = back ? i : UINT32_MAX;
        w->exits[w->nexit++] = e;
    } else {
        if (back && !gf_sim_reinsert_queue(sim, i)) {
            w->exit_failed = true;
            return false;
        }
        // Exits of one step share its time; keep them ordered by id so the list
        // does not depend on the order particles were found in.
        if (!gf_sim_exits_reserve(sim, 1)) {
            w->exit_failed = true;
            return false;
        }
        size_t k = sim->nexit++;
        while (k > 0 && sim->exits[k - 1].time == sim->t && sim->exits[k - 1].id > sim->id[i]) {
            sim->exits[k] = sim->exits[k - 1];
            k--;
        }
        sim->exits[k] = e;
        sim->n_alive--;
    }
    // Its cell (whose last particle takes its slot) and the rows it leaves.
    gf_work_touch(w, GF_TOUCH_PARTICLE, i);
    if (sim->grid.cell_of[i] != GF_NO_CELL) gf_work_touch(w, GF_TOUCH_CELL, sim->grid.cell_of[i]);
    gf_touch_row(sim, w, i);
    gf_grid_remove(&sim->grid, i);
    gf_nlist_drop(sim, i);
    sim->alive[i] = 0;
    q->x = q->y = q->z = GF_PARK_COORD;
    return true;
}

int gf_exit_cmp_time_id(const void *a, const void *b)
{
    const gf_exit *x = a, *y = b;
    if (x->time != y->time) return (x->time > y->time) - (x->time < y->time);
    return (x->id > y->id) - (x->id < y->id);
}

gf_status gf_sim_track_moves(gf_sim *sim, gf_work *w, size_t m, const uint8_t *moved)
{
    const uint32_t *inside = w->inside;
    const gf_pos *p = sim->p;
    gf_grid *g = &sim->grid;
    uint32_t *cross = w->cross;
    size_t nc = 0;
    // Cells first, so that the refreshes below search a grid that is current.
    // (Exited particles are not flagged in moved[]; they left the grid.)
    for (size_t k = 0; k < m; k++) {
        if (!moved[k]) continue;
        uint32_t i = inside[k];
        const gf_pos *q = &p[i];
        const gf_ref *a = &sim->p0[i];
        double dx = q->x - a->x, dy = q->y - a->y, dz = q->z - a->z, lim = a->h - GF_SKIN_SLACK;
        cross[nc] = i;
        nc += dx * dx + dy * dy + dz * dz > lim * lim;
        gf_work_touch(w, GF_TOUCH_MOVED, i);
        uint32_t c = gf_grid_cell(g, q->x, q->y, q->z);
        if (c != g->cell_of[i]) {
#ifdef GF_MPI
            // Into a rank's region from beyond it: the rank holds an old
            // record of it (list reference, row), so it gets the whole one.
            if (w->log && w->slabs && gf_slabs_crosses(w->slabs, g->cell_of[i], c)) {
                gf_work_touch(w, GF_TOUCH_PARTICLE, i);
                if (sim->use_nlist) gf_work_touch(w, GF_TOUCH_ROW, i);
            }
#endif
            gf_work_touch(w, GF_TOUCH_CELL, g->cell_of[i]);
            gf_work_touch(w, GF_TOUCH_CELL, c);
            gf_grid_remove(g, i);
            gf_status st = gf_grid_insert(g, i, c);
            if (st != GF_OK) return st;
            if (w->colmax) { // the highest layer entered in the column (domains.c settles the tops)
                int32_t cz;
                const uint32_t col = gf_grid_cell_column(g, c, &cz);
                if (cz > w->colmax[col]) w->colmax[col] = cz;
            }
        }
    }
    for (size_t k = 0; sim->use_nlist && k < nc; k++) {
        gf_touch_row(sim, w, cross[k]); // the rows it leaves and joins
        gf_work_touch(w, GF_TOUCH_PARTICLE, cross[k]); // its new p0
        gf_status st = gf_nlist_refresh(sim, cross[k]);
        gf_touch_row(sim, w, cross[k]);
        if (st != GF_OK) return st;
    }
    return GF_OK;
}

typedef struct gf_id_index {
    int64_t id;
    uint32_t index;
} gf_id_index;

static int gf_cmp_id(const void *a, const void *b)
{
    int64_t x = ((const gf_id_index *)a)->id, y = ((const gf_id_index *)b)->id;
    return (x > y) - (x < y);
}

gf_status gf_sim_particles(const gf_sim *sim, gf_packing *out)
{
    size_t m = 0, cap = sim->n_alive ? sim->n_alive : 1;
    gf_id_index *idx = GF_NEW(gf_id_index, cap);
    if (!idx) return gf_error_set(GF_ERR_NOMEM, "out of memory");
    for (size_t i = 0; i < sim->n; i++)
        if (sim->alive[i]) idx[m++] = (gf_id_index){sim->id[i], (uint32_t)i};
    qsort(idx, m, sizeof *idx, gf_cmp_id);
    out->n = 0;
    gf_status st = gf_packing_reserve(out, m);
    for (size_t k = 0; st == GF_OK && k < m; k++) {
        const gf_pos *q = &sim->p[idx[k].index];
        st = gf_packing_push(out, idx[k].id, sim->layer[idx[k].index], q->x, q->y, q->z, q->r);
    }
    GF_DELETE(idx, cap);
    return st;
}

gf_status gf_sim_passes(const gf_sim *sim, int32_t *pass, size_t n)
{
    if (n != sim->n_alive) return gf_error_set(GF_ERR_PARAM, "gf_sim_passes: %zu slots for %zu particles", n, sim->n_alive);
    gf_id_index *idx = GF_NEW(gf_id_index, n ? n : 1);
    if (!idx) return gf_error_set(GF_ERR_NOMEM, "out of memory");
    size_t m = 0;
    for (size_t i = 0; i < sim->n; i++)
        if (sim->alive[i]) idx[m++] = (gf_id_index){sim->id[i], (uint32_t)i};
    qsort(idx, m, sizeof *idx, gf_cmp_id);
    for (size_t k = 0; k < m; k++) pass[k] = sim->hist[idx[k].index].pass;
    GF_DELETE(idx, n ? n : 1);
    return GF_OK;
}

const gf_exit *gf_sim_exits(const gf_sim *sim, size_t *n)
{
    *n = sim->nexit;
    return sim->exits;
}
