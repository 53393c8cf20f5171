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
#else
#define gf_mpi_release() ((void)0)
#endif

#endif
