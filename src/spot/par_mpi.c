// SPDX-License-Identifier: MIT
// The spatial fixed step across MPI ranks (GF_MPI=ON): replicated state,
// owner computes. Every rank holds the whole simulation and makes the same
// global draws (phases, colour orders, insertions), so all agree on which
// blocks run in each colour phase; rank r runs the phase's blocks run[k] with
// k % R == r. Blocks of one colour never share a particle, a cell or a list
// (parallel.c), so the bytes one rank's blocks change are bytes no other
// rank's blocks touch: after the phase each rank sends the 8-byte words that
// differ from the copy it took before (value and a byte mask), every rank
// applies the others', and all hold the state a single process would have.
#include <mpi.h>
#include <inttypes.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "spot/par_mpi.h"

#define GF_MPI_NREG 20

typedef struct gf_mpi_word {
    uint64_t at;   ///< region << 48 | word index
    uint64_t val;  ///< the word's new bytes
    uint64_t mask; ///< which of its bytes changed
} gf_mpi_word;

static struct {
    unsigned char *reg[GF_MPI_NREG];
    size_t len[GF_MPI_NREG];
    size_t off[GF_MPI_NREG];
    int nreg;
    unsigned char *shadow;
    size_t shadow_cap;
    gf_mpi_word *out, *in;
    size_t out_cap, in_cap;
    int *counts, *displs;
    size_t ncounts; ///< entries of counts and displs (the ranks)
    uint64_t bytes, phases; ///< exchanged so far (all ranks' records), and phases exchanged
    uint64_t exit_bytes;    ///< exits exchanged so far
    uint64_t applied;       ///< words this rank took from the others
    int rank, size;
    bool stats_on;          ///< rank, size and report set
    bool report;            ///< GF_MPI_STATS is set
} gf_mpi_st;

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

// GF_MPI_STATS=1: when the exchange ends (gf_mpi_release), rank 0 passes
// its counters to gf_warn (the library never prints; docs/performance.md
// quotes them), then starts counting afresh.
static void gf_mpi_report_stats(void)
{
    if (gf_mpi_st.report && gf_mpi_st.rank == 0 && gf_mpi_st.phases > 0)
        gf_warn("mpi: %d ranks, %" PRIu64 " colour phases exchanged, %" PRIu64
                " bytes of changed words (all ranks), %.0f bytes per phase; %" PRIu64 " bytes of exits; rank 0 took %" PRIu64
                " words from the others",
                gf_mpi_st.size, gf_mpi_st.phases, gf_mpi_st.bytes, (double)gf_mpi_st.bytes / (double)gf_mpi_st.phases,
                gf_mpi_st.exit_bytes, gf_mpi_st.applied);
    gf_mpi_st.bytes = gf_mpi_st.phases = gf_mpi_st.exit_bytes = gf_mpi_st.applied = 0;
}

static void gf_mpi_add(void *p, size_t bytes)
{
    if (!p || bytes == 0) return;
    int k = gf_mpi_st.nreg++;
    gf_mpi_st.reg[k] = p;
    gf_mpi_st.len[k] = bytes;
}

gf_status gf_mpi_phase_begin(gf_sim *sim, void *dead, void *blocks, size_t block_bytes)
{
    if (gf_mpi_size() < 2) return GF_OK;
    if (!gf_mpi_st.stats_on) {
        gf_mpi_st.stats_on = true;
        gf_mpi_st.rank = gf_mpi_rank();
        gf_mpi_st.size = gf_mpi_size();
        const char *e = getenv("GF_MPI_STATS");
        gf_mpi_st.report = e && *e && *e != '0';
    }
    const size_t n = sim->n;
    gf_grid *g = &sim->grid;
    gf_mpi_st.nreg = 0;
    gf_mpi_add(sim->p, n * sizeof *sim->p);
    gf_mpi_add(sim->p0, n * sizeof *sim->p0);
    gf_mpi_add(sim->id, n * sizeof *sim->id);
    gf_mpi_add(sim->layer, n * sizeof *sim->layer);
    gf_mpi_add(sim->alive, n * sizeof *sim->alive);
    gf_mpi_add(sim->hist, n * sizeof *sim->hist);
    if (sim->use_nlist && sim->nl) gf_mpi_add(sim->nl, (n << sim->nl_shift) * sizeof *sim->nl);
    gf_mpi_add(sim->mark, n * sizeof *sim->mark);
    gf_mpi_add(g->count, g->ncell * sizeof *g->count);
    gf_mpi_add(g->slot, g->ncell * GF_CELL_CAP * sizeof *g->slot);
    gf_mpi_add(g->top, (size_t)g->nx * (size_t)g->ny * sizeof *g->top);
    gf_mpi_add(g->cell_of, g->np * sizeof *g->cell_of);
    gf_mpi_add(g->slot_of, g->np * sizeof *g->slot_of);
    gf_mpi_add(sim->sx, sim->ns * sizeof *sim->sx);
    gf_mpi_add(sim->sy, sim->ns * sizeof *sim->sy);
    gf_mpi_add(sim->sz, sim->ns * sizeof *sim->sz);
    gf_mpi_add(sim->scount, sim->ns * sizeof *sim->scount);
    gf_mpi_add(dead, sim->ns);
    gf_mpi_add(blocks, block_bytes);
    size_t total = 0;
    for (int k = 0; k < gf_mpi_st.nreg; k++) {
        gf_mpi_st.off[k] = total;
        total += gf_mpi_st.len[k];
    }
    if (total > gf_mpi_st.shadow_cap) {
        gf_free(gf_mpi_st.shadow, gf_mpi_st.shadow_cap);
        gf_mpi_st.shadow = gf_alloc(total);
        gf_mpi_st.shadow_cap = gf_mpi_st.shadow ? total : 0;
        if (!gf_mpi_st.shadow) return gf_error_set(GF_ERR_NOMEM, "out of memory for the MPI exchange");
    }
    for (int k = 0; k < gf_mpi_st.nreg; k++)
        memcpy(gf_mpi_st.shadow + gf_mpi_st.off[k], gf_mpi_st.reg[k], gf_mpi_st.len[k]);
    return GF_OK;
}

static bool gf_mpi_grow(gf_mpi_word **a, size_t *cap, size_t need)
{
    if (need <= *cap) return true;
    size_t c = need + need / 2 + 1024;
    gf_mpi_word *p = gf_realloc(*a, *cap * sizeof *p, c * sizeof *p);
    if (!p) return false;
    *a = p;
    *cap = c;
    return true;
}

gf_status gf_mpi_phase_end(gf_sim *sim)
{
    (void)sim;
    const int R = gf_mpi_size(), me = gf_mpi_rank();
    if (R < 2) return GF_OK;
    size_t nout = 0;
    for (int k = 0; k < gf_mpi_st.nreg; k++) {
        const unsigned char *now = gf_mpi_st.reg[k], *was = gf_mpi_st.shadow + gf_mpi_st.off[k];
        const size_t len = gf_mpi_st.len[k];
        for (size_t o = 0; o < len; o += 8) {
            size_t m = len - o < 8 ? len - o : 8;
            if (!memcmp(now + o, was + o, m)) continue;
            uint64_t a = 0, b = 0, mask = 0;
            memcpy(&a, now + o, m);
            memcpy(&b, was + o, m);
            for (size_t i = 0; i < m; i++)
                if (((a >> (8 * i)) & 0xff) != ((b >> (8 * i)) & 0xff)) mask |= 0xffull << (8 * i);
            if (!gf_mpi_grow(&gf_mpi_st.out, &gf_mpi_st.out_cap, nout + 1))
                return gf_error_set(GF_ERR_NOMEM, "out of memory for the MPI exchange");
            gf_mpi_st.out[nout++] = (gf_mpi_word){(uint64_t)k << 48 | (o / 8), a, mask};
        }
    }
    if (!gf_mpi_st.counts) {
        gf_mpi_st.counts = GF_NEW(int, gf_mpi_st.ncounts = (size_t)R);
        gf_mpi_st.displs = GF_NEW(int, R);
        if (!gf_mpi_st.counts || !gf_mpi_st.displs) return gf_error_set(GF_ERR_NOMEM, "out of memory for MPI");
    }
    int mine = (int)(nout * sizeof(gf_mpi_word));
    MPI_Allgather(&mine, 1, MPI_INT, gf_mpi_st.counts, 1, MPI_INT, MPI_COMM_WORLD);
    size_t total = 0;
    for (int r = 0; r < R; r++) {
        gf_mpi_st.displs[r] = (int)total;
        total += (size_t)gf_mpi_st.counts[r];
    }
    if (!gf_mpi_grow(&gf_mpi_st.in, &gf_mpi_st.in_cap, total / sizeof(gf_mpi_word)))
        return gf_error_set(GF_ERR_NOMEM, "out of memory for the MPI exchange");
    MPI_Allgatherv(gf_mpi_st.out, mine, MPI_BYTE, gf_mpi_st.in, gf_mpi_st.counts, gf_mpi_st.displs, MPI_BYTE,
                   MPI_COMM_WORLD);
    gf_mpi_st.bytes += total;
    gf_mpi_st.phases++;
    for (int r = 0; r < R; r++) {
        if (r == me) continue;
        const gf_mpi_word *w = (const gf_mpi_word *)((const unsigned char *)gf_mpi_st.in + gf_mpi_st.displs[r]);
        size_t nw = (size_t)gf_mpi_st.counts[r] / sizeof(gf_mpi_word);
        gf_mpi_st.applied += nw;
        for (size_t i = 0; i < nw; i++) {
            int k = (int)(w[i].at >> 48);
            size_t o = (size_t)(w[i].at & 0xffffffffffffull) * 8;
            size_t m = gf_mpi_st.len[k] - o < 8 ? gf_mpi_st.len[k] - o : 8;
            uint64_t cur = 0;
            memcpy(&cur, gf_mpi_st.reg[k] + o, m);
            cur = (cur & ~w[i].mask) | (w[i].val & w[i].mask);
            memcpy(gf_mpi_st.reg[k] + o, &cur, m);
        }
    }
    return GF_OK;
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
    int *counts = gf_mpi_st.counts, *displs = gf_mpi_st.displs;
    if (!counts) {
        counts = gf_mpi_st.counts = GF_NEW(int, gf_mpi_st.ncounts = (size_t)R);
        displs = gf_mpi_st.displs = GF_NEW(int, R);
        if (!counts || !displs) {
            GF_DELETE(out, mine + 1);
            return gf_error_set(GF_ERR_NOMEM, "out of memory for MPI");
        }
    }
    MPI_Allgather(&bytes, 1, MPI_INT, counts, 1, MPI_INT, MPI_COMM_WORLD);
    size_t total = 0;
    for (int r = 0; r < R; r++) {
        displs[r] = (int)total;
        total += (size_t)counts[r];
    }
    rec *all = gf_alloc(total + sizeof(rec));
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
    gf_free(all, total + sizeof(rec));
    return st;
}

void gf_mpi_release(void)
{
    gf_mpi_report_stats();
    gf_free(gf_mpi_st.shadow, gf_mpi_st.shadow_cap);
    gf_free(gf_mpi_st.out, gf_mpi_st.out_cap * sizeof *gf_mpi_st.out);
    gf_free(gf_mpi_st.in, gf_mpi_st.in_cap * sizeof *gf_mpi_st.in);
    GF_DELETE(gf_mpi_st.counts, gf_mpi_st.ncounts);
    GF_DELETE(gf_mpi_st.displs, gf_mpi_st.ncounts);
    gf_mpi_st.shadow = NULL;
    gf_mpi_st.out = gf_mpi_st.in = NULL;
    gf_mpi_st.counts = gf_mpi_st.displs = NULL;
    gf_mpi_st.shadow_cap = gf_mpi_st.out_cap = gf_mpi_st.in_cap = gf_mpi_st.ncounts = 0;
}
