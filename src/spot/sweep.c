// SPDX-License-Identifier: MIT
// The sweep engine (run.order = sweep): a data-parallel windowed spot
// engine. The domain engine (domains.c) keeps every pair of conflicting
// moves exact, and the column over the orifice, which every spot climbs,
// bounds its speedup whatever the schedule (docs/performance.md). The 2009
// paper allows reordering moves (Sec. 2.1) and relaxing the whole packing
// at intervals (Sec. 5, method 3); this engine goes further and lets every
// move of a window read the packing as it was when the window began:
//
// 1. insertions: Poisson(lambda W) spots at uniform times (as domains.c);
// 2. walk: every spot makes its moves of the window [t, t + W) (exponential
//    waits at rate mu, a stream per (seed, spot, move time)), its walk,
//    removal test and ball count (free-surface bias, influence weighting)
//    reading the window-start particles; each move is recorded (time,
//    centre, displacement u with gf_spot_apply's factors, mirror centres).
//    Parallel over chunks of spots;
// 3. displace: every particle within r_s of a recorded move's centre moves
//    by that move's u (times S(x), Sec. 4), summed over the moves in a fixed
//    order (by cell of the centre, then record order), read from window-start
//    positions; the particles within r_e of any move are the window's active
//    set. A gather over particles: parallel over chunks of cells;
// 4. relax: parallel.sweeps Jacobi sweeps over the active set with the rule
//    of relax() (SPEC 1.3: alpha delta / 2 each for two active particles,
//    alpha delta for an active one against a fixed one, alpha (r - gap) from
//    a wall), each reading the positions of the sweep's start;
// 5. bookkeeping: the chunks flag, side by side, the particles they moved
//    below the exit plane, into another cell or past their skin; groups of
//    chunks sort them side by side into exits, cell movers and crossers;
//    one thread does the exits (each timed by the last move that reached
//    the particle; a handful a window); cell moves run as parallel removals
//    (each group from its own cells) then insertions (each group into its
//    own cells); the list refreshes run as a batch (gf_sweep_refresh),
//    mostly side by side.
//
// Determinism: every sum runs in an order fixed by the state (cells, slots,
// rows, chunks of a fixed size), the records of the spot chunks are joined in
// chunk order and the window's exits sorted by (time, id): the result depends
// on the seed and the keys, never on run.threads.
//
// Profiling (gf_sim_set_par_profiling, on one thread): the CPU time of every
// chunk of every parallel block, less the cost of reading the clock, and the
// one-thread stretches timed one by one; the projected makespan on P workers
// is, per block, the LPT schedule of its chunks, plus the one-thread time.
#include <math.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "core/alloc.h"
#include "core/clock.h"
#include "core/error.h"
#include "geom/celllist.h"
#include "spot/sim_internal.h"

/// Spots per walk chunk and grid cells per gather chunk: the units of work
/// (and of the profile), independent of the thread count.
#define GF_SWEEP_SPOT_CHUNK 4
#define GF_SWEEP_CELL_CHUNK 4
/// Crossers per search task and rows per merge task of a batch of list refreshes.
#define GF_SWEEP_FIND_GROUP 4
#define GF_SWEEP_MERGE_GROUP 32
/// Cell chunks per group of the summary after a block: the one-thread loops
/// (counters, exits and cell moves, the list batch) visit a thousand groups
/// of the pebble bed, not 68,000 chunk records.
#define GF_SWEEP_GROUP 64
/// Grid columns per task of the column tops and the top recompute.
#define GF_SWEEP_COL_CHUNK 64
/// Worker counts the speedup is projected for (as the other engines').
static const int gf_sweep_proj_threads[GF_PAR_NPROJ] = {2, 8, 16, 64, 256};

/// One recorded move (64 bytes: the gather streams through them).
typedef struct gf_sweep_move {
    double t;      ///< its time
    double c[3];   ///< its ball's centre
    double u[3];   ///< what it gives each particle within r_s (weighting included)
    uint32_t mir;  ///< its mirror centres (walls = reflect, Sec. 4): mirs[mir, mir + nmir)
    int32_t nmir;
} gf_sweep_move;

/// A chunk of spots (walk) or of cells (gather, sweeps): its output and time.
typedef struct gf_sweep_chunk {
    gf_sweep_move *mv; ///< walk: its spots' moves, in spot then time order
    size_t nmv, mv_cap;
    double (*mirs)[3]; ///< walk: their mirror centres
    size_t nmirs, mirs_cap;
    size_t at, mir_at; ///< walk: where its moves and mirrors go in the window's arrays
    uint32_t *list;    ///< sweeps: the particles it is to move, in cell and slot order
    size_t nlist, list_cap;
    uint32_t *todo;    ///< the particles it moved that the bookkeeping must see (below the exit
                       ///< plane, into another cell, past their skin), in cell and slot order
    size_t ntodo, todo_cap;
    gf_sim_stats st;
    gf_status status;
    double seconds;
} gf_sweep_chunk;

/// The grid cells of a group (GF_SWEEP_GROUP chunks of GF_SWEEP_CELL_CHUNK cells).
#define GF_SWEEP_GROUP_CELLS ((size_t)GF_SWEEP_GROUP * GF_SWEEP_CELL_CHUNK)

/// A particle that changes cell: its index and its new cell.
typedef struct gf_sweep_mover {
    uint32_t i, cell;
} gf_sweep_mover;

/// A group of GF_SWEEP_GROUP cell chunks, summarised side by side after a
/// block: what its chunks flagged sorted into the bookkeeping's lists, and
/// their counters summed, in chunk order.
typedef struct gf_sweep_group {
    uint32_t *exit;        ///< below the exit plane (one thread: exits)
    size_t nexit, exit_cap;
    gf_sweep_mover *mover; ///< into another cell (cell moves, side by side)
    size_t nmover, mover_cap;
    uint32_t *skin;        ///< past their skin (the list batch)
    size_t nskin, skin_cap;
    ptrdiff_t reach_lo, reach_hi; ///< the groups its movers go to, relative to it
    double spot_dz, relax_dz;
    gf_status status;
    uint32_t full_cell;    ///< a cell the insertions found full (status GF_ERR_STATE)
} gf_sweep_group;

typedef struct gf_sweep {
    int threads;
    size_t nspot_chunk, spot_chunk_cap;
    gf_sweep_chunk *spot; ///< walk chunks
    size_t ncell_chunk;
    gf_sweep_chunk *cell; ///< gather and sweep chunks
    size_t ngroup;
    gf_sweep_group *group; ///< the cell chunks' summaries, GF_SWEEP_GROUP chunks a group
    double *gsecs;        ///< profiling: the last summary's time per group
    ptrdiff_t reach_lo, reach_hi; ///< the last summary: how far (in groups) its movers go
    uint32_t *xgroup;     ///< the last summary: the groups with particles below the exit plane
    size_t nxgroup;
    size_t *gat;          ///< the binning of the moves: where each group's start (ngroup + 1)
    size_t *gcur;         ///< its cursors (ngroup)
    uint32_t *gmv;        ///< the moves dealt to the groups of their cells, in record order
    size_t gmv_cap;
    gf_sweep_move *mv;    ///< the window's moves, joined in chunk order
    size_t nmv, mv_cap;
    double (*mirs)[3];    ///< their mirror centres
    size_t nmirs, mirs_cap;
    gf_celllist bycell;   ///< moves by the grid cell of their centre
    uint32_t **cand;      ///< per thread: the moves near a cell
    size_t *cand_cap;
    size_t cap;           ///< particles the per-particle arrays hold
    double (*disp)[3];    ///< per particle: the sweep's displacement
    uint32_t *active;     ///< per particle: the last window (stamp) with a move within r_e of it
    uint32_t stamp;       ///< this window's number: its active set and touched chunks carry it
    uint32_t *cstamp;     ///< per cell chunk: the last window with a move within reach of its cells
    uint32_t *touched;    ///< the window's touched cell chunks, in chunk order (its blocks visit these)
    size_t ntouched;
    size_t *gstart;       ///< per group: where its touched chunks start in touched[] (ngroup + 1)
    double *tsecs;        ///< profiling: the touched chunks' times in the last cell block
    double *tlast;        ///< per particle: time of the last move that reached it
    uint8_t *crossing;    ///< per particle: 1 while it is among the batch's crossers
    uint32_t *gain;       ///< per particle: 1 + its entry in aff[] while the batch rewrites its row, else 0
    uint32_t *cross;      ///< the batch's crossers (past their skin), in chunk order
    size_t cross_cap;
    uint32_t (*pairs)[2]; ///< the batch's (row j, crosser i or UINT32_MAX) to add to or filter from j's row
    size_t pairs_cap;
    uint32_t *aff;        ///< the rows the batch rewrites, first seen first
    size_t *aff_at;       ///< per aff entry: where its crossers start in adds[] (naff + 1 entries)
    uint32_t *adds;       ///< the crossers each aff row gains, grouped by row
    size_t aff_cap, aff_at_cap, adds_cap;
    gf_status *find_st;   ///< per crosser: its row's search
    uint32_t *segn;       ///< per crosser: the pairs its old row, then its new row, gave (2 nc)
    size_t segn_cap;
    size_t find_cap;
    double *fsecs, *msecs; ///< profiling: the last batch's times per crosser's search and per row's merge
    size_t fsecs_cap, msecs_cap, nf, nm;
    uint8_t *dead;
    size_t dead_cap;
    double *coltop;
    size_t ncol;
    double *csecs;        ///< profiling: the last column block's time per task
    gf_work w;            ///< the bookkeeping's worker (timed exits)
    double *secs;         ///< profiling scratch
    size_t secs_cap;
    bool profiling;
    bool dense;           ///< tests: every window visits every cell chunk (gf_sweep_set_dense)
    int full;             ///< an insertion found a cell full (the run then stops)
    double clock_cost;    ///< profiling: CPU seconds a reading of the clock adds to what it times
    double serial_acc;    ///< profiling: the window's one-thread CPU seconds so far
    gf_par_profile prof;
} gf_sweep;

// Profiling: the CPU time since t0 of this thread, less what the readings
// cost (tens of thousands of chunks a window, most of them with little to do:
// uncorrected, the readings would pass for parallel work).
static inline double gf_sweep_since(const gf_sweep *q, double t0)
{
    return fmax(gf_clock_thread_cpu() - t0 - q->clock_cost, 0.0);
}

// Profiling: the start of a stretch of one-thread work, and its end (added
// to the window's one-thread part).
static inline double gf_sweep_tic(const gf_sweep *q) { return q->profiling ? gf_clock_thread_cpu() : 0.0; }
static inline void gf_sweep_toc(gf_sweep *q, double t0)
{
    if (q->profiling) q->serial_acc += fmax(gf_clock_thread_cpu() - t0 - q->clock_cost, 0.0);
}

static void gf_sweep_chunk_free(gf_sweep_chunk *c)
{
    GF_DELETE(c->mv, c->mv_cap);
    gf_free(c->mirs, sizeof(double[3]) * c->mirs_cap);
    GF_DELETE(c->list, c->list_cap);
    GF_DELETE(c->todo, c->todo_cap);
    *c = (gf_sweep_chunk){0};
}

static void gf_sweep_threads_free(gf_sweep *q)
{
    for (int t = 0; t < q->threads; t++) GF_DELETE(q->cand[t], q->cand_cap[t]);
    GF_DELETE(q->cand, q->threads);
    GF_DELETE(q->cand_cap, q->threads);
    q->cand = NULL;
    q->cand_cap = NULL;
    q->threads = 0;
}

void gf_sweep_free(gf_sim *sim)
{
    gf_sweep *q = sim->sweep;
    if (!q) return;
    gf_sweep_threads_free(q);
    for (size_t k = 0; k < q->spot_chunk_cap; k++) gf_sweep_chunk_free(&q->spot[k]);
    GF_DELETE(q->spot, q->spot_chunk_cap);
    for (size_t k = 0; k < q->ncell_chunk; k++) gf_sweep_chunk_free(&q->cell[k]);
    GF_DELETE(q->cell, q->ncell_chunk);
    for (size_t k = 0; q->group && k < q->ngroup; k++) {
        gf_sweep_group *gr = &q->group[k];
        GF_DELETE(gr->exit, gr->exit_cap);
        GF_DELETE(gr->mover, gr->mover_cap);
        GF_DELETE(gr->skin, gr->skin_cap);
    }
    GF_DELETE(q->group, q->ngroup);
    GF_DELETE(q->gsecs, q->ngroup);
    GF_DELETE(q->gat, q->ngroup + 1);
    GF_DELETE(q->xgroup, q->ngroup);
    GF_DELETE(q->gcur, q->ngroup);
    GF_DELETE(q->gstart, q->ngroup + 1);
    GF_DELETE(q->cstamp, q->ncell_chunk);
    GF_DELETE(q->touched, q->ncell_chunk);
    GF_DELETE(q->tsecs, q->ncell_chunk);
    GF_DELETE(q->gmv, q->gmv_cap);
    GF_DELETE(q->mv, q->mv_cap);
    gf_free(q->mirs, sizeof(double[3]) * q->mirs_cap);
    gf_celllist_free(&q->bycell);
    gf_free(q->disp, sizeof(double[3]) * q->cap);
    GF_DELETE(q->active, q->cap);
    GF_DELETE(q->tlast, q->cap);
    GF_DELETE(q->crossing, q->cap);
    GF_DELETE(q->gain, q->cap);
    GF_DELETE(q->cross, q->cross_cap);
    gf_free(q->pairs, sizeof *q->pairs * q->pairs_cap);
    GF_DELETE(q->aff, q->aff_cap);
    GF_DELETE(q->aff_at, q->aff_at_cap);
    GF_DELETE(q->adds, q->adds_cap);
    GF_DELETE(q->find_st, q->find_cap);
    GF_DELETE(q->segn, q->segn_cap);
    GF_DELETE(q->fsecs, q->fsecs_cap);
    GF_DELETE(q->msecs, q->msecs_cap);
    GF_DELETE(q->dead, q->dead_cap);
    GF_DELETE(q->csecs, (q->ncol + GF_SWEEP_COL_CHUNK - 1) / GF_SWEEP_COL_CHUNK);
    GF_DELETE(q->coltop, q->ncol);
    GF_DELETE(q->secs, q->secs_cap);
    gf_work_free(&q->w);
    gf_free(q, sizeof *q);
    sim->sweep = NULL;
}

// An array of elements of `size` bytes, *cap of them, grown to hold `need`:
// the (possibly moved) array, or NULL when out of memory (the old one kept).
static void *gf_sweep_grow(void *v, size_t *cap, size_t need, size_t size)
{
    if (need == 0) need = 1; // (never NULL on success)
    if (need <= *cap) return v;
    size_t cap2 = need + need / 2 + 16;
    void *p = gf_realloc(v, *cap * size, cap2 * size);
    if (p) *cap = cap2;
    return p;
}

static gf_status gf_sweep_make(gf_sim *sim)
{
    const int threads = gf_par_threads(&sim->d);
    gf_sweep *q = sim->sweep;
    if (!q) {
        q = gf_alloc(sizeof *q);
        if (!q) return gf_error_set(GF_ERR_NOMEM, "out of memory for the sweep engine");
        *q = (gf_sweep){0};
        sim->sweep = q;
        const gf_grid *g = &sim->grid;
        q->ncol = (size_t)g->nx * (size_t)g->ny;
        q->coltop = GF_NEW(double, q->ncol);
        q->csecs = GF_NEW(double, (q->ncol + GF_SWEEP_COL_CHUNK - 1) / GF_SWEEP_COL_CHUNK);
        q->ncell_chunk = (g->ncell + GF_SWEEP_CELL_CHUNK - 1) / GF_SWEEP_CELL_CHUNK;
        q->cell = GF_NEW(gf_sweep_chunk, q->ncell_chunk);
        q->ngroup = (q->ncell_chunk + GF_SWEEP_GROUP - 1) / GF_SWEEP_GROUP;
        q->group = GF_NEW(gf_sweep_group, q->ngroup);
        q->gsecs = GF_NEW(double, q->ngroup);
        q->gat = GF_NEW(size_t, q->ngroup + 1);
        q->xgroup = GF_NEW(uint32_t, q->ngroup);
        q->gcur = GF_NEW(size_t, q->ngroup);
        q->gstart = GF_NEW(size_t, q->ngroup + 1);
        q->cstamp = GF_NEW(uint32_t, q->ncell_chunk);
        q->touched = GF_NEW(uint32_t, q->ncell_chunk);
        q->tsecs = GF_NEW(double, q->ncell_chunk);
        gf_status st = q->coltop && q->csecs && q->cell && q->group && q->gsecs && q->gat && q->gcur && q->xgroup &&
                               q->gstart && q->cstamp && q->touched && q->tsecs
                           ? GF_OK
                           : gf_error_set(GF_ERR_NOMEM, "out of memory for the sweep engine");
        if (q->cell)
            for (size_t k = 0; k < q->ncell_chunk; k++) q->cell[k] = (gf_sweep_chunk){0};
        if (q->cstamp) memset(q->cstamp, 0, q->ncell_chunk * sizeof *q->cstamp);
        if (q->group)
            for (size_t k = 0; k < q->ngroup; k++) q->group[k] = (gf_sweep_group){0};
        if (st == GF_OK) st = gf_work_init(sim, &q->w);
        if (st != GF_OK) {
            gf_sweep_free(sim);
            return st;
        }
        q->w.timed = true;
        q->w.st = &sim->st;
    }
    if (sim->cap > q->cap) { // the per-particle arrays, for every index the sim may use
        gf_free(q->disp, sizeof(double[3]) * q->cap);
        GF_DELETE(q->active, q->cap);
        GF_DELETE(q->tlast, q->cap);
        GF_DELETE(q->crossing, q->cap);
        GF_DELETE(q->gain, q->cap);
        q->cap = sim->cap;
        q->disp = gf_alloc(sizeof(double[3]) * q->cap);
        q->active = GF_NEW(uint32_t, q->cap);
        q->tlast = GF_NEW(double, q->cap);
        q->crossing = GF_NEW(uint8_t, q->cap);
        q->gain = GF_NEW(uint32_t, q->cap);
        if (!q->disp || !q->active || !q->tlast || !q->crossing || !q->gain) {
            gf_sweep_free(sim);
            return gf_error_set(GF_ERR_NOMEM, "out of memory for the sweep engine");
        }
        memset(q->active, 0, q->cap * sizeof *q->active);
        memset(q->crossing, 0, q->cap);
        memset(q->gain, 0, q->cap * sizeof *q->gain);
    }
    if (q->threads == threads) return GF_OK;
    gf_sweep_threads_free(q);
    q->cand = GF_NEW(uint32_t *, threads);
    q->cand_cap = GF_NEW(size_t, threads);
    if (!q->cand || !q->cand_cap) {
        gf_sweep_free(sim);
        return gf_error_set(GF_ERR_NOMEM, "out of memory for the sweep engine");
    }
    q->threads = threads;
    return GF_OK;
}

// The stream of one move of spot k: (seed, its birth number, its move time).
static void gf_sweep_seed(const gf_sim *sim, size_t k, gf_rng *r)
{
    uint64_t bits;
    memcpy(&bits, &sim->snext[k], sizeof bits);
    gf_rng_seed(r, sim->d.seed ^ 0x7377656570ull /* "sweep" */, (sim->sbirth[k] * 0x9e3779b97f4a7c15ull) ^ bits);
}

// Walk chunk c: its spots' moves up to t_end, recorded; positions read from
// the window's start (nothing here writes a particle).
static void gf_sweep_walk(gf_sim *sim, gf_sweep *q, size_t c, double t_end)
{
    gf_sweep_chunk *ch = &q->spot[c];
    double t0 = q->profiling ? gf_clock_thread_cpu() : 0.0;
    ch->nmv = ch->nmirs = 0;
    ch->st = (gf_sim_stats){0};
    ch->status = GF_OK;
    const gf_engine_defs *ed = &sim->d;
    gf_rng rng;
    gf_work w = {.rng = &rng, .coltop = q->coltop, .st = &ch->st};
    const double f = sim->ball_frac;
    const size_t end = (c + 1) * GF_SWEEP_SPOT_CHUNK < sim->ns ? (c + 1) * GF_SWEEP_SPOT_CHUNK : sim->ns;
    for (size_t k = c * GF_SWEEP_SPOT_CHUNK; k < end; k++) {
        double s[3] = {sim->sx[k], sim->sy[k], sim->sz[k]};
        while (sim->snext[k] <= t_end) {
            gf_sweep_seed(sim, k, &rng);
            double n[3];
            if (!gf_spot_walk(sim, &w, s, n)) {
                q->dead[k] = 1;
                break;
            }
            double v[3] = {n[0] - s[0], n[1] - s[1], n[2] - s[2]};
            gf_sweep_move m = {.t = sim->snext[k]};
            for (int a = 0; a < 3; a++) {
                m.c[a] = s[a] + f * v[a];
                m.u[a] = -v[a] * sim->inv_w;
            }
            ch->st.spot_moves++;
            size_t p_ball = gf_ball_count(sim, m.c, sim->rs);
            if (p_ball == 0 && n[2] > 0.0) { // SPEC 1.3 removal: no particle in reach
                q->dead[k] = 1;
                break;
            }
            if (p_ball > 0) {
                // Sec. 3 influence weighting, as gf_spot_apply (on the window's start).
                if (ed->weighting && m.c[2] >= ed->weighting_zmin) {
                    double wf = ed->weighting_bulk_count / fmax((double)p_ball, ed->weighting_min_count);
                    for (int a = 0; a < 3; a++) m.u[a] *= wf;
                }
                if (ed->walls == GF_WALLS_REFLECT) {
                    double mir[GF_WALL_HITS][3];
                    m.nmir = sim->box.ops->mirrors(&sim->box, m.c, sim->rs, mir);
                    double(*ms)[3] = gf_sweep_grow(ch->mirs, &ch->mirs_cap, ch->nmirs + (size_t)m.nmir, sizeof *ch->mirs);
                    if (!ms) {
                        ch->status = GF_ERR_NOMEM;
                        return;
                    }
                    ch->mirs = ms;
                    m.mir = (uint32_t)ch->nmirs;
                    memcpy(ch->mirs + ch->nmirs, mir, sizeof(double[3]) * (size_t)m.nmir);
                    ch->nmirs += (size_t)m.nmir;
                }
                gf_sweep_move *mv = gf_sweep_grow(ch->mv, &ch->mv_cap, ch->nmv + 1, sizeof *ch->mv);
                if (!mv) {
                    ch->status = GF_ERR_NOMEM;
                    return;
                }
                ch->mv = mv;
                ch->mv[ch->nmv++] = m;
            }
            s[0] = n[0];
            s[1] = n[1];
            s[2] = n[2];
            sim->snext[k] += gf_rng_exp(&rng, ed->move_rate);
        }
        sim->sx[k] = s[0];
        sim->sy[k] = s[1];
        sim->sz[k] = s[2];
    }
    if (q->profiling) ch->seconds = gf_sweep_since(q, t0);
}

// The moves whose centre lies in a grid cell within reach (r_e) of cell
// (cx, cy, cz), in cell then record order, into cand; returns their number.
// Those farther than r_e + h from the cell's centre are left out (no point
// of the cell is within r_e of them), except around an edge cell, which
// also holds the points clamped into it from beyond the grid.
static size_t gf_sweep_near(const gf_sim *sim, const gf_sweep *q, int cx, int cy, int cz, uint32_t *cand)
{
    const gf_grid *g = &sim->grid;
    const int R = (int)ceil(sim->re * g->inv_h);
    int lo[3] = {cx - R, cy - R, cz - R}, hi[3] = {cx + R, cy + R, cz + R};
    const int n[3] = {g->nx, g->ny, g->nz};
    for (int a = 0; a < 3; a++) {
        if (lo[a] < 0) lo[a] = 0;
        if (hi[a] > n[a] - 1) hi[a] = n[a] - 1;
    }
    const bool edge = cx == 0 || cy == 0 || cz == 0 || cx == g->nx - 1 || cy == g->ny - 1 || cz == g->nz - 1;
    const double ctr[3] = {g->ox + (cx + 0.5) * g->h, g->oy + (cy + 0.5) * g->h, g->oz + (cz + 0.5) * g->h};
    const double far2 = (sim->re + g->h) * (sim->re + g->h);
    size_t m = 0;
    const gf_celllist *cl = &q->bycell;
    for (int z = lo[2]; z <= hi[2]; z++)
        for (int y = lo[1]; y <= hi[1]; y++) {
            size_t row = ((size_t)z * (size_t)g->ny + (size_t)y) * (size_t)g->nx;
            for (size_t e = cl->start[row + (size_t)lo[0]]; e < cl->start[row + (size_t)hi[0] + 1]; e++) {
                const double *c = q->mv[cl->idx[e]].c;
                double dx = c[0] - ctr[0], dy = c[1] - ctr[1], dz = c[2] - ctr[2];
                cand[m] = cl->idx[e];
                m += edge || dx * dx + dy * dy + dz * dz < far2;
            }
        }
    return m;
}

// Whether particle i, just moved, needs the one-thread bookkeeping: below
// the exit plane, in another cell, or past its skin (a read-only test, so
// the chunks make it side by side and the bookkeeping sees only these).
static inline bool gf_sweep_needs_book(const gf_sim *sim, uint32_t i)
{
    const gf_pos *p = &sim->p[i];
    if (p->z < sim->box.z_exit || gf_grid_cell(&sim->grid, p->x, p->y, p->z) != sim->grid.cell_of[i]) return true;
    if (!sim->use_nlist) return false;
    const gf_ref *a = &sim->p0[i];
    double dx = p->x - a->x, dy = p->y - a->y, dz = p->z - a->z, lim = a->h - GF_SKIN_SLACK;
    return dx * dx + dy * dy + dz * dz > lim * lim;
}

// Gather chunk c: each particle of its cells moves by the sum of the u of
// the moves within r_s of it (window-start positions), in place (it reads
// no other particle); marks the active set and lists what moved.
static void gf_sweep_displace(gf_sim *sim, gf_sweep *q, int t, size_t c)
{
    gf_sweep_chunk *ch = &q->cell[c];
    double t0 = q->profiling ? gf_clock_thread_cpu() : 0.0;
    const gf_grid *g = &sim->grid;
    gf_pos *restrict p = sim->p;
    ch->status = GF_OK;
    ch->ntodo = 0;
    const size_t end = (c + 1) * GF_SWEEP_CELL_CHUNK < g->ncell ? (c + 1) * GF_SWEEP_CELL_CHUNK : g->ncell;
    const double rs2 = sim->rs2, re2 = sim->re2;
    double dz = 0.0;
    for (size_t cell = c * GF_SWEEP_CELL_CHUNK; cell < end; cell++) {
        const uint32_t cnt = g->count[cell];
        if (cnt == 0) continue;
        const uint32_t *slot = g->slot + cell * GF_CELL_CAP;
        int cc[3];
        gf_grid_cell_coords(g, cell, cc);
        size_t nc = gf_sweep_near(sim, q, cc[0], cc[1], cc[2], q->cand[t]);
        const uint32_t *cand = q->cand[t];
        uint32_t *todo = gf_sweep_grow(ch->todo, &ch->todo_cap, ch->ntodo + cnt, sizeof *ch->todo);
        if (!todo) {
            ch->status = GF_ERR_NOMEM;
            return;
        }
        ch->todo = todo;
        for (uint32_t k = 0; k < cnt; k++) {
            const uint32_t i = slot[k];
            double ux = 0.0, uy = 0.0, uz = 0.0, tl = -INFINITY;
            uint8_t act = 0;
            for (size_t e = 0; e < nc; e++) {
                const gf_sweep_move *m = &q->mv[cand[e]];
                double dx = p[i].x - m->c[0], dy = p[i].y - m->c[1], dzz = p[i].z - m->c[2];
                double d2 = dx * dx + dy * dy + dzz * dzz;
                if (!(d2 < re2)) continue;
                act = 1;
                tl = fmax(tl, m->t);
                if (!(d2 < rs2)) continue;
                // S(x) = 1 + the mirrored balls that also reach it (Sec. 4).
                double sx = 1.0;
                for (int k2 = 0; k2 < m->nmir; k2++) {
                    const double *mc = q->mirs[m->mir + (uint32_t)k2];
                    double ex = p[i].x - mc[0], ey = p[i].y - mc[1], ez = p[i].z - mc[2];
                    sx += ex * ex + ey * ey + ez * ez < rs2;
                }
                ux += sx * m->u[0];
                uy += sx * m->u[1];
                uz += sx * m->u[2];
            }
            q->active[i] = act ? q->stamp : 0;
            q->tlast[i] = tl;
            if (ux == 0.0 && uy == 0.0 && uz == 0.0) continue;
            p[i].x += ux;
            p[i].y += uy;
            p[i].z += uz;
            dz += uz;
            if (gf_sweep_needs_book(sim, i)) ch->todo[ch->ntodo++] = i;
        }
    }
    ch->st.spot_dz += dz;
    if (q->profiling) ch->seconds = gf_sweep_since(q, t0);
}

// Sweep chunk c: the relax() displacement of each active particle of its
// cells from the positions at the sweep's start (written to disp, applied
// after every chunk has read).
static void gf_sweep_relax(gf_sim *sim, gf_sweep *q, size_t c)
{
    gf_sweep_chunk *ch = &q->cell[c];
    double t0 = q->profiling ? gf_clock_thread_cpu() : 0.0;
    const gf_grid *g = &sim->grid;
    const gf_pos *restrict p = sim->p;
    const uint32_t *restrict act = q->active;
    const uint32_t stamp = q->stamp;
    ch->status = GF_OK;
    const double alpha = sim->alpha, half = 0.5 * sim->alpha;
    ch->nlist = 0;
    const size_t end = (c + 1) * GF_SWEEP_CELL_CHUNK < g->ncell ? (c + 1) * GF_SWEEP_CELL_CHUNK : g->ncell;
    for (size_t cell = c * GF_SWEEP_CELL_CHUNK; cell < end; cell++) {
        const uint32_t cnt = g->count[cell];
        if (cnt == 0) continue;
        const uint32_t *slot = g->slot + cell * GF_CELL_CAP;
        uint32_t *list = gf_sweep_grow(ch->list, &ch->list_cap, ch->nlist + cnt, sizeof *ch->list);
        if (!list) {
            ch->status = GF_ERR_NOMEM;
            return;
        }
        ch->list = list;
        for (uint32_t k = 0; k < cnt; k++) {
            const uint32_t i = slot[k];
            if (act[i] != stamp) continue;
            const uint32_t *row = sim->nl + ((size_t)i << sim->nl_shift);
            const double xi = p[i].x, yi = p[i].y, zi = p[i].z, ri = p[i].r;
            double ax = 0.0, ay = 0.0, az = 0.0;
            for (uint32_t e = 1; e <= row[0]; e++) {
                const uint32_t j = row[e];
                double dx = xi - p[j].x, dy = yi - p[j].y, dz = zi - p[j].z;
                double s = ri + p[j].r, r2 = dx * dx + dy * dy + dz * dz;
                if (!(r2 < s * s) || !(r2 > 0.0)) continue;
                double r = sqrt(r2), f = (act[j] == stamp ? half : alpha) * (s - r) / r;
                ax += f * dx;
                ay += f * dy;
                az += f * dz;
            }
            gf_container_push(&sim->box, xi, yi, zi, ri, alpha, &ax, &ay, &az);
            if (ax == 0.0 && ay == 0.0 && az == 0.0) continue;
            q->disp[i][0] = ax;
            q->disp[i][1] = ay;
            q->disp[i][2] = az;
            ch->list[ch->nlist++] = i;
        }
    }
    if (q->profiling) ch->seconds = gf_sweep_since(q, t0);
}

// Sweep chunk c's displacements applied (after every chunk has read).
static void gf_sweep_move_chunk(gf_sim *sim, gf_sweep *q, size_t c)
{
    gf_sweep_chunk *ch = &q->cell[c];
    double t0 = q->profiling ? gf_clock_thread_cpu() : 0.0;
    double dz = 0.0;
    ch->ntodo = 0; // (its status is the sweep's, set by gf_sweep_relax)
    uint32_t *todo = gf_sweep_grow(ch->todo, &ch->todo_cap, ch->nlist, sizeof *ch->todo);
    if (!todo) {
        ch->status = GF_ERR_NOMEM;
        return;
    }
    ch->todo = todo;
    for (size_t k = 0; k < ch->nlist; k++) {
        uint32_t i = ch->list[k];
        sim->p[i].x += q->disp[i][0];
        sim->p[i].y += q->disp[i][1];
        sim->p[i].z += q->disp[i][2];
        dz += q->disp[i][2];
        if (gf_sweep_needs_book(sim, i)) todo[ch->ntodo++] = i;
    }
    ch->st.relax_dz += dz;
    if (q->profiling) ch->seconds = gf_sweep_since(q, t0);
}

// Grows a batch array `arr` (capacity *cap) to hold `need`, through the
// function's `void *grown`; false when out of memory (the array kept).
#define GF_SWEEP_ROOM(arr, cap, need) \
    ((grown = gf_sweep_grow((arr), (cap), (need), sizeof *(arr))) != NULL ? ((arr) = grown, true) : false)

// Row aff[a] rewritten: its crossers dropped, the crossers that list it now
// (adds[aff_at[a], aff_at[a + 1])) merged in, in index order.
static gf_status gf_sweep_row_merge(gf_sim *sim, gf_sweep *q, size_t a, size_t slots)
{
    uint32_t *row = sim->nl + ((size_t)q->aff[a] << sim->nl_shift);
    uint32_t *add = q->adds + q->aff_at[a];
    const size_t nadd = q->aff_at[a + 1] - q->aff_at[a];
    for (size_t x = 1; x < nadd; x++) // (a handful: insertion sort)
        for (size_t y = x; y > 0 && add[y - 1] > add[y]; y--) {
            uint32_t t = add[y];
            add[y] = add[y - 1];
            add[y - 1] = t;
        }
    uint32_t keep[GF_NL_CAP_MAX];
    size_t nk = 0;
    for (uint32_t e = 1; e <= row[0]; e++)
        if (!q->crossing[row[e]]) keep[nk++] = row[e];
    if (nk + nadd > slots - 1) return GF_ERR_STATE;
    size_t x = 0, y = 0, n = 0;
    while (x < nk || y < nadd) row[1 + n++] = y == nadd || (x < nk && keep[x] < add[y]) ? keep[x++] : add[y++];
    row[0] = (uint32_t)n;
    return GF_OK;
}

static int gf_sweep_cmp_desc(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x < y) - (x > y);
}

// Profiling: one parallel block's chunk times (ch[k].seconds, or secs[k]), and
// the serial time since the last.
static void gf_sweep_record(gf_sweep *q, const gf_sweep_chunk *ch, const double *secs, size_t n, double serial,
                            int part)
{
    gf_par_profile *f = &q->prof;
    if (n > q->secs_cap) {
        GF_DELETE(q->secs, q->secs_cap);
        q->secs = GF_NEW(double, n);
        q->secs_cap = q->secs ? n : 0;
        if (!q->secs) return;
    }
    double work = 0.0;
    for (size_t k = 0; k < n; k++) {
        q->secs[k] = ch ? ch[k].seconds : secs[k];
        work += q->secs[k];
    }
    qsort(q->secs, n, sizeof(double), gf_sweep_cmp_desc); // LPT: heaviest first
    f->colour_phases++;
    f->barriers++;
    f->blocks_run += n;
    f->work_seconds += work + serial;
    if (part >= 0) f->part_seconds[part] += work;
    f->serial_seconds += serial;
    f->span_seconds += (n ? q->secs[0] : 0.0) + serial;
    for (int i = 0; i < GF_PAR_NPROJ; i++)
        f->makespan_seconds[i] += gf_par_makespan(q->secs, n, gf_sweep_proj_threads[i]) + serial;
}

// Profiling a bookkeeping: the list refreshes' two blocks, timed by groups
// (the rest of it is in the window's one-thread part).
static void gf_sweep_record_book(gf_sweep *q)
{
    if (q->nf) gf_sweep_record(q, NULL, q->fsecs, q->nf, 0.0, 3);
    if (q->nm) gf_sweep_record(q, NULL, q->msecs, q->nm, 0.0, 3);
}

// The neighbour-list refreshes of the particles the chunks flagged that went
// past their skin, as a batch. A row lists exactly the live j with
// |p0_i - p0_j| below the listing distance (nlist.c): a function of the
// references alone, so the batch leaves the rows one gf_nlist_refresh after
// another would: every crosser's reference is moved, its row found afresh
// (side by side: each writes its own row), and every other row that named a
// crosser or names one now drops the crossers and takes the ones that list
// it (side by side, a row each). What stays on one thread is listing the
// pairs and grouping them by row.
static gf_status gf_sweep_refresh(gf_sim *sim, gf_sweep *q)
{
    const int threads = q->threads;
    void *grown;
    q->nf = q->nm = 0;
    double ts = gf_sweep_tic(q);
    size_t nc = 0;
    for (size_t gi = 0; gi < q->ngroup; gi++) {
        const gf_sweep_group *gr = &q->group[gi];
        for (size_t k = 0; k < gr->nskin; k++) {
            uint32_t i = gr->skin[k]; // (past its skin: the summary tested it, and nothing moved since)
            if (!sim->alive[i] || q->crossing[i]) continue;
            if (!GF_SWEEP_ROOM(q->cross, &q->cross_cap, nc + 1)) {
                for (size_t k2 = 0; k2 < nc; k2++) q->crossing[q->cross[k2]] = 0;
                return gf_error_set(GF_ERR_NOMEM, "out of memory for the list refreshes");
            }
            q->cross[nc++] = i;
            q->crossing[i] = 1;
        }
    }
    if (nc == 0) {
        gf_sweep_toc(q, ts);
        return GF_OK;
    }
    const unsigned shift = sim->nl_shift;
    const size_t slots = (size_t)1 << shift;
    gf_status st = GF_OK;
    // The rows that named a crosser (before), then those that will: listed
    // side by side, each crosser into its own stretch of pairs[] (old rows
    // from 0, new rows from nc * slots), then closed up in crosser order.
    size_t np = 0;
    const size_t ngr = (nc + GF_SWEEP_FIND_GROUP - 1) / GF_SWEEP_FIND_GROUP;
    if (!GF_SWEEP_ROOM(q->pairs, &q->pairs_cap, 2 * nc * slots) || !GF_SWEEP_ROOM(q->find_st, &q->find_cap, nc) ||
        !GF_SWEEP_ROOM(q->segn, &q->segn_cap, 2 * nc) || (q->profiling && !GF_SWEEP_ROOM(q->fsecs, &q->fsecs_cap, 2 * ngr)))
        st = gf_error_set(GF_ERR_NOMEM, "out of memory for the list refreshes");
    if (st == GF_OK) {
        gf_sweep_toc(q, ts);
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (threads > 1 && nc > 2 * GF_SWEEP_FIND_GROUP)
#endif
        for (size_t g = 0; g < ngr; g++) {
            double t0 = q->profiling ? gf_clock_thread_cpu() : 0.0;
            for (size_t k = g * GF_SWEEP_FIND_GROUP; k < nc && k < (g + 1) * GF_SWEEP_FIND_GROUP; k++) {
                const uint32_t i = q->cross[k], *row = sim->nl + ((size_t)i << shift);
                uint32_t (*seg)[2] = q->pairs + k * slots, n = 0;
                for (uint32_t e = 1; e <= row[0]; e++)
                    if (!q->crossing[row[e]]) {
                        seg[n][0] = row[e];
                        seg[n++][1] = UINT32_MAX;
                    }
                q->segn[k] = n;
                sim->p0[i].x = (float)sim->p[i].x;
                sim->p0[i].y = (float)sim->p[i].y;
                sim->p0[i].z = (float)sim->p[i].z;
            }
            if (q->profiling) q->fsecs[ngr + g] = gf_sweep_since(q, t0);
        }
        if (q->profiling) gf_sweep_record(q, NULL, q->fsecs + ngr, ngr, 0.0, 3);
        // The new rows (every crosser's reference moved first: a row reads the others').
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (threads > 1 && nc > 2 * GF_SWEEP_FIND_GROUP)
#endif
        for (size_t g = 0; g < ngr; g++) {
            double t0 = q->profiling ? gf_clock_thread_cpu() : 0.0;
            for (size_t k = g * GF_SWEEP_FIND_GROUP; k < nc && k < (g + 1) * GF_SWEEP_FIND_GROUP; k++) {
                const uint32_t i = q->cross[k];
                q->find_st[k] = gf_nlist_find_row(sim, i);
                const uint32_t *row = sim->nl + ((size_t)i << shift);
                uint32_t (*seg)[2] = q->pairs + (nc + k) * slots, n = 0;
                for (uint32_t e = 1; q->find_st[k] == GF_OK && e <= row[0]; e++)
                    if (!q->crossing[row[e]]) {
                        seg[n][0] = row[e];
                        seg[n++][1] = i;
                    }
                q->segn[nc + k] = n;
            }
            if (q->profiling) q->fsecs[g] = gf_sweep_since(q, t0);
        }
        ts = gf_sweep_tic(q);
        if (q->profiling) q->nf = ngr;
        for (size_t k = 0; k < nc && st == GF_OK; k++)
            if (q->find_st[k] != GF_OK) st = gf_nlist_find_row(sim, q->cross[k]); // (again, for its message)
        for (size_t k = 0; st == GF_OK && k < 2 * nc; k++) { // closed up (moving left: memmove)
            if (q->segn[k]) memmove(q->pairs + np, q->pairs + k * slots, sizeof *q->pairs * q->segn[k]);
            np += q->segn[k];
        }
    }
    // Grouped by row: the rows in the order first seen, each's crossers in pair order.
    size_t naff = 0;
    for (size_t e = 0; st == GF_OK && e < np; e++) {
        uint32_t j = q->pairs[e][0];
        if (q->gain[j] == 0) {
            if (!GF_SWEEP_ROOM(q->aff, &q->aff_cap, naff + 1)) {
                st = gf_error_set(GF_ERR_NOMEM, "out of memory for the list refreshes");
                break;
            }
            q->aff[naff++] = j;
            q->gain[j] = (uint32_t)naff;
        }
    }
    // Each row's crossers counted, placed (a counting sort by row), then
    // each row rewritten: its crossers dropped, those that list it merged in.
    if (st == GF_OK && (!GF_SWEEP_ROOM(q->aff_at, &q->aff_at_cap, naff + 1) ||
                        !GF_SWEEP_ROOM(q->adds, &q->adds_cap, np) ||
                        !GF_SWEEP_ROOM(q->find_st, &q->find_cap, naff) ||
                        (q->profiling && !GF_SWEEP_ROOM(q->msecs, &q->msecs_cap, naff))))
        st = gf_error_set(GF_ERR_NOMEM, "out of memory for the list refreshes");
    if (st == GF_OK) {
        memset(q->aff_at, 0, (naff + 1) * sizeof *q->aff_at);
        for (size_t e = 0; e < np; e++)
            if (q->pairs[e][1] != UINT32_MAX) q->aff_at[q->gain[q->pairs[e][0]]]++;
        for (size_t a = 0; a < naff; a++) q->aff_at[a + 1] += q->aff_at[a];
        for (size_t e = 0; e < np; e++)
            if (q->pairs[e][1] != UINT32_MAX) q->adds[q->aff_at[q->gain[q->pairs[e][0]] - 1]++] = q->pairs[e][1];
        for (size_t a = naff; a > 0; a--) q->aff_at[a] = q->aff_at[a - 1];
        q->aff_at[0] = 0;
        gf_sweep_toc(q, ts);
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (threads > 1 && naff > 2 * GF_SWEEP_MERGE_GROUP)
#endif
        for (size_t g = 0; g < (naff + GF_SWEEP_MERGE_GROUP - 1) / GF_SWEEP_MERGE_GROUP; g++) {
            double t0 = q->profiling ? gf_clock_thread_cpu() : 0.0;
            for (size_t a = g * GF_SWEEP_MERGE_GROUP; a < naff && a < (g + 1) * GF_SWEEP_MERGE_GROUP; a++)
                q->find_st[a] = gf_sweep_row_merge(sim, q, a, slots);
            if (q->profiling) q->msecs[g] = gf_sweep_since(q, t0);
        }
        ts = gf_sweep_tic(q);
        if (q->profiling) q->nm = (naff + GF_SWEEP_MERGE_GROUP - 1) / GF_SWEEP_MERGE_GROUP;
        for (size_t a = 0; a < naff && st == GF_OK; a++)
            if (q->find_st[a] != GF_OK)
                st = gf_error_set(GF_ERR_STATE, "particle %lld has more than %zu neighbours within contact + skin: "
                                  "the packing overlaps far too much", (long long)sim->id[q->aff[a]], slots - 1);
    }
    for (size_t a = 0; a < naff; a++) q->gain[q->aff[a]] = 0;
    for (size_t k = 0; k < nc; k++) q->crossing[q->cross[k]] = 0;
    gf_sweep_toc(q, ts);
    return st;
}

// Group d's insertions: the movers of the groups that reach it, in group
// then list order, into its cells.
static void gf_sweep_arrive(gf_sim *sim, gf_sweep *q, size_t d, ptrdiff_t lo, ptrdiff_t hi)
{
    gf_sweep_group *gd = &q->group[d];
    double t0 = q->profiling ? gf_clock_thread_cpu() : 0.0;
    const uint32_t c0 = (uint32_t)(d * GF_SWEEP_GROUP_CELLS), c1 = (uint32_t)((d + 1) * GF_SWEEP_GROUP_CELLS);
    gd->status = GF_OK;
    for (ptrdiff_t s = (ptrdiff_t)d - hi; s <= (ptrdiff_t)d - lo; s++) {
        if (s < 0 || s >= (ptrdiff_t)q->ngroup) continue;
        const gf_sweep_group *gs = &q->group[s];
        for (size_t k = 0; k < gs->nmover; k++) {
            const gf_sweep_mover m = gs->mover[k];
            if (m.cell < c0 || m.cell >= c1) continue;
            if (sim->grid.count[m.cell] >= GF_CELL_CAP) {
                gd->status = GF_ERR_STATE;
                gd->full_cell = m.cell;
#ifdef _OPENMP
#pragma omp atomic write
#endif
                q->full = 1;
                continue;
            }
            (void)gf_grid_insert(&sim->grid, m.i, m.cell);
        }
    }
    if (q->profiling) q->gsecs[d] = gf_sweep_since(q, t0);
}

// The bookkeeping of what the chunks flagged, sorted by the groups'
// summaries: exits on one thread in chunk order (timed by the last move that
// reached the particle; a handful a window); then the cell moves side by
// side, every group taking its movers out of its own cells, then every group
// putting into its cells the movers bound for them; then the lists of those
// past their skin.
static gf_status gf_sweep_book(gf_sim *sim, gf_sweep *q)
{
    gf_grid *g = &sim->grid;
    gf_work *w = &q->w;
    double ts = gf_sweep_tic(q);
    const ptrdiff_t lo = q->reach_lo, hi = q->reach_hi;
    for (size_t x = 0; x < q->nxgroup; x++) {
        const gf_sweep_group *gr = &q->group[q->xgroup[x]];
        for (size_t k = 0; k < gr->nexit; k++) {
            uint32_t i = gr->exit[k];
            w->t = q->tlast[i];
            if (gf_sim_exit_check(sim, w, i)) continue;
            if (w->exit_failed) return gf_error_set(GF_ERR_NOMEM, "out of memory for the exits");
            gf_status st = gf_grid_update(g, i, sim->p[i].x, sim->p[i].y, sim->p[i].z);
            if (st != GF_OK) return st;
        }
    }
    gf_sweep_toc(q, ts);
    const size_t n = q->ngroup;
    const int threads = q->threads;
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 4) num_threads(threads) if (threads > 1 && n > 1)
#endif
    for (size_t gi = 0; gi < n; gi++) {
        double t0 = q->profiling ? gf_clock_thread_cpu() : 0.0;
        const gf_sweep_group *gr = &q->group[gi];
        for (size_t k = 0; k < gr->nmover; k++) gf_grid_remove(g, gr->mover[k].i);
        if (q->profiling) q->gsecs[gi] = gf_sweep_since(q, t0);
    }
    if (q->profiling) gf_sweep_record(q, NULL, q->gsecs, n, 0.0, 3);
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 4) num_threads(threads) if (threads > 1 && n > 1)
#endif
    for (size_t d = 0; d < n; d++) gf_sweep_arrive(sim, q, d, lo, hi);
    (void)threads;
    if (q->profiling) gf_sweep_record(q, NULL, q->gsecs, n, 0.0, 3);
    if (q->full) { // (rare: the first full group found again on one thread, for its message)
        for (size_t d = 0; d < n; d++)
            if (q->group[d].status != GF_OK)
                return gf_error_set(GF_ERR_STATE,
                                    "more than %d particle centres in one %.2g d cell (cell %u): the packing "
                                    "overlaps far too much",
                                    GF_CELL_CAP, g->h, q->group[d].full_cell);
    }
    return sim->use_nlist ? gf_sweep_refresh(sim, q) : GF_OK;
}

static gf_status gf_sweep_status(const gf_sweep_chunk *ch, size_t n)
{
    for (size_t k = 0; k < n; k++)
        if (ch[k].status != GF_OK) return gf_error_set(ch[k].status, "out of memory in the sweep engine");
    return GF_OK;
}

// Group g's moves (dealt to it in record order) counted and placed by cell:
// its cells' start[] and their stretch of idx[], as gf_celllist_sort.
static void gf_sweep_bin_group(gf_sweep *q, size_t g)
{
    double t0 = q->profiling ? gf_clock_thread_cpu() : 0.0;
    gf_celllist *cl = &q->bycell;
    const size_t c0 = g * GF_SWEEP_GROUP_CELLS;
    const size_t c1 = c0 + GF_SWEEP_GROUP_CELLS < cl->ncell ? c0 + GF_SWEEP_GROUP_CELLS : cl->ncell;
    size_t *start = cl->start;
    for (size_t c = c0; c < c1; c++) start[c] = 0;
    for (size_t k = q->gat[g]; k < q->gat[g + 1]; k++) start[cl->cell[q->gmv[k]]]++;
    size_t at = q->gat[g], cur[GF_SWEEP_GROUP_CELLS];
    for (size_t c = c0; c < c1; c++) {
        size_t m = start[c];
        start[c] = cur[c - c0] = at;
        at += m;
    }
    for (size_t k = q->gat[g]; k < q->gat[g + 1]; k++) {
        uint32_t e = q->gmv[k];
        cl->idx[cur[cl->cell[e] - c0]++] = e;
    }
    if (q->profiling) q->gsecs[g] = gf_sweep_since(q, t0);
}

// The window's moves binned by the cell of their centre (q->bycell, as
// gf_celllist_sort leaves it: by cell, then record order), the counting over
// 273,000 cells of the pebble bed side by side: one thread deals the moves to
// the groups of their cells (a pass over the moves and one over the groups),
// then each group counts and places its own.
static gf_status gf_sweep_bin(gf_sweep *q)
{
    gf_celllist *cl = &q->bycell;
    const size_t n = q->nmv, ng = q->ngroup;
    uint32_t *gmv = gf_sweep_grow(q->gmv, &q->gmv_cap, n, sizeof *gmv);
    if (!gmv) return gf_error_set(GF_ERR_NOMEM, "out of memory for %zu moves", n);
    q->gmv = gmv;
    double ts = gf_sweep_tic(q);
    memset(q->gat, 0, (ng + 1) * sizeof *q->gat);
    for (size_t e = 0; e < n; e++) q->gat[cl->cell[e] / GF_SWEEP_GROUP_CELLS + 1]++;
    for (size_t g = 0; g < ng; g++) {
        q->gat[g + 1] += q->gat[g];
        q->gcur[g] = q->gat[g];
    }
    for (size_t e = 0; e < n; e++) gmv[q->gcur[cl->cell[e] / GF_SWEEP_GROUP_CELLS]++] = (uint32_t)e;
    cl->start[cl->ncell] = n;
    cl->nidx = n;
    gf_sweep_toc(q, ts);
    const int threads = q->threads;
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 4) num_threads(threads) if (threads > 1 && ng > 1)
#endif
    for (size_t g = 0; g < ng; g++) gf_sweep_bin_group(q, g);
    (void)threads;
    if (q->profiling) gf_sweep_record(q, NULL, q->gsecs, ng, 0.0, 0);
    return GF_OK;
}

// The walk: chunks of spots, then their records joined and binned by cell.
static gf_status gf_sweep_walk_all(gf_sim *sim, gf_sweep *q, double t_end)
{
    const size_t nchunk = (sim->ns + GF_SWEEP_SPOT_CHUNK - 1) / GF_SWEEP_SPOT_CHUNK;
    if (nchunk > q->spot_chunk_cap) {
        size_t cap = nchunk + nchunk / 2 + 16;
        gf_sweep_chunk *v = gf_realloc(q->spot, q->spot_chunk_cap * sizeof *v, cap * sizeof *v);
        if (!v) return gf_error_set(GF_ERR_NOMEM, "out of memory for the sweep engine");
        for (size_t k = q->spot_chunk_cap; k < cap; k++) v[k] = (gf_sweep_chunk){0};
        q->spot = v;
        q->spot_chunk_cap = cap;
    }
    if (sim->ns > q->dead_cap) {
        GF_DELETE(q->dead, q->dead_cap);
        q->dead_cap = sim->ns + sim->ns / 2 + 64;
        q->dead = GF_NEW(uint8_t, q->dead_cap);
        if (!q->dead) {
            q->dead_cap = 0;
            return gf_error_set(GF_ERR_NOMEM, "out of memory for %zu spots", sim->ns);
        }
    }
    if (sim->ns) memset(q->dead, 0, sim->ns); // (no spot yet: dead may still be NULL)
    q->nspot_chunk = nchunk; // (each chunk resets its record as it starts)
    const int threads = q->threads;
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (threads > 1 && nchunk > 1)
#endif
    for (size_t c = 0; c < nchunk; c++) gf_sweep_walk(sim, q, c, t_end);
    (void)threads;
    gf_status st = gf_sweep_status(q->spot, nchunk);
    if (st != GF_OK) return st;
    if (q->profiling) gf_sweep_record(q, q->spot, NULL, nchunk, 0.0, 0);
    // The join: each chunk's moves copied to their place (side by side), then
    // binned by the cell of their centre.
    double ts = gf_sweep_tic(q);
    size_t total = 0, mirs = 0;
    for (size_t c = 0; c < nchunk; c++) {
        q->spot[c].at = total;
        q->spot[c].mir_at = mirs;
        total += q->spot[c].nmv;
        mirs += q->spot[c].nmirs;
        gf_par_add(&sim->st, &q->spot[c].st);
    }
    gf_sweep_move *mv = gf_sweep_grow(q->mv, &q->mv_cap, total, sizeof *q->mv);
    if (mv) q->mv = mv;
    double(*ms)[3] = mv ? gf_sweep_grow(q->mirs, &q->mirs_cap, mirs, sizeof *q->mirs) : NULL;
    if (ms) q->mirs = ms;
    const gf_grid *g = &sim->grid;
    if (!mv || !ms) return gf_error_set(GF_ERR_NOMEM, "out of memory for %zu moves", total);
    if ((st = gf_celllist_keys(&q->bycell, g->ncell, total)) != GF_OK) return st;
    q->nmv = total;
    q->nmirs = mirs;
    gf_sweep_toc(q, ts);
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 4) num_threads(threads) if (threads > 1 && nchunk > 1)
#endif
    for (size_t c = 0; c < nchunk; c++) {
        gf_sweep_chunk *ch = &q->spot[c];
        double t1 = q->profiling ? gf_clock_thread_cpu() : 0.0;
        for (size_t k = 0; k < ch->nmv; k++) {
            gf_sweep_move m = ch->mv[k];
            m.mir += (uint32_t)ch->mir_at;
            q->mv[ch->at + k] = m;
            q->bycell.cell[ch->at + k] = gf_grid_cell(g, m.c[0], m.c[1], m.c[2]);
        }
        if (ch->nmirs) memcpy(q->mirs + ch->mir_at, ch->mirs, sizeof(double[3]) * ch->nmirs);
        if (q->profiling) ch->seconds = gf_sweep_since(q, t1);
    }
    if ((st = gf_sweep_bin(q)) != GF_OK) return st;
    ts = gf_sweep_tic(q);
    for (int t = 0; t < q->threads; t++) {
        uint32_t *cand = gf_sweep_grow(q->cand[t], &q->cand_cap[t], q->nmv + 1, sizeof(uint32_t));
        if (!cand) return gf_error_set(GF_ERR_NOMEM, "out of memory for %zu moves", q->nmv);
        q->cand[t] = cand;
    }
    gf_sweep_toc(q, ts);
    if (q->profiling) gf_sweep_record(q, q->spot, NULL, nchunk, 0.0, 0);
    return GF_OK;
}

// Group g's part of the touch pass (what): 0, its cells that hold a move
// stamp the cell chunks within reach: every chunk with a cell within R =
// ceil(r_e / h) cells of such a cell on each axis (the cells gf_sweep_near
// looks in), so a chunk left unstamped has no move within r_e of its
// particles (the stores race only with stores of the same value: relaxed
// atomics; tests: every chunk of the group, gf_sweep_set_dense); 1, its
// own stamped chunks counted into gstart[g + 1]; 2, listed from gstart[g].
static void gf_sweep_touch_group(const gf_sim *sim, gf_sweep *q, size_t g, int what)
{
    double t0 = q->profiling ? gf_clock_thread_cpu() : 0.0;
    const uint32_t stamp = q->stamp;
    const size_t lo = g * GF_SWEEP_GROUP, hi = lo + GF_SWEEP_GROUP < q->ncell_chunk ? lo + GF_SWEEP_GROUP : q->ncell_chunk;
    if (what == 0 && q->dense) {
        for (size_t c = lo; c < hi; c++) q->cstamp[c] = stamp;
    } else if (what == 0) {
        const gf_grid *gd = &sim->grid;
        const size_t *start = q->bycell.start;
        const int R = (int)ceil(sim->re * gd->inv_h), n[3] = {gd->nx, gd->ny, gd->nz};
        const size_t c0 = g * GF_SWEEP_GROUP_CELLS, c1 = c0 + GF_SWEEP_GROUP_CELLS < gd->ncell ? c0 + GF_SWEEP_GROUP_CELLS : gd->ncell;
        for (size_t cell = c0; cell < c1; cell++) {
            if (start[cell] == start[cell + 1]) continue;
            int cc[3], a[3], b[3];
            gf_grid_cell_coords(gd, cell, cc);
            for (int k = 0; k < 3; k++) {
                a[k] = cc[k] - R > 0 ? cc[k] - R : 0;
                b[k] = cc[k] + R < n[k] - 1 ? cc[k] + R : n[k] - 1;
            }
            for (int z = a[2]; z <= b[2]; z++)
                for (int y = a[1]; y <= b[1]; y++) {
                    const size_t row = ((size_t)z * (size_t)gd->ny + (size_t)y) * (size_t)gd->nx;
                    for (size_t c = (row + (size_t)a[0]) / GF_SWEEP_CELL_CHUNK; c <= (row + (size_t)b[0]) / GF_SWEEP_CELL_CHUNK; c++)
                        __atomic_store_n(&q->cstamp[c], stamp, __ATOMIC_RELAXED);
                }
        }
    } else if (what == 1) {
        size_t m = 0;
        for (size_t c = lo; c < hi; c++) m += q->cstamp[c] == stamp;
        q->gstart[g + 1] = m;
    } else {
        size_t k = q->gstart[g];
        for (size_t c = lo; c < hi; c++)
            if (q->cstamp[c] == stamp) q->touched[k++] = (uint32_t)c;
    }
    if (q->profiling) q->gsecs[g] = gf_sweep_since(q, t0);
}

// One step of the touch pass over every group side by side (a block of the
// gather's part of the profile).
static void gf_sweep_touch_groups(gf_sim *sim, gf_sweep *q, int what)
{
    const size_t ng = q->ngroup;
    const int threads = q->threads;
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 4) num_threads(threads) if (threads > 1 && ng > 1)
#endif
    for (size_t g = 0; g < ng; g++) gf_sweep_touch_group(sim, q, g, what);
    (void)threads;
    if (q->profiling) gf_sweep_record(q, NULL, q->gsecs, ng, 0.0, 1);
}

// The window's touched cell chunks (docs/performance.md "Windows that cost
// what their moves cost"): stamped from the binned moves, counted, then
// listed in chunk order, so each block of the window visits the chunks its
// moves reach and not the whole grid (a window of a few hundred moves in
// the pebble bed reaches a few percent of its 68,000 chunks).
static void gf_sweep_touch(gf_sim *sim, gf_sweep *q)
{
    if (++q->stamp == 0) { // (after 2^32 windows: every old stamp forgotten)
        memset(q->cstamp, 0, q->ncell_chunk * sizeof *q->cstamp);
        memset(q->active, 0, q->cap * sizeof *q->active);
        q->stamp = 1;
    }
    gf_sweep_touch_groups(sim, q, 0);
    gf_sweep_touch_groups(sim, q, 1);
    const double ts = gf_sweep_tic(q);
    q->gstart[0] = 0;
    for (size_t g = 0; g < q->ngroup; g++) q->gstart[g + 1] += q->gstart[g];
    q->ntouched = q->gstart[q->ngroup];
    gf_sweep_toc(q, ts);
    gf_sweep_touch_groups(sim, q, 2);
}

// Profiling a cell block: the times of the touched chunks it ran.
static void gf_sweep_record_cells(gf_sweep *q, int part)
{
    for (size_t k = 0; k < q->ntouched; k++) q->tsecs[k] = q->cell[q->touched[k]].seconds;
    gf_sweep_record(q, NULL, q->tsecs, q->ntouched, 0.0, part);
}

// Runs a block over the window's touched cell chunks: 0 gather, 1 relax, 2
// apply (the others have no move within reach: nothing of theirs moves, and
// none of their particles is active).
static void gf_sweep_cells(gf_sim *sim, gf_sweep *q, int what)
{
    const size_t n = q->ntouched;
    const int threads = q->threads;
    // Dispatches of ~1/16 of a thread's share (at least 4 chunks): neighbouring
    // chunks write neighbouring particles' bytes, so a thread keeps a stretch.
    const size_t grain = n / (16 * (size_t)threads) > 4 ? n / (16 * (size_t)threads) : 4;
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, grain) num_threads(threads) if (threads > 1)
#endif
    for (size_t k = 0; k < n; k++) {
        const int t = gf_sim_thread();
        const size_t c = q->touched[k];
        if (what == 0)
            gf_sweep_displace(sim, q, t, c);
        else if (what == 1)
            gf_sweep_relax(sim, q, c);
        else
            gf_sweep_move_chunk(sim, q, c);
    }
    (void)threads;
}

// Group g's summary: its chunks' status, counters (they count nothing but
// spot_dz and relax_dz, reset here) and todo lists, in chunk order.
static void gf_sweep_summarise(gf_sim *sim, gf_sweep *q, size_t g)
{
    gf_sweep_group *gr = &q->group[g];
    double t0 = q->profiling ? gf_clock_thread_cpu() : 0.0;
    const size_t lo = q->gstart[g], hi = q->gstart[g + 1]; // its touched chunks: touched[lo, hi)
    const gf_grid *grid = &sim->grid;
    gr->status = GF_OK;
    gr->nexit = gr->nmover = gr->nskin = 0;
    gr->reach_lo = gr->reach_hi = 0;
    gr->spot_dz = gr->relax_dz = 0.0;
    size_t need = 0;
    for (size_t k = lo; k < hi; k++) need += q->cell[q->touched[k]].ntodo;
    uint32_t *ex = gf_sweep_grow(gr->exit, &gr->exit_cap, need, sizeof *ex);
    if (ex) gr->exit = ex;
    gf_sweep_mover *mv = ex ? gf_sweep_grow(gr->mover, &gr->mover_cap, need, sizeof *mv) : NULL;
    if (mv) gr->mover = mv;
    uint32_t *sk = mv ? gf_sweep_grow(gr->skin, &gr->skin_cap, need, sizeof *sk) : NULL;
    if (!sk) {
        gr->status = GF_ERR_NOMEM;
        return;
    }
    gr->skin = sk;
    for (size_t k0 = lo; k0 < hi; k0++) {
        gf_sweep_chunk *ch = &q->cell[q->touched[k0]];
        if (gr->status == GF_OK) gr->status = ch->status;
        gr->spot_dz += ch->st.spot_dz;
        gr->relax_dz += ch->st.relax_dz;
        ch->st.spot_dz = ch->st.relax_dz = 0.0;
        for (size_t k = 0; k < ch->ntodo; k++) {
            const uint32_t i = ch->todo[k];
            const gf_pos *p = &sim->p[i];
            const uint32_t cell = gf_grid_cell(grid, p->x, p->y, p->z);
            if (p->z < sim->box.z_exit) {
                ex[gr->nexit++] = i; // (if it stays, its cell is moved on one thread too)
            } else if (cell != grid->cell_of[i]) {
                mv[gr->nmover++] = (gf_sweep_mover){i, cell};
                ptrdiff_t dg = (ptrdiff_t)(cell / GF_SWEEP_GROUP_CELLS) - (ptrdiff_t)g;
                gr->reach_lo = dg < gr->reach_lo ? dg : gr->reach_lo;
                gr->reach_hi = dg > gr->reach_hi ? dg : gr->reach_hi;
            }
            if (sim->use_nlist) {
                const gf_ref *a = &sim->p0[i];
                double dx = p->x - a->x, dy = p->y - a->y, dz = p->z - a->z, lim = a->h - GF_SKIN_SLACK;
                if (dx * dx + dy * dy + dz * dz > lim * lim) sk[gr->nskin++] = i;
            }
        }
    }
    if (q->profiling) q->gsecs[g] = gf_sweep_since(q, t0);
}

// After a gather or a sweep: the groups summarised side by side, then their
// counters added on one thread in group order (a thousand groups on the
// pebble bed, where one thread once went through 68,000 chunk records three
// times a window).
static gf_status gf_sweep_counters(gf_sim *sim, gf_sweep *q)
{
    const size_t n = q->ngroup;
    const int threads = q->threads;
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (threads > 1 && n > 1)
#endif
    for (size_t g = 0; g < n; g++) gf_sweep_summarise(sim, q, g);
    (void)threads;
    if (q->profiling) gf_sweep_record(q, NULL, q->gsecs, n, 0.0, 3);
    const double ts = gf_sweep_tic(q);
    gf_status st = GF_OK;
    q->reach_lo = q->reach_hi = 0;
    q->nxgroup = 0;
    for (size_t g = 0; g < n; g++) {
        const gf_sweep_group *gr = &q->group[g];
        sim->st.spot_dz += gr->spot_dz;
        sim->st.relax_dz += gr->relax_dz;
        if (st == GF_OK && gr->status != GF_OK) st = gf_error_set(gr->status, "out of memory in the sweep engine");
        if (gr->nexit) q->xgroup[q->nxgroup++] = (uint32_t)g;
        if (gr->nmover) {
            q->reach_lo = gr->reach_lo < q->reach_lo ? gr->reach_lo : q->reach_lo;
            q->reach_hi = gr->reach_hi > q->reach_hi ? gr->reach_hi : q->reach_hi;
        }
    }
    gf_sweep_toc(q, ts);
    return st;
}

// The grid's columns side by side: 0, the column tops the window's walk
// reads (as the window begins); 1, the grid's top[] (as it ends).
static void gf_sweep_columns(gf_sim *sim, gf_sweep *q, int what)
{
    const size_t n = (q->ncol + GF_SWEEP_COL_CHUNK - 1) / GF_SWEEP_COL_CHUNK;
    const int threads = q->threads;
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (threads > 1 && n > 1)
#endif
    for (size_t c = 0; c < n; c++) {
        double t0 = q->profiling ? gf_clock_thread_cpu() : 0.0;
        const size_t lo = c * GF_SWEEP_COL_CHUNK, hi = lo + GF_SWEEP_COL_CHUNK < q->ncol ? lo + GF_SWEEP_COL_CHUNK : q->ncol;
        if (what == 0)
            for (size_t col = lo; col < hi; col++)
                q->coltop[col] = gf_grid_column_top_at(&sim->grid, (uint32_t)col, &sim->p[0].z, 4);
        else
            gf_grid_recompute_top_cols(&sim->grid, lo, hi);
        if (q->profiling) q->csecs[c] = gf_sweep_since(q, t0);
    }
    (void)threads;
    if (q->profiling) gf_sweep_record(q, NULL, q->csecs, n, 0.0, -1);
}

gf_status gf_sim_sweep_window(gf_sim *sim)
{
    gf_status st = gf_sweep_make(sim);
    if (st != GF_OK) return st;
    gf_sweep *q = sim->sweep;
    q->serial_acc = 0.0;
    double ts = gf_sweep_tic(q);
    const gf_engine_defs *c = &sim->d;
    const double window = c->window, t_end = sim->t_pending;
    sim->t = t_end;
    sim->pending = false;
    sim->fstep++;
    sim->st.events++;
    const size_t nexit0 = sim->nexit;
    if ((st = gf_spots_insert_window(sim, t_end, window)) != GF_OK) return st;
    sim->grid.lazy_top = true; // top[] is redone after the window
    gf_sweep_toc(q, ts);
    gf_sweep_columns(sim, q, 0);
    st = gf_sweep_walk_all(sim, q, t_end);
    if (st == GF_OK && q->nmv > 0) {
        double t1 = sim->timing ? gf_clock_now() : 0.0;
        gf_sweep_touch(sim, q);
        gf_sweep_cells(sim, q, 0);
        if (q->profiling) gf_sweep_record_cells(q, 1);
        st = gf_sweep_counters(sim, q);
        if (st == GF_OK) st = gf_sweep_book(sim, q);
        if (q->profiling) gf_sweep_record_book(q);
        if (sim->timing) sim->st.spot_seconds += gf_clock_now() - t1;
        const int64_t sweeps = sim->no_relax || c->method == GF_RELAX_NONE ? 0 : c->sweeps;
        double t2 = gf_clock_now();
        for (int64_t s = 0; s < sweeps && st == GF_OK; s++) {
            gf_sweep_cells(sim, q, 1);
            if (q->profiling) gf_sweep_record_cells(q, 2);
            gf_sweep_cells(sim, q, 2);
            if (q->profiling) gf_sweep_record_cells(q, 2);
            st = gf_sweep_counters(sim, q);
            if (st == GF_OK) st = gf_sweep_book(sim, q);
            if (q->profiling) gf_sweep_record_book(q);
            sim->st.relax_calls++;
        }
        sim->st.relax_seconds += gf_clock_now() - t2;
    }
    sim->grid.lazy_top = false;
    gf_sweep_columns(sim, q, 1);
    ts = gf_sweep_tic(q);
    if (st != GF_OK) return st;
    if (sim->nexit > nexit0) qsort(sim->exits + nexit0, sim->nexit - nexit0, sizeof(gf_exit), gf_exit_cmp_time_id);
    gf_spots_compact(sim, q->dead);
    gf_sweep_toc(q, ts);
    if (q->profiling) {
        gf_sweep_record(q, NULL, NULL, 0, q->serial_acc, -1);
        q->prof.profiled_tau += window;
    }
    return GF_OK;
}

size_t gf_sweep_touched_chunks(const gf_sim *sim) { return sim->sweep ? sim->sweep->ntouched : 0; }

void gf_sweep_set_dense(gf_sim *sim, int on)
{
    if (gf_sweep_make(sim) == GF_OK) sim->sweep->dense = on != 0;
}

void gf_sweep_set_profiling(gf_sim *sim, int on)
{
    if (gf_sweep_make(sim) != GF_OK) return;
    sim->sweep->profiling = on != 0;
    sim->sweep->prof = (gf_par_profile){0};
    // The cost of a reading: the median of 101 back-to-back pairs.
    double d[101];
    for (int k = 0; k < 101; k++) {
        double a = gf_clock_thread_cpu();
        d[k] = gf_clock_thread_cpu() - a;
    }
    qsort(d, 101, sizeof(double), gf_sweep_cmp_desc);
    sim->sweep->clock_cost = d[50];
}

gf_par_profile gf_sweep_profile(const gf_sim *sim)
{
    gf_par_profile f = {0};
    const gf_sweep *q = sim->sweep;
    if (!q) return f;
    f = q->prof;
    f.blocks = q->ncell_chunk;
    f.colours = 1;
    f.phases = 1;
    f.window = sim->d.window;
    for (int i = 0; i < GF_PAR_NPROJ; i++) f.proj_threads[i] = gf_sweep_proj_threads[i];
    return f;
}
