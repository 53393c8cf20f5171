// SPDX-License-Identifier: MIT
// The domain engine's phases over slabs (GF_MPI=ON; issue 23 item 3, first
// step). Rank r owns a slab of domains along the tallest axis and runs its
// slab's sectors in every phase (slabs.h). Everything its moves read or write
// lies within a reach of its slab, inside its region (the slab and a halo of
// a reach and a cell diagonal each side), so after a phase it sends what they
// changed to the ranks whose region holds it: its neighbour slabs, point to
// point. Spots, sectors and removed particles (few, and read by every rank:
// spots are replicated, as the design in docs/performance.md keeps them) go
// to every rank in one collective. A particle moved into a rank's region from
// beyond it is sent whole, with its list row (particles.c logs it so), since
// that rank's record of it is old. The state outside a rank's region goes
// stale; gf_mpi_whole makes it whole again before anything reads it.
//
// A rank that read only its region of packing.file (window.c) holds only
// that region's records until gf_mpi_whole gathers the others' (every rank's
// arrays are allocated whole, their pages outside the region never written:
// docs/performance.md).
#include <mpi.h>
#include <inttypes.h>
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "spot/mpi_records.h"
#include "spot/par_mpi.h"

enum { GF_SLAB_TAG = 2323, GF_SLAB_CHECK_TAG = 2324 };

typedef struct gf_slab_buf {
    unsigned char *b;
    size_t cap, len;
} gf_slab_buf;

static struct {
    const gf_slabs *slabs; ///< the engine's, while its phases leave the state partial
    bool dirty;            ///< a slab phase ran since the state was last whole
    int *lay;              ///< per collected entry: the layer that routes it, -1: every rank
    size_t lay_cap;
    gf_slab_buf *out;      ///< per rank: the message to it (out[me]: the one to every rank)
    gf_slab_buf *in;       ///< per rank: the message from it (point to point)
    unsigned char *all;    ///< every rank's message to every rank
    size_t all_cap;
    int *counts, *displs;
    MPI_Request *req;
    int R;
} gf_slab_st;

static bool gf_slab_arrays(int R)
{
    if (gf_slab_st.out) return true;
    gf_slab_st.R = R;
    gf_slab_st.out = GF_NEW(gf_slab_buf, R);
    gf_slab_st.in = GF_NEW(gf_slab_buf, R);
    gf_slab_st.counts = GF_NEW(int, R);
    gf_slab_st.displs = GF_NEW(int, R);
    gf_slab_st.req = GF_NEW(MPI_Request, R);
    return gf_slab_st.out && gf_slab_st.in && gf_slab_st.counts && gf_slab_st.displs && gf_slab_st.req;
}

void gf_mpi_slabs_release(void)
{
    const int R = gf_slab_st.R;
    for (int r = 0; gf_slab_st.out && r < R; r++) gf_free(gf_slab_st.out[r].b, gf_slab_st.out[r].cap);
    for (int r = 0; gf_slab_st.in && r < R; r++) gf_free(gf_slab_st.in[r].b, gf_slab_st.in[r].cap);
    if (gf_slab_st.out) GF_DELETE(gf_slab_st.out, R);
    if (gf_slab_st.in) GF_DELETE(gf_slab_st.in, R);
    if (gf_slab_st.counts) GF_DELETE(gf_slab_st.counts, R);
    if (gf_slab_st.displs) GF_DELETE(gf_slab_st.displs, R);
    if (gf_slab_st.req) GF_DELETE(gf_slab_st.req, R);
    if (gf_slab_st.lay) GF_DELETE(gf_slab_st.lay, gf_slab_st.lay_cap);
    gf_free(gf_slab_st.all, gf_slab_st.all_cap);
    memset(&gf_slab_st, 0, sizeof gf_slab_st);
}

// The layer whose regions a record goes to; -1: every rank (spots, sectors,
// removed particles and their rows, anything outside the grid).
static int gf_slab_route(const gf_sim *sim, const gf_slabs *s, int k, uint32_t v)
{
    const gf_grid *g = &sim->grid;
    switch (k) {
    case GF_TOUCH_PARTICLE:
        return sim->alive[v] && g->cell_of[v] != GF_NO_CELL ? gf_slabs_layer(s, g->cell_of[v]) : -1;
    case GF_TOUCH_MOVED:
    case GF_TOUCH_ROW:
        return g->cell_of[v] != GF_NO_CELL ? gf_slabs_layer(s, g->cell_of[v]) : -1;
    case GF_TOUCH_CELL:
        return gf_slabs_layer(s, v);
    default:
        return -1;
    }
}

bool gf_mpi_test_break(const char *what)
{
    const char *e = getenv("GF_MPI_TEST_BREAK");
    return e && strcmp(e, what) == 0;
}

// GF_MPI_TEST_BREAK=moved (tests only): the moved particles' positions are
// not sent to the neighbours, so the halos go wrong and GF_MPI_CHECK must say so.
static bool gf_slab_broken(void)
{
    static int known = -1;
    if (known < 0) known = gf_mpi_test_break("moved");
    return known == 1;
}

// The message to rank `to` (to == me: to every rank): the collected records
// whose layer its region holds (or that go to every rank).
static gf_status gf_slab_pack(const gf_sim *sim, const gf_slabs *s, int to, int me, const uint32_t *list,
                              const size_t first[GF_TOUCH_KINDS], const size_t count[GF_TOUCH_KINDS],
                              const size_t rec[GF_TOUCH_KINDS], const uint8_t *dead, const void *blocks,
                              size_t block_size)
{
    gf_slab_buf *m = &gf_slab_st.out[to];
    gf_mpi_head h = {{0}};
    size_t need = sizeof h;
    for (int k = 0; k < GF_TOUCH_KINDS; k++) {
        for (size_t e = first[k]; e < first[k] + count[k]; e++) {
            int L = gf_slab_st.lay[e];
            if (L >= 0 && k == GF_TOUCH_MOVED && gf_slab_broken()) L = gf_slab_st.lay[e] = INT_MAX; // sent to no one
            h.v[1 + k] += to == me ? L < 0 : L >= 0 && gf_slabs_holds(s, to, L);
        }
        need += h.v[1 + k] * rec[k];
    }
    if (need > UINT32_MAX || !gf_mpi_room((void **)&m->b, &m->cap, need, 1))
        return gf_error_set(GF_ERR_NOMEM, "out of memory for the MPI exchange (%zu bytes to rank %d)", need, to);
    h.v[0] = (uint32_t)need;
    memcpy(m->b, &h, sizeof h);
    unsigned char *o = m->b + sizeof h;
    for (int k = 0; k < GF_TOUCH_KINDS; k++)
        for (size_t e = first[k]; e < first[k] + count[k]; e++) {
            int L = gf_slab_st.lay[e];
            if (to == me ? L >= 0 : L < 0 || !gf_slabs_holds(s, to, L)) continue;
            gf_mpi_record_write(sim, k, list[e], dead, blocks, block_size, o);
            o += rec[k];
        }
    m->len = need;
    return GF_OK;
}

// Every rank's message to every rank, into gf_slab_st.all (rank r's from
// displs[r], counts[r] bytes). One collective of lengths, one of messages.
static gf_status gf_slab_allgather(const gf_slab_buf *mine, int R, uint64_t *total_out)
{
    int len = (int)mine->len;
    MPI_Allgather(&len, 1, MPI_INT, gf_slab_st.counts, 1, MPI_INT, MPI_COMM_WORLD);
    size_t total = 0;
    for (int r = 0; r < R; r++) {
        if (gf_slab_st.counts[r] < (int)sizeof(gf_mpi_head) || total + (size_t)gf_slab_st.counts[r] > INT_MAX)
            return gf_error_set(GF_ERR_STATE, "MPI exchange: rank %d announces a message of %d bytes (%zu before it)",
                                r, gf_slab_st.counts[r], total);
        gf_slab_st.displs[r] = (int)total;
        total += (size_t)gf_slab_st.counts[r];
    }
    if (!gf_mpi_room((void **)&gf_slab_st.all, &gf_slab_st.all_cap, total, 1))
        return gf_error_set(GF_ERR_NOMEM, "out of memory for the MPI exchange (%zu bytes)", total);
    MPI_Allgatherv(mine->b, len, MPI_BYTE, gf_slab_st.all, gf_slab_st.counts, gf_slab_st.displs, MPI_BYTE,
                   MPI_COMM_WORLD);
    *total_out = total;
    return GF_OK;
}

// The messages from the partners (point to point): sends posted first, then
// each partner's received whole (probed for its length).
/// Receives the next message from rank r with `tag` into m (grown to fit),
/// returning its length. Out of memory sets *st (naming `what`) and returns
/// 0, the message still received (its sender waits for it).
static int gf_slab_recv(int r, int tag, gf_slab_buf *m, const char *what, gf_status *st)
{
    MPI_Status ms;
    int len = 0;
    MPI_Probe(r, tag, MPI_COMM_WORLD, &ms);
    MPI_Get_count(&ms, MPI_BYTE, &len);
    if (len < 0 || !gf_mpi_room((void **)&m->b, &m->cap, (size_t)len + 1, 1)) {
        *st = gf_error_set(GF_ERR_NOMEM, "out of memory for %s (%d bytes from rank %d)", what, len, r);
        len = 0;
    }
    MPI_Recv(len ? m->b : NULL, len, MPI_BYTE, r, tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    return len;
}

static gf_status gf_slab_swap(const gf_slabs *s, int me, int R, uint64_t *sent, uint64_t *got)
{
    int nreq = 0;
    for (int r = 0; r < R; r++)
        if (gf_slabs_partners(s, me, r))
            MPI_Isend(gf_slab_st.out[r].b, (int)gf_slab_st.out[r].len, MPI_BYTE, r, GF_SLAB_TAG, MPI_COMM_WORLD,
                      &gf_slab_st.req[nreq++]);
    gf_status st = GF_OK;
    for (int r = 0; r < R; r++) {
        if (!gf_slabs_partners(s, me, r)) continue;
        *sent += gf_slab_st.out[r].len;
        gf_slab_buf *m = &gf_slab_st.in[r];
        int len = gf_slab_recv(r, GF_SLAB_TAG, m, "the MPI exchange", &st);
        m->len = (size_t)len;
        *got += (size_t)len;
    }
    MPI_Waitall(nreq, gf_slab_st.req, MPI_STATUSES_IGNORE);
    return st;
}

// The messages received (the collective's from every other rank, the
// partners' own), checked, then applied: every kind but the cells, then the cells.
static gf_status gf_slab_apply(gf_sim *sim, const gf_slabs *s, int me, int R, uint8_t *dead, void *blocks,
                               size_t nblock, size_t block_size)
{
    gf_mpi_tallies *t = gf_mpi_tally();
    gf_status st;
    for (int r = 0; r < R; r++) {
        if (r == me) continue;
        const unsigned char *a = gf_slab_st.all + gf_slab_st.displs[r];
        if ((st = gf_mpi_records_check(sim, a, (size_t)gf_slab_st.counts[r], nblock, block_size, r)) != GF_OK)
            return st;
        if (gf_slabs_partners(s, me, r) &&
            (st = gf_mpi_records_check(sim, gf_slab_st.in[r].b, gf_slab_st.in[r].len, nblock, block_size, r)) != GF_OK)
            return st;
    }
    for (int pass = 0; pass < 2; pass++)
        for (int r = 0; r < R; r++) {
            if (r == me) continue;
            gf_mpi_records_apply(sim, gf_slab_st.all + gf_slab_st.displs[r], dead, blocks, nblock, block_size,
                                 pass == 1, &t->applied_p, &t->applied_c);
            if (pass == 0) t->applied += (uint64_t)gf_slab_st.counts[r];
            if (!gf_slabs_partners(s, me, r)) continue;
            gf_mpi_records_apply(sim, gf_slab_st.in[r].b, dead, blocks, nblock, block_size, pass == 1, &t->applied_p,
                                 &t->applied_c);
            if (pass == 0) t->applied += gf_slab_st.in[r].len;
        }
    return GF_OK;
}

gf_status gf_mpi_slab_phase_end(gf_sim *sim, gf_work *work, int threads, uint8_t *dead, void *blocks, size_t nblock,
                                size_t block_size, const gf_slabs *s)
{
    const int R = gf_mpi_size(), me = gf_mpi_rank();
    if (R < 2) return GF_OK;
    for (int t = 0; t < threads; t++)
        if (work[t].log_failed) return gf_error_set(GF_ERR_NOMEM, "out of memory for the MPI exchange's logs");
    if (!gf_slab_arrays(R)) return gf_error_set(GF_ERR_NOMEM, "out of memory for MPI");
    gf_slab_st.slabs = s;
    gf_slab_st.dirty = true;
    size_t limit[GF_TOUCH_KINDS], rec[GF_TOUCH_KINDS], first[GF_TOUCH_KINDS], count[GF_TOUCH_KINDS];
    gf_mpi_records_kinds(sim, nblock, block_size, limit, rec);
    const uint32_t *list;
    gf_status st = gf_mpi_collect(sim, work, threads, nblock, block_size, &list, first, count);
    if (st != GF_OK) return st;
    size_t n = first[GF_TOUCH_KINDS - 1] + count[GF_TOUCH_KINDS - 1];
    if (!gf_mpi_room((void **)&gf_slab_st.lay, &gf_slab_st.lay_cap, n, sizeof(int)))
        return gf_error_set(GF_ERR_NOMEM, "out of memory for the MPI exchange");
    for (int k = 0; k < GF_TOUCH_KINDS; k++)
        for (size_t e = first[k]; e < first[k] + count[k]; e++) gf_slab_st.lay[e] = gf_slab_route(sim, s, k, list[e]);
    for (int r = 0; r < R && st == GF_OK; r++)
        if (r == me || gf_slabs_partners(s, me, r))
            st = gf_slab_pack(sim, s, r, me, list, first, count, rec, dead, blocks, block_size);
    if (st != GF_OK) return st;
    gf_mpi_tallies *t = gf_mpi_tally();
    double t0 = MPI_Wtime();
    uint64_t total = 0, sent = 0, got = 0;
    if ((st = gf_slab_allgather(&gf_slab_st.out[me], R, &total)) != GF_OK) return st;
    st = gf_slab_swap(s, me, R, &sent, &got);
    t->wait += MPI_Wtime() - t0;
    t->phases++;
    t->slabs = true;
    t->sent += sent + gf_slab_st.out[me].len;
    t->sent_near += sent;
    t->bytes += sent + got + total;
    if (st != GF_OK) return st;
    if ((st = gf_slab_apply(sim, s, me, R, dead, blocks, nblock, block_size)) != GF_OK) return st;
    return gf_mpi_checking() ? gf_mpi_halo_check(sim, s, dead, blocks, nblock * block_size) : GF_OK;
}

// The hash of the records in layers [a, b) (GF_MPI_CHECK): every cell's count
// and slots, and every particle in them, whole, with its list row.
static uint64_t gf_slab_hash(const gf_sim *sim, const gf_slabs *s, int a, int b)
{
    const gf_grid *g = &sim->grid;
    uint64_t h = 0xcbf29ce484222325ull;
    const size_t row = sim->use_nlist && sim->nl ? sizeof(uint32_t) << sim->nl_shift : 0;
    for (size_t c = 0; c < g->ncell; c++) {
        int L = gf_slabs_layer(s, (uint32_t)c);
        if (L < a || L >= b) continue;
        h = gf_mpi_hash(h, &g->count[c], sizeof g->count[c]);
        const uint32_t *sl = g->slot + c * GF_CELL_CAP;
        for (uint32_t k = 0; k < g->count[c]; k++) {
            uint32_t i = sl[k];
            gf_mpi_part r = gf_mpi_part_of(sim, i);
            h = gf_mpi_hash(h, &r, sizeof r);
            if (row) h = gf_mpi_hash(h, sim->nl + ((size_t)i << sim->nl_shift), row);
        }
    }
    return h;
}

gf_status gf_mpi_halo_check(const gf_sim *sim, const gf_slabs *s, const uint8_t *dead, const void *blocks,
                            size_t block_bytes)
{
    const int R = gf_mpi_size(), me = gf_mpi_rank();
    // Each pair of partners hashes the overlap of their regions; the partner's
    // hash comes back point to point.
    uint64_t bad = 0; // UINT64_MAX less the first pair that differs (lower rank R + higher), 0: none
    int nreq = 0;
    uint64_t *mine = GF_NEW(uint64_t, 2 * (size_t)R);
    if (!mine) return gf_error_set(GF_ERR_NOMEM, "out of memory for GF_MPI_CHECK");
    uint64_t *theirs = mine + R;
    for (int r = 0; r < R; r++) {
        if (!gf_slabs_partners(s, me, r)) continue;
        int a = s->rlo[me] > s->rlo[r] ? s->rlo[me] : s->rlo[r], b = s->rhi[me] < s->rhi[r] ? s->rhi[me] : s->rhi[r];
        mine[r] = gf_slab_hash(sim, s, a, b);
        MPI_Isend(&mine[r], 1, MPI_UINT64_T, r, GF_SLAB_CHECK_TAG, MPI_COMM_WORLD, &gf_slab_st.req[nreq++]);
    }
    for (int r = 0; r < R; r++) {
        if (!gf_slabs_partners(s, me, r)) continue;
        MPI_Recv(&theirs[r], 1, MPI_UINT64_T, r, GF_SLAB_CHECK_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        uint64_t pair = r < me ? (uint64_t)r * (uint64_t)R + (uint64_t)me : (uint64_t)me * (uint64_t)R + (uint64_t)r;
        if (theirs[r] != mine[r] && UINT64_MAX - pair > bad) bad = UINT64_MAX - pair;
    }
    MPI_Waitall(nreq, gf_slab_st.req, MPI_STATUSES_IGNORE);
    GF_DELETE(mine, 2 * (size_t)R);
    // The replicated part (spots, dead flags, sectors): equal on every rank.
    uint64_t h = 0xcbf29ce484222325ull;
    h = gf_mpi_hash(h, sim->sx, sim->ns * sizeof *sim->sx);
    h = gf_mpi_hash(h, sim->sy, sim->ns * sizeof *sim->sy);
    h = gf_mpi_hash(h, sim->sz, sim->ns * sizeof *sim->sz);
    h = gf_mpi_hash(h, sim->scount, sim->ns * sizeof *sim->scount);
    h = gf_mpi_hash(h, dead, sim->ns);
    h = gf_mpi_hash(h, blocks, block_bytes);
    uint64_t v[3] = {h, ~h, bad}, most[3];
    MPI_Allreduce(v, most, 3, MPI_UINT64_T, MPI_MAX, MPI_COMM_WORLD);
    const uint64_t phase = gf_mpi_tally()->phases;
    if (most[2] != 0) {
        const uint64_t pair = UINT64_MAX - most[2];
        const int lo = (int)(pair / (uint64_t)R), hi = (int)(pair % (uint64_t)R);
        return gf_error_set(GF_ERR_STATE,
                            "GF_MPI_CHECK: after sector phase %" PRIu64 " (cycle %" PRIu64 ") ranks %d and %d hold "
                            "different records in the overlap of their regions (layers %d to %d along axis %c): a "
                            "ghost differs from its owner's particle",
                            phase, sim->fstep, lo, hi, s->rlo[hi], s->rhi[lo] - 1, "xyz"[s->axis]);
    }
    if (most[0] != ~most[1])
        return gf_error_set(GF_ERR_STATE,
                            "GF_MPI_CHECK: the ranks hold different spots or sectors after sector phase %" PRIu64
                            " (cycle %" PRIu64 ")",
                            phase, sim->fstep);
    return GF_OK;
}

gf_status gf_mpi_column_tops(const gf_sim *sim, const gf_slabs *s, double *coltop, size_t ncol)
{
    const gf_grid *g = &sim->grid;
    const int me = gf_mpi_rank();
    const size_t layer = (size_t)g->nx * (size_t)g->ny;
    for (size_t col = 0; col < ncol; col++) {
        double best = -INFINITY;
        for (int cz = g->nz - 1; cz >= 0; cz--) {
            uint32_t c = (uint32_t)((size_t)cz * layer + col);
            int L = gf_slabs_layer(s, c);
            if (L < s->lo[me] || L >= s->hi[me] || g->count[c] == 0) continue;
            const uint32_t *sl = g->slot + (size_t)c * GF_CELL_CAP;
            for (uint32_t k = 0; k < g->count[c]; k++)
                if (sim->p[sl[k]].z > best) best = sim->p[sl[k]].z;
            break;
        }
        coltop[col] = best;
    }
    if (ncol > INT_MAX) return gf_error_set(GF_ERR_PARAM, "%zu columns for MPI", ncol);
    MPI_Allreduce(MPI_IN_PLACE, coltop, (int)ncol, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
    return GF_OK;
}

gf_status gf_mpi_slabs_partial(const gf_slabs *s)
{
    if (!gf_slab_arrays(gf_mpi_size())) return gf_error_set(GF_ERR_NOMEM, "out of memory for MPI");
    gf_slab_st.slabs = s;
    gf_slab_st.dirty = true;
    return GF_OK;
}

/// Writes cell c's record and, whole, its particles' (and their list rows'
/// when `rows`), advancing the three write positions by their record sizes.
static void gf_slab_write_cell(const gf_sim *sim, size_t c, bool rows, const size_t *rec, unsigned char **o,
                               unsigned char **orow, unsigned char **ocell)
{
    const gf_grid *g = &sim->grid;
    gf_mpi_record_write(sim, GF_TOUCH_CELL, (uint32_t)c, NULL, NULL, 0, *ocell);
    *ocell += rec[GF_TOUCH_CELL];
    for (uint32_t k = 0; k < g->count[c]; k++) {
        uint32_t i = g->slot[c * GF_CELL_CAP + k];
        gf_mpi_record_write(sim, GF_TOUCH_PARTICLE, i, NULL, NULL, 0, *o);
        *o += rec[GF_TOUCH_PARTICLE];
        if (!rows) continue;
        gf_mpi_record_write(sim, GF_TOUCH_ROW, i, NULL, NULL, 0, *orow);
        *orow += rec[GF_TOUCH_ROW];
    }
}

gf_status gf_mpi_whole(gf_sim *sim)
{
    if (!gf_slab_st.dirty) return GF_OK;
    const gf_slabs *s = gf_slab_st.slabs;
    const int R = gf_mpi_size(), me = gf_mpi_rank();
    const gf_grid *g = &sim->grid;
    gf_slab_st.dirty = false;
    size_t limit[GF_TOUCH_KINDS], rec[GF_TOUCH_KINDS];
    gf_mpi_records_kinds(sim, 0, 0, limit, rec);
    const bool rows = limit[GF_TOUCH_ROW] > 0;
    // This rank's message: the cells it owns and their particles, whole.
    gf_mpi_head h = {{0}};
    for (size_t c = 0; c < g->ncell; c++) {
        int L = gf_slabs_layer(s, (uint32_t)c);
        if (L < s->lo[me] || L >= s->hi[me]) continue;
        h.v[1 + GF_TOUCH_CELL]++;
        h.v[1 + GF_TOUCH_PARTICLE] += g->count[c];
    }
    if (rows) h.v[1 + GF_TOUCH_ROW] = h.v[1 + GF_TOUCH_PARTICLE];
    size_t need = sizeof h;
    for (int k = 0; k < GF_TOUCH_KINDS; k++) need += h.v[1 + k] * rec[k];
    gf_slab_buf *m = &gf_slab_st.out[me];
    if (need > INT_MAX || !gf_mpi_room((void **)&m->b, &m->cap, need, 1))
        return gf_error_set(GF_ERR_NOMEM, "out of memory for the MPI gather of the state (%zu bytes)", need);
    h.v[0] = (uint32_t)need;
    memcpy(m->b, &h, sizeof h);
    unsigned char *o = m->b + sizeof h;
    unsigned char *orow = o + h.v[1 + GF_TOUCH_PARTICLE] * rec[GF_TOUCH_PARTICLE];
    unsigned char *ocell = orow + h.v[1 + GF_TOUCH_ROW] * rec[GF_TOUCH_ROW];
    for (size_t c = 0; c < g->ncell; c++) {
        int L = gf_slabs_layer(s, (uint32_t)c);
        if (L < s->lo[me] || L >= s->hi[me]) continue;
        gf_slab_write_cell(sim, c, rows, rec, &o, &orow, &ocell);
    }
    m->len = need;
    // One rank's records at a time (MPI_Bcast from each in turn, applied
    // before the next): a rank holds its own message and one other, not every
    // rank's at once (on 2,000,000 spheres and 4 ranks that buffer was
    // ~270 MB a rank). The ranks' records are disjoint (each cell and the
    // particles in it come from its owner only), so the order is free.
    gf_mpi_tallies *t = gf_mpi_tally();
    double t0 = MPI_Wtime();
    int len = (int)need;
    MPI_Allgather(&len, 1, MPI_INT, gf_slab_st.counts, 1, MPI_INT, MPI_COMM_WORLD);
    size_t most = 0;
    for (int r = 0; r < R; r++)
        if (r != me && (size_t)gf_slab_st.counts[r] > most) most = (size_t)gf_slab_st.counts[r];
    gf_slab_buf *in = &gf_slab_st.in[me]; // (the point-to-point buffer nobody sends this rank from itself)
    // (Out of memory here fails this rank; mpi_app aborts the job, so the
    // others do not wait for it in the broadcast.)
    if (!gf_mpi_room((void **)&in->b, &in->cap, most + 1, 1))
        return gf_error_set(GF_ERR_NOMEM, "out of memory for the MPI gather of the state (%zu bytes)", most);
    gf_status st = GF_OK;
    for (int r = 0; r < R; r++) {
        unsigned char *buf = r == me ? m->b : in->b;
        MPI_Bcast(buf, gf_slab_st.counts[r], MPI_BYTE, r, MPI_COMM_WORLD);
        if (r == me || st != GF_OK) continue;
        const size_t n = (size_t)gf_slab_st.counts[r];
        if ((st = gf_mpi_records_check(sim, buf, n, 0, 0, r)) != GF_OK) continue;
        gf_mpi_records_apply(sim, buf, NULL, NULL, 0, 0, false, &t->applied_p, &t->applied_c);
        gf_mpi_records_apply(sim, buf, NULL, NULL, 0, 0, true, &t->applied_p, &t->applied_c);
        t->applied += n;
    }
    t->wait += MPI_Wtime() - t0;
    t->wholes++;
    if (st != GF_OK) return st;
    // Every rank holds every particle again (a rank that read its region
    // only now holds the rest: its window is the whole).
    sim->part = false;
    sim->win_lo = 0;
    sim->win_hi = sim->n;
    sim->grid.i0 = 0;
    sim->grid.i1 = sim->grid.np;
    gf_grid_recompute_top(&sim->grid);
    return gf_mpi_checking() ? gf_mpi_check(sim, NULL, NULL, 0) : GF_OK;
}

// The message of this rank's owned cells from c on and their particles
// (whole, with their rows), up to about `most` bytes (at least one cell);
// *c is left at the first cell not sent. An empty message (no cell) ends a
// rank's part of the gather to rank 0.
// Layers [a0, a1) and [b0, b1), of those this rank owns.
typedef struct gf_slab_pick {
    int a0, a1, b0, b1;
} gf_slab_pick;

static inline bool gf_slab_picked(const gf_slabs *s, int me, const gf_slab_pick *k, int L)
{
    return L >= s->lo[me] && L < s->hi[me] && ((L >= k->a0 && L < k->a1) || (L >= k->b0 && L < k->b1));
}

static gf_status gf_slab_chunk(const gf_sim *sim, const gf_slabs *s, int me, const gf_slab_pick *pick, size_t *c,
                               size_t most, gf_slab_buf *m)
{
    const gf_grid *g = &sim->grid;
    size_t limit[GF_TOUCH_KINDS], rec[GF_TOUCH_KINDS];
    gf_mpi_records_kinds(sim, 0, 0, limit, rec);
    const bool rows = limit[GF_TOUCH_ROW] > 0;
    const size_t per = rec[GF_TOUCH_PARTICLE] + (rows ? rec[GF_TOUCH_ROW] : 0);
    gf_mpi_head h = {{0}};
    size_t need = sizeof h, end = *c;
    for (; end < g->ncell; end++) {
        if (!gf_slab_picked(s, me, pick, gf_slabs_layer(s, (uint32_t)end))) continue;
        const size_t more = rec[GF_TOUCH_CELL] + g->count[end] * per;
        if (h.v[1 + GF_TOUCH_CELL] > 0 && need + more > most) break;
        h.v[1 + GF_TOUCH_CELL]++;
        h.v[1 + GF_TOUCH_PARTICLE] += g->count[end];
        need += more;
    }
    if (rows) h.v[1 + GF_TOUCH_ROW] = h.v[1 + GF_TOUCH_PARTICLE];
    if (need > INT_MAX || !gf_mpi_room((void **)&m->b, &m->cap, need, 1))
        return gf_error_set(GF_ERR_NOMEM, "out of memory for the MPI gather of the state (%zu bytes)", need);
    h.v[0] = (uint32_t)need;
    memcpy(m->b, &h, sizeof h);
    unsigned char *o = m->b + sizeof h;
    unsigned char *orow = o + h.v[1 + GF_TOUCH_PARTICLE] * rec[GF_TOUCH_PARTICLE];
    unsigned char *ocell = orow + h.v[1 + GF_TOUCH_ROW] * rec[GF_TOUCH_ROW];
    for (size_t k = *c; k < end; k++) {
        if (!gf_slab_picked(s, me, pick, gf_slabs_layer(s, (uint32_t)k))) continue;
        gf_slab_write_cell(sim, k, rows, rec, &o, &orow, &ocell);
    }
    m->len = need;
    *c = end;
    return GF_OK;
}

gf_status gf_mpi_gather0(gf_sim *sim)
{
    if (!gf_slab_st.dirty) return GF_OK;
    enum { GF_GATHER_TAG = 2325 };
    // Messages of ~4 MB: a rank's buffer, kept from gather to gather, stays
    // small beside its region (its whole slab at once was ~0.9 of it).
    const size_t most = (size_t)4 << 20;
    const gf_slabs *s = gf_slab_st.slabs;
    const int R = gf_mpi_size(), me = gf_mpi_rank();
    gf_mpi_tallies *t = gf_mpi_tally();
    double t0 = MPI_Wtime();
    gf_status st = GF_OK;
    if (me != 0) {
        gf_slab_buf *m = &gf_slab_st.out[me];
        size_t c = 0;
        for (bool last = false; !last;) {
            // (Out of memory fails this rank; mpi_app aborts the job.)
            const gf_slab_pick all = {0, s->n, 0, 0};
            if ((st = gf_slab_chunk(sim, s, me, &all, &c, most, m)) != GF_OK) return st;
            uint32_t cells;
            memcpy(&cells, m->b + sizeof(uint32_t) * (1 + GF_TOUCH_CELL), sizeof cells);
            last = cells == 0;
            MPI_Send(m->b, (int)m->len, MPI_BYTE, 0, GF_GATHER_TAG, MPI_COMM_WORLD);
            t->sent += m->len;
        }
    } else {
        gf_slab_buf *in = &gf_slab_st.in[me];
        for (int r = 1; r < R; r++)
            for (bool last = false; !last;) {
                MPI_Status ms;
                int len = 0;
                MPI_Probe(r, GF_GATHER_TAG, MPI_COMM_WORLD, &ms);
                MPI_Get_count(&ms, MPI_BYTE, &len);
                if (len < 0 || !gf_mpi_room((void **)&in->b, &in->cap, (size_t)len + 1, 1))
                    return gf_error_set(GF_ERR_NOMEM, "out of memory for the MPI gather of the state (%d bytes)", len);
                MPI_Recv(in->b, len, MPI_BYTE, r, GF_GATHER_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
                if (st != GF_OK) continue;
                if ((size_t)len < sizeof(gf_mpi_head)) {
                    st = gf_error_set(GF_ERR_STATE, "MPI gather: rank %d sent %d bytes", r, len);
                    break;
                }
                uint32_t cells;
                memcpy(&cells, in->b + sizeof(uint32_t) * (1 + GF_TOUCH_CELL), sizeof cells);
                last = cells == 0;
                if ((st = gf_mpi_records_check(sim, in->b, (size_t)len, 0, 0, r)) != GF_OK) break;
                gf_mpi_records_apply(sim, in->b, NULL, NULL, 0, 0, false, &t->applied_p, &t->applied_c);
                gf_mpi_records_apply(sim, in->b, NULL, NULL, 0, 0, true, &t->applied_p, &t->applied_c);
                t->applied += (size_t)len;
            }
        if (st == GF_OK) {
            // Rank 0 holds every particle now; the others still their regions.
            sim->part = false;
            sim->win_lo = 0;
            sim->win_hi = sim->n;
            sim->grid.i0 = 0;
            sim->grid.i1 = sim->grid.np;
            gf_grid_recompute_top(&sim->grid);
        }
    }
    t->wait += MPI_Wtime() - t0;
    t->wholes++;
    return st;
}

gf_status gf_mpi_resort(gf_sim *sim, const gf_slabs *s)
{
    enum { GF_MARGIN_TAG = 2326 };
    const int R = gf_mpi_size(), me = gf_mpi_rank();
    const gf_grid *g = &sim->grid;
    const int m = gf_window_margin(sim);
    const size_t layer = (size_t)g->nx * (size_t)g->ny;
    if (!gf_slab_arrays(R)) return gf_error_set(GF_ERR_NOMEM, "out of memory for MPI");
    gf_status st = GF_OK;
    // Each partner's margin (the layers of its window beyond its region)
    // from the ranks that own them, whole: its window is then exact.
    int nreq = 0;
    for (int r = 0; r < R && st == GF_OK; r++) {
        if (!gf_slabs_partners(s, me, r)) continue;
        const gf_slab_pick pick = {s->rlo[r] - m, s->rlo[r], s->rhi[r], s->rhi[r] + m};
        size_t c = 0;
        if ((st = gf_slab_chunk(sim, s, me, &pick, &c, SIZE_MAX, &gf_slab_st.out[r])) != GF_OK) break;
        MPI_Isend(gf_slab_st.out[r].b, (int)gf_slab_st.out[r].len, MPI_BYTE, r, GF_MARGIN_TAG, MPI_COMM_WORLD,
                  &gf_slab_st.req[nreq++]);
    }
    gf_mpi_tallies *t = gf_mpi_tally();
    for (int r = 0; r < R; r++) {
        if (!gf_slabs_partners(s, me, r)) continue;
        gf_slab_buf *in = &gf_slab_st.in[r];
        int len = gf_slab_recv(r, GF_MARGIN_TAG, in, "the re-sort's margins", &st);
        if (st != GF_OK || (st = gf_mpi_records_check(sim, in->b, (size_t)len, 0, 0, r)) != GF_OK) continue;
        gf_mpi_records_apply(sim, in->b, NULL, NULL, 0, 0, false, &t->applied_p, &t->applied_c);
        gf_mpi_records_apply(sim, in->b, NULL, NULL, 0, 0, true, &t->applied_p, &t->applied_c);
    }
    MPI_Waitall(nreq, gf_slab_st.req, MPI_STATUSES_IGNORE);
    // (An error here is this rank's: mpi_app aborts the job.)
    if (st != GF_OK) return st;
    // The particles in the cells each rank owns, and their radii: one
    // process's index of the first particle of a cell is the count below it.
    int wlo = s->rlo[me] - m > 0 ? s->rlo[me] - m : 0, whi = s->rhi[me] + m < s->n ? s->rhi[me] + m : s->n;
    if (s->rlo[me] >= s->rhi[me]) wlo = whi = 0;
    uint64_t own = 0, below = 0;
    double r2[2] = {INFINITY, INFINITY}; // the smallest radius, and the largest negated
    for (size_t c = (size_t)wlo * layer; c < (size_t)whi * layer; c++) {
        const int L = (int)(c / layer);
        if (L < s->lo[me]) below += g->count[c];
        if (L < s->lo[me] || L >= s->hi[me]) continue;
        own += g->count[c];
        for (uint32_t k = 0; k < g->count[c]; k++) {
            const double r = sim->p[g->slot[c * GF_CELL_CAP + k]].r;
            r2[0] = fmin(r2[0], r);
            r2[1] = fmin(r2[1], -r);
        }
    }
    uint64_t *owns = GF_NEW(uint64_t, (size_t)R);
    if (!owns) return gf_error_set(GF_ERR_NOMEM, "out of memory for the re-sort");
    MPI_Allgather(&own, 1, MPI_UINT64_T, owns, 1, MPI_UINT64_T, MPI_COMM_WORLD);
    MPI_Allreduce(MPI_IN_PLACE, r2, 2, MPI_DOUBLE, MPI_MIN, MPI_COMM_WORLD);
    uint64_t total = 0, first = 0;
    for (int r = 0; r < R; r++) {
        if (r < me) first += owns[r];
        total += owns[r];
    }
    GF_DELETE(owns, (size_t)R);
    if (total != sim->n_alive)
        return gf_error_set(GF_ERR_STATE, "re-sort: the ranks' cells hold %" PRIu64 " particles, %zu are in the container",
                            total, sim->n_alive);
    return gf_window_resort(sim, (size_t)wlo * layer, (size_t)whi * layer, (size_t)(first - below), (size_t)total,
                            r2[0], -r2[1]);
}

int gf_mpi_rank_figures(const double mine[GF_MPI_FIGURES], double *all, int cap)
{
    enum { F = GF_MPI_FIGURES + 2 };
    const int R = gf_mpi_size(), me = gf_mpi_rank();
    const gf_mpi_tallies *t = gf_mpi_tally();
    // Every rank fills its own entries of a zeroed table and the sum lands on
    // rank 0: exact (one non-zero term an entry), and nothing to allocate.
    memset(all, 0, (size_t)cap * F * sizeof(double));
    if (me < cap) {
        for (int k = 0; k < GF_MPI_FIGURES; k++) all[me * F + k] = mine[k];
        all[me * F + GF_MPI_FIGURES] = t->phases ? (double)t->sent / (double)t->phases : 0.0;
        all[me * F + GF_MPI_FIGURES + 1] = (double)t->phases;
    }
    if (R > 1)
        MPI_Reduce(me == 0 ? MPI_IN_PLACE : all, all, cap * F, MPI_DOUBLE, MPI_SUM, 0, MPI_COMM_WORLD);
    return R;
}
