// SPDX-License-Identifier: MIT
// The CLI's MPI side (GF_MPI=ON): see mpi_app.h.
#define _XOPEN_SOURCE 700
#include "mpi_app.h"

#include <ftw.h>
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

int gf_mpi_app_init(int *argc, char ***argv)
{
    MPI_Init(argc, argv);
    return gf_mpi_app_rank();
}

int gf_mpi_app_rank(void)
{
    int r = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &r);
    return r;
}

static int gf_mpi_app_size(void)
{
    int n = 1;
    MPI_Comm_size(MPI_COMM_WORLD, &n);
    return n;
}

int gf_mpi_app_ranks(void) { return gf_mpi_app_size(); }

int gf_mpi_app_end(int rc)
{
    if (rc != 0 && rc != 130 && gf_mpi_app_size() > 1) MPI_Abort(MPI_COMM_WORLD, rc);
    MPI_Finalize();
    return rc;
}

int gf_mpi_app_check(const gf_config *cfg)
{
    if (gf_mpi_app_size() < 2 ||
        (cfg->run_mode == GF_MODE_FIXED && (cfg->run_order == GF_ORDER_SPATIAL || cfg->run_order == GF_ORDER_DOMAINS)))
        return 0;
    if (gf_mpi_app_rank() == 0)
        fprintf(stderr, "granflow run: error: %d MPI ranks need run.mode = fixed and run.order = spatial or "
                        "domains (the engines split between ranks); run the others as one process\n",
                gf_mpi_app_size());
    return 2;
}

static bool gf_mpi_copy(const char *from_dir, const char *to_dir, const char *name)
{
    char a[4096], b[4096];
    snprintf(a, sizeof a, "%s/%s", from_dir, name);
    snprintf(b, sizeof b, "%s/%s", to_dir, name);
    FILE *in = fopen(a, "rb"), *out = in ? fopen(b, "wb") : NULL;
    bool ok = in && out;
    char buf[1 << 16];
    size_t k;
    while (ok && (k = fread(buf, 1, sizeof buf, in)) > 0) ok = fwrite(buf, 1, k, out) == k;
    if (in) ok = ok && !ferror(in) && fclose(in) == 0;
    if (out) ok = fclose(out) == 0 && ok;
    if (!ok) fprintf(stderr, "granflow run: error: rank %d cannot copy %s to %s\n", gf_mpi_app_rank(), a, b);
    return ok;
}

bool gf_mpi_app_scratch(const char *dir, bool resume, char *out, size_t n)
{
    const char *tmp = getenv("TMPDIR");
    snprintf(out, n, "%s/granflow-rank%d-XXXXXX", tmp && *tmp ? tmp : "/tmp", gf_mpi_app_rank());
    if (!mkdtemp(out)) {
        fprintf(stderr, "granflow run: error: rank %d cannot make a scratch directory %s\n", gf_mpi_app_rank(), out);
        return false;
    }
    return !resume || (gf_mpi_copy(dir, out, "config.ini") && gf_mpi_copy(dir, out, "checkpoint.bin"));
}

static int gf_mpi_rm(const char *path, const struct stat *sb, int flag, struct FTW *ftw)
{
    (void)sb;
    (void)flag;
    (void)ftw;
    return remove(path);
}

void gf_mpi_app_scratch_remove(const char *scratch) { nftw(scratch, gf_mpi_rm, 16, FTW_DEPTH | FTW_PHYS); }
