// SPDX-License-Identifier: MIT
// The spatial fixed step across MPI ranks (GF_MPI=ON): replicated state,
// owner computes. Every rank holds the whole simulation and makes the same
// global draws (phases, colour orders, insertions), so all agree on which
// blocks run in each colour phase; rank r runs the phase's blocks run[k] with
// k % R == r. Blocks of one colour never share a particle, a cell or a list
// (parallel.c), so the records one rank's blocks change are records no other
// rank's blocks touch. The workers log what their moves change (gf_work.touched:
// the particles moved or whose list rows changed, the cells they left or
// entered, the spots and blocks run); after the phase each rank sends those
// records whole (as its blocks left them), every rank applies the others',
// and all hold the state a single process would have. GF_MPI_CHECK=1 then
// compares a hash of the whole state across ranks after every phase.
#include <mpi.h>
#include <inttypes.h>
#include <limits.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "spot/mpi_records.h"
#include "spot/par_mpi.h"

static struct {
    unsigned char *out, *whole, *in; ///< this rank's message; every rank's chunk; every rank's message
    size_t out_cap, whole_cap, in_cap;
    size_t chunk;                    ///< bytes every rank sends in the phase's first collective
    uint8_t *flag;                   ///< per entry of a kind: already in this phase's message
    size_t flag_cap;
    uint32_t *list; ///< this phase's entries, kind by kind, each once
    size_t list_cap;
    int *counts, *displs, *tcounts, *tdispls;
    gf_mpi_tallies t;       ///< what the exchange did so far
    uint64_t exit_bytes;    ///< exits exchanged so far
    int rank, size;
    int threads;            ///< this rank's threads (the last phase's)
    bool stats_on, check;
    bool report;            ///< GF_MPI_STATS is set: gf_mpi_release passes the counters to gf_warn
    int ncounts;            ///< entries of counts, displs, tcounts, tdispls (the ranks)
} gf_mpi_st;

gf_mpi_tallies *gf_mpi_tally(void) { return &gf_mpi_st.t; }
bool gf_mpi_checking(void) { return gf_mpi_st.check; }

int gf_mpi_rank(void)
{
    int init = 0, r = 0;
    MPI_Initialized(&init);
    if (init) MPI_Comm_rank(MPI_COMM_WORLD, &r);
    return r;
}

int gf_mpi_size(void)
{
    int init = 0, n = 1;
    MPI_Initialized(&init);
    if (init) MPI_Comm_size(MPI_COMM_WORLD, &n);
    return n;
}

int gf_mpi_local_size(void)
{
    static int known = 0; // a collective: asked once, by every rank at the same point (the first step)
    int init = 0, n = 1;
    if (known > 0) return known;
    MPI_Initialized(&init);
    if (!init) return 1;
    MPI_Comm local;
    if (MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &local) != MPI_SUCCESS) return 1;
    MPI_Comm_size(local, &n);
    MPI_Comm_free(&local);
    known = n > 0 ? n : 1;
    return known;
}

bool gf_mpi_stop(volatile sig_atomic_t *stop)
{
    int mine = stop && *stop, any = mine;
    if (gf_mpi_size() < 2) return mine;
    MPI_Allreduce(&mine, &any, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
    if (any && stop) *stop = 1;
    return any;
}

// GF_MPI_STATS=1: when the exchange ends (gf_mpi_release), rank 0 passes
// its counters to gf_warn (the library never prints; docs/performance.md
// quotes them), then counts afresh.
static void gf_mpi_report_stats(void)
{
    if (gf_mpi_st.report && gf_mpi_st.rank == 0 && gf_mpi_st.t.phases > 0) {
        gf_warn("mpi: %d ranks of %d threads, %" PRIu64 " colour phases exchanged, %" PRIu64
                " bytes of changed records (all ranks), %.0f bytes per phase; %" PRIu64 " bytes of exits; rank 0 took %" PRIu64
                " words from the others (%" PRIu64 " particle and %" PRIu64 " cell records)",
                gf_mpi_st.size, gf_mpi_st.threads, gf_mpi_st.t.phases, gf_mpi_st.t.bytes, (double)gf_mpi_st.t.bytes / (double)gf_mpi_st.t.phases,
                gf_mpi_st.exit_bytes, gf_mpi_st.t.applied / 8, gf_mpi_st.t.applied_p, gf_mpi_st.t.applied_c);
        gf_warn("mpi: rank 0 spent %.3f s in the exchange's collectives (waiting included)", gf_mpi_st.t.wait);
        if (gf_mpi_st.t.slabs)
            gf_warn("mpi: rank 0 sent %" PRIu64 " bytes, %.0f per phase (slabs: %.0f per phase to its neighbours, the "
                    "rest, spots, sectors and removals, to every rank); the state made whole %" PRIu64 " times",
                    gf_mpi_st.t.sent, (double)gf_mpi_st.t.sent / (double)gf_mpi_st.t.phases,
                    (double)gf_mpi_st.t.sent_near / (double)gf_mpi_st.t.phases, gf_mpi_st.t.wholes);
        else
            gf_warn("mpi: rank 0 sent %" PRIu64 " bytes, %.0f per phase (to every rank)", gf_mpi_st.t.sent,
                    (double)gf_mpi_st.t.sent / (double)gf_mpi_st.t.phases);
    }
    gf_mpi_st.t = (gf_mpi_tallies){0};
    gf_mpi_st.exit_bytes = 0;
}

// The per-rank count arrays, made once (by the first phase or exit merge).
static bool gf_mpi_counts(int R)
{
    if (gf_mpi_st.counts) return true;
    gf_mpi_st.ncounts = R;
    gf_mpi_st.counts = GF_NEW(int, R);
    gf_mpi_st.displs = GF_NEW(int, R);
    gf_mpi_st.tcounts = GF_NEW(int, R);
    gf_mpi_st.tdispls = GF_NEW(int, R);
    gf_mpi_st.chunk = 16384;
    return gf_mpi_st.counts && gf_mpi_st.displs && gf_mpi_st.tcounts && gf_mpi_st.tdispls;
}

void gf_mpi_release(void)
{
    gf_mpi_report_stats();
    gf_mpi_slabs_release();
    gf_free(gf_mpi_st.out, gf_mpi_st.out_cap);
    gf_free(gf_mpi_st.whole, gf_mpi_st.whole_cap);
    gf_free(gf_mpi_st.in, gf_mpi_st.in_cap);
    gf_free(gf_mpi_st.flag, gf_mpi_st.flag_cap);
    gf_free(gf_mpi_st.list, gf_mpi_st.list_cap * sizeof(uint32_t));
    const size_t n = (size_t)gf_mpi_st.ncounts;
    if (gf_mpi_st.counts) GF_DELETE(gf_mpi_st.counts, n);
    if (gf_mpi_st.displs) GF_DELETE(gf_mpi_st.displs, n);
    if (gf_mpi_st.tcounts) GF_DELETE(gf_mpi_st.tcounts, n);
    if (gf_mpi_st.tdispls) GF_DELETE(gf_mpi_st.tdispls, n);
    gf_mpi_st.out = gf_mpi_st.whole = gf_mpi_st.in = NULL;
    gf_mpi_st.flag = NULL;
    gf_mpi_st.list = NULL;
    gf_mpi_st.out_cap = gf_mpi_st.whole_cap = gf_mpi_st.in_cap = gf_mpi_st.flag_cap = gf_mpi_st.list_cap = 0;
    gf_mpi_st.counts = gf_mpi_st.displs = gf_mpi_st.tcounts = gf_mpi_st.tdispls = NULL;
    gf_mpi_st.ncounts = 0;
}

bool gf_mpi_room(void **a, size_t *cap, size_t need, size_t size)
{
    if (need <= *cap) return true;
    size_t c = need + need / 2 + 1024;
    void *p = gf_realloc(*a, *cap * size, c * size); // zeroes the new part: flags start clear
    if (!p) return false;
    *a = p;
    *cap = c;
    return true;
}

void gf_mpi_assign(const uint32_t *load, size_t n, uint64_t *scratch, uint8_t *mine)
{
    const size_t R = (size_t)gf_mpi_size(), me = (size_t)gf_mpi_rank();
    const size_t m = n < R ? n : R; // ranks that can get a block
    for (size_t r = 0; r < m; r++) scratch[r] = 0;
    for (size_t k = 0; k < n; k++) {
        size_t best = 0;
        for (size_t r = 1; r < m; r++)
            if (scratch[r] < scratch[best]) best = r;
        scratch[best] += load[k];
        mine[k] = best == me;
    }
}

gf_status gf_mpi_phase_begin(gf_sim *sim, gf_work *work, int threads)
{
    (void)sim;
    if (gf_mpi_size() < 2) return GF_OK;
    if (!gf_mpi_st.stats_on) {
        gf_mpi_st.stats_on = true;
        gf_mpi_st.rank = gf_mpi_rank();
        gf_mpi_st.size = gf_mpi_size();
        const char *e = getenv("GF_MPI_STATS");
        gf_mpi_st.report = e && *e && *e != '0';
        e = getenv("GF_MPI_CHECK");
        gf_mpi_st.check = e && *e && *e != '0';
    }
    gf_mpi_st.threads = threads;
    for (int t = 0; t < threads; t++) {
        work[t].log = true;
        for (int k = 0; k < GF_TOUCH_KINDS; k++) work[t].touched[k].n = 0;
    }
    return GF_OK;
}

uint64_t gf_mpi_hash(uint64_t h, const void *p, size_t bytes)
{
    const unsigned char *b = p;
    for (size_t o = 0; o < bytes; o += 8) {
        uint64_t w = 0;
        memcpy(&w, b + o, bytes - o < 8 ? bytes - o : 8);
        h = (h ^ w) * 0x100000001b3ull;
        h ^= h >> 29;
    }
    return h;
}

/// The particles' arrays (positions, start positions, ids, layers, alive flags, histories) into h.
static uint64_t gf_mpi_hash_particles(uint64_t h, const gf_sim *sim)
{
    const size_t n = sim->n;
    h = gf_mpi_hash(h, sim->p, n * sizeof *sim->p);
    h = gf_mpi_hash(h, sim->p0, n * sizeof *sim->p0);
    h = gf_mpi_hash(h, sim->id, n * sizeof *sim->id);
    h = gf_mpi_hash(h, sim->layer, n * sizeof *sim->layer);
    h = gf_mpi_hash(h, sim->alive, n * sizeof *sim->alive);
    h = gf_mpi_hash(h, sim->hist, n * sizeof *sim->hist);
    return h;
}

/// The spots' arrays (positions and move counts) into h.
static uint64_t gf_mpi_hash_spots(uint64_t h, const gf_sim *sim)
{
    const size_t ns = sim->ns;
    h = gf_mpi_hash(h, sim->sx, ns * sizeof *sim->sx);
    h = gf_mpi_hash(h, sim->sy, ns * sizeof *sim->sy);
    h = gf_mpi_hash(h, sim->sz, ns * sizeof *sim->sz);
    h = gf_mpi_hash(h, sim->scount, ns * sizeof *sim->scount);
    return h;
}

gf_status gf_mpi_agree(const gf_sim *sim)
{
    if (gf_mpi_size() < 2) return GF_OK;
    uint64_t h = 0xcbf29ce484222325ull, counts[5] = {sim->n, sim->n_alive, sim->n_initial, sim->ns, sim->nexit};
    h = gf_mpi_hash(h, counts, sizeof counts);
    h = gf_mpi_hash(h, &sim->t, sizeof sim->t);
    h = gf_mpi_hash(h, &sim->fstep, sizeof sim->fstep);
    h = gf_mpi_hash(h, &sim->next_snap, sizeof sim->next_snap);
    h = gf_mpi_hash(h, &sim->rng.s, sizeof sim->rng.s);
    // (Ranks holding their regions only differ there: GF_MPI_CHECK compares
    // the overlaps of their regions after every phase. What each read of
    // the whole file agrees: the count above, the grid's top, the radii.)
    h = gf_mpi_hash(h, &sim->grid_ztop, sizeof sim->grid_ztop);
    h = gf_mpi_hash(h, &sim->rmax, sizeof sim->rmax);
    int part = sim->part, any = part;
    MPI_Allreduce(&part, &any, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
    if (!any) h = gf_mpi_hash_particles(h, sim);
    h = gf_mpi_hash_spots(h, sim);
    h = gf_mpi_hash(h, sim->exits, sim->nexit * sizeof *sim->exits);
    uint64_t h0 = h;
    MPI_Bcast(&h0, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD);
    int mine = h != h0 ? gf_mpi_rank() : INT_MAX, first = INT_MAX;
    MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
    if (first == INT_MAX) return GF_OK;
    return gf_error_set(GF_ERR_STATE,
                        "the MPI ranks do not hold the same state before the first step (t = %g): rank %d differs from "
                        "rank 0 (a packing file or checkpoint that differs between nodes, or builds of granflow "
                        "that compute differently)",
                        sim->t, first);
}

gf_status gf_mpi_check(const gf_sim *sim, const uint8_t *dead, const void *blocks, size_t block_bytes)
{
    const size_t n = sim->n;
    const gf_grid *g = &sim->grid;
    uint64_t h = 0xcbf29ce484222325ull;
    h = gf_mpi_hash_particles(h, sim);
    h = gf_mpi_hash(h, sim->mark, n * sizeof *sim->mark);
    if (sim->use_nlist && sim->nl) h = gf_mpi_hash(h, sim->nl, (n << sim->nl_shift) * sizeof *sim->nl);
    h = gf_mpi_hash(h, g->count, g->ncell * sizeof *g->count);
    h = gf_mpi_hash(h, g->slot, g->ncell * GF_CELL_CAP * sizeof *g->slot);
    h = gf_mpi_hash(h, g->cell_of, g->np * sizeof *g->cell_of);
    h = gf_mpi_hash(h, g->slot_of, g->np * sizeof *g->slot_of);
    h = gf_mpi_hash_spots(h, sim);
    if (dead) h = gf_mpi_hash(h, dead, sim->ns);
    if (blocks) h = gf_mpi_hash(h, blocks, block_bytes);
    uint64_t mine[2] = {h, ~h}, most[2]; // the largest hash and the complement of the smallest
    MPI_Allreduce(mine, most, 2, MPI_UINT64_T, MPI_MAX, MPI_COMM_WORLD);
    if (most[0] != ~most[1])
        return gf_error_set(GF_ERR_STATE, "GF_MPI_CHECK: the ranks hold different states after colour phase %" PRIu64
                                          " (step %" PRIu64 ")%s: the exchange missed a change",
                            gf_mpi_st.t.phases, sim->fstep, dead ? "" : ", once made whole");
    return GF_OK;
}

gf_status gf_mpi_collect(const gf_sim *sim, gf_work *work, int threads, size_t nblock, size_t block_size,
                         const uint32_t **list, size_t first[GF_TOUCH_KINDS], size_t count[GF_TOUCH_KINDS])
{
    const gf_grid *g = &sim->grid;
    size_t limit[GF_TOUCH_KINDS], rec[GF_TOUCH_KINDS], logged = 0;
    gf_mpi_records_kinds(sim, nblock, block_size, limit, rec);
    for (int t = 0; t < threads; t++)
        for (int k = 0; k < GF_TOUCH_KINDS; k++) logged += work[t].touched[k].n;
    size_t flags = sim->n > g->ncell ? sim->n : g->ncell;
    if (flags < sim->ns) flags = sim->ns;
    if (flags < nblock) flags = nblock;
    if (!gf_mpi_room((void **)&gf_mpi_st.flag, &gf_mpi_st.flag_cap, flags, 1) ||
        !gf_mpi_room((void **)&gf_mpi_st.list, &gf_mpi_st.list_cap, logged, sizeof(uint32_t)))
        return gf_error_set(GF_ERR_NOMEM, "out of memory for the MPI exchange");
    // Each kind's entries, each once, one after the other in list[].
    size_t n = 0;
    for (int k = 0; k < GF_TOUCH_KINDS; k++) {
        first[k] = n;
        for (int t = 0; t < threads; t++) {
            const gf_touch *l = &work[t].touched[k];
            for (size_t e = 0; e < l->n; e++) {
                uint32_t v = l->v[e];
                if (v >= limit[k] || gf_mpi_st.flag[v]) continue;
                gf_mpi_st.flag[v] = 1;
                gf_mpi_st.list[n++] = v;
            }
        }
        // A particle with a whole record needs no position record: the
        // whole records' flags stay up until the moved ones are listed.
        if (k != GF_TOUCH_PARTICLE)
            for (size_t e = k == GF_TOUCH_MOVED ? first[GF_TOUCH_PARTICLE] : first[k]; e < n; e++)
                gf_mpi_st.flag[gf_mpi_st.list[e]] = 0;
        count[k] = n - first[k];
    }
    *list = gf_mpi_st.list;
    return GF_OK;
}

void gf_mpi_record_write(const gf_sim *sim, int k, uint32_t v, const uint8_t *dead, const void *blocks,
                         size_t block_size, unsigned char *o)
{
    const gf_grid *g = &sim->grid;
    switch (k) {
    case GF_TOUCH_PARTICLE: {
        gf_mpi_part r = gf_mpi_part_of(sim, v);
        memcpy(o, &r, sizeof r);
        break;
    }
    case GF_TOUCH_MOVED: {
        gf_mpi_pos r = {v, 0, sim->p[v].x, sim->p[v].y, sim->p[v].z};
        memcpy(o, &r, sizeof r);
        break;
    }
    case GF_TOUCH_ROW:
        memcpy(o, &v, sizeof v);
        memcpy(o + sizeof v, sim->nl + ((size_t)v << sim->nl_shift), sizeof(uint32_t) << sim->nl_shift);
        break;
    case GF_TOUCH_CELL: {
        gf_mpi_cell r = {v, g->count[v]};
        memcpy(o, &r, sizeof r);
        memcpy(o + sizeof r, g->slot + (size_t)v * GF_CELL_CAP, GF_CELL_CAP * sizeof(uint32_t));
        break;
    }
    case GF_TOUCH_SPOT: {
        gf_mpi_spot r = {sim->sx[v], sim->sy[v], sim->sz[v], sim->snext[v], v, sim->scount[v], dead[v], 0};
        memcpy(o, &r, sizeof r);
        break;
    }
    default:
        memcpy(o, &v, sizeof v);
        memcpy(o + sizeof v, (const unsigned char *)blocks + v * block_size, block_size);
    }
}

// This rank's message: its length, the number of records of each kind, then
// the records kind by kind (each entry once, as this rank's blocks left it).
static gf_status gf_mpi_pack(gf_sim *sim, gf_work *work, int threads, const uint8_t *dead, const void *blocks,
                             size_t nblock, size_t block_size, size_t *bytes)
{
    size_t limit[GF_TOUCH_KINDS], rec[GF_TOUCH_KINDS], first[GF_TOUCH_KINDS], count[GF_TOUCH_KINDS];
    gf_mpi_records_kinds(sim, nblock, block_size, limit, rec);
    const uint32_t *list;
    gf_status st = gf_mpi_collect(sim, work, threads, nblock, block_size, &list, first, count);
    if (st != GF_OK) return st;
    uint32_t head[1 + GF_TOUCH_KINDS];
    size_t need = sizeof head;
    for (int k = 0; k < GF_TOUCH_KINDS; k++) {
        head[1 + k] = (uint32_t)count[k];
        need += count[k] * rec[k];
    }
    head[0] = (uint32_t)need;
    if (!gf_mpi_room((void **)&gf_mpi_st.out, &gf_mpi_st.out_cap, need > gf_mpi_st.chunk ? need : gf_mpi_st.chunk, 1))
        return gf_error_set(GF_ERR_NOMEM, "out of memory for the MPI exchange");
    unsigned char *o = gf_mpi_st.out;
    memcpy(o, head, sizeof head);
    o += sizeof head;
    for (int k = 0; k < GF_TOUCH_KINDS; k++)
        for (size_t e = first[k]; e < first[k] + count[k]; e++, o += rec[k])
            gf_mpi_record_write(sim, k, list[e], dead, blocks, block_size, o);
    *bytes = need;
    return GF_OK;
}

// Every rank's message into gf_mpi_st.in, rank r's from in + displs[r]. One
// collective in the common case: every rank sends `chunk` bytes (its message,
// or the head of it); the longer messages' tails follow in a second one. The
// chunk stays 16 KB: grown to the longest message seen, it made every later
// phase send that much (papers' silo, 2 ranks: 0.20 s in the collectives
// over 0.5 tau against 0.16 s with the fixed chunk).
static gf_status gf_mpi_swap(size_t mine)
{
    const int R = gf_mpi_st.size;
    const size_t C = gf_mpi_st.chunk;
    if (!gf_mpi_room((void **)&gf_mpi_st.whole, &gf_mpi_st.whole_cap, (size_t)R * C, 1))
        return gf_error_set(GF_ERR_NOMEM, "out of memory for the MPI exchange");
    MPI_Allgather(gf_mpi_st.out, (int)C, MPI_BYTE, gf_mpi_st.whole, (int)C, MPI_BYTE, MPI_COMM_WORLD);
    size_t total = 0, tails = 0;
    for (int r = 0; r < R; r++) {
        uint32_t len;
        memcpy(&len, gf_mpi_st.whole + (size_t)r * C, sizeof len);
        // Every rank sees every length: a bad one is refused by all of them.
        if (len < sizeof(gf_mpi_head) || len > INT_MAX || total + len > INT_MAX)
            return gf_error_set(GF_ERR_STATE,
                                "MPI exchange: rank %d announces a message of %u bytes (%zu before it): the ranks are "
                                "out of step",
                                r, len, total);
        gf_mpi_st.displs[r] = (int)total;
        gf_mpi_st.counts[r] = (int)len;
        total += len;
        tails += len > C ? len - C : 0;
    }
    if (!gf_mpi_room((void **)&gf_mpi_st.in, &gf_mpi_st.in_cap, total + tails, 1))
        return gf_error_set(GF_ERR_NOMEM, "out of memory for the MPI exchange");
    for (int r = 0; r < R; r++) {
        size_t len = (size_t)gf_mpi_st.counts[r];
        memcpy(gf_mpi_st.in + gf_mpi_st.displs[r], gf_mpi_st.whole + (size_t)r * C, len < C ? len : C);
    }
    if (tails > 0) {
        // The tails land after the messages, then join their heads.
        int *tc = gf_mpi_st.tcounts, *td = gf_mpi_st.tdispls;
        size_t at = total;
        for (int r = 0; r < R; r++) {
            size_t len = (size_t)gf_mpi_st.counts[r];
            tc[r] = len > C ? (int)(len - C) : 0;
            td[r] = (int)at;
            at += (size_t)tc[r];
        }
        MPI_Allgatherv(gf_mpi_st.out + C, mine > C ? (int)(mine - C) : 0, MPI_BYTE, gf_mpi_st.in, tc, td, MPI_BYTE,
                       MPI_COMM_WORLD);
        for (int r = 0; r < R; r++)
            if (tc[r] > 0) memmove(gf_mpi_st.in + gf_mpi_st.displs[r] + C, gf_mpi_st.in + td[r], (size_t)tc[r]);

    }
    gf_mpi_st.t.bytes += total;
    gf_mpi_st.t.sent += mine;
    return GF_OK;
}

gf_status gf_mpi_phase_end(gf_sim *sim, gf_work *work, int threads, uint8_t *dead, void *blocks, size_t nblock,
                          size_t block_size)
{
    const int R = gf_mpi_size(), me = gf_mpi_rank();
    if (R < 2) return GF_OK;
    bool failed = false;
    for (int t = 0; t < threads; t++) failed = failed || work[t].log_failed;
    if (failed) return gf_error_set(GF_ERR_NOMEM, "out of memory for the MPI exchange's logs");
    // (or made by gf_mpi_merge_exits, in a step with no phase to exchange)
    if (!gf_mpi_counts(R)) return gf_error_set(GF_ERR_NOMEM, "out of memory for MPI");
    size_t mine = 0;
    gf_status st = gf_mpi_pack(sim, work, threads, dead, blocks, nblock, block_size, &mine);
    if (st != GF_OK) return st;
    double t0 = MPI_Wtime();
    if ((st = gf_mpi_swap(mine)) != GF_OK) return st;
    gf_mpi_st.t.wait += MPI_Wtime() - t0;
    gf_mpi_st.t.phases++;
    // Every rank checks every message (its own too) before applying any:
    // all come to the same verdict, and fail together, with no collective more.
    for (int r = 0; r < R; r++)
        if ((st = gf_mpi_records_check(sim, gf_mpi_st.in + gf_mpi_st.displs[r], (size_t)gf_mpi_st.counts[r], nblock,
                                       block_size, r)) != GF_OK)
            return st;
    for (int pass = 0; pass < 2; pass++)
        for (int r = 0; r < R; r++) {
            if (r == me) continue;
            gf_mpi_records_apply(sim, gf_mpi_st.in + gf_mpi_st.displs[r], dead, blocks, nblock, block_size, pass == 1,
                                 &gf_mpi_st.t.applied_p, &gf_mpi_st.t.applied_c);
            if (pass == 0) gf_mpi_st.t.applied += (uint64_t)gf_mpi_st.counts[r];
        }
    return gf_mpi_st.check ? gf_mpi_check(sim, dead, blocks, nblock * block_size) : GF_OK;
}

gf_status gf_mpi_merge_exits(gf_sim *sim, gf_work *work, int threads)
{
    const int R = gf_mpi_size();
    if (R < 2) return GF_OK;
    size_t mine = 0;
    for (int t = 0; t < threads; t++) mine += work[t].nexit;
    typedef struct {
        gf_exit e;
        uint32_t slot, pad_;
    } rec;
    rec *out = GF_NEW(rec, mine + 1);
    if (!out) return gf_error_set(GF_ERR_NOMEM, "out of memory for the MPI exits");
    size_t k = 0;
    for (int t = 0; t < threads; t++) {
        for (size_t i = 0; i < work[t].nexit; i++, k++) {
            out[k].e = work[t].exits[i];
            out[k].slot = work[t].exit_slot[i];
        }
        work[t].nexit = 0;
    }
    int bytes = (int)(mine * sizeof(rec));
    if (!gf_mpi_counts(R)) {
        GF_DELETE(out, mine + 1);
        return gf_error_set(GF_ERR_NOMEM, "out of memory for MPI");
    }
    int *counts = gf_mpi_st.counts, *displs = gf_mpi_st.displs;
    MPI_Allgather(&bytes, 1, MPI_INT, counts, 1, MPI_INT, MPI_COMM_WORLD);
    size_t total = 0;
    for (int r = 0; r < R; r++) {
        displs[r] = (int)total;
        total += (size_t)counts[r];
    }
    const size_t all_bytes = total + sizeof(rec);
    rec *all = gf_alloc(all_bytes);
    if (!all) {
        GF_DELETE(out, mine + 1);
        return gf_error_set(GF_ERR_NOMEM, "out of memory for the MPI exits");
    }
    MPI_Allgatherv(out, bytes, MPI_BYTE, all, counts, displs, MPI_BYTE, MPI_COMM_WORLD);
    GF_DELETE(out, mine + 1);
    gf_mpi_st.exit_bytes += total;
    size_t n = total / sizeof(rec);
    gf_status st = GF_OK;
    if (!gf_sim_exits_reserve(sim, n)) st = gf_error_set(GF_ERR_NOMEM, "out of memory for %zu exits", n);
    for (size_t i = 0; i < n && st == GF_OK; i++) {
        sim->exits[sim->nexit++] = all[i].e;
        sim->n_alive--;
        if (all[i].slot != UINT32_MAX && !gf_sim_reinsert_queue(sim, all[i].slot))
            st = gf_error_set(GF_ERR_NOMEM, "out of memory for the re-insertions");
    }
    // The owner's gf_sim_exit_slow changed the particle's cell and lists:
    // the phase exchange carried those. The caller sorts the step's exits.
    gf_free(all, all_bytes);
    return st;
}
