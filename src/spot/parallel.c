// SPDX-License-Identifier: MIT
// The spatial fixed step, run in parallel (2009 paper Sec. 2.1: the fixed
// timestep "makes a parallel algorithm possible"; SPEC 1.4 and Sec. 3).
//
// A step inserts Poisson(lambda / mu) spots, then moves every spot once. The
// container is cut into horizontal slabs of cps grid layers, coloured
// 0, 1, ..., C - 1, 0, 1, ... from the bottom. A spot belongs to the slab of
// its cell when the step begins. Colours run one after the other, in a fresh
// random order each step; the slabs of one colour run at the same time, each
// on one thread, its spots one after the other in a fresh random order. So
// any two spots that can interact move in either order with probability 1/2,
// as in the random order of SPEC 1.4 (a bottom-up order would drain like the
// newest-first one, ~10% slower). Two slabs of one colour are C - 1 slabs apart,
// wider than twice the reach of a spot step (everything spot(), relax() and the
// list and cell bookkeeping read or write) plus a cell, so they never share a
// particle, a list or a cell. The order of every conflicting pair of moves is
// therefore fixed by the geometry alone, each move draws on its own random
// stream (seed, spot, step), and counters are summed slab by slab: the result
// is the same bit for bit whatever the number of threads.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "core/alloc.h"
#include "core/error.h"
#include "spot/sim_internal.h"

/// Colours of the slab cycle: slabs of one colour are GF_PAR_COLOURS - 1
/// slabs apart. More colours make thinner slabs (more of them per colour:
/// better balance between threads) at the price of more barriers per step;
/// 4 gives 5-6 slabs per colour in the papers' silo.
#define GF_PAR_COLOURS 4
/// Slack added to the reach of a spot step, d (rounding, weighting and
/// reflection factors that stretch a spot() displacement).
#define GF_PAR_MARGIN 0.5

typedef struct gf_slab {
    gf_sim_stats st;   ///< the slab's counters this step (summed in slab order)
    gf_status status;  ///< first error of the slab
    char err[256];     ///< its message
    size_t first, end; ///< its spots: order[first, end)
} gf_slab;

typedef struct gf_par {
    int threads;
    gf_work *work; ///< one per thread
    int cps;       ///< grid layers per slab
    size_t nslab;
    gf_slab *slab;
    uint32_t *order, *cellof;       ///< spots sorted by (cell, index); each spot's cell
    uint8_t *dead;                  ///< per spot: removed this step
    size_t spot_cap;
    uint32_t *bucket;               ///< counting sort: first entry of each cell
    uint32_t *run;                  ///< slabs of the current colour, heaviest first
    double *coltop;                 ///< per grid column: its top z at the step start
    size_t ncol, ncell;
    uint64_t shared_phases; ///< colour phases with two or more slabs to run
} gf_par;

// Everything a step of a spot at s touches lies within this distance of s:
// the ball centre (a step away), the gather (r_e), then the neighbours of the
// gathered particles and the cells a list refresh searches, a box of half-width
// r_i + r_max + h_i + 2 h_max + slack around p0 (its diagonal). Distances are
// to the nearest point of a cell touched: the slabs add a cell diagonal.
static double gf_par_reach(const gf_sim *sim)
{
    const gf_config *c = &sim->cfg;
    double step = sqrt(2.0 * c->spot_step_xy * c->spot_step_xy + c->spot_step_z * c->spot_step_z);
    double h = fmax(sim->hmax, GF_SKIN);
    double list = h + GF_SKIN_SLACK + sqrt(3.0) * (2.0 * sim->rmax + 3.0 * h + GF_SKIN_SLACK);
    // The biased walk counts balls of r_s in boxes of cells around its candidates.
    return step + fmax(sim->re + list, sqrt(3.0) * sim->rs) + GF_PAR_MARGIN;
}

void gf_par_free(gf_sim *sim)
{
    gf_par *q = sim->par;
    if (!q) return;
    for (int t = 0; t < q->threads; t++) gf_work_free(&q->work[t]);
    GF_DELETE(q->work, q->threads);
    GF_DELETE(q->slab, q->nslab);
    GF_DELETE(q->order, q->spot_cap);
    GF_DELETE(q->cellof, q->spot_cap);
    GF_DELETE(q->dead, q->spot_cap);
    GF_DELETE(q->bucket, q->ncell + 1);
    GF_DELETE(q->run, q->nslab);
    GF_DELETE(q->coltop, q->ncol);
    gf_free(q, sizeof *q);
    sim->par = NULL;
}

static int gf_par_threads(const gf_config *c)
{
#ifdef _OPENMP
    return c->run_threads > 0 ? (int)c->run_threads : omp_get_num_procs();
#else
    (void)c;
    return 1;
#endif
}

static gf_status gf_par_make(gf_sim *sim)
{
    int threads = gf_par_threads(&sim->cfg);
    if (sim->par && sim->par->threads == threads) return GF_OK;
    gf_par_free(sim);
    gf_par *q = gf_alloc(sizeof *q);
    if (!q) return gf_error_set(GF_ERR_NOMEM, "out of memory for the parallel step");
    sim->par = q;
    const gf_grid *g = &sim->grid;
    // Same-colour slabs are (C - 1) cps layers apart: at least two reaches
    // and a cell diagonal (a cell both reaches could end in).
    double need = 2.0 * gf_par_reach(sim) + sqrt(3.0) * g->h;
    q->cps = (int)ceil(need / ((GF_PAR_COLOURS - 1) * g->h));
    q->nslab = (size_t)((g->nz + q->cps - 1) / q->cps);
    q->ncol = (size_t)g->nx * (size_t)g->ny;
    q->ncell = g->ncell;
    q->threads = threads;
    q->work = GF_NEW(gf_work, threads);
    q->slab = GF_NEW(gf_slab, q->nslab);
    q->bucket = GF_NEW(uint32_t, q->ncell + 1);
    q->run = GF_NEW(uint32_t, q->nslab);
    q->coltop = GF_NEW(double, q->ncol);
    if (!q->work || !q->slab || !q->bucket || !q->run || !q->coltop) {
        if (!q->work) q->threads = 0;
        gf_par_free(sim);
        return gf_error_set(GF_ERR_NOMEM, "out of memory for the parallel step");
    }
    for (int t = 0; t < threads; t++) {
        gf_status st = gf_work_init(sim, &q->work[t]);
        if (st != GF_OK) {
            gf_par_free(sim);
            return st;
        }
        q->work[t].defer_exits = true;
        q->work[t].coltop = q->coltop;
    }
    return GF_OK;
}

static gf_status gf_par_spots(gf_par *q, size_t ns)
{
    if (ns <= q->spot_cap) return GF_OK;
    size_t cap = ns + ns / 2 + 64;
    GF_DELETE(q->order, q->spot_cap);
    GF_DELETE(q->cellof, q->spot_cap);
    GF_DELETE(q->dead, q->spot_cap);
    q->order = GF_NEW(uint32_t, cap);
    q->cellof = GF_NEW(uint32_t, cap);
    q->dead = GF_NEW(uint8_t, cap);
    q->spot_cap = cap;
    if (!q->order || !q->cellof || !q->dead) {
        GF_DELETE(q->order, cap);
        GF_DELETE(q->cellof, cap);
        GF_DELETE(q->dead, cap);
        q->order = q->cellof = NULL;
        q->dead = NULL;
        q->spot_cap = 0;
        return gf_error_set(GF_ERR_NOMEM, "out of memory for %zu spots", ns);
    }
    return GF_OK;
}

// The removal test's column tops, as gf_grid_column_top would answer now.
static void gf_par_column_tops(const gf_sim *sim, double *coltop, size_t ncol)
{
    for (size_t col = 0; col < ncol; col++)
        coltop[col] = gf_grid_column_top_at(&sim->grid, (uint32_t)col, &sim->p[0].z, 4);
}

// Spots sorted by (cell, index) with a counting sort over the cells; cells
// are numbered layer by layer, so each slab's spots come out contiguous.
static void gf_par_sort(gf_sim *sim, gf_par *q)
{
    const gf_grid *g = &sim->grid;
    const size_t ns = sim->ns, layer = q->ncol * (size_t)q->cps;
    memset(q->bucket, 0, sizeof(uint32_t) * (q->ncell + 1));
    for (size_t k = 0; k < ns; k++) {
        q->cellof[k] = gf_grid_cell(g, sim->sx[k], sim->sy[k], sim->sz[k]);
        q->bucket[q->cellof[k] + 1]++;
    }
    for (size_t c = 0; c < q->ncell; c++) q->bucket[c + 1] += q->bucket[c];
    for (size_t b = 0; b < q->nslab; b++) {
        size_t c0 = b * layer, c1 = c0 + layer < q->ncell ? c0 + layer : q->ncell;
        q->slab[b].first = q->bucket[c0];
        q->slab[b].end = q->bucket[c1];
    }
    for (size_t k = 0; k < ns; k++) q->order[q->bucket[q->cellof[k]]++] = (uint32_t)k;
}

// The random stream of spot k's move in this step: a function of the seed,
// the spot's birth number and the step, not of the thread that runs it.
static void gf_par_seed(const gf_sim *sim, size_t k, gf_rng *r)
{
    uint64_t stream = (sim->sbirth[k] << 32) ^ (sim->fstep & 0xffffffffu);
    gf_rng_seed(r, sim->cfg.run_seed ^ 0x7370617469616cull /* "spatial" */, stream);
}

// The spots of one slab on worker w, in a random order drawn from the slab's
// own stream (seed, step, slab).
static void gf_par_slab(gf_sim *sim, gf_par *q, gf_work *w, gf_slab *sl, size_t b)
{
    gf_rng rng;
    gf_rng_seed(&rng, sim->cfg.run_seed ^ 0x736c6162ull /* "slab" */, (sim->fstep << 24) ^ b);
    for (size_t k = sl->end - sl->first; k > 1; k--) { // Fisher-Yates
        size_t j = (size_t)gf_rng_below(&rng, k);
        uint32_t tmp = q->order[sl->first + k - 1];
        q->order[sl->first + k - 1] = q->order[sl->first + j];
        q->order[sl->first + j] = tmp;
    }
    w->rng = &rng;
    w->st = &sl->st;
    for (size_t o = sl->first; o < sl->end; o++) {
        size_t k = q->order[o];
        gf_par_seed(sim, k, &rng);
        double s[3] = {sim->sx[k], sim->sy[k], sim->sz[k]};
        bool deleted;
        long ball;
        gf_status st = gf_spot_step(sim, w, s, &sim->scount[k], &deleted, &ball);
        if (st != GF_OK) {
            sl->status = st;
            snprintf(sl->err, sizeof sl->err, "%s", gf_last_error());
            return;
        }
        if (deleted) {
            q->dead[k] = 1;
            continue;
        }
        sim->sx[k] = s[0];
        sim->sy[k] = s[1];
        sim->sz[k] = s[2];
    }
}

// Adds the counters a slab's moves changed, slab by slab (fixed order: the
// floating-point sums do not depend on the threads either).
static void gf_par_add(gf_sim_stats *to, const gf_sim_stats *a)
{
    to->spot_moves += a->spot_moves;
    to->relax_calls += a->relax_calls;
    to->spot_seconds += a->spot_seconds;
    to->relax_seconds += a->relax_seconds;
    to->spot_dz += a->spot_dz;
    to->relax_dz += a->relax_dz;
}

static int gf_par_cmp_exit(const void *a, const void *b)
{
    int64_t x = ((const gf_exit *)a)->id, y = ((const gf_exit *)b)->id;
    return (x > y) - (x < y);
}

// The exits the workers found this step, appended and sorted by id (they
// share the step's time), as the serial engine keeps them.
static gf_status gf_par_merge_exits(gf_sim *sim, gf_par *q)
{
    size_t first = sim->nexit, total = 0;
    for (int t = 0; t < q->threads; t++) total += q->work[t].nexit;
    if (!gf_sim_exits_reserve(sim, total)) return gf_error_set(GF_ERR_NOMEM, "out of memory for %zu exits", total);
    for (int t = 0; t < q->threads; t++) {
        gf_work *w = &q->work[t];
        if (w->nexit == 0) continue;
        memcpy(sim->exits + sim->nexit, w->exits, w->nexit * sizeof(gf_exit));
        for (size_t k = 0; k < w->nexit; k++) // recirculation (gf_sim_reinsert puts them back in id order)
            if (w->exit_slot[k] != UINT32_MAX && !gf_sim_reinsert_queue(sim, w->exit_slot[k]))
                return gf_error_set(GF_ERR_NOMEM, "out of memory for the re-insertions");
        sim->nexit += w->nexit;
        sim->n_alive -= w->nexit;
        w->nexit = 0;
    }
    if (sim->nexit > first) qsort(sim->exits + first, sim->nexit - first, sizeof(gf_exit), gf_par_cmp_exit);
    return GF_OK;
}

uint64_t gf_par_shared_phases(const gf_sim *sim) { return sim->par ? sim->par->shared_phases : 0; }

gf_status gf_sim_spatial_step(gf_sim *sim)
{
    gf_status st = gf_par_make(sim);
    if (st != GF_OK) return st;
    gf_par *q = sim->par;
    if ((st = gf_sim_fixed_begin(sim)) != GF_OK) return st;
    const size_t ns = sim->ns;
    if ((st = gf_par_spots(q, ns)) != GF_OK) return st;
    memset(q->dead, 0, ns);
    gf_par_column_tops(sim, q->coltop, q->ncol);
    gf_par_sort(sim, q);
    for (size_t b = 0; b < q->nslab; b++) {
        q->slab[b].st = (gf_sim_stats){0};
        q->slab[b].status = GF_OK;
    }
    int colours[GF_PAR_COLOURS];
    for (int k = 0; k < GF_PAR_COLOURS; k++) colours[k] = k;
    for (int k = GF_PAR_COLOURS; k > 1; k--) { // Fisher-Yates
        int j = (int)gf_rng_below(&sim->rng, (uint64_t)k), tmp = colours[k - 1];
        colours[k - 1] = colours[j];
        colours[j] = tmp;
    }
    sim->grid.lazy_top = true; // top[] is shared by whole columns: redone after the step
    for (int ci = 0; ci < GF_PAR_COLOURS && st == GF_OK; ci++) {
        const int colour = colours[ci];
        // The colour's slabs with spots, heaviest first (the threads take
        // them in turn; which thread runs a slab does not change its result).
        size_t nrun = 0;
        for (size_t b = (size_t)colour; b < q->nslab; b += GF_PAR_COLOURS) {
            if (q->slab[b].end == q->slab[b].first) continue;
            size_t load = q->slab[b].end - q->slab[b].first, k = nrun++;
            while (k > 0 && q->slab[q->run[k - 1]].end - q->slab[q->run[k - 1]].first < load) {
                q->run[k] = q->run[k - 1];
                k--;
            }
            q->run[k] = (uint32_t)b;
        }
        q->shared_phases += nrun >= 2;
        int threads = nrun < (size_t)q->threads ? (int)nrun : q->threads;
        if (threads < 1) threads = 1;
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (threads > 1)
#endif
        for (size_t r = 0; r < nrun; r++) {
#ifdef _OPENMP
            gf_work *w = &q->work[omp_get_thread_num()];
#else
            gf_work *w = &q->work[0];
#endif
            gf_par_slab(sim, q, w, &q->slab[q->run[r]], q->run[r]);
        }
        for (size_t b = 0; b < q->nslab && st == GF_OK; b++)
            if (q->slab[b].status != GF_OK) st = gf_error_set(q->slab[b].status, "%s", q->slab[b].err);
    }
    sim->grid.lazy_top = false;
    gf_grid_recompute_top(&sim->grid);
    for (size_t b = 0; b < q->nslab; b++) gf_par_add(&sim->st, &q->slab[b].st);
    gf_status se = gf_par_merge_exits(sim, q);
    if (st == GF_OK) st = se;
    if (st != GF_OK) return st;
    gf_spots_compact(sim, q->dead);
    return gf_sim_fixed_end(sim);
}
