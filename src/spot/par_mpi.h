// SPDX-License-Identifier: MIT
// Internal: the MPI side of the spatial fixed step (par_mpi.c, built with
// GF_MPI=ON). Every rank holds the whole state; in a colour phase each rank
// runs its share of the colour's blocks, then the ranks swap what their
// blocks changed. Without GF_MPI the hooks compile to nothing.
#ifndef GF_SPOT_PAR_MPI_H
#define GF_SPOT_PAR_MPI_H

#include <stddef.h>

#include "spot/sim_internal.h"

#ifdef GF_MPI
/// This process's rank and the number of ranks (0 and 1 before MPI_Init).
int gf_mpi_rank(void);
int gf_mpi_size(void);
/// Before a colour phase: remembers the state the blocks can change (the
/// particle, list, grid and spot arrays, and the phase's dead[] and blocks).
gf_status gf_mpi_phase_begin(gf_sim *sim, void *dead, void *blocks, size_t block_bytes);
/// After it: every rank sends the bytes its blocks changed and applies the
/// others' (same-colour blocks never change the same byte).
gf_status gf_mpi_phase_end(gf_sim *sim);
/// After the phases: the exits every rank's workers found, appended to the
/// sim (sorted by id, re-insertions queued) as gf_par_merge_exits does.
gf_status gf_mpi_merge_exits(gf_sim *sim, gf_work *work, int threads);
/// Frees the exchange's buffers (they are kept from phase to phase and
/// regrow on the next run) and, with GF_MPI_STATS=1, passes rank 0's
/// counters to gf_warn; gf_par_free calls it.
void gf_mpi_release(void);
#define GF_MPI_OWNS(r) ((int)((r) % (size_t)gf_mpi_size()) == gf_mpi_rank())
#else
#define GF_MPI_OWNS(r) true
#define gf_mpi_release() ((void)0)
#endif

#endif
