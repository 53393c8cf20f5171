// SPDX-License-Identifier: MIT
// The domain engine (run.order = domains): the "fully distributed parallel
// spot algorithm, where all spot motions are taken care of locally" that the
// 2009 paper's Sec. 2.1 leaves as future work, using the leeway it notes in
// "reordering spot motions while still achieving similar results".
//
// The container is cut into domains of whole grid cells, and each domain
// into S sectors along every cut axis (S = parallel.sectors, 2 as in
// SPPARKS' `sector` command and the synchronous sublattice algorithm of
// Shim and Amar, PRB 71, 125432, 2005). A sector is a block of cells; its
// index along an axis is its block's position modulo S. Same-index sectors
// of two domains are S - 1 sectors apart along some cut axis, at least two
// reaches of a spot step (gf_par_reach) and a cell diagonal: they never
// share a particle, a list row or a cell, so they run side by side.
//
// A cycle covers a window (t - W, t] of simulated time, W = parallel.window.
// Its spot insertions are drawn first (Poisson(lambda W), each at a uniform
// time in the window). Then every sector index in turn, in a random order
// drawn for the cycle, is a phase: each domain moves the spots in that
// sector, each at its own rate mu (a spot carries the time of its next move,
// exponentially spaced as in the event engine), in time order, until the
// window ends or the spot leaves the sector; a spot that leaves waits for
// its new sector's phase (this cycle's, or the next cycle's when that phase
// has run: its late moves are then made first, none is lost). As W -> 0
// every spot's moves fall in windows of their own and the order becomes the
// event engine's.
//
// Determinism: each move draws on a stream of (seed, spot, move time),
// a sector's spots move in the order of their times (ties by birth), the
// sectors of a phase touch disjoint state, counters are summed sector by
// sector and the cycle's exits are sorted by (time, id): the result depends
// on the seed and the parallel keys, never on the number of threads.
//
// MPI ranks (GF_MPI=ON): the domains are cut into one slab a rank along the
// axis with the most of them (slabs.h); each rank runs its slab's sectors in
// every phase and exchanges with its neighbour slabs (par_mpi_slabs.c). The
// sectors of a phase are independent whoever runs them, so the result does
// not depend on the number of ranks either.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "core/alloc.h"
#include "core/clock.h"
#include "core/error.h"
#include "geom/celllist.h"
#include "spot/par_mpi.h"
#include "spot/sim_internal.h"

/// Worker counts the speedup is projected for (as the spatial step's).
static const int gf_dom_proj_threads[GF_PAR_NPROJ] = {2, 8, 16, 64, 256};
/// The halo exchange model of the projections: per message, and per byte.
#define GF_DOM_MSG_SECONDS 2e-6
#define GF_DOM_BYTE_SECONDS (1.0 / 10e9)
/// Bytes a moved particle costs in the exchange: its position record.
#define GF_DOM_RECORD_BYTES 32.0
/// A phase with fewer spots than this runs on one thread (waking the others
/// and the barrier would cost more than the moves).
#define GF_DOM_MIN_SHARED 8

typedef struct gf_sector {
    gf_sim_stats st;  ///< its counters this cycle (summed in sector order)
    gf_status status; ///< first error
    char err[256];
    double seconds;    ///< CPU time of its last phase (profiling)
    uint64_t moved;    ///< particles its spot() calls moved in its last phase (exchange model)
    uint32_t nparticle; ///< particles in its cells at its last phase (profiling)
} gf_sector;

typedef struct gf_dom {
    int threads;
    gf_work *work;          ///< one per thread
    uint32_t **heap;        ///< per thread: the sector's spots by next move time
    size_t *heap_cap;
    int S;                  ///< sectors per cut axis
    int bs[3];              ///< cells per sector along x, y, z
    int nb[3];              ///< sectors along x, y, z (whole container)
    int nc[3];              ///< sector indices along x, y, z (S on a cut axis, else 1)
    int nsect;              ///< sector indices: nc[0] nc[1] nc[2] (phases per cycle)
    size_t ndomain;
    size_t nblock;          ///< sectors of all domains
    gf_sector *sec;
    uint32_t *blockof;      ///< per grid cell: its sector
    gf_celllist bycolour;   ///< sectors by index: colour c's are bycolour.idx[start[c], start[c + 1])
    gf_celllist spots;      ///< spots by sector, redone at every phase
    uint8_t *dead;
    size_t spot_cap;
    double *coltop;
    size_t ncol;
    uint32_t *run;          ///< sectors of the current phase with spots
    uint32_t *runload;      ///< their spots (MPI: the ranks share the phase by these)
    uint8_t *mine;          ///< per run[] entry: this rank runs it
    uint64_t *rankload;     ///< scratch of gf_mpi_assign
    double *secs;           ///< their times (profiling)
    int messages;           ///< neighbours a domain exchanges with: 3^(cut axes) - 1
    uint64_t shared;        ///< phases with two or more sectors to run side by side
    bool drop_crossing;     ///< tests only: a spot whose move leaves its sector is lost with its moves
    gf_par_profile prof;
    bool profiling;
    gf_slabs slabs;         ///< MPI ranks: the slab of domains each owns (slabs.h)
    int *owner;             ///< MPI ranks: per sector, the rank that runs it (NULL: one process)
} gf_dom;

// The workers (scratch, column marks, heaps) freed; none left.
static void gf_dom_workers_free(gf_dom *q)
{
    for (int t = 0; t < q->threads; t++) {
        if (q->work[t].colmax) GF_DELETE(q->work[t].colmax, q->ncol);
        gf_work_free(&q->work[t]);
        if (q->heap) GF_DELETE(q->heap[t], q->heap_cap[t]);
    }
    GF_DELETE(q->work, q->threads);
    GF_DELETE(q->heap, q->threads);
    GF_DELETE(q->heap_cap, q->threads);
    q->threads = 0;
}

void gf_dom_free(gf_sim *sim)
{
    gf_dom *q = sim->dom;
    if (!q) return;
    gf_dom_workers_free(q);
    GF_DELETE(q->sec, q->nblock);
    GF_DELETE(q->blockof, sim->grid.ncell);
    gf_celllist_free(&q->bycolour);
    gf_celllist_free(&q->spots);
    GF_DELETE(q->dead, q->spot_cap);
    GF_DELETE(q->coltop, q->ncol);
    GF_DELETE(q->run, q->nblock);
    GF_DELETE(q->runload, q->nblock);
    GF_DELETE(q->mine, q->nblock);
    GF_DELETE(q->rankload, q->nblock);
    GF_DELETE(q->secs, q->nblock);
    if (q->owner) GF_DELETE(q->owner, q->nblock);
    gf_mpi_release(); // (it forgets the slabs before they go)
    gf_slabs_free(&q->slabs);
    gf_free(q, sizeof *q);
    sim->dom = NULL;
}

// Sectors along one axis of n cells (cell size h): a sector spans `need`
// over S - 1 sectors, or `size` / S when parallel.domain_size is set; an
// axis left out of parallel.cut, or too short for two sectors, is not cut.
static gf_status gf_dom_axis(int n, bool cut, double need, double size, int S, double h, int *bs, int *nb, int *nc)
{
    if (!cut) {
        *bs = n;
        *nb = 1;
        *nc = 1;
        return GF_OK;
    }
    int least = (int)ceil(need / ((S - 1) * h));
    *bs = least;
    if (size > 0) {
        *bs = (int)floor(size / (S * h));
        if (*bs < least)
            return gf_error_set(GF_ERR_PARAM,
                                "parallel.domain_size = %g d is below the smallest domain that keeps the sectors "
                                "of neighbouring domains independent, %g d (%d sectors of %d cells of %.3g d)",
                                size, S * least * h, S, least, h);
    }
    *nb = (n + *bs - 1) / *bs;
    *nc = S;
    if (*nb < 2) {
        *bs = n;
        *nb = 1;
        *nc = 1;
    }
    return GF_OK;
}

// The keys' decomposition of the grid: cells per sector, sectors and sector
// indices along x, y and z (what the engine runs and what a rank's window
// of packing.file is cut from).
static gf_status gf_dom_cuts(const gf_sim *sim, int bs[3], int nb[3], int nc[3])
{
    const gf_grid *g = &sim->grid;
    const gf_engine_defs *c = &sim->d;
    const int n[3] = {g->nx, g->ny, g->nz};
    const double need = 2.0 * gf_par_reach(sim) + sqrt(3.0) * g->h;
    for (int a = 0; a < 3; a++) {
        gf_status st = gf_dom_axis(n[a], (c->cut >> a) & 1, need, c->domain_size, (int)c->sectors, g->h, &bs[a],
                                   &nb[a], &nc[a]);
        if (st != GF_OK) return st;
    }
    return GF_OK;
}

// MPI ranks: the domains cut into one slab a rank along the axis with the
// most domains (the tallest; z on a tie). The halo: a reach and a cell
// diagonal, in whole layers. (No MPI here: window.c asks before the grid is made.)
static gf_status gf_dom_slabs_of(const gf_sim *sim, const gf_grid *g, const int nb[3], const int nc[3],
                                 const int bs[3], int R, gf_slabs *out)
{
    int axis = 2, D = 1;
    for (int a = 0; a < 3; a++) {
        int d = (nb[a] + nc[a] - 1) / nc[a];
        if (nc[a] > 1 && d >= D) {
            axis = a;
            D = d;
        }
    }
    const int n[3] = {g->nx, g->ny, g->nz};
    const int per = nc[axis] * bs[axis];
    const int halo = (int)ceil((gf_par_reach(sim) + sqrt(3.0) * g->h) / g->h);
    return gf_slabs_make(out, axis, n[axis], g->nx, g->ny, D, per, R, halo);
}

#ifdef GF_MPI
// Each sector run by its slab's rank.
static gf_status gf_dom_slabs(const gf_sim *sim, gf_dom *q)
{
    gf_status st = gf_dom_slabs_of(sim, &sim->grid, q->nb, q->nc, q->bs, gf_mpi_size(), &q->slabs);
    if (st != GF_OK) return st;
    const int axis = q->slabs.axis;
    q->owner = GF_NEW(int, q->nblock);
    if (!q->owner) return gf_error_set(GF_ERR_NOMEM, "out of memory for the domain engine");
    for (size_t b = 0; b < q->nblock; b++) {
        size_t pos = axis == 0   ? b % (size_t)q->nb[0]
                     : axis == 1 ? b / (size_t)q->nb[0] % (size_t)q->nb[1]
                                 : b / ((size_t)q->nb[0] * (size_t)q->nb[1]);
        q->owner[b] = gf_slabs_owner(&q->slabs, (int)pos * q->bs[axis]);
    }
    return GF_OK;
}
#endif

gf_status gf_dom_window_layers(const gf_sim *sim, int R, int me, int margin, int *lo, int *hi)
{
    const gf_grid *g = &sim->grid;
    int bs[3], nb[3], nc[3];
    *lo = 0;
    *hi = g->nz;
    gf_status st = gf_dom_cuts(sim, bs, nb, nc);
    if (st != GF_OK) return st;
    gf_slabs s;
    st = gf_dom_slabs_of(sim, g, nb, nc, bs, R, &s);
    if (st != GF_OK) return st;
    if (s.axis == 2 && me >= 0 && me < R) {
        *lo = s.rlo[me] - margin > 0 ? s.rlo[me] - margin : 0;
        *hi = s.rhi[me] + margin < g->nz ? s.rhi[me] + margin : g->nz;
        if (s.rlo[me] >= s.rhi[me]) *lo = *hi = 0; // a rank with no slab holds nothing
    }
    gf_slabs_free(&s);
    return GF_OK;
}

static gf_status gf_dom_blocks(gf_sim *sim, gf_dom *q)
{
    const gf_grid *g = &sim->grid;
    q->S = (int)sim->d.sectors;
    gf_status st = gf_dom_cuts(sim, q->bs, q->nb, q->nc);
    if (st != GF_OK) return st;
    int cut = 0;
    q->ndomain = 1;
    for (int a = 0; a < 3; a++) {
        cut += q->nc[a] > 1;
        q->ndomain *= (size_t)((q->nb[a] + q->nc[a] - 1) / q->nc[a]);
    }
    q->messages = cut == 0 ? 0 : cut == 1 ? 2 : cut == 2 ? 8 : 26;
    q->nsect = q->nc[0] * q->nc[1] * q->nc[2];
    q->nblock = (size_t)q->nb[0] * (size_t)q->nb[1] * (size_t)q->nb[2];
    q->sec = GF_NEW(gf_sector, q->nblock);
    q->blockof = GF_NEW(uint32_t, g->ncell);
    q->run = GF_NEW(uint32_t, q->nblock);
    q->runload = GF_NEW(uint32_t, q->nblock);
    q->mine = GF_NEW(uint8_t, q->nblock);
    q->rankload = GF_NEW(uint64_t, q->nblock);
    q->secs = GF_NEW(double, q->nblock);
    if (!q->sec || !q->blockof || !q->run || !q->runload || !q->mine || !q->rankload || !q->secs)
        return gf_error_set(GF_ERR_NOMEM, "out of memory for the domain engine");
    st = gf_par_colour_blocks(g, q->bs, q->nb, q->nc, q->blockof, &q->bycolour);
#ifdef GF_MPI
    if (st == GF_OK && gf_mpi_size() > 1) st = gf_dom_slabs(sim, q);
#endif
    return st;
}

// The workers for the current thread count; the decomposition is made once
// (it depends on the keys and the packing, never on the threads).
static gf_status gf_dom_make(gf_sim *sim)
{
    const int threads = gf_par_threads(&sim->d);
    gf_dom *q = sim->dom;
    if (q && q->threads == threads) return GF_OK;
    if (!q) {
        q = gf_alloc(sizeof *q);
        if (!q) return gf_error_set(GF_ERR_NOMEM, "out of memory for the domain engine");
        *q = (gf_dom){0};
        sim->dom = q;
        q->ncol = (size_t)sim->grid.nx * (size_t)sim->grid.ny;
        q->coltop = GF_NEW(double, q->ncol);
        gf_status st = q->coltop ? gf_dom_blocks(sim, q) : gf_error_set(GF_ERR_NOMEM, "out of memory");
        if (st != GF_OK) {
            gf_dom_free(sim);
            return st;
        }
    }
    gf_dom_workers_free(q);
    q->work = GF_NEW(gf_work, threads);
    q->heap = GF_NEW(uint32_t *, threads);
    q->heap_cap = GF_NEW(size_t, threads);
    if (!q->work || !q->heap || !q->heap_cap) {
        gf_dom_free(sim);
        return gf_error_set(GF_ERR_NOMEM, "out of memory for the domain engine");
    }
    q->threads = threads;
    for (int t = 0; t < threads; t++) {
        gf_status st = gf_work_init(sim, &q->work[t]);
        if (st != GF_OK) {
            gf_dom_free(sim);
            return st;
        }
        q->work[t].defer_exits = true;
        q->work[t].timed = true;
        q->work[t].coltop = q->coltop;
#ifdef GF_MPI
        q->work[t].slabs = q->owner && !gf_mpi_test_break("entry") ? &q->slabs : NULL;
        if (gf_mpi_size() > 1) continue; // cells also change by the neighbours' records: tops rescanned whole
#endif
        q->work[t].colmax = GF_NEW(int32_t, q->ncol);
        if (!q->work[t].colmax) {
            gf_dom_free(sim);
            return gf_error_set(GF_ERR_NOMEM, "out of memory for the domain engine");
        }
        for (size_t col = 0; col < q->ncol; col++) q->work[t].colmax[col] = -1;
    }
    return GF_OK;
}

// After a cycle (run with lazy tops): each column's top non-empty layer.
// One process: a column's top is at most the larger of its top before the
// cycle (exact: every change outside a cycle keeps it) and the highest layer
// a particle entered in it during the cycle, so it is found walking down
// from there, not from the top of the grid; the marks are reset.
static void gf_dom_settle_top(gf_sim *sim, gf_dom *q)
{
    gf_grid *g = &sim->grid;
    if (q->threads == 0 || !q->work[0].colmax) {
        gf_grid_recompute_top(g);
        return;
    }
    for (size_t col = 0; col < q->ncol; col++) {
        int32_t z = g->top[col];
        for (int t = 0; t < q->threads; t++) {
            if (q->work[t].colmax[col] > z) z = q->work[t].colmax[col];
            q->work[t].colmax[col] = -1;
        }
        g->top[col] = gf_grid_top_from(g, (uint32_t)col, z);
    }
}

// The stream of one move of spot k: (seed, its birth number, its move time).
static void gf_dom_seed(const gf_sim *sim, size_t k, gf_rng *r)
{
    uint64_t bits;
    memcpy(&bits, &sim->snext[k], sizeof bits);
    gf_rng_seed(r, sim->d.seed ^ 0x646f6d61696e73ull /* "domains" */, (sim->sbirth[k] * 0x9e3779b97f4a7c15ull) ^ bits);
}

// Heap order: earlier move first, then older spot.
static inline bool gf_dom_before(const gf_sim *sim, uint32_t a, uint32_t b)
{
    return sim->snext[a] < sim->snext[b] || (sim->snext[a] == sim->snext[b] && sim->sbirth[a] < sim->sbirth[b]);
}

static void gf_dom_push(const gf_sim *sim, uint32_t *h, size_t *n, uint32_t k)
{
    size_t i = (*n)++;
    while (i > 0) {
        size_t p = (i - 1) / 2;
        if (!gf_dom_before(sim, k, h[p])) break;
        h[i] = h[p];
        i = p;
    }
    h[i] = k;
}

static uint32_t gf_dom_pop(const gf_sim *sim, uint32_t *h, size_t *n)
{
    uint32_t top = h[0], last = h[--(*n)];
    size_t i = 0;
    for (;;) {
        size_t c = 2 * i + 1;
        if (c >= *n) break;
        if (c + 1 < *n && gf_dom_before(sim, h[c + 1], h[c])) c++;
        if (!gf_dom_before(sim, h[c], last)) break;
        h[i] = h[c];
        i = c;
    }
    if (*n > 0) h[i] = last;
    return top;
}

// Sector b's phase on worker w (thread t): its spots in time order until the
// window ends at t_end or each leaves the sector.
static void gf_dom_sector(gf_sim *sim, gf_dom *q, int t, size_t b, double t_end)
{
    gf_sector *sc = &q->sec[b];
    gf_work *w = &q->work[t];
    const gf_grid *g = &sim->grid;
    const size_t first = q->spots.start[b], end = q->spots.start[b + 1];
    if (end - first > q->heap_cap[t]) {
        size_t cap = end - first + (end - first) / 2 + 16;
        uint32_t *h = gf_realloc(q->heap[t], q->heap_cap[t] * sizeof(uint32_t), cap * sizeof(uint32_t));
        if (!h) {
            sc->status = gf_error_set(GF_ERR_NOMEM, "out of memory for a sector's spots");
            snprintf(sc->err, sizeof sc->err, "%s", gf_last_error());
            return;
        }
        q->heap[t] = h;
        q->heap_cap[t] = cap;
    }
    double t0 = q->profiling ? gf_clock_thread_cpu() : 0.0;
    uint64_t moved = 0;
    uint32_t *h = q->heap[t];
    size_t nh = 0;
    for (size_t o = first; o < end; o++) {
        uint32_t k = q->spots.idx[o];
        if (sim->snext[k] <= t_end) gf_dom_push(sim, h, &nh, k);
    }
    gf_rng rng;
    w->rng = &rng;
    w->st = &sc->st;
    gf_work_touch(w, GF_TOUCH_BLOCK, (uint32_t)b);
    while (nh > 0) {
        uint32_t k = gf_dom_pop(sim, h, &nh);
        gf_work_touch(w, GF_TOUCH_SPOT, k);
        gf_dom_seed(sim, k, &rng);
        // A late move (the spot waited for this sector's phase) is made, and
        // timed, at the window's start: exits stay in time order.
        w->t = fmax(sim->snext[k], t_end - sim->d.window);
        double s[3] = {sim->sx[k], sim->sy[k], sim->sz[k]};
        bool deleted;
        long ball = 0;
        gf_status st = gf_spot_step(sim, w, s, &sim->scount[k], &deleted, &ball);
        if (st != GF_OK) {
            sc->status = st;
            snprintf(sc->err, sizeof sc->err, "%s", gf_last_error());
            return;
        }
        moved += ball > 0 ? (uint64_t)ball : 0;
        if (deleted) {
            q->dead[k] = 1;
            continue;
        }
        sim->sx[k] = s[0];
        sim->sy[k] = s[1];
        sim->sz[k] = s[2];
        sim->snext[k] += gf_rng_exp(&rng, sim->d.move_rate);
        const bool stays = q->blockof[gf_grid_cell(g, s[0], s[1], s[2])] == b;
        if (!stays && q->drop_crossing) { // the broken engine of the tests: the spot and its moves are lost
            q->dead[k] = 1;
            continue;
        }
        if (sim->snext[k] <= t_end && stays) gf_dom_push(sim, h, &nh, k);
    }
    if (q->profiling) {
        sc->seconds = gf_clock_thread_cpu() - t0;
        sc->moved = moved;
    }
}

// The exits the workers found in a phase, appended to the sim's (sorted by
// time and id at the end of the cycle).
static gf_status gf_dom_merge_exits(gf_sim *sim, gf_dom *q)
{
#ifdef GF_MPI
    gf_status sm = gf_mpi_merge_exits(sim, q->work, q->threads); // every rank's exits (sorted at the cycle's end)
    if (sm != GF_OK) return sm;
#endif
    size_t total = 0;
    for (int t = 0; t < q->threads; t++) total += q->work[t].nexit;
    if (total == 0) return GF_OK;
    if (!gf_sim_exits_reserve(sim, total)) return gf_error_set(GF_ERR_NOMEM, "out of memory for %zu exits", total);
    for (int t = 0; t < q->threads; t++) {
        gf_work *w = &q->work[t];
        if (w->exit_failed) return gf_error_set(GF_ERR_NOMEM, "out of memory for the exits");
        if (w->nexit == 0) continue; // (its exits[] may not exist yet)
        memcpy(sim->exits + sim->nexit, w->exits, w->nexit * sizeof(gf_exit));
        for (size_t k = 0; k < w->nexit; k++)
            if (w->exit_slot[k] != UINT32_MAX && !gf_sim_reinsert_queue(sim, w->exit_slot[k]))
                return gf_error_set(GF_ERR_NOMEM, "out of memory for the re-insertions");
        sim->nexit += w->nexit;
        sim->n_alive -= w->nexit;
        w->nexit = 0;
    }
    return GF_OK;
}

static gf_status gf_dom_spots(gf_dom *q, size_t ns)
{
    gf_status st = gf_celllist_keys(&q->spots, q->nblock, ns);
    if (st != GF_OK || ns <= q->spot_cap) return st;
    size_t cap = ns + ns / 2 + 64;
    GF_DELETE(q->dead, q->spot_cap);
    q->dead = GF_NEW(uint8_t, cap);
    q->spot_cap = q->dead ? cap : 0;
    return q->dead ? GF_OK : gf_error_set(GF_ERR_NOMEM, "out of memory for %zu spots", ns);
}

// Profiling: a phase's sectors (run[0, nrun)) timed; the projected makespan
// on T > 1 workers adds the exchange of the heaviest sector's domain.
static void gf_dom_record(gf_dom *q, size_t nrun)
{
    gf_par_profile *f = &q->prof;
    f->colour_phases++;
    f->barriers++;
    f->blocks_run += nrun;
    double work = 0.0, longest = 0.0, xmax = 0.0;
    // Heaviest first, as the OpenMP loop hands them out.
    for (size_t r = 0; r < nrun; r++) {
        size_t k = r;
        double s = q->sec[q->run[r]].seconds;
        while (k > 0 && q->secs[k - 1] < s) {
            q->secs[k] = q->secs[k - 1];
            k--;
        }
        q->secs[k] = s;
        work += s;
        if (s > longest) longest = s;
        size_t layer = q->run[r] / ((size_t)q->nb[0] * (size_t)q->nb[1]);
        f->layer_seconds[layer < GF_PAR_LAYERS ? layer : GF_PAR_LAYERS - 1] += s;
        const gf_sector *sc = &q->sec[q->run[r]];
        double bytes = GF_DOM_RECORD_BYTES * (double)(sc->moved < sc->nparticle ? sc->moved : sc->nparticle);
        f->exchange_bytes += bytes;
        f->exchange_messages += (uint64_t)q->messages;
        double x = q->messages * GF_DOM_MSG_SECONDS + bytes * GF_DOM_BYTE_SECONDS;
        if (x > xmax) xmax = x;
    }
    f->work_seconds += work;
    f->span_seconds += longest;
    for (int i = 0; i < GF_PAR_NPROJ; i++)
        f->makespan_seconds[i] += gf_par_makespan(q->secs, nrun, gf_dom_proj_threads[i]) + xmax;
}

// Particles in sector b's cells (the exchange model's cap on what it sends).
static uint32_t gf_dom_particles(const gf_sim *sim, const gf_dom *q, size_t b)
{
    const gf_grid *g = &sim->grid;
    size_t bx = b % (size_t)q->nb[0], by = b / (size_t)q->nb[0] % (size_t)q->nb[1];
    size_t bz = b / ((size_t)q->nb[0] * (size_t)q->nb[1]);
    uint32_t n = 0;
    for (int cz = (int)bz * q->bs[2]; cz < g->nz && cz < ((int)bz + 1) * q->bs[2]; cz++)
        for (int cy = (int)by * q->bs[1]; cy < g->ny && cy < ((int)by + 1) * q->bs[1]; cy++)
            for (int cx = (int)bx * q->bs[0]; cx < g->nx && cx < ((int)bx + 1) * q->bs[0]; cx++)
                n += g->count[((size_t)cz * (size_t)g->ny + (size_t)cy) * (size_t)g->nx + (size_t)cx];
    return n;
}

// Phase `colour`: the spots grouped by sector, then that index's sectors
// side by side, heaviest first.
static gf_status gf_dom_phase(gf_sim *sim, gf_dom *q, int colour, double t_end)
{
    const gf_grid *g = &sim->grid;
    gf_celllist *cl = &q->spots;
    for (size_t k = 0; k < sim->ns; k++)
        cl->cell[k] = q->dead[k] ? GF_CELLLIST_OUT : q->blockof[gf_grid_cell(g, sim->sx[k], sim->sy[k], sim->sz[k])];
    gf_celllist_sort(cl, sim->ns);
    size_t nrun = 0, spots = 0;
    for (size_t i = q->bycolour.start[colour]; i < q->bycolour.start[colour + 1]; i++) {
        const uint32_t b = q->bycolour.idx[i];
        size_t load = cl->start[b + 1] - cl->start[b];
        if (load == 0) continue;
        spots += load;
        size_t k = nrun++;
        while (k > 0 && q->runload[k - 1] < load) {
            q->run[k] = q->run[k - 1];
            q->runload[k] = q->runload[k - 1];
            k--;
        }
        q->run[k] = b;
        q->runload[k] = (uint32_t)load;
    }
    if (nrun == 0) return GF_OK;
    q->shared += nrun >= 2;
    int threads = nrun < (size_t)q->threads ? (int)nrun : q->threads;
    if (threads < 1 || spots < GF_DOM_MIN_SHARED) threads = 1;
    if (q->profiling)
        for (size_t r = 0; r < nrun; r++) q->sec[q->run[r]].nparticle = gf_dom_particles(sim, q, q->run[r]);
    gf_status st = GF_OK;
#ifdef GF_MPI
    // Each rank runs the sectors of its own slab (par_mpi_slabs.c), then
    // sends its neighbour slabs what its moves changed near them.
    if ((st = gf_mpi_phase_begin(sim, q->work, q->threads)) != GF_OK) return st;
    if (q->owner) { // slabs: each rank runs its own slab's sectors
        const int me = gf_mpi_rank();
        for (size_t r = 0; r < nrun; r++) q->mine[r] = q->owner[q->run[r]] == me;
    } else {
        gf_mpi_assign(q->runload, nrun, q->rankload, q->mine);
    }
#else
    memset(q->mine, 1, nrun);
#endif
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (threads > 1)
#endif
    for (size_t r = 0; r < nrun; r++) {
        const int t = gf_sim_thread();
        if (q->mine[r]) gf_dom_sector(sim, q, t, q->run[r], t_end);
    }
#ifdef GF_MPI
    st = q->owner ? gf_mpi_slab_phase_end(sim, q->work, q->threads, q->dead, q->sec, q->nblock, sizeof *q->sec, &q->slabs)
                  : gf_mpi_phase_end(sim, q->work, q->threads, q->dead, q->sec, q->nblock, sizeof *q->sec);
    if (st != GF_OK) return st;
#endif
    (void)st;
    if (q->profiling) gf_dom_record(q, nrun);
    for (size_t r = 0; r < nrun; r++)
        if (q->sec[q->run[r]].status != GF_OK)
            return gf_error_set(q->sec[q->run[r]].status, "%s", q->sec[q->run[r]].err);
    return gf_dom_merge_exits(sim, q);
}

gf_status gf_sim_domains_cycle(gf_sim *sim)
{
    const gf_engine_defs *c = &sim->d;
    gf_status st = gf_dom_make(sim);
    if (st != GF_OK) return st;
    gf_dom *q = sim->dom;
    const double window = c->window, t_end = sim->t_pending;
    sim->t = t_end;
    sim->pending = false;
    sim->fstep++;
    sim->st.events++;
    const size_t nexit0 = sim->nexit;
    if ((st = gf_spots_insert_window(sim, t_end, window)) != GF_OK) return st;
    if ((st = gf_dom_spots(q, sim->ns)) != GF_OK) return st;
    memset(q->dead, 0, sim->ns);
#ifdef GF_MPI
    if (q->owner) { // the tops from the cells each rank owns
        if ((st = gf_mpi_column_tops(sim, &q->slabs, q->coltop, q->ncol)) != GF_OK) return st;
    } else
#endif
        gf_par_column_tops(sim, q->coltop, q->ncol);
    for (size_t b = 0; b < q->nblock; b++) {
        q->sec[b].st = (gf_sim_stats){0};
        q->sec[b].status = GF_OK;
    }
    int order[64];
    for (int k = 0; k < q->nsect; k++) order[k] = k;
    for (int k = q->nsect; k > 1; k--) { // Fisher-Yates: this cycle's order of the sector indices
        int j = (int)gf_rng_below(&sim->rng, (uint64_t)k), tmp = order[k - 1];
        order[k - 1] = order[j];
        order[j] = tmp;
    }
    sim->grid.lazy_top = true; // top[] is shared by whole columns: redone after the cycle
    for (int p = 0; p < q->nsect && st == GF_OK; p++) st = gf_dom_phase(sim, q, order[p], t_end);
    sim->grid.lazy_top = false;
    gf_dom_settle_top(sim, q);
    for (size_t b = 0; b < q->nblock; b++) gf_par_add(&sim->st, &q->sec[b].st);
    if (st != GF_OK) return st;
    if (sim->nexit > nexit0) qsort(sim->exits + nexit0, sim->nexit - nexit0, sizeof(gf_exit), gf_exit_cmp_time_id);
    gf_spots_compact(sim, q->dead);
    if (q->profiling) q->prof.profiled_tau += window;
    // Method 3 (Sec. 5): the whole packing every k / mu, at the end of the
    // cycle in which it falls due.
    if (c->method == GF_RELAX_GLOBAL) {
        const double every = c->k / c->move_rate;
        if (floor(t_end / every) > floor((t_end - window) / every)) {
#ifdef GF_MPI
            if ((st = gf_mpi_whole(sim)) != GF_OK) return st; // it moves every particle
#endif
            return gf_sim_global(sim);
        }
    }
    return GF_OK;
}

uint64_t gf_dom_shared_phases(const gf_sim *sim) { return sim->dom ? sim->dom->shared : 0; }

void gf_dom_region_particles(const gf_sim *sim, uint64_t *region, uint64_t *owned)
{
    const gf_grid *g = &sim->grid;
    const gf_dom *q = sim->dom;
    *region = *owned = 0;
#ifdef GF_MPI
    const int me = gf_mpi_rank();
#endif
    for (size_t c = 0; c < g->ncell; c++) {
        bool in = true, own = true;
#ifdef GF_MPI
        if (q && q->owner) {
            int L = gf_slabs_layer(&q->slabs, (uint32_t)c);
            in = gf_slabs_holds(&q->slabs, me, L);
            own = L >= q->slabs.lo[me] && L < q->slabs.hi[me];
        }
#else
        (void)q;
#endif
        *region += in ? g->count[c] : 0;
        *owned += own ? g->count[c] : 0;
    }
}

const gf_slabs *gf_dom_slabs_made(gf_sim *sim, gf_status *st)
{
    *st = GF_OK;
    if (sim->d.mode != GF_MODE_FIXED || sim->d.order != GF_ORDER_DOMAINS) return NULL;
    if ((*st = gf_dom_make(sim)) != GF_OK) return NULL;
    return sim->dom->owner ? &sim->dom->slabs : NULL;
}

gf_status gf_dom_test_drop_crossing(gf_sim *sim)
{
    gf_status st = gf_dom_make(sim);
    if (st == GF_OK) sim->dom->drop_crossing = true;
    return st;
}

void gf_dom_set_profiling(gf_sim *sim, int on)
{
    if (gf_dom_make(sim) != GF_OK) return;
    sim->dom->profiling = on != 0;
    sim->dom->prof = (gf_par_profile){0};
}

gf_par_profile gf_dom_profile(const gf_sim *sim)
{
    gf_par_profile f = {0};
    const gf_dom *q = sim->dom;
    if (!q) return f;
    f = q->prof;
    f.blocks = q->nblock;
    f.colours = q->nsect;
    f.phases = 1;
    f.domains = q->ndomain;
    f.window = sim->d.window;
    for (int a = 0; a < 3; a++) {
        f.blocks_along[a] = q->nb[a];
        f.block_cells[a] = q->bs[a];
    }
    for (int i = 0; i < GF_PAR_NPROJ; i++) f.proj_threads[i] = gf_dom_proj_threads[i];
    return f;
}
