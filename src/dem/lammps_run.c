// SPDX-License-Identifier: MIT
// Running LAMMPS on the inputs of gf_dem_write_inputs: lmp (under mpirun -np N
// when asked and available) in the run directory, its output read line by
// line for the phase markers (`granflow-phase NAME A B`, printed by the
// inputs) and the thermo lines (step time particles ke) that drive progress.
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "core/alloc.h"
#include "core/clock.h"
#include "core/error.h"
#include "dem/lammps_output.h"
#include "granflow/dem.h"

/// Finds `name` on PATH (or takes it as a path when it holds a '/').
static int gf_dem_which(const char *name, char *out, size_t n)
{
    if (strchr(name, '/')) {
        snprintf(out, n, "%s", name);
        return access(out, X_OK) == 0;
    }
    const char *path = getenv("PATH");
    if (!path) path = "/usr/local/bin:/usr/bin:/bin";
    while (*path) {
        const char *end = strchr(path, ':');
        size_t len = end ? (size_t)(end - path) : strlen(path);
        if (len > 0 && snprintf(out, n, "%.*s/%s", (int)len, path, name) < (int)n && access(out, X_OK) == 0)
            return 1;
        path += len + (end ? 1 : 0);
    }
    return 0;
}

/// Runs one input file; returns GF_OK when LAMMPS exits 0.
static gf_status gf_dem_run_one(const char *dir, const char *script, const char *lmp, const char *mpirun, int ranks,
                                gf_dem_reader *r)
{
    char log[64], np[16];
    snprintf(log, sizeof log, "log.%s", script + 3); // in.fill -> log.fill
    snprintf(np, sizeof np, "%d", ranks);
    const char *argv[16];
    int k = 0;
    if (mpirun) {
        argv[k++] = mpirun;
        argv[k++] = "-np";
        argv[k++] = np;
        if (ranks > gf_cpu_count()) argv[k++] = "--oversubscribe";
    }
    argv[k++] = lmp;
    argv[k++] = "-in";
    argv[k++] = script;
    argv[k++] = "-log";
    argv[k++] = log;
    argv[k++] = "-nocite";
    argv[k] = NULL;
    int fd[2];
    if (pipe(fd) != 0) return gf_error_set(GF_ERR_IO, "cannot make a pipe for LAMMPS: %s", strerror(errno));
    fflush(NULL);
    pid_t pid = fork();
    if (pid < 0) {
        close(fd[0]);
        close(fd[1]);
        return gf_error_set(GF_ERR_IO, "cannot start LAMMPS: %s", strerror(errno));
    }
    if (pid == 0) {
        dup2(fd[1], STDOUT_FILENO);
        dup2(fd[1], STDERR_FILENO);
        close(fd[0]);
        close(fd[1]);
        int devnull = open("/dev/null", O_RDONLY);
        if (devnull >= 0) dup2(devnull, STDIN_FILENO);
        if (chdir(dir) != 0) _exit(126);
        // Open MPI refuses root unless told; CI containers run as root.
        if (geteuid() == 0) {
            setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 1);
            setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 1);
        }
        if (!getenv("OMP_NUM_THREADS")) setenv("OMP_NUM_THREADS", "1", 1);
        execv(argv[0], (char *const *)argv);
        _exit(127);
    }
    close(fd[1]);
    FILE *in = fdopen(fd[0], "r");
    if (!in) {
        close(fd[0]);
        kill(pid, SIGTERM);
        waitpid(pid, NULL, 0);
        return gf_error_set(GF_ERR_IO, "cannot read LAMMPS' output: %s", strerror(errno));
    }
    char *line = NULL;
    size_t cap = 0;
    while (gf_getline(&line, &cap, in) >= 0) gf_dem_line(r, line);
    gf_free(line, cap);
    fclose(in);
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0 && !r->error[0]) return GF_OK;
    if (WIFEXITED(status) && WEXITSTATUS(status) == 127)
        return gf_error_set(GF_ERR_IO, "cannot execute %s", argv[0]);
    if (WIFSIGNALED(status))
        return gf_error_set(GF_ERR_INTERRUPTED, "LAMMPS (%s/%s) stopped by signal %d", dir, script, WTERMSIG(status));
    return gf_error_set(GF_ERR_PARAM, "LAMMPS failed on %s/%s (see %s/%s): %s", dir, script, dir, log,
                        r->error[0] ? r->error : "non-zero exit status");
}

gf_status gf_dem_run(const char *dir, const gf_dem_run_opts *o)
{
    gf_dem_run_opts def = gf_dem_run_opts_default();
    if (!o) o = &def;
    char lmp[4096], mpirun[4096];
    const char *want = o->lmp ? o->lmp : getenv("GF_LMP") ? getenv("GF_LMP") : "lmp";
    if (!gf_dem_which(want, lmp, sizeof lmp))
        return gf_error_set(GF_ERR_IO,
                            "LAMMPS not found (%s): install it with `apt-get install lammps` (Debian's package "
                            "has the GRANULAR styles), or set GF_LMP to the binary",
                            want);
    int ranks = o->ranks < 1 ? gf_cpu_count() : o->ranks;
    bool use_mpi = ranks > 1 && gf_dem_which("mpirun", mpirun, sizeof mpirun);
    if (!use_mpi) ranks = 1;
    const char *scripts[2] = {"in.fill", "in.drain"};
    gf_dem_reader r = {.o = o, .wall0 = gf_clock_now(), .t_phase = NAN};
    for (int k = o->drain_only ? 1 : 0; k < 2; k++) {
        char path[GF_PATH_MAX + 32];
        snprintf(path, sizeof path, "%s/%s", dir, scripts[k]);
        if (access(path, R_OK) != 0)
            return gf_error_set(GF_ERR_IO, "%s: %s (no LAMMPS inputs there: write them first)", path, strerror(errno));
        gf_status st = gf_dem_run_one(dir, scripts[k], lmp, use_mpi ? mpirun : NULL, ranks, &r);
        if (st != GF_OK) return st;
    }
    return GF_OK;
}

gf_dem_run_opts gf_dem_run_opts_default(void) { return (gf_dem_run_opts){.ranks = 1}; }
