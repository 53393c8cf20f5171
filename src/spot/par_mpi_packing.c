// SPDX-License-Identifier: MIT
// The initial packing of a run on MPI ranks (GF_MPI=ON; spot/par_mpi.h):
// made once, by rank 0, and sent to the others, with its status and message;
// or, for the domain engine and a packing.file, read by every rank keeping
// its own region (window.c: a rank holds only its region, issue 23).
// Every rank packing its own copy (as before issue 26) left a rank that a
// signal stopped while packing waiting at the first step for ranks that went
// on, for ever; and cost every rank the whole generation.
#include <mpi.h>
#include <inttypes.h>
#include <limits.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "core/error.h"
#include "granflow/defs.h"
#include "granflow/particles.h"
#include "spot/par_mpi.h"

// Rank 0's outcome: its status, the particle count and the message of a failure.
typedef struct gf_mpi_pack_head {
    int32_t status;
    uint64_t n;
    char message[1024];
} gf_mpi_pack_head;

gf_status gf_mpi_share_packing(gf_status st, gf_packing *pk, volatile sig_atomic_t *stop)
{
    if (gf_mpi_size() < 2) return st;
    int rank = gf_mpi_rank();
    gf_mpi_pack_head head = {.status = (int32_t)st, .n = st == GF_OK ? (uint64_t)pk->n : 0};
    if (rank == 0 && st != GF_OK) snprintf(head.message, sizeof head.message, "%s", gf_last_error());
    MPI_Bcast(&head, (int)sizeof head, MPI_BYTE, 0, MPI_COMM_WORLD);
    if (head.status != GF_OK) { // every rank fails as rank 0 did (interrupted: all of them)
        if (rank > 0) {
            gf_packing_free(pk);
            return gf_error_set((gf_status)head.status, "%s", head.message);
        }
        return st;
    }
    // A rank that cannot hold the particles fails; the others then learn it
    // in the agreement below, rather than waiting in a broadcast for it.
    int ok = rank == 0 || gf_packing_reserve(pk, (size_t)head.n) == GF_OK, all = ok;
    MPI_Allreduce(&ok, &all, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
    if (!all) {
        if (rank > 0) gf_packing_free(pk);
        return ok ? gf_error_set(GF_ERR_NOMEM, "packing: another rank is out of memory for %" PRIu64 " particles", head.n)
                  : gf_error_set(GF_ERR_NOMEM, "packing: out of memory for %" PRIu64 " particles", head.n);
    }
    // At most GF_MAX_PARTICLES (1e8) elements per array: an int count.
    int n = (int)head.n;
    MPI_Bcast(pk->id, n, MPI_INT64_T, 0, MPI_COMM_WORLD);
    MPI_Bcast(pk->layer, n, MPI_INT32_T, 0, MPI_COMM_WORLD);
    MPI_Bcast(pk->x, n, MPI_DOUBLE, 0, MPI_COMM_WORLD);
    MPI_Bcast(pk->y, n, MPI_DOUBLE, 0, MPI_COMM_WORLD);
    MPI_Bcast(pk->z, n, MPI_DOUBLE, 0, MPI_COMM_WORLD);
    MPI_Bcast(pk->r, n, MPI_DOUBLE, 0, MPI_COMM_WORLD);
    pk->n = (size_t)head.n;
    // A stop asked on any rank while rank 0 packed (the others were waiting
    // in the broadcast): all stop here, together.
    if (gf_mpi_stop(stop)) {
        gf_packing_free(pk);
        return gf_error_set(GF_ERR_INTERRUPTED, "packing: interrupted on one of the ranks");
    }
    return GF_OK;
}

bool gf_mpi_windowed(const gf_config *cfg)
{
    if (gf_mpi_size() < 2) return false;
    gf_engine_defs d;
    gf_packing_defs pd;
    gf_config_engine_defs(cfg, &d);
    gf_config_packing_defs(cfg, &pd);
    return d.mode == GF_MODE_FIXED && d.order == GF_ORDER_DOMAINS && pd.file[0] && !pd.types[0];
}

gf_status gf_mpi_sim_create_part(const gf_config *cfg, gf_sim **out)
{
    *out = NULL;
    const int R = gf_mpi_size(), me = gf_mpi_rank();
    gf_sim *sim = NULL;
    gf_status st = gf_sim_create_part(cfg, R, me, &sim);
    // Every rank fails with the first failing rank's status and message.
    int mine = st == GF_OK ? INT_MAX : me, first = INT_MAX;
    MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
    if (first == INT_MAX) {
        *out = sim;
        return GF_OK;
    }
    gf_sim_destroy(sim);
    gf_mpi_pack_head head = {.status = (int32_t)st};
    if (me == first) snprintf(head.message, sizeof head.message, "%s", gf_last_error());
    MPI_Bcast(&head, (int)sizeof head, MPI_BYTE, first, MPI_COMM_WORLD);
    return gf_error_set((gf_status)head.status, "%s", head.message);
}
