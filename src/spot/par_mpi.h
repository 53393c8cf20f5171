// SPDX-License-Identifier: MIT
// Internal: the MPI side of the spatial fixed step (par_mpi.c, built with
// GF_MPI=ON). Every rank holds the whole state; in a colour phase each rank
// runs its share of the colour's blocks, then the ranks swap what their
// blocks changed. Without GF_MPI the hooks compile to nothing.
#ifndef GF_SPOT_PAR_MPI_H
#define GF_SPOT_PAR_MPI_H

#include <signal.h>
#include <stddef.h>
#include <stdint.h>

#include "spot/sim_internal.h"
#include "spot/slabs.h"

#ifdef GF_MPI
/// This process's rank and the number of ranks (0 and 1 before MPI_Init).
int gf_mpi_rank(void);
int gf_mpi_size(void);
/// Ranks on this machine (MPI_COMM_TYPE_SHARED), 1 before MPI_Init: with
/// run.threads = 0 each rank takes its share of the cores, not all of them.
int gf_mpi_local_size(void);
/// Before the first step of a run (gf_sim_run): every rank hashes the
/// engine's state (particles, spots, exits, clock, random stream) and all
/// compare; GF_ERR_STATE on every rank, naming the first rank that differs
/// from rank 0, when they do not hold the same state (a packing file or a
/// checkpoint that differs between nodes, builds that compute differently).
gf_status gf_mpi_agree(const gf_sim *sim);
/// Before a colour phase: empties the workers' logs of what their moves
/// change (gf_work.touched) and has them log.
gf_status gf_mpi_phase_begin(gf_sim *sim, gf_work *work, int threads);
/// After it: every rank sends the records its workers logged (particles,
/// cells, spots with their dead[] flags, blocks: nblock of block_size bytes)
/// and applies the others' (same-colour blocks never change the same record).
gf_status gf_mpi_phase_end(gf_sim *sim, gf_work *work, int threads, uint8_t *dead, void *blocks, size_t nblock,
                          size_t block_size);
/// Whether a stop was asked on any rank (*stop on one of them): every rank
/// calls it at the same point of the run and gets the same answer, and
/// *stop is set on all when it is true. Without ranks: *stop.
bool gf_mpi_stop(volatile sig_atomic_t *stop);
/// After the phases: the exits every rank's workers found, appended to the
/// sim (sorted by id, re-insertions queued) as gf_par_merge_exits does.
gf_status gf_mpi_merge_exits(gf_sim *sim, gf_work *work, int threads);
/// Frees the exchange's buffers (they are kept from phase to phase and
/// regrow on the next run) and, with GF_MPI_STATS=1, passes rank 0's
/// counters to gf_warn; gf_par_free calls it.
void gf_mpi_release(void);
/// What the exchange did since the last gf_mpi_release (this rank's view).
typedef struct gf_mpi_tallies {
    uint64_t phases;               ///< colour phases (sector phases) exchanged
    uint64_t bytes;                ///< replicated: all ranks' messages; slabs: what this rank sent and received
    uint64_t sent;                 ///< bytes this rank sent: its message (replicated), or its point-to-point
                                   ///< messages to each neighbour plus its part of the collective (slabs)
    uint64_t sent_near;            ///< slabs: the part of `sent` that went to its neighbours
    uint64_t applied;              ///< bytes of messages this rank took from the others
    uint64_t applied_p, applied_c; ///< particle and cell records among them
    uint64_t wholes;               ///< times the slabs' state was made whole (gf_mpi_whole)
    double wait;                   ///< seconds in the exchange's communication, waiting included
    bool slabs;                    ///< the last phases ran over slabs
} gf_mpi_tallies;
/// This rank's tallies (reset by gf_mpi_release).
gf_mpi_tallies *gf_mpi_tally(void);
/// Whether GF_MPI_CHECK is set (known from the first phase on).
bool gf_mpi_checking(void);
/// A 64-bit hash of `bytes` bytes at p, continuing h (GF_MPI_CHECK).
uint64_t gf_mpi_hash(uint64_t h, const void *p, size_t bytes);
/// Room for `need` entries of `size` bytes in *a (regrown by half, zeroed); false when out of memory.
bool gf_mpi_room(void **a, size_t *cap, size_t need, size_t size);
/// GF_MPI_CHECK: the hash of the whole state (particles, lists, cells, spots,
/// and dead[] and the blocks when not NULL) equal on every rank, else
/// GF_ERR_STATE on every rank. A collective.
gf_status gf_mpi_check(const gf_sim *sim, const uint8_t *dead, const void *blocks, size_t block_bytes);
/// The records the workers logged, each once, kind by kind: list[first[k],
/// first[k] + count[k]) are kind k's (a particle with a whole record has no
/// position record). The list lives until the next call.
gf_status gf_mpi_collect(const gf_sim *sim, gf_work *work, int threads, size_t nblock, size_t block_size,
                         const uint32_t **list, size_t first[GF_TOUCH_KINDS], size_t count[GF_TOUCH_KINDS]);
/// Writes the record of entry v of kind k at o (its size: gf_mpi_records_kinds).
void gf_mpi_record_write(const gf_sim *sim, int k, uint32_t v, const uint8_t *dead, const void *blocks,
                         size_t block_size, unsigned char *o);

/// The domain engine's phase over slabs (par_mpi_slabs.c): each rank ran its
/// slab's sectors; it sends the particle, list-row and cell records its moves
/// changed to the ranks whose region holds them (point to point, its
/// neighbour slabs only), and the spot, sector and removed-particle records to
/// every rank (one collective); then applies what it received. With
/// GF_MPI_CHECK every rank's halo is compared with its owners' records
/// (gf_mpi_halo_check). The state outside a rank's region goes stale until
/// gf_mpi_whole.
gf_status gf_mpi_slab_phase_end(gf_sim *sim, gf_work *work, int threads, uint8_t *dead, void *blocks, size_t nblock,
                                size_t block_size, const gf_slabs *s);
/// GF_MPI_CHECK after a slab phase: for every pair of neighbour ranks, a hash
/// of the records in the overlap of their regions (cells, and every particle
/// in them: position, list reference, alive, cell, slot, list row) is the
/// same on both, so every ghost equals its owner's particle; and the spots,
/// dead[] and the blocks are equal on every rank. GF_ERR_STATE on every rank
/// otherwise, naming the ranks and the layers. A collective.
gf_status gf_mpi_halo_check(const gf_sim *sim, const gf_slabs *s, const uint8_t *dead, const void *blocks,
                            size_t block_bytes);
/// The per-column tops the removal test reads (as gf_par_column_tops), each
/// rank from the cells it owns, then the maximum over the ranks. A collective.
gf_status gf_mpi_column_tops(const gf_sim *sim, const gf_slabs *s, double *coltop, size_t ncol);
/// After slab phases, before anything reads the state outside a rank's
/// region (the neighbour-list rebuild and re-sort, re-insertion, the global
/// relaxation, snapshots, checkpoints, the end of gf_sim_run): every rank
/// sends the records of the cells it owns and of the particles in them to
/// every rank, so that all hold the single process's state again. Nothing to
/// do when no slab phase ran since. A collective (every rank decides alike).
gf_status gf_mpi_whole(gf_sim *sim);
/// gf_mpi_whole for rank 0 alone (snapshots, checkpoints and the end of a
/// run of ranks that read their regions: rank 0 writes them): every other
/// rank sends it the cells it owns and their particles, in messages of a
/// few MB, and keeps its own region only. The state stays partial on the
/// others (the next gf_mpi_whole still gathers it). A collective.
gf_status gf_mpi_gather0(gf_sim *sim);
/// The neighbour-list re-sort of ranks holding their windows (slabs along
/// z): each rank gets its margin layers from their owners, then re-sorts its
/// window as one process re-sorts the whole (gf_window_resort), keeping only
/// its window. A collective.
gf_status gf_mpi_resort(gf_sim *sim, const gf_slabs *s);
/// A rank holding only its window (sim->part) before any slab phase: the
/// state is partial over these slabs, so the next gf_mpi_whole gathers it.
gf_status gf_mpi_slabs_partial(const gf_slabs *s);
/// Tests only: whether GF_MPI_TEST_BREAK names this break of the slabs'
/// exchange ("moved": moved positions kept from the neighbours; "entry":
/// particles entering a region not sent whole), which GF_MPI_CHECK must catch.
bool gf_mpi_test_break(const char *what);
/// Forgets the slabs (their owner frees them) and whether the state is whole.
void gf_mpi_slabs_release(void);
/// Rank 0 gets every rank's figures: rank r's mine[k] (its own, e.g. its
/// peak resident set) in all[r (GF_MPI_FIGURES + 2) + k], then its bytes sent
/// per phase and phases exchanged, for the first `cap` ranks (`all` holds
/// cap (GF_MPI_FIGURES + 2) doubles on every rank); returns the number of
/// ranks. A collective.
#define GF_MPI_FIGURES 4
int gf_mpi_rank_figures(const double mine[GF_MPI_FIGURES], double *all, int cap);
/// Which of a colour phase's n blocks (heaviest first, load[k] moves each)
/// this rank runs: each block in turn goes to the rank with the fewest moves
/// so far (the lowest rank on a tie), as threads taking blocks in turn would
/// share them; every rank computes the same split. mine[k] = 1 for this
/// rank's; scratch holds n entries.
void gf_mpi_assign(const uint32_t *load, size_t n, uint64_t *scratch, uint8_t *mine);
/// The initial packing of a run, made by rank 0 alone (`st` its status there;
/// the others pass GF_OK and an empty `pk`) and sent to every rank
/// (par_mpi_packing.c). A failure on rank 0 is every rank's, with its message;
/// a stop asked on any rank meanwhile (*stop) stops all of them here,
/// together: GF_ERR_INTERRUPTED on every rank. A collective: every rank calls it.
gf_status gf_mpi_share_packing(gf_status st, struct gf_packing *pk, volatile sig_atomic_t *stop);
/// Whether the ranks read packing.file each keeping its region
/// (gf_mpi_sim_create_part): more than one rank, the domain engine, a
/// packing.file and no packing.types.
bool gf_mpi_windowed(const gf_config *cfg);
/// Every rank's sim of its region of packing.file (gf_sim_create_part); a
/// failure on any rank is every rank's, with the first failing rank's
/// message. A collective.
gf_status gf_mpi_sim_create_part(const gf_config *cfg, gf_sim **out);
#else
#define gf_mpi_release() ((void)0)
#endif

#endif
