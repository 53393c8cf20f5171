// SPDX-License-Identifier: MIT
// The spatial fixed step, run in parallel (2009 paper Sec. 2.1: the fixed
// timestep "makes a parallel algorithm possible"; SPEC 1.4 and Sec. 3).
//
// A step inserts Poisson(lambda / mu) spots, then moves every spot once. The
// container is cut into blocks of whole grid cells: layers in z, and columns
// in x and y where the container is wide enough to hold more than one block
// of a colour. Along each cut axis the blocks are coloured 0, 1, ..., C - 1,
// 0, 1, ...; a block's colour combines its colours along the axes. A spot
// belongs to the block of its cell when the step begins, and moves in one of
// GF_PAR_PHASES phases, drawn at random. Each phase runs the colours one after
// the other, in a fresh random order; the blocks of one colour run at the same
// time, each on one thread, its spots of the phase one after the other in a
// random order. Two blocks of one colour are C - 1 blocks apart along some
// axis, wider than twice the reach of a spot step (everything spot(),
// relax() and the list and cell bookkeeping read or write) plus a cell, so
// they never share a particle, a list or a cell. The order of every
// conflicting pair of moves is therefore fixed by the geometry and the drawn
// phases and orders alone, each move draws on its own random stream (seed,
// spot, step), and counters are summed block by block: the result is the same
// bit for bit whatever the number of threads.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "core/alloc.h"
#include "geom/celllist.h"
#include "core/clock.h"
#include "core/error.h"
#include "spot/par_mpi.h"
#include "spot/sim_internal.h"

/// Colours along each cut axis: blocks of one colour are GF_PAR_COLOURS - 1
/// blocks apart. More colours make thinner blocks (more of them per colour:
/// better balance between threads) at the price of more barriers per step;
/// 4 gives 6 d blocks in the papers' silo.
#define GF_PAR_COLOURS 4
/// Slack added to the reach of a spot step, d (rounding, weighting and
/// reflection factors that stretch a spot() displacement).
#define GF_PAR_MARGIN 0.5
/// Phases of a step: each spot moves in one of them, drawn at random (its
/// own stream), and every phase runs all the colours. Two spots of different
/// blocks that can interact move in the order of their phases, and only when
/// they drew the same one (probability 1/P) in the order of their blocks'
/// colours, which is the same for every such pair of the two blocks. With one
/// phase that shared order biased the flow (the papers' silo drained 4.6%
/// slower than with the event engine: docs/performance.md); as P grows the
/// order of a step tends to a uniformly random one (SPEC 1.4).
#ifndef GF_PAR_PHASES
#define GF_PAR_PHASES 16
#endif
/// A colour phase with fewer spot moves than this runs on one thread: its
/// work (~16 us a move) would not pay for waking the others and the barrier.
#define GF_PAR_MIN_SHARED 32
/// Thread counts the step projects its speedup for (gf_par_profile).
static const int gf_par_proj_threads[GF_PAR_NPROJ] = {2, 8, 16, 64, 256};

typedef struct gf_block {
    gf_sim_stats st;   ///< the block's counters this step (summed in block order)
    gf_status status;  ///< first error of the block
    char err[256];     ///< its message
    size_t first, end; ///< its spots: order[first, end)
    double seconds;    ///< CPU time of its last run (profiling)
} gf_block;

typedef struct gf_par {
    int threads;
    gf_work *work;   ///< one per thread
    int bs[3];       ///< cells per block along x, y, z
    int nb[3];       ///< blocks along x, y, z
    int nc[3];       ///< colours along x, y, z (1: the axis is not cut)
    int ncolour;     ///< nc[0] nc[1] nc[2]
    size_t nblock;
    gf_block *block;
    gf_celllist colours;       ///< the blocks by colour: colour c's are colours.idx[start[c], start[c + 1])
    uint32_t *blockof;         ///< per grid cell: its block
    uint32_t *pstart; ///< block b's spots of phase p: spots.idx[pstart[b (P+1) + p], pstart[b (P+1) + p + 1])
    gf_celllist spots;              ///< spots by block (cell = block): spots.idx is their order (then by phase)
    uint32_t *tmp;                  ///< scratch
    uint8_t *dead;                  ///< per spot: removed this step
    uint8_t *phase;                 ///< per spot: its phase this step
    size_t spot_cap;
    uint32_t *run;                  ///< blocks of the current colour, heaviest first
    uint32_t *runload;              ///< their moves in the current phase
    double *secs;                   ///< their CPU times (profiling)
    uint8_t *mine;                  ///< per run[] entry: this rank runs it (gf_mpi_assign)
    uint64_t *rankload;             ///< scratch of gf_mpi_assign
    double *coltop;                 ///< per grid column: its top z at the step start
    size_t ncol;
    uint64_t shared_phases; ///< colour phases with two or more blocks to run
    gf_par_profile prof;    ///< per-block work and projections (when profiling)
    bool profiling;
} gf_par;

// Everything a step of a spot at s touches lies within this distance of s:
// the ball centre (a step away), the gather (r_e), then the neighbours of the
// gathered particles and the cells a list refresh searches, a box of half-width
// r_i + r_max + h_i + 2 h_max + slack around p0 (its diagonal). Distances are
// to the nearest point of a cell touched: the blocks add a cell diagonal.
double gf_par_reach(const gf_sim *sim)
{
    const gf_engine_defs *c = &sim->d;
    double step = sqrt(2.0 * c->step_xy * c->step_xy + c->step_z * c->step_z);
    double h = fmax(sim->hmax, GF_SKIN);
    double list = h + GF_SKIN_SLACK + sqrt(3.0) * (2.0 * sim->rmax + 3.0 * h + GF_SKIN_SLACK);
    // The biased walk counts balls of r_s in boxes of cells around its candidates.
    return step + fmax(sim->re + list, sqrt(3.0) * sim->rs) + GF_PAR_MARGIN;
}

void gf_par_free(gf_sim *sim)
{
    gf_par *q = sim->par;
    gf_mpi_release();
    if (!q) return;
    for (int t = 0; t < q->threads; t++) gf_work_free(&q->work[t]);
    GF_DELETE(q->work, q->threads);
    GF_DELETE(q->block, q->nblock);
    gf_celllist_free(&q->colours);
    GF_DELETE(q->blockof, sim->grid.ncell);
    GF_DELETE(q->pstart, q->nblock * (GF_PAR_PHASES + 1));
    gf_celllist_free(&q->spots);
    GF_DELETE(q->tmp, q->spot_cap);
    GF_DELETE(q->dead, q->spot_cap);
    GF_DELETE(q->phase, q->spot_cap);
    GF_DELETE(q->run, q->nblock);
    GF_DELETE(q->runload, q->nblock);
    GF_DELETE(q->secs, q->nblock);
    GF_DELETE(q->mine, q->nblock);
    GF_DELETE(q->rankload, q->nblock);
    GF_DELETE(q->coltop, q->ncol);
    gf_free(q, sizeof *q);
    sim->par = NULL;
}

int gf_par_threads(const gf_engine_defs *d)
{
#ifdef _OPENMP
#ifdef GF_MPI
    if (d->threads_auto) {
        // Every core, shared by this machine's ranks: more threads than cores
        // make every colour phase's barrier wait for a preempted thread.
        const int t = d->threads / gf_mpi_local_size();
        return t > 0 ? t : 1;
    }
#endif
    return d->threads; // run.threads, or every core (gf_config_engine_defs)
#else
    (void)d;
    return 1;
#endif
}

// The blocks along one axis of n cells: C colours of bs cells, where C - 1
// blocks span `need`; an axis too short to hold two blocks of one colour is
// not cut (one block, one colour).
static void gf_par_axis(int n, double need, double h, int *bs, int *nb, int *nc)
{
    *bs = (int)ceil(need / ((GF_PAR_COLOURS - 1) * h));
    *nb = (n + *bs - 1) / *bs;
    *nc = GF_PAR_COLOURS;
    if (*nb <= GF_PAR_COLOURS) {
        *bs = n;
        *nb = 1;
        *nc = 1;
    }
}

// The blocks and their colours; each colour's blocks listed in index order.
static gf_status gf_par_blocks(gf_sim *sim, gf_par *q)
{
    const gf_grid *g = &sim->grid;
    // Same-colour blocks are (C - 1) blocks apart along some axis: at least
    // two reaches and a cell diagonal (a cell both reaches could end in).
    double need = 2.0 * gf_par_reach(sim) + sqrt(3.0) * g->h;
    const int n[3] = {g->nx, g->ny, g->nz};
    for (int a = 0; a < 3; a++) gf_par_axis(n[a], need, g->h, &q->bs[a], &q->nb[a], &q->nc[a]);
    q->ncolour = q->nc[0] * q->nc[1] * q->nc[2];
    q->nblock = (size_t)q->nb[0] * (size_t)q->nb[1] * (size_t)q->nb[2];
    q->block = GF_NEW(gf_block, q->nblock);
    q->blockof = GF_NEW(uint32_t, g->ncell);
    q->pstart = GF_NEW(uint32_t, q->nblock * (GF_PAR_PHASES + 1));
    q->run = GF_NEW(uint32_t, q->nblock);
    q->runload = GF_NEW(uint32_t, q->nblock);
    q->secs = GF_NEW(double, q->nblock);
    q->mine = GF_NEW(uint8_t, q->nblock);
    q->rankload = GF_NEW(uint64_t, q->nblock);
    if (!q->block || !q->blockof || !q->pstart || !q->run || !q->runload || !q->secs || !q->mine || !q->rankload)
        return gf_error_set(GF_ERR_NOMEM, "out of memory for the parallel step");
    return gf_par_colour_blocks(g, q->bs, q->nb, q->nc, q->blockof, &q->colours);
}

gf_status gf_par_colour_blocks(const gf_grid *g, const int bs[3], const int nb[3], const int nc[3], uint32_t *blockof,
                               gf_celllist *bycolour)
{
    const size_t nblock = (size_t)nb[0] * (size_t)nb[1] * (size_t)nb[2];
    gf_status st = gf_celllist_keys(bycolour, (size_t)nc[0] * (size_t)nc[1] * (size_t)nc[2], nblock);
    if (st != GF_OK) return st;
    for (int cz = 0; cz < g->nz; cz++)
        for (int cy = 0; cy < g->ny; cy++)
            for (int cx = 0; cx < g->nx; cx++) {
                size_t bx = (size_t)(cx / bs[0]), by = (size_t)(cy / bs[1]), bz = (size_t)(cz / bs[2]);
                blockof[((size_t)cz * (size_t)g->ny + (size_t)cy) * (size_t)g->nx + (size_t)cx] =
                    (uint32_t)((bz * (size_t)nb[1] + by) * (size_t)nb[0] + bx);
            }
    for (size_t b = 0; b < nblock; b++) {
        size_t bx = b % (size_t)nb[0], by = b / (size_t)nb[0] % (size_t)nb[1], bz = b / ((size_t)nb[0] * (size_t)nb[1]);
        bycolour->cell[b] = (uint32_t)((bx % (size_t)nc[0]) + (size_t)nc[0] * ((by % (size_t)nc[1]) + (size_t)nc[1] * (bz % (size_t)nc[2])));
    }
    gf_celllist_sort(bycolour, nblock);
    return GF_OK;
}

static gf_status gf_par_make(gf_sim *sim)
{
    int threads = gf_par_threads(&sim->d);
    if (sim->par && sim->par->threads == threads) return GF_OK;
    gf_par_free(sim);
    gf_par *q = gf_alloc(sizeof *q);
    if (!q) return gf_error_set(GF_ERR_NOMEM, "out of memory for the parallel step");
    sim->par = q;
    const gf_grid *g = &sim->grid;
    q->ncol = (size_t)g->nx * (size_t)g->ny;
    q->threads = threads;
    q->work = GF_NEW(gf_work, threads);
    q->coltop = GF_NEW(double, q->ncol);
    if (!q->work) q->threads = 0;
    gf_status st = !q->work || !q->coltop ? gf_error_set(GF_ERR_NOMEM, "out of memory for the parallel step")
                                          : gf_par_blocks(sim, q);
    for (int t = 0; t < q->threads && st == GF_OK; t++) {
        st = gf_work_init(sim, &q->work[t]);
        q->work[t].defer_exits = true;
        q->work[t].coltop = q->coltop;
    }
    if (st != GF_OK) gf_par_free(sim);
    return st;
}

static gf_status gf_par_spots(gf_par *q, size_t ns)
{
    gf_status st = gf_celllist_keys(&q->spots, q->nblock, ns);
    if (st != GF_OK || ns <= q->spot_cap) return st;
    size_t cap = ns + ns / 2 + 64;
    GF_DELETE(q->tmp, q->spot_cap);
    GF_DELETE(q->dead, q->spot_cap);
    GF_DELETE(q->phase, q->spot_cap);
    q->tmp = GF_NEW(uint32_t, cap);
    q->dead = GF_NEW(uint8_t, cap);
    q->phase = GF_NEW(uint8_t, cap);
    q->spot_cap = cap;
    if (!q->tmp || !q->dead || !q->phase) {
        GF_DELETE(q->tmp, cap);
        GF_DELETE(q->dead, cap);
        GF_DELETE(q->phase, cap);
        q->tmp = NULL;
        q->dead = q->phase = NULL;
        q->spot_cap = 0;
        return gf_error_set(GF_ERR_NOMEM, "out of memory for %zu spots", ns);
    }
    return GF_OK;
}

void gf_par_column_tops(const gf_sim *sim, double *coltop, size_t ncol)
{
    for (size_t col = 0; col < ncol; col++)
        coltop[col] = gf_grid_column_top_at(&sim->grid, (uint32_t)col, &sim->p[0].z, 4);
}

// Spots grouped by block (in index order within a block).
static void gf_par_sort(gf_sim *sim, gf_par *q)
{
    const gf_grid *g = &sim->grid;
    const size_t ns = sim->ns;
    gf_celllist *cl = &q->spots;
    for (size_t k = 0; k < ns; k++) cl->cell[k] = q->blockof[gf_grid_cell(g, sim->sx[k], sim->sy[k], sim->sz[k])];
    gf_celllist_sort(cl, ns);
    for (size_t b = 0; b < q->nblock; b++) {
        q->block[b].first = cl->start[b];
        q->block[b].end = cl->start[b + 1];
    }
}

// The random stream of spot k's move in this step: a function of the seed,
// the spot's birth number and the step, not of the thread that runs it.
static void gf_par_seed(const gf_sim *sim, size_t k, gf_rng *r)
{
    uint64_t stream = (sim->sbirth[k] << 32) ^ (sim->fstep & 0xffffffffu);
    gf_rng_seed(r, sim->d.seed ^ 0x7370617469616cull /* "spatial" */, stream);
}

// Each block's spots in a random order drawn from the block's own stream
// (seed, step, block), then grouped by phase (a stable counting sort, so the
// order within a phase stays random); a spot's phase comes from its own stream.
static void gf_par_phases(gf_sim *sim, gf_par *q, int phases)
{
    for (size_t b = 0; b < q->nblock; b++) {
        gf_block *bl = &q->block[b];
        uint32_t *ps = &q->pstart[b * (GF_PAR_PHASES + 1)];
        memset(ps, 0, sizeof(uint32_t) * (GF_PAR_PHASES + 1));
        ps[0] = (uint32_t)bl->first;
        if (bl->end == bl->first) {
            for (int p = 0; p < GF_PAR_PHASES; p++) ps[p + 1] = ps[p];
            continue;
        }
        gf_rng rng;
        gf_rng_seed(&rng, sim->d.seed ^ 0x736c6162ull /* "slab" */, (sim->fstep << 24) ^ b);
        for (size_t k = bl->end - bl->first; k > 1; k--) { // Fisher-Yates
            size_t j = (size_t)gf_rng_below(&rng, k);
            uint32_t tmp = q->spots.idx[bl->first + k - 1];
            q->spots.idx[bl->first + k - 1] = q->spots.idx[bl->first + j];
            q->spots.idx[bl->first + j] = tmp;
        }
        for (size_t o = bl->first; o < bl->end; o++) {
            uint32_t k = q->spots.idx[o];
            gf_rng_seed(&rng, sim->d.seed ^ 0x7068617365ull /* "phase" */,
                        (sim->sbirth[k] << 32) ^ (sim->fstep & 0xffffffffu));
            q->phase[k] = (uint8_t)gf_rng_below(&rng, (uint64_t)phases);
            ps[q->phase[k] + 1]++;
        }
        for (int p = 0; p < GF_PAR_PHASES; p++) ps[p + 1] += ps[p];
        uint32_t next[GF_PAR_PHASES];
        memcpy(next, ps, sizeof next);
        for (size_t o = bl->first; o < bl->end; o++) q->tmp[next[q->phase[q->spots.idx[o]]]++] = q->spots.idx[o];
        memcpy(q->spots.idx + bl->first, q->tmp + bl->first, sizeof(uint32_t) * (bl->end - bl->first));
    }
}

// The spots of phase p of block b on worker w, in their drawn order.
static void gf_par_block(gf_sim *sim, gf_par *q, gf_work *w, size_t b, int p)
{
    gf_block *bl = &q->block[b];
    if (bl->status != GF_OK) return;
    const uint32_t *ps = &q->pstart[b * (GF_PAR_PHASES + 1)];
    double t0 = q->profiling ? gf_clock_thread_cpu() : 0.0;
    gf_rng rng;
    w->rng = &rng;
    w->st = &bl->st;
    gf_work_touch(w, GF_TOUCH_BLOCK, (uint32_t)b);
    for (size_t o = ps[p]; o < ps[p + 1]; o++) {
        size_t k = q->spots.idx[o];
        gf_work_touch(w, GF_TOUCH_SPOT, (uint32_t)k);
        gf_par_seed(sim, k, &rng);
        double s[3] = {sim->sx[k], sim->sy[k], sim->sz[k]};
        bool deleted;
        long ball;
        gf_status st = gf_spot_step(sim, w, s, &sim->scount[k], &deleted, &ball);
        if (st != GF_OK) {
            bl->status = st;
            snprintf(bl->err, sizeof bl->err, "%s", gf_last_error());
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
    if (q->profiling) bl->seconds = gf_clock_thread_cpu() - t0;
}

// Adds the counters a block's moves changed, block by block (fixed order:
// the floating-point sums do not depend on the threads either).
void gf_par_add(gf_sim_stats *to, const gf_sim_stats *a)
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
#ifdef GF_MPI
    gf_status sm = gf_mpi_merge_exits(sim, q->work, q->threads); // all ranks' exits (sorted below)
    if (sm != GF_OK) return sm;
#endif
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

// The phases of a step; GF_PAR_PHASES_TRY overrides it (experiments only).
static int gf_par_phase_count(void)
{
    const char *e = getenv("GF_PAR_PHASES_TRY");
    int p = e ? atoi(e) : GF_PAR_PHASES;
    return p < 1 ? 1 : p > GF_PAR_PHASES ? GF_PAR_PHASES : p;
}

uint64_t gf_par_shared_phases(const gf_sim *sim)
{
    if (sim->d.order == GF_ORDER_DOMAINS) return gf_dom_shared_phases(sim);
    return sim->par ? sim->par->shared_phases : 0;
}

double gf_par_makespan(const double *secs, size_t n, int T)
{
    double busy[256] = {0};
    if (T > 256) T = 256;
    double span = 0.0;
    for (size_t r = 0; r < n; r++) {
        int best = 0;
        for (int t = 1; t < T; t++)
            if (busy[t] < busy[best]) best = t;
        busy[best] += secs[r];
        if (busy[best] > span) span = busy[best];
    }
    return span;
}

static void gf_par_record(gf_par *q, size_t nrun)
{
    gf_par_profile *f = &q->prof;
    f->colour_phases++;
    f->barriers++;
    f->blocks_run += nrun;
    double work = 0.0, longest = 0.0;
    for (size_t r = 0; r < nrun; r++) {
        double s = q->block[q->run[r]].seconds;
        q->secs[r] = s;
        work += s;
        if (s > longest) longest = s;
    }
    f->work_seconds += work;
    f->span_seconds += longest;
    for (int i = 0; i < GF_PAR_NPROJ; i++)
        f->makespan_seconds[i] += gf_par_makespan(q->secs, nrun, gf_par_proj_threads[i]);
}

void gf_sim_set_par_profiling(gf_sim *sim, int on)
{
    if (sim->d.order == GF_ORDER_DOMAINS) {
        gf_dom_set_profiling(sim, on);
        return;
    }
    if (sim->d.order == GF_ORDER_SWEEP) {
        gf_sweep_set_profiling(sim, on);
        return;
    }
    if (gf_par_make(sim) != GF_OK) return;
    sim->par->profiling = on != 0;
    sim->par->prof = (gf_par_profile){0};
}

gf_par_profile gf_sim_par_profile(const gf_sim *sim)
{
    if (sim->d.order == GF_ORDER_DOMAINS) return gf_dom_profile(sim);
    if (sim->d.order == GF_ORDER_SWEEP) return gf_sweep_profile(sim);
    gf_par_profile f = {0};
    const gf_par *q = sim->par;
    if (!q) return f;
    f = q->prof;
    f.blocks = q->nblock;
    f.colours = q->ncolour;
    f.phases = gf_par_phase_count();
    for (int a = 0; a < 3; a++) {
        f.blocks_along[a] = q->nb[a];
        f.block_cells[a] = q->bs[a];
    }
    for (int i = 0; i < GF_PAR_NPROJ; i++) f.proj_threads[i] = gf_par_proj_threads[i];
    return f;
}

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
    for (size_t b = 0; b < q->nblock; b++) {
        q->block[b].st = (gf_sim_stats){0};
        q->block[b].status = GF_OK;
    }
    const int phases = gf_par_phase_count();
    gf_par_phases(sim, q, phases);
    int colours[GF_PAR_COLOURS * GF_PAR_COLOURS * GF_PAR_COLOURS];
    sim->grid.lazy_top = true; // top[] is shared by whole columns: redone after the step
    for (int p = 0; p < phases && st == GF_OK; p++) {
        for (int k = 0; k < q->ncolour; k++) colours[k] = k;
        for (int k = q->ncolour; k > 1; k--) { // Fisher-Yates
            int j = (int)gf_rng_below(&sim->rng, (uint64_t)k), tmp = colours[k - 1];
            colours[k - 1] = colours[j];
            colours[j] = tmp;
        }
        for (int ci = 0; ci < q->ncolour && st == GF_OK; ci++) {
            const int colour = colours[ci];
            // The colour's blocks with spots of this phase, heaviest first (the
            // threads take them in turn; which thread runs a block does not
            // change its result).
            size_t nrun = 0, moves = 0;
            for (size_t i = q->colours.start[colour]; i < q->colours.start[colour + 1]; i++) {
                const uint32_t b = q->colours.idx[i], *ps = &q->pstart[(size_t)b * (GF_PAR_PHASES + 1)];
                uint32_t load = ps[p + 1] - ps[p];
                if (load == 0) continue;
                moves += load;
                size_t k = nrun++;
                while (k > 0 && q->runload[k - 1] < load) {
                    q->run[k] = q->run[k - 1];
                    q->runload[k] = q->runload[k - 1];
                    k--;
                }
                q->run[k] = b;
                q->runload[k] = load;
            }
            q->shared_phases += nrun >= 2;
#ifdef GF_MPI
            if (nrun > 0 && (st = gf_mpi_phase_begin(sim, q->work, q->threads)) != GF_OK) break;
            gf_mpi_assign(q->runload, nrun, q->rankload, q->mine);
#else
            memset(q->mine, 1, nrun);
#endif
            int threads = nrun < (size_t)q->threads ? (int)nrun : q->threads;
            if (threads < 1 || moves < GF_PAR_MIN_SHARED) threads = 1;
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (threads > 1)
#endif
            for (size_t r = 0; r < nrun; r++) {
                gf_work *w = &q->work[gf_sim_thread()];
                if (q->mine[r]) gf_par_block(sim, q, w, q->run[r], p);
            }
#ifdef GF_MPI
            if (nrun > 0 &&
                (st = gf_mpi_phase_end(sim, q->work, q->threads, q->dead, q->block, q->nblock, sizeof *q->block)) != GF_OK)
                break;
#endif
            if (q->profiling && nrun > 0) gf_par_record(q, nrun);
            for (size_t r = 0; r < nrun && st == GF_OK; r++)
                if (q->block[q->run[r]].status != GF_OK)
                    st = gf_error_set(q->block[q->run[r]].status, "%s", q->block[q->run[r]].err);
        }
    }
    sim->grid.lazy_top = false;
    gf_grid_recompute_top(&sim->grid);
    for (size_t b = 0; b < q->nblock; b++) gf_par_add(&sim->st, &q->block[b].st);
    gf_status se = gf_par_merge_exits(sim, q);
    if (st == GF_OK) st = se;
    if (st != GF_OK) return st;
    gf_spots_compact(sim, q->dead);
    return gf_sim_fixed_end(sim);
}
