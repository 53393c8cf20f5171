// SPDX-License-Identifier: MIT
// The CLI's MPI side (GF_MPI=ON, app/mpi_app.c): MPI_Init and MPI_Finalize
// around a command, and for `run` the check that every rank runs the same
// settings, version and checkpoint before the first step. Only rank 0 writes
// the run directory; the other ranks run in step with it writing nothing
// (gf_run_opts.replica), so a rank killed leaves no file behind.
#ifndef GF_APP_MPI_APP_H
#define GF_APP_MPI_APP_H

#include <stdbool.h>
#include <stddef.h>

#include "granflow/config.h"

#ifdef GF_MPI
/// MPI_Init; the rank.
int gf_mpi_app_init(int *argc, char ***argv);
/// MPI_Finalize after a command that returned rc (MPI_Abort when it failed
/// on some ranks, so that no rank waits for one that is gone; not when every
/// rank refused together, after gf_mpi_app_agree or gf_mpi_app_check).
int gf_mpi_app_end(int rc);
int gf_mpi_app_rank(void);
/// The number of ranks (1 without mpirun).
int gf_mpi_app_ranks(void);
/// Seconds a signalled rank has to stop cleanly when there are several
/// (gf_cli_stop_grace).
#define GF_MPI_STOP_GRACE 15
/// A collective of every rank: 0 when all run the same configuration (but
/// run.threads), granflow version, checkpoint (resume_dir/checkpoint.bin,
/// when resuming; else NULL) and packing.file contents; else 2 on every rank,
/// rank 0 having printed which key differs on which rank.
int gf_mpi_app_agree(const gf_config *cfg, const char *resume_dir);
/// 0 when cfg can run on the ranks there are; else prints why (run.order =
/// spatial, run.mode = fixed are needed for more than one rank) and returns 2
/// (on every rank: they run the same configuration).
int gf_mpi_app_check(const gf_config *cfg);
#endif

#endif
