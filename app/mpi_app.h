// SPDX-License-Identifier: MIT
// The CLI's MPI side (GF_MPI=ON, app/mpi_app.c): MPI_Init and MPI_Finalize
// around a command, and for `run` on ranks other than 0 a private scratch
// run directory, so that only rank 0 writes the run directory.
#ifndef GF_APP_MPI_APP_H
#define GF_APP_MPI_APP_H

#include <stdbool.h>
#include <stddef.h>

#include "granflow/config.h"

#ifdef GF_MPI
/// MPI_Init; the rank.
int gf_mpi_app_init(int *argc, char ***argv);
/// MPI_Finalize after a command that returned rc (MPI_Abort when it failed on
/// more than one rank, so that no rank waits for one that is gone).
int gf_mpi_app_end(int rc);
int gf_mpi_app_rank(void);
/// The number of ranks (1 without mpirun).
int gf_mpi_app_ranks(void);
/// Seconds a signalled rank has to stop cleanly when there are several
/// (gf_cli_stop_grace).
#define GF_MPI_STOP_GRACE 15
/// 0 when cfg can run on the ranks there are; else prints why (run.order =
/// spatial, run.mode = fixed are needed for more than one rank) and returns 2.
int gf_mpi_app_check(const gf_config *cfg);
/// Rank > 0: a scratch run directory in $TMPDIR (with config.ini and
/// checkpoint.bin of `dir` when resuming) written to `out`; false on failure.
bool gf_mpi_app_scratch(const char *dir, bool resume, char *out, size_t n);
/// Removes a scratch directory.
void gf_mpi_app_scratch_remove(const char *scratch);
#endif

#endif
